//! The `[trochoid]` section: Thon et al.'s procedural ocean (`--method trochoid`).

use serde::{Deserialize, Serialize};

use crate::error::ParamError;

/// Largest samples per side of a trochoid field (streamed outputs are not held in memory).
pub const MAX_STREAM_SIDE: usize = 1 << 20;
/// Largest samples in all of a streamed trochoid field.
pub const MAX_STREAM_SAMPLES: u64 = 1 << 38;

/// Thon, Dischler & Ghazanfarpour (2000): the strongest components of a sampled spectrum
/// as 2D trochoids, plus Perlin turbulence fitted to the spectrum beyond them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TrochoidParams {
    /// Components n: the strongest of the sampled matrix become trochoids.
    pub components: usize,
    /// Side of the matrix on which the directional spectrum is sampled (the paper: 64).
    pub matrix: usize,
    /// Period of the virtual tile whose Fourier grid the matrix is, m (wavevector spacing
    /// 2π/this); default 3 peak wavelengths (the matrix then reaches ±10 kp).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub matrix_extent_m: Option<f64>,
    /// Sharpness k·r of the trochoid profile, 0 ≤ kr < 1 (0: a cosine; → 1: a cusp).
    pub sharpness: f64,
    /// Add the spectrum-fitted Perlin turbulence (eq. 9–10).
    pub turbulence: bool,
    /// Turbulence octaves n_o.
    pub octaves: u32,
    /// Frequency multiplier m between octaves (default: fitted to the spectrum's slope).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub multiplier: Option<f64>,
    /// Turbulence amplitude A_t, m (default: fitted to the spectrum's level).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub amplitude_m: Option<f64>,
    /// Drift of the turbulence along the wind, m/s (default: the phase speed at f_max).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drift_mps: Option<f64>,
    /// Drift along the noise's third axis, lattice cells of the first octave per second
    /// (default: f_max / 4).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub evolve_per_s: Option<f64>,
    /// Attenuate trochoids and octaves above the grid's Nyquist wavenumber π/Δ (§2.4).
    pub antialias: bool,
    /// World position of sample (0, 0), m: a grid is a window on an endless sea.
    pub origin_m: [f64; 2],
}

impl Default for TrochoidParams {
    fn default() -> Self {
        Self {
            components: 48,
            matrix: 64,
            matrix_extent_m: None,
            sharpness: 0.5,
            turbulence: true,
            octaves: 8,
            multiplier: None,
            amplitude_m: None,
            drift_mps: None,
            evolve_per_s: None,
            antialias: true,
            origin_m: [0.0, 0.0],
        }
    }
}

fn err(name: &str, allowed: &str, got: impl std::fmt::Display) -> ParamError {
    ParamError {
        name: format!("trochoid.{name}"),
        allowed: allowed.to_string(),
        got: got.to_string(),
    }
}

impl TrochoidParams {
    /// Checks every value of the section.
    pub fn validate(&self) -> Result<(), ParamError> {
        if !(4..=512).contains(&self.matrix) || self.matrix % 2 != 0 {
            return Err(err(
                "matrix",
                "an even number between 4 and 512",
                self.matrix,
            ));
        }
        let cells = self.matrix * self.matrix;
        if !(1..=cells.min(4096)).contains(&self.components) {
            return Err(err(
                "components",
                &format!(
                    "between 1 and {} (the matrix's cells, at most 4096)",
                    cells.min(4096)
                ),
                self.components,
            ));
        }
        if let Some(l) = self.matrix_extent_m {
            if !(l.is_finite() && l > 0.0) {
                return Err(err("matrix_extent_m", "a finite number > 0 m", l));
            }
        }
        if !(self.sharpness.is_finite() && (0.0..0.99).contains(&self.sharpness)) {
            return Err(err("sharpness", "≥ 0 and < 0.99", self.sharpness));
        }
        if !(1..=16).contains(&self.octaves) {
            return Err(err("octaves", "between 1 and 16", self.octaves));
        }
        if let Some(m) = self.multiplier {
            if !(m.is_finite() && m > 1.0 && m <= 8.0) {
                return Err(err("multiplier", "> 1 and ≤ 8", m));
            }
        }
        if let Some(a) = self.amplitude_m {
            if !(a.is_finite() && a >= 0.0) {
                return Err(err("amplitude_m", "a finite number ≥ 0 m", a));
            }
        }
        if let Some(v) = self.drift_mps {
            if !v.is_finite() {
                return Err(err("drift_mps", "a finite number of m/s", v));
            }
        }
        if let Some(v) = self.evolve_per_s {
            if !v.is_finite() {
                return Err(err("evolve_per_s", "a finite number per second", v));
            }
        }
        for (axis, v) in [("x", self.origin_m[0]), ("y", self.origin_m[1])] {
            if !(v.is_finite() && v.abs() <= 1e9) {
                return Err(err(&format!("origin_m ({axis})"), "finite, |·| ≤ 1e9 m", v));
            }
        }
        Ok(())
    }
}
