//! Tessendorf's FFT ocean (Li Tian eq. 1–8; Li, He & Gong §3).
//!
//! Conventions, stated once:
//! - Wavevector indices `(n, m)` with k = 2π·(n/Lx, m/Ly); the grid resolves
//!   n ∈ [−N/2, N/2), m ∈ [−M/2, M/2) (Li Tian eq. 5).
//! - Amplitudes: h̃0(k) = (ξr + iξi)/√2 · √P(k), with (ξr, ξi) drawn from
//!   `(seed, n, m)` by [`crate::rng::gaussian_pair`], so the same seed over the same extent
//!   gives the same long waves at every resolution.
//! - Time: h̃(k,t) = h̃0(k)·e^{−iωt} + conj(h̃0(−k))·e^{iωt}. With the synthesis sum below,
//!   the energy placed at k travels toward +k (so waves travel with the wind); Tessendorf's
//!   notes write the opposite sign of t, which makes the same waves run backwards.
//!   h̃(−k,t) = conj(h̃(k,t)), so the field is real by construction.
//! - Synthesis: h(x, t) = Σ_k h̃(k,t)·e^{ik·x}, unnormalized (no 1/NM), as in the papers:
//!   an inverse FFT with a positive exponent.
//! - Excluded wavevectors: k = 0 (mean zero), and the Nyquist row and column (n = −N/2 for
//!   even N, m = −M/2 for even M), whose partner −k is not on the grid; without them the
//!   spectrum is exactly Hermitian.
//!
//! The transform: a complex inverse FFT along y for each kx index 0..=N/2 (lines stored
//! contiguously), a blocked transpose, then a complex-to-real inverse FFT along x per row.

use rayon::prelude::*;
use rustfft::num_complex::{Complex, Complex32};

mod inverse;
mod lines;
pub mod second_order;
mod shift;

pub use inverse::InverseFft2;
pub use shift::shift_samples;

use crate::fastmath;
use crate::grid::{Grid, GridSpec};
pub use crate::grid::{is_resolved, signed_index};
use crate::rng::gaussian_polar;
use crate::simd::{Isa, multiversion, sin_cos_line_on};
use crate::spectrum::{Dispersion, PairOut, Spectrum};
use lines::draw_line;
pub(crate) use lines::{build_lines, draw_line_in, visit_lines, window};

/// Everything that fixes the random spectrum of one field.
#[derive(Clone, Copy)]
pub struct SpectrumSetup<'a> {
    pub spec: GridSpec,
    pub spectrum: &'a dyn Spectrum,
    pub dispersion: Dispersion,
    /// Seed of the amplitude stream (already a sub-seed).
    pub seed: u64,
    pub time_s: f64,
    /// Seamless loop period T, s: every ω is rounded to the nearest non-zero multiple of
    /// 2π/T (see [`loop_omega`]), so h̃(k, t + T) = h̃(k, t).
    pub loop_period_s: Option<f64>,
}

/// ω rounded to the nearest non-zero multiple of 2π/T: waves slower than 2π/T take one
/// cycle per period instead of freezing; ω = 0 stays 0.
pub fn loop_omega(omega: f64, period_s: f64) -> f64 {
    loop_omega_base(omega, std::f64::consts::TAU / period_s)
}

/// [`loop_omega`] given the base frequency 2π/T (straight-line code, for the line passes).
#[inline(always)]
fn loop_omega_base(omega: f64, base: f64) -> f64 {
    if omega == 0.0 {
        0.0
    } else {
        (omega / base).round().max(1.0) * base
    }
}

