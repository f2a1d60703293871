//! Wave-by-wave statistics of a height field: what a researcher checks first of a sea
//! that is meant to be real.
//!
//! - **Moments.** Skewness E[(η − η̄)³]/σ³ and kurtosis E[(η − η̄)⁴]/σ⁴ (3 for a Gaussian
//!   sea); the fraction of the surface above 3σ against the Gaussian 0.00135.
//! - **Mean-square slope** Σ k²·P(k) over the measured spectrum (the radial bins), next
//!   to Cox & Munk's clean-surface value 0.003 + 5.12·10⁻³·U (U the wind speed at 12.5 m,
//!   taken as the sidecar's wind speed when known). A grid resolves only the waves longer
//!   than two samples, so its slope variance is a part of the ocean's.
//! - **Zero-crossing waves** along transects in the mean wave direction (the axial peak
//!   direction of the measured spectrum): parallel lines one sample apart, sampled every
//!   min(dx, dy) by bilinear interpolation and clipped to the grid (at most 2·max(nx, ny)
//!   lines and samples per line, for grids of very unequal spacings). A wave runs from one
//!   zero up-crossing (of η − η̄) to the next; its height H = max − min. H1/3 is the mean
//!   of the highest third. Exceedance P(H > h) against Rayleigh exp(−2h²/Hs²), Hs = 4σ.
//! - **Crests**: the maximum of η − η̄ between an up-crossing and the next down-crossing.
//!   Exceedance against Rayleigh exp(−8c²/Hs²) and Forristall's (2000) short-crested
//!   second-order fit exp(−(c/(α·Hs))^β), α = 0.3536 + 0.2568·S1 + 0.0800·Ur,
//!   β = 2 − 1.7912·S1 − 0.5302·Ur + 0.2824·Ur², with the steepness S1 = 2πHs/(g·Tm01²)
//!   and the Ursell number Ur = Hs/(k1²·d³) from the measured field: Tm01 = m0/m1 of the
//!   frequency spectrum (frequencies of the measured wavenumbers by the dispersion
//!   relation at depth d), k1 the wavenumber of period Tm01; deep water: Ur = 0.

use serde::Serialize;

use crate::grid::Grid;
use crate::measure::Analysis;
use crate::spectrum::{Dispersion, G};

/// The Gaussian probability of η − η̄ > 3σ.
pub const GAUSSIAN_P_3SIGMA: f64 = 0.001_349_898_031_630_095;
/// Levels, in units of Hs, of the exceedance tables.
const LEVELS: [f64; 12] = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.2, 1.4];

/// What the statistics need to know of the sea besides its heights.
#[derive(Debug, Clone, Copy, Default)]
pub struct SeaContext {
    /// Wind speed, m/s, when the sidecar says it.
    pub wind_speed_mps: Option<f64>,
    /// Water depth, m (None: deep).
    pub depth_m: Option<f64>,
}

/// One level of an exceedance table: P(X > level·Hs), measured and by the references.
#[derive(Debug, Clone, Serialize)]
pub struct Exceedance {
    pub level_hs: f64,
    pub measured: f64,
    pub rayleigh: f64,
    /// Forristall (2000), crests only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub forristall: Option<f64>,
}

/// Zero-crossing wave heights along the transects.
#[derive(Debug, Clone, Serialize)]
pub struct WaveHeights {
    pub count: usize,
    /// Mean of the highest third, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub h_third_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub h_max_m: Option<f64>,
    /// H1/3 / (4σ): about 0.95–1 for a real narrow-band sea, 1 for Rayleigh heights.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub h_third_over_hs: Option<f64>,
    pub exceedance: Vec<Exceedance>,
}

/// Crest heights along the transects, with Forristall's parameters.
#[derive(Debug, Clone, Serialize)]
pub struct Crests {
    pub count: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub c_max_m: Option<f64>,
    /// Mean of the highest third, over Hs.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub c_third_over_hs: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steepness_s1: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ursell: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_period_tm01_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub forristall_alpha: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub forristall_beta: Option<f64>,
    pub exceedance: Vec<Exceedance>,
}

