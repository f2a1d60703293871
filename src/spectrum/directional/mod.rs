//! A directional sea F(f)·D(f, θ) as a wavenumber spectrum, the physical scaling of the
//! `pierson-moskowitz`, `jonswap` and `tma` spectra.
//!
//! # Change of variables
//! F(f) D(f, θ) df dθ = Ψ(k, θ) k dk dθ and dkx dky = k dk dθ, so
//! Ψ(kx, ky) = F(f) · D(f, θ) · (df/dk) / k, with f = ω(k)/2π, df/dk = c_g/2π and
//! θ = atan2(ky, kx) − wind direction. ∫Ψ dkx dky = m0.
//!
//! # Discrete amplitudes
//! E|h̃0(k)|² = P(k) = ½ ∫_cell Ψ dkx dky over the grid cell of size dkx × dky centred
//! on k; with h̃(k) = h̃0(k)e^{−iωt} + conj(h̃0(−k))e^{iωt} the expected variance of the
//! field Σ_k (P(k) + P(−k)) is then ∫Ψ over the cells of the resolved wavevectors.
//!
//! # Cell integration rule
//! Each cell is integrated by an n_x × n_y tensor Gauss–Legendre rule (n = 1 is the
//! midpoint), n chosen per axis from the ratio m = Δk/ℓ of the cell size to the smallest
//! length scale ℓ of Ψ near the cell (a Gaussian of width σ needs n ≈ 2 + 1.2·Δk/σ points
//! for 1e-4 of its integral):
//! - radial: ℓ = 0.02·(c/c_g)(kp)·kp for k < 2.5 kp (the steep low-frequency flank, the
//!   γ peak and the kinks of p(f) and Φ live there; 0.02 in f/fp is the width of the
//!   low-frequency exponential at 0.6 fp, c/c_g converts widths in f to widths in k), and
//!   k/5 beyond (the f⁻⁵ tail: |Ψ''/Ψ| ≤ 20/k²);
//! - angular: ℓ = k·σ_θ, σ_θ = √(2/s) for cos^{2s}(θ/2) at the largest s of the model
//!   (incl. swell), ≤ 0.5 (Cos2 and wide spreads), ≤ 0.29 for Donelan–Banner;
//! - n = 1 when m ≤ 0.15 (midpoint error ≲ 1e-3 of the cell), else
//!   n = min(16, ⌈2 + 1.2 m⌉).
//!
//! With a peak spanning ~5 cells (15 m/s PM on 1024 m) the ~400 cells below 2.5 kp get
//! 9 × 9 points and the rest of the plane (beyond ~35 Δk) the midpoint, so accurate cells
//! cost well under 1 % of a 4096² spectrum. A far cell is recognised by two comparisons
//! of k² before anything else.
//!
//! # Evaluation
//! For the JONSWAP-family models (see [`FrequencySpectrum::shape`]) F, D and the Jacobian
//! fold into Ψ = a(|k|) · m(θ) · cos^{2s}(θ/2), with the radial part
//! a = A(2π)⁴ · c_g/(k ω⁵) · Φ · exp(−5/4 (ωp/ω)⁴ + r ln γ − ln Z) computed from k² alone,
//! and m = 1 (cos^{2s} family), cos²θ (Cos2) or sech²(βθ) (Donelan–Banner), from k̂·ŵ
//! without trigonometry (atan only for Donelan–Banner's θ). The per-frequency spreading
//! quantities [s, ln Z, β] at x = ln(f/fp) (s = p + s_ξ, ln Z = ln N_s, ln Z_cos2 or the
//! Donelan–Banner normalizer) come from a cubic table built at construction (256 nodes per
//! unit of x on x ∈ [−3, 6], split at the breakpoints of the formulas; error of the
//! exponent ~3e-9; exact outside). Other frequency models go through
//! `FrequencySpectrum::density` (a virtual call). A line reuses the radial part for
//! entries of equal k² (see `amplitude_variance_line`). The midpoint cells of a grid
//! (nearly all of them) are computed as one single-precision power of two each, with
//! a single-precision radial part for the common deep-water seas (see `grid`: within
//! 1e-6·(1 + |log2 of the value below the peak cell's|), tested; 0 below 2^−300 of the peak cell): that is most of the arithmetic of a
//! spectrum, runs sixteen lanes wide with AVX-512, and the amplitudes are
//! single-precision numbers anyway. The near-peak cells of a line take the cell rule in
//! whole-array passes (see `cells`); [`DirectionalSpectrum::psi`] and the cell rule keep
//! double precision. Only basic IEEE operations and `fastmath`
//! are used, so values are bit-identical on every platform.

