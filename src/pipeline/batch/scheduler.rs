//! The shard of a batch from a scheduler's task index: Slurm array jobs, Kubernetes
//! Indexed Jobs, AWS Batch and GCP Batch array jobs (`--shard auto`).
//!
//! Each scheduler hands every task of an array an index in its environment; the task's
//! shard is that index counted from 0 within the array (plus `--shard-offset` when one
//! array was split into several submissions), of the array's size (or `--shard-count`).
//! Slurm's `--array=1-7:3` runs tasks 1, 4 and 7: K = (ID − MIN)/STEP gives 0, 1, 2.

use crate::error::{Error, ParamError, Result};

use super::plan::{MAX_JOBS, Shard};

/// A scheduler whose array tasks seasynth reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheduler {
    Slurm,
    Kubernetes,
    AwsBatch,
    GcpBatch,
}

impl Scheduler {
    /// The name recorded in indexes (`slurm`, `kubernetes`, `aws-batch`, `gcp-batch`).
    pub fn name(&self) -> &'static str {
        match self {
            Scheduler::Slurm => "slurm",
            Scheduler::Kubernetes => "kubernetes",
            Scheduler::AwsBatch => "aws-batch",
            Scheduler::GcpBatch => "gcp-batch",
        }
    }

    /// The environment variable holding the task's index.
    pub fn index_variable(&self) -> &'static str {
        match self {
            Scheduler::Slurm => "SLURM_ARRAY_TASK_ID",
            Scheduler::Kubernetes => "JOB_COMPLETION_INDEX",
            Scheduler::AwsBatch => "AWS_BATCH_JOB_ARRAY_INDEX",
            Scheduler::GcpBatch => "BATCH_TASK_INDEX",
        }
    }
}

/// The order in which the schedulers are looked for.
const ORDER: [Scheduler; 4] = [
    Scheduler::Slurm,
    Scheduler::Kubernetes,
    Scheduler::AwsBatch,
    Scheduler::GcpBatch,
];

/// A task of a scheduler's array, and the shard it runs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Task {
    pub scheduler: Scheduler,
    /// The task as the scheduler names it: `JOBID_ID` for Slurm (or `ID`), the index for
    /// the others.
    pub task: String,
    pub shard: Shard,
}

impl Task {
    /// The one line a batch prints when it found its shard this way.
    pub fn describe(&self) -> String {
        format!(
            "{} task {} ({}): shard {}",
            self.scheduler.name(),
            self.task,
            self.scheduler.index_variable(),
            self.shard
        )
    }
}

/// What the command line says beside `--shard auto`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Overrides {
    /// `--shard-count N`: the shards of the whole batch (every submission's tasks).
    pub count: Option<usize>,
    /// `--shard-offset M`: the shard (from 0) of this submission's first task.
    pub offset: usize,
}

fn bad(allowed: String, got: String) -> Error {
    Error::Param(ParamError {
        name: "--shard auto".into(),
        allowed,
        got,
    })
}

fn number(env: &dyn Fn(&str) -> Option<String>, var: &str) -> Result<Option<usize>> {
    match env(var) {
        None => Ok(None),
        Some(v) => v.trim().parse().map(Some).map_err(|_| {
            bad(
                format!("given a whole number ≥ 0 in {var}"),
                format!("{var}={v}"),
            )
        }),
    }
}

/// The scheduler whose index variable is set, first in the order Slurm, Kubernetes, AWS
/// Batch, GCP Batch.
pub fn find(env: &dyn Fn(&str) -> Option<String>) -> Option<Scheduler> {
    ORDER
        .into_iter()
        .find(|s| env(s.index_variable()).is_some())
}

