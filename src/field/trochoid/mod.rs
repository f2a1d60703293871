//! Thon, Dischler & Ghazanfarpour (2000): a procedural ocean of trochoids chosen from a
//! spectrum, plus spectrum-fitted 3D Perlin turbulence (eq. 10):
//!
//! ```text
//! h(x, y, t) = Σ_i A_i·v(k_i·x − ω_i t + φ_i) + A_t·Σ_{o<n_o} N(P(x, y, t)·m^o)/m^o
//! ```
//!
//! - v: the trochoid profile of sharpness kr ([`profile`]);
//! - the components: the n strongest cells of the directional spectrum sampled on a
//!   matrix ([`select`]);
//! - the turbulence: 3D gradient noise ([`crate::field::noise3`]) with m and A_t fitted
//!   to the spectrum's slope and level at k_max ([`fit`]); P = ((x − d_x t)/ℓ0,
//!   (y − d_y t)/ℓ0, e·t) drifts along the wind at d (the phase speed at k_max) and along
//!   the third axis at e (f_max/4 cells per second) (§3);
//! - antialiasing (§2.4): for sample spacings (Δx, Δy), each term is weighted by the mean
//!   of a cosine of its wavevector over the sample's footprint,
//!   sinc(kx Δx/2)·sinc(ky Δy/2) (what averaging the fine field over the coarse pixel does
//!   to it), times a taper 1 − smoothstep from the Nyquist wavenumber π/Δ (q = 1) to 0 at
//!   twice it (q = max(|kx|Δx, |ky|Δy)/π); an octave of lattice frequency s (cells per
//!   meter) is weighted alike at the peak of its spectrum, |k| = 3.2·s. Weights that are 0
//!   drop the term, which also saves its work.
//!
//! The field is continuous: [`Frame::at`] gives the height at any (x, y), and
//! [`Frame::row`] a row of samples (the same bits at the same points: a point is a row of
//! one sample). Rows do not depend on each other, so any window of the endless sea can be
//! computed strip by strip.

pub mod fit;
pub mod profile;
pub mod select;

use serde::Serialize;

use crate::config::{Params, SpectrumModel};
use crate::error::Result;
use crate::field::fft::SpectrumSetup;
use crate::field::noise3;
use crate::grid::{Grid, GridSpec};
use crate::rng::{self, Stream, sub_seed};
use crate::simd::{Isa, multiversion};
use profile::Profile;
use select::Component;

/// Antialiasing: the taper runs from q = AA_START to 0 at q = AA_END (q = k/k_Nyquist).
pub const AA_START: f64 = 1.0;
pub const AA_END: f64 = 2.0;
/// Where the noise's radial spectrum peaks, rad per lattice cell (measured: see [`fit`]).
pub const NOISE_PEAK_PER_CELL: f64 = 3.2;

/// What the sidecar records about a trochoid field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrochoidInfo {
    /// Components used (≤ `trochoid.components`: empty cells are skipped).
    pub components: usize,
    /// Side of the virtual tile whose Fourier grid the matrix is, m.
    pub matrix_extent_m: f64,
    /// The largest selected wavenumber, rad/m, its frequency, Hz, and wavelength, m.
    pub k_max_rad_per_m: f64,
    pub f_max_hz: f64,
    pub lambda_min_m: f64,
    /// Σ A_i²/2 of the trochoids (cosine equivalent), m².
    pub trochoid_variance_m2: f64,
    /// The fitted (or given) turbulence; none without turbulence.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turbulence: Option<fit::Fit>,
    /// Turbulence drift along the wind, m/s, and along the noise's third axis, cells/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drift_mps: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub evolve_per_s: Option<f64>,
    /// A bound on |h|: Σ A_i(1 + kr/2) + A_t·Σ m^−o·1.1, m.
    pub height_bound_m: f64,
}

/// One octave of the turbulence.
#[derive(Debug, Clone, Copy)]
struct Octave {
    key: u32,
    /// Lattice cells per meter, m^o/ℓ0.
    scale: f64,
    /// 1/m^o.
    weight: f64,
    /// Lattice offsets of this octave (decorrelates the octaves' lattices).
    offset: [f64; 3],
}

/// The spectrum-fitted turbulence.
#[derive(Debug, Clone)]
struct Turbulence {
    fit: fit::Fit,
    octaves: Vec<Octave>,
    /// Drift velocity along the wind, m/s.
    drift: (f64, f64),
    /// Third-axis drift, cells of the first octave per second.
    evolve_per_s: f64,
}

