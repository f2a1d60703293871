//! Second-order random seas: the bound waves of every pair of free waves (Longuet-Higgins
//! 1963; Sharma & Dean 1981, in the form of Forristall 2000 and Dalzell 1999).
//!
//! The linear sea of [`super`] is η1 = Σ_i a_i cos ψ_i over every resolved wavevector k_i
//! of the whole plane, with a_i = 2|h̃0(k_i)|, ψ_i = k_i·x − ω_i t + arg h̃0(k_i). To
//! second order,
//!
//! η2 = Σ_i Σ_j a_i a_j [K⁺_ij cos(ψ_i + ψ_j) + K⁻_ij cos(ψ_i − ψ_j)],
//!
//! a double sum over all ordered pairs, with R = k tanh(kd) = ω²/g, s = √R, Q = k² − R²,
//! k_i·k_j the dot product and k± = |k_i ± k_j|:
//!
//! ```text
//! K⁺ = ¼ [(D⁺ − (k_i·k_j − R_i R_j))/(s_i s_j) + R_i + R_j]
//! D⁺ = [(s_i + s_j)(s_i Q_j + s_j Q_i) + 2(s_i + s_j)²(k_i·k_j − R_i R_j)]
//!      / [(s_i + s_j)² − k⁺ tanh(k⁺ d)]
//! K⁻ = ¼ [(D⁻ − (k_i·k_j + R_i R_j))/(s_i s_j) + R_i + R_j]
//! D⁻ = [(s_i − s_j)(s_j Q_i − s_i Q_j) + 2(s_i − s_j)²(k_i·k_j + R_i R_j)]
//!      / [(s_i − s_j)² − k⁻ tanh(k⁻ d)]
//! ```
//!
//! Deep water (d → ∞: R = k, Q = 0, tanh = 1) and collinear waves give K⁺ = (k_i + k_j)/4
//! and K⁻ = −|k_i − k_j|/4; a single wave gives Stokes' η2 = ½ k a² cos 2ψ. On the
//! diagonal K⁻_ii is the limit of collinear pairs, the set-down under a wave group with
//! its return flow: ½[(k²/(2R) − R/2 + g k/(ω c_g))/(1 − g d/c_g²) − k/sinh 2kd], zero in
//! deep water.
//!
//! On the grid: k_i ± k_j is a grid wavevector, so every pair adds a_i a_j K (with the
//! pair's phase) to one cell of a full-plane array Z, η2 = Re Σ_q Z_q e^{iq·x}, and the
//! half spectrum H2(q) = ½(Z_q + conj Z_{−q}) joins the linear one before the one
//! inverse transform. Pairs whose k_i ± k_j falls outside the grid (beyond Nyquist, or on
//! the Nyquist row or column, which the synthesis leaves out) are dropped and counted.
//!
//! Cost: the pairs of the components that carry a fraction q of the spectrum's variance
//! (the strongest by E|h̃0|², ties by index), so a few thousand components instead of
//! the whole grid. Each Z line is summed by one task in a fixed order, so the field does
//! not depend on the number of threads. Time: ψ_i ± ψ_j move with ω_i ± ω_j, the ω of
//! the linear sea (rounded to the loop's multiples when looping, so sums and differences
//! stay multiples).

use rayon::prelude::*;
use rustfft::num_complex::{Complex, Complex32};
use serde::Serialize;

use super::{HalfSpectrum, SpectrumSetup};
use crate::fastmath;
use crate::grid::signed_index;
use crate::simd::Isa;
use crate::spectrum::{Dispersion, G};
pub use cutoff::Cutoff;
use draws::{Draw, each_line, flat, lines_within, octave, octaves};

pub(crate) type C64 = Complex<f64>;

/// A free wave of the linear sea.
#[derive(Debug, Clone, Copy)]
pub struct Component {
    pub n: i64,
    pub m: i64,
    pub kx: f64,
    pub ky: f64,
    pub k: f64,
    /// R = k tanh(kd) = ω²/g, rad/m.
    pub r: f64,
    /// √R.
    pub s: f64,
    /// k² − R² (0 in deep water).
    pub q: f64,
    /// h̃0 = ρ e^{iφ}.
    pub rho: f64,
    pub phi: f64,
    /// E|h̃0|², m² (the ranking).
    pub p: f64,
}

