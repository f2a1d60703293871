//! The exact pair sum on the grid (see [`super`]): every pair of paired components adds
//! a_i a_j K (with the pair's phase) to the cell of k_i ± k_j of a full-plane array.
//!
//! One task per output kx line sums its pairs in a fixed order (lines a ≤ b with
//! n_a + n_b = n_q, then i, then j ascending; the difference terms likewise), so the
//! field does not depend on the number of threads. The kernels of one component against
//! a run of partners on one kx line are computed as a whole line ([`Columns`]): a
//! branch-free loop over the partners' columns that the compiler vectorizes, compiled for
//! each instruction set by [`multiversion!`], performing the scalar kernels' operations
//! in the same order (so the same bits as [`super::kernel_plus`] and [`super::kernel_minus`] pair by
//! pair, which a test checks).

use std::ops::Range;

use rayon::prelude::*;

use super::{C64, Component, SecondOrder, SpectrumSetup, on_grid, resolved_span, self_kernels};
use crate::fastmath;
use crate::grid::signed_index;
use crate::simd::{Isa, multiversion};
use crate::spectrum::spreading::tanh_series;

/// The kernels of one component (index i) against a run of partners js on one kx line:
/// `out[j − js.start]`. `plus` includes j = i (K⁺_ii); `minus` leaves the value at
/// j = i unused (the set-down of one wave is exact, [`self_kernels`]).
pub trait LineKernels: Sync {
    fn plus(&self, i: usize, js: Range<usize>, out: &mut [f64]);
    fn minus(&self, i: usize, js: Range<usize>, out: &mut [f64]);
}

/// The components' kernel inputs as columns (the order of `comps`), for whole-line
/// kernels.
pub struct Columns {
    isa: Isa,
    /// The water depth, m; 0 in deep water (`deep`).
    depth: f64,
    deep: bool,
    kx: Vec<f64>,
    ky: Vec<f64>,
    /// k², R, √R, k² − R².
    kk: Vec<f64>,
    r: Vec<f64>,
    s: Vec<f64>,
    q: Vec<f64>,
    /// The ky index m (the outputs' index, not a kernel input).
    m: Vec<i64>,
}

impl Columns {
    pub fn of(comps: &[Component], depth: Option<f64>) -> Self {
        let col = |f: fn(&Component) -> f64| comps.iter().map(f).collect::<Vec<f64>>();
        Self {
            isa: Isa::detect(),
            depth: depth.unwrap_or(0.0),
            deep: depth.is_none(),
            kx: col(|c| c.kx),
            ky: col(|c| c.ky),
            kk: col(|c| c.k * c.k),
            r: col(|c| c.r),
            s: col(|c| c.s),
            q: col(|c| c.q),
            m: comps.iter().map(|c| c.m).collect(),
        }
    }

    /// The single wave i as the scalars the line kernels take.
    #[inline(always)]
    fn one(&self, i: usize) -> [f64; 6] {
        [
            self.kx[i], self.ky[i], self.kk[i], self.r[i], self.s[i], self.q[i],
        ]
    }

    #[inline(always)]
    fn run(&self, js: Range<usize>) -> [&[f64]; 6] {
        [
            &self.kx[js.clone()],
            &self.ky[js.clone()],
            &self.kk[js.clone()],
            &self.r[js.clone()],
            &self.s[js.clone()],
            &self.q[js],
        ]
    }
}

impl LineKernels for Columns {
    fn plus(&self, i: usize, js: Range<usize>, out: &mut [f64]) {
        let (a, b) = (self.one(i), self.run(js));
        kernel_line(self.isa, a, b, 1.0, self.deep, self.depth, out);
    }

    fn minus(&self, i: usize, js: Range<usize>, out: &mut [f64]) {
        let (a, b) = (self.one(i), self.run(js));
        kernel_line(self.isa, a, b, -1.0, self.deep, self.depth, out);
    }
}

