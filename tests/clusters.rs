//! Batches split over a scheduler's tasks (docs/clusters.md): `--shard auto` under each
//! scheduler's variables, `--items`, `--plan`, the exit code of an interruption, two
//! writers of one shard, the recipes of the docs (a Kubernetes Indexed Job, an AWS Batch
//! job definition) run for each index, and GNU parallel. Each sharded set of files is
//! compared byte for byte with one unsharded run.

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{json_file, names_in, read};
use seasynth::error::exit;
use serde_json::Value;

/// Every variable a scheduler sets that `--shard auto` reads.
const SCHEDULER_VARS: &[&str] = &[
    "SLURM_ARRAY_JOB_ID",
    "SLURM_ARRAY_TASK_ID",
    "SLURM_ARRAY_TASK_COUNT",
    "SLURM_ARRAY_TASK_MIN",
    "SLURM_ARRAY_TASK_MAX",
    "SLURM_ARRAY_TASK_STEP",
    "JOB_COMPLETION_INDEX",
    "AWS_BATCH_JOB_ARRAY_INDEX",
    "AWS_BATCH_JOB_ARRAY_SIZE",
    "BATCH_TASK_INDEX",
    "BATCH_TASK_COUNT",
];

/// A small batch: 7 FFT seas of 32², two files each, one mapping given.
const BATCH: &[&str] = &[
    "batch",
    "--method",
    "fft",
    "--size",
    "32",
    "--extent",
    "64",
    "--sweep",
    "seed=1:8:1",
    "--height-range",
    "-2:2",
    "--format",
    "png,tif",
    "-q",
];

/// `seasynth ARGS` in `dir` with the scheduler variables `vars` (and no others).
fn run_with(dir: &Path, args: &[&str], vars: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_seasynth"));
    cmd.current_dir(dir).args(args);
    for v in SCHEDULER_VARS {
        cmd.env_remove(v);
    }
    cmd.envs(vars.iter().copied());
    cmd.output().expect("seasynth runs")
}

fn ok_with(dir: &Path, args: &[&str], vars: &[(&str, &str)]) -> String {
    let out = run_with(dir, args, vars);
    assert!(
        out.status.success(),
        "seasynth {} with {vars:?} failed ({:?}):\n{}",
        args.join(" "),
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8")
}

fn with(base: &[&'static str], extra: &[&'static str]) -> Vec<&'static str> {
    base.iter().chain(extra).copied().collect()
}

/// The job files of a folder (outputs and sidecars; not indexes, batch.json or logs).
fn job_files(dir: &Path) -> BTreeSet<String> {
    names_in(dir)
        .into_iter()
        .filter(|n| !n.starts_with("index") && n != "batch.json" && !n.ends_with(".log"))
        .collect()
}

/// Asserts that `dir` holds exactly the job files of `reference`, byte for byte, and no
/// temporary file.
fn same_files(dir: &Path, reference: &Path) {
    let (got, want) = (job_files(dir), job_files(reference));
    assert!(!want.is_empty(), "the reference run wrote nothing");
    assert_eq!(got, want, "the files of {}", dir.display());
    for f in &want {
        assert!(
            read(&dir.join(f)) == read(&reference.join(f)),
            "{f} differs from the unsharded run's"
        );
    }
}

/// The rows of a merged index, checked to hold every job once.
fn merged_rows(dir: &Path, jobs: usize) -> Vec<Value> {
    let index = json_file(&dir.join("index.json"));
    let rows = index["rows"].as_array().expect("rows").clone();
    let numbers: Vec<u64> = rows.iter().map(|r| r["job"].as_u64().unwrap()).collect();
    assert_eq!(
        numbers,
        (0..jobs as u64).collect::<Vec<_>>(),
        "every job once"
    );
    rows
}

fn slurm(
    job: &'static str,
    id: usize,
    min: usize,
    max: usize,
    step: usize,
    count: usize,
) -> Vec<(&'static str, String)> {
    vec![
        ("SLURM_ARRAY_JOB_ID", job.to_string()),
        ("SLURM_ARRAY_TASK_ID", id.to_string()),
        ("SLURM_ARRAY_TASK_MIN", min.to_string()),
        ("SLURM_ARRAY_TASK_MAX", max.to_string()),
        ("SLURM_ARRAY_TASK_STEP", step.to_string()),
        ("SLURM_ARRAY_TASK_COUNT", count.to_string()),
    ]
}

