//! Spectrum-fitted turbulence (Thon et al. §2.3, eq. 9–10).
//!
//! The turbulence T(P) = Σ_{o<n_o} N(P·m^o)/m^o of 3D gradient noise N, with P in
//! lattice cells of the first octave (spacing ℓ0), has the omnidirectional wavenumber
//! spectrum (of a plane slice, m² per rad/m)
//!
//! ```text
//! S_T(k) = A_t² Σ_o m^{−3o} ℓ0 S_N(k ℓ0 / m^o)
//! ```
//!
//! (N(x m^o/ℓ0) has the spectrum (ℓ0/m^o)·S_N(k ℓ0/m^o), times the amplitude² m^{−2o}),
//! where S_N(κ) is the noise's own radial spectrum in lattice units, measured once
//! ([`noise_spectrum`]: 4 slices of 1024² samples over a 64-cell periodic lattice,
//! smoothed over ±10 % in κ; it peaks at κ ≈ 3.2 rad per cell and falls steeply beyond).
//! The first octave's lattice spacing is ℓ0 = 0.8·2π/k_max: k_max then lies just past the
//! first octave's peak, where the slope at k_max runs monotonically from −1.5 (m = 1.2)
//! to −3.7 (m = 4) — the range of a sea spectrum between near its peak and its k⁻³ tail
//! (with ℓ0 = 2π/k_max it would run from −2.7 to −8.6, too steep near the peak; with
//! 0.6·2π/k_max from −0.05 to −0.8).
//!
//! The target is the model's omnidirectional spectrum S(k) = k∫Ψ(k, θ)dθ with
//! Ψ = 2P(k)/(Δkx Δky) on the selection matrix (for the physical spectra this is
//! F(f)·df/dk, the 1-D Pierson–Moskowitz filter of the paper as a function of k). m is
//! chosen by a scan of m ∈ [1.1, 4] in steps of 0.005 refined by bisection (the paper's
//! relaxation) so that the log–log slope d ln S_T/d ln k at k_max (central difference over
//! ±10 %) equals the target's there; then A_t so that S_T(k_max) = S(k_max).

use std::sync::OnceLock;

use crate::field::noise3;
use crate::grid::{Grid, GridSpec};
use crate::spectrum::Spectrum;

/// Half-width of the slope's central difference, in ln k.
pub const SLOPE_STEP: f64 = 0.1;
/// The scanned multipliers.
pub const M_RANGE: (f64, f64) = (1.1, 4.0);
/// The first octave's lattice spacing in wavelengths of k_max.
pub const LATTICE_PER_WAVELENGTH: f64 = 0.8;

/// The noise's radial spectrum S_N(κ), κ in rad per lattice cell: (ln κ, smoothed ln S).
pub struct NoiseSpectrum {
    ln_k: Vec<f64>,
    ln_s: Vec<f64>,
}

/// Lattice cells across the measurement tile, and samples per cell.
const TILE_CELLS: usize = 64;
const SAMPLES_PER_CELL: usize = 16;

/// The measured spectrum of the noise (computed once per process, the same every time).
pub fn noise_spectrum() -> &'static NoiseSpectrum {
    static SPECTRUM: OnceLock<NoiseSpectrum> = OnceLock::new();
    SPECTRUM.get_or_init(measure_noise_spectrum)
}

fn measure_noise_spectrum() -> NoiseSpectrum {
    use rayon::prelude::*;
    let n = TILE_CELLS * SAMPLES_PER_CELL;
    let spec = GridSpec::new(n, n, TILE_CELLS as f64, TILE_CELLS as f64);
    let slices = [0.125, 0.375, 0.625, 0.875];
    let mut sum: Vec<f64> = Vec::new();
    let mut ks: Vec<f64> = Vec::new();
    for (s, &w) in slices.iter().enumerate() {
        let key = 0x5eed_0000 + s as u32;
        let xs: Vec<f64> = (0..n).map(|i| spec.x_m(i)).collect();
        let mut data = vec![0.0f32; n * n];
        data.par_chunks_mut(n).enumerate().for_each(|(j, row)| {
            let ctx = noise3::row_context(key, spec.y_m(j), w, TILE_CELLS as i64);
            let mut scratch = noise3::Scratch::default();
            noise3::add_row(&ctx, &xs, 1.0, 0.0, 1.0, row, &mut scratch);
        });
        let a = crate::measure::analyze(&Grid::new(spec, data), None);
        let bins: Vec<_> = a.radial_spectrum.iter().filter(|b| b.complete).collect();
        if sum.is_empty() {
            sum = vec![0.0; bins.len()];
            ks = bins.iter().map(|b| b.k_rad_per_m).collect();
        }
        for (acc, b) in sum.iter_mut().zip(&bins) {
            *acc += b.s_m2_per_rad_per_m / slices.len() as f64;
        }
    }
    let ln_k: Vec<f64> = ks.iter().map(|k| k.ln()).collect();
    let raw: Vec<f64> = sum.iter().map(|s| s.max(1e-300).ln()).collect();
    let ln_s = (0..raw.len())
        .map(|i| {
            let near: Vec<f64> = (0..raw.len())
                .filter(|&j| (ln_k[j] - ln_k[i]).abs() <= 0.1)
                .map(|j| raw[j])
                .collect();
            near.iter().sum::<f64>() / near.len() as f64
        })
        .collect();
    NoiseSpectrum { ln_k, ln_s }
}

