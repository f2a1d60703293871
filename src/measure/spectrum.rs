//! The measured wavenumber spectrum and statistics of a height field, compared with a
//! target spectrum when one is given (`seasynth analyze` and the trochoid fit use it).
//!
//! Conventions, stated once:
//! - **Input.** A one-channel 32-bit float TIFF in meters, or a 16-bit grayscale PNG with
//!   its sidecar `NAME.json` (same folder and stem) whose `mapping` {min_m, max_m} turns
//!   values into meters: h = min_m + v·(max_m − min_m)/65535. The kind of file is told by
//!   its first bytes, not its extension. The spacing (dx_m, dy_m) comes from the
//!   sidecar's `grid` object when there is one, else 1 m per sample is assumed (and the
//!   output says which: `spacing_source`).
//! - **Axes.** Image row j is y = j·dy, column i is x = i·dx (as every output writes).
//!   Wavevectors are k = 2π·(n/Lx, m/Ly) with Lx = nx·dx, Ly = ny·dy; directions are
//!   measured from +x toward +y, like the wind direction.
//! - **Discrete power.** Ĥ(k) = Σ_x (h(x) − mean)·e^{−ik·x} (forward FFT, unnormalized);
//!   the power of wavevector k is |Ĥ(k)|²/(nx·ny)², so the powers over the whole k plane
//!   sum to the variance of the field (Parseval). A field synthesized as
//!   h = Σ_k h̃(k)·e^{ik·x} has power |h̃(k)|² at k.
//! - **Radial bins.** Width Δk = 2π/max(Lx, Ly); bin b collects the wavevectors with
//!   (b − ½)·Δk ≤ |k| < (b + ½)·Δk and is reported at its center k = b·Δk. Bin 0 holds
//!   only k = 0 (the removed mean) and is not reported. `power_m2` is the sum of the
//!   discrete powers in the bin (Σ over bins = variance), `s_m2_per_rad_per_m` =
//!   power_m2/Δk the omnidirectional wavenumber spectrum S(k) (∫S dk = variance). Bins
//!   beyond the smaller Nyquist wavenumber are only partly covered by the grid
//!   (`complete` = false); their S(k) falls off because of the grid, not the sea.
//! - **Peak.** The largest bin of S(k) (a sum over a whole annulus, far less noisy than
//!   the largest single wavevector of a random field), refined by a parabola through it
//!   and its two neighbours (at most half a bin): k_peak, `peak_wavelength_m` = 2π/k_peak.
//! - **Direction.** A real field's spectrum is symmetric (k and −k carry the same power),
//!   so a snapshot gives directions only modulo 180°: `peak_direction_deg` ∈ [0, 180) is
//!   the power-weighted axial mean direction (the mean of e^{2iθ}, halved) of the
//!   wavevectors in the peak bin and its two neighbours; `peak_direction_concentration`
//!   is the length of that mean (1: one direction, 0: no preferred axis).
//! - **Target.** When the sidecar's `params` say the field was made by a method whose
//!   wavevector amplitudes follow the spectrum (`fft`, `filtered-noise`), the expected
//!   power at k is E|h̃(k)|² = P(k) + P(−k), P = E|h̃0|² of the model
//!   (`Spectrum::amplitude_variance`), over the wavevectors the synthesis uses (no mean,
//!   no Nyquist row or column). For the hybrid blend only the α = 1 region follows the
//!   spectrum, so there is no target (`"target": null` and a `target_note`).
//! - **Plot.** `--plot FILE.png`: S(k) on log–log axes, 800×500 8-bit RGB: the measured
//!   curve (blue; pale blue beyond the Nyquist circle), the target (red) and the peak
//!   (dashed). Values below the bottom of the axis (8 decades under the top) are drawn on it.

use rayon::prelude::*;
use realfft::RealFftPlanner;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;
use serde::Serialize;

use crate::grid::{Grid, GridSpec, is_resolved, signed_index};
use crate::spectrum::{LineQuery, PairOut, Spectrum};

/// Bins whose target power is at least this fraction of the largest target bin take
/// part in the log-spectrum comparison.
pub const COMPARE_FLOOR: f64 = 1e-3;

