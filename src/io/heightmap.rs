//! Reading height maps: a float TIFF in meters, a 16-bit PNG with its sidecar's mapping,
//! or any other image through `image` ([`super::raster`]); the kind of file told by its
//! first bytes (a name that says another image format is refused), the spacing by
//! `--extent`, else the sidecar, else 1 m.

use std::io::Read;
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::Value;

use super::{HeightReader, Heights, READERS, ReadOptions, input_error};
use crate::error::Error;
use crate::grid::{Grid, GridSpec};

/// The kinds of file `analyze` reads, told by their first bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ImageKind {
    /// 16-bit grayscale PNG (needs its sidecar's mapping).
    Png16,
    /// One-channel 32-bit float TIFF in meters.
    TiffF32,
    /// Any other PNG (8-bit, color, or 16-bit without a sidecar).
    Png,
    Jpeg,
    /// A TIFF other than one float channel (8/16-bit, color, float RGB).
    Tiff,
    Exr,
    Bmp,
    Webp,
}

impl ImageKind {
    /// The kind in words, for reports.
    pub fn describe(self) -> &'static str {
        match self {
            ImageKind::Png16 => "16-bit PNG",
            ImageKind::TiffF32 => "float TIFF",
            ImageKind::Png => "PNG",
            ImageKind::Jpeg => "JPEG",
            ImageKind::Tiff => "TIFF",
            ImageKind::Exr => "OpenEXR",
            ImageKind::Bmp => "BMP",
            ImageKind::Webp => "WebP",
        }
    }
}

/// A height map as read, with what was learned reading it.
pub struct Loaded {
    pub grid: Grid,
    pub sidecar: Option<Value>,
    pub kind: ImageKind,
    /// `"sidecar"` or `"assumed 1 m"`.
    pub spacing_source: &'static str,
    /// Meters per 16-bit step (PNG only).
    pub quantization_step_m: Option<f64>,
}

/// The first bytes of `path` (up to 16), refusing folders and empty files.
fn head_of(path: &Path) -> Result<Vec<u8>, Error> {
    let mut head = [0u8; 16];
    let mut file =
        std::fs::File::open(path).map_err(|e| input_error(path, format!("cannot read: {e}")))?;
    if path.is_dir() {
        return Err(input_error(path, "is a folder, not a height map"));
    }
    let mut got = 0;
    while got < head.len() {
        match file.read(&mut head[got..]) {
            Ok(0) => break,
            Ok(k) => got += k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(input_error(path, format!("cannot read: {e}"))),
        }
    }
    if got == 0 {
        return Err(input_error(path, "is empty, not a height map"));
    }
    Ok(head[..got].to_vec())
}

/// seasynth's own reader of `path` when it applies: a 16-bit grayscale PNG with a
/// sidecar, or a one-channel float TIFF (or a TIFF whose header does not read, for its
/// message); None for any other image.
fn own_reader(path: &Path, head: &[u8], has_sidecar: bool) -> Option<&'static dyn HeightReader> {
    let reader = READERS.iter().copied().find(|r| r.sniff(head))?;
    let applies = match reader.kind() {
        ImageKind::Png16 => has_sidecar && png_is_gray16(path),
        _ => tiff_is_float_gray(path),
    };
    applies.then_some(reader)
}

fn png_is_gray16(path: &Path) -> bool {
    let Ok(file) = std::fs::File::open(path) else {
        return true;
    };
    match png::Decoder::new(std::io::BufReader::new(file)).read_info() {
        Ok(r) => {
            let info = r.info();
            info.bit_depth == png::BitDepth::Sixteen && info.color_type == png::ColorType::Grayscale
        }
        Err(_) => true,
    }
}

fn tiff_is_float_gray(path: &Path) -> bool {
    let Ok(file) = std::fs::File::open(path) else {
        return true;
    };
    let Ok(mut dec) = tiff::decoder::Decoder::new(std::io::BufReader::new(file)) else {
        return true;
    };
    let float = dec
        .find_tag_unsigned_vec::<u16>(tiff::tags::Tag::SampleFormat)
        .ok()
        .flatten()
        .is_some_and(|v| v.iter().all(|&f| f == 3));
    match dec.colortype() {
        Ok(tiff::ColorType::Gray(32)) => float,
        Ok(_) => false,
        Err(_) => true,
    }
}

