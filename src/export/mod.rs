//! Writing height fields to files: one writer per format behind [`Exporter`], chosen
//! from the one table of file names in [`format`](mod@format).
//!
//! The format of each output follows its extension. Every file is staged ([`Staged`]):
//! created before any computation (so a bad path fails at once), written, and renamed
//! over the target only when complete, leaving no partial file.
//!
//! Rows: every format stores grid row j (y = j·dy) as image row j, row 0 first, so in an
//! image viewer +x points right and +y points down. Meshes put row j at y = j·dy too
//! (`mesh` gives the engine frames).

pub mod exr;
pub mod format;
pub mod glb;
pub mod live;
pub mod mapping;
pub mod maps;
pub mod mesh;
pub mod obj;
pub mod options;
pub mod png16;
pub mod png_par;
pub mod raw;
pub mod rgb8;
pub mod sidecar;
pub mod staged;
pub mod tiff32;
pub mod tiles;

use std::io::{self, Seek, Write};
use std::path::{Path, PathBuf};

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::grid::{Grid, GridSpec};
pub use format::{EXTENSIONS, Format, OutputKind};
pub use mapping::HeightMapping;
use mesh::{MeshLayout, Slopes, Tile};
use options::{Engine, ExportOptions};
use raw::{R16Encoding, RawLayout};
use sidecar::Sidecar;
pub use staged::{Allowed, Staged};

/// A file a writer can also seek in (TIFF and EXR place their tables after the samples).
pub trait WriteSeek: Write + Seek {}

impl<T: Write + Seek + ?Sized> WriteSeek for T {}

/// One writer per format: serializes a field, or each of its tiles, to a file.
///
/// An exporter is built from the output's path and the export options before any work
/// ([`Output::plan`]), so it holds its layout (mesh vertices, raw lattice, tiles) and the
/// files can be staged at once.
pub trait Exporter: Send + Sync {
    /// The format written.
    fn format(&self) -> Format;

    /// The tiles, one file each, row by row (one tile when untiled); `None` for formats
    /// that are written whole.
    fn tiles(&self) -> Option<&[Tile]> {
        None
    }

    /// Writes file `part` of the output (the tile of that index, 0 when written whole),
    /// whose file stem is `name`, to `out`.
    fn write(
        &self,
        field: &FieldOut,
        part: usize,
        name: &str,
        out: &mut dyn WriteSeek,
    ) -> io::Result<()>;

    /// True when the file stores 16-bit values through the field's [`HeightMapping`].
    fn uses_mapping(&self) -> bool {
        false
    }

    /// Adds what the sidecar says about this format's files (frame, layout, import
    /// settings).
    fn describe(&self, _doc: &mut Sidecar, _cx: &Describe) {}

    /// The writer of this format for fields that come row by row, if it takes them so.
    fn row_sink(&self) -> Option<&dyn RowSink> {
        None
    }

    /// The mesh layout of a mesh format.
    fn mesh_layout(&self) -> Option<&MeshLayout> {
        None
    }

    /// The lattice of a raw format.
    fn raw_layout(&self) -> Option<&RawLayout> {
        None
    }
}

/// What [`Exporter::describe`] knows besides the format: the field's grid, its 16-bit
/// mapping, and the formats of every output sharing the sidecar.
pub struct Describe<'a> {
    pub spec: &'a GridSpec,
    pub mapping: &'a HeightMapping,
    pub formats: &'a [Format],
    /// Meshes take the field's exact spectral slopes for their normals.
    pub exact_slopes: bool,
}

/// A writer that takes a field's rows in order, batch by batch, holding one batch in
/// memory (streamed outputs, far larger than memory). The file equals the exporter's for
/// the same field.
pub trait RowSink {
    /// Writes a field of `spec` to `out`: `fill(first_row, batch)` fills the heights of
    /// rows `first_row..` (`batch.len()/nx` of them, about `batch_rows`). `mapping` is the
    /// 16-bit mapping, given when the exporter [uses one](Exporter::uses_mapping).
    fn write_rows(
        &self,
        out: &mut dyn WriteSeek,
        spec: &GridSpec,
        mapping: Option<&HeightMapping>,
        batch_rows: usize,
        fill: &mut dyn FnMut(usize, &mut [f32]) -> io::Result<()>,
    ) -> io::Result<()>;
}

/// The exporter of a format written whole, without a layout (PNG, TIFF, EXR).
fn image_exporter(format: Format, options: &ExportOptions) -> Option<Box<dyn Exporter>> {
    let (exr, area) = (options.exr, !options.sample_at.is_corners());
    match format {
        Format::Png16 => Some(Box::new(png16::Png16)),
        Format::Tiff32 => Some(Box::new(tiff32::Tiff32 { area })),
        Format::Exr => Some(Box::new(exr::Exr { options: exr })),
        _ => None,
    }
}

