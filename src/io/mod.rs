//! Reading height maps that seasynth (or another tool) wrote: one reader per format
//! behind [`HeightReader`], picked by a file's first bytes.

pub mod heightmap;
pub mod png16;
pub mod tiff32;

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::error::Error;
pub use heightmap::{ImageKind, Loaded, load, load_detailed};

/// Heights as a reader gives them: meters, row by row (row 0 is y = 0).
pub struct Heights {
    pub nx: usize,
    pub ny: usize,
    pub data: Vec<f32>,
    /// Meters per stored step, for quantized formats.
    pub quantization_step_m: Option<f64>,
}

/// A reader of one height-map format.
pub trait HeightReader: Sync {
    /// The kind of file it reads.
    fn kind(&self) -> ImageKind;

    /// True when a file starting with `head` (its first bytes, up to 8) is of this format.
    fn sniff(&self, head: &[u8]) -> bool;

    /// Reads the heights of `path`; `sidecar` is its sidecar (path and document), if any.
    fn read(&self, path: &Path, sidecar: Option<&(PathBuf, Value)>) -> Result<Heights, Error>;
}

/// Every reader, in the order they are tried.
pub const READERS: &[&dyn HeightReader] = &[&png16::Png16Reader, &tiff32::Tiff32Reader];

/// An input error about `path`, on one line whatever a decoder says.
pub(crate) fn input_error(path: &Path, message: impl std::fmt::Display) -> Error {
    let message = message.to_string().replace(['\n', '\r'], " ");
    Error::Input {
        path: path.to_path_buf(),
        message,
    }
}
