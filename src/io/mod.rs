//! Reading height maps that seasynth (or another tool) wrote: seasynth's own formats one
//! reader each behind [`HeightReader`], picked by a file's first bytes, and every other
//! image through `image` ([`raster`]).

pub mod heightmap;
pub mod png16;
pub mod raster;
pub mod tiff32;

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::error::Error;
pub use heightmap::{ImageKind, Loaded, load, load_detailed, load_with};

/// What the command line says about a height map that its file does not: the heights of
/// an integer image's extreme values (`--height-range`) and the extent (`--extent`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ReadOptions {
    /// Heights in meters of an integer image's smallest and largest value (0 and 255 or
    /// 65535), for images without a sidecar mapping.
    pub height_range: Option<(f64, f64)>,
    /// Extent in meters (x, y): the spacing is extent / samples, in place of the sidecar's.
    pub extent_m: Option<(f64, f64)>,
}

impl ReadOptions {
    /// Parses `--height-range MIN:MAX` and `--extent L|LXxLY` as typed.
    pub fn parse(height_range: Option<&str>, extent: Option<&str>) -> Result<Self, Error> {
        let height_range = height_range
            .map(|t| {
                let bad = || {
                    Error::Param(crate::error::ParamError {
                        name: "--height-range".into(),
                        allowed: "MIN:MAX in meters with finite MIN < MAX".into(),
                        got: t.into(),
                    })
                };
                let (a, b) = t.split_once(':').ok_or_else(bad)?;
                let (a, b): (f64, f64) = (
                    a.trim().parse().map_err(|_| bad())?,
                    b.trim().parse().map_err(|_| bad())?,
                );
                if a.is_finite() && b.is_finite() && a < b {
                    Ok((a, b))
                } else {
                    Err(bad())
                }
            })
            .transpose()?;
        let extent_m = extent
            .map(|t| {
                let bad = || {
                    Error::Param(crate::error::ParamError {
                        name: "--extent".into(),
                        allowed: "L or LXxLY in meters, finite numbers > 0".into(),
                        got: t.into(),
                    })
                };
                let (a, b) = t.split_once('x').unwrap_or((t, t));
                let (a, b): (f64, f64) = (
                    a.trim().parse().map_err(|_| bad())?,
                    b.trim().parse().map_err(|_| bad())?,
                );
                if a.is_finite() && b.is_finite() && a > 0.0 && b > 0.0 {
                    Ok((a, b))
                } else {
                    Err(bad())
                }
            })
            .transpose()?;
        Ok(Self {
            height_range,
            extent_m,
        })
    }
}

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
