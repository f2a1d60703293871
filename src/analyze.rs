//! `seasynth analyze`: statistics and the measured wavenumber spectrum of a height map,
//! compared with the spectrum it was generated from when its sidecar says so.
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

use std::io::Read;
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use realfft::RealFftPlanner;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;
use serde::Serialize;
use serde_json::Value;

use crate::config::Params;
use crate::error::Error;
use crate::export::rgb8::draw_err;
use crate::export::{HeightMapping, Staged};
use crate::field::fft::{is_resolved, signed_index};
use crate::grid::{Grid, GridSpec};
use crate::spectrum::Spectrum;

/// Command-line arguments of `seasynth analyze`.
#[derive(Debug, clap::Args)]
pub struct AnalyzeArgs {
    /// Height map: a float TIFF in meters, or a 16-bit PNG with its sidecar NAME.json
    pub file: PathBuf,
    /// Print one JSON object on stdout instead of the report
    #[arg(long)]
    pub json: bool,
    /// Write a log-log plot of the measured (and target) radial spectrum S(k), 800×500 PNG
    #[arg(long, value_name = "PNG")]
    pub plot: Option<PathBuf>,
}

/// The methods whose wavevector amplitudes follow the spectrum model, so the measured
/// spectrum can be compared with it.
pub const COMPARABLE_METHODS: &[&str] = &["fft", "filtered-noise"];

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

impl Target {
    /// The target described by a sidecar's `params`, for a field on `spec`; `Err` says
    /// in one sentence why there is none.
    pub fn from_sidecar(sidecar: &Value, spec: &GridSpec) -> Result<Target, String> {
        let raw = sidecar
            .get("params")
            .ok_or("the sidecar has no `params`, so there is no target spectrum")?;
        let params: Params = serde_json::from_value(raw.clone())
            .map_err(|e| format!("the sidecar's `params` do not parse ({e}); no target"))?;
        let method = params.method.name().to_string();
        if !COMPARABLE_METHODS.contains(&method.as_str()) {
            return Err(match method.as_str() {
                "hybrid" => "method hybrid: only the alpha = 1 region follows the spectrum, \
                             so the whole field has no target spectrum"
                    .to_string(),
                m => format!(
                    "method {m} does not follow a spectrum model; targets exist for {}",
                    COMPARABLE_METHODS.join(", ")
                ),
            });
        }
        params
            .validate()
            .map_err(|e| format!("the sidecar's `params` are not valid ({e}); no target"))?;
        let pspec = params.grid_spec();
        if (pspec.nx, pspec.ny) != (spec.nx, spec.ny) {
            return Err(format!(
                "the sidecar's `params` describe a {}×{} grid but the image is {}×{}; no target",
                pspec.nx, pspec.ny, spec.nx, spec.ny
            ));
        }
        if !same_length(pspec.extent_x_m, spec.extent_x_m)
            || !same_length(pspec.extent_y_m, spec.extent_y_m)
        {
            return Err(format!(
                "the sidecar's `params` describe a {} m × {} m extent but the spacing gives {} m × {} m; no target",
                pspec.extent_x_m, pspec.extent_y_m, spec.extent_x_m, spec.extent_y_m
            ));
        }
        let model = serde_json::to_value(params.spectrum.model)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_else(|| "?".into());
        let (spectrum, _dispersion) = crate::field::spectrum_model(&params)
            .map_err(|e| format!("the sidecar's spectrum cannot be built ({e}); no target"))?;
        Ok(Target {
            spectrum,
            spec: pspec,
            method,
            model,
        })
    }
}

