//! The index of a batch: `index.csv` and `index.json`, one row per job (its swept
//! values, files, statistics, time and status), and the merge of shard indexes.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::export::Staged;
use crate::grid::Stats;

/// How a job ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Computed and written in this run.
    Ok,
    /// Found complete from an earlier run (`--resume`) and kept.
    Kept,
    /// Failed; `error` says why.
    Failed,
}

impl Status {
    fn name(&self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Kept => "kept",
            Status::Failed => "failed",
        }
    }
}

/// One job of the index.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    pub job: usize,
    pub name: String,
    pub status: Status,
    /// The job's value of every swept key (as the keys were typed).
    pub params: BTreeMap<String, String>,
    /// The files written, relative to the index's folder (outputs, then the sidecar).
    pub files: Vec<String>,
    /// Statistics of the job's field.
    pub stats: Option<Stats>,
    /// Seconds the job took (none when kept from an earlier run).
    pub seconds: Option<f64>,
    /// The parameter hash recorded in the job's sidecar.
    pub hash: Option<String>,
    pub error: Option<String>,
    /// The scheduler whose task ran the job (`slurm`, `kubernetes`, `aws-batch`,
    /// `gcp-batch`), when the shard came from one (`--shard auto`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scheduler: Option<String>,
    /// That task as the scheduler names it (Slurm: `ARRAYJOBID_TASKID`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub task: Option<String>,
}

/// `index.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Index {
    pub tool: String,
    pub version: String,
    /// Identifies the batch (every job's name and parameter hash): shards of one batch share it.
    pub batch: String,
    /// Jobs in the whole batch.
    pub jobs: usize,
    /// The slice this index covers (`K/N`), none for a whole or merged batch.
    pub shard: Option<String>,
    /// The jobs this index covers when run with `--items` (`A-B`, `A-B:STEP`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub items: Option<String>,
    /// The scheduler and task that wrote this index (`--shard auto`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scheduler: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub task: Option<String>,
    /// The swept keys, in the order of the CSV columns.
    pub keys: Vec<String>,
    pub rows: Vec<Row>,
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn num(v: Option<f64>) -> String {
    v.map(|v| format!("{v}")).unwrap_or_default()
}