/// The task and shard from the environment `env` (a variable's value by name), or `None`
/// when no scheduler's index is set. Refuses what cannot give a shard: a Slurm list array
/// (`--array=0,2,5`), a count that is unknown (Kubernetes, AWS Batch without
/// `AWS_BATCH_JOB_ARRAY_SIZE`: pass `--shard-count`), or an index outside the count.
pub fn detect(env: &dyn Fn(&str) -> Option<String>, over: Overrides) -> Result<Option<Task>> {
    let Some(scheduler) = find(env) else {
        return Ok(None);
    };
    let var = scheduler.index_variable();
    let id = number(env, var)?.expect("found by its index variable");
    let (local, count, task) = match scheduler {
        Scheduler::Slurm => {
            let min = number(env, "SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let step = number(env, "SLURM_ARRAY_TASK_STEP")?.unwrap_or(1).max(1);
            let max = number(env, "SLURM_ARRAY_TASK_MAX")?;
            let tasks = number(env, "SLURM_ARRAY_TASK_COUNT")?;
            let range = max.filter(|&m| m >= min).map(|m| (m - min) / step + 1);
            let list = |why: &str| {
                bad(
                    "a Slurm range array (--array=A-B or A-B:STEP); for a list array pass \
                     --shard K/N explicitly or submit a range"
                        .into(),
                    why.into(),
                )
            };
            if id < min || (id - min) % step != 0 {
                return Err(list(&format!(
                    "task {id} is not MIN + i·STEP of MIN {min}, STEP {step}"
                )));
            }
            match (tasks, range) {
                (Some(t), Some(r)) if t != r => {
                    return Err(list(&format!(
                        "{t} tasks between {min} and {} by {step}: a list array",
                        max.unwrap_or(min)
                    )));
                }
                _ => {}
            }
            let task = match env("SLURM_ARRAY_JOB_ID") {
                Some(j) => format!("{}_{id}", j.trim()),
                None => id.to_string(),
            };
            ((id - min) / step, tasks.or(range), task)
        }
        Scheduler::Kubernetes => (id, None, id.to_string()),
        Scheduler::AwsBatch => (id, number(env, "AWS_BATCH_JOB_ARRAY_SIZE")?, id.to_string()),
        Scheduler::GcpBatch => (id, number(env, "BATCH_TASK_COUNT")?, id.to_string()),
    };
    if over.offset > 0 && over.count.is_none() {
        return Err(bad(
            "used with --shard-count N, the shards of every submission together".into(),
            format!("--shard-offset {} without --shard-count", over.offset),
        ));
    }
    let n = over.count.or(count).ok_or_else(|| {
        bad(
            format!(
                "told the number of tasks with --shard-count N ({} does not export it)",
                scheduler.name()
            ),
            format!("{var}={id} and no count"),
        )
    })?;
    let k0 = local + over.offset;
    if n == 0 || n > MAX_JOBS || k0 >= n {
        return Err(bad(
            format!("a task from 0 to the shard count − 1 (≤ {MAX_JOBS})"),
            format!("task {k0} (index {id} + offset {}) of {n}", over.offset),
        ));
    }
    Ok(Some(Task {
        scheduler,
        task,
        shard: Shard { k: k0 + 1, n },
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env(vars: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let vars: Vec<(String, String)> = vars
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        move |k| vars.iter().find(|(n, _)| n == k).map(|(_, v)| v.clone())
    }

    fn slurm(
        id: usize,
        min: usize,
        max: usize,
        step: usize,
        count: usize,
    ) -> Vec<(String, String)> {
        [
            ("SLURM_ARRAY_JOB_ID", "42".to_string()),
            ("SLURM_ARRAY_TASK_ID", id.to_string()),
            ("SLURM_ARRAY_TASK_MIN", min.to_string()),
            ("SLURM_ARRAY_TASK_MAX", max.to_string()),
            ("SLURM_ARRAY_TASK_STEP", step.to_string()),
            ("SLURM_ARRAY_TASK_COUNT", count.to_string()),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect()
    }

    fn shard_of(vars: &[(String, String)], over: Overrides) -> Result<Option<Task>> {
        let pairs: Vec<(&str, &str)> = vars.iter().map(|(k, v)| (k.as_str(), v.as_str())).collect();
        detect(&env(&pairs), over)
    }

    #[test]
    fn a_slurm_range_with_a_step_gives_consecutive_shards() {
        // --array=1-7:3: tasks 1, 4, 7 (what Slurm 22.05 exports, as read on a live cluster).
        let shards: Vec<Shard> = [1, 4, 7]
            .iter()
            .map(|&id| {
                shard_of(&slurm(id, 1, 7, 3, 3), Overrides::default())
                    .unwrap()
                    .unwrap()
                    .shard
            })
            .collect();
        assert_eq!(
            shards,
            [
                Shard { k: 1, n: 3 },
                Shard { k: 2, n: 3 },
                Shard { k: 3, n: 3 }
            ]
        );
        let t = shard_of(&slurm(4, 1, 7, 3, 3), Overrides::default())
            .unwrap()
            .unwrap();
        assert_eq!((t.scheduler, t.task.as_str()), (Scheduler::Slurm, "42_4"));
    }

    #[test]
    fn a_slurm_list_array_is_refused_with_what_to_do() {
        // --array=0,2,5: STEP reads 1, COUNT 3, but MIN..MAX spans 6.
        let e = shard_of(&slurm(2, 0, 5, 1, 3), Overrides::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("--shard K/N") && e.contains("range"), "{e}");
        assert!(e.contains("list array"), "{e}");
    }

    #[test]
    fn an_array_split_into_submissions_takes_an_offset_and_the_whole_count() {
        // 2500 shards as --array=0-999 three times (MaxArraySize 1001): the third's task 7.
        let over = Overrides {
            count: Some(2500),
            offset: 2000,
        };
        let t = shard_of(&slurm(7, 0, 499, 1, 500), over).unwrap().unwrap();
        assert_eq!(t.shard, Shard { k: 2008, n: 2500 });
        let e = shard_of(
            &slurm(7, 0, 499, 1, 500),
            Overrides {
                count: None,
                offset: 2000,
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("--shard-count"), "{e}");
        let e = shard_of(
            &slurm(600, 0, 999, 1, 1000),
            Overrides {
                count: Some(2500),
                offset: 2000,
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("2600") && e.contains("2500"), "{e}");
    }

    #[test]
    fn kubernetes_needs_the_count_and_the_others_export_it() {
        let k8s = [("JOB_COMPLETION_INDEX", "3")];
        let e = detect(&env(&k8s), Overrides::default()).unwrap_err();
        assert!(
            e.is_usage() && e.to_string().contains("--shard-count"),
            "{e}"
        );
        let over = Overrides {
            count: Some(8),
            offset: 0,
        };
        let t = detect(&env(&k8s), over).unwrap().unwrap();
        assert_eq!(
            (t.scheduler, t.shard),
            (Scheduler::Kubernetes, Shard { k: 4, n: 8 })
        );
        let aws = [
            ("AWS_BATCH_JOB_ARRAY_INDEX", "0"),
            ("AWS_BATCH_JOB_ARRAY_SIZE", "5"),
        ];
        let t = detect(&env(&aws), Overrides::default()).unwrap().unwrap();
        assert_eq!(
            (t.scheduler, t.shard),
            (Scheduler::AwsBatch, Shard { k: 1, n: 5 })
        );
        let gcp = [("BATCH_TASK_INDEX", "4"), ("BATCH_TASK_COUNT", "5")];
        let t = detect(&env(&gcp), Overrides::default()).unwrap().unwrap();
        assert_eq!(
            (t.scheduler, t.shard),
            (Scheduler::GcpBatch, Shard { k: 5, n: 5 })
        );
        let e = detect(
            &env(&[("BATCH_TASK_INDEX", "5"), ("BATCH_TASK_COUNT", "5")]),
            Overrides::default(),
        );
        assert!(e.is_err(), "index 5 of 5 tasks");
        assert_eq!(detect(&env(&[]), Overrides::default()).unwrap(), None);
        let e = detect(&env(&[("BATCH_TASK_INDEX", "x")]), Overrides::default()).unwrap_err();
        assert!(e.to_string().contains("BATCH_TASK_INDEX=x"), "{e}");
    }

    #[test]
    fn slurm_comes_first_when_several_are_set() {
        let mut vars = slurm(1, 0, 1, 1, 2);
        vars.push(("JOB_COMPLETION_INDEX".into(), "0".into()));
        let t = shard_of(&vars, Overrides::default()).unwrap().unwrap();
        assert_eq!(t.scheduler, Scheduler::Slurm);
    }
}
