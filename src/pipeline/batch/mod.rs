//! Batches: the plan of jobs (sweeps, manifests, shards, items, name templates), the
//! shard a scheduler's task runs, and the index of what every job wrote.

pub mod design;
pub mod files;
pub mod index;
pub mod list;
pub mod plan;
pub mod scheduler;

use std::path::{Path, PathBuf};

/// The entries of folder `dir` whose name is UTF-8 and satisfies `wanted`.
pub fn files_named(dir: &Path, wanted: impl Fn(&str) -> bool) -> std::io::Result<Vec<PathBuf>> {
    Ok(std::fs::read_dir(dir)?
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.file_name().and_then(|n| n.to_str()).is_some_and(&wanted))
        .collect())
}