/// A trochoid sea: everything that does not depend on time or on the sampling.
#[derive(Debug, Clone)]
pub struct TrochoidSea {
    profile: Profile,
    components: Vec<Component>,
    turbulence: Option<Turbulence>,
    loop_period_s: Option<f64>,
    origin_m: [f64; 2],
    antialias: bool,
    info: TrochoidInfo,
    /// The instruction set the frames' row passes run on, chosen when the sea is built.
    isa: Isa,
}

/// The default side of the matrix's virtual tile, in peak wavelengths: Δk = kp/3, so the
/// matrix reaches ±10 kp and its 48 strongest cells hold about 3/4 of the variance.
pub const MATRIX_PEAK_WAVELENGTHS: f64 = 3.0;

/// Side of the matrix's virtual tile, m: `trochoid.matrix_extent_m`, else
/// [`MATRIX_PEAK_WAVELENGTHS`] peak wavelengths (physical seas, Phillips), else as many
/// `fractal.rolloff_m`, or the grid's extent.
fn matrix_extent_m(params: &Params) -> Result<f64> {
    if let Some(l) = params.trochoid.matrix_extent_m {
        return Ok(l);
    }
    let tau = std::f64::consts::TAU;
    if let Some(sea) = crate::field::sea_model(params)? {
        let kp = sea.dispersion.wavenumber(tau * sea.freq.peak_hz());
        return Ok(MATRIX_PEAK_WAVELENGTHS * tau / kp);
    }
    Ok(match params.spectrum.model {
        SpectrumModel::Phillips => {
            // The radial density k·P(k) of Phillips' spectrum peaks at k = √(2/3)/L.
            let l = crate::field::phillips(params).largest_wave_m();
            MATRIX_PEAK_WAVELENGTHS * tau * l / (2.0f64 / 3.0).sqrt()
        }
        _ => match params.fractal.rolloff_m {
            Some(r) => MATRIX_PEAK_WAVELENGTHS * r,
            None => params.grid.extent_m.0[0].max(params.grid.extent_m.0[1]),
        },
    })
}

impl TrochoidSea {
    /// The sea of validated `params` (method `trochoid`).
    pub fn new(params: &Params) -> Result<Self> {
        let tp = &params.trochoid;
        let extent = matrix_extent_m(params)?;
        // The spectrum on the matrix's grid (the fractal spectrum is normalized on it).
        let mut on_matrix = params.clone();
        on_matrix.grid.size = crate::config::Size2([tp.matrix, tp.matrix]);
        on_matrix.grid.extent_m = crate::config::Extent2([extent, extent]);
        let (spectrum, dispersion) = crate::field::spectrum_model(&on_matrix)?;
        let setup = SpectrumSetup {
            spec: on_matrix.grid_spec(),
            spectrum: spectrum.as_ref(),
            dispersion,
            seed: 0,
            time_s: 0.0,
            loop_period_s: params.motion.loop_period_s,
        };
        let phase_seed = sub_seed(params.seed, Stream::TrochoidPhase);
        let components = select::select(&setup, tp.matrix, tp.components, phase_seed);
        let k_max = components
            .iter()
            .map(Component::wavenumber)
            .fold(0.0f64, f64::max);
        let tau = std::f64::consts::TAU;
        let omega_max = dispersion.omega(k_max);
        let f_max = omega_max / tau;
        let kr = tp.sharpness;
        let mut bound: f64 = components
            .iter()
            .map(|c| c.amplitude_m * (1.0 + 0.5 * kr))
            .sum();
        let turbulence = (tp.turbulence && k_max > 0.0).then(|| {
            let dk = setup.dk();
            let f = fit::fit(
                |k| fit::target_spectrum(spectrum.as_ref(), k, dk),
                k_max,
                tp.octaves,
                tp.multiplier,
                tp.amplitude_m,
            );
            let seed = sub_seed(params.seed, Stream::Turbulence);
            let mut scale = 1.0 / f.lattice_m;
            let mut weight = 1.0;
            let octaves = (0..tp.octaves as u64)
                .map(|o| {
                    let h = rng::hash_words(&[seed, o]);
                    let unit = |shift: u32| ((h >> shift) & 0xffff) as f64 / 65536.0;
                    let oct = Octave {
                        key: (h >> 32) as u32 ^ (h as u32),
                        scale,
                        weight,
                        offset: [unit(0), unit(16), unit(32)],
                    };
                    scale *= f.multiplier;
                    weight /= f.multiplier;
                    oct
                })
                .collect::<Vec<_>>();
            let dir = params.wind.direction_deg.to_radians();
            let speed = tp.drift_mps.unwrap_or(omega_max / k_max);
            Turbulence {
                fit: f,
                octaves,
                drift: {
                    let (sin, cos) = crate::fastmath::sin_cos(dir);
                    (speed * cos, speed * sin)
                },
                evolve_per_s: tp.evolve_per_s.unwrap_or(f_max / 4.0),
            }
        });
        if let Some(t) = &turbulence {
            bound += t.fit.amplitude_m * t.octaves.iter().map(|o| o.weight * 1.1).sum::<f64>();
        }
        let info = TrochoidInfo {
            components: components.len(),
            matrix_extent_m: extent,
            k_max_rad_per_m: k_max,
            f_max_hz: f_max,
            lambda_min_m: if k_max > 0.0 {
                tau / k_max
            } else {
                f64::INFINITY
            },
            trochoid_variance_m2: components
                .iter()
                .map(|c| 0.5 * c.amplitude_m * c.amplitude_m)
                .sum(),
            turbulence: turbulence.as_ref().map(|t| t.fit),
            drift_mps: turbulence.as_ref().map(|t| t.drift.0.hypot(t.drift.1)),
            evolve_per_s: turbulence.as_ref().map(|t| t.evolve_per_s),
            height_bound_m: bound,
        };
        Ok(Self {
            profile: Profile::new(kr),
            components,
            turbulence,
            loop_period_s: params.motion.loop_period_s,
            // Samples at texel centres: the grid's first sample half a cell in.
            origin_m: {
                let (o, spec) = (params.grid.sample_at.offset(), params.grid_spec());
                [
                    tp.origin_m[0] + o * spec.dx_m(),
                    tp.origin_m[1] + o * spec.dy_m(),
                ]
            },
            antialias: tp.antialias,
            info,
            isa: Isa::detect(),
        })
    }