fn same_length(a: f64, b: f64) -> bool {
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
                    t.spectrum
                        .amplitude_variance_pair_line(kx, &kg.ky, kg.dkx, kg.dky, &mut pa, &mut pb);
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

fn input_error(path: &Path, message: impl std::fmt::Display) -> Error {
    // One line, whatever a decoder says.
    let message = message.to_string().replace(['\n', '\r'], " ");
    Error::Input {
        path: path.to_path_buf(),
        message,
    }
}

/// The kind of image at `path`, by its first bytes.
fn sniff(path: &Path) -> Result<ImageKind, Error> {
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
    if head.starts_with(b"\x89PNG\r\n\x1a\n") {
        Ok(ImageKind::Png16)
    } else if head.starts_with(b"II*\0")
        || head.starts_with(b"MM\0*")
        || head.starts_with(b"II+\0")
        || head.starts_with(b"MM\0+")
    {
        Ok(ImageKind::TiffF32)
    } else {
        Err(input_error(
            path,
            "is not a PNG or TIFF image (expected a 32-bit float TIFF in meters or a 16-bit PNG with its sidecar)",
        ))
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
    let kind = sniff(path)?;
    let sidecar = read_sidecar(path)?;
    let (nx, ny, data, step) = match kind {
        ImageKind::TiffF32 => {
            let (w, h, v) = crate::export::tiff32::read(path).map_err(|e| {
                input_error(
                    path,
                    format!("not a readable one-channel 32-bit float TIFF: {e}"),
                )
            })?;
            if v.len() != w * h {
                return Err(input_error(
                    path,
                    format!(
                        "expected one channel of 32-bit float samples, found {} values for {w}×{h} pixels",
                        v.len()
                    ),
                ));
            }
            (w, h, v, None)
        }
        ImageKind::Png16 => {
            let (w, h, v) = crate::export::png16::read(path).map_err(|e| {
                input_error(path, format!("not a readable 16-bit grayscale PNG: {e}"))
            })?;
            let Some((side, doc)) = &sidecar else {
                let want = crate::export::sidecar::path_for(path);
                return Err(input_error(
                    path,
                    format!(
                        "has no sidecar {}: the PNG's heights cannot be converted to meters (analyze the .tif, or keep the .json beside the PNG)",
                        want.file_name()
                            .map(|n| n.to_string_lossy())
                            .unwrap_or_default()
                    ),
                ));
            };
            let mapping = doc.get("mapping").and_then(|m| {
                let lo = m.get("min_m")?.as_f64()?;
                let hi = m.get("max_m")?.as_f64()?;
                Some(HeightMapping {
                    min_m: lo,
                    max_m: hi,
                })
            });
            let Some(mapping) = mapping.filter(|m| m.min_m.is_finite() && m.max_m.is_finite())
            else {
                return Err(input_error(
                    side,
                    "sidecar has no `mapping` {min_m, max_m}: the PNG's heights cannot be converted to meters",
                ));
            };
            let heights = v.iter().map(|&x| mapping.decode(x) as f32).collect();
            (w, h, heights, Some(mapping.step_m()))
        }
    };
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
        kind,
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

/// What `analyze --json` prints: the file, then the [`Analysis`].
#[derive(Serialize)]
struct Report<'a> {
    file: String,
    format: ImageKind,
    spacing_source: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    quantization_step_m: Option<f64>,
    #[serde(flatten)]
    analysis: &'a Analysis,
}

/// Runs `seasynth analyze`.
pub fn run(args: AnalyzeArgs) -> anyhow::Result<()> {
    // The plot file is staged before any work: a bad path fails now, and an error later
    // leaves no partial file.
    let plot = args
        .plot
        .as_deref()
        .map(|p| stage_plot(p, &args.file))
        .transpose()?;
    let loaded = load_detailed(&args.file)?;
    let (target, note) = match &loaded.sidecar {
        Some(doc) => match Target::from_sidecar(doc, &loaded.grid.spec) {
            Ok(t) => (Some(t), None),
            Err(note) => (None, Some(note)),
        },
        None => (
            None,
            Some("no sidecar, so there is no target spectrum".to_string()),
        ),
    };
    let mut analysis = analyze(&loaded.grid, target.as_ref());
    if analysis.target_note.is_none() {
        analysis.target_note = note;
    }
    let report = Report {
        file: args.file.display().to_string(),
        format: loaded.kind,
        spacing_source: loaded.spacing_source,
        quantization_step_m: loaded.quantization_step_m,
        analysis: &analysis,
    };
    if let Some(staged) = plot {
        let name = args
            .file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| report.file.clone());
        let image = render_plot(&analysis, &name).map_err(|e| Error::io(&staged.path, e))?;
        crate::export::rgb8::write(staged, &image, PLOT_SIZE)?;
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        serde_json::to_writer(&mut out, &report)?;
        std::io::Write::write_all(&mut out, b"\n")?;
    } else {
        std::io::Write::write_all(&mut out, human_report(&report).as_bytes())?;
    }
    Ok(())
}

/// Size of the `--plot` image, pixels.
pub const PLOT_SIZE: (u32, u32) = (800, 500);
/// Decades of S(k) shown below the highest value.
const PLOT_DECADES: f64 = 8.0;
/// Font of every text in the plot.
const FONT: &str = "sans-serif";

/// Checks a plot path (a `.png`, not the analyzed file) and stages it.
fn stage_plot(path: &Path, input: &Path) -> Result<Staged, Error> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if ext.as_deref() != Some("png") {
        return Err(Error::Output {
            path: path.to_path_buf(),
            message: "plots are PNG images: the file name must end in .png".into(),
        });
    }
    let same = match (std::fs::canonicalize(path), std::fs::canonicalize(input)) {
        (Ok(a), Ok(b)) => a == b,
        _ => path == input,
    };
    if same {
        return Err(Error::Output {
            path: path.to_path_buf(),
            message: "is the file being analyzed".into(),
        });
    }
    Staged::create(path)
}

