//! A batch on a live one-node Slurm cluster (docs/clusters.md): the Slurm script of the
//! docs submitted as `sbatch --array=1-7:3` with `--shard auto`, one task requeued once
//! running, one cancelled and resumed by submitting the array again, then
//! `--merge-index`; the files must be byte for byte those of one unsharded local run.
//!
//! The cluster is the one `.ci/run` starts (`SLURM_CONF`), or one this test starts with
//! `.ci/slurm.sh` and stops when done. Without Slurm (not installed, not root, the
//! daemons do not start) the test prints why and is skipped.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use serde_json::Value;

/// The batch of every task: 9 FFT seas of 1536², 3 per task, slow enough (a few seconds
/// a task) to be caught running when the test requeues or cancels it.
const MANIFEST: &str = r#"format = ["png", "tif"]

[set]
method = "fft"
size = 1536
extent = 2048

[sweep]
seed = "1:10:1"
"#;
const JOBS: usize = 9;

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

/// A running cluster: its `slurm.conf`, and its folder when this test started it.
struct Cluster {
    conf: PathBuf,
    started: Option<tempfile::TempDir>,
}

impl Drop for Cluster {
    fn drop(&mut self) {
        if let Some(dir) = &self.started {
            let status = Command::new("bash")
                .arg(script())
                .arg("stop")
                .arg(dir.path())
                .status();
            if !status.is_ok_and(|s| s.success()) {
                eprintln!(
                    "could not stop the Slurm daemons of {}",
                    dir.path().display()
                );
            }
        }
    }
}

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(".ci/slurm.sh")
}

impl Cluster {
    fn command(&self, program: &str) -> Command {
        let mut c = Command::new(program);
        c.env("SLURM_CONF", &self.conf);
        c
    }

    fn output(&self, program: &str, args: &[&str], dir: &Path) -> String {
        let out = self
            .command(program)
            .args(args)
            .current_dir(dir)
            .output()
            .unwrap_or_else(|e| panic!("{program} does not run: {e}"));
        assert!(
            out.status.success(),
            "{program} {} failed: {}",
            args.join(" "),
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).into_owned()
    }

    fn idle(&self) -> bool {
        self.command("sinfo")
            .args(["-h", "-o", "%t"])
            .output()
            .is_ok_and(|o| {
                String::from_utf8_lossy(&o.stdout)
                    .lines()
                    .any(|l| l == "idle")
            })
    }
}

/// A free TCP port of 127.0.0.1 (free when asked; the daemons bind it right after).
fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port")
}

