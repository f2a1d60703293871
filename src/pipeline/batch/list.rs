//! The job list of a batch: the base parameters, the job entries of a manifest or of a
//! random design, the product of the sweeps, each job resolved and named. `seasynth
//! batch` runs it and `--plan` prints it; the Python package's `plan` returns it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::config::Params;
use crate::config::layers::{self, Assignment, canonical_key};
use crate::error::{Error, ParamError, Result};
use crate::pipeline::batch::design;
use crate::pipeline::batch::index::{Row, Status};
use crate::pipeline::batch::plan::{self, JobSpec, NameTemplate, Sweep};

/// What makes a job list: `seasynth batch`'s options.
#[derive(Debug, Clone, Default)]
pub struct ListArgs {
    /// `--preset` (or the manifest's).
    pub preset: Option<String>,
    /// Every job's assignments (the manifest's `set`, then `--set` and flags).
    pub base: Vec<Assignment>,
    /// `--sweep`s (the manifest's first).
    pub sweeps: Vec<Sweep>,
    /// The manifest's jobs (none: one job of the base parameters).
    pub entries: Vec<JobSpec>,
    /// `--name` (or the manifest's).
    pub name: Option<String>,
    pub design: DesignArgs,
}

/// A random design: `--sample N --vary KEY=DIST … --design random|lhs --design-seed S`.
#[derive(Debug, Clone)]
pub struct DesignArgs {
    pub sample: Option<usize>,
    pub vary: Vec<String>,
    pub design: String,
    pub design_seed: Option<String>,
}

impl Default for DesignArgs {
    fn default() -> Self {
        Self {
            sample: None,
            vary: Vec::new(),
            design: "random".into(),
            design_seed: None,
        }
    }
}

/// The jobs of a batch, in order, with the keys that vary between them.
pub struct JobList {
    pub jobs: Vec<Job>,
    /// The swept and designed keys, as typed, each once.
    pub keys: Vec<String>,
    /// The name template's text.
    pub template: String,
}

/// Makes the job list: every value checked, every job resolved (a bad job keeps its
/// error), every name unique.
pub fn job_list(args: ListArgs) -> Result<JobList> {
    let ListArgs {
        preset,
        base,
        sweeps,
        entries,
        name,
        design,
    } = args;
    for s in &sweeps {
        plan::check_key(&s.key, &s.values[0], &s.origin)?;
        check_sweep_values(s)?;
    }
    let entries = if entries.is_empty() {
        vec![JobSpec {
            preset: None,
            assignments: Vec::new(),
        }]
    } else {
        entries
    };
    // Random designs: each drawn point is a job entry, its values its assignments.
    let entries = design_entries(&design, entries, preset.as_deref(), &base, &sweeps)?;
    let specs = plan::product(&entries, &sweeps)?;
    let mut keys: Vec<String> = Vec::new();
    for k in entries
        .iter()
        .flat_map(|e| e.assignments.iter().map(|a| &a.key))
        .chain(sweeps.iter().map(|s| &s.key))
    {
        if !keys.iter().any(|x| canonical_key(x) == canonical_key(k)) {
            keys.push(k.clone());
        }
    }
    let template = match &name {
        Some(t) => NameTemplate::parse(t)?,
        None => NameTemplate::default_for(&keys),
    };
    let total = specs.len();
    let all: Vec<Job> = specs
        .iter()
        .enumerate()
        .map(|(index, spec)| {
            let mut assignments = base.clone();
            assignments.extend(spec.assignments.iter().cloned());
            let params =
                layers::resolve(spec.preset.as_deref().or(preset.as_deref()), &assignments)
                    .map_err(|e| e.to_string());
            // A key's value: the resolved one, or as typed when the job is bad.
            let typed = |k: &str| {
                spec.assignments
                    .iter()
                    .rev()
                    .find(|a| canonical_key(&a.key) == canonical_key(k))
                    .map(|a| a.value.clone())
            };
            // The parameters as a tree once, not once per key and name placeholder.
            let tree = params.as_ref().ok().and_then(plan::params_tree);
            let value = |k: &str| {
                tree.as_ref()
                    .and_then(|t| plan::value_text(t, k))
                    .or_else(|| typed(k))
                    .unwrap_or_default()
            };
            let values = keys.iter().map(|k| (k.clone(), value(k))).collect();
            let name = template.render(index, total, value);
            Job {
                index,
                name,
                params,
                values,
            }
        })
        .collect();
    let mut names: BTreeMap<&str, usize> = BTreeMap::new();
    for j in &all {
        if let Some(first) = names.insert(&j.name, j.index) {
            return Err(Error::Set {
                origin: format!("--name {}", template.text),
                message: format!(
                    "jobs {first} and {} are both named `{}`: put {{index}} or every swept key in the name",
                    j.index, j.name
                ),
            });
        }
    }
    Ok(JobList {
        jobs: all,
        keys,
        template: template.text,
    })
}

/// One job, resolved.
pub struct Job {
    pub index: usize,
    pub name: String,
    /// The parameters, or why they are bad.
    pub params: std::result::Result<Params, String>,
    pub values: BTreeMap<String, String>,
}