/// [`crate::spectrum::spreading::tanh`] of x ≥ 0 without branches: the same bits (its
/// three ranges computed and one chosen), so it vectorizes.
#[inline(always)]
fn tanh_nonnegative(x: f64) -> f64 {
    let series = tanh_series(x);
    // −2x lies in the fast range of exp wherever this branch is chosen (0.1 ≤ x ≤ 20).
    let e = fastmath::exp_fast(-2.0 * x);
    let mid = (1.0 - e) / (1.0 + e);
    if x < 0.1 {
        series
    } else if x > 20.0 {
        1.0
    } else {
        mid
    }
}

/// T = k tanh(k d), or k in deep water.
#[inline(always)]
fn resonance(k: f64, deep: bool, depth: f64) -> f64 {
    if deep {
        k
    } else {
        k * tanh_nonnegative(k * depth)
    }
}

multiversion! {
    @on
    /// `out[j] = kernel_plus(a, b_j)` bit for bit (a and b as [`Columns`] hold them) with
    /// `sign` = 1, and `kernel_minus(a, b_j)` with −1: K⁻ is K⁺ of the partner
    /// (−k_j, −s_j), and negating those negates every intermediate exactly.
    fn kernel_line(isa: Isa, a: [f64; 6], b: [&[f64]; 6], sign: f64, deep: bool, depth: f64, out: &mut [f64]) {
        let [ax, ay, akk, ar, as_, aq] = a;
        let [bx, by, bkk, br, bs, bq] = b;
        let n = out.len();
        let (bx, by, bkk, br, bs, bq) = (&bx[..n], &by[..n], &bkk[..n], &br[..n], &bs[..n], &bq[..n]);
        for j in 0..n {
            let (bxj, byj, bsj) = (sign * bx[j], sign * by[j], sign * bs[j]);
            let dot = ax * bxj + ay * byj;
            let kp = (akk + bkk[j] + 2.0 * dot).max(0.0).sqrt();
            let tp = resonance(kp, deep, depth);
            let rr = ar * br[j];
            let sp = as_ + bsj;
            let den = sp * sp - tp;
            let num = sp * (as_ * bq[j] + bsj * aq) + 2.0 * sp * sp * (dot - rr);
            let d = num / den;
            let d = if den != 0.0 { d } else { 0.0 };
            out[j] = 0.25 * ((d - (dot - rr)) / (as_ * bsj) + ar + br[j]);
        }
    }
}

/// Where [`SecondOrder::row_pairs`] hands the weighted pairs: `(i, sign, js, (re, im))`.
pub(super) type AddPairs<'a> = dyn FnMut(usize, i64, Range<usize>, (&[f64], &[f64])) + 'a;

/// The complex amplitudes b_i of the paired components, and as columns.
pub(super) struct Amps {
    pub b: Vec<C64>,
    re: Vec<f64>,
    im: Vec<f64>,
}

impl Amps {
    pub fn new(b: Vec<C64>) -> Self {
        let (re, im) = b.iter().map(|v| (v.re, v.im)).unzip();
        Self { b, re, im }
    }
}

/// Kernels given pair by pair (the fitted kernels in the tests), as line kernels.
pub struct PairwiseKernels<'a, P, M> {
    pub comps: &'a [Component],
    /// `plus(a, b, a is b)` and `minus(a, b)` of different waves.
    pub plus: P,
    pub minus: M,
}

impl<P, M> LineKernels for PairwiseKernels<'_, P, M>
where
    P: Fn(&Component, &Component, bool) -> f64 + Sync,
    M: Fn(&Component, &Component) -> f64 + Sync,
{
    fn plus(&self, i: usize, js: Range<usize>, out: &mut [f64]) {
        let c = self.comps;
        for (o, j) in out.iter_mut().zip(js) {
            *o = (self.plus)(&c[i], &c[j], i == j);
        }
    }

    fn minus(&self, i: usize, js: Range<usize>, out: &mut [f64]) {
        let c = self.comps;
        for (o, j) in out.iter_mut().zip(js) {
            *o = if i == j {
                0.0
            } else {
                (self.minus)(&c[i], &c[j])
            };
        }
    }
}