impl Component {
    /// The wave of wavevector (kx, ky) with h̃0 = ρ e^{iφ}, at depth `depth` (None: deep).
    pub fn new(kx: f64, ky: f64, rho: f64, phi: f64, depth: Option<f64>) -> Self {
        let k = kx.hypot(ky);
        let r = r_of_k(k, depth);
        Self {
            n: 0,
            m: 0,
            kx,
            ky,
            k,
            r,
            s: r.sqrt(),
            q: (k - r) * (k + r),
            rho,
            phi,
            p: rho * rho,
        }
    }
}

fn tanh(x: f64) -> f64 {
    crate::spectrum::spreading::tanh(x.abs()).copysign(x)
}

/// K⁺ and K⁻ of two different waves (see the module notes); `depth` None is deep water.
#[inline]
pub fn kernels(a: &Component, b: &Component, depth: Option<f64>) -> (f64, f64) {
    (kernel_plus(a, b, depth), kernel_minus(a, b, depth))
}

/// K⁺ of two different waves.
#[inline]
pub fn kernel_plus(a: &Component, b: &Component, depth: Option<f64>) -> f64 {
    let dot = a.kx * b.kx + a.ky * b.ky;
    let kp = (a.k * a.k + b.k * b.k + 2.0 * dot).max(0.0).sqrt();
    let tp = match depth {
        Some(d) => kp * tanh(kp * d),
        None => kp,
    };
    let rr = a.r * b.r;
    let sp = a.s + b.s;
    let den = sp * sp - tp;
    let d_plus = if den != 0.0 {
        (sp * (a.s * b.q + b.s * a.q) + 2.0 * sp * sp * (dot - rr)) / den
    } else {
        0.0
    };
    0.25 * ((d_plus - (dot - rr)) / (a.s * b.s) + a.r + b.r)
}

/// K⁻ of two different waves.
#[inline]
pub fn kernel_minus(a: &Component, b: &Component, depth: Option<f64>) -> f64 {
    let dot = a.kx * b.kx + a.ky * b.ky;
    let km = (a.k * a.k + b.k * b.k - 2.0 * dot).max(0.0).sqrt();
    let tm = match depth {
        Some(d) => km * tanh(km * d),
        None => km,
    };
    kernel_minus_at([a.kx, a.ky, a.r, a.s, a.q], [b.kx, b.ky, b.r, b.s, b.q], tm)
}

/// K⁻ of two different waves (kx, ky, R, s, Q each, as a [`Component`] holds them) whose
/// difference k_a − k_b has T = `tm` ([`fit::resonance_t`] of its norm).
#[inline]
pub fn kernel_minus_at(a: [f64; 5], b: [f64; 5], tm: f64) -> f64 {
    let [ax, ay, ar, a_s, aq] = a;
    let [bx, by, br, bs, bq] = b;
    let dot = ax * bx + ay * by;
    let rr = ar * br;
    let sm = a_s - bs;
    let den = sm * sm - tm;
    let d_minus = if den != 0.0 {
        (sm * (bs * aq - a_s * bq) + 2.0 * sm * sm * (dot + rr)) / den
    } else {
        0.0
    };
    0.25 * ((d_minus - (dot + rr)) / (a_s * bs) + ar + br)
}

/// K⁺_ii (Stokes' ½k in deep water) and K⁻_ii (the set-down; 0 in deep water) of one wave.
pub fn self_kernels(c: &Component, depth: Option<f64>) -> (f64, f64) {
    let k_plus = kernel_plus(c, c, depth);
    let k_minus = match depth {
        None => 0.0,
        Some(d) => {
            let (k, r) = (c.k, c.r);
            let omega = (G * r).sqrt();
            let kd = k * d;
            let t = tanh(kd);
            let cg = 0.5 * G * (t + kd * (1.0 - t * t)) / omega;
            let t1 = 0.5 * k * k / r;
            let t2 = 0.5 * r;
            let t3 = G * k / (omega * cg);
            let sinh_term = if 2.0 * kd < 300.0 {
                let e = fastmath::exp(2.0 * kd);
                k / (0.5 * (e - 1.0 / e))
            } else {
                0.0
            };
            0.5 * ((t1 - t2 + t3) / (1.0 - G * d / (cg * cg)) - sinh_term)
        }
    };
    (k_plus, k_minus)
}

