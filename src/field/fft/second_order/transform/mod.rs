//! The bound waves of the fitted kernels ([`super::fit`]) by transforms: each term of
//! K̃ = ¼[B + R_i + R_j + (S·A + 2T·B)·G̃] is a product of two weighted linear fields in
//! physical space, one forward transform and a multiplication by a function of the output
//! wavevector. Exactly the pair sum of K̃ (up to rounding), at the cost of a few dozen
//! transforms of a grid padded by 3/2 per axis, so that no sum or difference of two
//! resolved wavevectors wraps onto a kept output. The non-default
//! `spectrum.nonlinear_method = "fitted"` (see docs/methods.md for its error and cost).
//!
//! With A_f(x) = Σ_i f(k_i) b_i e^{ik_i·x} over every component (b_i = a_i e^{i(φ_i − ω_i t)})
//! the sum terms are Re(A_f A_g) and the difference terms Re(A_f conj A_g); the diagonal
//! of the difference terms (q = 0) is replaced by the exact set-down Σ a_i² K⁻_ii.

use std::sync::Arc;

use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::fit::{BASIS_PAIRS, Box2, DIFF_POWERS, EXPONENTS, KernelFit, resonance_t};
use super::{
    C64, Component, HalfSpectrum, SecondOrder, SecondOrderInfo, SpectrumSetup, on_grid,
    self_kernels,
};
use crate::fastmath;
use crate::grid::signed_index;

/// An even length ≥ 3n/2.
fn padded(n: usize) -> usize {
    let p = (3 * n).div_ceil(2);
    p + p % 2
}

/// 2D transforms of a px × py grid (rows of py).
struct Plan {
    px: usize,
    py: usize,
    inv_x: Arc<dyn Fft<f64>>,
    inv_y: Arc<dyn Fft<f64>>,
    fwd_x: Arc<dyn Fft<f64>>,
    fwd_y: Arc<dyn Fft<f64>>,
}

impl Plan {
    fn new(px: usize, py: usize) -> Self {
        let mut p = FftPlanner::new();
        Self {
            px,
            py,
            inv_x: p.plan_fft_inverse(px),
            inv_y: p.plan_fft_inverse(py),
            fwd_x: p.plan_fft_forward(px),
            fwd_y: p.plan_fft_forward(py),
        }
    }

    /// Rows of `b` transformed by `fb`, transposed, rows of `a` transformed by `fa`:
    /// `data` (a rows of b) becomes b rows of a.
    fn two_d(data: &mut Vec<C64>, a: usize, b: usize, fa: &dyn Fft<f64>, fb: &dyn Fft<f64>) {
        data.par_chunks_mut(b).for_each(|row| fb.process(row));
        let src = &*data;
        let mut t = vec![C64::new(0.0, 0.0); a * b];
        t.par_chunks_mut(a).enumerate().for_each(|(j, row)| {
            for (i, v) in row.iter_mut().enumerate() {
                *v = src[i * b + j];
            }
        });
        t.par_chunks_mut(a).for_each(|row| fa.process(row));
        *data = t;
    }

    /// Spectrum (px rows of py, kx by row) → field (py rows of px, y by row).
    fn inverse(&self, data: &mut Vec<C64>) {
        Self::two_d(data, self.px, self.py, &*self.inv_x, &*self.inv_y);
    }

    /// Field (py rows of px) → spectrum (px rows of py).
    fn forward(&self, data: &mut Vec<C64>) {
        Self::two_d(data, self.py, self.px, &*self.fwd_y, &*self.fwd_x);
    }
}

/// The single-wave factors of the products.
#[derive(Clone, Copy, PartialEq)]
enum Factor {
    /// k_x/s, k_y/s, s (the B terms).
    X,
    Y,
    V,
    /// Q/s, Q, 1 (the S·A terms of finite depth).
    U,
    W1,
    W0,
    /// R (the R_i + R_j term).
    R,
}

impl Factor {
    fn of(self, c: &Component) -> f64 {
        match self {
            Factor::X => c.kx / c.s,
            Factor::Y => c.ky / c.s,
            Factor::V => c.s,
            Factor::U => c.q / c.s,
            Factor::W1 => c.q,
            Factor::W0 => 1.0,
            Factor::R => c.r,
        }
    }
}