/// The sidecar of `path` (same folder and stem, `.json`), if there is a file of that name.
fn read_sidecar(path: &Path) -> Result<Option<(PathBuf, Value)>, Error> {
    let side = crate::export::sidecar::path_for(path);
    if side == path || !side.is_file() {
        return Ok(None);
    }
    let bytes =
        std::fs::read(&side).map_err(|e| input_error(&side, format!("cannot read: {e}")))?;
    let doc: Value = serde_json::from_slice(&bytes)
        .map_err(|e| input_error(&side, format!("sidecar is not valid JSON: {e}")))?;
    if !doc.is_object() {
        return Err(input_error(&side, "sidecar is not a JSON object"));
    }
    Ok(Some((side, doc)))
}

/// Spacing (dx_m, dy_m) from the sidecar's `grid`, checked against the image size.
fn sidecar_spacing(
    side: &Path,
    doc: &Value,
    nx: usize,
    ny: usize,
) -> Result<Option<(f64, f64)>, Error> {
    let Some(grid) = doc.get("grid") else {
        return Ok(None);
    };
    let size = (
        grid.get("nx").and_then(Value::as_u64),
        grid.get("ny").and_then(Value::as_u64),
    );
    if let (Some(gx), Some(gy)) = size {
        if (gx, gy) != (nx as u64, ny as u64) {
            return Err(input_error(
                side,
                format!("sidecar describes a {gx}×{gy} grid but the image is {nx}×{ny}"),
            ));
        }
    }
    let dx = grid.get("dx_m").and_then(Value::as_f64);
    let dy = grid.get("dy_m").and_then(Value::as_f64);
    match (dx, dy) {
        (Some(dx), Some(dy)) if dx.is_finite() && dx > 0.0 && dy.is_finite() && dy > 0.0 => {
            Ok(Some((dx, dy)))
        }
        (None, None) => Ok(None),
        _ => Err(input_error(
            side,
            format!(
                "sidecar grid spacing must be two finite numbers > 0 (got dx_m = {}, dy_m = {})",
                grid.get("dx_m").unwrap_or(&Value::Null),
                grid.get("dy_m").unwrap_or(&Value::Null)
            ),
        )),
    }
}

/// Reads a height map and its sidecar, if any (see the module docs).
pub fn load_detailed(path: &Path) -> Result<Loaded, Error> {
    load_with(path, &ReadOptions::default())
}

/// Reads a height map and its sidecar, if any, with what the command line says of it.
pub fn load_with(path: &Path, opts: &ReadOptions) -> Result<Loaded, Error> {
    let head = head_of(path)?;
    if let Ok(format) = image::guess_format(&head) {
        crate::raster::check_extension(path, format).map_err(|m| input_error(path, m))?;
    }
    let sidecar = read_sidecar(path)?;
    let (heights, kind) = match own_reader(path, &head, sidecar.is_some()) {
        Some(reader) => (reader.read(path, sidecar.as_ref())?, reader.kind()),
        None => super::raster::read(path, opts)?,
    };
    let Heights {
        nx,
        ny,
        data,
        quantization_step_m: step,
    } = heights;
    if nx == 0 || ny == 0 || data.len() != nx * ny {
        return Err(input_error(path, format!("has no samples ({nx}×{ny})")));
    }
    if let Some(i) = data.iter().position(|v| !v.is_finite()) {
        return Err(input_error(
            path,
            format!(
                "sample (x {}, row {}) is {}: heights must be finite",
                i % nx,
                i / nx,
                data[i]
            ),
        ));
    }
    let spacing = match &sidecar {
        Some((side, doc)) => sidecar_spacing(side, doc, nx, ny)?,
        None => None,
    };
    let (spec, spacing_source) = match (opts.extent_m, spacing) {
        (Some((ex, ey)), _) => (GridSpec::new(nx, ny, ex, ey), "--extent"),
        (None, Some((dx, dy))) => (
            GridSpec::new(nx, ny, dx * nx as f64, dy * ny as f64),
            "sidecar",
        ),
        (None, None) => (GridSpec::new(nx, ny, nx as f64, ny as f64), "assumed 1 m"),
    };
    Ok(Loaded {
        grid: Grid::new(spec, data),
        sidecar: sidecar.map(|(_, d)| d),
        kind,
        spacing_source,
        quantization_step_m: step,
    })
}

/// Reads a height map in meters and its sidecar, if any.
pub fn load(path: &Path) -> Result<(Grid, Option<Value>), Error> {
    load_detailed(path).map(|l| (l.grid, l.sidecar))
}