    /// The continuous field (no antialiasing) at world (x, y) and time t, m.
    pub fn height_at(&self, x: f64, y: f64, time_s: f64) -> f32 {
        self.frame(time_s, None).at(x, y)
    }

    pub fn info(&self) -> &TrochoidInfo {
        &self.info
    }

    pub fn components(&self) -> &[Component] {
        &self.components
    }

    pub fn profile(&self) -> &Profile {
        &self.profile
    }

    /// The sea at time `t`, sampled with spacings `spacing` (antialiased for them when
    /// `trochoid.antialias` is on; `None`: no antialiasing, the continuous field).
    pub fn frame(&self, time_s: f64, spacing: Option<(f64, f64)>) -> Frame<'_> {
        let tau = std::f64::consts::TAU;
        let spacing = spacing.filter(|_| self.antialias);
        // ω·(t mod T) with a loop period, as the FFT methods do.
        let t = match self.loop_period_s {
            Some(p) if time_s != 0.0 => time_s - p * (time_s / p).floor(),
            _ => time_s,
        };
        let waves = self
            .components
            .iter()
            .filter_map(|c| {
                let w = spacing.map_or(1.0, |(dx, dy)| attenuation(c.k.0 * dx, c.k.1 * dy));
                let wt = if time_s == 0.0 { 0.0 } else { c.omega * t };
                // Positions on the table: (phase/2π + 1/2)·LUT_SIZE.
                let n = profile::LUT_SIZE as f64;
                (w > 0.0).then(|| Wave {
                    ax: c.k.0 / tau * n,
                    ay: c.k.1 / tau * n,
                    c0: (c.phase - wt) / tau * n + 0.5 * n,
                    amp: (c.amplitude_m * w) as f32,
                })
            })
            .collect();
        let (octaves, shift, depth) = match &self.turbulence {
            Some(tb) => {
                let octs = tb
                    .octaves
                    .iter()
                    .filter_map(|o| {
                        let w = spacing.map_or(1.0, |(dx, dy)| {
                            let k = NOISE_PEAK_PER_CELL * o.scale;
                            attenuation(k * dx, k * dy)
                        });
                        let amp = tb.fit.amplitude_m * o.weight * w;
                        (amp > 0.0).then_some(FrameOctave {
                            octave: *o,
                            amp: amp as f32,
                        })
                    })
                    .collect();
                (
                    octs,
                    (tb.drift.0 * time_s, tb.drift.1 * time_s),
                    tb.evolve_per_s * time_s,
                )
            }
            None => (Vec::new(), (0.0, 0.0), 0.0),
        };
        Frame {
            table: self.profile.table(),
            waves,
            octaves,
            shift,
            depth,
            origin_m: self.origin_m,
            isa: self.isa,
        }
    }

    /// The field on `spec` at `time_s` (sample (i, j) at the origin + (i·dx, j·dy)),
    /// antialiased for the grid's spacing.
    pub fn grid(&self, spec: &GridSpec, time_s: f64) -> Grid {
        use rayon::prelude::*;
        let frame = self.frame(time_s, Some((spec.dx_m(), spec.dy_m())));
        let mut data = vec![0.0f32; spec.len()];
        data.par_chunks_mut(spec.nx)
            .enumerate()
            .for_each_init(RowScratch::default, |s, (j, row)| {
                frame.grid_row(spec, j, row, s)
            });
        Grid::new(*spec, data)
    }
}

