//! The spectrum's kx lines: per-thread line buffers, the half spectrum built line by line,
//! the lines visited without one (on a window of their ky indices), and each line's
//! scaled draws.

use std::ops::Range;

use rayon::prelude::*;
use rustfft::num_complex::Complex32;

use super::{HalfSpectrum, SpectrumSetup, scale_draw};
use crate::grid::signed_index;
use crate::simd::{Isa, multiversion, polar_range_on};
use crate::spectrum::{LineQuery, PairOut};

/// Per-thread buffers of one kx line.
pub(crate) struct LineBuffers {
    pub ky: Vec<f64>,
    /// E|h̃0(k)|² and E|h̃0(−k)|² of the line (kernels may reuse them).
    pub pa: Vec<f64>,
    pub pb: Vec<f64>,
    /// Scratch for kernels: Rayleigh factors and phases of the k (a) and −k (b) terms.
    pub ra: Vec<f64>,
    pub rb: Vec<f64>,
    pub pha: Vec<f64>,
    pub phb: Vec<f64>,
}

/// Builds the half spectrum line by line in parallel: for each kx line n, the spectrum
/// E|h̃0(±k)|² over the whole line first (one call, a loop the compiler can pipeline),
/// then `kernel(n, kx, buffers, line)` fills the line and returns a peak value; the
/// result's `h0max_m` is the square root of the largest peak.
pub(crate) fn build_lines<K>(setup: &SpectrumSetup, kernel: K) -> HalfSpectrum
where
    K: Fn(i64, f64, &mut LineBuffers, &mut [Complex32]) -> f64 + Sync,
{
    let (nx, ny) = (setup.spec.nx, setup.spec.ny);
    let lines = nx / 2 + 1;
    let ky = line_ky(setup);
    let mut data = vec![Complex32::new(0.0, 0.0); lines * ny];
    let peak = data
        .par_chunks_mut(ny)
        .enumerate()
        .map_init(
            || LineBuffers::new(&ky),
            |buf, (n, line)| {
                let kx = line_variances(setup, n as i64, buf);
                kernel(n as i64, kx, buf, line)
            },
        )
        .reduce(|| 0.0, f64::max);
    HalfSpectrum {
        nx,
        ny,
        data,
        h0max_m: peak.sqrt(),
    }
}

/// What `visit(n, buffers)` makes of each kx line n < `lines` (n ≥ 0, at most the half
/// spectrum's nx/2 + 1 lines), in line order, with the line's E|h̃0(±k)|² in the buffers
/// at the indices of `cols` ([`window`]; elsewhere unset), the values [`build_lines`]
/// gives them: the lines' passes that need no half spectrum.
pub(crate) fn visit_lines<T, V>(
    setup: &SpectrumSetup,
    (lines, cols): (usize, &[Range<usize>; 2]),
    visit: V,
) -> Vec<T>
where
    T: Send,
    V: Fn(i64, &mut LineBuffers) -> T + Sync,
{
    let ky = line_ky(setup);
    let lines = lines.min(setup.spec.nx / 2 + 1);
    (0..lines)
        .into_par_iter()
        .map_init(
            || LineBuffers::new(&ky),
            |buf, n| {
                for r in cols.iter().filter(|r| !r.is_empty()) {
                    line_variances_in(setup, n as i64, buf, r.clone());
                }
                visit(n as i64, buf)
            },
        )
        .collect()
}

/// The indices of a line of `ny` (FFT order) with |m| < `cols`: m = 0 ..< cols, then
/// the negative m from −(cols − 1) (every index when they cover the line).
pub(crate) fn window(ny: usize, cols: usize) -> [Range<usize>; 2] {
    if cols == 0 {
        [0..0, ny..ny]
    } else if 2 * cols > ny {
        [0..ny, ny..ny]
    } else {
        [0..cols, ny + 1 - cols..ny]
    }
}

/// E|h̃0(±k)|² of the indices `r` of kx line n into `buf.pa`, `buf.pb` (the values of
/// [`line_variances`] there).
fn line_variances_in(setup: &SpectrumSetup, n: i64, buf: &mut LineBuffers, r: Range<usize>) {
    let (dkx, dky) = setup.dk();
    let kx = setup.wavevector(n, 0).0;
    let q = LineQuery {
        kx,
        ky: &buf.ky[r.clone()],
        dkx,
        dky,
    };
    let out = PairOut {
        a: &mut buf.pa[r.clone()],
        b: &mut buf.pb[r],
    };
    setup.spectrum.amplitude_variance_pair_line(&q, out);
}

/// The ky of each index of a line (FFT order).
fn line_ky(setup: &SpectrumSetup) -> Vec<f64> {
    let ny = setup.spec.ny;
    (0..ny)
        .map(|idx| setup.wavevector(0, signed_index(idx, ny)).1)
        .collect()
}

impl LineBuffers {
    fn new(ky: &[f64]) -> Self {
        let ny = ky.len();
        Self {
            ky: ky.to_vec(),
            pa: vec![0.0; ny],
            pb: vec![0.0; ny],
            ra: vec![0.0; ny],
            rb: vec![0.0; ny],
            pha: vec![0.0; ny],
            phb: vec![0.0; ny],
        }
    }
}

/// E|h̃0(±k)|² of kx line n into `buf.pa`, `buf.pb` (one call over the whole line); its kx.
fn line_variances(setup: &SpectrumSetup, n: i64, buf: &mut LineBuffers) -> f64 {
    line_variances_in(setup, n, buf, 0..buf.ky.len());
    setup.wavevector(n, 0).0
}

/// The scaled draws ρ, φ of h̃0(k) (ra, pha) and h̃0(−k) (rb, phb) of line n, from the
/// amplitude variances in `buf.pa`, `buf.pb`, on `isa`.
pub(super) fn draw_line(setup: &SpectrumSetup, isa: Isa, n: i64, buf: &mut LineBuffers) {
    let ny = setup.spec.ny;
    draw_line_in(setup, isa, n, buf, &window(ny, ny));
}

/// [`draw_line`] at the indices `cols` of the line only ([`window`]; elsewhere unset):
/// the same values there, bit for bit.
pub(crate) fn draw_line_in(
    setup: &SpectrumSetup,
    isa: Isa,
    n: i64,
    buf: &mut LineBuffers,
    cols: &[Range<usize>; 2],
) {
    let ny = setup.spec.ny;
    for r in cols.iter().filter(|r| !r.is_empty()) {
        let r = r.clone();
        let (ra, pha) = (&mut buf.ra[r.clone()], &mut buf.pha[r.clone()]);
        polar_range_on(isa, (setup.seed, n, 1), ny, r.clone(), ra, pha);
        let (rb, phb) = (&mut buf.rb[r.clone()], &mut buf.phb[r.clone()]);
        polar_range_on(isa, (setup.seed, n, -1), ny, r.clone(), rb, phb);
        scale_draws(isa, &buf.pa[r.clone()], ra, pha);
        scale_draws(isa, &buf.pb[r], rb, phb);
    }
}

multiversion! {
    @on
    /// `(r[j], phi[j]) = scale_draw(p[j], r[j], phi[j])` for every j.
    fn scale_draws(isa: Isa, p: &[f64], r: &mut [f64], phi: &mut [f64]) {
        let n = p.len();
        let (r, phi) = (&mut r[..n], &mut phi[..n]);
        for j in 0..n {
            (r[j], phi[j]) = scale_draw(p[j], r[j], phi[j]);
        }
    }
}
