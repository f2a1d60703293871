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