/// δ^{2m} = (x_i − x_j)^{2m} = Σ_a w_a x_i^a x_j^{2m−a}: the terms (a, w_a).
fn expansion(m: usize) -> impl Iterator<Item = (usize, f64)> {
    let n = 2 * m;
    let mut binom = 1.0;
    (0..=n).map(move |a| {
        let w = if a % 2 == 0 { binom } else { -binom };
        binom = binom * (n - a) as f64 / (a + 1) as f64;
        (a, w)
    })
}

/// Adds `scale`·Σ_a w_a Re(f_a conj g_{2m−a}) (the terms of [`expansion`]) to the
/// difference part (im) of `acc`, in one pass.
fn add_power(acc: &mut [C64], f: &[Vec<C64>], g: &[Vec<C64>], m: usize, scale: f64) {
    const CHUNK: usize = 4096;
    let terms: Vec<(usize, f64)> = expansion(m).collect();
    acc.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
        let at = c * CHUNK;
        for (x, o) in out.iter_mut().enumerate() {
            let mut d = 0.0;
            for &(a, w) in &terms {
                d += w * (f[a][at + x] * g[2 * m - a][at + x].conj()).re;
            }
            o.im += scale * d;
        }
    });
}

/// The bound waves of a set of components through the fitted kernels, by transforms.
pub struct TransformBound {
    comps: Vec<Component>,
    depth: Option<f64>,
    nx: usize,
    ny: usize,
    plan: Plan,
    fit: KernelFit,
}

impl TransformBound {
    pub fn new(
        comps: Vec<Component>,
        nx: usize,
        ny: usize,
        depth: Option<f64>,
        fit: KernelFit,
    ) -> Self {
        Self {
            comps,
            depth,
            nx,
            ny,
            plan: Plan::new(padded(nx), padded(ny)),
            fit,
        }
    }

    /// Every component of `setup` (its draws; the time is not used), the kernels fitted to
    /// its spectrum, and what the sidecar records (the dropped pairs counted).
    pub fn for_setup(setup: &SpectrumSetup) -> (Self, SecondOrderInfo) {
        let all = SecondOrder::new(setup, 1.0);
        let (nx, ny) = (setup.spec.nx, setup.spec.ny);
        let (dkx, dky) = setup.dk();
        let bounds = Box2::of(setup);
        let fit = KernelFit::new(setup.spectrum, setup.dispersion, bounds, (dkx, dky));
        let mut info = all.info.clone();
        let depth = all.depth;
        let me = Self::new(all.comps, nx, ny, depth, fit);
        let (sums, diffs) = me.dropped_pairs();
        info.sum_pairs_dropped = sums;
        info.difference_pairs_dropped = diffs;
        info.method = Some("fitted".into());
        info.estimated_rel_rms_error = Some(me.fit.rel_rms_error);
        (me, info)
    }

    /// The field Σ_i f(k_i)·w(k_i)·b_i e^{ik_i·x} on the padded grid (py rows of px).
    fn field(&self, b: &[C64], f: Factor, exponent: Option<i32>) -> Vec<C64> {
        let (px, py) = (self.plan.px, self.plan.py);
        let mut data = vec![C64::new(0.0, 0.0); px * py];
        for (c, &bi) in self.comps.iter().zip(b) {
            let w = exponent.map_or(1.0, |e| (c.s.abs() / self.fit.s_ref).powi(e));
            let row = c.n.rem_euclid(px as i64) as usize;
            let col = c.m.rem_euclid(py as i64) as usize;
            data[row * py + col] += bi * (f.of(c) * w);
        }
        self.plan.inverse(&mut data);
        data
    }

    /// The fields of f·(|s|/s_p)^e for every exponent a term needs, e = −1 ..= 2·[`DIFF_POWERS`]
    /// (index e + 1): the sum basis' [`EXPONENTS`], the difference powers, and e = 0 for
    /// the separable part, each transformed once.
    fn powers(&self, b: &[C64], f: Factor) -> Vec<Vec<C64>> {
        (-1..=2 * DIFF_POWERS as i32)
            .map(|e| self.field(b, f, Some(e)))
            .collect()
    }

