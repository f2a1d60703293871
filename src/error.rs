//! Error types of the library. Messages are one line and name the value at fault and
//! what is allowed; [`Error::is_usage`] tells bad input (exit code 2) from failures.

use std::path::PathBuf;

/// A parameter outside its allowed range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{name} must be {allowed} (got {got})")]
pub struct ParamError {
    /// The parameter, as the user can write it (`--wind-speed (wind.speed_mps)`).
    pub name: String,
    /// What is allowed, e.g. `> 0 m/s`.
    pub allowed: String,
    /// The value given.
    pub got: String,
}

#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A preset or parameter file that does not parse or has unknown keys.
    #[error("{0}")]
    Preset(String),
    /// A `--set` or flag that does not parse or names an unknown key; `origin` is what
    /// the user typed (`--set wind.sped_mps=3`, `--size`).
    #[error("{origin}: {message}")]
    Set { origin: String, message: String },
    /// An output path that cannot be used (unknown extension, unwritable folder).
    #[error("output {path}: {message}")]
    Output { path: PathBuf, message: String },
    /// An input file (weight map, preset) that cannot be read or decoded.
    #[error("{path}: {message}")]
    Input { path: PathBuf, message: String },
    /// A run refused before the work: its estimated peak memory exceeds what is available.
    #[error(
        "{what} needs about {} of memory but {} is available: use a smaller --size, --method trochoid (streams any size), or --force to run anyway",
        crate::units::human_bytes(*needed_bytes),
        crate::units::human_bytes(*available_bytes)
    )]
    Memory {
        what: String,
        needed_bytes: u64,
        available_bytes: u64,
    },
    /// Parameters that are each allowed but together overflow the 32-bit float field.
    #[error(
        "{what} is not finite ({detail}): the parameters give heights beyond the 32-bit float range; lower the amplitudes or heights"
    )]
    NotFinite { what: String, detail: String },
    /// Reading or writing a file failed while working: the file and the OS error (shown
    /// once, not again as a cause).
    #[error("{path}: {error}")]
    Io {
        path: PathBuf,
        error: std::io::Error,
    },
}

impl Error {
    /// True for errors caused by the user's input (exit code 2).
    pub fn is_usage(&self) -> bool {
        !matches!(self, Error::Io { .. })
    }

    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            error: source,
        }
    }
}

/// The candidate closest to `word` by edit distance (case-insensitive), if it is close
/// enough to be what was meant: at most a third of the longer name's letters differ (in
/// names of three letters, only a swap). Ties go to the first candidate.
pub fn closest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let word = word.to_lowercase();
    candidates
        .into_iter()
        .filter(|c| !c.is_empty() && c.to_lowercase() != word)
        .map(|c| (edit_distance(&word, &c.to_lowercase()), c))
        .filter(|(d, c)| {
            let longer = word.chars().count().max(c.chars().count());
            match longer {
                // Three letters: only the same letters swapped (`pgn`), not another name
                // (`gif` is no misspelt `tif`).
                0..=3 => sorted(&word) == sorted(&c.to_lowercase()),
                _ => *d <= longer / 3,
            }
        })
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

fn sorted(text: &str) -> Vec<char> {
    let mut v: Vec<char> = text.chars().collect();
    v.sort_unstable();
    v
}

/// `; did you mean `X`?` for the [`closest`] candidate, or nothing.
pub fn did_you_mean<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    closest(word, candidates)
        .map(|c| format!("; did you mean `{c}`?"))
        .unwrap_or_default()
}

/// Levenshtein distance counted in characters, with an adjacent swap counting as one
/// edit (`wind-dri` → `wind-dir` is one slip).
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[a.len()][b.len()]
}

/// The exit codes of every command, for people and for schedulers (a Kubernetes
/// `podFailurePolicy`, a Slurm epilog) to act on: retry an interruption, never bad input.
pub mod exit {
    /// Every output complete.
    pub const DONE: i32 = 0;
    /// A failure while working (a write that failed: disk full, an I/O error); the
    /// outputs of the failed jobs are absent, never partial.
    pub const FAILED: i32 = 1;
    /// Bad input (a parameter, a preset, an input file, an output path, a run the memory
    /// guard refuses): the same command fails again, do not retry.
    pub const USAGE: i32 = 2;
    /// Interrupted by SIGINT or SIGTERM (a scheduler's preemption, cancel or time limit):
    /// outputs renamed before the signal are complete, no temporary file is left; safe to
    /// retry, with `--resume` for a batch (75 is `EX_TEMPFAIL` of sysexits.h).
    pub const INTERRUPTED: i32 = 75;
}

pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn close_names_are_suggested_and_far_ones_are_not() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(
            edit_distance("wind-dri", "wind-dir"),
            1,
            "a swap is one edit"
        );
        assert_eq!(edit_distance("", "abc"), 3);
        let presets = ["calm", "storm", "storm-loop", "swell", "li-tian"];
        assert_eq!(closest("strom", presets), Some("storm"));
        assert_eq!(
            closest("STORM-LOOP", presets),
            None,
            "the same name is no suggestion"
        );
        assert_eq!(closest("hurricane", presets), None);
        assert_eq!(closest("pgn", ["png", "tif", "exr"]), Some("png"));
        assert_eq!(
            closest("gif", ["png", "tif", "exr"]),
            None,
            "another format, no slip"
        );
        assert_eq!(
            did_you_mean("fftt", ["hybrid", "fft"]),
            "; did you mean `fft`?"
        );
        assert_eq!(did_you_mean("zzz", ["hybrid", "fft"]), "");
    }
}