/// The wave-by-wave statistics of a field.
#[derive(Debug, Clone, Serialize)]
pub struct WaveStats {
    pub skewness: f64,
    pub kurtosis: f64,
    /// Fraction of samples with η − η̄ > 3σ, and the Gaussian value.
    pub exceed_3sigma: f64,
    pub exceed_3sigma_gaussian: f64,
    /// Σ k²·P(k) over the measured spectrum.
    pub mean_square_slope: f64,
    /// 0.003 + 5.12e-3·U, when U is known.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cox_munk_mss: Option<f64>,
    pub mss_note: &'static str,
    /// Direction of the transects, degrees from +x (modulo 180).
    pub transect_direction_deg: f64,
    pub transects: usize,
    pub waves: WaveHeights,
    pub crests: Crests,
    /// Every wave height and crest over Hs, ascending (the plot's empirical curves).
    #[serde(skip)]
    pub heights_over_hs: Vec<f64>,
    #[serde(skip)]
    pub crests_over_hs: Vec<f64>,
}

/// What `mss_note` says.
pub const MSS_NOTE: &str = "the grid resolves only waves longer than two samples: its mean-square slope is the \
     part of the ocean's below the Nyquist wavenumber (Cox & Munk's includes the capillary waves)";

/// Skewness and kurtosis of `data` about its mean, with σ; (0, 0, 0) for a flat field.
pub fn moments(data: &[f32]) -> (f64, f64, f64) {
    let n = data.len() as f64;
    let mean = data.iter().map(|&v| f64::from(v)).sum::<f64>() / n;
    let (mut m2, mut m3, mut m4) = (0.0, 0.0, 0.0);
    for &v in data {
        let d = f64::from(v) - mean;
        let d2 = d * d;
        m2 += d2;
        m3 += d2 * d;
        m4 += d2 * d2;
    }
    let (m2, m3, m4) = (m2 / n, m3 / n, m4 / n);
    if m2 <= 0.0 {
        return (0.0, 0.0, 0.0);
    }
    (m3 / m2.powf(1.5), m4 / (m2 * m2), m2.sqrt())
}

/// Cox & Munk's (1954) clean-surface mean-square slope at wind speed `u_mps`.
pub fn cox_munk_mss(u_mps: f64) -> f64 {
    0.003 + 5.12e-3 * u_mps
}

/// Forristall's (2000) short-crested α and β for steepness `s1` and Ursell number `ur`.
pub fn forristall_params(s1: f64, ur: f64) -> (f64, f64) {
    (
        0.3536 + 0.2568 * s1 + 0.0800 * ur,
        2.0 - 1.7912 * s1 - 0.5302 * ur + 0.2824 * ur * ur,
    )
}

/// Heights and crests of one transect `line` (η − η̄), appended to `heights`, `crests`.
pub fn zero_crossings(line: &[f64], heights: &mut Vec<f64>, crests: &mut Vec<f64>) {
    // Up-crossings: line[i] < 0 ≤ line[i+1]; down-crossings: line[i] ≥ 0 > line[i+1].
    let mut last_up: Option<usize> = None;
    let (mut hi, mut lo) = (f64::NEG_INFINITY, f64::INFINITY);
    let mut crest = f64::NEG_INFINITY;
    let mut in_crest = false;
    for i in 0..line.len().saturating_sub(1) {
        let (a, b) = (line[i], line[i + 1]);
        if last_up.is_some() {
            hi = hi.max(a);
            lo = lo.min(a);
            if in_crest {
                crest = crest.max(a);
            }
        }
        if a < 0.0 && b >= 0.0 {
            if last_up.is_some() {
                heights.push(hi - lo);
            }
            last_up = Some(i);
            (hi, lo) = (f64::NEG_INFINITY, f64::INFINITY);
            in_crest = true;
            crest = f64::NEG_INFINITY;
        } else if a >= 0.0 && b < 0.0 && in_crest {
            crests.push(crest.max(a));
            in_crest = false;
        }
    }
}