/// The exporter of `format` for the output `path` of a field of `spec`: with
/// [`image_exporter`], the one place a format becomes its writer.
fn exporter(
    format: Format,
    path: &Path,
    options: &ExportOptions,
    spec: &GridSpec,
    periodic: bool,
) -> Result<Box<dyn Exporter>> {
    // A 16-bit PNG for an engine is a lattice of the engine's size, as a `.r16`.
    let engine_png = format == Format::Png16 && options.engine.is_some();
    if let Some(e) = image_exporter(format, options).filter(|_| !engine_png) {
        return Ok(e);
    }
    let tiled = options.tiles.filter(|_| format.is_tiled() || engine_png);
    Ok(match format {
        Format::Png16 | Format::R16 | Format::R32 => {
            let layout = RawLayout::new(spec, periodic, options.engine, tiled, options.byte_order)?;
            Box::new(raw::Raw {
                layout,
                r16: format != Format::R32,
                png: format == Format::Png16,
            })
        }
        Format::Tiff32 | Format::Exr => unreachable!("written whole"),
        Format::Obj => {
            let (layout, tiles) = MeshLayout::plan(options, spec, periodic, options.up, tiled)?;
            Box::new(obj::Obj::new(layout, tiles, path))
        }
        Format::Glb => {
            let up = options::UpAxis::Y;
            let (layout, tiles) = MeshLayout::plan(options, spec, periodic, up, tiled)?;
            Box::new(glb::Glb { layout, tiles })
        }
    })
}

impl Format {
    /// True when the format's writer also takes a field row by row ([`RowSink`]).
    pub fn streams(self) -> bool {
        image_exporter(self, &ExportOptions::default()).is_some_and(|e| e.row_sink().is_some())
    }
}

/// Formats `rows` rows of bytes with `format_row`, in parallel batches on all cores, and
/// writes them in order. `row_bytes` estimates one row's length (better high than low: a
/// buffer that grows is copied). At most one batch of a few megabytes is alive at once.
///
/// Writing a batch from a second thread while the next is formatted measured slower on
/// 2 cores (the buffers then move between threads, and the kernel's copy into the page
/// cache competes with the formatting for the same cores), so the two alternate.
pub(crate) fn par_rows<W: Write + ?Sized>(
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

/// One requested output: its exporter and its staged files.
pub struct Output {
    /// The path given; tiles are named after it.
    pub path: PathBuf,
    /// The files to write: the path itself, or its tiles row by row.
    pub files: Vec<Staged>,
    pub exporter: Box<dyn Exporter>,
}

impl Output {
    /// An output of the field's samples as they are (no tiles, default options).
    pub fn prepare(path: &Path) -> Result<Self> {
        Self::prepare_with(path, &ExportOptions::default())
    }

    /// [`prepare`](Self::prepare) with `options` (the EXR options, where samples sit).
    pub fn prepare_with(path: &Path, options: &ExportOptions) -> Result<Self> {
        let format = Format::from_path(path)?;
        let exporter = image_exporter(format, options).ok_or_else(|| Error::Output {
            path: path.to_path_buf(),
            message: "needs the export options: use Output::plan".into(),
        })?;
        Ok(Self {
            path: path.to_path_buf(),
            files: vec![Staged::create(path)?],
            exporter,
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
        let exporter = exporter(format, path, options, spec, periodic)?;
        let tiled = options.tiles.is_some()
            && (format.is_tiled() || (format == Format::Png16 && options.engine.is_some()));
        let targets: Vec<PathBuf> = match exporter.tiles().filter(|_| tiled) {
            Some(tiles) => tiles
                .iter()
                .map(|t| tiles::tile_path(path, t.column, t.row))
                .collect(),
            None => vec![path.to_path_buf()],
        };
        let files = targets
            .iter()
            .map(|t| Staged::create(t))
            .collect::<Result<Vec<_>>>()?;
        Ok(Self {
            path: path.to_path_buf(),
            files,
            exporter,
        })
    }

    /// The format written.
    pub fn format(&self) -> Format {
        self.exporter.format()
    }

    /// The tiles of a mesh or raw output (one when untiled); `None` for images.
    pub fn tiles(&self) -> Option<&[Tile]> {
        self.exporter.tiles()
    }

    /// True when the output is split into tile files.
    pub fn is_tiled(&self) -> bool {
        self.files.len() > 1 || self.files.first().is_some_and(|f| f.path != self.path)
    }

    /// Writes the field through the exporter, file by file (tiles one after another,
    /// each streamed straight to its staged file).
    pub fn write(self, field: &FieldOut) -> Result<()> {
        for (part, staged) in self.files.into_iter().enumerate() {
            let name = staged
                .path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let exporter = &self.exporter;
            staged.write_with(|w| exporter.write(field, part, &name, w))?;
        }
        Ok(())
    }
}

/// The outputs of one field, each with its exporter, staged together before any work and
/// written together once the field is computed.
pub struct ExportManager {
    pub outputs: Vec<Output>,
}

impl ExportManager {
    /// Plans and stages every output of `paths` ([`Output::plan`]).
    pub fn plan(
        paths: &[PathBuf],
        options: &ExportOptions,
        spec: &GridSpec,
        periodic: bool,
    ) -> Result<Self> {
        let outputs = paths
            .iter()
            .map(|p| Output::plan(p, options, spec, periodic))
            .collect::<Result<Vec<_>>>()?;
        Ok(Self { outputs })
    }

    /// Writes every output, in parallel; the first error in output order is returned.
    pub fn write_all(self, field: &FieldOut) -> Result<()> {
        let results: Vec<Result<()>> = self
            .outputs
            .into_par_iter()
            .map(|o| o.write(field))
            .collect();
        results.into_iter().collect()
    }
}

#[cfg(test)]
mod tests;