fn pairs<'a>(v: &'a [(&'static str, String)]) -> Vec<(&'static str, &'a str)> {
    v.iter().map(|(k, v)| (*k, v.as_str())).collect()
}

#[test]
fn shard_auto_under_each_scheduler_merges_to_the_bytes_of_one_unsharded_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok_with(d, &with(BATCH, &["-o", "whole"]), &[]);
    let jobs = 7;

    // Slurm --array=1-7:3: tasks 1, 4, 7 are slices 1/3, 2/3, 3/3, found without --shard.
    for id in [1, 4, 7] {
        let vars = slurm("812", id, 1, 7, 3, 3);
        let out = run_with(d, &with(BATCH, &["-o", "slurm"]), &pairs(&vars));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{stderr}");
        let k = (id - 1) / 3 + 1;
        assert!(
            stderr.contains(&format!(
                "slurm task 812_{id} (SLURM_ARRAY_TASK_ID): shard {k}/3"
            )),
            "one line says where the shard came from, even with -q: {stderr}"
        );
        let shard = json_file(&d.join(format!("slurm/index.shard-{k}-of-3.json")));
        assert_eq!(shard["scheduler"], "slurm");
        assert_eq!(shard["task"], format!("812_{id}"));
    }
    ok_with(d, &["batch", "--merge-index", "slurm", "-q"], &[]);
    same_files(&d.join("slurm"), &d.join("whole"));
    for r in merged_rows(&d.join("slurm"), jobs) {
        let job = r["job"].as_u64().unwrap() as usize;
        let id = 1 + 3 * (job % 3);
        assert_eq!(r["scheduler"], "slurm", "{r}");
        assert_eq!(r["task"], format!("812_{id}"), "job {job} ran in task {id}");
    }
    let csv = std::fs::read_to_string(d.join("slurm/index.csv")).unwrap();
    assert!(
        csv.lines().next().unwrap().ends_with(",scheduler,task"),
        "{csv}"
    );

    // A list array (--array=0,2,5) is refused: bad input, nothing written.
    let list = slurm("813", 2, 0, 5, 1, 3);
    let out = run_with(
        d,
        &with(BATCH, &["--shard", "auto", "-o", "list"]),
        &pairs(&list),
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(exit::USAGE), "{stderr}");
    assert!(
        stderr.contains("--shard K/N") && stderr.contains("range"),
        "{stderr}"
    );
    assert!(!d.join("list").exists(), "nothing written");

    // 6 shards as two submissions of --array=0-2 (a site's MaxArraySize).
    for (offset, id) in [("0", 0), ("0", 1), ("0", 2), ("3", 0), ("3", 1), ("3", 2)] {
        let vars = slurm("900", id, 0, 2, 1, 3);
        let args = with(
            BATCH,
            &[
                "--shard",
                "auto",
                "--shard-count",
                "6",
                "--shard-offset",
                offset,
                "-o",
                "split",
            ],
        );
        ok_with(d, &args, &pairs(&vars));
    }
    ok_with(d, &["batch", "--merge-index", "split", "-q"], &[]);
    same_files(&d.join("split"), &d.join("whole"));

    // Kubernetes (the count from --shard-count), AWS Batch, GCP Batch.
    type Vars = fn(usize) -> Vec<(&'static str, String)>;
    let others: [(&str, Vars, &[&'static str]); 3] = [
        (
            "kubernetes",
            |i| vec![("JOB_COMPLETION_INDEX", i.to_string())],
            &["--shard-count", "3"],
        ),
        (
            "aws-batch",
            |i| {
                vec![
                    ("AWS_BATCH_JOB_ARRAY_INDEX", i.to_string()),
                    ("AWS_BATCH_JOB_ARRAY_SIZE", "3".into()),
                ]
            },
            &[],
        ),
        (
            "gcp-batch",
            |i| {
                vec![
                    ("BATCH_TASK_INDEX", i.to_string()),
                    ("BATCH_TASK_COUNT", "3".into()),
                ]
            },
            &[],
        ),
    ];
    for (name, vars, extra) in others {
        for i in 0..3 {
            let mut args = with(BATCH, &["--shard", "auto", "-o", name]);
            args.extend(extra);
            ok_with(d, &args, &pairs(&vars(i)));
        }
        ok_with(d, &["batch", "--merge-index", name, "-q"], &[]);
        same_files(&d.join(name), &d.join("whole"));
        for r in merged_rows(&d.join(name), jobs) {
            assert_eq!(r["scheduler"], name, "{r}");
            let job = r["job"].as_u64().unwrap();
            assert_eq!(r["task"], (job % 3).to_string(), "{r}");
        }
    }

    // Kubernetes without the count, and --shard auto outside any scheduler: bad input.
    let out = run_with(
        d,
        &with(BATCH, &["-o", "k"]),
        &[("JOB_COMPLETION_INDEX", "0")],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(exit::USAGE), "{stderr}");
    assert!(stderr.contains("--shard-count"), "{stderr}");
    let out = run_with(d, &with(BATCH, &["--shard", "auto", "-o", "k"]), &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(exit::USAGE), "{stderr}");
    assert!(stderr.contains("SLURM_ARRAY_TASK_ID"), "{stderr}");

    // Work items: three chunks, one with a step, merge to the whole batch too.
    for items in ["0-2", "3-5:2", "4-6:2"] {
        ok_with(d, &with(BATCH, &["--items", items, "-o", "items"]), &[]);
    }
    assert!(d.join("items/index.items-3-5-by-2.json").is_file());
    ok_with(d, &["batch", "--merge-index", "items", "-q"], &[]);
    same_files(&d.join("items"), &d.join("whole"));
    merged_rows(&d.join("items"), jobs);
}

/// The rows of `--plan` (CSV) as lines, after the header.
fn plan_lines(d: &Path, extra: &[&'static str]) -> Vec<String> {
    let out = ok_with(
        d,
        &with(&BATCH[..BATCH.len() - 1], &with(&["--plan"], extra)),
        &[],
    );
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("job,name,seed,error"), "{out}");
    lines.map(String::from).collect()
}

#[test]
fn the_plan_lists_every_job_and_no_split_changes_a_jobs_number_name_or_seed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let all = plan_lines(d, &["-o", "never"]);
    assert!(!d.join("never").exists(), "--plan writes nothing");
    assert_eq!(all.len(), 7);
    for (i, line) in all.iter().enumerate() {
        let seed = i + 1;
        assert_eq!(line, &format!("{i},{i}_seed={seed},{seed},"), "job {i}");
    }
    // Every shard and item range lists rows of the whole plan, unchanged.
    let mut seen = Vec::new();
    for k in 1..=3 {
        let shard = format!("{k}/3").leak() as &'static str;
        let rows = plan_lines(d, &["--shard", shard]);
        for r in &rows {
            assert!(
                all.contains(r),
                "{r} of shard {k} is not a row of the whole plan"
            );
        }
        seen.extend(rows);
    }
    seen.sort();
    let mut sorted = all.clone();
    sorted.sort();
    assert_eq!(seen, sorted, "the shards together list every job once");
    assert_eq!(
        plan_lines(d, &["--items", "2-6:2"]),
        [all[2].clone(), all[4].clone(), all[6].clone()]
    );
    // A scheduler's task, with --shard auto.
    let out = run_with(
        d,
        &with(&BATCH[..BATCH.len() - 1], &["--plan", "--shard", "auto"]),
        &[("BATCH_TASK_INDEX", "1"), ("BATCH_TASK_COUNT", "3")],
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let rows: Vec<&str> = text.lines().skip(1).collect();
    assert_eq!(rows, [&all[1], &all[4]], "slice 2/3: jobs 1 and 4");

    // JSON: the same jobs, with their swept values.
    let out = ok_with(
        d,
        &with(&BATCH[..BATCH.len() - 1], &["--plan", "--json"]),
        &[],
    );
    let doc: Value = serde_json::from_str(&out).expect("JSON");
    assert_eq!(doc["jobs"], 7);
    let rows = doc["rows"].as_array().unwrap();
    for (r, line) in rows.iter().zip(&all) {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(r["job"].to_string(), cells[0]);
        assert_eq!(r["name"], cells[1]);
        assert_eq!(r["seed"].to_string(), cells[2]);
        assert_eq!(r["params"]["seed"], cells[2]);
    }
    // A manifest's jobs, each entry times the sweep, with their own seeds and presets.
    let manifest = "name = \"{index}-{wind-speed}-{wind-dir}\"\n[sweep]\nwind-dir = [0, 45]\n\
                    [[job]]\nwind-speed = 6\n[[job]]\npreset = \"moderate\"\nseed = 5\n";
    std::fs::write(d.join("m.toml"), manifest).unwrap();
    let out = ok_with(d, &["batch", "--manifest", "m.toml", "--plan"], &[]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "job,name,seed,wind-speed,wind-dir,error", "{out}");
    assert_eq!(lines.len(), 5, "2 entries × 2 directions: {out}");
    assert!(
        lines[2].starts_with("1,1-6-45,") && lines[2].ends_with(",6,45,"),
        "{out}"
    );
    assert!(
        lines[4].starts_with("3,3-") && lines[4].contains(",5,"),
        "entry 2 has seed 5: {out}"
    );
    // A bad value is a row with its error, not a failure of the plan.
    let out = ok_with(d, &["batch", "--sweep", "wind-speed=5,-3", "--plan"], &[]);
    let bad = out.lines().nth(2).expect("two jobs");
    assert!(
        bad.starts_with("1,1_wind-speed=-3,") && bad.contains("must be > 0"),
        "{out}"
    );
}

/// The hidden temporary files of a folder.
fn parts_in(dir: &Path) -> Vec<String> {
    names_in(dir)
        .into_iter()
        .filter(|n| n.ends_with(".part"))
        .collect()
}

/// Jobs of tens of milliseconds, one at a time, so a signal lands in the middle.
const SLOW: &[&str] = &[
    "batch",
    "--size",
    "256",
    "--sweep",
    "wind-dir=0:360:20",
    "--format",
    "png,tif",
    "--jobs",
    "1",
    "-q",
];

fn sidecars(dir: &Path) -> usize {
    if !dir.is_dir() {
        return 0;
    }
    names_in(dir)
        .iter()
        .filter(|n| n.ends_with(".json") && n.contains("wind-dir"))
        .count()
}

fn spawn(dir: &Path, args: &[&str]) -> std::process::Child {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_seasynth"));
    cmd.current_dir(dir).args(args).stderr(Stdio::piped());
    for v in SCHEDULER_VARS {
        cmd.env_remove(v);
    }
    cmd.spawn().expect("seasynth starts")
}

#[test]
fn sigterm_mid_batch_exits_75_with_no_partial_file_and_resume_gives_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok_with(d, &with(SLOW, &["-o", "whole"]), &[]);
    let jobs = 18;
    let mut child = spawn(d, &with(SLOW, &["-o", "cut"]));
    let cut = d.join("cut");
    let t0 = Instant::now();
    while sidecars(&cut) < 2 {
        assert!(
            t0.elapsed() < Duration::from_secs(120),
            "no job in 2 minutes"
        );
        assert!(child.try_wait().unwrap().is_none(), "the batch ended first");
        std::thread::sleep(Duration::from_millis(2));
    }
    // SAFETY: kill(2) on the pid of a child this test started and has not reaped.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGTERM) }, 0);
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(exit::INTERRUPTED), "{stderr}");
    assert!(stderr.contains("safe to retry"), "{stderr}");
    let done = sidecars(&cut);
    assert!(
        done < jobs,
        "the signal came after the last job: slower jobs needed"
    );
    assert_eq!(
        parts_in(&cut),
        Vec::<String>::new(),
        "no temporary file left"
    );
    assert!(
        !cut.join("index.json").exists(),
        "no index of a half-done batch"
    );
    // Every file there is complete: byte for byte the uninterrupted run's.
    for f in job_files(&cut) {
        assert!(
            read(&cut.join(&f)) == read(&d.join("whole").join(&f)),
            "{f} is partial"
        );
    }
    ok_with(d, &with(SLOW, &["-o", "cut", "--resume"]), &[]);
    same_files(&cut, &d.join("whole"));
    let index = json_file(&cut.join("index.json"));
    let kept = index["rows"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["status"] == "kept")
        .count();
    assert!(
        kept >= 2 && kept <= done,
        "{kept} kept, {done} were complete"
    );
}

#[test]
fn two_writers_of_one_shard_at_once_both_succeed_with_complete_files_and_a_whole_index() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Meshes take a while to write: the second writer starts while the first writes one,
    // so that its start removes the first's temporary file as stale.
    let loud = &SLOW[..SLOW.len() - 1];
    let args =
        |out: &'static str| with(loud, &["--format", "png,obj", "--shard", "1/2", "-o", out]);
    ok_with(d, &args("whole"), &[]);
    let both = d.join("both");
    let a = spawn(d, &args("both"));
    let t0 = Instant::now();
    while !both.is_dir() || parts_in(&both).is_empty() {
        assert!(
            t0.elapsed() < Duration::from_secs(120),
            "the first writer wrote nothing"
        );
        std::thread::sleep(Duration::from_millis(1));
    }
    let b = spawn(d, &args("both"));
    let mut met = 0;
    for c in [a, b] {
        let out = c.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(exit::DONE),
            "a writer failed: {stderr}"
        );
        met += stderr.matches("writing it again").count()
            + stderr.matches("complete from another run").count();
    }
    // Whether the cleanup meets a temporary file depends on timing: said, not asserted.
    eprintln!("{met} jobs of one writer met the other's cleanup of stale temporary files");
    assert_eq!(
        parts_in(&both),
        Vec::<String>::new(),
        "no temporary file left"
    );
    same_files(&both, &d.join("whole"));
    let index = json_file(&both.join("index.shard-1-of-2.json"));
    let rows = index["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 9, "one whole index");
    assert!(rows.iter().all(|r| r["status"] != "failed"), "{index}");
    // A later run keeps every job, computing nothing.
    ok_with(d, &with(&args("both"), &["--resume"]), &[]);
    let index = json_file(&both.join("index.shard-1-of-2.json"));
    let rows = index["rows"].as_array().unwrap();
    assert!(rows.iter().all(|r| r["status"] == "kept"), "{index}");
    same_files(&both, &d.join("whole"));
}

