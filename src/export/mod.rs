//! Writing height fields to files.
//!
//! The format of each output follows its extension. Every file is staged: a temporary
//! file is created next to the target before any computation (so a bad path fails at
//! once), written, flushed, and renamed over the target only when complete. An error or
//! an interruption leaves no partial file and any earlier file of that name intact.
//!
//! Rows: every format stores grid row j (y = j·dy) as image row j, row 0 first, so in an
//! image viewer +x points right and +y points down. Meshes put row j at y = j·dy too
//! (`mesh` gives the engine frames).

pub mod exr;
pub mod glb;
pub mod live;
pub mod maps;
pub mod mesh;
pub mod obj;
pub mod options;
pub mod png16;
pub mod raw;
pub mod rgb8;
pub mod sidecar;
pub mod tiff32;
pub mod tiles;

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::Serialize;
use tempfile::NamedTempFile;

use crate::error::{Error, Result};
use crate::grid::{Grid, GridSpec};
use mesh::{Mesh, MeshLayout, Placement, Slopes, Tile};
use options::{Engine, ExportOptions, UpAxis};
use raw::{R16Encoding, RawLayout};

/// Output formats, chosen by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Format {
    /// `.png`: 16-bit grayscale, heights mapped linearly to 0..65535.
    Png16,
    /// `.tif`, `.tiff`: 32-bit float, one channel, meters, GeoTIFF spacing.
    Tiff32,
    /// `.exr`: OpenEXR, one 32-bit float channel `Y`, meters.
    Exr,
    /// `.obj`: triangle mesh with normals and texture coordinates, meters.
    Obj,
    /// `.glb`: binary glTF 2.0 mesh, +Y up, meters.
    Glb,
    /// `.r16`, `.raw`: unsigned 16-bit samples, no header.
    R16,
    /// `.r32`: 32-bit float samples in meters, no header.
    R32,
}

/// Extensions and what they give, for error messages and the README.
pub const EXTENSIONS: &[(&str, Format)] = &[
    ("png", Format::Png16),
    ("tif", Format::Tiff32),
    ("tiff", Format::Tiff32),
    ("exr", Format::Exr),
    ("obj", Format::Obj),
    ("glb", Format::Glb),
    ("r16", Format::R16),
    ("raw", Format::R16),
    ("r32", Format::R32),
];

impl Format {
    /// Meshes: OBJ and glTF.
    pub fn is_mesh(&self) -> bool {
        matches!(self, Format::Obj | Format::Glb)
    }

    /// Headerless samples: `.r16` and `.r32`.
    pub fn is_raw(&self) -> bool {
        matches!(self, Format::R16 | Format::R32)
    }

    /// Formats that `--tiles` splits.
    pub fn is_tiled(&self) -> bool {
        self.is_mesh() || self.is_raw()
    }

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
    /// The 16-bit mapping of a field and where it came from (for the sidecar): the given
    /// height range (`range_source`, e.g. "--height-range"), else the field's min..max
    /// (`field()`, asked for only then).
    pub fn choose(
        range: Option<crate::config::Range2>,
        range_source: &'static str,
        field: impl FnOnce() -> crate::grid::Stats,
    ) -> (HeightMapping, &'static str) {
        match range {
            Some(r) => (
                HeightMapping {
                    min_m: r.0[0],
                    max_m: r.0[1],
                },
                range_source,
            ),
            None => {
                let s = field();
                (
                    HeightMapping {
                        min_m: s.min_m,
                        max_m: s.max_m,
                    },
                    "field min..max",
                )
            }
        }
    }

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

/// A file being written: a temporary file beside its target, registered in [`live`]
/// from its creation until it is renamed or dropped, so SIGINT/SIGTERM remove it.
pub struct Staged {
    pub path: PathBuf,
    /// `None` once renamed over the target.
    tmp: Option<NamedTempFile>,
    id: u64,
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
        // Created and registered under the lock: a signal cannot fall between the two.
        let mut live = live::lock();
        let tmp = builder.tempfile_in(dir).map_err(|e| Error::Output {
            path: path.to_path_buf(),
            message: format!("cannot write in {}: {e}", dir.display()),
        })?;
        let id = live::register(&mut live, tmp.path());
        Ok(Self {
            path: path.to_path_buf(),
            tmp: Some(tmp),
            id,
        })
    }

