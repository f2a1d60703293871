//! What multiplies the fitted frame's transforms at each output kept: the output
//! coefficients of the fit (a function of |q| alone, so the same at (n, m) and (n, −m);
//! tabulated once for a sequence), and the gathering of the transforms there.

use rayon::prelude::*;
use rustfft::Fft;
use rustfft::num_complex::Complex;

use super::super::C64;
use super::super::fit::{ANGLE_NODES, KernelFit, MAX_NB, resonance_t};
use super::TransformBound;
use super::products::{Acc, Layout, Part, Real, wide};
use super::stages::{Passes, folds, twiddles};
use crate::grid::{GridSpec, bin_index};

/// The output coefficients at output (n, m) of a grid `spec`, depth `depth`:
/// [`KernelFit::output_coefficients`]' sum and difference coefficients, and T.
/// (Of |q| alone: the fit has one angle node, and (n, −m) has the same |q| to the bit.)
#[inline]
pub(super) fn coefficients_at(
    fit: &KernelFit,
    spec: GridSpec,
    depth: Option<f64>,
    n: i64,
    m: i64,
) -> ([f64; MAX_NB], [f64; MAX_NB], f64) {
    let (qn, qx, qy, t) = output_t(spec, depth, n, m);
    let (cp, cm) = fit.output_coefficients(qn, qx, qy, t);
    (cp, cm, t)
}

/// |q|, q and T(|q|) of output (n, m).
#[inline]
pub(super) fn output_t(spec: GridSpec, depth: Option<f64>, n: i64, m: i64) -> (f64, f64, f64, f64) {
    let (qx, qy) = spec.wavevector(n, m);
    // (Not `hypot`: no overflow to guard against here, at a fraction of its cost.)
    let qn = (qx * qx + qy * qy).sqrt();
    (qn, qx, qy, resonance_t(qn, depth))
}

/// The output coefficients of the kept outputs (lines 0 ..= o_x, columns −o_y ..= o_y),
/// n_sum + n_diff + 1 values a cell: the sum basis's, the difference powers', T; held
/// for columns 0 ..= o_y (column −m reads m's).
pub(super) struct Outputs {
    values: Vec<f64>,
    n_sum: usize,
    n_diff: usize,
    columns: usize,
}

impl Outputs {
    fn new(fit: &KernelFit, spec: GridSpec, depth: Option<f64>, (ox, oy): (i64, i64)) -> Self {
        let (n_sum, n_diff) = (fit.bases.len(0), fit.bases.len(1));
        let stride = n_sum + n_diff + 1;
        let columns = (oy + 1).max(0) as usize;
        let lines = (ox + 1).max(0) as usize;
        let mut values = vec![0.0; lines * columns * stride];
        values
            .par_chunks_mut(columns * stride)
            .enumerate()
            .for_each(|(n, line)| {
                for (j, cell) in line.chunks_exact_mut(stride).enumerate() {
                    let (cp, cm, t) = coefficients_at(fit, spec, depth, n as i64, j as i64);
                    cell[..n_sum].copy_from_slice(&cp[..n_sum]);
                    cell[n_sum..n_sum + n_diff].copy_from_slice(&cm[..n_diff]);
                    cell[stride - 1] = t;
                }
            });
        Self {
            values,
            n_sum,
            n_diff,
            columns,
        }
    }

    /// The sum coefficients, the difference coefficients and T of output (n, ±m).
    #[inline]
    fn at(&self, n: usize, m: usize) -> ([f64; MAX_NB], [f64; MAX_NB], f64) {
        let stride = self.n_sum + self.n_diff + 1;
        let c = &self.values[(n * self.columns + m) * stride..][..stride];
        let (mut cp, mut cm) = ([0.0; MAX_NB], [0.0; MAX_NB]);
        cp[..self.n_sum].copy_from_slice(&c[..self.n_sum]);
        cm[..self.n_diff].copy_from_slice(&c[self.n_sum..self.n_sum + self.n_diff]);
        (cp, cm, c[stride - 1])
    }
}