impl NoiseSpectrum {
    /// S_N(κ), κ > 0 in rad per lattice cell: log–log interpolation between the bins,
    /// ∝ κ below the first (the slice spectrum vanishes at 0) and 0 beyond the last.
    pub fn at(&self, kappa: f64) -> f64 {
        let x = kappa.ln();
        let (k, s) = (&self.ln_k, &self.ln_s);
        if x <= k[0] {
            return (s[0] + (x - k[0])).exp();
        }
        if x >= k[k.len() - 1] {
            return 0.0;
        }
        let i = k.partition_point(|&v| v <= x) - 1;
        let t = (x - k[i]) / (k[i + 1] - k[i]);
        (s[i] + t * (s[i + 1] - s[i])).exp()
    }
}

/// S_T(k) of unit amplitude for multiplier `m`, `octaves` octaves, first spacing `ell0`.
pub fn turbulence_spectrum(k: f64, m: f64, octaves: u32, ell0: f64) -> f64 {
    let sn = noise_spectrum();
    let mut total = 0.0;
    let mut mo = 1.0;
    for _ in 0..octaves {
        total += ell0 / (mo * mo * mo) * sn.at(k * ell0 / mo);
        mo *= m;
    }
    total
}

/// The omnidirectional spectrum S(k) = k∫Ψ dθ of `spectrum`, Ψ = 2P/(Δkx Δky) for the
/// spacing `dk` (720 directions).
pub fn target_spectrum(spectrum: &dyn Spectrum, k: f64, dk: (f64, f64)) -> f64 {
    const DIRECTIONS: usize = 720;
    let step = std::f64::consts::TAU / DIRECTIONS as f64;
    let sum: f64 = (0..DIRECTIONS)
        .map(|j| {
            let t = (j as f64 + 0.5) * step;
            spectrum.amplitude_variance(k * t.cos(), k * t.sin(), dk.0, dk.1)
        })
        .sum();
    k * 2.0 * sum * step / (dk.0 * dk.1)
}

/// Log–log slope of `f` at `k` (central difference over ±[`SLOPE_STEP`]).
pub fn log_slope(f: impl Fn(f64) -> f64, k: f64) -> f64 {
    let h = SLOPE_STEP;
    ((f(k * h.exp())).ln() - (f(k * (-h).exp())).ln()) / (2.0 * h)
}

/// The fitted turbulence.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Fit {
    /// Frequency multiplier m.
    pub multiplier: f64,
    /// Amplitude A_t, m.
    pub amplitude_m: f64,
    /// Lattice spacing of the first octave, m.
    pub lattice_m: f64,
    /// The target's log–log slope at k_max, and the fitted turbulence's.
    pub target_slope: f64,
    pub turbulence_slope: f64,
    /// The target's S(k_max), m²/(rad/m).
    pub target_level_m2_per_rad_per_m: f64,
}

/// Fits m (unless `multiplier` is given) and A_t (unless `amplitude_m` is given) to the
/// target spectrum at `k_max`.
pub fn fit(
    target: impl Fn(f64) -> f64,
    k_max: f64,
    octaves: u32,
    multiplier: Option<f64>,
    amplitude_m: Option<f64>,
) -> Fit {
    let ell0 = LATTICE_PER_WAVELENGTH * std::f64::consts::TAU / k_max;
    let target_slope = log_slope(&target, k_max);
    let slope_of = |m: f64| log_slope(|k| turbulence_spectrum(k, m, octaves, ell0), k_max);
    let m = multiplier.unwrap_or_else(|| {
        let (lo, hi) = M_RANGE;
        let steps = ((hi - lo) / 0.005).round() as usize;
        let ms: Vec<f64> = (0..=steps).map(|i| lo + i as f64 * 0.005).collect();
        let err: Vec<f64> = ms.iter().map(|&m| slope_of(m) - target_slope).collect();
        let best = (0..ms.len())
            .min_by(|&a, &b| err[a].abs().total_cmp(&err[b].abs()))
            .unwrap_or(0);
        // Refine by bisection where the error changes sign next to the best.
        let bracket = [best.saturating_sub(1), best]
            .into_iter()
            .find(|&i| i + 1 < ms.len() && err[i].signum() != err[i + 1].signum());
        match bracket {
            Some(i) => {
                let (mut a, mut b, mut ea) = (ms[i], ms[i + 1], err[i]);
                for _ in 0..30 {
                    let c = 0.5 * (a + b);
                    let ec = slope_of(c) - target_slope;
                    if ec.signum() == ea.signum() {
                        (a, ea) = (c, ec);
                    } else {
                        b = c;
                    }
                }
                0.5 * (a + b)
            }
            None => ms[best],
        }
    });
    let level = target(k_max);
    let unit = turbulence_spectrum(k_max, m, octaves, ell0);
    let amplitude = amplitude_m.unwrap_or_else(|| {
        if unit > 0.0 {
            (level / unit).sqrt()
        } else {
            0.0
        }
    });
    Fit {
        multiplier: m,
        amplitude_m: amplitude,
        lattice_m: ell0,
        target_slope,
        turbulence_slope: slope_of(m),
        target_level_m2_per_rad_per_m: level,
    }
}
