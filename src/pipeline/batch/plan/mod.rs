//! The job list of a batch: sweeps (`KEY=A,B,C` or `KEY=START:STOP:STEP`) and their
//! cartesian product, manifests, job names from a template, and shards.
//!
//! Jobs are numbered in the order of nested loops over the sweeps as given, the first
//! sweep outermost (and, with a manifest, its `[[job]]` entries outside every sweep).
//! Every job's values go through the same resolution and validation as `--set`, so a
//! sweep key is a flag name (`wind-dir`) or a preset key (`wind.direction_deg`).

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;
use toml::{Spanned, Value};

use crate::config::Params;
use crate::config::layers::{self, Assignment, canonical_key};
use crate::error::{Error, Result};

/// Most jobs one batch may hold.
pub const MAX_JOBS: usize = 1_000_000;

/// One swept key and its values, as typed.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    /// The key as the user wrote it (`wind-dir`, `wind.direction_deg`).
    pub key: String,
    /// Each value as text that `--set` accepts.
    pub values: Vec<String>,
    /// Where the sweep was given, for error messages (`--sweep wind-dir=0,90`, `m.toml:4`).
    pub origin: String,
}

/// Decimal places of a number as typed (`0.25` → 2, `45` → 0, `1e-3` → none known).
fn decimals(text: &str) -> Option<usize> {
    if text.contains(['e', 'E']) {
        return None;
    }
    Some(text.split_once('.').map_or(0, |(_, f)| f.len()))
}

impl Sweep {
    /// Parses `KEY=A,B,C` or `KEY=START:STOP:STEP` (STOP excluded, like a range).
    pub fn parse(text: &str) -> Result<Self> {
        let origin = format!("--sweep {text}");
        let bad = |message: String| Error::Set {
            origin: origin.clone(),
            message,
        };
        let (key, values) = text.split_once('=').ok_or_else(|| {
            bad("expected KEY=A,B,C or KEY=START:STOP:STEP (STOP excluded)".into())
        })?;
        let key = key.trim();
        if key.is_empty() {
            return Err(bad("the key is missing".into()));
        }
        let values = Self::values_of(values.trim()).map_err(bad)?;
        Ok(Self {
            key: key.to_string(),
            values,
            origin,
        })
    }

    /// The values of `A,B,C` or `START:STOP:STEP`.
    pub fn values_of(text: &str) -> std::result::Result<Vec<String>, String> {
        let parts: Vec<&str> = text.split(':').collect();
        let numbers: Option<Vec<f64>> = (parts.len() == 3 && !text.contains(','))
            .then(|| parts.iter().map(|p| p.trim().parse::<f64>().ok()).collect())
            .flatten();
        if let Some(n) = numbers {
            return Self::range(&parts, n[0], n[1], n[2]);
        }
        let values: Vec<String> = text.split(',').map(|v| v.trim().to_string()).collect();
        if values.iter().any(String::is_empty) {
            return Err(format!(
                "empty value in `{text}`: expected A,B,C or START:STOP:STEP"
            ));
        }
        Ok(values)
    }

    fn range(
        parts: &[&str],
        start: f64,
        stop: f64,
        step: f64,
    ) -> std::result::Result<Vec<String>, String> {
        let span = stop - start;
        if !(start.is_finite() && stop.is_finite() && step.is_finite())
            || step == 0.0
            || span * step < 0.0
        {
            return Err(format!(
                "START:STOP:STEP must have a non-zero STEP leading from START toward STOP (got {})",
                parts.join(":")
            ));
        }
        // STOP excluded; a value within 1e-9 steps of STOP counts as STOP.
        let count = (span / step - 1e-9).ceil().max(0.0);
        if count > MAX_JOBS as f64 {
            return Err(format!("{} values: at most {MAX_JOBS}", count));
        }
        if count == 0.0 {
            return Err(format!("{} gives no value", parts.join(":")));
        }
        let places = [parts[0], parts[2]]
            .iter()
            .map(|p| decimals(p.trim()))
            .try_fold(0, |a, d| d.map(|d| a.max(d)));
        Ok((0..count as usize)
            .map(|i| {
                let v = start + i as f64 * step;
                match places {
                    Some(p) => format!("{v:.p$}"),
                    None => format!("{v}"),
                }
            })
            .collect())
    }
}

/// One job before resolution: the preset and the assignments over the base.
#[derive(Debug, Clone, PartialEq)]
pub struct JobSpec {
    pub preset: Option<String>,
    /// Assignments of this job, after the batch's own (`--set`, flags, the manifest's `[set]`).
    pub assignments: Vec<Assignment>,
}