/// A number with 3 significant digits and no trailing zeros (`0.0123`, `45.6`, `1e-5`).
fn short_number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let mag = v.abs().log10().floor();
    if !(-3.0..5.0).contains(&mag) {
        return format!("{v:.0e}");
    }
    let decimals = (2.0 - mag).max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Draws the measured (and target) S(k) of `a` on log–log axes into an RGB buffer of
/// [`PLOT_SIZE`]; `name` heads the title.
pub fn render_plot(a: &Analysis, name: &str) -> std::io::Result<Vec<u8>> {
    use plotters::prelude::*;

    let (w, h) = PLOT_SIZE;
    let mut buf = vec![0u8; (w * h * 3) as usize];
    let bins = &a.radial_spectrum;
    let highest = bins
        .iter()
        .flat_map(|b| {
            [
                b.s_m2_per_rad_per_m,
                b.target_s_m2_per_rad_per_m.unwrap_or(0.0),
            ]
        })
        .fold(0.0f64, f64::max);
    let lowest = bins
        .iter()
        .flat_map(|b| {
            [
                b.s_m2_per_rad_per_m,
                b.target_s_m2_per_rad_per_m.unwrap_or(0.0),
            ]
        })
        .filter(|&v| v > 0.0)
        .fold(f64::INFINITY, f64::min);
    let (y_lo, y_hi) = if highest > 0.0 {
        let hi = 10f64.powf((highest * 2.0).log10().ceil());
        let lo = 10f64
            .powf(lowest.log10().floor())
            .max(hi * 10f64.powf(-PLOT_DECADES));
        (lo, hi)
    } else {
        (1e-6, 1.0)
    };
    let k_lo = bins.first().map_or(a.dk_rad_per_m, |b| b.k_rad_per_m) / 1.1;
    let k_hi = bins.last().map_or(10.0 * a.dk_rad_per_m, |b| b.k_rad_per_m) * 1.1;
    let k_hi = k_hi.max(k_lo * 10.0);
    let clamp = |v: f64| v.clamp(y_lo, y_hi);
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (head, body) = root.split_vertically(62);
        head.draw(&Text::new(
            format!("{name}: radial wavenumber spectrum S(k)"),
            (12, 8),
            (FONT, 22).into_font().style(FontStyle::Bold),
        ))
        .map_err(draw_err)?;
        let mut sub = format!(
            "{}×{} over {}×{} m  ·  Hs {} m",
            a.nx,
            a.ny,
            short_number(a.extent_m[0]),
            short_number(a.extent_m[1]),
            short_number(a.hs_m)
        );
        if let Some(t) = &a.target {
            sub += &format!(
                "  ·  target Hs {} m, variance ratio {}",
                short_number(t.target_hs_m),
                t.variance_ratio.map_or("-".into(), |r| format!("{r:.3}"))
            );
        }
        head.draw(&Text::new(sub, (12, 36), (FONT, 16)))
            .map_err(draw_err)?;
        let mut chart = ChartBuilder::on(&body)
            .margin_left(10)
            .margin_right(25)
            .margin_top(8)
            .margin_bottom(8)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d((k_lo..k_hi).log_scale(), (y_lo..y_hi).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("wavenumber k (rad/m)")
            .y_desc("S(k) (m²/(rad/m))")
            .x_label_formatter(&|v| short_number(*v))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .axis_desc_style((FONT, 17))
            .label_style((FONT, 14))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(205, 205, 205))
            .draw()
            .map_err(draw_err)?;
        let blue = RGBColor(30, 90, 200);
        let pale = RGBColor(150, 180, 230);
        let red = RGBColor(200, 30, 30);
        let gray = RGBColor(90, 90, 90);
        let complete: Vec<(f64, f64)> = bins
            .iter()
            .filter(|b| b.complete)
            .map(|b| (b.k_rad_per_m, clamp(b.s_m2_per_rad_per_m)))
            .collect();
        // Bins beyond the Nyquist circle start from the last complete one.
        let partial: Vec<(f64, f64)> = bins
            .iter()
            .enumerate()
            .filter(|(i, b)| !b.complete || bins.get(i + 1).is_some_and(|n| !n.complete))
            .map(|(_, b)| (b.k_rad_per_m, clamp(b.s_m2_per_rad_per_m)))
            .collect();
        // The target first, so the measured curve stays visible over it.
        if let Some(t) = &a.target {
            let curve: Vec<(f64, f64)> = bins
                .iter()
                .map(|b| {
                    (
                        b.k_rad_per_m,
                        clamp(b.target_s_m2_per_rad_per_m.unwrap_or(0.0)),
                    )
                })
                .collect();
            chart
                .draw_series(LineSeries::new(curve, red.stroke_width(2)))
                .map_err(draw_err)?
                .label(format!(
                    "target: expected S(k), {} ({})",
                    t.spectrum, t.method
                ))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], red.stroke_width(2))
                });
        }
        chart
            .draw_series(LineSeries::new(complete, blue.stroke_width(2)))
            .map_err(draw_err)?
            .label("measured")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], blue.stroke_width(2))
            });
        if partial.len() > 1 {
            chart
                .draw_series(LineSeries::new(partial, pale.stroke_width(2)))
                .map_err(draw_err)?
                .label("measured, beyond Nyquist (partial annuli)")
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], pale.stroke_width(2))
                });
        }
        if let (Some(kp), Some(wl)) = (a.peak_k_rad_per_m, a.peak_wavelength_m) {
            let dir = a
                .peak_direction_deg
                .map_or(String::new(), |d| format!(", {d:.1}° (mod 180°)"));
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(kp, y_lo), (kp, y_hi)],
                    6,
                    4,
                    gray.stroke_width(1),
                ))
                .map_err(draw_err)?
                .label(format!("peak: λ = {} m{dir}", short_number(wl)))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], gray.stroke_width(1))
                });
        }
        crate::export::rgb8::draw_legend(&mut chart, SeriesLabelPosition::LowerLeft)?;
        root.present().map_err(draw_err)?;
    }
    Ok(buf)
}

