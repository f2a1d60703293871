//! `seasynth batch`: many fields from one command — sweeps over any parameter and their
//! cartesian product, manifests, one 16-bit mapping for the whole batch, parallel jobs
//! under a memory bound, `--resume`, `--shard K/N`, and an index of every job.
//!
//! Each job is a `generate` run: the same resolution of parameters, the same writers,
//! sidecars and staged files. Its sidecar gains a `batch` record with the job's number,
//! name, swept values and a hash of everything that fixes its files; `--resume` keeps a
//! job whose files and sidecar are there with that hash.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

use anyhow::Result;
use serde::{Deserialize, Serialize};

use crate::cli::BatchArgs;
use crate::config::Range2;
use crate::config::layers::canonical_key;
use crate::error::{Error, ParamError};
use crate::export::options::ExportOptions;
use crate::export::sidecar::JobRecord;
use crate::export::{Format, HeightMapping, OutputKind, Staged};
use crate::field::Synthesis;
use crate::pipeline::batch::files::{complete_files, hash_hex, remove_stale_temporaries, suffixes};
use crate::pipeline::batch::index::{self, Index, Row, Status};
use crate::pipeline::batch::list::{
    DesignArgs, Job, JobList, ListArgs, job_list, plan_json, plan_rows,
};
use crate::pipeline::batch::plan::{Items, Manifest, Selection, Shard, Sweep};
use crate::pipeline::batch::scheduler::{self, Overrides, Task};
use crate::pipeline::jobs::{self, Progress};
use crate::pipeline::write::{SidecarExtras, write_field};

/// `DIR/batch.json`: what every shard of the batch shares.
#[derive(Debug, Serialize, Deserialize)]
struct BatchDoc {
    tool: String,
    version: String,
    jobs: usize,
    /// Hash of the job list before the mapping (names and parameters).
    plan: String,
    name_template: String,
    formats: Vec<String>,
    keys: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mapping_min_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mapping_max_m: Option<f64>,
    mapping_source: String,
}

/// Most bytes of fields the first pass keeps for writing (a cluster node's memory may be
/// shared by many tasks, whatever `MemAvailable` says).
const KEEP_MAX_BYTES: u64 = 512 << 20;

/// The mapping source recorded in sidecars of jobs whose range the batch computed.
const BATCH_RANGE: &str = "min..max over every job of the batch";

