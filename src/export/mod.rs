//! Writing height fields to files.
//!
//! The format of each output follows its extension. Every file is staged: a temporary
//! file is created next to the target before any computation (so a bad path fails at
//! once), written, flushed, and renamed over the target only when complete. An error or
//! an interruption leaves no partial file and any earlier file of that name intact.
//!
//! Rows: every format stores grid row j (y = j·dy) as image row j, row 0 first, so in an
//! image viewer +x points right and +y points down.

pub mod png16;
pub mod rgb8;
pub mod sidecar;
pub mod tiff32;

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;
use tempfile::NamedTempFile;

use crate::error::{Error, Result};
use crate::grid::Grid;

/// Output formats, chosen by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Format {
    /// `.png`: 16-bit grayscale, heights mapped linearly to 0..65535.
    Png16,
    /// `.tif`, `.tiff`: 32-bit float, one channel, meters.
    Tiff32,
}

/// Extensions and what they give, for error messages and the README.
pub const EXTENSIONS: &[(&str, Format)] = &[
    ("png", Format::Png16),
    ("tif", Format::Tiff32),
    ("tiff", Format::Tiff32),
];

impl Format {
    /// The format of `path` by its extension (case-insensitive).
    pub fn from_path(path: &Path) -> Result<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .unwrap_or_default();
        EXTENSIONS
            .iter()
            .find(|(e, _)| *e == ext)
            .map(|(_, f)| *f)
            .ok_or_else(|| {
                let allowed: Vec<String> =
                    EXTENSIONS.iter().map(|(e, _)| format!(".{e}")).collect();
                Error::Output {
                    path: path.to_path_buf(),
                    message: format!(
                        "unknown extension `{}` (allowed: {})",
                        if ext.is_empty() {
                            "(none)".to_string()
                        } else {
                            format!(".{ext}")
                        },
                        allowed.join(", ")
                    ),
                }
            })
    }
}

/// The linear map from heights to 16-bit values: v = round((h − min_m)/(max_m − min_m)·65535),
/// clamped to 0..65535. A flat field (min = max) maps to 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HeightMapping {
    pub min_m: f64,
    pub max_m: f64,
}

impl HeightMapping {
    /// Meters per 16-bit step.
    pub fn step_m(&self) -> f64 {
        (self.max_m - self.min_m) / 65535.0
    }

    #[inline]
    pub fn encode(&self, h: f32) -> u16 {
        let span = self.max_m - self.min_m;
        if span <= 0.0 {
            return 0;
        }
        let v = ((h as f64 - self.min_m) / span * 65535.0).round();
        v.clamp(0.0, 65535.0) as u16
    }

    pub fn decode(&self, v: u16) -> f64 {
        self.min_m + v as f64 * self.step_m()
    }
}

/// A file being written: a temporary file beside its target.
pub struct Staged {
    pub path: PathBuf,
    tmp: NamedTempFile,
}

impl Staged {
    /// Creates the temporary file now, so an unwritable target fails before any work.
    pub fn create(path: &Path) -> Result<Self> {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .ok_or_else(|| Error::Output {
                path: path.to_path_buf(),
                message: "not a file name".into(),
            })?;
        if path.is_dir() {
            return Err(Error::Output {
                path: path.to_path_buf(),
                message: "is a folder".into(),
            });
        }
        let prefix = format!(".{name}.");
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(".part");
        // Finished files get ordinary permissions, not the private mode of temporary files.
        #[cfg(unix)]
        builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o644));
        let tmp = builder.tempfile_in(dir).map_err(|e| Error::Output {
            path: path.to_path_buf(),
            message: format!("cannot write in {}: {e}", dir.display()),
        })?;
        Ok(Self {
            path: path.to_path_buf(),
            tmp,
        })
    }

    /// Writes the content through a buffered writer, then renames over the target.
    pub fn write_with(
        self,
        f: impl FnOnce(&mut BufWriter<&File>) -> std::io::Result<()>,
    ) -> Result<()> {
        let io = |e| Error::io(&self.path, e);
        {
            let mut w = BufWriter::with_capacity(1 << 20, self.tmp.as_file());
            f(&mut w).map_err(io)?;
            w.flush().map_err(io)?;
        }
        self.tmp
            .persist(&self.path)
            .map_err(|e| Error::io(&self.path, e.error))?;
        Ok(())
    }
}

/// One requested output file and its format.
pub struct Output {
    pub format: Format,
    pub staged: Staged,
}

impl Output {
    pub fn prepare(path: &Path) -> Result<Self> {
        let format = Format::from_path(path)?;
        Ok(Self {
            format,
            staged: Staged::create(path)?,
        })
    }

    /// Writes `grid` in this output's format.
    pub fn write(self, grid: &Grid, mapping: &HeightMapping) -> Result<()> {
        match self.format {
            Format::Png16 => self.staged.write_with(|w| png16::write(w, grid, mapping)),
            Format::Tiff32 => self.staged.write_with(|w| tiff32::write(w, grid)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_follow_extensions() {
        assert_eq!(
            Format::from_path(Path::new("a/b.PNG")).unwrap(),
            Format::Png16
        );
        assert_eq!(
            Format::from_path(Path::new("b.tiff")).unwrap(),
            Format::Tiff32
        );
        let e = Format::from_path(Path::new("b.bmp"))
            .unwrap_err()
            .to_string();
        assert!(e.contains(".bmp") && e.contains(".png"), "{e}");
        assert!(Format::from_path(Path::new("noext")).is_err());
    }

    #[test]
    fn mapping_encodes_the_range_ends_and_clamps() {
        let m = HeightMapping {
            min_m: -2.0,
            max_m: 3.0,
        };
        assert_eq!(m.encode(-2.0), 0);
        assert_eq!(m.encode(3.0), 65535);
        assert_eq!(m.encode(-5.0), 0);
        assert_eq!(m.encode(9.0), 65535);
        assert!((m.decode(m.encode(0.5)) - 0.5).abs() <= m.step_m() / 2.0 + 1e-12);
        assert_eq!(
            HeightMapping {
                min_m: 1.0,
                max_m: 1.0
            }
            .encode(1.0),
            0
        );
    }

    #[test]
    fn a_failed_write_leaves_no_file_and_keeps_an_earlier_one() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("x.png");
        std::fs::write(&target, b"earlier").unwrap();
        let staged = Staged::create(&target).unwrap();
        let r = staged.write_with(|w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("disk full"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&target).unwrap(), b"earlier");
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(left.len(), 1, "temporary file removed");
    }

    #[test]
    fn an_unwritable_folder_fails_at_once() {
        let e = Staged::create(Path::new("/nonexistent-dir/x.png"))
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("/nonexistent-dir"), "{e}");
    }
}
