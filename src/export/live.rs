//! The temporary files alive in this process, and what happens to them on SIGINT/SIGTERM.
//!
//! Every [`Staged`](super::Staged) file is registered here from its creation until it is
//! renamed over its target or dropped. [`install`] starts a thread that waits for SIGINT
//! or SIGTERM; on either it removes every registered file and exits with
//! [`INTERRUPTED`](crate::error::exit::INTERRUPTED) (75: interrupted, safe to retry).
//! Creation, renaming and the cleanup all hold one lock, so an
//! interrupted run leaves each output either complete (renamed before the signal) or
//! absent, and no temporary file — whatever the command, with no code of its own.
//!
//! [`install`] also ignores SIGXFSZ, so a file-size limit (`ulimit -f`) makes a write fail
//! with EFBIG, reported like any other write error, instead of killing the process.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};

/// Live temporary files by registration number.
static LIVE: Mutex<BTreeMap<u64, PathBuf>> = Mutex::new(BTreeMap::new());
static NEXT: AtomicU64 = AtomicU64::new(0);

/// The registry, locked; a poisoned lock (a panic while held) still gives the map.
pub(crate) fn lock() -> MutexGuard<'static, BTreeMap<u64, PathBuf>> {
    LIVE.lock().unwrap_or_else(|p| p.into_inner())
}

/// Registers `path` (with the lock held by the caller); returns its number.
pub(crate) fn register(live: &mut BTreeMap<u64, PathBuf>, path: &Path) -> u64 {
    let id = NEXT.fetch_add(1, Ordering::Relaxed);
    live.insert(id, path.to_path_buf());
    id
}

/// The temporary files alive now (for tests and diagnostics).
pub fn live_files() -> Vec<PathBuf> {
    lock().values().cloned().collect()
}

/// Removes every live temporary file; returns how many were removed. The lock stays
/// held by the caller's guard, so no file is created or renamed meanwhile.
fn remove_all(live: &mut BTreeMap<u64, PathBuf>) -> usize {
    let mut removed = 0;
    for path in live.values() {
        if std::fs::remove_file(path).is_ok() {
            removed += 1;
        }
    }
    live.clear();
    removed
}

/// Starts the signal thread (SIGINT, SIGTERM) and ignores SIGXFSZ. Call once, early in
/// `main`; a second call does nothing.
pub fn install() -> std::io::Result<()> {
    static STARTED: std::sync::Once = std::sync::Once::new();
    let mut result = Ok(());
    STARTED.call_once(|| result = start());
    result
}

#[cfg(unix)]
fn start() -> std::io::Result<()> {
    use crate::error::exit;
    use signal_hook::consts::{SIGINT, SIGTERM, SIGXFSZ};
    // SAFETY: setting a signal's disposition to SIG_IGN installs no handler code.
    unsafe {
        libc::signal(SIGXFSZ, libc::SIG_IGN);
    }
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM])?;
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                let mut live = lock();
                let removed = remove_all(&mut live);
                let name = if sig == SIGINT { "SIGINT" } else { "SIGTERM" };
                eprintln!(
                    "Error: interrupted by {name}; removed {removed} temporary file(s), no partial output; safe to retry (exit code {})",
                    exit::INTERRUPTED
                );
                // The guard is held until the process ends: nothing is renamed after this.
                std::process::exit(exit::INTERRUPTED);
            }
        })?;
    Ok(())
}

#[cfg(not(unix))]
fn start() -> std::io::Result<()> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removing_all_deletes_the_registered_files_and_empties_the_registry() {
        let dir = tempfile::tempdir().unwrap();
        let mut map = BTreeMap::new();
        let a = dir.path().join("a.part");
        std::fs::write(&a, b"x").unwrap();
        register(&mut map, &a);
        register(&mut map, &dir.path().join("gone.part"));
        assert_eq!(remove_all(&mut map), 1, "one file existed");
        assert!(!a.exists(), "the registered file is removed");
        assert!(map.is_empty());
    }
}
