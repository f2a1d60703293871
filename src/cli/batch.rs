//! `seasynth batch`.

use std::path::PathBuf;

use clap::Args;

use super::{ExportArgs, FieldArgs};

#[derive(Debug, Args)]
pub struct BatchArgs {
    #[command(flatten)]
    pub field: FieldArgs,
    /// KEY=A,B,C or KEY=START:STOP:STEP (STOP excluded) over any parameter (flag name or
    /// preset key); several sweeps give their cartesian product; values are checked against
    /// the key's type before anything is written [default: none]
    #[arg(long, value_name = "KEY=VALUES")]
    pub sweep: Vec<String>,
    /// A TOML manifest: base preset, a set table of overrides, sweep tables, job entries
    /// [default: none]
    #[arg(long, value_name = "FILE.toml")]
    pub manifest: Option<PathBuf>,
    /// Output folder (created if missing); with --merge-index, where the merged index goes
    /// [default: none, required but with --plan; with --merge-index the first DIR]
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    pub dir: Option<PathBuf>,
    /// File name template: {index} and {KEY} for any key (default: the index and every swept key)
    #[arg(long, value_name = "TEMPLATE")]
    pub name: Option<String>,
    /// Files per job: png, tif, exr, r16, r32, raw, obj, glb, normal, foam, jacobian, disp,
    /// preview, or a map as EXR (disp.exr, normal.exr, foam.exr, jacobian.exr) [default: png]
    #[arg(long, value_delimiter = ',')]
    pub format: Vec<String>,
    /// Jobs computed at once [default: cores, limited by memory]
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
    /// Run only the K-th of N disjoint slices of the jobs (job i is in slice i mod N + 1);
    /// `auto`: the slice of this scheduler task (Slurm, Kubernetes, AWS or GCP Batch), as
    /// found without --shard (default: every job, or the scheduler task's slice)
    #[arg(long, value_name = "K/N|auto")]
    pub shard: Option<String>,
    // ---- Schedulers, work items and the plan ----
    /// With --shard auto: the shards of the whole batch, when the scheduler does not export
    /// its task count (Kubernetes) or one array was split into several submissions
    /// (default: the scheduler's task count)
    #[arg(long, value_name = "N")]
    pub shard_count: Option<usize>,
    /// With --shard auto: the shard (from 0) of this submission's first task, for an array
    /// split into several submissions
    #[arg(long, value_name = "M", default_value_t = 0)]
    pub shard_offset: usize,
    /// Run exactly the jobs A to B (both included), every STEP-th (default STEP 1); a
    /// render farm's chunk [default: every job]
    #[arg(long, value_name = "A-B[:STEP]", conflicts_with = "shard")]
    pub items: Option<String>,
    /// Print every job (or those of --shard/--items): its number, name, seed and swept
    /// values as CSV, and compute nothing
    #[arg(long)]
    pub plan: bool,
    /// With --plan: print JSON instead of CSV
    #[arg(long, requires = "plan")]
    pub json: bool,
    // ---- end of schedulers, work items and the plan ----
    /// Keep jobs whose files and sidecar are complete and match the job's parameters
    #[arg(long)]
    pub resume: bool,
    /// Merge the shard (and --items) indexes found in these folders into one index.csv and
    /// index.json [default: none]
    #[arg(long, value_name = "DIR", num_args = 1..)]
    pub merge_index: Vec<PathBuf>,
    // Random designs (`--sample N --vary KEY=DIST`).
    /// Draw N points of the --vary distributions, one job each (with --sweep, each point
    /// runs the whole sweep; with a manifest, each of its jobs runs every point); default:
    /// no design
    #[arg(long, value_name = "N")]
    pub sample: Option<usize>,
    /// KEY=DIST over any --sweep key, DIST one of uniform:A:B, log-uniform:A:B,
    /// normal:MEAN:SD, normal:MEAN:SD:MIN:MAX, int:A:B, choice:A|B|C (repeatable; default:
    /// none)
    #[arg(long, value_name = "KEY=DIST")]
    pub vary: Vec<String>,
    /// How the --sample points are drawn: random (each value independently) or lhs (Latin
    /// hypercube: each of N equal-probability strata of every key hit once)
    #[arg(long, value_name = "KIND", default_value = "random")]
    pub design: String,
    /// Seed of the design's draws (default: the batch's --seed)
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub design_seed: Option<String>,
    /// How meshes, raw height maps and tiles are written
    #[command(flatten)]
    pub export: ExportArgs,
    /// Print nothing but errors (and the scheduler task found without --shard)
    #[arg(short, long)]
    pub quiet: bool,
    /// Worker threads; results do not depend on it [default: all cores]
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
}