pub fn run(args: BatchArgs) -> Result<()> {
    crate::commands::common::set_threads(args.threads)?;
    if !args.merge_index.is_empty() {
        let out = args
            .dir
            .clone()
            .unwrap_or_else(|| args.merge_index[0].clone());
        let merged = index::merge(&args.merge_index, &out)?;
        if !args.quiet {
            let failed = merged
                .rows
                .iter()
                .filter(|r| r.status == Status::Failed)
                .count();
            eprintln!(
                "merged {} ({} failed) into {}",
                plural(merged.rows.len(), "job"),
                failed,
                out.join("index.csv").display()
            );
        }
        return Ok(());
    }
    let dir = args.dir.clone().ok_or_else(|| {
        Error::Param(ParamError {
            name: "-o".into(),
            allowed: "the output folder of the batch".into(),
            got: "nothing".into(),
        })
    });
    let manifest = match &args.manifest {
        Some(p) => Manifest::load(p)?,
        None => Manifest::default(),
    };
    let formats: Vec<String> = match (&args.format, &manifest.format) {
        (f, _) if !f.is_empty() => f.clone(),
        (_, Some(f)) => f.clone(),
        _ => vec!["png".into()],
    };
    let suffixes = suffixes(&formats)?;
    let options = ExportOptions::from_flags(args.export.flags())?;

    // The job list: base assignments, then each job's.
    let mut sweeps = manifest.sweeps.clone();
    for s in &args.sweep {
        sweeps.push(Sweep::parse(s)?);
    }
    let mut base = manifest.set.clone();
    base.extend(super::common::assignments(&args.field)?);
    let JobList {
        jobs: mut all,
        keys,
        template,
    } = job_list(ListArgs {
        preset: args.field.preset.clone().or(manifest.preset.clone()),
        base,
        sweeps,
        entries: manifest.jobs.clone(),
        name: args.name.as_ref().or(manifest.name.as_ref()).cloned(),
        design: DesignArgs {
            sample: args.sample,
            vary: args.vary.clone(),
            design: args.design.clone(),
            design_seed: args.design_seed.clone(),
        },
    })?;
    let total = all.len();

    // ---- Schedulers, work items and the plan ----
    let (selection, task) = selection(&args, total)?;
    if args.plan {
        print_plan(&all, &keys, selection, args.json)?;
        return Ok(());
    }
    let dir = dir?;
    // ---- end of schedulers, work items and the plan ----

    // Every job's parameters are checked before anything is written, so that a bad value
    // fails the command at once (exit code 2), not one job at a time.
    let bad: Vec<&Job> = all.iter().filter(|j| j.params.is_err()).collect();
    if let Some(first) = bad.first() {
        let others = match bad.len() {
            1 => String::new(),
            n => format!(" (and {} more; --plan lists them)", n - 1),
        };
        return Err(Error::Set {
            origin: format!("job {} {}", first.index, first.name),
            message: format!(
                "{}{others}; nothing was written",
                first.params.as_ref().expect_err("a bad job")
            ),
        }
        .into());
    }

    let plan_hash = {
        let text: Vec<String> = all
            .iter()
            .map(|j| match &j.params {
                Ok(p) => format!(
                    "{}\n{}",
                    j.name,
                    serde_json::to_string(p).unwrap_or_default()
                ),
                Err(e) => format!("{}\n{e}", j.name),
            })
            .collect();
        hash_hex(
            format!(
                "{}\n{:?}\n{}",
                text.join("\n"),
                suffixes,
                env!("CARGO_PKG_VERSION")
            )
            .as_bytes(),
        )
    };

    std::fs::create_dir_all(&dir).map_err(|e| Error::Output {
        path: dir.clone(),
        message: format!("cannot create the folder: {e}"),
    })?;
    let doc_path = dir.join("batch.json");
    let earlier: Option<BatchDoc> = if args.resume {
        std::fs::read(&doc_path)
            .ok()
            .and_then(|b| serde_json::from_slice(&b).ok())
            .filter(|d: &BatchDoc| d.plan == plan_hash)
    } else {
        None
    };

    // One 16-bit mapping for the whole batch: every job without a height range of its
    // own gets the range over all those jobs' heights (a first pass without files, over
    // every job of every shard, so shards agree), or the earlier run's.
    let uses_mapping = suffixes.iter().any(|s| {
        matches!(
            OutputKind::of_path(Path::new(&format!("x.{s}"))),
            Ok(OutputKind::Height(Format::Png16 | Format::R16))
        )
    });
    let needs: Vec<usize> = all
        .iter()
        .filter(|j| {
            j.params
                .as_ref()
                .is_ok_and(|p| p.output.height_range.is_none())
        })
        .map(|j| j.index)
        .collect();
    let per_job = all
        .iter()
        .filter_map(|j| j.params.as_ref().ok())
        .map(|p| jobs::field_bytes(p, suffixes.iter().filter(|s| s.contains('.')).count()))
        .max()
        .unwrap_or(1);
    let workers = jobs::parallel_jobs(args.jobs, per_job);
    let started = Instant::now();
    let computed: Mutex<BTreeMap<usize, Synthesis>> = Mutex::new(BTreeMap::new());
    let mapping: Option<HeightMapping> = if uses_mapping && !needs.is_empty() {
        match earlier
            .as_ref()
            .and_then(|e| e.mapping_min_m.zip(e.mapping_max_m))
        {
            Some((lo, hi)) => Some(HeightMapping {
                min_m: lo,
                max_m: hi,
            }),
            None => {
                if !args.quiet {
                    eprintln!(
                        "first pass: the 16-bit mapping over the heights of {}",
                        plural(needs.len(), "job")
                    );
                }
                // The fields of this run's jobs are kept for writing while they fit in a
                // quarter of the available memory and 512 MiB; the others are computed again.
                // (Outputs that need derived fields, such as maps, previews and meshes, are
                // computed again with them: `write_field` decides, by the same rule.)
                let budget = (crate::limits::available_memory()
                    .ok()
                    .flatten()
                    .unwrap_or(0)
                    / 4)
                .min(KEEP_MAX_BYTES);
                let reserved = std::sync::atomic::AtomicU64::new(0);
                let ranges = jobs::run_pool(needs.len(), workers, |i| {
                    let job = needs[i];
                    let p = all[job].params.as_ref().expect("resolved");
                    let s = crate::field::Synthesizer::new(p, Default::default(), false).ok()?;
                    let syn = s.frame(p.time_s);
                    let st = syn.grid.stats();
                    let bytes = syn.grid.data.len() as u64 * 4;
                    let keep = selection.contains(job)
                        && !crate::pipeline::write::needs_extras(
                            p,
                            &all[job].paths(&dir, &suffixes),
                        )
                        && reserved.fetch_add(bytes, std::sync::atomic::Ordering::Relaxed) + bytes
                            <= budget;
                    if keep {
                        computed
                            .lock()
                            .expect("no worker panicked")
                            .insert(job, syn);
                    }
                    Some((st.min_m, st.max_m))
                });
                jobs::union_range(ranges.into_iter().flatten())
            }
        }
    } else {
        None
    };
    if let Some(m) = mapping {
        for &i in &needs {
            if let Ok(p) = all[i].params.as_mut() {
                p.output.height_range = Some(Range2([m.min_m, m.max_m]));
            }
        }
    }
    let doc = BatchDoc {
        tool: "seasynth".into(),
        version: env!("CARGO_PKG_VERSION").into(),
        jobs: total,
        plan: plan_hash,
        name_template: template.clone(),
        formats: suffixes.clone(),
        keys: keys.clone(),
        mapping_min_m: mapping.map(|m| m.min_m),
        mapping_max_m: mapping.map(|m| m.max_m),
        mapping_source: match mapping {
            Some(_) => BATCH_RANGE.into(),
            None if uses_mapping => "each job's --height-range".into(),
            None => "no 16-bit heights written".into(),
        },
    };
    Staged::create(&doc_path)?.write_json(&doc)?;

    let export_key = format!("{options:?}");
    let records: Vec<JobRecord> = all
        .iter()
        .map(|j| {
            let files: Vec<String> = suffixes.iter().map(|s| format!("{}.{s}", j.name)).collect();
            let params = j
                .params
                .as_ref()
                .map(|p| serde_json::to_string(p).unwrap_or_default());
            let text = format!(
                "{}\n{:?}\n{:?}\n{export_key}",
                env!("CARGO_PKG_VERSION"),
                params,
                files
            );
            JobRecord {
                job: j.index,
                jobs: total,
                name: j.name.clone(),
                hash: hash_hex(text.as_bytes()),
                values: j.values.clone(),
            }
        })
        .collect();
    let batch_hash = hash_hex(
        records
            .iter()
            .map(|r| format!("{} {}", r.name, r.hash))
            .collect::<Vec<_>>()
            .join("\n")
            .as_bytes(),
    );
    let mine: Vec<usize> = (0..total).filter(|&i| selection.contains(i)).collect();
    remove_stale_temporaries(&dir, mine.iter().map(|&i| all[i].name.as_str()))?;

    // Jobs complete from an earlier run are kept, with the statistics of their sidecar.
    let mut rows: BTreeMap<usize, Row> = BTreeMap::new();
    if args.resume {
        for &i in &mine {
            if let Some(row) = kept_row(&all[i], &suffixes, &records[i], &dir) {
                rows.insert(i, row);
            }
        }
    }
    let todo: Vec<usize> = mine
        .iter()
        .copied()
        .filter(|i| !rows.contains_key(i))
        .collect();
    if !args.quiet {
        let m = match mapping {
            Some(m) => format!(", 16-bit mapping {:.4}..{:.4} m", m.min_m, m.max_m),
            None => String::new(),
        };
        let of = match selection {
            Selection::Shard(s) if s.n > 1 => format!(" (shard {s}: {} of them)", mine.len()),
            Selection::Items(i) => format!(" (items {i}: {} of them)", mine.len()),
            _ => String::new(),
        };
        eprintln!(
            "batch of {}{of} in {}: {} to do, {} kept, {workers} at once{m}",
            plural(total, "job"),
            dir.display(),
            todo.len(),
            rows.len()
        );
    }
    let progress = Progress::new(todo.len(), "jobs", args.quiet, true);
    let done = jobs::run_pool(todo.len(), workers, |t| {
        let i = todo[t];
        let job = &all[i];
        let paths = job.paths(&dir, &suffixes);
        let start = Instant::now();
        let attempt = || match &job.params {
            Err(e) => Err((e.clone(), true, false)),
            Ok(p) => {
                let extras = SidecarExtras {
                    mapping_source: mapping.is_some().then_some(BATCH_RANGE),
                    batch: Some(&records[i]),
                };
                let syn = computed.lock().expect("no worker panicked").remove(&i);
                write_field(p, &paths, &options, &extras, syn, args.field.force).map_err(|e| {
                    let error = e.downcast_ref::<Error>();
                    let usage = error.is_some_and(|e| e.is_usage());
                    let vanished = matches!(error, Some(Error::Io { error, .. })
                        if error.kind() == std::io::ErrorKind::NotFound);
                    (format!("{e:#}"), usage, vanished)
                })
            }
        };
        let mut result = attempt();
        let label = format!("job {i} {}", job.name);
        // Another run of the same job (a duplicate task on another node) may have removed
        // this run's temporary file as stale when it started, failing its rename: the job
        // is kept when that run completed it, else written once more.
        if let Err((message, false, vanished)) = &result {
            if let Some(row) = kept_row(job, &suffixes, &records[i], &dir) {
                progress.finished(&format!("{label}: complete from another run ({message})"));
                return (row, true);
            }
            if *vanished {
                progress.println(&format!(
                    "{label}: another run removed its temporary file ({message}); writing it again"
                ));
                result = attempt();
            }
        }
        let result = result.map_err(|(message, usage, _)| (message, usage));
        let seconds = start.elapsed().as_secs_f64();
        let (row, usage) = match result {
            Ok(w) => {
                progress.finished(&format!(
                    "{label}: ok, {seconds:.3} s, Hs {:.3} m",
                    w.stats.hs_m
                ));
                (
                    Row {
                        files: complete_files(&job.name, &suffixes, &records[i].hash, &dir)
                            .map(|(f, _)| f)
                            .unwrap_or_default(),
                        stats: Some(w.stats),
                        seconds: Some(seconds),
                        hash: Some(records[i].hash.clone()),
                        ..job.row(Status::Ok)
                    },
                    true,
                )
            }
            Err((message, usage)) => {
                progress.println(&format!("Error: {label} failed: {message}"));
                if args.quiet {
                    eprintln!("Error: {label} failed: {message}");
                }
                progress.finished(&format!("{label}: FAILED"));
                (
                    Row {
                        seconds: Some(seconds),
                        error: Some(message),
                        ..job.row(Status::Failed)
                    },
                    usage,
                )
            }
        };
        (row, usage)
    });
    progress.finish();
    let mut io_failure = false;
    let stem = selection.index_stem();
    // A kept job keeps the task that wrote it, from this shard's earlier index.
    let earlier_tasks = earlier_tasks(&dir, &stem, &batch_hash);
    for (mut row, usage) in done {
        io_failure |= row.status == Status::Failed && !usage;
        if let Some(t) = &task {
            row.scheduler = Some(t.scheduler.name().into());
            row.task = Some(t.task.clone());
        }
        rows.insert(row.job, row);
    }
    for row in rows.values_mut().filter(|r| r.status == Status::Kept) {
        if let Some((s, t)) = earlier_tasks.get(&row.job) {
            (row.scheduler, row.task) = (Some(s.clone()), Some(t.clone()));
        }
    }
    let index = Index {
        tool: "seasynth".into(),
        version: env!("CARGO_PKG_VERSION").into(),
        batch: batch_hash,
        jobs: total,
        shard: match selection {
            Selection::Shard(s) if s.n > 1 => Some(s.to_string()),
            _ => None,
        },
        items: match selection {
            Selection::Items(i) => Some(i.to_string()),
            _ => None,
        },
        scheduler: task.as_ref().map(|t| t.scheduler.name().into()),
        task: task.as_ref().map(|t| t.task.clone()),
        keys,
        rows: rows.into_values().collect(),
    };
    index.write(&dir, &stem)?;
    let failed: Vec<String> = index
        .rows
        .iter()
        .filter(|r| r.status == Status::Failed)
        .map(|r| r.job.to_string())
        .collect();
    let secs = started.elapsed().as_secs_f64();
    if !args.quiet {
        eprintln!(
            "wrote {} of {} in {secs:.2} s ({:.2} jobs/s), {} kept, {} failed; index {}",
            todo.len() - failed.len(),
            plural(mine.len(), "job"),
            (todo.len() - failed.len()) as f64 / secs.max(1e-9),
            mine.len() - todo.len(),
            failed.len(),
            dir.join(format!("{stem}.csv")).display()
        );
    }
    if !failed.is_empty() {
        let message = format!(
            "{} of {} failed (job {}); the others were written, see {stem}.csv",
            failed.len(),
            plural(mine.len(), "job"),
            failed.join(", ")
        );
        return Err(if io_failure {
            Error::io(&dir, std::io::Error::other(message))
        } else {
            Error::Input { path: dir, message }
        }
        .into());
    }
    Ok(())
}