impl SpectrumSetup<'_> {
    /// Wavevector of indices `(n, m)`, rad/m.
    #[inline]
    pub fn wavevector(&self, n: i64, m: i64) -> (f64, f64) {
        self.spec.wavevector(n, m)
    }

    pub fn dk(&self) -> (f64, f64) {
        self.wavevector(1, 1)
    }

    /// ρ = √(p/2)·r and the phase φ of h̃0 = ρ·e^{iφ} at indices `(n, m)`, given
    /// p = E|h̃0|² there.
    #[inline]
    fn polar_from(&self, p: f64, n: i64, m: i64) -> (f64, f64) {
        if p <= P_FLOOR_M2 {
            return (0.0, 0.0);
        }
        let (r, phi) = gaussian_polar(self.seed, n, m);
        scale_draw(p, r, phi)
    }

    fn h0_polar(&self, n: i64, m: i64) -> (f64, f64) {
        let (kx, ky) = self.wavevector(n, m);
        let (dkx, dky) = self.dk();
        self.polar_from(self.spectrum.amplitude_variance(kx, ky, dkx, dky), n, m)
    }

    /// ω(k), rad/s, from the dispersion relation, rounded for a loop when one is set.
    pub fn omega(&self, kx: f64, ky: f64) -> f64 {
        let w = self.dispersion.omega((kx * kx + ky * ky).sqrt());
        match self.loop_period_s {
            Some(t) => loop_omega(w, t),
            None => w,
        }
    }

    /// ω(k)·t. With a loop period T the phase is ω·(t mod T), so frames T apart match.
    #[inline]
    pub fn omega_t(&self, kx: f64, ky: f64) -> f64 {
        if self.time_s == 0.0 {
            return 0.0;
        }
        self.omega(kx, ky) * self.phase_time()
    }

    /// The time the phases ω·t use: t, or t mod T with a loop period T.
    #[inline]
    pub(crate) fn phase_time(&self) -> f64 {
        match self.loop_period_s {
            Some(period) => self.time_s - period * (self.time_s / period).floor(),
            None => self.time_s,
        }
    }

    /// h̃0 at indices `(n, m)`: (ξr + iξi)/√2·√P(k).
    pub fn h0(&self, n: i64, m: i64) -> Complex<f64> {
        let (rho, phi) = self.h0_polar(n, m);
        Complex::from_polar(rho, phi)
    }

    /// h̃(k, t) at indices `(n, m)`, and max(|h̃0(k)|², |h̃0(−k)|²), one wavevector at a
    /// time (the reference for [`synthesize_spectrum`]).
    pub fn amplitude(&self, n: i64, m: i64) -> (Complex<f64>, f64) {
        let (ra, pa) = self.h0_polar(n, m);
        let (rb, pb) = self.h0_polar(-n, -m);
        let (kx, ky) = self.wavevector(n, m);
        combine(ra, pa, rb, pb, self.omega_t(kx, ky))
    }
}

/// With h̃0(k) = ρa·e^{iφa} and h̃0(−k) = ρb·e^{iφb}: h̃(k, t) = ρa·e^{i(φa − ωt)} +
/// ρb·e^{−i(φb − ωt)} (one sine and cosine per term), and max(ρa², ρb²).
#[inline]
fn combine(ra: f64, pa: f64, rb: f64, pb: f64, wt: f64) -> (Complex<f64>, f64) {
    let (sa, ca) = fastmath::sin_cos(pa - wt);
    let (sb, cb) = fastmath::sin_cos(pb - wt);
    let h = Complex::new(ra * ca + rb * cb, ra * sa - rb * sb);
    (h, (ra * ra).max(rb * rb))
}

/// The non-redundant half of h̃(k, t): `nx/2 + 1` lines (kx index n = 0..=nx/2), each
/// holding the `ny` ky bins in FFT order.
pub struct HalfSpectrum {
    pub nx: usize,
    pub ny: usize,
    pub data: Vec<Complex32>,
    /// h0max = max over resolved k of |h̃0(k)| (Li Tian §2, the β scale), meters.
    pub h0max_m: f64,
}

impl HalfSpectrum {
    pub fn lines(&self) -> usize {
        self.nx / 2 + 1
    }