/// What the sidecar records of a second-order field.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SecondOrderInfo {
    /// The variance fraction asked for.
    pub fraction: f64,
    /// The convergence limits ω_up and ω_lo of the paired waves, rad/s (absent: every
    /// wave; ω_lo absent in deep water).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cutoff_rad_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cutoff_low_rad_s: Option<f64>,
    /// Linear components paired, of the resolved ones with energy (within the limits).
    pub components: usize,
    pub components_available: usize,
    /// The fraction of the expected variance the paired components carry.
    pub variance_fraction_kept: f64,
    /// Pairs (unordered, with the self-pairs) whose sum or difference wavevector fell
    /// outside the grid and were dropped, and all pairs.
    pub sum_pairs_dropped: u64,
    pub difference_pairs_dropped: u64,
    pub pairs: u64,
    /// `pairs` (the exact pair sum) or `fitted` (the fitted kernels by transforms).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub method: Option<String>,
    /// The fitted kernels' estimated rms error, as a fraction of the bound waves' rms.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimated_rel_rms_error: Option<f64>,
    /// The fitted difference term's powers m ≤ M of (δ²/T)^m / T (3 in deep water; at
    /// finite depth 3 where the fit's estimate with them is within `auto`'s bound, else 4).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub difference_powers: Option<usize>,
    /// Why `nonlinear_method = auto` chose the method (absent: it was asked for).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub method_reason: Option<String>,
    /// With a loop period: the multiples ν of 2π/T the pairs turn with, when the pair
    /// sum is binned by them once for every time (absent: summed at each time).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub loop_multiples: Option<usize>,
}

/// The paired components of a sea, by kx line.
pub struct SecondOrder {
    comps: Vec<Component>,
    /// For every kx index n (offset by nx), the range of `comps` on that line.
    lines: Vec<std::ops::Range<usize>>,
    /// The kx indices that hold components, ascending.
    occupied: Vec<i64>,
    depth: Option<f64>,
    nx: usize,
    ny: usize,
    /// The kernel inputs of `comps` as columns (the pair sum's line kernels), made at the
    /// pair sum's first use: 56 bytes a wave the fitted method never reads.
    columns: std::sync::OnceLock<pairs::Columns>,
    pub info: SecondOrderInfo,
}

fn depth_of(d: Dispersion) -> Option<f64> {
    match d {
        Dispersion::Deep => None,
        Dispersion::Finite { depth_m } => Some(depth_m),
    }
}

/// The resolved indices lo ..= hi of an axis of `len` samples (without the Nyquist index
/// of an even length).
#[inline]
fn resolved_span(len: usize) -> (i64, i64) {
    let half = (len / 2) as i64;
    if len % 2 == 0 {
        (1 - half, half - 1)
    } else {
        (-half, half)
    }
}

/// n lies on the grid's resolved range (not the Nyquist index of an even length).
#[inline]
fn on_grid(n: i64, len: usize) -> bool {
    let (lo, hi) = resolved_span(len);
    n >= lo && n <= hi
}

/// R = k tanh(kd) = ω²/g of wavenumber k (`depth` None: deep, R = k).
#[inline]
fn r_of_k(k: f64, depth: Option<f64>) -> f64 {
    match depth {
        Some(d) => k * tanh(k * d),
        None => k,
    }
}

/// R of the grid wave (n, m).
fn r_of(setup: &SpectrumSetup, depth: Option<f64>, n: i64, m: i64) -> f64 {
    let (kx, ky) = setup.wavevector(n, m);
    // (Not `hypot`: no overflow to guard against, at a fraction of its cost.)
    r_of_k((kx * kx + ky * ky).sqrt(), depth)
}