/// `1 job`, `2 jobs`.
fn plural(n: usize, noun: &str) -> String {
    match n {
        1 => format!("1 {noun}"),
        n => format!("{n} {noun}s"),
    }
}

/// The index row of a job complete from an earlier run ([`complete_files`]).
fn kept_row(job: &Job, suffixes: &[String], record: &JobRecord, dir: &Path) -> Option<Row> {
    let (files, stats) = complete_files(&job.name, suffixes, &record.hash, dir)?;
    Some(Row {
        files,
        stats: Some(stats),
        hash: Some(record.hash.clone()),
        ..job.row(Status::Kept)
    })
}

// ---- Schedulers, work items and the plan ----

/// The jobs this run does, and the scheduler task it found: `--items`, `--shard K/N`,
/// `--shard auto`, or without either the scheduler task's shard when one is found (one
/// line says so), else every job.
fn selection(args: &BatchArgs, total: usize) -> Result<(Selection, Option<Task>)> {
    let over = Overrides {
        count: args.shard_count,
        offset: args.shard_offset,
    };
    let env = |k: &str| std::env::var(k).ok();
    let from_scheduler = |task: Task| -> Result<(Selection, Option<Task>)> {
        Ok((Selection::Shard(task.shard), Some(task)))
    };
    let explicit = args.items.is_some() || args.shard.as_deref().is_some_and(|s| s != "auto");
    if explicit && (args.shard_count.is_some() || args.shard_offset > 0) {
        return Err(Error::Param(ParamError {
            name: "--shard-count and --shard-offset".into(),
            allowed: "given with --shard auto, or without --shard and --items".into(),
            got: match (&args.items, &args.shard) {
                (Some(i), _) => format!("--items {i}"),
                (_, s) => format!("--shard {}", s.as_deref().unwrap_or_default()),
            },
        })
        .into());
    }
    if let Some(i) = &args.items {
        return Ok((Selection::Items(Items::parse(i, total)?), None));
    }
    match args.shard.as_deref() {
        Some("auto") => match scheduler::detect(&env, over)? {
            Some(task) => {
                if !args.quiet && !args.plan {
                    eprintln!("{}", task.describe());
                }
                from_scheduler(task)
            }
            None => Err(Error::Param(ParamError {
                name: "--shard auto".into(),
                allowed: "run in a scheduler's array task, which sets SLURM_ARRAY_TASK_ID, \
                          JOB_COMPLETION_INDEX, AWS_BATCH_JOB_ARRAY_INDEX or BATCH_TASK_INDEX"
                    .into(),
                got: "none of them set".into(),
            })
            .into()),
        },
        Some(s) => Ok((Selection::Shard(Shard::parse(s)?), None)),
        // --plan lists the whole batch unless told which part.
        None if args.plan => Ok((Selection::All, None)),
        None => match scheduler::detect(&env, over)? {
            // Said even with -q: the task runs part of the batch without being told to.
            Some(task) => {
                eprintln!(
                    "{} (found without --shard; --shard 1/1 runs every job)",
                    task.describe()
                );
                from_scheduler(task)
            }
            None if args.shard_count.is_some() || args.shard_offset > 0 => {
                Err(Error::Param(ParamError {
                    name: "--shard-count and --shard-offset".into(),
                    allowed: "used in a scheduler's array task (--shard auto)".into(),
                    got: "no scheduler's task index in the environment".into(),
                })
                .into())
            }
            None => Ok((Selection::All, None)),
        },
    }
}