/// The cartesian product of `sweeps` over each of `entries`, in job order.
pub fn product(entries: &[JobSpec], sweeps: &[Sweep]) -> Result<Vec<JobSpec>> {
    let total = sweeps
        .iter()
        .try_fold(entries.len(), |a, s| a.checked_mul(s.values.len()))
        .filter(|&n| n <= MAX_JOBS)
        .ok_or_else(|| Error::Set {
            origin: "--sweep".into(),
            message: format!("the sweeps give more than {MAX_JOBS} jobs"),
        })?;
    let mut jobs = entries.to_vec();
    for s in sweeps {
        jobs = jobs
            .into_iter()
            .flat_map(|j| {
                s.values.iter().map(move |v| {
                    let mut j = j.clone();
                    j.assignments.push(Assignment {
                        origin: format!("--sweep {}={v}", s.key),
                        key: s.key.clone(),
                        value: v.clone(),
                    });
                    j
                })
            })
            .collect();
    }
    debug_assert_eq!(jobs.len(), total);
    Ok(jobs)
}

/// Refuses a key that no parameter has (`--sweep` and manifest keys are checked before
/// any work; a bad value fails only its job).
pub fn check_key(key: &str, sample_value: &str, origin: &str) -> Result<()> {
    let a = Assignment {
        origin: origin.to_string(),
        key: key.to_string(),
        value: sample_value.to_string(),
    };
    match layers::apply(Params::default(), &[a]) {
        Err(Error::Set { message, .. })
            if message.contains("unknown field") || message.contains("is not a key") =>
        {
            Err(Error::Set {
                origin: origin.to_string(),
                message: format!("unknown key `{key}`: {message}"),
            })
        }
        _ => Ok(()),
    }
}

/// A job's parameters as a TOML tree, made once per job for every [`value_text`].
pub fn params_tree(params: &Params) -> Option<Value> {
    toml::Table::try_from(params).ok().map(Value::Table)
}

/// A job's value of `key` (a flag name or preset key) in its [`params_tree`], as text for
/// names and the index: numbers in their shortest form (`45`, `0.25`), sizes as `NxM`.
pub fn value_text(tree: &Value, key: &str) -> Option<String> {
    let mut cur = tree;
    for part in canonical_key(key).split('.') {
        cur = cur.as_table()?.get(part)?;
    }
    Some(render(cur))
}

fn render(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Integer(i) => i.to_string(),
        Value::Float(f) => format!("{f}"),
        Value::Boolean(b) => b.to_string(),
        Value::Array(a) => a.iter().map(render).collect::<Vec<_>>().join("x"),
        other => other
            .to_string()
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(""),
    }
}

/// A `--name` template: literal text with `{index}` (the job number, zero-padded to the
/// width of the largest) and `{KEY}` for any parameter key or flag name.
#[derive(Debug, Clone, PartialEq)]
pub struct NameTemplate {
    pub text: String,
    parts: Vec<Part>,
}

#[derive(Debug, Clone, PartialEq)]
enum Part {
    Text(String),
    Index,
    Key(String),
}

impl NameTemplate {
    /// The default: the job number and every swept key, `{index}_wind-dir={wind-dir}`.
    pub fn default_for(keys: &[String]) -> Self {
        let mut t = "{index}".to_string();
        for k in keys {
            t.push_str(&format!("_{}={{{k}}}", short_key(k)));
        }
        Self::parse(&t).expect("the default template parses")
    }

    pub fn parse(text: &str) -> Result<Self> {
        let bad = |message: String| Error::Set {
            origin: format!("--name {text}"),
            message,
        };
        let mut parts = Vec::new();
        let mut rest = text;
        while let Some(open) = rest.find('{') {
            if open > 0 {
                parts.push(Part::Text(rest[..open].to_string()));
            }
            let close = rest[open..]
                .find('}')
                .ok_or_else(|| bad("a `{` without its `}`".into()))?;
            let key = rest[open + 1..open + close].trim();
            parts.push(match key {
                "index" => Part::Index,
                "" => return Err(bad("an empty placeholder `{}`".into())),
                k => {
                    check_key(k, "0", &format!("--name {text}"))?;
                    Part::Key(k.to_string())
                }
            });
            rest = &rest[open + close + 1..];
        }
        if rest.contains('}') {
            return Err(bad("a `}` without its `{`".into()));
        }
        if !rest.is_empty() {
            parts.push(Part::Text(rest.to_string()));
        }
        if parts.is_empty() || text.contains(['/', '\\']) {
            return Err(bad(
                "a name template must be non-empty, without folders".into()
            ));
        }
        Ok(Self {
            text: text.to_string(),
            parts,
        })
    }