// ---- The recipes of docs/clusters.md ----

/// The first fenced block of `lang` in docs/clusters.md that contains `marker`.
fn docs_block(lang: &str, marker: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/clusters.md");
    let text = std::fs::read_to_string(&path).expect("docs/clusters.md");
    let fence = format!("```{lang}\n");
    text.split(&fence)
        .skip(1)
        .map(|b| b.split("\n```").next().unwrap().to_string())
        .find(|b| b.contains(marker))
        .unwrap_or_else(|| panic!("no {lang} block with {marker} in docs/clusters.md"))
}

/// A crude YAML reader for the subset a Kubernetes manifest uses: block maps and
/// sequences by indentation, flow sequences `[a, "b"]`, plain and quoted scalars, and
/// comments. Scalars are strings, numbers or booleans.
mod yaml {
    use serde_json::{Map, Value};

    pub fn parse(text: &str) -> Value {
        let lines: Vec<(usize, String)> = text
            .lines()
            .map(strip_comment)
            .filter(|l| !l.trim().is_empty())
            .map(|l| (l.len() - l.trim_start().len(), l.trim().to_string()))
            .collect();
        let mut at = 0;
        let v = block(&lines, &mut at, 0);
        assert_eq!(at, lines.len(), "unparsed YAML from line `{}`", lines[at].1);
        v
    }