/// The transects of `grid` along `theta` (radians from +x): lines one step apart across
/// the grid, sampled every step `ds` = min(dx, dy) by bilinear interpolation, η − `mean`.
pub fn transects(grid: &Grid, theta: f64, mean: f64) -> Vec<Vec<f64>> {
    let spec = grid.spec;
    let (dx, dy) = (spec.dx_m(), spec.dy_m());
    let ds = dx.min(dy);
    let (xmax, ymax) = (
        (spec.nx.max(1) - 1) as f64 * dx,
        (spec.ny.max(1) - 1) as f64 * dy,
    );
    let (u, v) = (theta.cos(), theta.sin());
    // Normal n = (−v, u); offsets o of the lines span the projections of the corners.
    let corners = [(0.0, 0.0), (xmax, 0.0), (0.0, ymax), (xmax, ymax)];
    let proj = |(x, y): (f64, f64)| -v * x + u * y;
    let omin = corners
        .iter()
        .map(|&c| proj(c))
        .fold(f64::INFINITY, f64::min);
    let omax = corners
        .iter()
        .map(|&c| proj(c))
        .fold(f64::NEG_INFINITY, f64::max);
    let (cx, cy) = (0.5 * xmax, 0.5 * ymax);
    let o_center = proj((cx, cy));
    // At most 2·max(nx, ny) lines and samples per line: a grid of very unequal spacings
    // (1e-7 m by 1e8 m) would otherwise ask for 1e15 of them.
    let cap = 2.0 * spec.nx.max(spec.ny) as f64;
    let line_step = ds.max((omax - omin) / cap);
    let lines = ((omax - omin) / line_step).floor() as i64;
    let mut out = Vec::new();
    for l in 0..=lines {
        let o = omin + l as f64 * line_step - o_center;
        // Points p(s) = c + o·n + s·(u, v); the s interval inside the rectangle.
        let (px, py) = (cx - v * o, cy + u * o);
        let (mut s0, mut s1) = (f64::NEG_INFINITY, f64::INFINITY);
        for (p, d, hi) in [(px, u, xmax), (py, v, ymax)] {
            if d.abs() < 1e-12 {
                if p < -1e-9 || p > hi + 1e-9 {
                    s0 = f64::INFINITY;
                }
                continue;
            }
            let (a, b) = ((0.0 - p) / d, (hi - p) / d);
            s0 = s0.max(a.min(b));
            s1 = s1.min(a.max(b));
        }
        let step = ds.max((s1 - s0) / cap);
        if s1 - s0 < 2.0 * step {
            continue;
        }
        let count = ((s1 - s0) / step).floor() as usize + 1;
        let line: Vec<f64> = (0..count)
            .map(|i| {
                let s = s0 + i as f64 * step;
                bilinear(grid, px + s * u, py + s * v) - mean
            })
            .collect();
        out.push(line);
    }
    out
}

/// The grid's height at (x, y) m, bilinear, (x, y) inside [0, xmax] × [0, ymax].
fn bilinear(grid: &Grid, x: f64, y: f64) -> f64 {
    let spec = grid.spec;
    let fx = (x / spec.dx_m()).clamp(0.0, (spec.nx - 1) as f64);
    let fy = (y / spec.dy_m()).clamp(0.0, (spec.ny - 1) as f64);
    let (i, j) = (fx.floor() as usize, fy.floor() as usize);
    let (i1, j1) = ((i + 1).min(spec.nx - 1), (j + 1).min(spec.ny - 1));
    let (tx, ty) = (fx - i as f64, fy - j as f64);
    let g = |i: usize, j: usize| f64::from(grid.get(i, j));
    let a = g(i, j) * (1.0 - tx) + g(i1, j) * tx;
    let b = g(i, j1) * (1.0 - tx) + g(i1, j1) * tx;
    a * (1.0 - ty) + b * ty
}

/// Fraction of `values` above `level`.
fn fraction_above(sorted: &[f64], level: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    let below = sorted.partition_point(|&v| v <= level);
    (sorted.len() - below) as f64 / sorted.len() as f64
}

/// Mean of the highest third of sorted (ascending) values.
fn top_third(sorted: &[f64]) -> Option<f64> {
    let n = sorted.len() / 3;
    let m = sorted[sorted.len() - n..].iter().sum::<f64>() / n.max(1) as f64;
    (n > 0 && m.is_finite()).then_some(m)
}

/// Tm01 = m0/m1 of the frequency spectrum of the measured radial spectrum, s.
fn mean_period(a: &Analysis, dispersion: Dispersion) -> Option<f64> {
    let (mut m0, mut m1) = (0.0, 0.0);
    for b in &a.radial_spectrum {
        let f = dispersion.omega(b.k_rad_per_m) / (2.0 * std::f64::consts::PI);
        m0 += b.power_m2;
        m1 += b.power_m2 * f;
    }
    (m1 > 0.0).then(|| m0 / m1)
}