    /// The name of job `index` of `total`, whose value of a key is `value(key)`.
    pub fn render(&self, index: usize, total: usize, value: impl Fn(&str) -> String) -> String {
        let width = (total.max(1) - 1).to_string().len();
        let mut s = String::new();
        for p in &self.parts {
            match p {
                Part::Text(t) => s.push_str(t),
                Part::Index => s.push_str(&format!("{index:0width$}")),
                Part::Key(k) => s.push_str(&sanitize(&value(k))),
            }
        }
        s
    }
}

/// The flag name of a preset key when it has one (`wind.direction_deg` → `wind-dir`).
pub fn short_key(key: &str) -> String {
    let canonical = canonical_key(key);
    layers::FLAG_KEYS
        .iter()
        .find(|(_, k)| *k == canonical)
        .map(|(f, _)| f.to_string())
        .unwrap_or_else(|| key.to_string())
}

/// A value made safe in a file name: anything but letters, digits and `+-.=_` becomes `_`.
fn sanitize(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "+-.=_".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// `--shard K/N`: the K-th (1-based) of N slices; job i is in slice i mod N + 1, so
/// slices are disjoint, deterministic and cover every job, and each gets every N-th job
/// (a sweep that grows in cost along one axis spreads evenly).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub k: usize,
    pub n: usize,
}

impl Shard {
    pub fn parse(text: &str) -> Result<Self> {
        let bad = || {
            Error::Param(crate::error::ParamError {
                name: "--shard".into(),
                allowed: "K/N with 1 ≤ K ≤ N ≤ 1000000, e.g. 2/8".into(),
                got: text.into(),
            })
        };
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if k == 0 || k > n || n > MAX_JOBS {
            return Err(bad());
        }
        Ok(Self { k, n })
    }

    pub fn all() -> Self {
        Self { k: 1, n: 1 }
    }

    pub fn contains(&self, job: usize) -> bool {
        job % self.n == self.k - 1
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

/// `--items A-B[:STEP]`: the jobs A, A + STEP, … up to B, both ends included (the
/// chunks of render farms); `A` alone is one job.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Items {
    pub first: usize,
    pub last: usize,
    pub step: usize,
}

impl Items {
    /// Parses `A-B`, `A-B:STEP` or `A` for a batch of `total` jobs.
    pub fn parse(text: &str, total: usize) -> Result<Self> {
        let bad = || {
            Error::Param(crate::error::ParamError {
                name: "--items".into(),
                allowed: format!(
                    "A-B or A-B:STEP, job numbers with 0 ≤ A ≤ B < {total} (the jobs of the batch) and STEP ≥ 1"
                ),
                got: text.into(),
            })
        };
        let (range, step) = match text.split_once(':') {
            Some((r, s)) => (r, s.trim().parse::<usize>().map_err(|_| bad())?),
            None => (text, 1),
        };
        let (a, b) = range.split_once('-').unwrap_or((range, range));
        let first: usize = a.trim().parse().map_err(|_| bad())?;
        let last: usize = b.trim().parse().map_err(|_| bad())?;
        if step == 0 || first > last || last >= total {
            return Err(bad());
        }
        Ok(Self { first, last, step })
    }

    pub fn contains(&self, job: usize) -> bool {
        (self.first..=self.last).contains(&job) && (job - self.first) % self.step == 0
    }
}

impl std::fmt::Display for Items {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}-{}", self.first, self.last)?;
        if self.step > 1 {
            write!(f, ":{}", self.step)?;
        }
        Ok(())
    }
}

/// The jobs of the batch that one run does: all, a shard, or items.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Selection {
    All,
    Shard(Shard),
    Items(Items),
}

impl Selection {
    pub fn contains(&self, job: usize) -> bool {
        match self {
            Selection::All => true,
            Selection::Shard(s) => s.contains(job),
            Selection::Items(i) => i.contains(job),
        }
    }

    /// The stem of this run's index files: `index`, `index.shard-K-of-N`, or
    /// `index.items-A-B` (`index.items-A-B-by-STEP`); `--merge-index` reads every one.
    pub fn index_stem(&self) -> String {
        match self {
            Selection::All => "index".into(),
            Selection::Shard(s) if s.n == 1 => "index".into(),
            Selection::Shard(s) => format!("index.shard-{}-of-{}", s.k, s.n),
            Selection::Items(i) if i.step > 1 => {
                format!("index.items-{}-{}-by-{}", i.first, i.last, i.step)
            }
            Selection::Items(i) => format!("index.items-{}-{}", i.first, i.last),
        }
    }
}