    /// The unordered pairs (self-pairs included) whose sum, and whose difference, falls
    /// off the grid: the pair counts at every output, from the transform of the squared
    /// occupancy field (the outputs the transforms leave out).
    pub fn dropped_pairs(&self) -> (u64, u64) {
        let (nx, ny) = (self.nx as i64, self.ny as i64);
        let (px, py) = (self.plan.px, self.plan.py);
        let ones = vec![C64::new(1.0, 0.0); self.comps.len()];
        let a = self.field(&ones, Factor::W0, None);
        let mut acc: Vec<C64> = a
            .iter()
            .map(|x| C64::new((x * x).re, x.norm_sqr()))
            .collect();
        drop(a);
        self.plan.forward(&mut acc);
        let (mut sums, mut diffs) = (0.0f64, 0.0f64);
        for row in 0..px {
            let n = signed_index(row, px);
            for col in 0..py {
                let m = signed_index(col, py);
                if on_grid(n, nx as usize) && on_grid(m, ny as usize) {
                    continue;
                }
                let here = acc[row * py + col];
                let there = acc[(-n).rem_euclid(px as i64) as usize * py
                    + (-m).rem_euclid(py as i64) as usize]
                    .conj();
                sums += 0.5 * (here + there).re;
                diffs += (0.5 * (here - there) * C64::new(0.0, -1.0)).re;
            }
        }
        let norm = (px * py) as f64;
        let doubled_off = self
            .comps
            .iter()
            .filter(|c| !(on_grid(2 * c.n, self.nx) && on_grid(2 * c.m, self.ny)))
            .count() as u64;
        let sums = (sums / norm).round() as u64;
        let diffs = (diffs / norm).round() as u64;
        ((sums + doubled_off) / 2, diffs / 2)
    }