    fn strip_comment(line: &str) -> &str {
        let mut quoted = None;
        for (i, c) in line.char_indices() {
            match (c, quoted) {
                ('"' | '\'', None) => quoted = Some(c),
                (c, Some(q)) if c == q => quoted = None,
                ('#', None) if i == 0 || line[..i].ends_with(' ') => return &line[..i],
                _ => {}
            }
        }
        line
    }

    /// The block starting at line `at`, whose lines are indented by `indent`.
    fn block(lines: &[(usize, String)], at: &mut usize, indent: usize) -> Value {
        if lines[*at].1.starts_with("- ") || lines[*at].1 == "-" {
            let mut items = Vec::new();
            while *at < lines.len() && lines[*at].0 == indent && lines[*at].1.starts_with('-') {
                let rest = lines[*at].1[1..].trim_start().to_string();
                if rest.contains(": ") || rest.ends_with(':') {
                    // A map whose first key sits on the dash's line, indented past it.
                    let inner = indent + 2;
                    let mut sub = vec![(inner, rest)];
                    *at += 1;
                    while *at < lines.len() && lines[*at].0 >= inner {
                        sub.push(lines[*at].clone());
                        *at += 1;
                    }
                    let mut i = 0;
                    items.push(block(&sub, &mut i, inner));
                } else {
                    items.push(scalar(&rest));
                    *at += 1;
                }
            }
            return Value::Array(items);
        }
        let mut map = Map::new();
        while *at < lines.len() && lines[*at].0 == indent {
            let line = lines[*at].1.clone();
            let (key, value) = line
                .split_once(':')
                .unwrap_or_else(|| panic!("not `key: value`: {line}"));
            *at += 1;
            let value = value.trim();
            let v = if value.is_empty() {
                let deeper = *at < lines.len()
                    && (lines[*at].0 > indent
                        || (lines[*at].0 == indent && lines[*at].1.starts_with("- ")));
                if deeper {
                    let next = lines[*at].0;
                    block(lines, at, next)
                } else {
                    Value::Null
                }
            } else {
                scalar(value)
            };
            map.insert(key.trim().to_string(), v);
        }
        Value::Object(map)
    }