impl SecondOrder {
    /// The components of `setup` (its draws; the time is not used) that carry `fraction`
    /// of the expected variance.
    pub fn new(setup: &SpectrumSetup, fraction: f64) -> Self {
        Self::within(setup, fraction, None)
    }

    /// The components of `setup` within `cutoff` (None: every one) that carry `fraction`
    /// of the expected variance within it.
    pub fn within(setup: &SpectrumSetup, fraction: f64, cutoff: Option<Cutoff>) -> Self {
        let isa = Isa::detect();
        let (nx, ny) = (setup.spec.nx, setup.spec.ny);
        let depth = depth_of(setup.dispersion);
        let admit = |d: &Draw| cutoff.is_none_or(|c| c.admits(r_of(setup, depth, d.n, d.m)));
        let lines = lines_within(setup, cutoff);
        let component = |d: &Draw| {
            let (kx, ky) = setup.wavevector(d.n, d.m);
            let mut c = Component::new(kx, ky, d.rho, d.phi, depth);
            (c.n, c.m, c.p) = (d.n, d.m, d.p);
            c
        };
        let info = SecondOrderInfo {
            fraction,
            cutoff_rad_s: cutoff.map(|c| c.omega_up),
            cutoff_low_rad_s: cutoff.map(|c| c.omega_lo).filter(|&w| w > 0.0),
            ..SecondOrderInfo::default()
        };
        if fraction >= 1.0 {
            // Every draw within the limits: nothing to rank, one pass.
            let all = flat(each_line(setup, isa, lines, &|d| {
                admit(&d).then(|| component(&d))
            }));
            let info = SecondOrderInfo {
                components_available: all.len(),
                variance_fraction_kept: if all.is_empty() { 0.0 } else { 1.0 },
                ..info
            };
            return Self::of(all, nx, ny, depth, info);
        }
        // The ranking: by E|h̃0|² descending, ties by index (a total order, so the same
        // whatever the sort or the threads), of light keys (E|h̃0|² and the indices (n, m)
        // packed in their order), sorted in parallel.
        type Key = (f64, u64);
        let rank = |a: &Key, b: &Key| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1));
        // Only the candidates are ranked: the draws of the octaves that reach the fraction
        // of the total, and one octave below them (a margin far beyond the rounding of the
        // octaves' sums); all of them if the margin fell short.
        let (by_octave, total) = octaves(setup, isa, lines, &admit);
        let available = by_octave.iter().map(|b| b.1).sum();
        let mut floor = 0;
        let mut acc = 0.0;
        for o in (0..by_octave.len()).rev() {
            acc += by_octave[o].0;
            if acc >= fraction * total {
                floor = o.saturating_sub(1);
                break;
            }
        }
        let select = |floor: usize| {
            let mut keys: Vec<Key> = flat(each_line(setup, isa, lines, &|d| {
                (octave(d.p) >= floor && admit(&d)).then(|| d.key())
            }));
            keys.par_sort_unstable_by(rank);
            let mut kept = 0.0;
            let mut count = 0usize;
            for k in &keys {
                if kept >= fraction * total {
                    break;
                }
                kept += k.0;
                count += 1;
            }
            let reached = kept >= fraction * total || floor == 0;
            reached.then(|| (kept, count.checked_sub(1).map(|i| keys[i])))
        };
        let (kept, last) = select(floor)
            .or_else(|| select(0))
            .expect("every draw reaches the fraction");
        // The kept components: those ranked no later than the last kept key.
        let all: Vec<Component> = match last {
            None => Vec::new(),
            Some(last) => flat(each_line(setup, isa, lines, &|d| {
                (rank(&d.key(), &last).is_le() && admit(&d)).then(|| component(&d))
            })),
        };
        let info = SecondOrderInfo {
            components_available: available,
            variance_fraction_kept: if total > 0.0 { kept / total } else { 0.0 },
            ..info
        };
        Self::of(all, nx, ny, depth, info)
    }

    /// A sea of the given components (tests, the single-pair checks), at `depth`.
    pub fn from_components(
        comps: Vec<Component>,
        nx: usize,
        ny: usize,
        depth: Option<f64>,
    ) -> Self {
        let info = SecondOrderInfo {
            fraction: 1.0,
            components_available: comps.len(),
            variance_fraction_kept: 1.0,
            ..SecondOrderInfo::default()
        };
        Self::of(comps, nx, ny, depth, info)
    }

    /// The paired components `comps` (any order), by kx line; `info` with the counts.
    fn of(
        mut comps: Vec<Component>,
        nx: usize,
        ny: usize,
        depth: Option<f64>,
        info: SecondOrderInfo,
    ) -> Self {
        // (The indices are distinct: one order, however sorted.)
        comps.par_sort_unstable_by_key(|c| (c.n, c.m));
        let mut lines = vec![0..0; 2 * nx + 1];
        let mut occupied = Vec::new();
        let mut start = 0;
        while start < comps.len() {
            let n = comps[start].n;
            let end = start + comps[start..].iter().take_while(|c| c.n == n).count();
            lines[(n + nx as i64) as usize] = start..end;
            occupied.push(n);
            start = end;
        }
        let c = comps.len() as u64;
        let info = SecondOrderInfo {
            components: comps.len(),
            pairs: c * (c + 1) / 2,
            ..info
        };
        Self {
            columns: std::sync::OnceLock::new(),
            comps,
            lines,
            occupied,
            depth,
            nx,
            ny,
            info,
        }
    }

    pub fn components(&self) -> &[Component] {
        &self.comps
    }

    /// The indices of `comps` on kx line n.
    fn line(&self, n: i64) -> std::ops::Range<usize> {
        let i = n + self.nx as i64;
        if i < 0 || i as usize >= self.lines.len() {
            return 0..0;
        }
        self.lines[i as usize].clone()
    }

    /// The complex amplitudes a_i e^{i(φ_i − ω_i t)} of the components at `setup`'s time,
    /// in the order of `comps`.
    fn amplitudes(&self, setup: &SpectrumSetup) -> Vec<C64> {
        self.comps
            .iter()
            .map(|c| {
                let wt = setup.omega_t(c.kx, c.ky);
                let (s, co) = fastmath::sin_cos(c.phi - wt);
                C64::new(2.0 * c.rho * co, 2.0 * c.rho * s)
            })
            .collect()
    }

    /// Adds the bound waves at `setup`'s time to the linear half spectrum `half`, and
    /// returns the pair counts for the sidecar.
    pub fn add_to(&self, setup: &SpectrumSetup, half: &mut HalfSpectrum) -> SecondOrderInfo {
        let (z, sums, diffs) = self.bound_plane(setup);
        add_plane(&z, half);
        SecondOrderInfo {
            sum_pairs_dropped: self.info.pairs - sums,
            difference_pairs_dropped: self.info.pairs - diffs,
            ..self.info.clone()
        }
    }
}

/// Adds the half spectrum ½(Z_q + conj Z_−q) of a full-plane Z (nx lines of ny, FFT
/// order) to `half`, on the grid's resolved cells.
pub fn add_plane(z: &[C64], half: &mut HalfSpectrum) {
    let (nx, ny) = (half.nx, half.ny);
    half.data
        .par_chunks_mut(ny)
        .enumerate()
        .for_each(|(n, line)| {
            let n = n as i64;
            if !on_grid(n, nx) {
                return;
            }
            let row = n as usize;
            let mirror = (-n).rem_euclid(nx as i64) as usize;
            for (idx, v) in line.iter_mut().enumerate() {
                let m = signed_index(idx, ny);
                if !on_grid(m, ny) {
                    continue;
                }
                let midx = (-m).rem_euclid(ny as i64) as usize;
                let h = 0.5 * (z[row * ny + idx] + z[mirror * ny + midx].conj());
                *v += Complex32::new(h.re as f32, h.im as f32);
            }
        });
}

mod cutoff;
mod draws;
pub mod fit;
pub mod looped;
mod pairs;
pub mod transform;

#[cfg(test)]
mod tests;