    /// Σ over the full k plane of |h̃(k)|²: by Parseval, the mean square of the field.
    pub fn total_power(&self) -> f64 {
        let lines: Vec<f64> = self
            .data
            .par_chunks(self.ny)
            .enumerate()
            .map(|(n, line)| {
                let partner_counted = n == 0 || (self.nx % 2 == 0 && n == self.nx / 2);
                let w = if partner_counted { 1.0 } else { 2.0 };
                w * line.iter().map(|c| c.norm_sqr() as f64).sum::<f64>()
            })
            .collect();
        lines.iter().sum()
    }
}

/// Builds h̃(k, t) for every resolved wavevector with n ≥ 0 (Tessendorf). Values equal
/// [`SpectrumSetup::amplitude`]'s.
pub fn synthesize_spectrum(setup: &SpectrumSetup) -> HalfSpectrum {
    // The instruction set of this synthesis, chosen once for all its lines.
    let isa = Isa::detect();
    build_lines(setup, |n, kx, buf, line| {
        // Whole-line passes that vectorize (see `crate::simd`); the values are those of
        // `polar_from` and `combine`, bit for bit.
        draw_line(setup, isa, n, buf);
        let draws = Draws {
            ra: &buf.ra,
            pha: &buf.pha,
            rb: &buf.rb,
            phb: &buf.phb,
        };
        combine_line(setup, isa, n, kx, &buf.ky, draws, line)
    })
}

/// The index ranges of line n's ky bins that take part in the synthesis (see
/// [`is_resolved`]): all but m = 0 on the kx = 0 line and the Nyquist row, and none on the
/// Nyquist line.
fn resolved_ranges(n: i64, nx: usize, ny: usize) -> [std::ops::Range<usize>; 2] {
    if nx % 2 == 0 && n.unsigned_abs() as usize == nx / 2 {
        return [0..0, 0..0];
    }
    let start = usize::from(n == 0).min(ny);
    if ny % 2 == 0 {
        [start..ny / 2, (ny / 2 + 1).min(ny)..ny]
    } else {
        [start..ny, ny..ny]
    }
}

multiversion! {
    @on
    /// h̃ = ρa·(ca + i·sa) + ρb·(cb − i·sb) into `out` (as f32), and the peak
    /// max(ρa², ρb²), for one range of a line.
    fn combine_run(isa: Isa, ra: &[f64], rb: &[f64], e: Phasors, out: &mut [Complex32]) -> f64 {
        const LANES: usize = 8;
        let n = out.len();
        let (ra, rb) = (&ra[..n], &rb[..n]);
        let (sa, ca, sb, cb) = (&e.sa[..n], &e.ca[..n], &e.sb[..n], &e.cb[..n]);
        // Per-lane maxima (a reduction the compiler keeps in vector registers).
        let mut peaks = [0.0f64; LANES];
        for j in 0..n {
            let (a, b) = (ra[j], rb[j]);
            let re = a * ca[j] + b * cb[j];
            let im = a * sa[j] - b * sb[j];
            out[j] = Complex32::new(re as f32, im as f32);
            let l = j % LANES;
            peaks[l] = peaks[l].max((a * a).max(b * b));
        }
        peaks.iter().fold(0.0f64, |p, &q| p.max(q))
    }
}

/// The unit phasors of a range of a line: e^{i(φa − ωt)} = ca + i·sa and
/// e^{i(φb − ωt)} = cb + i·sb.
#[derive(Clone, Copy)]
struct Phasors<'a> {
    sa: &'a [f64],
    ca: &'a [f64],
    sb: &'a [f64],
    cb: &'a [f64],
}

/// The scaled draws of one line: h̃0(k) = ρa·e^{iφa}, h̃0(−k) = ρb·e^{iφb}.
#[derive(Clone, Copy)]
pub(crate) struct Draws<'a> {
    pub ra: &'a [f64],
    pub pha: &'a [f64],
    pub rb: &'a [f64],
    pub phb: &'a [f64],
}

/// Per-thread buffers of [`combine_line`]: arguments, sines and cosines.
#[derive(Default)]
struct CombineBuffers {
    xa: Vec<f64>,
    xb: Vec<f64>,
    sa: Vec<f64>,
    ca: Vec<f64>,
    sb: Vec<f64>,
    cb: Vec<f64>,
}