impl Index {
    /// The CSV text: `job,name,status,<keys>,files,hs_m,min_m,max_m,mean_m,std_m,seconds,error`,
    /// files separated by spaces; then `scheduler,task` when a scheduler ran any job.
    pub fn csv(&self) -> String {
        let tasks = self.rows.iter().any(|r| r.scheduler.is_some());
        let mut out = String::from("job,name,status");
        for k in &self.keys {
            out.push(',');
            out.push_str(&csv_field(k));
        }
        out.push_str(",files,hs_m,min_m,max_m,mean_m,std_m,seconds,error");
        out.push_str(if tasks { ",scheduler,task\n" } else { "\n" });
        for r in &self.rows {
            let mut cells = vec![
                r.job.to_string(),
                csv_field(&r.name),
                r.status.name().into(),
            ];
            for k in &self.keys {
                cells.push(csv_field(r.params.get(k).map_or("", String::as_str)));
            }
            cells.push(csv_field(&r.files.join(" ")));
            let s = r.stats;
            cells.push(num(s.map(|s| s.hs_m)));
            cells.push(num(s.map(|s| s.min_m)));
            cells.push(num(s.map(|s| s.max_m)));
            cells.push(num(s.map(|s| s.mean_m)));
            cells.push(num(s.map(|s| s.std_m)));
            cells.push(num(r.seconds));
            cells.push(csv_field(r.error.as_deref().unwrap_or("")));
            if tasks {
                cells.push(csv_field(r.scheduler.as_deref().unwrap_or("")));
                cells.push(csv_field(r.task.as_deref().unwrap_or("")));
            }
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    }

    /// Writes `STEM.json` and `STEM.csv` in `dir` (staged, renamed when complete).
    pub fn write(&self, dir: &Path, stem: &str) -> Result<()> {
        Staged::create(&dir.join(format!("{stem}.json")))?.write_json(self)?;
        let csv = self.csv();
        Staged::create(&dir.join(format!("{stem}.csv")))?
            .write_with(|w| std::io::Write::write_all(w, csv.as_bytes()))
    }

    pub fn read(path: &Path) -> Result<Self> {
        let bytes = std::fs::read(path).map_err(|e| Error::Input {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        serde_json::from_slice(&bytes).map_err(|e| Error::Input {
            path: path.to_path_buf(),
            message: format!("not a batch index: {e}"),
        })
    }
}

/// The index files to merge in `dir`: its shard and item indexes
/// (`index.shard-K-of-N.json`, `index.items-A-B.json`), or else its `index.json`.
fn indexes_in(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut shards = super::files_named(dir, |n| {
        (n.starts_with("index.shard-") || n.starts_with("index.items-")) && n.ends_with(".json")
    })
    .map_err(|e| Error::Input {
        path: dir.to_path_buf(),
        message: format!("cannot read the folder: {e}"),
    })?;
    shards.sort();
    if shards.is_empty() && dir.join("index.json").is_file() {
        shards.push(dir.join("index.json"));
    }
    if shards.is_empty() {
        return Err(Error::Input {
            path: dir.to_path_buf(),
            message:
                "holds no batch index (index.json, index.shard-K-of-N.json or index.items-A-B.json)"
                    .into(),
        });
    }
    Ok(shards)
}

/// The path of folder `dir` relative to folder `out` (`../b` for sibling folders), so
/// that a merged index in `out` names the files of every shard from where it lies.
fn prefix_from(out: &Path, dir: &Path) -> PathBuf {
    let canon = |p: &Path| {
        std::fs::canonicalize(p)
            .or_else(|_| std::path::absolute(p))
            .unwrap_or_else(|_| p.to_path_buf())
    };
    let (o, d) = (canon(out), canon(dir));
    let (oc, dc): (Vec<_>, Vec<_>) = (o.components().collect(), d.components().collect());
    let common = oc.iter().zip(&dc).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return d;
    }
    let mut rel = PathBuf::new();
    for _ in common..oc.len() {
        rel.push("..");
    }
    for c in &dc[common..] {
        rel.push(c);
    }
    rel
}

/// Merges the shard indexes found in `dirs` into one index of the whole batch, written
/// to `out` (`index.csv`, `index.json`). Every index must be of the same batch, and
/// together they must hold every job exactly once.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<Index> {
    let mut merged: Option<Index> = None;
    let mut seen: BTreeMap<usize, PathBuf> = BTreeMap::new();
    let mut rows = Vec::new();
    for dir in dirs {
        let prefix = prefix_from(out, dir);
        for path in indexes_in(dir)? {
            let index = Index::read(&path)?;
            if let Some(m) = &merged {
                if m.batch != index.batch || m.jobs != index.jobs {
                    return Err(Error::Input {
                        path,
                        message: format!(
                            "is the index of another batch ({} jobs, batch {}) than the first ({} jobs, batch {})",
                            index.jobs, index.batch, m.jobs, m.batch
                        ),
                    });
                }
            }
            for mut row in index.rows.clone() {
                if let Some(first) = seen.insert(row.job, path.clone()) {
                    return Err(Error::Input {
                        path,
                        message: format!("job {} is also in {}", row.job, first.display()),
                    });
                }
                row.files = row
                    .files
                    .iter()
                    .map(|f| prefix.join(f).to_string_lossy().into_owned())
                    .collect();
                rows.push(row);
            }
            merged.get_or_insert(index);
        }
    }
    let mut index = merged.ok_or_else(|| Error::Input {
        path: out.to_path_buf(),
        message: "--merge-index needs at least one folder".into(),
    })?;
    let missing: Vec<String> = (0..index.jobs)
        .filter(|j| !seen.contains_key(j))
        .map(|j| j.to_string())
        .collect();
    if !missing.is_empty() {
        let shown: Vec<String> = missing.iter().take(10).cloned().collect();
        return Err(Error::Input {
            path: out.to_path_buf(),
            message: format!(
                "the indexes miss {} of {} jobs ({}{}): merge every shard",
                missing.len(),
                index.jobs,
                shown.join(", "),
                if missing.len() > shown.len() {
                    ", …"
                } else {
                    ""
                }
            ),
        });
    }
    rows.sort_by_key(|r| r.job);
    index.rows = rows;
    index.shard = None;
    index.items = None;
    index.scheduler = None;
    index.task = None;
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    index.write(out, "index")?;
    Ok(index)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(job: usize) -> Row {
        Row {
            job,
            name: format!("{job}_a=\"x,y\""),
            status: Status::Ok,
            params: BTreeMap::from([("a".to_string(), "x,y".to_string())]),
            files: vec![format!("{job}.png"), format!("{job}.json")],
            stats: Some(Stats {
                hs_m: 1.0,
                min_m: -0.5,
                max_m: 0.5,
                mean_m: 0.0,
                std_m: 0.25,
            }),
            seconds: Some(0.5),
            hash: None,
            error: None,
            scheduler: None,
            task: None,
        }
    }

    #[test]
    fn shard_folders_are_named_from_the_merged_index() {
        let t = tempfile::tempdir().unwrap();
        let p = t.path();
        for d in ["a/s1", "b"] {
            std::fs::create_dir_all(p.join(d)).unwrap();
        }
        assert_eq!(prefix_from(&p.join("a"), &p.join("a/s1")), Path::new("s1"));
        assert_eq!(prefix_from(&p.join("a"), &p.join("a")), Path::new(""));
        assert_eq!(
            prefix_from(&p.join("a/s1"), &p.join("b")),
            Path::new("../../b")
        );
        assert_eq!(prefix_from(&p.join("new"), &p.join("b")), Path::new("../b"));
    }

    #[test]
    fn csv_cells_with_commas_and_quotes_are_quoted() {
        let index = Index {
            tool: "seasynth".into(),
            version: "0".into(),
            batch: "b".into(),
            jobs: 1,
            shard: None,
            items: None,
            scheduler: None,
            task: None,
            keys: vec!["a".into()],
            rows: vec![row(0)],
        };
        let csv = index.csv();
        let line = csv.lines().nth(1).unwrap();
        assert_eq!(
            line,
            "0,\"0_a=\"\"x,y\"\"\",ok,\"x,y\",0.png 0.json,1,-0.5,0.5,0,0.25,0.5,"
        );
        assert_eq!(csv.lines().next().unwrap().split(',').count(), 12);
        // Rows run by a scheduler's task add its two columns.
        let mut run = index.clone();
        run.rows[0].scheduler = Some("slurm".into());
        run.rows[0].task = Some("7_4".into());
        let csv = run.csv();
        let head = csv.lines().next().unwrap();
        assert!(head.ends_with(",error,scheduler,task"), "{head}");
        let line = csv.lines().nth(1).unwrap();
        assert!(line.ends_with(",0.5,,slurm,7_4"), "{line}");
    }
}