impl SecondOrder {
    /// The components' kernel inputs as columns, made at the first call.
    pub(super) fn columns(&self) -> &Columns {
        self.columns
            .get_or_init(|| Columns::of(&self.comps, self.depth))
    }

    /// The full-plane Z of the bound waves at `setup`'s time (nx lines of ny, both in FFT
    /// order), and the sum and difference pairs kept on the grid.
    pub fn bound_plane(&self, setup: &SpectrumSetup) -> (Vec<C64>, u64, u64) {
        self.bound_plane_with(setup, self.columns())
    }

    /// [`Self::bound_plane`] with the kernels `plus(a, b, a is b)` and `minus(a, b)` of
    /// different waves (the set-down of one wave stays exact).
    pub fn bound_plane_by<P, M>(
        &self,
        setup: &SpectrumSetup,
        plus: P,
        minus: M,
    ) -> (Vec<C64>, u64, u64)
    where
        P: Fn(&Component, &Component, bool) -> f64 + Sync,
        M: Fn(&Component, &Component) -> f64 + Sync,
    {
        let kernels = PairwiseKernels {
            comps: &self.comps,
            plus,
            minus,
        };
        self.bound_plane_with(setup, &kernels)
    }

    fn bound_plane_with(
        &self,
        setup: &SpectrumSetup,
        kernels: &dyn LineKernels,
    ) -> (Vec<C64>, u64, u64) {
        let (nx, ny) = (self.nx, self.ny);
        let b = Amps::new(self.amplitudes(setup));
        let columns = self.columns();
        let (ms, isa) = (&columns.m, columns.isa);
        let mut z = vec![C64::new(0.0, 0.0); nx * ny];
        let counts: Vec<(u64, u64)> = z
            .par_chunks_mut(ny)
            .enumerate()
            .map(|(row, zline)| {
                // The outputs m = m_i ± m_j of consecutive kept partners are consecutive
                // (ascending for sums, descending for differences): one run each side of
                // where the output's index wraps.
                let mut add = |i: usize, sign: i64, js: Range<usize>, v: (&[f64], &[f64])| {
                    let (mi, m) = (ms[i], &ms[js]);
                    let out = |mj: i64| mi + sign * mj;
                    let wrap = if sign > 0 {
                        m.partition_point(|&mj| out(mj) < 0)
                    } else {
                        m.partition_point(|&mj| out(mj) >= 0)
                    };
                    let (neg, pos) = if sign > 0 {
                        (0..wrap, wrap..m.len())
                    } else {
                        (wrap..m.len(), 0..wrap)
                    };
                    for (range, offset) in [(neg, ny as i64), (pos, 0)] {
                        if range.is_empty() {
                            continue;
                        }
                        let (a, b) = (range.start, range.end);
                        if m[b - 1] - m[a] == (b - a - 1) as i64 {
                            let (vr, vi) = (&v.0[a..b], &v.1[a..b]);
                            if sign > 0 {
                                let at = (out(m[a]) + offset) as usize;
                                add_run(isa, &mut zline[at..at + (b - a)], vr, vi, false);
                            } else {
                                let at = (out(m[b - 1]) + offset) as usize;
                                add_run(isa, &mut zline[at..at + (b - a)], vr, vi, true);
                            }
                            continue;
                        }
                        for j in range {
                            zline[(out(m[j]) + offset) as usize] += C64::new(v.0[j], v.1[j]);
                        }
                    }
                };
                self.row_pairs(signed_index(row, nx), &b, kernels, &mut add)
            })
            .collect();
        let (s, d) = counts.iter().fold((0, 0), |(s, d), &(a, b)| (s + a, d + b));
        (z, s, d)
    }