    /// Adds the bound waves at `setup`'s time to `half`.
    pub fn add_to(&self, setup: &SpectrumSetup, half: &mut HalfSpectrum) {
        let (nx, ny) = (self.nx, self.ny);
        let (px, py) = (self.plan.px, self.plan.py);
        let b: Vec<C64> = self
            .comps
            .iter()
            .map(|c| {
                let wt = setup.omega_t(c.kx, c.ky);
                let (s, co) = fastmath::sin_cos(c.phi - wt);
                C64::new(2.0 * c.rho * co, 2.0 * c.rho * s)
            })
            .collect();
        let finite = self.depth.is_some();
        // Products: re = sum term Re(A_f A_g), im = difference term Re(A_f conj A_g).
        let accumulate = |acc: &mut [C64], f: &[C64], g: &[C64], sum_w: f64, diff_w: f64| {
            acc.par_iter_mut()
                .zip(f.par_iter().zip(g.par_iter()))
                .for_each(|(a, (x, y))| {
                    let s = if sum_w != 0.0 {
                        sum_w * (x * y).re
                    } else {
                        0.0
                    };
                    let d = if diff_w != 0.0 {
                        diff_w * (x * y.conj()).re
                    } else {
                        0.0
                    };
                    *a += C64::new(s, d);
                });
        };
        let transform = |mut acc: Vec<C64>| {
            self.plan.forward(&mut acc);
            acc
        };
        // The fields of exponent e are `powers[e + 1]`.
        let at = |e: i32| (e + 1) as usize;
        // The separable part B + R_i + R_j (its B terms with the factors' fields below).
        let mut sep = vec![C64::new(0.0, 0.0); px * py];
        {
            let one = self.field(&b, Factor::W0, None);
            let r = self.field(&b, Factor::R, None);
            accumulate(&mut sep, &r, &one, 2.0, 2.0);
        }
        // Group l holds the sum term's basis pair l (re) and the difference term's power
        // m = l (im): the B terms (multiplied by 2T c) and the S·A terms (by c).
        let pairs = BASIS_PAIRS;
        let zeros = || vec![vec![C64::new(0.0, 0.0); px * py]; pairs.len()];
        let mut b_acc = zeros();
        let types: &[(Factor, f64)] = &[(Factor::X, 1.0), (Factor::Y, 1.0), (Factor::V, -1.0)];
        for &(f, sign) in types {
            let powers = self.powers(&b, f);
            accumulate(&mut sep, &powers[at(0)], &powers[at(0)], sign, 1.0);
            for (acc, &(u, v)) in b_acc.iter_mut().zip(&pairs) {
                let (u, v) = (at(EXPONENTS[u]), at(EXPONENTS[v]));
                accumulate(acc, &powers[u], &powers[v], sign, 0.0);
            }
            for (m, acc) in b_acc.iter_mut().enumerate().take(DIFF_POWERS + 1) {
                add_power(acc, &powers[at(0)..], &powers[at(0)..], m, 1.0);
            }
        }
        let mut groups: Vec<(Vec<C64>, bool)> = vec![(transform(sep), false)];
        let mut sa_acc = Vec::new();
        if finite {
            sa_acc = zeros();
            for (f, g, sign) in [(Factor::W1, Factor::W0, 1.0), (Factor::U, Factor::V, -1.0)] {
                let (pf, pg) = (self.powers(&b, f), self.powers(&b, g));
                for (acc, &(u, v)) in sa_acc.iter_mut().zip(&pairs) {
                    let (u, v) = (at(EXPONENTS[u]), at(EXPONENTS[v]));
                    accumulate(acc, &pf[u], &pg[v], 1.0, 0.0);
                    accumulate(acc, &pf[v], &pg[u], 1.0, 0.0);
                }
                // Difference: S·A = Q_i + Q_j − (Q/s)_i s_j − s_i (Q/s)_j, each with its
                // mirror (the expansion is symmetric in a ↔ 2m − a).
                for (m, acc) in sa_acc.iter_mut().enumerate().take(DIFF_POWERS + 1) {
                    add_power(acc, &pf[at(0)..], &pg[at(0)..], m, 2.0 * sign);
                }
            }
        }
        for acc in b_acc {
            groups.push((transform(acc), true));
        }
        let sa: Vec<Vec<C64>> = sa_acc.into_iter().map(transform).collect();
        let depth = self.depth;
        let setdown: f64 = self
            .comps
            .iter()
            .map(|c| 4.0 * c.rho * c.rho * self_kernels(c, depth).1)
            .sum();
        let norm = 0.25 / (px * py) as f64;
        let fit = &self.fit;
        half.data
            .par_chunks_mut(ny)
            .enumerate()
            .for_each(|(n, line)| {
                let n = n as i64;
                if !on_grid(n, nx) {
                    return;
                }
                for (idx, v) in line.iter_mut().enumerate() {
                    let m = signed_index(idx, ny);
                    if !on_grid(m, ny) {
                        continue;
                    }
                    let here =
                        n.rem_euclid(px as i64) as usize * py + m.rem_euclid(py as i64) as usize;
                    let there = (-n).rem_euclid(px as i64) as usize * py
                        + (-m).rem_euclid(py as i64) as usize;
                    // The sum (re) and difference (im) parts of a packed transform.
                    let unpack = |f: &[C64]| {
                        let (a, b) = (f[here], f[there].conj());
                        (0.5 * (a + b), (a - b) * C64::new(0.0, -0.5))
                    };
                    let (qx, qy) = setup.wavevector(n, m);
                    let qn = qx.hypot(qy);
                    let t = resonance_t(qn, depth);
                    let cp = fit.coefficients(0, qx, qy);
                    // The difference powers: c_m (s_p² / T)^m / T on δ^{2m} in units of s_p.
                    let mut cm = fit.coefficients(1, qx, qy);
                    // (At q = 0 the set-down replaces the difference terms.)
                    let mut scale = 1.0 / t;
                    for c in cm.iter_mut() {
                        *c = if t > 0.0 { *c * scale } else { 0.0 };
                        scale *= fit.s_ref * fit.s_ref / t;
                    }
                    let zero_diff = n == 0 && m == 0;
                    let mut h = C64::new(0.0, 0.0);
                    for (g, (f, weighted)) in groups.iter().enumerate() {
                        let (s, d) = unpack(f);
                        let d = if zero_diff { C64::new(0.0, 0.0) } else { d };
                        if *weighted {
                            let l = g - 1;
                            h += s * (2.0 * t * cp[l]) + d * (2.0 * t * cm[l]);
                        } else {
                            h += s + d;
                        }
                    }
                    for (l, f) in sa.iter().enumerate() {
                        let (s, d) = unpack(f);
                        let d = if zero_diff { C64::new(0.0, 0.0) } else { d };
                        h += s * cp[l] + d * cm[l];
                    }
                    let mut h = h * norm;
                    if zero_diff {
                        h += C64::new(setdown, 0.0);
                    }
                    *v += Complex::new(h.re as f32, h.im as f32);
                }
            });
    }
}

#[cfg(test)]
mod tests;