use super::frequency::{
    C_HIGH, C_LOW, DEPTH, FrequencySpectrum, WIND_SPEED, gauss_legendre, kitaigorodskii,
};
use super::spreading::{
    DB_R_1, DB_R_2, DB_R_MIN, Spreading, SpreadingModel, db_beta_branch, donelan_banner_norm,
    half_one_plus, ln_half_one_plus, ln_np, ln_z_cos2, mitsuyasu_s_max, sech2, tanh,
};
use super::{Dispersion, G, LineQuery, PairOut, Spectrum};
use crate::error::ParamError;
use crate::fastmath::{ln, sin_cos};
use crate::simd::Isa;

mod angle;
mod cells;
mod fast_radial;
mod grid;
mod kernel;
mod line;
mod spread_table;

pub(crate) use angle::atan2_pos;
use kernel::{Kernel, Radial, ShapeK, SpreadKind, half_one_plus_f32, power_f32};
use spread_table::{SpreadExact, SpreadTable};

const PI: f64 = std::f64::consts::PI;
const TWO_PI: f64 = 2.0 * PI;

/// Largest Gauss–Legendre order per axis of the cell rule.
pub const MAX_CELL_ORDER: usize = 16;
/// Radial length scale near the peak, in units of (c/c_g)·kp.
const PEAK_SCALE: f64 = 0.02;
/// The accurate zone: k < this × kp.
const ZONE: f64 = 2.5;
/// Tail length scale k × this.
const TAIL_SCALE: f64 = 0.2;
/// Midpoint when Δk/ℓ ≤ this.
const MIDPOINT_RATIO: f64 = 0.15;

/// Ψ is 0 where the low-frequency factor exp(−5/4 (ωp/ω)⁴) is below e^−200 (≈ 1e-87),
/// that is where u = (ωp/ω)⁴ exceeds this.
const U_MAX: f64 = 160.0;
/// ... and where the directional power cos^{2s}(θ/2) is below e^−200. Both floors keep
/// every product of the spectrum away from subnormal numbers, which the processor
/// computes dozens of times more slowly; what they drop is ~1e-87 of the peak.
const POWER_EXPONENT_MIN: f64 = -200.0;

/// A directional sea: F(f)·D(f, θ), converted to the wavenumber spectrum through the
/// dispersion relation.
pub struct DirectionalSpectrum {
    freq: Box<dyn FrequencySpectrum>,
    spreading: Spreading,
    wind_dir_rad: f64,
    u10_mps: f64,
    dispersion: Dispersion,
    kern: Kernel,
    /// The instruction set of the line passes, chosen when the model is built.
    isa: Isa,
}

impl std::fmt::Debug for DirectionalSpectrum {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DirectionalSpectrum")
            .field("freq", &self.freq)
            .field("spreading", &self.spreading)
            .field("wind_dir_rad", &self.wind_dir_rad)
            .field("u10_mps", &self.u10_mps)
            .field("dispersion", &self.dispersion)
            .finish_non_exhaustive()
    }
}

/// k of ω for the dispersion of depth `depth` (∞: deep), by Newton's method with the
/// portable tanh.
fn wavenumber(depth: f64, omega: f64) -> f64 {
    let deep = omega * omega / G;
    if !depth.is_finite() {
        return deep;
    }
    let mut k = deep.max(omega / (G * depth).sqrt());
    for _ in 0..200 {
        let kd = k * depth;
        let t = tanh(kd);
        let f = G * k * t - omega * omega;
        let df = G * (t + kd * (1.0 - t * t));
        let step = f / df;
        k -= step;
        if step.abs() <= 1e-15 * k {
            break;
        }
    }
    k
}