    /// The pairs of output kx line `nq`, in the fixed order of the module notes: for each
    /// wave i and run of partners js whose outputs m_i ± m_j (+ for sums, `sign` = 1; −
    /// for differences) lie on the grid, `add(i, sign, js, v)` with the weighted pairs
    /// v_j = b_i·b_j′·2K (b_j′ = conj b_j for differences; the self-pair's set-down
    /// exact). Returns the sum and difference pairs kept.
    pub(super) fn row_pairs(
        &self,
        nq: i64,
        amps: &Amps,
        kernels: &dyn LineKernels,
        add: &mut AddPairs,
    ) -> (u64, u64) {
        if !on_grid(nq, self.nx) {
            return (0, 0);
        }
        let (b, bre, bim) = (&amps.b, &amps.re, &amps.im);
        let columns = self.columns();
        let (ms, isa) = (&columns.m, columns.isa);
        let longest = self.lines.iter().map(|r| r.len()).max().unwrap_or(0);
        // The resolved outputs m: lo ..= hi.
        let (lo, hi) = resolved_span(self.ny);
        let mut kv = vec![0.0; longest];
        let mut vre = vec![0.0; longest];
        let mut vim = vec![0.0; longest];
        let (mut sums, mut diffs) = (0u64, 0u64);
        // The pairs of wave i with the partners of js whose output is on the grid (one
        // run: the partners are in ascending m): kernels, weights, `add`.
        let mut pairs_of = |i: usize, js: Range<usize>, sum: bool| -> u64 {
            let (mi, sign) = (ms[i], if sum { 1 } else { -1 });
            let m = &ms[js.clone()];
            let (first, last) = if sum {
                (
                    m.partition_point(|&mj| mi + mj < lo),
                    m.partition_point(|&mj| mi + mj <= hi),
                )
            } else {
                (
                    m.partition_point(|&mj| mi - mj > hi),
                    m.partition_point(|&mj| mi - mj >= lo),
                )
            };
            let js = js.start + first..js.start + last.max(first);
            let n = js.len();
            if n == 0 {
                return 0;
            }
            let (kv, vre, vim) = (&mut kv[..n], &mut vre[..n], &mut vim[..n]);
            if sum {
                kernels.plus(i, js.clone(), kv);
            } else {
                kernels.minus(i, js.clone(), kv);
            }
            let conj = if sum { 1.0 } else { -1.0 };
            let bj = (&bre[js.clone()], &bim[js.clone()]);
            weigh(isa, (bre[i], bim[i]), conj, bj, kv, vre, vim);
            if js.start == i {
                // The self-pair, counted once; its set-down is exact.
                let v = if sum {
                    b[i] * b[i] * kv[0]
                } else {
                    b[i] * b[i].conj() * self_kernels(&self.comps[i], self.depth).1
                };
                (vre[0], vim[0]) = (v.re, v.im);
            }
            add(i, sign, js, (vre, vim));
            n as u64
        };
        // Sum terms: lines a ≤ b with a + b = nq; within a line, i ≤ j.
        for &na in &self.occupied {
            let nb = nq - na;
            if nb < na {
                break;
            }
            let lb = self.line(nb);
            for i in self.line(na) {
                let js = if na == nb { i..lb.end } else { lb.clone() };
                sums += pairs_of(i, js, true);
            }
        }
        // Difference terms, oriented so that nq = n_a − n_b ≥ 0; on nq = 0, i ≤ j.
        if nq >= 0 {
            for &na in &self.occupied {
                let lb = self.line(na - nq);
                for i in self.line(na) {
                    let js = if nq == 0 { i..lb.end } else { lb.clone() };
                    diffs += pairs_of(i, js, false);
                }
            }
        }
        (sums, diffs)
    }
}