    /// Writes the content through a buffered writer, then renames over the target.
    pub fn write_with(
        mut self,
        f: impl FnOnce(&mut BufWriter<&File>) -> std::io::Result<()>,
    ) -> Result<()> {
        let io = |e| Error::io(&self.path, e);
        let tmp = self.tmp.take().expect("a staged file is written once");
        let written = (|| {
            let mut w = BufWriter::with_capacity(1 << 20, tmp.as_file());
            f(&mut w)?;
            w.flush()
        })();
        if let Err(e) = written {
            // Removed before the registry forgets it.
            drop(tmp);
            return Err(io(e));
        }
        // Renamed under the lock: an interruption leaves the target complete or untouched.
        let persisted = {
            let _live = live::lock();
            tmp.persist(&self.path)
        };
        persisted.map_err(|e| Error::io(&self.path, e.error))?;
        Ok(())
    }
}

impl Staged {
    /// Writes `value` as pretty-printed JSON with a final newline (sidecars, indexes).
    pub fn write_json(self, value: &impl Serialize) -> Result<()> {
        self.write_with(|w| {
            serde_json::to_writer_pretty(&mut *w, value)?;
            w.write_all(b"\n")
        })
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        let mut live = live::lock();
        // An unwritten file is removed (NamedTempFile's drop) while the lock is held.
        drop(self.tmp.take());
        live.remove(&self.id);
    }
}

/// Formats `rows` rows of bytes with `format_row`, in parallel batches on all cores, and
/// writes them in order. `row_bytes` estimates one row's length (better high than low: a
/// buffer that grows is copied). At most one batch of a few megabytes is alive at once.
///
/// Writing a batch from a second thread while the next is formatted measured slower on
/// 2 cores (the buffers then move between threads, and the kernel's copy into the page
/// cache competes with the formatting for the same cores), so the two alternate.
pub(crate) fn par_rows<W: Write>(
    w: &mut W,
    rows: usize,
    row_bytes: usize,
    format_row: impl Fn(usize, &mut Vec<u8>) + Sync,
) -> io::Result<()> {
    // About 2 MiB per task: enough to amortize scheduling, and more than the 1 MiB of the
    // staged file's buffer, which chunks then bypass instead of being copied into it.
    let per_task = ((2 << 20) / row_bytes.max(1)).clamp(1, 1024);
    let per_batch = per_task * 4 * rayon::current_num_threads();
    let mut start = 0;
    while start < rows {
        let end = (start + per_batch).min(rows);
        let firsts: Vec<usize> = (start..end).step_by(per_task).collect();
        let chunks: Vec<Vec<u8>> = firsts
            .into_par_iter()
            .map(|first| {
                let last = (first + per_task).min(end);
                let mut buf = Vec::with_capacity((last - first) * row_bytes + 64);
                for r in first..last {
                    format_row(r, &mut buf);
                }
                buf
            })
            .collect();
        for c in &chunks {
            w.write_all(c)?;
        }
        start = end;
    }
    Ok(())
}

/// How an output lays out the field.
#[derive(Debug, Clone, PartialEq)]
pub enum Plan {
    /// The field's samples as they are (PNG, TIFF, EXR).
    Image,
    /// A triangle grid and its tiles (one tile when untiled).
    Mesh(MeshLayout, Vec<Tile>),
    /// A raw lattice, resampled for an engine or not, and its tiles.
    Raw(RawLayout),
}

/// The field and what the writers share, once computed.
pub struct FieldOut<'a> {
    pub grid: &'a Grid,
    /// The 16-bit mapping of PNG and of `.r16` outside Unreal's encoding.
    pub mapping: &'a HeightMapping,
    /// Slopes of the whole field for mesh normals (e.g. exact spectral slopes); `None`:
    /// central differences of the field, computed tile by tile.
    pub slopes: Option<&'a Slopes>,
    /// Lines about the field for file headers (method, size, seed, parameters).
    pub about: &'a str,
}

/// The `.r16` encoding of an output for `engine`: Unreal's, with the Z scale that fits
/// the mapping's range, or the 16-bit mapping itself.
pub fn r16_encoding(engine: Option<Engine>, mapping: &HeightMapping) -> R16Encoding {
    match engine {
        Some(Engine::Unreal) => R16Encoding::Unreal {
            z_scale: raw::unreal_z_scale(mapping.min_m.abs().max(mapping.max_m.abs())),
        },
        _ => R16Encoding::Mapping(*mapping),
    }
}

/// One requested output: its format, its layout and its staged files.
pub struct Output {
    pub format: Format,
    /// The path given; tiles are named after it.
    pub path: PathBuf,
    /// The files to write: the path itself, or its tiles row by row.
    pub files: Vec<Staged>,
    pub plan: Plan,
}