/// The wave-by-wave statistics of `grid`, whose spectrum `analysis` measured.
pub fn wave_statistics(grid: &Grid, analysis: &Analysis, sea: &SeaContext) -> WaveStats {
    let (skewness, kurtosis, sigma) = moments(&grid.data);
    let mean = analysis.mean_m;
    let above = grid
        .data
        .iter()
        .filter(|&&v| f64::from(v) - mean > 3.0 * sigma)
        .count();
    let exceed_3sigma = above as f64 / grid.data.len().max(1) as f64;
    let mean_square_slope: f64 = analysis
        .radial_spectrum
        .iter()
        .map(|b| b.k_rad_per_m * b.k_rad_per_m * b.power_m2)
        .sum();
    let theta_deg = analysis.peak_direction_deg.unwrap_or(0.0);
    let lines = transects(grid, theta_deg.to_radians(), mean);
    let (mut heights, mut crests) = (Vec::new(), Vec::new());
    for l in &lines {
        zero_crossings(l, &mut heights, &mut crests);
    }
    // Sums of extreme heights can overflow; only finite values are counted.
    heights.retain(|v| v.is_finite());
    crests.retain(|v| v.is_finite());
    heights.sort_by(f64::total_cmp);
    crests.sort_by(f64::total_cmp);
    let hs = 4.0 * sigma;
    let dispersion = Dispersion::for_depth(sea.depth_m);
    let tm01 = mean_period(analysis, dispersion);
    let s1 = tm01.map(|t| 2.0 * std::f64::consts::PI * hs / (G * t * t));
    let ur = match (sea.depth_m, tm01) {
        (Some(d), Some(t)) if d.is_finite() => {
            let k1 = dispersion.wavenumber(2.0 * std::f64::consts::PI / t);
            Some(hs / (k1 * k1 * d * d * d))
        }
        (_, Some(_)) => Some(0.0),
        _ => None,
    };
    let fp = s1.zip(ur).map(|(s, u)| forristall_params(s, u));
    let table = |sorted: &[f64], rayleigh_coef: f64, forristall: bool| -> Vec<Exceedance> {
        LEVELS
            .iter()
            .map(|&x| Exceedance {
                level_hs: x,
                measured: fraction_above(sorted, x * hs),
                rayleigh: (-rayleigh_coef * x * x).exp(),
                forristall: if forristall {
                    fp.map(|(a, b)| (-(x / a).powf(b)).exp())
                } else {
                    None
                },
            })
            .collect()
    };
    let per_hs = |v: Option<f64>| v.filter(|_| hs > 0.0).map(|v| v / hs);
    let scaled = |v: &[f64]| -> Vec<f64> {
        if hs > 0.0 {
            v.iter().map(|x| x / hs).collect()
        } else {
            Vec::new()
        }
    };
    WaveStats {
        skewness,
        kurtosis,
        exceed_3sigma,
        exceed_3sigma_gaussian: GAUSSIAN_P_3SIGMA,
        mean_square_slope,
        cox_munk_mss: sea.wind_speed_mps.map(cox_munk_mss),
        mss_note: MSS_NOTE,
        transect_direction_deg: theta_deg,
        transects: lines.len(),
        waves: WaveHeights {
            count: heights.len(),
            h_third_m: top_third(&heights),
            h_max_m: heights.last().copied(),
            h_third_over_hs: per_hs(top_third(&heights)),
            exceedance: table(&heights, 2.0, false),
        },
        crests: Crests {
            count: crests.len(),
            c_max_m: crests.last().copied(),
            c_third_over_hs: per_hs(top_third(&crests)),
            steepness_s1: s1,
            ursell: ur,
            mean_period_tm01_s: tm01,
            forristall_alpha: fp.map(|p| p.0),
            forristall_beta: fp.map(|p| p.1),
            exceedance: table(&crests, 8.0, true),
        },
        heights_over_hs: scaled(&heights),
        crests_over_hs: scaled(&crests),
    }
}

#[cfg(test)]
mod tests;