/// What `spectrum_normalization` says in the output.
pub const NORMALIZATION: &str = "power_m2 = sum over the bin's wavevectors of |FFT(h - mean)|^2/(nx*ny)^2 \
     (sums to the variance); s_m2_per_rad_per_m = power_m2/dk (integrates to the variance over k); \
     bins of width dk = 2*pi/max(Lx, Ly) centered on k = b*dk";

/// The expected spectrum of a field: the model it was synthesized from.
pub struct Target {
    /// E|h̃0(k)|² per wavevector.
    pub spectrum: Box<dyn Spectrum>,
    /// The grid the field was synthesized on (its wavevectors).
    pub spec: GridSpec,
    /// The synthesis method (`fft`, ...).
    pub method: String,
    /// The spectrum model (`phillips`, ...).
    pub model: String,
}

/// True when two lengths agree to 1e-9 relative.
pub fn same_length(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

/// One radial bin of the spectrum (see the module docs for the normalization).
#[derive(Debug, Clone, Serialize)]
pub struct RadialBin {
    /// Bin center b·Δk, rad/m.
    pub k_rad_per_m: f64,
    /// 2π/k, meters.
    pub wavelength_m: f64,
    /// Wavevectors of the whole k plane in the bin.
    pub cells: u64,
    /// True when the grid covers the whole annulus (it lies inside both Nyquist limits).
    pub complete: bool,
    /// Σ of the discrete power over the bin, m².
    pub power_m2: f64,
    /// power_m2/Δk: the omnidirectional wavenumber spectrum S(k), m²/(rad/m).
    pub s_m2_per_rad_per_m: f64,
    /// Expected power_m2 of the target (only with a target).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target_power_m2: Option<f64>,
    /// Expected S(k) of the target (only with a target).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target_s_m2_per_rad_per_m: Option<f64>,
}

/// The measured spectrum against the target.
#[derive(Debug, Clone, Serialize)]
pub struct TargetSummary {
    pub method: String,
    pub spectrum: String,
    /// sqrt of the expected variance: Σ over the synthesized wavevectors of P(k) + P(−k).
    pub target_std_m: f64,
    /// 4·target_std_m.
    pub target_hs_m: f64,
    /// Peak wavelength of the target's S(k), found as for the measured one.
    pub target_peak_wavelength_m: Option<f64>,
    /// Measured variance / expected variance.
    pub variance_ratio: Option<f64>,
    /// RMS over the compared bins of log10(measured S / target S).
    pub log10_rms_difference: Option<f64>,
    /// Bins compared: target power ≥ `COMPARE_FLOOR` × the largest target bin, measured > 0.
    pub bins_compared: usize,
}

/// Statistics and spectrum of a height field.
#[derive(Debug, Clone, Serialize)]
pub struct Analysis {
    pub nx: usize,
    pub ny: usize,
    pub dx_m: f64,
    pub dy_m: f64,
    pub extent_m: [f64; 2],
    pub min_m: f64,
    pub max_m: f64,
    pub mean_m: f64,
    pub std_m: f64,
    /// 4·std_m.
    pub hs_m: f64,
    /// Wavenumber of the peak of S(k), rad/m (None for a flat field).
    pub peak_k_rad_per_m: Option<f64>,
    pub peak_wavelength_m: Option<f64>,
    /// Axial direction of the peak, degrees in [0, 180), from +x toward +y.
    pub peak_direction_deg: Option<f64>,
    /// Directions are only defined modulo this many degrees (180: k and −k are one).
    pub direction_modulo_deg: f64,
    /// Length of the mean of e^{2iθ} around the peak: 1 = one direction, 0 = none.
    pub peak_direction_concentration: Option<f64>,
    /// Radial bin width Δk, rad/m.
    pub dk_rad_per_m: f64,
    pub spectrum_normalization: &'static str,
    pub target: Option<TargetSummary>,
    /// Why there is no target, when there is none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target_note: Option<String>,
    pub radial_spectrum: Vec<RadialBin>,
}

/// The half plane of the forward spectrum: `nx/2 + 1` lines (kx index n = 0..=nx/2),
/// each holding the `ny` ky bins in FFT order, of Ĥ(k)/(nx·ny).
struct HalfSpectrum {
    ny: usize,
    data: Vec<Complex64>,
}

/// Forward 2D FFT of `grid − mean`, divided by nx·ny: a real-to-complex transform of each
/// row (x), a blocked transpose, then a complex transform of each kx line (y).
fn forward_half_spectrum(grid: &Grid, mean: f64) -> HalfSpectrum {
    let (nx, ny) = (grid.spec.nx, grid.spec.ny);
    let lines = nx / 2 + 1;
    let r2c = RealFftPlanner::<f64>::new().plan_fft_forward(nx);
    let mut rows = vec![Complex64::new(0.0, 0.0); ny * lines];
    let scale = 1.0 / (nx as f64 * ny as f64);
    rows.par_chunks_mut(lines)
        .zip(grid.data.par_chunks(nx))
        .for_each_init(
            || (r2c.make_input_vec(), r2c.make_scratch_vec()),
            |(input, scratch), (out, row)| {
                for (d, &v) in input.iter_mut().zip(row) {
                    *d = (v as f64 - mean) * scale;
                }
                r2c.process_with_scratch(input, out, scratch)
                    .expect("buffer lengths come from the plan");
            },
        );
    const BLOCK: usize = 8;
    let mut data = vec![Complex64::new(0.0, 0.0); lines * ny];
    data.par_chunks_mut(BLOCK * ny)
        .enumerate()
        .for_each(|(c, block)| {
            let n0 = c * BLOCK;
            let nb = block.len() / ny;
            for j in 0..ny {
                let src = &rows[j * lines + n0..j * lines + n0 + nb];
                for (b, v) in src.iter().enumerate() {
                    block[b * ny + j] = *v;
                }
            }
        });
    drop(rows);
    let fft = FftPlanner::<f64>::new().plan_fft_forward(ny);
    let scratch_len = fft.get_inplace_scratch_len();
    data.par_chunks_mut(ny).for_each_init(
        || vec![Complex64::new(0.0, 0.0); scratch_len],
        |scratch, line| fft.process_with_scratch(line, scratch),
    );
    HalfSpectrum { ny, data }
}

/// Lines per unit of parallel work when binning; fixed, so sums do not depend on threads.
const LINES_PER_CHUNK: usize = 16;

#[derive(Clone, Default)]
struct BinAcc {
    power: f64,
    target: f64,
    cells: u64,
}

/// Wavevector geometry of a grid.
struct KGrid {
    nx: usize,
    ny: usize,
    dkx: f64,
    dky: f64,
    dk: f64,
    /// ky of each FFT bin m, rad/m.
    ky: Vec<f64>,
    nbins: usize,
}

/// Radial bins per sample of the longer side, at most (square grids use 0.71).
const MAX_BINS_PER_SAMPLE: usize = 64;

impl KGrid {
    fn new(spec: &GridSpec) -> Self {
        let tau = 2.0 * std::f64::consts::PI;
        let (nx, ny) = (spec.nx, spec.ny);
        let dkx = tau / spec.extent_x_m;
        let dky = tau / spec.extent_y_m;
        let ky: Vec<f64> = (0..ny).map(|m| dky * signed_index(m, ny) as f64).collect();
        let kx_max = dkx * (nx / 2) as f64;
        let ky_max = ky.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
        // Bins of the coarser axis' spacing, but at most MAX_BINS_PER_SAMPLE per sample of
        // the longer side: a grid of very unequal spacings (1e-6 m by 1e9 m) would
        // otherwise ask for 1e15 bins.
        let k_max = kx_max.hypot(ky_max);
        let cap = (MAX_BINS_PER_SAMPLE * nx.max(ny)) as f64;
        let dk = (tau / spec.extent_x_m.max(spec.extent_y_m)).max(k_max / cap);
        let nbins = ((k_max / dk).round() as usize) + 2;
        Self {
            nx,
            ny,
            dkx,
            dky,
            dk,
            ky,
            nbins,
        }
    }

    /// kx of half-plane line n (n = nx/2 is the Nyquist column, taken as +π/dx).
    fn kx(&self, n: usize) -> f64 {
        self.dkx * n as f64
    }

    /// How many wavevectors of the whole plane half-plane line n stands for per cell.
    fn weight(&self, n: usize) -> u64 {
        if n == 0 || (self.nx % 2 == 0 && n == self.nx / 2) {
            1
        } else {
            2
        }
    }

    /// Bin 0 holds k = 0 alone (the mean, left out); every other wavevector is in bin 1
    /// or above, also when the bins are wider than the grid's smallest wavenumber.
    fn bin(&self, kx: f64, ky: f64) -> usize {
        let k = kx.hypot(ky);
        if k == 0.0 {
            return 0;
        }
        ((k / self.dk).round() as usize).clamp(1, self.nbins - 1)
    }
}

/// Power per radial bin (and the target's, if any), summed in a fixed order.
fn radial_sums(half: &HalfSpectrum, kg: &KGrid, target: Option<&Target>) -> Vec<BinAcc> {
    let ny = half.ny;
    let partials: Vec<Vec<BinAcc>> = half
        .data
        .par_chunks(LINES_PER_CHUNK * ny)
        .enumerate()
        .map(|(c, chunk)| {
            let mut acc = vec![BinAcc::default(); kg.nbins];
            let mut pa = vec![0.0; ny];
            let mut pb = vec![0.0; ny];
            for (l, line) in chunk.chunks(ny).enumerate() {
                let n = c * LINES_PER_CHUNK + l;
                let kx = kg.kx(n);
                let w = kg.weight(n);
                if let Some(t) = target {
                    let q = LineQuery {
                        kx,
                        ky: &kg.ky,
                        dkx: kg.dkx,
                        dky: kg.dky,
                    };
                    let out = PairOut {
                        a: &mut pa,
                        b: &mut pb,
                    };
                    t.spectrum.amplitude_variance_pair_line(&q, out);
                }
                for (m, v) in line.iter().enumerate() {
                    if n == 0 && m == 0 {
                        continue;
                    }
                    let b = kg.bin(kx, kg.ky[m]);
                    let a = &mut acc[b];
                    a.power += w as f64 * v.norm_sqr();
                    a.cells += w;
                    if target.is_some() && is_resolved(n as i64, signed_index(m, ny), kg.nx, kg.ny)
                    {
                        a.target += w as f64 * (pa[m] + pb[m]);
                    }
                }
            }
            acc
        })
        .collect();
    let mut total = vec![BinAcc::default(); kg.nbins];
    for p in partials {
        for (t, a) in total.iter_mut().zip(p) {
            t.power += a.power;
            t.target += a.target;
            t.cells += a.cells;
        }
    }
    total
}

/// The power-weighted mean of (cos 2θ, sin 2θ) over the wavevectors in bins `lo..=hi`.
fn axial_mean(half: &HalfSpectrum, kg: &KGrid, lo: usize, hi: usize) -> (f64, f64, f64) {
    let ny = half.ny;
    let partials: Vec<(f64, f64, f64)> = half
        .data
        .par_chunks(LINES_PER_CHUNK * ny)
        .enumerate()
        .map(|(c, chunk)| {
            let mut s = (0.0, 0.0, 0.0);
            for (l, line) in chunk.chunks(ny).enumerate() {
                let n = c * LINES_PER_CHUNK + l;
                let kx = kg.kx(n);
                let w = kg.weight(n) as f64;
                for (m, v) in line.iter().enumerate() {
                    let ky = kg.ky[m];
                    let k2 = kx * kx + ky * ky;
                    if k2 == 0.0 {
                        continue;
                    }
                    let b = kg.bin(kx, ky);
                    if b < lo || b > hi {
                        continue;
                    }
                    let p = w * v.norm_sqr();
                    s.0 += p;
                    s.1 += p * (kx * kx - ky * ky) / k2;
                    s.2 += p * 2.0 * kx * ky / k2;
                }
            }
            s
        })
        .collect();
    partials
        .iter()
        .fold((0.0, 0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1, a.2 + p.2))
}

/// Index of the largest value of `s` among bins 1.., refined by a parabola through it and
/// its neighbours (bins 1.. only), in units of bins. None when every bin is 0.
fn peak_bin(s: &[f64]) -> Option<(usize, f64)> {
    let (b, &top) = s.iter().enumerate().skip(1).fold(
        None,
        |best: Option<(usize, &f64)>, (i, v)| match best {
            Some((_, bv)) if bv >= v => best,
            _ => Some((i, v)),
        },
    )?;
    if top.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let mut pos = b as f64;
    if b >= 2 && b + 1 < s.len() {
        let (l, r) = (s[b - 1], s[b + 1]);
        let den = l - 2.0 * top + r;
        if den < 0.0 {
            pos += (0.5 * (l - r) / den).clamp(-0.5, 0.5);
        }
    }
    Some((b, pos))
}

/// Statistics and the radial spectrum of `heights`, compared with `target` when given
/// (a target on another grid is ignored with a note).
pub fn analyze(heights: &Grid, target: Option<&Target>) -> Analysis {
    let spec = heights.spec;
    let stats = heights.stats();
    let mut target_note = None;
    let target = target.filter(|t| {
        let fits = t.spec.nx == spec.nx
            && t.spec.ny == spec.ny
            && same_length(t.spec.extent_x_m, spec.extent_x_m)
            && same_length(t.spec.extent_y_m, spec.extent_y_m);
        if !fits {
            target_note = Some("the target spectrum belongs to another grid; no target".into());
        }
        fits
    });
    let kg = KGrid::new(&spec);
    let half = forward_half_spectrum(heights, stats.mean_m);
    let sums = radial_sums(&half, &kg, target);
    let last = sums
        .iter()
        .rposition(|a| a.cells > 0)
        .unwrap_or(0)
        .max(1)
        .min(sums.len() - 1);
    let sums = &sums[..=last];
    let s: Vec<f64> = sums.iter().map(|a| a.power / kg.dk).collect();
    let tau = 2.0 * std::f64::consts::PI;
    let k_nyquist = (std::f64::consts::PI / spec.dx_m()).min(std::f64::consts::PI / spec.dy_m());
    let radial_spectrum = sums
        .iter()
        .enumerate()
        .skip(1)
        .map(|(b, a)| {
            let k = b as f64 * kg.dk;
            RadialBin {
                k_rad_per_m: k,
                wavelength_m: tau / k,
                cells: a.cells,
                complete: (b as f64 + 0.5) * kg.dk <= k_nyquist * (1.0 + 1e-12),
                power_m2: a.power,
                s_m2_per_rad_per_m: a.power / kg.dk,
                target_power_m2: target.map(|_| a.target),
                target_s_m2_per_rad_per_m: target.map(|_| a.target / kg.dk),
            }
        })
        .collect();

    let peak = peak_bin(&s);
    let (peak_k, peak_dir, peak_conc) = match peak {
        Some((b, pos)) => {
            let (w, c, si) = axial_mean(&half, &kg, b.saturating_sub(1).max(1), b + 1);
            let (dir, conc) = if w > 0.0 {
                let deg = (0.5 * si.atan2(c).to_degrees()).rem_euclid(180.0);
                // rem_euclid can round up to exactly 180.
                (
                    Some(if deg >= 180.0 { 0.0 } else { deg }),
                    Some(c.hypot(si) / w),
                )
            } else {
                (None, None)
            };
            (Some(pos * kg.dk), dir, conc)
        }
        None => (None, None, None),
    };

    let target_summary = target.map(|t| {
        let expected: f64 = sums.iter().map(|a| a.target).sum();
        let ts: Vec<f64> = sums.iter().map(|a| a.target / kg.dk).collect();
        let floor = COMPARE_FLOOR * ts.iter().skip(1).fold(0.0f64, |a, &v| a.max(v));
        let diffs: Vec<f64> = s
            .iter()
            .zip(&ts)
            .skip(1)
            .filter(|&(&m, &t)| t > 0.0 && t >= floor && m > 0.0)
            .map(|(&m, &t)| (m / t).log10())
            .collect();
        let var = stats.std_m * stats.std_m;
        TargetSummary {
            method: t.method.clone(),
            spectrum: t.model.clone(),
            target_std_m: expected.sqrt(),
            target_hs_m: 4.0 * expected.sqrt(),
            target_peak_wavelength_m: peak_bin(&ts).map(|(_, pos)| tau / (pos * kg.dk)),
            variance_ratio: (expected > 0.0).then(|| var / expected),
            log10_rms_difference: (!diffs.is_empty())
                .then(|| (diffs.iter().map(|d| d * d).sum::<f64>() / diffs.len() as f64).sqrt()),
            bins_compared: diffs.len(),
        }
    });

    Analysis {
        nx: spec.nx,
        ny: spec.ny,
        dx_m: spec.dx_m(),
        dy_m: spec.dy_m(),
        extent_m: [spec.extent_x_m, spec.extent_y_m],
        min_m: stats.min_m,
        max_m: stats.max_m,
        mean_m: stats.mean_m,
        std_m: stats.std_m,
        hs_m: stats.hs_m,
        peak_k_rad_per_m: peak_k,
        peak_wavelength_m: peak_k.map(|k| tau / k),
        peak_direction_deg: peak_dir,
        direction_modulo_deg: 180.0,
        peak_direction_concentration: peak_conc,
        dk_rad_per_m: kg.dk,
        spectrum_normalization: NORMALIZATION,
        target: target_summary,
        target_note,
        radial_spectrum,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Relative tolerance of sums that should agree up to f64 rounding.
    const PARSEVAL_REL_TOL: f64 = 1e-9;

    pub(crate) fn cosine(n: usize, extent: f64, wavelength: f64, dir_deg: f64, amp: f64) -> Grid {
        let spec = GridSpec::new(n, n, extent, extent);
        let k = 2.0 * std::f64::consts::PI / wavelength;
        let (kx, ky) = (
            k * dir_deg.to_radians().cos(),
            k * dir_deg.to_radians().sin(),
        );
        let mut data = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                data.push((amp * (kx * spec.x_m(i) + ky * spec.y_m(j)).cos()) as f32);
            }
        }
        Grid::new(spec, data)
    }

    #[test]
    fn radial_powers_sum_to_the_variance_on_odd_and_even_grids() {
        for (nx, ny) in [(64, 64), (33, 20), (17, 48)] {
            let spec = GridSpec::new(nx, ny, nx as f64 * 0.7, ny as f64 * 1.3);
            let data = (0..nx * ny)
                .map(|v| (v as f32 * 0.37).sin() + (v as f32 * 0.011).cos() * 2.0)
                .collect();
            let g = Grid::new(spec, data);
            let a = analyze(&g, None);
            let total: f64 = a.radial_spectrum.iter().map(|b| b.power_m2).sum();
            let var = a.std_m * a.std_m;
            assert!(
                (total - var).abs() <= PARSEVAL_REL_TOL * var,
                "{nx}×{ny}: Σ power {total} vs variance {var}"
            );
            let cells: u64 = a.radial_spectrum.iter().map(|b| b.cells).sum();
            assert_eq!(
                cells as usize,
                nx * ny - 1,
                "every wavevector but k = 0 binned"
            );
        }
    }

    #[test]
    fn a_cosine_on_a_bin_has_its_wavelength_and_axis() {
        // 64 m along 0°, on a 256 m grid: exactly bin 4, no leakage.
        let a = analyze(&cosine(128, 256.0, 64.0, 0.0, 1.5), None);
        assert!((a.peak_wavelength_m.unwrap() - 64.0).abs() < 1e-9, "{a:?}");
        assert!(a.peak_direction_deg.unwrap().abs() < 1e-6);
        assert!((a.peak_direction_concentration.unwrap() - 1.0).abs() < 1e-9);
        assert!((a.std_m - 1.5 / 2f64.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn a_cosine_toward_120_degrees_reports_120_modulo_180() {
        // Wavevector (−4, 4·√3)·Δk is not on the grid; the axis still comes out.
        let a = analyze(&cosine(256, 256.0, 32.0, 120.0, 1.0), None);
        let d = a.peak_direction_deg.unwrap();
        assert!((d - 120.0).abs() < 5.0, "direction {d}");
        let b = analyze(&cosine(256, 256.0, 32.0, 300.0, 1.0), None);
        let d2 = b.peak_direction_deg.unwrap();
        assert!(
            (d2 - 120.0).abs() < 5.0,
            "300° is 120° modulo 180°, got {d2}"
        );
    }

    #[test]
    fn a_flat_field_has_no_peak_and_no_direction() {
        let g = Grid::new(GridSpec::new(8, 8, 8.0, 8.0), vec![0.25; 64]);
        let a = analyze(&g, None);
        assert_eq!(a.peak_wavelength_m, None);
        assert_eq!(a.peak_direction_deg, None);
        assert_eq!(a.std_m, 0.0);
        assert!(serde_json::to_string(&a).is_ok());
    }

    #[test]
    fn tiny_and_one_dimensional_grids_are_analyzed_without_panicking() {
        for (nx, ny) in [(1, 1), (1, 5), (5, 1), (2, 2), (3, 1)] {
            let data = (0..nx * ny).map(|v| v as f32).collect();
            let g = Grid::new(GridSpec::new(nx, ny, nx as f64, ny as f64), data);
            let a = analyze(&g, None);
            let total: f64 = a.radial_spectrum.iter().map(|b| b.power_m2).sum();
            let var = a.std_m * a.std_m;
            assert!(
                (total - var).abs() <= PARSEVAL_REL_TOL * var.max(1e-300),
                "{nx}×{ny}"
            );
            assert!(serde_json::to_string(&a).is_ok());
        }
    }

    #[test]
    fn very_unequal_spacings_get_a_bounded_number_of_bins_and_keep_parseval() {
        // Found by fuzzing: 1e-6 m by 1e9 m asked for about 1e15 radial bins.
        let (nx, ny) = (8, 6);
        let data = (0..nx * ny).map(|v| ((v * 7) % 5) as f32).collect();
        let g = Grid::new(
            GridSpec::new(nx, ny, 1e-6 * nx as f64, 1e9 * ny as f64),
            data,
        );
        let a = analyze(&g, None);
        assert!(
            a.radial_spectrum.len() <= MAX_BINS_PER_SAMPLE * nx + 2,
            "{} bins",
            a.radial_spectrum.len()
        );
        let total: f64 = a.radial_spectrum.iter().map(|b| b.power_m2).sum();
        let var = a.std_m * a.std_m;
        assert!(
            (total - var).abs() <= PARSEVAL_REL_TOL * var,
            "{total} vs {var}"
        );
    }

    #[test]
    fn the_peak_parabola_stays_within_half_a_bin() {
        assert_eq!(peak_bin(&[0.0, 0.0, 1.0, 0.0]).unwrap(), (2, 2.0));
        let (b, pos) = peak_bin(&[0.0, 1.0, 3.0, 2.9, 0.0]).unwrap();
        assert_eq!(b, 2);
        assert!(pos > 2.0 && pos <= 2.5, "{pos}");
        assert_eq!(peak_bin(&[0.0, 0.0, 0.0]), None);
    }

    /// The `swell` preset is long-crested: the wavevectors around its peak share one axis
    /// (the second circular moment |E e^{2iθ}| near 1), more so than with the swell
    /// term at ξ = 1.
    #[test]
    fn the_swell_preset_is_long_crested() {
        const LONG_CRESTED: f64 = 0.95;
        let concentration = |xi: Option<f64>| {
            let mut p = crate::config::Params::preset("swell").unwrap();
            p.grid.size = crate::config::Size2([256, 256]);
            if let Some(xi) = xi {
                p.spectrum.swell = xi;
            }
            let s = crate::field::synthesize(&p).unwrap();
            analyze(&s.grid, None).peak_direction_concentration.unwrap()
        };
        let (now, before) = (concentration(None), concentration(Some(1.0)));
        eprintln!("second circular moment at the peak: {now:.4} (ξ = 1: {before:.4})");
        assert!(now > LONG_CRESTED, "{now}");
        assert!(now > before);
    }
}