thread_local! {
    static COMBINE: std::cell::RefCell<CombineBuffers> =
        std::cell::RefCell::new(CombineBuffers::default());
}

/// h̃(k, t) = ρa·e^{i(φa − ωt)} + ρb·e^{−i(φb − ωt)} of line n into `line`, and the
/// line's peak max(ρa², ρb²), on `isa`. The values of [`SpectrumSetup::amplitude`], bit
/// for bit.
pub(crate) fn combine_line(
    setup: &SpectrumSetup,
    isa: Isa,
    n: i64,
    kx: f64,
    ky: &[f64],
    d: Draws,
    line: &mut [Complex32],
) -> f64 {
    let (nx, ny) = (setup.spec.nx, setup.spec.ny);
    COMBINE.with(|cell| {
        let mut guard = cell.borrow_mut();
        let b = &mut *guard;
        for v in [
            &mut b.xa, &mut b.xb, &mut b.sa, &mut b.ca, &mut b.sb, &mut b.cb,
        ] {
            v.resize(ny, 0.0);
        }
        if setup.time_s == 0.0 {
            // ω·t = 0 (exactly what omega_t gives): the phases themselves.
            sin_cos_line_on(isa, &d.pha[..ny], &mut b.sa, &mut b.ca);
            sin_cos_line_on(isa, &d.phb[..ny], &mut b.sb, &mut b.cb);
        } else {
            if setup.dispersion == Dispersion::Deep {
                let x = PairOut {
                    a: &mut b.xa,
                    b: &mut b.xb,
                };
                deep_phases(setup, isa, kx, &ky[..ny], d, x);
            } else {
                for (idx, &y) in ky.iter().enumerate().take(ny) {
                    let wt = setup.omega_t(kx, y);
                    b.xa[idx] = d.pha[idx] - wt;
                    b.xb[idx] = d.phb[idx] - wt;
                }
            }
            sin_cos_line_on(isa, &b.xa, &mut b.sa, &mut b.ca);
            sin_cos_line_on(isa, &b.xb, &mut b.sb, &mut b.cb);
        }
        let mut peak = 0.0f64;
        for r in resolved_ranges(n, nx, ny) {
            let phasors = Phasors {
                sa: &b.sa[r.clone()],
                ca: &b.ca[r.clone()],
                sb: &b.sb[r.clone()],
                cb: &b.cb[r.clone()],
            };
            let p = combine_run(
                isa,
                &d.ra[r.clone()],
                &d.rb[r.clone()],
                phasors,
                &mut line[r],
            );
            peak = peak.max(p);
        }
        peak
    })
}

/// φa − ω·t into `x.a` and φb − ω·t into `x.b` for a line in deep water, bit for bit as
/// with [`SpectrumSetup::omega_t`] (the time reduced by the loop period once, ω rounded to
/// the loop's multiples per lane).
fn deep_phases(setup: &SpectrumSetup, isa: Isa, kx: f64, ky: &[f64], d: Draws, x: PairOut<f64>) {
    // base = 0 stands for no loop.
    let base = setup
        .loop_period_s
        .map_or(0.0, |p| std::f64::consts::TAU / p);
    deep_phase_run(isa, kx, ky, setup.phase_time(), base, d, x);
}

multiversion! {
    @on
    /// See [`deep_phases`]: ω = √(g·|k|), [`loop_omega`]'s rounding where `base` > 0.
    fn deep_phase_run(
        isa: Isa,
        kx: f64,
        ky: &[f64],
        t: f64,
        base: f64,
        d: Draws,
        x: PairOut<f64>,
    ) {
        let (pha, phb) = (d.pha, d.phb);
        let n = ky.len();
        let (pha, phb, xa, xb) = (&pha[..n], &phb[..n], &mut x.a[..n], &mut x.b[..n]);
        for j in 0..n {
            let y = ky[j];
            let w = (crate::spectrum::G * (kx * kx + y * y).sqrt()).sqrt();
            let w = if base > 0.0 { loop_omega_base(w, base) } else { w };
            let wt = w * t;
            xa[j] = pha[j] - wt;
            xb[j] = phb[j] - wt;
        }
    }
}