impl Job {
    /// The job's index row: its number, name, swept values and `status`, nothing else.
    pub fn row(&self, status: Status) -> Row {
        Row {
            job: self.index,
            name: self.name.clone(),
            status,
            params: self.values.clone(),
            files: Vec::new(),
            stats: None,
            seconds: None,
            hash: None,
            error: None,
            scheduler: None,
            task: None,
        }
    }

    pub fn paths(&self, dir: &Path, suffixes: &[String]) -> Vec<PathBuf> {
        suffixes
            .iter()
            .map(|s| dir.join(format!("{}.{s}", self.name)))
            .collect()
    }
}

/// Checks that every value of a sweep reads as a value of its key (a number for
/// `wind-dir`, a method name for `method`, …), before any job is made: a range without
/// its step (`0:360`) is named as such.
pub fn check_sweep_values(sweep: &Sweep) -> Result<(), Error> {
    for v in &sweep.values {
        let a = Assignment {
            origin: sweep.origin.clone(),
            key: sweep.key.clone(),
            value: v.clone(),
        };
        let message = match layers::apply(Default::default(), &[a]) {
            Err(Error::Set { message, .. })
                if ["invalid type", "invalid value", "unknown variant"]
                    .iter()
                    .any(|m| message.contains(m)) =>
            {
                message
            }
            _ => continue,
        };
        let range = match v.contains(':') {
            true => "; a range is START:STOP:STEP (STOP excluded), e.g. 0:360:5",
            false => "",
        };
        return Err(Error::Set {
            origin: sweep.origin.clone(),
            message: format!("`{v}` is not a value of {}: {message}{range}", sweep.key),
        });
    }
    Ok(())
}

/// The job entries of a random design (`--sample N --vary KEY=DIST`): each of `entries`
/// once per drawn point, or `entries` as they are without a design. Checked before any
/// file is written: the design seed defaults to the seed of the batch's base parameters.
pub fn design_entries(
    args: &DesignArgs,
    entries: Vec<JobSpec>,
    preset: Option<&str>,
    base: &[Assignment],
    sweeps: &[Sweep],
) -> Result<Vec<JobSpec>> {
    let kind = design::DesignKind::parse(&args.design)?;
    let Some(n) = args.sample else {
        if let Some(v) = args.vary.first() {
            return Err(Error::Set {
                origin: format!("--vary {v}"),
                message: "--vary needs --sample N, the number of points to draw".into(),
            });
        }
        if args.design_seed.is_some() || kind != design::DesignKind::Random {
            return Err(Error::Set {
                origin: "--design".into(),
                message: "--design and --design-seed need --sample N and --vary KEY=DIST".into(),
            });
        }
        return Ok(entries);
    };
    let varies = args
        .vary
        .iter()
        .map(|v| design::Vary::parse(v))
        .collect::<crate::error::Result<Vec<_>>>()?;
    let seed = match &args.design_seed {
        Some(s) => s.trim().parse::<u64>().map_err(|_| {
            Error::Param(ParamError {
                name: "--design-seed".into(),
                allowed: "a whole number from 0 to 18446744073709551615".into(),
                got: s.clone(),
            })
        })?,
        None => layers::resolve(preset, base)?.seed,
    };
    // The design's values are checked with the first job's other values.
    let mut first = base.to_vec();
    first.extend(entries[0].assignments.iter().cloned());
    first.extend(sweeps.iter().map(|s| Assignment {
        origin: s.origin.clone(),
        key: s.key.clone(),
        value: s.values[0].clone(),
    }));
    let preset = entries[0].preset.as_deref().or(preset);
    let design = design::Design::new(kind, n, seed, varies, |a| {
        let mut with = first.clone();
        with.extend(a.iter().cloned());
        layers::resolve(preset, &with).map(|_| ())
    })?;
    design.entries(&entries)
}

/// One job of `--plan`.
#[derive(Serialize)]
pub struct PlanRow<'a> {
    pub job: usize,
    pub name: &'a str,
    pub seed: Option<u64>,
    pub params: &'a BTreeMap<String, String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<&'a str>,
}

/// The rows of `--plan`: the jobs `selected(job)` holds, in order.
pub fn plan_rows(jobs: &[Job], selected: impl Fn(usize) -> bool) -> Vec<PlanRow<'_>> {
    jobs.iter()
        .filter(|j| selected(j.index))
        .map(|j| PlanRow {
            job: j.index,
            name: &j.name,
            seed: j.params.as_ref().ok().map(|p| p.seed),
            params: &j.values,
            error: j.params.as_ref().err().map(String::as_str),
        })
        .collect()
}

/// The `--plan --json` document of `jobs` (the selected ones: `selected(job)`).
pub fn plan_json(
    jobs: &[Job],
    keys: &[String],
    selected: impl Fn(usize) -> bool,
) -> serde_json::Value {
    let rows = plan_rows(jobs, selected);
    serde_json::json!({ "jobs": jobs.len(), "keys": keys, "rows": rows })
}