impl Output {
    /// An output of the field's samples as they are (no tiles, default options).
    pub fn prepare(path: &Path) -> Result<Self> {
        let format = Format::from_path(path)?;
        if format.is_mesh() || format.is_raw() {
            return Err(Error::Output {
                path: path.to_path_buf(),
                message: "needs the export options: use Output::plan".into(),
            });
        }
        Ok(Self {
            format,
            path: path.to_path_buf(),
            files: vec![Staged::create(path)?],
            plan: Plan::Image,
        })
    }

    /// Lays out `path` for a field of `spec` with `options`, and stages every file it
    /// will write (each tile's too), so a bad path or option fails before any work.
    pub fn plan(
        path: &Path,
        options: &ExportOptions,
        spec: &GridSpec,
        periodic: bool,
    ) -> Result<Self> {
        let format = Format::from_path(path)?;
        let tiled = options.tiles.filter(|_| format.is_tiled());
        let plan = if format.is_mesh() {
            let layout = MeshLayout {
                xs: mesh::axis_vertices(spec.nx, options.mesh_step, periodic),
                ys: mesh::axis_vertices(spec.ny, options.mesh_step, periodic),
                step: options.mesh_step,
                up: if format == Format::Glb {
                    UpAxis::Y
                } else {
                    options.up
                },
                vertical_scale: options.vertical_scale,
                uv: options.tile_uv,
                placement: if options.periodic_tiles {
                    Placement::Tile
                } else {
                    Placement::Global
                },
                periodic,
            };
            let (vx, vy) = (layout.xs.len(), layout.ys.len());
            let tiles = match tiled {
                None => vec![Tile::whole(vx, vy)],
                Some(t) => mesh::tiles(vx, vy, t)?,
            };
            if options.periodic_tiles {
                equal_tiles(&layout, &tiles, spec, options.mesh_step)?;
            }
            Plan::Mesh(layout, tiles)
        } else if format.is_raw() {
            Plan::Raw(RawLayout::new(
                spec,
                periodic,
                options.engine,
                tiled,
                options.byte_order,
            )?)
        } else {
            Plan::Image
        };
        let mut out = Self {
            format,
            path: path.to_path_buf(),
            files: Vec::new(),
            plan,
        };
        let targets: Vec<PathBuf> = match out.tiles().filter(|_| tiled.is_some()) {
            Some(tiles) => tiles
                .iter()
                .map(|t| tiles::tile_path(path, t.column, t.row))
                .collect(),
            None => vec![path.to_path_buf()],
        };
        for t in targets {
            out.files.push(Staged::create(&t)?);
        }
        Ok(out)
    }

    /// The tiles of a mesh or raw output (one when untiled); `None` for images.
    pub fn tiles(&self) -> Option<&[Tile]> {
        match &self.plan {
            Plan::Mesh(_, t) => Some(t),
            Plan::Raw(l) => Some(&l.tiles),
            Plan::Image => None,
        }
    }

    /// True when the output is split into tile files.
    pub fn is_tiled(&self) -> bool {
        self.files.len() > 1 || self.files.first().is_some_and(|f| f.path != self.path)
    }

    /// Writes the field in this output's format, file by file (tiles one after another,
    /// each streamed straight to its staged file).
    pub fn write(self, field: &FieldOut) -> Result<()> {
        let grid = field.grid;
        match (&self.plan, self.format) {
            (Plan::Image, format) => {
                let staged = self.files.into_iter().next().expect("one file");
                match format {
                    Format::Png16 => staged.write_with(|w| png16::write(w, grid, field.mapping)),
                    Format::Tiff32 => staged.write_with(|w| tiff32::write(w, grid)),
                    Format::Exr => staged.write_with(|w| exr::write(w, grid)),
                    other => unreachable!("{other:?} is laid out as a mesh or raw"),
                }
            }
            (Plan::Mesh(layout, tiles), format) => {
                let mesh = Mesh {
                    layout,
                    grid,
                    field_slopes: field.slopes,
                };
                let header_base = mesh_header(layout, grid, field.about, &self.path);
                for (staged, tile) in self.files.into_iter().zip(tiles) {
                    let name = staged
                        .path
                        .file_stem()
                        .map(|s| s.to_string_lossy().into_owned())
                        .unwrap_or_default();
                    if format == Format::Obj {
                        let mut header = header_base.clone();
                        header.push(tile_line(tile, tiles.len(), layout.placement));
                        staged.write_with(|w| obj::write_tile(w, &mesh, tile, &name, &header))?;
                    } else {
                        staged.write_with(|w| glb::write_tile(w, &mesh, tile, &name))?;
                    }
                }
                Ok(())
            }
            (Plan::Raw(layout), format) => {
                let samples = if format == Format::R16 {
                    raw::Samples::R16(r16_encoding(layout.engine, field.mapping))
                } else {
                    raw::Samples::R32
                };
                for (staged, tile) in self.files.into_iter().zip(&layout.tiles) {
                    staged.write_with(|w| raw::write_tile(w, grid, layout, tile, samples))?;
                }
                Ok(())
            }
        }
    }
}