/// The scaled draws of every line of a spectrum, kept so that the frames of an
/// animation only redo the time-dependent part (sines and cosines of φ − ωt).
pub struct Amplitudes {
    /// The instruction set the frames' line passes run on, chosen with the draws.
    isa: Isa,
    ky: Vec<f64>,
    /// Per line n: ρa, φa, ρb, φb, each `ny` long.
    lines: Vec<[Vec<f64>; 4]>,
    h0max_m: f64,
}

impl Amplitudes {
    /// The draws of `setup` (its time is not used).
    pub fn new(setup: &SpectrumSetup) -> Self {
        let isa = Isa::detect();
        let ny = setup.spec.ny;
        let lines = setup.spec.nx / 2 + 1;
        let mut store: Vec<[Vec<f64>; 4]> = Vec::with_capacity(lines);
        store.resize_with(lines, Default::default);
        let slots = std::sync::Mutex::new(&mut store);
        let half = build_lines(setup, |n, _kx, buf, _line| {
            draw_line(setup, isa, n, buf);
            let peak = buf
                .ra
                .iter()
                .zip(&buf.rb)
                .fold(0.0f64, |p, (a, b)| p.max((a * a).max(b * b)));
            let v = [
                buf.ra.clone(),
                buf.pha.clone(),
                buf.rb.clone(),
                buf.phb.clone(),
            ];
            slots.lock().expect("no panics while holding the lock")[n as usize] = v;
            peak
        });
        let ky = (0..ny)
            .map(|idx| setup.wavevector(0, signed_index(idx, ny)).1)
            .collect();
        Self {
            isa,
            ky,
            lines: store,
            h0max_m: half.h0max_m,
        }
    }

    /// h̃(k, t) at `setup.time_s`: bit for bit [`synthesize_spectrum`] of the same setup.
    pub fn frame(&self, setup: &SpectrumSetup) -> HalfSpectrum {
        let (nx, ny) = (setup.spec.nx, setup.spec.ny);
        let mut data = vec![Complex32::new(0.0, 0.0); (nx / 2 + 1) * ny];
        data.par_chunks_mut(ny)
            .zip(self.lines.par_iter())
            .enumerate()
            .for_each(|(n, (line, [ra, pha, rb, phb]))| {
                let kx = setup.wavevector(n as i64, 0).0;
                let d = Draws { ra, pha, rb, phb };
                combine_line(setup, self.isa, n as i64, kx, &self.ky, d, line);
            });
        HalfSpectrum {
            nx,
            ny,
            data,
            h0max_m: self.h0max_m,
        }
    }
}

/// Amplitude variances at or below this (amplitudes of ~1e-30 m) are left out: they
/// change no height, and as f32 they would be subnormal numbers, which slow the
/// transform's arithmetic many times over.
pub const P_FLOOR_M2: f64 = 1e-60;

/// ρ = √(p/2)·r and φ of a draw (r, φ) for E|h̃0|² = p; (0, 0) where p ≤ [`P_FLOOR_M2`],
/// as [`SpectrumSetup::polar_from`].
#[inline(always)]
fn scale_draw(p: f64, r: f64, phi: f64) -> (f64, f64) {
    if p <= P_FLOOR_M2 {
        (0.0, 0.0)
    } else {
        ((p * 0.5).sqrt() * r, phi)
    }
}

/// The FFT height field at `setup.time_s`, and h0max.
pub fn fft_field(setup: &SpectrumSetup) -> (Grid, f64) {
    let half = synthesize_spectrum(setup);
    let h0max = half.h0max_m;
    let data = InverseFft2::new(setup.spec.nx, setup.spec.ny).process(half);
    (Grid::new(setup.spec, data), h0max)
}

#[cfg(test)]
mod tests;
#[cfg(test)]
pub(crate) use tests::OneComponent;