/// Extreme but allowed inputs (a wind of 1e-300 m/s) can put a model's peak frequency or
/// its Hs out of the range of floating point numbers: an error naming the inputs.
pub fn check_peak(freq: &dyn FrequencySpectrum, u10_mps: f64) -> Result<(), ParamError> {
    let (fpeak, hs) = (freq.peak_hz(), freq.hs_m());
    if fpeak > 0.0 && fpeak.is_finite() && hs.is_finite() {
        return Ok(());
    }
    Err(ParamError {
        name: format!("{WIND_SPEED} or --tp (spectrum.tp_s)"),
        allowed: "a value giving a finite spectral peak and Hs".into(),
        got: format!("wind {u10_mps:e} m/s: peak {fpeak:e} Hz, Hs {hs:e} m"),
    })
}

impl DirectionalSpectrum {
    /// `wind_dir_rad`: the direction the wind blows toward (0 = +x), finite.
    /// `u10_mps` ≥ 0 (> 0 for Mitsuyasu spreading). A finite-depth `dispersion` needs
    /// depth > 0 (+∞ is deep water).
    pub fn new(
        freq: Box<dyn FrequencySpectrum>,
        spreading: Spreading,
        wind_dir_rad: f64,
        u10_mps: f64,
        dispersion: Dispersion,
    ) -> Result<Self, ParamError> {
        if !wind_dir_rad.is_finite() {
            return Err(ParamError {
                name: "--wind-dir (wind.direction_deg)".into(),
                allowed: "finite".into(),
                got: wind_dir_rad.to_degrees().to_string(),
            });
        }
        let mitsuyasu = spreading.model == SpreadingModel::Mitsuyasu;
        if !(u10_mps.is_finite() && (u10_mps > 0.0 || (!mitsuyasu && u10_mps == 0.0))) {
            return Err(ParamError {
                name: WIND_SPEED.into(),
                allowed: if mitsuyasu {
                    "> 0 m/s (Mitsuyasu spreading)"
                } else {
                    "≥ 0 m/s"
                }
                .into(),
                got: u10_mps.to_string(),
            });
        }
        Spreading::new(spreading.model, spreading.swell)?;
        let depth = match dispersion {
            Dispersion::Deep => f64::INFINITY,
            Dispersion::Finite { depth_m } => {
                if depth_m.is_nan() || depth_m <= 0.0 {
                    return Err(ParamError {
                        name: DEPTH.into(),
                        allowed: "> 0 m".into(),
                        got: depth_m.to_string(),
                    });
                }
                depth_m
            }
        };
        let fpeak = freq.peak_hz();
        check_peak(freq.as_ref(), u10_mps)?;
        let w_peak = TWO_PI * fpeak;
        let ln_w_peak = ln(w_peak);
        let shape = freq.shape().map(|s| {
            let wp = TWO_PI * s.fp_hz();
            let wp2 = wp * wp;
            ShapeK {
                coef: s.a() * TWO_PI.powi(4),
                inv_wp4: 1.0 / (wp2 * wp2),
                ln_gamma: s.ln_gamma(),
                tma_h: if s.depth_m().is_finite() {
                    wp * (s.depth_m() / G).sqrt()
                } else {
                    f64::INFINITY
                },
                x_shift: ln_w_peak - ln(wp),
            }
        });
        let xi = spreading.swell;
        let swell16 = 16.0 * xi * xi;
        let (kind, coef, mu_lo, mu_hi, s_peak, cap) = match spreading.model {
            SpreadingModel::Cos2 if swell16 == 0.0 => {
                (SpreadKind::Cos2Plain, 0.0, 0.0, 0.0, 0.0, 0.5)
            }
            SpreadingModel::Cos2 => (SpreadKind::Cos2Swell, 0.0, 0.0, 0.0, swell16, 0.5),
            SpreadingModel::Hasselmann => {
                (SpreadKind::Family, 9.77, 4.06, -2.34, 9.77 + swell16, 0.5)
            }
            SpreadingModel::Mitsuyasu => {
                let smax = mitsuyasu_s_max(u10_mps, fpeak);
                (SpreadKind::Family, smax, 5.0, -2.5, smax + swell16, 0.5)
            }
            SpreadingModel::DonelanBanner => {
                (SpreadKind::DonelanBanner, 0.0, 0.0, 0.0, swell16, 0.29)
            }
        };
        let exact = SpreadExact {
            kind,
            coef,
            mu_lo,
            mu_hi,
            swell16,
        };
        let table = if kind == SpreadKind::Cos2Plain {
            SpreadTable::empty(exact)
        } else {
            SpreadTable::new(exact)
        };
        let sigma_theta = if s_peak > 0.0 {
            (2.0 / s_peak).sqrt().min(cap)
        } else {
            cap
        };
        // Cell rule: the peak wavenumber and c/c_g there.
        let kp = wavenumber(depth, w_peak);
        let c_over_cg = if depth.is_finite() {
            let kd = kp * depth;
            let t = tanh(kd);
            2.0 * t / (t + kd * (1.0 - t * t))
        } else {
            2.0
        };
        let rules = (1..=MAX_CELL_ORDER)
            .map(|n| {
                gauss_legendre(n)
                    .into_iter()
                    .map(|(x, w)| (0.5 * x, 0.5 * w))
                    .collect()
            })
            .collect();
        let zone_k = ZONE * kp;
        let far = MIDPOINT_RATIO * TAIL_SCALE.min(sigma_theta);
        let (sd, cd) = sin_cos(wind_dir_rad);
        let mut kern = Kernel {
            wx: cd,
            wy: sd,
            depth,
            shape,
            ln_w_peak,
            kind,
            table,
            zone_k,
            zone2: zone_k * zone_k,
            ell_peak: PEAK_SCALE * c_over_cg * kp,
            sigma_theta,
            far_c2: far * far,
            rules,
            grid_l0: 0.0,
            fast: None,
        };
        let a_peak = kern.radial(kp * kp, freq.as_ref()).a;
        if a_peak > 0.0 && a_peak.is_finite() {
            kern.grid_l0 = ln(a_peak) * std::f64::consts::LOG2_E;
        }
        kern.fast = fast_radial::FastRadial::new(&kern);
        Ok(Self {
            freq,
            spreading,
            wind_dir_rad,
            u10_mps,
            dispersion,
            kern,
            isa: Isa::detect(),
        })
    }