/// A manifest file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ManifestFile {
    /// Base preset of every job (a job may give its own).
    preset: Option<String>,
    /// Name template (`--name` wins).
    name: Option<String>,
    /// File kinds of every job (`--format` wins).
    format: Option<Vec<String>>,
    /// Assignments for every job.
    #[serde(default)]
    set: BTreeMap<String, Spanned<Value>>,
    /// Sweeps: KEY = [A, B, C] or "START:STOP:STEP"; their product runs over every job.
    #[serde(default)]
    sweep: BTreeMap<String, Spanned<Value>>,
    /// Jobs: each a table of assignments (and optionally `preset`).
    #[serde(default)]
    job: Vec<BTreeMap<String, Spanned<Value>>>,
}

/// A manifest, read and checked.
#[derive(Debug, Default)]
pub struct Manifest {
    pub preset: Option<String>,
    pub name: Option<String>,
    pub format: Option<Vec<String>>,
    pub set: Vec<Assignment>,
    pub sweeps: Vec<Sweep>,
    /// Each `[[job]]`: its preset and assignments (none: one job of the base).
    pub jobs: Vec<JobSpec>,
}

fn line_of(text: &str, at: usize) -> usize {
    text[..at.min(text.len())].matches('\n').count() + 1
}

/// `(key, value)` pairs of a TOML value, nested tables flattened to dotted keys; a table
/// with a `kind` is one value (setting a kind starts its table afresh).
fn flatten(prefix: &str, v: &Value, out: &mut Vec<(String, Value)>) {
    match v {
        Value::Table(t) if !t.contains_key("kind") => {
            for (k, v) in t {
                flatten(&format!("{prefix}.{k}"), v, out)
            }
        }
        other => out.push((prefix.to_string(), other.clone())),
    }
}

/// Assignments of one manifest table, each with its line, keys checked.
fn assignments(
    source: &str,
    text: &str,
    table: &BTreeMap<String, Spanned<Value>>,
) -> Result<Vec<Assignment>> {
    let mut out = Vec::new();
    for (key, v) in table {
        let line = line_of(text, v.span().start);
        let mut pairs = Vec::new();
        flatten(key, v.get_ref(), &mut pairs);
        for (k, value) in pairs {
            let value = match value {
                Value::String(s) => s,
                other => other.to_string(),
            };
            let origin = format!("{source}:{line}: {k}");
            check_key(&k, &value, &origin)?;
            out.push(Assignment {
                origin,
                key: k,
                value,
            });
        }
    }
    Ok(out)
}

impl Manifest {
    /// Reads `path`; syntax errors and unknown keys name the file and the line.
    pub fn load(path: &Path) -> Result<Self> {
        let source = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| Error::Input {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let file: ManifestFile = toml::from_str(&text).map_err(|e| {
            let line = e
                .span()
                .map(|s| format!(":{}", line_of(&text, s.start)))
                .unwrap_or_default();
            Error::Preset(format!(
                "{source}{line}: {}",
                e.message().split_whitespace().collect::<Vec<_>>().join(" ")
            ))
        })?;
        let set = assignments(&source, &text, &file.set)?;
        let mut sweeps = Vec::new();
        for (key, v) in &file.sweep {
            let line = line_of(&text, v.span().start);
            let origin = format!("{source}:{line}: {key}");
            let values = match v.get_ref() {
                Value::Array(a) => a
                    .iter()
                    .map(|x| match x {
                        Value::String(s) => s.clone(),
                        other => other.to_string(),
                    })
                    .collect(),
                Value::String(s) => Sweep::values_of(s).map_err(|message| Error::Set {
                    origin: origin.clone(),
                    message,
                })?,
                other => vec![other.to_string()],
            };
            if values.is_empty() {
                return Err(Error::Set {
                    origin,
                    message: "a sweep needs at least one value".into(),
                });
            }
            check_key(key, &values[0], &origin)?;
            sweeps.push(Sweep {
                key: key.clone(),
                values,
                origin,
            });
        }
        let mut jobs = Vec::new();
        for entry in &file.job {
            let mut entry = entry.clone();
            let preset = match entry.remove("preset") {
                Some(p) => match p.get_ref() {
                    Value::String(s) => Some(s.clone()),
                    _ => {
                        return Err(Error::Preset(format!(
                            "{source}:{}: preset must be a name or a file",
                            line_of(&text, p.span().start)
                        )));
                    }
                },
                None => None,
            };
            jobs.push(JobSpec {
                preset,
                assignments: assignments(&source, &text, &entry)?,
            });
        }
        Ok(Self {
            preset: file.preset,
            name: file.name,
            format: file.format,
            set,
            sweeps,
            jobs,
        })
    }
}

#[cfg(test)]
mod tests;