/// Periodic tiles must all be alike: the same number of equal cells.
fn equal_tiles(layout: &MeshLayout, tiles: &[Tile], spec: &GridSpec, step: usize) -> Result<()> {
    let uniform = spec.nx % step == 0 && spec.ny % step == 0;
    let first = tiles[0].size();
    if uniform && tiles.iter().all(|t| t.size() == first) {
        return Ok(());
    }
    let columns = tiles.iter().map(|t| t.column).max().unwrap_or(0) + 1;
    let rows = tiles.len() / columns;
    Err(Error::Set {
        origin: "--periodic-tiles".into(),
        message: format!(
            "needs equal tiles: --mesh-step {step} must divide the grid size {}x{} and the              tiles {columns}x{rows} the mesh's {}x{} cells",
            spec.nx,
            spec.ny,
            layout.xs.len() - 1,
            layout.ys.len() - 1
        ),
    })
}

/// The comment lines of a mesh file: the frame, the winding, the field.
fn mesh_header(layout: &MeshLayout, grid: &Grid, about: &str, path: &Path) -> Vec<String> {
    let info = layout.info();
    let s = &grid.spec;
    let mut lines = vec![format!(
        "seasynth {} height-field mesh, meters",
        env!("CARGO_PKG_VERSION")
    )];
    lines.extend(about.lines().map(str::to_string));
    lines.extend([
        format!(
            "grid {}x{} samples over {} x {} m, periodic: {}; parameters in {}",
            s.nx,
            s.ny,
            s.extent_x_m,
            s.extent_y_m,
            if layout.periodic { "yes" } else { "no" },
            sidecar::path_for(path)
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default()
        ),
        format!(
            "{} with vertical_scale {}",
            info.coordinates, layout.vertical_scale
        ),
        format!("triangles {}; normals: {}", info.winding, info.normals),
        match layout.uv {
            options::TileUv::Global => "uv: u = x / Lx, v = 1 - y / Ly (0..1 over the field)",
            options::TileUv::Tile => "uv: 0..1 across each tile, v = 1 at the tile's y = 0 edge",
        }
        .to_string(),
        format!(
            "mesh step {}: {}x{} vertices (samples 0, {}, {}, ... and the far edge)",
            layout.step,
            layout.xs.len(),
            layout.ys.len(),
            layout.step,
            2 * layout.step
        ),
    ]);
    lines
}

/// The header line naming a tile and its vertex counts.
fn tile_line(tile: &Tile, count: usize, placement: Placement) -> String {
    let (w, h) = tile.size();
    if count == 1 {
        return format!("{} vertices, {} triangles", w * h, tile.triangle_count());
    }
    format!(
        "tile x{} y{} of {count}: mesh vertices {}..={} x {}..={}; {} vertices, {} triangles; positions {}",
        tile.column,
        tile.row,
        tile.vx.0,
        tile.vx.1,
        tile.vy.0,
        tile.vy.1,
        w * h,
        tile.triangle_count(),
        match placement {
            Placement::Global => "in field coordinates",
            Placement::Tile => "relative to the tile's corner",
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_come_out_in_order_across_batches_and_write_errors_surface() {
        let mut out = Vec::new();
        par_rows(&mut out, 5000, 3, |r, buf| {
            buf.extend_from_slice(format!("{r}\n").as_bytes())
        })
        .unwrap();
        let want: String = (0..5000).map(|r| format!("{r}\n")).collect();
        assert_eq!(String::from_utf8(out).unwrap(), want);
        struct Full;
        impl Write for Full {
            fn write(&mut self, _: &[u8]) -> io::Result<usize> {
                Err(io::Error::other("disk full"))
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let e = par_rows(&mut Full, 100_000, 1000, |_, buf| buf.push(b'x')).unwrap_err();
        assert_eq!(e.to_string(), "disk full");
    }

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
    fn a_staged_file_is_listed_for_cleanup_until_written_or_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let ours = || {
            live::live_files()
                .iter()
                .filter(|f| f.starts_with(dir.path()))
                .count()
        };
        let a = Staged::create(&dir.path().join("a.png")).unwrap();
        let b = Staged::create(&dir.path().join("b.png")).unwrap();
        assert_eq!(ours(), 2, "both temporary files are listed");
        a.write_with(|w| w.write_all(b"a")).unwrap();
        drop(b);
        assert_eq!(ours(), 0, "renamed and dropped files leave the list");
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("a.png")]);
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