    fn scalar(s: &str) -> Value {
        let s = s.trim();
        if let Some(inner) = s.strip_prefix('[').and_then(|s| s.strip_suffix(']')) {
            return Value::Array(split_flow(inner).iter().map(|x| scalar(x)).collect());
        }
        if s.len() >= 2
            && (s.starts_with('"') && s.ends_with('"') || s.starts_with('\'') && s.ends_with('\''))
        {
            return Value::String(s[1..s.len() - 1].to_string());
        }
        if let Ok(i) = s.parse::<i64>() {
            return Value::from(i);
        }
        match s {
            "true" => Value::Bool(true),
            "false" => Value::Bool(false),
            _ => Value::String(s.to_string()),
        }
    }

    /// The items of a flow sequence, split at commas outside quotes.
    fn split_flow(s: &str) -> Vec<String> {
        let (mut out, mut cur, mut quoted) = (Vec::new(), String::new(), None);
        for c in s.chars() {
            match (c, quoted) {
                ('"' | '\'', None) => quoted = Some(c),
                (c, Some(q)) if c == q => quoted = None,
                (',', None) => {
                    out.push(std::mem::take(&mut cur));
                    continue;
                }
                _ => {}
            }
            cur.push(c);
        }
        if !cur.trim().is_empty() {
            out.push(cur);
        }
        out
    }
}