/// The scheduler and task of each job of this shard's earlier index, when it is of the
/// same batch.
fn earlier_tasks(dir: &Path, stem: &str, batch: &str) -> BTreeMap<usize, (String, String)> {
    let Ok(earlier) = Index::read(&dir.join(format!("{stem}.json"))) else {
        return BTreeMap::new();
    };
    if earlier.batch != batch {
        return BTreeMap::new();
    }
    earlier
        .rows
        .into_iter()
        .filter_map(|r| Some((r.job, (r.scheduler?, r.task?))))
        .collect()
}

/// `--plan`: the selected jobs, in order, as CSV (`job,name,seed,<swept keys>,error`) or
/// JSON (`{"jobs": N, "keys": [...], "rows": [...]}`) on stdout. Takes any job list, so
/// every way of making jobs prints through it.
fn print_plan(all: &[Job], keys: &[String], selection: Selection, json: bool) -> Result<()> {
    // The seed has its own column.
    let columns: Vec<&String> = keys.iter().filter(|k| canonical_key(k) != "seed").collect();
    let rows = plan_rows(all, |j| selection.contains(j));
    let text = if json {
        let doc = plan_json(all, keys, |j| selection.contains(j));
        format!("{}\n", serde_json::to_string_pretty(&doc)?)
    } else {
        let cell = |s: &str| {
            if s.contains([',', '"', '\n', '\r']) {
                format!("\"{}\"", s.replace('"', "\"\""))
            } else {
                s.to_string()
            }
        };
        let mut out = String::from("job,name,seed");
        for k in &columns {
            out.push(',');
            out.push_str(&cell(k));
        }
        out.push_str(",error\n");
        for r in &rows {
            let mut cells = vec![
                r.job.to_string(),
                cell(r.name),
                r.seed.map(|s| s.to_string()).unwrap_or_default(),
            ];
            cells.extend(
                columns
                    .iter()
                    .map(|k| cell(r.params.get(*k).map_or("", String::as_str))),
            );
            cells.push(cell(r.error.unwrap_or("")));
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    };
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush())
    {
        // A closed pipe (`| head`) is not an error.
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Error::io("stdout", e).into()),
        _ => Ok(()),
    }
}
// ---- end of schedulers, work items and the plan ----