/// How a share's value at a kept output is added to where the outputs are kept.
pub(super) type Put<'a, T> = &'a (dyn Fn(&mut T, C64) + Sync);

impl TransformBound {
    /// Tabulates the output coefficients for the frames to come (a sequence: the same at
    /// every time, 8 bytes × (the bases' functions + 1) an output kept of m ≥ 0; the
    /// same values as computed at each frame).
    pub fn keep_outputs(&mut self) {
        let o = (self.reach.0.o, self.reach.1.o);
        self.outputs = Some(Outputs::new(&self.fit, self.spec, self.depth, o));
    }

    /// Transforms the accumulators `acc` of share p of `passes` along y and adds them at
    /// each kept output (lines 0 ..= o_x, columns −o_y ..= o_y) by `put` to the rows of
    /// `to` (rows of `stride`, column m at m mod `stride`). They are the
    /// share's py/P_a rows of y of px, transformed along x already
    /// ([`super::stages::Passes`]); `fwd_b` and `fwd_s` transform py/P_a values in their
    /// precisions. The B terms' are the separable part, then the slots of `layout` times
    /// 2T and their output coefficients; the S·A terms' the slots times their
    /// coefficients. A few output lines n at a time, the columns n and −n of every
    /// accumulator are copied out and transformed there (no whole transposed array is
    /// made, and only the kept lines' columns are transformed). A share's transform at
    /// ky index m is the whole transform's part of its rows of y: times e^{−2πi m p/py},
    /// the shares add up to the whole.
    pub(super) fn gather<B: Real, S: Real, T: Send>(
        &self,
        (to, stride, put): (&mut [T], usize, Put<T>),
        acc: &Acc<B, S>,
        layout: &Layout,
        (p, passes): (usize, &Passes),
        (fwd_b, fwd_s): (&dyn Fft<B>, &dyn Fft<S>),
    ) {
        let (px, py) = (self.plan.px, self.plan.py);
        let len = passes.acc_len;
        let (n_b, n_acc) = (acc.b.len(), acc.b.len() + acc.sa.len());
        debug_assert_eq!((fwd_b.len(), fwd_s.len()), (len, len));
        let oy = self.reach.1.o;
        let columns = (2 * oy + 1).max(0) as usize;
        let (outputs, depth) = (&self.outputs, self.depth);
        // e^{−2πi ky p/py} of each ky < py (the share's twiddles; none in one share), and
        // ky's place in the share's transform.
        let turns = twiddles(py, p, passes.acc, -1.0);
        let fold = folds(py, len);
        const { assert!(ANGLE_NODES == 1, "output coefficients of |q| alone") };
        // Output lines a task: their columns n (and −n) are neighbours in each row.
        const LINES: usize = 4;
        to.par_chunks_mut((stride * LINES).max(1))
            .enumerate()
            .for_each_init(
                || ((Vec::new(), Vec::new()), (Vec::new(), Vec::new())),
                |(cols_b, cols_s), (c, lines)| {
                    let n0 = c * LINES;
                    let nl = lines.len() / stride.max(1);
                    // Column l < nl of accumulator f is line n0 + l's (x = n), column
                    // nl + l its mirror's (x = −n): at `(f·2nl + column)·len`.
                    let xs: Vec<usize> = (0..2 * nl)
                        .map(|l| {
                            let n = (n0 + l % nl) as i64;
                            bin_index(if l < nl { n } else { -n }, px)
                        })
                        .collect();
                    columns_of(&acc.b, (&xs, px), fwd_b, cols_b);
                    columns_of(&acc.sa, (&xs, px), fwd_s, cols_s);
                    let (cols_b, cols_s) = (&cols_b.0, &cols_s.0);
                    for (l, line) in lines.chunks_exact_mut(stride).enumerate() {
                        let n = (n0 + l) as i64;
                        // Without the table, the line's coefficients once for ±m.
                        let of_line: Vec<_> = match outputs {
                            Some(_) => Vec::new(),
                            None => (0..=oy)
                                .map(|m| coefficients_at(&self.fit, self.spec, depth, n, m))
                                .collect(),
                        };
                        for j in 0..columns {
                            let m = j as i64 - oy;
                            let (ky, ky_neg) = (bin_index(m, py), bin_index(-m, py));
                            let here = l * len + fold[ky] as usize;
                            let there = (nl + l) * len + fold[ky_neg] as usize;
                            // The sum (re) and difference (im) parts of accumulator f's
                            // packed transform.
                            let unpack = |f: usize| {
                                let (a, b) = if f < n_b {
                                    let at = f * 2 * nl * len;
                                    (wide(cols_b[at + here]), wide(cols_b[at + there]))
                                } else {
                                    let at = (f - n_b) * 2 * nl * len;
                                    (wide(cols_s[at + here]), wide(cols_s[at + there]))
                                };
                                let b = b.conj();
                                (0.5 * (a + b), (a - b) * C64::new(0.0, -0.5))
                            };
                            let (cp, cm, t) = match outputs {
                                Some(o) => o.at(n as usize, m.unsigned_abs() as usize),
                                None => of_line[m.unsigned_abs() as usize],
                            };
                            // (The difference terms nearest q = 0 are their pairs',
                            // [`Exact`].)
                            let exact_diff = t <= self.exact.t_max;
                            // A slot's part times its output coefficient (`k` 2T for the
                            // B terms, 1 for the S·A terms).
                            let weighted = |v: C64, p: Option<Part>, k: f64| match p {
                                Some(Part::Sum(l)) => v * (k * cp[l]),
                                Some(Part::Diff(m)) if !exact_diff => v * (k * cm[m]),
                                _ => C64::new(0.0, 0.0),
                            };
                            // This share's part, with its twiddle in several.
                            let (s, d) = unpack(0);
                            let mut part = s + if exact_diff { C64::new(0.0, 0.0) } else { d };
                            for (f, slot) in (1..n_b).zip(&layout.slots) {
                                let (s, d) = unpack(f);
                                part +=
                                    weighted(s, slot[0], 2.0 * t) + weighted(d, slot[1], 2.0 * t);
                            }
                            for (f, slot) in (n_b..n_acc).zip(&layout.slots) {
                                let (s, d) = unpack(f);
                                part += weighted(s, slot[0], 1.0) + weighted(d, slot[1], 1.0);
                            }
                            if !turns.is_empty() {
                                part *= turns[ky];
                            }
                            put(&mut line[bin_index(m, stride)], part);
                        }
                    }
                },
            );
    }
}

/// The columns `xs` of every accumulator of `accs` (rows of px), each transformed by
/// `fwd`, into `cols.0`: accumulator f's column l at (f·xs.len() + l)·len (`cols.1` the
/// transform's scratch).
fn columns_of<T: Real>(
    accs: &[Vec<Complex<T>>],
    (xs, px): (&[usize], usize),
    fwd: &dyn Fft<T>,
    (cols, scratch): &mut (Vec<Complex<T>>, Vec<Complex<T>>),
) {
    let len = fwd.len();
    let zero = Complex::new(T::of(0.0), T::of(0.0));
    cols.resize(accs.len() * xs.len() * len, zero);
    scratch.resize(fwd.get_inplace_scratch_len(), zero);
    for (block, acc) in cols.chunks_exact_mut(xs.len() * len).zip(accs) {
        for (i, row) in acc.chunks_exact(px).enumerate() {
            for (l, &x) in xs.iter().enumerate() {
                block[l * len + i] = row[x];
            }
        }
        for col in block.chunks_exact_mut(len) {
            fwd.process_with_scratch(col, scratch);
        }
    }
}