/// The strings of a JSON array.
fn strings(v: &Value) -> Vec<String> {
    v.as_array()
        .unwrap_or_else(|| panic!("not a list: {v}"))
        .iter()
        .map(|x| {
            x.as_str()
                .unwrap_or_else(|| panic!("not a string: {x}"))
                .to_string()
        })
        .collect()
}

/// The value after `flag` in `args`.
fn value_of<'a>(args: &'a [String], flag: &str) -> &'a str {
    let i = args
        .iter()
        .position(|a| a == flag)
        .unwrap_or_else(|| panic!("no {flag} in {args:?}"));
    &args[i + 1]
}

/// Runs a recipe's `batch` arguments on a 32² grid into `out` for each task index (set as
/// `index_var`), merges, and compares with the same batch run unsharded.
fn run_recipe(d: &Path, args: &[String], index_var: &str, tasks: usize, out: &str) {
    let mut small: Vec<String> = args.to_vec();
    for (flag, value) in [("--size", "32"), ("-o", out)] {
        let i = small.iter().position(|a| a == flag).unwrap() + 1;
        small[i] = value.into();
    }
    let refs: Vec<&str> = small.iter().map(String::as_str).collect();
    for k in 0..tasks {
        ok_with(d, &refs, &[(index_var, &k.to_string())]);
    }
    ok_with(d, &["batch", "--merge-index", out, "-q"], &[]);
    // The same batch, unsharded.
    let mut whole: Vec<&str> = Vec::new();
    let mut skip = 0;
    for a in &refs {
        if skip > 0 {
            skip -= 1;
            continue;
        }
        match *a {
            "--shard" | "--shard-count" => skip = 1,
            "--resume" => {}
            _ => whole.push(a),
        }
    }
    let i = whole.iter().position(|a| *a == out).unwrap();
    let reference = format!("{out}-whole");
    whole[i] = &reference;
    ok_with(d, &whole, &[]);
    same_files(&d.join(out), &d.join(&reference));
}