    pub fn freq(&self) -> &dyn FrequencySpectrum {
        self.freq.as_ref()
    }
    pub fn spreading(&self) -> Spreading {
        self.spreading
    }
    pub fn wind_dir_rad(&self) -> f64 {
        self.wind_dir_rad
    }
    pub fn u10_mps(&self) -> f64 {
        self.u10_mps
    }
    pub fn dispersion(&self) -> Dispersion {
        self.dispersion
    }
    /// Significant wave height of the frequency spectrum, m (∫Ψ = m0).
    pub fn hs_m(&self) -> f64 {
        self.freq.hs_m()
    }
    /// The wavenumber of the spectral peak frequency, rad/m.
    pub fn peak_wavenumber(&self) -> f64 {
        self.kern.zone_k / ZONE
    }

    /// Ψ(kx, ky) in m⁴ (per unit kx·ky): F(f) D(f, θ) (df/dk) / k; 0 at k = 0.
    #[inline]
    pub fn psi(&self, kx: f64, ky: f64) -> f64 {
        self.kern.psi(kx, ky, self.freq.as_ref())
    }

    /// ∫ Ψ over the cell of size `dkx` × `dky` centred on (kx, ky), m² (see the module
    /// docs for the rule): twice the amplitude variance.
    #[inline]
    pub fn cell_integral(&self, kx: f64, ky: f64, dkx: f64, dky: f64) -> f64 {
        match self.gauss_orders(kx, ky, dkx, dky) {
            None => {
                2.0 * self
                    .kern
                    .grid_variance(kx, ky, dkx, dky, self.freq.as_ref())
            }
            Some((nx, ny)) => self.gauss_cell(kx, ky, dkx, dky, nx, ny),
        }
    }

