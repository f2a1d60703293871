//! Reading height maps: a float TIFF in meters, or a 16-bit PNG with its sidecar's
//! mapping; the kind of file told by its first bytes, the spacing by the sidecar.

use std::io::Read;
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::Value;

use super::{HeightReader, Heights, READERS, input_error};
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

/// The reader of the file at `path`, picked by its first bytes.
fn sniff(path: &Path) -> Result<&'static dyn HeightReader, Error> {
    let mut head = [0u8; 8];
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
    let head = &head[..got];
    if head.is_empty() {
        return Err(input_error(path, "is empty, not a height map"));
    }
    READERS
        .iter()
        .copied()
        .find(|r| r.sniff(head))
        .ok_or_else(|| {
            input_error(
                path,
                "is not a PNG or TIFF image (expected a 32-bit float TIFF in meters or a 16-bit PNG with its sidecar)",
            )
        })
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
    let reader = sniff(path)?;
    let sidecar = read_sidecar(path)?;
    let Heights {
        nx,
        ny,
        data,
        quantization_step_m: step,
    } = reader.read(path, sidecar.as_ref())?;
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
    let (dx, dy) = spacing.unwrap_or((1.0, 1.0));
    let spec = GridSpec::new(nx, ny, dx * nx as f64, dy * ny as f64);
    Ok(Loaded {
        grid: Grid::new(spec, data),
        sidecar: sidecar.map(|(_, d)| d),
        kind: reader.kind(),
        spacing_source: if spacing.is_some() {
            "sidecar"
        } else {
            "assumed 1 m"
        },
        quantization_step_m: step,
    })
}

/// Reads a height map in meters and its sidecar, if any.
pub fn load(path: &Path) -> Result<(Grid, Option<Value>), Error> {
    load_detailed(path).map(|l| (l.grid, l.sidecar))
}