#[test]
fn the_kubernetes_indexed_job_of_the_docs_parses_and_its_command_runs_each_index() {
    let doc = yaml::parse(&docs_block("yaml", "kind: Job"));
    assert_eq!(doc["kind"], "Job");
    let spec = &doc["spec"];
    assert_eq!(spec["completionMode"], "Indexed");
    let completions = spec["completions"].as_u64().expect("completions") as usize;
    // The pod failure policy: bad input fails the Job, an interruption is retried.
    let rules = spec["podFailurePolicy"]["rules"].as_array().expect("rules");
    let action_for = |code: i32| {
        rules
            .iter()
            .find(|r| {
                r["onExitCodes"]["values"]
                    .as_array()
                    .is_some_and(|v| v.contains(&Value::from(code)))
            })
            .map(|r| r["action"].as_str().unwrap().to_string())
    };
    assert_eq!(action_for(exit::USAGE).as_deref(), Some("FailJob"));
    assert_eq!(action_for(exit::INTERRUPTED).as_deref(), Some("Ignore"));
    let container = &spec["template"]["spec"]["containers"][0];
    assert_eq!(strings(&container["command"]), ["seasynth"]);
    assert_eq!(spec["template"]["spec"]["restartPolicy"], "Never");
    let args = strings(&container["args"]);
    assert_eq!(
        value_of(&args, "--shard-count"),
        completions.to_string(),
        "--shard-count is the Job's completions"
    );
    assert_eq!(value_of(&args, "--shard"), "auto");
    let mount = container["volumeMounts"][0]["mountPath"].as_str().unwrap();
    assert!(
        value_of(&args, "-o").starts_with(mount),
        "the output is on the volume"
    );
    let dir = tempfile::tempdir().unwrap();
    run_recipe(
        dir.path(),
        &args,
        "JOB_COMPLETION_INDEX",
        completions,
        "k8s",
    );
}

#[test]
fn the_aws_batch_job_definition_of_the_docs_parses_and_its_command_runs_each_index() {
    let def: Value = serde_json::from_str(&docs_block("json", "jobDefinitionName")).expect("JSON");
    let command = strings(&def["containerProperties"]["command"]);
    assert_eq!(command[0], "seasynth");
    let on_exit = def["retryStrategy"]["evaluateOnExit"].as_array().unwrap();
    let action_for = |code: i32| {
        on_exit
            .iter()
            .find(|r| r["onExitCode"].as_str() == Some(code.to_string().as_str()))
            .map(|r| r["action"].as_str().unwrap().to_string())
    };
    assert_eq!(action_for(exit::USAGE).as_deref(), Some("EXIT"));
    assert_eq!(action_for(exit::INTERRUPTED).as_deref(), Some("RETRY"));
    let tasks: usize = value_of(&command, "--shard-count").parse().unwrap();
    let dir = tempfile::tempdir().unwrap();
    run_recipe(
        dir.path(),
        &command[1..],
        "AWS_BATCH_JOB_ARRAY_INDEX",
        tasks,
        "aws",
    );
}

/// `parallel` on PATH, or why not.
fn gnu_parallel() -> Result<PathBuf, String> {
    let out = Command::new("parallel")
        .arg("--version")
        .output()
        .map_err(|e| format!("`parallel` cannot run: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    if !text.starts_with("GNU parallel") {
        return Err(format!(
            "`parallel` is not GNU parallel: {}",
            text.lines().next().unwrap_or("")
        ));
    }
    Ok(PathBuf::from("parallel"))
}

#[test]
fn gnu_parallel_runs_the_shards_and_they_merge_to_the_unsharded_run() {
    let parallel = match gnu_parallel() {
        Ok(p) => p,
        Err(why) => {
            eprintln!(
                "SKIPPED: GNU parallel is not available ({why}); Debian's `parallel` installs it"
            );
            return;
        }
    };
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok_with(d, &with(BATCH, &["-o", "whole"]), &[]);
    let mut cmd = Command::new(parallel);
    cmd.current_dir(d)
        .args([
            "--will-cite",
            "--halt",
            "now,fail=1",
            "-j",
            "2",
            env!("CARGO_BIN_EXE_seasynth"),
        ])
        .args(BATCH)
        .args([
            "--jobs", "1", "--shard", "{}/3", "--resume", "-o", "par", ":::", "1", "2", "3",
        ]);
    for v in SCHEDULER_VARS {
        cmd.env_remove(v);
    }
    let out = cmd.output().expect("parallel runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    ok_with(d, &["batch", "--merge-index", "par", "-q"], &[]);
    same_files(&d.join("par"), &d.join("whole"));
    merged_rows(&d.join("par"), 7);
}