    /// The orders of the cell's Gauss–Legendre rule, or `None` for a midpoint cell.
    #[inline(always)]
    fn gauss_orders(&self, kx: f64, ky: f64, dkx: f64, dky: f64) -> Option<(usize, usize)> {
        let kern = &self.kern;
        let k2 = kx * kx + ky * ky;
        if kern.is_far(k2, dkx.max(dky)) {
            return None;
        }
        let k = k2.sqrt();
        let (nx, ny) = (kern.order(k, dkx), kern.order(k, dky));
        if nx == 1 && ny == 1 {
            None
        } else {
            Some((nx, ny))
        }
    }

    /// ∫ Ψ over the cell by the nx × ny Gauss–Legendre rule (double precision).
    fn gauss_cell(&self, kx: f64, ky: f64, dkx: f64, dky: f64, nx: usize, ny: usize) -> f64 {
        let kern = &self.kern;
        let mut sum = 0.0;
        for &(ox, wx) in &kern.rules[nx - 1] {
            let x = kx + ox * dkx;
            let mut line = 0.0;
            for &(oy, wy) in &kern.rules[ny - 1] {
                line += wy * self.psi(x, ky + oy * dky);
            }
            sum += wx * line;
        }
        sum * dkx * dky
    }

    /// The Gauss–Legendre orders (n_x, n_y) the cell rule uses for the cell at (kx, ky).
    pub fn cell_orders(&self, kx: f64, ky: f64, dkx: f64, dky: f64) -> (usize, usize) {
        let k = (kx * kx + ky * ky).sqrt();
        (self.kern.order(k, dkx), self.kern.order(k, dky))
    }
}

impl Spectrum for DirectionalSpectrum {
    /// P(k) = ½ ∫_cell Ψ dkx dky.
    fn amplitude_variance(&self, kx: f64, ky: f64, dkx: f64, dky: f64) -> f64 {
        match self.gauss_orders(kx, ky, dkx, dky) {
            None => self
                .kern
                .grid_variance(kx, ky, dkx, dky, self.freq.as_ref()),
            Some((nx, ny)) => 0.5 * self.gauss_cell(kx, ky, dkx, dky, nx, ny),
        }
    }

    fn amplitude_variance_line(&self, q: &LineQuery, out: &mut [f64]) {
        let mut mirror = vec![0.0; out.len()];
        self.amplitude_variance_pair_line(
            q,
            PairOut {
                a: out,
                b: &mut mirror,
            },
        );
    }

    /// Bit for bit the values of `amplitude_variance`: every cell by the midpoint, in
    /// whole-line passes that vectorize (see `grid`), then the cells near the peak again
    /// by the cell rule, all nodes of the line's near cells together (see `cells`).
    fn amplitude_variance_pair_line(&self, q: &LineQuery, out: PairOut<f64>) {
        let n = q.ky.len().min(out.a.len()).min(out.b.len());
        let q = q.part(0..n);
        let LineQuery { kx, dkx, dky, .. } = q;
        let (pa, pb) = (&mut out.a[..n], &mut out.b[..n]);
        let (isa, freq, kern) = (self.isa, self.freq.as_ref(), &self.kern);
        let mut line = |scratch: &mut LineScratch| {
            let out = PairOut { a: pa, b: pb };
            kern.grid_pair_line_on(isa, freq, &q, out, &mut scratch.grid);
            // k² ≥ kx²: a line whose kx is far has only far cells.
            if !kern.is_far(kx * kx, dkx.max(dky)) {
                let out = PairOut { a: pa, b: pb };
                kern.near_cells_pair_line_on(isa, freq, &q, out, &mut scratch.cells);
            }
        };
        LINE_SCRATCH.with(|cell| match cell.try_borrow_mut() {
            Ok(mut scratch) => line(&mut scratch),
            Err(_) => line(&mut LineScratch::default()),
        });
    }
}

/// Buffers of the line passes.
#[derive(Debug, Default)]
struct LineScratch {
    grid: grid::GridScratch,
    cells: cells::CellScratch,
}

thread_local! {
    /// Buffers of the line passes, one set per thread.
    static LINE_SCRATCH: std::cell::RefCell<LineScratch> =
        std::cell::RefCell::new(LineScratch::default());
}

#[cfg(test)]
mod tests;