multiversion! {
    @on
    /// `z[j] += (vre[j], vim[j])`, or with the values in reverse order (`reversed`).
    fn add_run(isa: Isa, z: &mut [C64], vre: &[f64], vim: &[f64], reversed: bool) {
        let n = z.len();
        let (vre, vim) = (&vre[..n], &vim[..n]);
        if reversed {
            for (z, (r, i)) in z.iter_mut().zip(vre.iter().rev().zip(vim.iter().rev())) {
                z.re += r;
                z.im += i;
            }
        } else {
            for (z, (r, i)) in z.iter_mut().zip(vre.iter().zip(vim.iter())) {
                z.re += r;
                z.im += i;
            }
        }
    }
}

multiversion! {
    @on
    /// `v_j = b_i · b_j′ · 2 k_j` with b_j′ = b_j (`conj` = 1, sum terms) or its conjugate
    /// (−1, difference terms), as `Complex` computes it.
    fn weigh(
        isa: Isa,
        bi: (f64, f64),
        conj: f64,
        bj: (&[f64], &[f64]),
        k: &[f64],
        vre: &mut [f64],
        vim: &mut [f64],
    ) {
        let n = k.len();
        let (br, bm) = (&bj.0[..n], &bj.1[..n]);
        let (vre, vim) = (&mut vre[..n], &mut vim[..n]);
        for j in 0..n {
            let (cr, ci) = (br[j], conj * bm[j]);
            let re = bi.0 * cr - bi.1 * ci;
            let im = bi.0 * ci + bi.1 * cr;
            let f = 2.0 * k[j];
            vre[j] = re * f;
            vim[j] = im * f;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{kernel_minus, kernel_plus};
    use super::*;

    /// Waves of every kind the pair sum meets: near-equal, opposing, short on long,
    /// shallow and deep, including a pair whose resonance denominator vanishes.
    fn waves(depth: Option<f64>) -> Vec<Component> {
        let mut v = Vec::new();
        for (i, &k) in [0.003, 0.02, 0.031, 0.0311, 0.2, 1.3, 4.0]
            .iter()
            .enumerate()
        {
            for a in 0..7 {
                let th = a as f64 * 0.9 + i as f64 * 0.1;
                v.push(Component::new(k * th.cos(), k * th.sin(), 0.1, 0.2, depth));
            }
        }
        v.push(Component::new(0.05, 0.0, 0.1, 0.0, depth));
        v.push(Component::new(-0.05, 0.0, 0.1, 0.0, depth));
        v
    }

    #[test]
    fn the_line_kernels_give_the_pair_kernels_bits() {
        for depth in [None, Some(0.7), Some(18.0), Some(400.0)] {
            let comps = waves(depth);
            for isa in Isa::available() {
                let cols = Columns {
                    isa,
                    ..Columns::of(&comps, depth)
                };
                let mut out = vec![0.0; comps.len()];
                for i in 0..comps.len() {
                    cols.plus(i, 0..comps.len(), &mut out);
                    for (j, &v) in out.iter().enumerate() {
                        let want = kernel_plus(&comps[i], &comps[j], depth);
                        assert_eq!(v.to_bits(), want.to_bits(), "K+ {i} {j} {depth:?} {isa:?}");
                    }
                    cols.minus(i, 0..comps.len(), &mut out);
                    for (j, &v) in out.iter().enumerate() {
                        let want = kernel_minus(&comps[i], &comps[j], depth);
                        assert_eq!(v.to_bits(), want.to_bits(), "K- {i} {j} {depth:?} {isa:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn the_branch_free_tanh_is_the_scalar_one() {
        for i in 0..4000 {
            let x = i as f64 * 0.0125;
            let want = crate::spectrum::spreading::tanh(x);
            assert_eq!(tanh_nonnegative(x).to_bits(), want.to_bits(), "{x}");
        }
        for x in [0.0, 0.0999999, 0.1, 20.0, 20.000001, 1e3, 1e9] {
            let want = crate::spectrum::spreading::tanh(x);
            assert_eq!(tanh_nonnegative(x).to_bits(), want.to_bits(), "{x}");
        }
    }
}