/// The cluster of `SLURM_CONF`, or a new one; `Err` says why there is none.
fn cluster() -> Result<Cluster, String> {
    if let Some(conf) = std::env::var_os("SLURM_CONF") {
        let c = Cluster {
            conf: conf.into(),
            started: None,
        };
        if c.idle() {
            return Ok(c);
        }
        eprintln!(
            "SLURM_CONF={} has no idle node: starting a cluster",
            c.conf.display()
        );
    }
    let missing: Vec<&str> = ["sbatch", "slurmctld", "slurmd", "munged"]
        .into_iter()
        .filter(|p| {
            !std::env::var_os("PATH").is_some_and(|path| {
                std::env::split_paths(&path)
                    .chain([PathBuf::from("/usr/sbin"), PathBuf::from("/sbin")])
                    .any(|d| d.join(p).is_file())
            })
        })
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "{} not installed (Debian's slurm-wlm and munge; .ci/run installs them)",
            missing.join(", ")
        ));
    }
    // SAFETY: geteuid has no preconditions.
    if unsafe { libc::geteuid() } != 0 {
        return Err("the Slurm daemons need root".into());
    }
    let dir = tempfile::Builder::new()
        .prefix("seasynth-slurm")
        .tempdir()
        .map_err(|e| e.to_string())?;
    let out = Command::new("bash")
        .arg(script())
        .arg("start")
        .arg(dir.path())
        .env(
            "SLURM_TEST_PORTS",
            format!("{} {}", free_port(), free_port()),
        )
        .output()
        .map_err(|e| format!("{} does not run: {e}", script().display()))?;
    let c = Cluster {
        conf: dir.path().join("slurm.conf"),
        started: Some(dir),
    };
    if !out.status.success() {
        return Err(format!(
            "the cluster did not start: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    Ok(c)
}

/// The script of docs/clusters.md (the bash block with `#SBATCH` lines).
fn docs_script() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/clusters.md");
    let text = std::fs::read_to_string(path).expect("docs/clusters.md");
    text.split("```bash\n")
        .skip(1)
        .map(|b| b.split("\n```").next().unwrap().to_string())
        .find(|b| b.contains("#SBATCH"))
        .expect("a Slurm script in docs/clusters.md")
}

/// Each task of array job `job` by its task ID: (JobState, ExitCode, Restarts).
fn tasks(c: &Cluster, job: &str, dir: &Path) -> BTreeMap<usize, (String, String, usize)> {
    let text = c.output("scontrol", &["show", "job", job, "-o"], dir);
    let mut out = BTreeMap::new();
    for line in text.lines() {
        let field = |name: &str| {
            line.split_whitespace()
                .find_map(|w| w.strip_prefix(&format!("{name}=")))
                .unwrap_or_default()
                .to_string()
        };
        if let Ok(id) = field("ArrayTaskId").parse::<usize>() {
            let restarts = field("Restarts").parse().unwrap_or(0);
            out.insert(id, (field("JobState"), field("ExitCode"), restarts));
        }
    }
    out
}

/// Waits until no task of array job `job` is pending or running.
fn wait_done(c: &Cluster, job: &str, dir: &Path, logs: &Path) {
    let t0 = Instant::now();
    loop {
        let queued = c.output("squeue", &["-h", "-j", job, "-o", "%i %T"], dir);
        if queued.trim().is_empty() {
            return;
        }
        if t0.elapsed() > Duration::from_secs(180) {
            let logs: Vec<String> = std::fs::read_dir(logs)
                .unwrap()
                .filter_map(|e| e.ok())
                .filter(|e| e.file_name().to_string_lossy().ends_with(".log"))
                .map(|e| std::fs::read_to_string(e.path()).unwrap_or_default())
                .collect();
            panic!(
                "job {job} not done in 3 minutes:\n{queued}\n{}",
                logs.join("\n")
            );
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// Waits until task `id` of array job `job` is RUNNING.
/// Waits until task `id` runs and its script has started (its first log line is
/// written): a task that Slurm reports RUNNING may not have run a line yet on a busy node.
fn wait_running(c: &Cluster, job: &str, id: usize, dir: &Path) {
    let t0 = Instant::now();
    let log = dir.join(format!("sea-{job}_{id}.log"));
    loop {
        if let Some((state, _, _)) = tasks(c, job, dir).get(&id) {
            let started = std::fs::read_to_string(&log).is_ok_and(|t| t.contains(", run 0"));
            if state == "RUNNING" && started {
                return;
            }
            assert!(
                state == "PENDING" || state == "RUNNING",
                "task {id} is {state}: it ended before the test could act on it (slower jobs needed)"
            );
        }
        assert!(
            t0.elapsed() < Duration::from_secs(120),
            "task {id} never ran"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn job_files(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with("index") && n != "batch.json")
        .collect()
}

fn seasynth(dir: &Path, args: &[&str]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_seasynth"));
    cmd.current_dir(dir).args(args);
    for v in SCHEDULER_VARS {
        cmd.env_remove(v);
    }
    let out = cmd.output().expect("seasynth runs");
    assert!(
        out.status.success(),
        "seasynth {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

#[test]
fn an_array_job_with_a_requeue_and_a_cancel_merges_to_the_bytes_of_one_local_run() {
    let t0 = Instant::now();
    let c = match cluster() {
        Ok(c) => c,
        Err(why) => {
            eprintln!("SKIPPED: no Slurm cluster: {why}");
            return;
        }
    };
    let work = tempfile::tempdir().unwrap();
    let w = work.path();
    std::fs::write(w.join("sea.toml"), MANIFEST).unwrap();
    std::fs::write(w.join("sea.sh"), docs_script()).unwrap();
    // The local reference: the script's batch, unsharded.
    seasynth(
        w,
        &[
            "batch",
            "--manifest",
            "sea.toml",
            "--height-range",
            "-20:20",
            "-q",
            "-o",
            "whole",
        ],
    );
    assert_eq!(job_files(&w.join("whole")).len(), 3 * JOBS);

    // The tasks find `seasynth` on PATH (sbatch passes the environment on).
    let bin = Path::new(env!("CARGO_BIN_EXE_seasynth")).parent().unwrap();
    let path = std::env::join_paths(std::iter::once(bin.to_path_buf()).chain(
        std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default()),
    ))
    .unwrap();
    let submit = |array: &str| {
        let mut cmd = c.command("sbatch");
        cmd.current_dir(w)
            .env("PATH", &path)
            .args(["--parsable", &format!("--array={array}")]);
        // The script asks for 2 CPUs a task; a node with fewer runs them with 1.
        if std::thread::available_parallelism().map_or(1, |n| n.get()) < 2 {
            cmd.arg("--cpus-per-task=1");
        }
        cmd.arg("sea.sh");
        for v in SCHEDULER_VARS {
            cmd.env_remove(v);
        }
        let out = cmd.output().expect("sbatch runs");
        assert!(
            out.status.success(),
            "sbatch: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).trim().to_string()
    };

    // Tasks 1, 4 and 7: slices 1/3, 2/3, 3/3. Task 4 is requeued once running, task 7
    // cancelled once running.
    let a = submit("1-7:3");
    wait_running(&c, &a, 4, w);
    c.output("scontrol", &["requeue", &format!("{a}_4")], w);
    wait_running(&c, &a, 7, w);
    c.output("scancel", &[&format!("{a}_7")], w);
    wait_done(&c, &a, w, w);
    let first = tasks(&c, &a, w);
    eprintln!("first submission {a}: {first:?}");
    assert_eq!(first[&1].0, "COMPLETED", "task 1: {first:?}");
    assert_eq!(first[&1].1, "0:0");
    assert_eq!(
        (first[&4].0.as_str(), first[&4].2),
        ("COMPLETED", 1),
        "task 4 ran twice"
    );
    assert_eq!(first[&4].1, "0:0");
    assert_eq!(first[&7].0, "CANCELLED", "task 7: {first:?}");
    let log4 = std::fs::read_to_string(w.join(format!("sea-{a}_4.log"))).unwrap();
    assert!(
        log4.contains(", run 0") && log4.contains(", run 1"),
        "--open-mode=append keeps both runs of the requeued task:\n{log4}"
    );
    let sea = w.join("sea");
    assert!(
        !sea.join("index.shard-3-of-3.json").exists(),
        "the cancelled task wrote no index"
    );
    let parts: Vec<String> = std::fs::read_dir(&sea)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".part"))
        .collect();
    assert_eq!(
        parts,
        Vec::<String>::new(),
        "SIGTERM removed the temporary files"
    );

    // The array again: tasks 1 and 4 keep everything, task 7 does what was missing.
    let b = submit("1-7:3");
    wait_done(&c, &b, w, w);
    let second = tasks(&c, &b, w);
    eprintln!("second submission {b}: {second:?}");
    for id in [1, 4, 7] {
        assert_eq!(second[&id].0, "COMPLETED", "task {id}: {second:?}");
        assert_eq!(second[&id].1, "0:0", "task {id}: {second:?}");
    }
    seasynth(w, &["batch", "--merge-index", "sea", "-q"]);

    // Byte for byte the local run.
    let whole = w.join("whole");
    assert_eq!(job_files(&sea), job_files(&whole), "the same files");
    for f in job_files(&whole) {
        assert!(
            std::fs::read(sea.join(&f)).unwrap() == std::fs::read(whole.join(&f)).unwrap(),
            "{f} differs from the local run's"
        );
    }
    // The index says which task wrote each job.
    let index: Value =
        serde_json::from_slice(&std::fs::read(sea.join("index.json")).unwrap()).unwrap();
    let rows = index["rows"].as_array().unwrap();
    assert_eq!(rows.len(), JOBS);
    let mut resumed = 0;
    for r in rows {
        let job = r["job"].as_u64().unwrap() as usize;
        let (status, task) = (r["status"].as_str().unwrap(), &r["task"]);
        match job % 3 {
            0 => assert_eq!(
                (status, task),
                ("kept", &Value::from(format!("{a}_1"))),
                "{r}"
            ),
            // Kept by the rerun of the requeued task, or by the resubmission.
            1 => assert!(
                status == "kept" && (task == &Value::from(format!("{a}_4")) || task.is_null()),
                "{r}"
            ),
            _ if status == "ok" => {
                assert_eq!(task, &Value::from(format!("{b}_7")), "{r}");
                resumed += 1;
            }
            // Complete before the cancel, kept; the cancelled task wrote no index to say so.
            _ => assert_eq!((status, task), ("kept", &Value::Null), "{r}"),
        }
    }
    assert!(resumed >= 1, "the cancel left work for the resubmission");
    eprintln!(
        "the Slurm test took {:.1} s ({resumed} jobs of the cancelled task done by the resubmission)",
        t0.elapsed().as_secs_f64()
    );
}