/// The antialiasing weight of a wave of phase steps (kx·Δx, ky·Δy) per sample: the mean of
/// cos(k·x) over the sample's Δx × Δy footprint, sinc(kx·Δx/2)·sinc(ky·Δy/2), times
/// 1 − smoothstep((q − AA_START)/(AA_END − AA_START)), q = max(|kx|Δx, |ky|Δy)/π, which
/// takes it smoothly to 0 between the Nyquist wavenumber and twice it.
pub fn attenuation(kx_dx: f64, ky_dy: f64) -> f64 {
    let sinc = |u: f64| {
        if u.abs() < 1e-8 {
            1.0
        } else {
            crate::fastmath::sin_cos(u).0 / u
        }
    };
    let q = kx_dx.abs().max(ky_dy.abs()) / std::f64::consts::PI;
    let t = ((q - AA_START) / (AA_END - AA_START)).clamp(0.0, 1.0);
    (sinc(0.5 * kx_dx) * sinc(0.5 * ky_dy) * (1.0 - t * t * (3.0 - 2.0 * t))).max(0.0)
}

/// One component at one time: its position on the profile's table is ax·x + ay·y + c0.
#[derive(Debug, Clone, Copy)]
struct Wave {
    ax: f64,
    ay: f64,
    c0: f64,
    amp: f32,
}

#[derive(Debug, Clone, Copy)]
struct FrameOctave {
    octave: Octave,
    amp: f32,
}

/// The sea at one time and sampling: evaluates rows and points.
pub struct Frame<'a> {
    table: &'a profile::Table,
    waves: Vec<Wave>,
    octaves: Vec<FrameOctave>,
    /// Turbulence displacement along x and y at this time, m, and along the third axis,
    /// cells.
    shift: (f64, f64),
    depth: f64,
    origin_m: [f64; 2],
    /// The sea's instruction set.
    isa: Isa,
}

/// Per-thread buffers of [`Frame::row`].
#[derive(Debug, Default)]
pub struct RowScratch {
    xs: Vec<f64>,
    txs: Vec<f64>,
    noise: noise3::Scratch,
}

impl Frame<'_> {
    /// Heights at world x = x0 + i·dx (i < out.len()), world y: trochoids in component
    /// order, then the octaves in order, each added in f32.
    pub fn row(&self, x0: f64, dx: f64, y: f64, out: &mut [f32], s: &mut RowScratch) {
        let n = out.len();
        s.xs.clear();
        s.xs.extend((0..n).map(|i| x0 + i as f64 * dx));
        out.fill(0.0);
        for w in &self.waves {
            wave_run(
                self.isa,
                self.table,
                &s.xs,
                w.ax,
                w.ay * y + w.c0,
                w.amp,
                out,
            );
        }
        if self.octaves.is_empty() {
            return;
        }
        s.txs.clear();
        s.txs.extend(s.xs.iter().map(|&x| x - self.shift.0));
        let ty = y - self.shift.1;
        for fo in &self.octaves {
            let o = &fo.octave;
            let ctx = noise3::row_context(
                o.key,
                ty * o.scale + o.offset[1],
                self.depth / o.weight + o.offset[2],
                0,
            );
            noise3::add_row(
                &ctx,
                &s.txs,
                o.scale,
                o.offset[0],
                fo.amp,
                out,
                &mut s.noise,
            );
        }
    }

    /// Row `j` of the grid `spec` (world origin added).
    pub fn grid_row(&self, spec: &GridSpec, j: usize, out: &mut [f32], s: &mut RowScratch) {
        self.row(
            self.origin_m[0],
            spec.dx_m(),
            self.origin_m[1] + spec.y_m(j),
            out,
            s,
        );
    }

    /// The height at world (x, y): the same bits as a row through that point.
    pub fn at(&self, x: f64, y: f64) -> f32 {
        let mut out = [0.0f32];
        self.row(x, 0.0, y, &mut out, &mut RowScratch::default());
        out[0]
    }
}

multiversion! {
    @on
    /// `out[i] += amp·v(·)` at table position ax·xs[i] + cy (see [`profile::lookup_pos`]).
    fn wave_run(
        isa: Isa,
        table: &profile::Table,
        xs: &[f64],
        ax: f64,
        cy: f64,
        amp: f32,
        out: &mut [f32],
    ) {
        for (o, &x) in out.iter_mut().zip(xs) {
            *o += amp * profile::lookup_pos(table, ax * x + cy);
        }
    }
}

#[cfg(test)]
mod tests;
