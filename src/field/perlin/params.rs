//! The parameters of the Perlin fBm, and the lattice each octave uses.

use crate::grid::GridSpec;

/// Parameters of the Perlin fBm. Units: meters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PerlinParams {
    /// Number of octaves P, ≥ 1.
    pub octaves: u32,
    /// a in (0,1): amplitude ratio between successive octaves.
    pub persistence: f64,
    /// Frequency ratio between successive octaves (2 by default), > 1.
    pub lacunarity: f64,
    /// λ0, base lattice spacing in meters, > 0. When `tileable`, adjusted per octave to the
    /// nearest value dividing the extent.
    pub wavelength_m: f64,
    /// Periodic over the grid extent.
    pub tileable: bool,
    pub seed: u64,
}

impl Default for PerlinParams {
    fn default() -> Self {
        Self {
            octaves: 6,
            persistence: 0.5,
            lacunarity: 2.0,
            wavelength_m: 100.0,
            tileable: true,
            seed: 0,
        }
    }
}

impl PerlinParams {
    /// Checks the documented ranges: `octaves ≥ 1`, `0 < persistence < 1`, `lacunarity > 1`,
    /// `wavelength_m > 0`, all finite.
    pub fn validate(&self) -> Result<(), String> {
        if self.octaves < 1 {
            return Err(format!("perlin octaves must be >= 1, got {}", self.octaves));
        }
        if !(self.persistence > 0.0 && self.persistence < 1.0) {
            return Err(format!(
                "perlin persistence must be in (0, 1), got {}",
                self.persistence
            ));
        }
        if !(self.lacunarity > 1.0 && self.lacunarity.is_finite()) {
            return Err(format!(
                "perlin lacunarity must be finite and > 1, got {}",
                self.lacunarity
            ));
        }
        if !(self.wavelength_m > 0.0 && self.wavelength_m.is_finite()) {
            return Err(format!(
                "perlin wavelength_m must be finite and > 0, got {}",
                self.wavelength_m
            ));
        }
        Ok(())
    }
}

/// Panics with a clear message on invalid parameters or a grid without positive extent.
pub(super) fn check(spec: &GridSpec, p: &PerlinParams) {
    if let Err(e) = p.validate() {
        panic!("{e}");
    }
    assert!(
        spec.extent_x_m > 0.0
            && spec.extent_x_m.is_finite()
            && spec.extent_y_m > 0.0
            && spec.extent_y_m.is_finite(),
        "grid extents must be finite and > 0, got {} x {}",
        spec.extent_x_m,
        spec.extent_y_m
    );
}

/// `lac^i` for `i < octaves`, by repeated multiplication (portable, unlike `powi`).
pub(super) fn lacunarity_powers(p: &PerlinParams) -> Vec<f64> {
    let mut m = 1.0f64;
    (0..p.octaves)
        .map(|_| {
            let v = m;
            m *= p.lacunarity;
            v
        })
        .collect()
}

/// `max(1, round(extent · m / λ0))` as an integer cell count (saturating for absurd values).
fn cell_count(extent_m: f64, m: f64, wavelength_m: f64) -> u64 {
    let c = (extent_m * m / wavelength_m).round();
    if c >= 1.0 { c as u64 } else { 1 }
}

/// Per-octave lattice periods actually used (for documentation / sidecar):
/// when tileable, the number of lattice cells across the extent in x and y for each octave,
/// `cx_i = max(1, round(extent_x_m · lac^i / λ0))` (same for y).
///
/// The counts are computed the same way when `tileable` is false, but are then only nominal:
/// the non-tileable field uses the exact wavelength `λ0 / lac^i` (see [`octave_wavelengths`]).
pub fn octave_cells(spec: &GridSpec, p: &PerlinParams) -> Vec<(u64, u64)> {
    lacunarity_powers(p)
        .into_iter()
        .map(|m| {
            (
                cell_count(spec.extent_x_m, m, p.wavelength_m),
                cell_count(spec.extent_y_m, m, p.wavelength_m),
            )
        })
        .collect()
}

/// Per-octave lattice spacings actually used, in meters, `(along x, along y)`:
/// `extent / cells` when tileable, `λ0 / lac^i` in both directions otherwise.
pub fn octave_wavelengths(spec: &GridSpec, p: &PerlinParams) -> Vec<(f64, f64)> {
    if p.tileable {
        octave_cells(spec, p)
            .into_iter()
            .map(|(cx, cy)| (spec.extent_x_m / cx as f64, spec.extent_y_m / cy as f64))
            .collect()
    } else {
        lacunarity_powers(p)
            .into_iter()
            .map(|m| {
                let w = p.wavelength_m / m;
                (w, w)
            })
            .collect()
    }
}