fn opt(v: Option<f64>, digits: usize, unit: &str) -> String {
    match v {
        Some(v) => format!("{v:.digits$}{unit}"),
        None => "-".into(),
    }
}

/// The short report printed without `--json`.
fn human_report(r: &Report) -> String {
    let a = r.analysis;
    let mut s = String::new();
    let kind = match r.format {
        ImageKind::Png16 => "16-bit PNG",
        ImageKind::TiffF32 => "float TIFF",
    };
    s += &format!(
        "{}: {kind}, {}×{} samples, spacing {} m × {} m ({}), extent {} m × {} m\n",
        r.file, a.nx, a.ny, a.dx_m, a.dy_m, r.spacing_source, a.extent_m[0], a.extent_m[1]
    );
    s += &format!(
        "heights: mean {:.4} m, std {:.4} m, Hs (4·std) {:.4} m, min {:.4} m, max {:.4} m\n",
        // A mean of −0.00001 m would print as "-0.0000".
        if a.mean_m.abs() < 5e-5 { 0.0 } else { a.mean_m },
        a.std_m,
        a.hs_m,
        a.min_m,
        a.max_m
    );
    if let Some(q) = r.quantization_step_m {
        s += &format!("16-bit step: {q:.3e} m\n");
    }
    s += &format!(
        "spectral peak: wavelength {} (k = {}), direction {} modulo 180°, concentration {}\n",
        opt(a.peak_wavelength_m, 2, " m"),
        opt(a.peak_k_rad_per_m, 4, " rad/m"),
        opt(a.peak_direction_deg, 1, "°"),
        opt(a.peak_direction_concentration, 2, "")
    );
    match (&a.target, &a.target_note) {
        (Some(t), _) => {
            s += &format!(
                "target ({} method, {} spectrum): std {:.4} m, Hs {:.4} m, peak wavelength {}\n",
                t.method,
                t.spectrum,
                t.target_std_m,
                t.target_hs_m,
                opt(t.target_peak_wavelength_m, 2, " m")
            );
            s += &format!(
                "measured/target variance {}, RMS log10 spectrum difference {} over {} bins\n",
                opt(t.variance_ratio, 3, ""),
                opt(t.log10_rms_difference, 3, ""),
                t.bins_compared
            );
        }
        (None, Some(note)) => s += &format!("target: none ({note})\n"),
        (None, None) => s += "target: none\n",
    }
    s += &format!(
        "radial spectrum: {} bins of {:.4} rad/m (--json for the values)\n",
        a.radial_spectrum.len(),
        a.dk_rad_per_m
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative tolerance of sums that should agree up to f64 rounding.
    const PARSEVAL_REL_TOL: f64 = 1e-9;

    fn cosine(n: usize, extent: f64, wavelength: f64, dir_deg: f64, amp: f64) -> Grid {
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
    fn plot_labels_are_short_numbers() {
        assert_eq!(short_number(0.0123456), "0.0123");
        assert_eq!(short_number(45.0), "45");
        assert_eq!(short_number(1234.6), "1235");
        assert_eq!(short_number(2e-5), "2e-5");
    }

    #[test]
    fn the_plot_renders_for_a_cosine_and_for_a_flat_field() {
        for g in [
            cosine(64, 64.0, 8.0, 30.0, 1.0),
            Grid::new(GridSpec::new(8, 8, 8.0, 8.0), vec![0.5; 64]),
        ] {
            let rgb = render_plot(&analyze(&g, None), "test").unwrap();
            assert_eq!(rgb.len(), (PLOT_SIZE.0 * PLOT_SIZE.1 * 3) as usize);
            assert!(rgb.iter().any(|&v| v != 255), "something is drawn");
        }
    }

    #[test]
    fn the_peak_parabola_stays_within_half_a_bin() {
        assert_eq!(peak_bin(&[0.0, 0.0, 1.0, 0.0]).unwrap(), (2, 2.0));
        let (b, pos) = peak_bin(&[0.0, 1.0, 3.0, 2.9, 0.0]).unwrap();
        assert_eq!(b, 2);
        assert!(pos > 2.0 && pos <= 2.5, "{pos}");
        assert_eq!(peak_bin(&[0.0, 0.0, 0.0]), None);
    }

    #[test]
    fn a_target_on_another_grid_is_ignored_with_a_note() {
        let params = Params::default();
        let (spectrum, _) = crate::field::spectrum_model(&params).unwrap();
        let t = Target {
            spectrum,
            spec: params.grid_spec(),
            method: "fft".into(),
            model: "phillips".into(),
        };
        let a = analyze(&cosine(16, 16.0, 4.0, 0.0, 1.0), Some(&t));
        assert!(a.target.is_none());
        assert!(a.target_note.unwrap().contains("another grid"));
    }

    #[test]
    fn the_expected_spectrum_of_a_synthesized_field_matches_its_measured_one_on_average() {
        // Average of three seeds of the FFT method at 128² over 128 m at 3 m/s: the
        // measured variance is the sum of |h̃(k)|², whose expectation is the target.
        const RATIO_TOL: f64 = 0.1;
        let mut ratio = 0.0;
        for seed in 1..=3 {
            let mut p = Params {
                method: crate::config::Method::Fft,
                seed,
                ..Params::default()
            };
            p.grid.size = crate::config::Size2([128, 128]);
            p.grid.extent_m = crate::config::Extent2([128.0, 128.0]);
            p.wind.speed_mps = 3.0;
            let g = crate::field::synthesize(&p).unwrap().grid;
            let side = serde_json::json!({ "params": serde_json::to_value(&p).unwrap() });
            let t = Target::from_sidecar(&side, &g.spec).unwrap();
            let a = analyze(&g, Some(&t));
            ratio += a.target.unwrap().variance_ratio.unwrap() / 3.0;
        }
        assert!(
            (ratio - 1.0).abs() < RATIO_TOL,
            "mean variance ratio {ratio}"
        );
    }
}
