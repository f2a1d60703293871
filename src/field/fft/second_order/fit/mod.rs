//! A separable (low-rank) form of the second-order kernels: what the `fitted` method
//! ([`super::transform`]) evaluates by transforms.
//!
//! With the signed partner j′ = (±k_j, ±s_j) (+ for the sum term, − for the difference
//! term: K⁻_ij is K⁺ of k_i and −k_j with s_j → −s_j), q = k_i + k_j′, T = |q| tanh(|q| d),
//! S = s_i + s_j′, and
//!
//! ```text
//! B = (k_i·k_j′ − R_i R_j)/(s_i s_j′)      A = Q_i/s_i + Q_j/s_j′
//! ```
//!
//! the kernel of [`super`] is exactly
//!
//! ```text
//! K = ¼ [B + R_i + R_j + (S·A + 2T·B) G],   G = 1/(S² − T)
//! ```
//!
//! B, R_i + R_j, S·A and 2T·B are sums of products of a function of k_i, a function of
//! k_j and (for T) a function of q: products of transformed fields. G alone mixes the
//! pair. At a fixed output q it is a function of one variable: of σ = s_i + s_j for the
//! sum term, of δ = s_i − s_j for the difference term. The low-rank forms replace it by
//!
//! ```text
//! sum, deep:    G̃ = Σ_{u ≤ v} c_uv(q) · ½ [w_u(s_i) w_v(s_j) + w_v(s_i) w_u(s_j)],   w_u(s) = (|s|/s_p)^u
//! sum, finite:  G̃ = Σ_{a ≤ m ≤ 3} c_ma(q) · (T/s_p²)^{m−a} (x_i² + x_j²)^a / (x_i x_j)^{m+1},   x = |s|/s_p
//! difference:   G̃ = Σ_{m ≤ M} c_m(q) · (δ²/T)^m / T   (M = 3 deep, 4 finite)
//! ```
//!
//! (the finite-depth sum form is the Neumann series of G = 1/(2 s_i s_j + P − T),
//! P = R_i + R_j, whose terms follow the near-resonant collinear pairs of shallow water)
//!
//! (the difference form is the Taylor series of −1/(T − δ²) in δ²/T < 1 with fitted
//! coefficients; δ^{2m} expands into products s_i^a s_j^{2m−a}), whose coefficients,
//! smooth functions of |q| (piecewise linear in √|q| between nodes), are fitted by least
//! squares to the pairs of the sea's own spectrum: pairs drawn with probability
//! ∝ E|h̃0(k_i)|²·E|h̃0(k_j)|², each weighted by the magnitude of its factor S·A + 2T·B,
//! so the fit minimizes the expected mean square of the bound waves' error. The same kind
//! of draw, independent of the fit's, estimates the relative rms error of the bound waves,
//! (E|η2,fit − η2|² / E|η2|²)^½ (the pairs of distinct waves have independent phases, so
//! their errors add in power).
//!
//! Every term of K̃ is then a product w(k_i)·w′(k_j)·h(q): two weighted linear fields
//! multiplied in physical space, one forward transform, a multiplication by h(q).
//! Measured against the exact pair sum (`transform/tests.rs`), the error is below 1 % of
//! η2's rms in deep water and at depths of 0.2–0.05 peak wavelengths (0.2–0.3 % at 0.1 λp);
//! the default `auto` takes the fitted method where the estimate is within its margin.

use crate::config::AUTO_MAX_ESTIMATE;
use crate::fastmath::powi;
use crate::spectrum::{Dispersion, Spectrum};
use rayon::prelude::*;

use super::{Component, depth_of};
use bases::FINITE_LIGHT_DIFF_POWERS;
pub use bases::{Bases, SumTerm, binomial};
use sample::{Sampler, spectrum_sample, uniform};

/// The most functions of a term's basis (the Neumann sum basis of finite depth).
pub const MAX_NB: usize = 10;
/// The most exponents e of the fields (|s|/s_p)^e a basis reads (−1 ..= 6 in deep water,
/// −4 ..= 8 at finite depth).
pub const POWERS: usize = 13;
/// Nodes of the coefficients in √|q|, and in the angle of q over [0, π).
const Q_NODES: usize = 24;
pub(super) const ANGLE_NODES: usize = 1;
/// Pairs drawn for the fit, and again for the error estimate.
const FIT_PAIRS: usize = 60_000;
/// The chunks of a term's draws summed apart (in parallel), then added in order.
const FIT_CHUNKS: usize = 4;
/// T = |q| tanh(|q| d) of an output wavevector of norm `qn` (|q| in deep water).
#[inline]
pub fn resonance_t(qn: f64, depth: Option<f64>) -> f64 {
    match depth {
        Some(d) => qn * tanh(qn * d),
        None => qn,
    }
}

/// The split of one kernel: K = ¼ [sep + num · G] (`g` the exact G, `ns` = num · G, or
/// −2B where S² = T, the pair formula's D = 0).
#[derive(Debug, Clone, Copy)]
pub struct Split {
    pub sep: f64,
    pub num: f64,
    pub ns: f64,
    /// |q| and T.
    pub qn: f64,
    pub qx: f64,
    pub qy: f64,
}

fn tanh(x: f64) -> f64 {
    crate::spectrum::spreading::tanh(x.abs()).copysign(x)
}

/// The split of K⁺ (`sign` = 1) or K⁻ (`sign` = −1) of two different waves.
#[inline]
pub fn split(a: &Component, b: &Component, sign: f64, depth: Option<f64>) -> Split {
    let (kxb, kyb, sb) = (sign * b.kx, sign * b.ky, sign * b.s);
    let dot = a.kx * kxb + a.ky * kyb;
    let (qx, qy) = (a.kx + kxb, a.ky + kyb);
    // (Not `hypot`: no overflow to guard against, at a fraction of its cost.)
    let qn = (qx * qx + qy * qy).sqrt();
    let t = resonance_t(qn, depth);
    let bb = (dot - a.r * b.r) / (a.s * sb);
    let aa = a.q / a.s + b.q / sb;
    let s = a.s + sb;
    let num = s * aa + 2.0 * t * bb;
    let den = s * s - t;
    let ns = if den != 0.0 { num / den } else { -2.0 * bb };
    Split {
        sep: bb + a.r + b.r,
        num,
        ns,
        qn,
        qx,
        qy,
    }
}

/// The fitted coefficients c_uv(|q|) of the sum (index 0) and difference (index 1) terms.
#[derive(Debug, Clone)]
pub struct KernelFit {
    /// s_p, √(rad/m): the scale of the basis.
    pub s_ref: f64,
    /// √|q| of the nodes, √(rad/m).
    nodes: Vec<f64>,
    /// [term][node][basis function].
    coef: [Vec<[f64; MAX_NB]>; 2],
    /// The bases of the two terms.
    pub bases: Bases,
    /// Angle nodes over [0, π).
    na: usize,
    /// The estimated relative rms error of the bound waves (independent draws).
    pub rel_rms_error: f64,
    depth: Option<f64>,
}

/// Where (kx, ky) lies in the grid's resolved box (|kx| < kx_N, |ky| < ky_N).
#[derive(Debug, Clone, Copy)]
pub struct Box2 {
    pub kx_max: f64,
    pub ky_max: f64,
}

impl Box2 {
    /// The resolved box of `setup`'s grid: below the Nyquist wavenumber on each axis.
    pub fn of(setup: &super::SpectrumSetup) -> Self {
        let (dkx, dky) = setup.dk();
        Self {
            kx_max: dkx * setup.spec.nx as f64 / 2.0,
            ky_max: dky * setup.spec.ny as f64 / 2.0,
        }
    }

    #[inline]
    pub fn contains(&self, kx: f64, ky: f64) -> bool {
        kx.abs() < self.kx_max && ky.abs() < self.ky_max
    }
}

/// Where the fit's pairs come from and land: the box of the paired waves, the box of the
/// outputs kept, the least E|h̃0|² of a paired cell (0: every wave of the box) and the
/// largest |k| of a paired wave (infinite: every wave of the box; the convergence limit
/// is a circle, and the waves of the box beyond it, never paired, would draw the fit and
/// its estimate to short nearly opposed pairs that do not occur).
#[derive(Debug, Clone, Copy)]
pub struct Region {
    pub waves: Box2,
    pub outputs: Box2,
    pub floor: f64,
    pub k_max: f64,
}

impl Region {
    /// Every resolved wave of `setup`'s grid, every resolved output.
    pub fn of(setup: &super::SpectrumSetup) -> Self {
        let b = Box2::of(setup);
        Self {
            waves: b,
            outputs: b,
            floor: 0.0,
            k_max: f64::INFINITY,
        }
    }
}

/// Hat weights of (√|q|, angle of q mod π): (node, weight) four times.
#[inline]
fn hats2(nodes: &[f64], na: usize, qn: f64, qx: f64, qy: f64) -> [(usize, f64); 4] {
    let h = hats(nodes, qn);
    if na == 1 {
        return [(h[0].0, h[0].1), (h[1].0, h[1].1), (0, 0.0), (0, 0.0)];
    }
    let a = qy.atan2(qx).rem_euclid(std::f64::consts::PI) / std::f64::consts::PI * na as f64;
    let i0 = (a.floor() as usize).min(na - 1);
    let f = a - i0 as f64;
    let i1 = (i0 + 1) % na;
    [
        (h[0].0 * na + i0, h[0].1 * (1.0 - f)),
        (h[0].0 * na + i1, h[0].1 * f),
        (h[1].0 * na + i0, h[1].1 * (1.0 - f)),
        (h[1].0 * na + i1, h[1].1 * f),
    ]
}

/// Hat weights of √|q| between nodes: (node, weight) twice.
#[inline]
fn hats(nodes: &[f64], qn: f64) -> [(usize, f64); 2] {
    let x = qn.sqrt();
    let last = nodes.len() - 1;
    if x >= nodes[last] {
        return [(last, 1.0), (last, 0.0)];
    }
    let step = nodes[1] - nodes[0];
    // (The cast truncates and saturates: floor and max(0) for every value, NaN to 0,
    // without a call to `floor` where the processor has no rounding instruction.)
    let i = ((x - nodes[0]) / step) as usize;
    let i = i.min(last - 1);
    let f = ((x - nodes[i]) / step).clamp(0.0, 1.0);
    [(i, 1.0 - f), (i + 1, f)]
}

impl KernelFit {
    /// Fits the coefficients to the pairs of `spectrum` in `region` on a grid of cell `dk`
    /// (deterministic: fixed draws).
    pub fn new(
        spectrum: &dyn Spectrum,
        dispersion: Dispersion,
        region: Region,
        dk: (f64, f64),
    ) -> Self {
        // (The spectrum's sample does not depend on the bases: drawn once.)
        let sample = spectrum_sample(spectrum, dispersion, region, dk);
        let fit = |bases: Bases| Self::of_sample(&sample, depth_of(dispersion), region, bases);
        match dispersion {
            Dispersion::Deep => fit(Bases::for_depth(None)),
            Dispersion::Finite { depth_m } => {
                // The lighter difference basis where its estimate is within what `auto`
                // accepts, else the fuller one.
                let fuller = Bases::for_depth(Some(depth_m));
                let light = fit(fuller.clone().with_diff_powers(FINITE_LIGHT_DIFF_POWERS));
                if light.rel_rms_error <= AUTO_MAX_ESTIMATE {
                    light
                } else {
                    fit(fuller)
                }
            }
        }
    }

    /// [`Self::new`] with the bases `bases`.
    pub fn with_bases(
        spectrum: &dyn Spectrum,
        dispersion: Dispersion,
        region: Region,
        dk: (f64, f64),
        bases: Bases,
    ) -> Self {
        let sample = spectrum_sample(spectrum, dispersion, region, dk);
        Self::of_sample(&sample, depth_of(dispersion), region, bases)
    }

    /// The fit of the bases `bases` to the pairs of the spectrum's sample `(waves,
    /// weights)` ([`spectrum_sample`]) at depth `depth`.
    fn of_sample(
        (waves, weights): &(Vec<Component>, Vec<f64>),
        depth: Option<f64>,
        region: Region,
        bases: Bases,
    ) -> Self {
        let bounds = region.outputs;
        let q_max = bounds.kx_max.hypot(bounds.ky_max);
        let (qn_count, na) = (Q_NODES, ANGLE_NODES);
        let nodes: Vec<f64> = (0..qn_count)
            .map(|i| q_max.sqrt() * i as f64 / (qn_count - 1) as f64)
            .collect();
        // (Each node's coefficients in a fixed array, zero beyond the term's count: the
        // blend of two nodes is then one loop of fixed length.)
        let empty = || vec![[0.0; MAX_NB]; qn_count * na];
        if waves.is_empty() {
            return Self {
                s_ref: 1.0,
                nodes,
                coef: [empty(), empty()],
                bases,
                na,
                rel_rms_error: 0.0,
                depth,
            };
        }
        // s_p: the s of the sample's largest weight.
        let ip = (0..waves.len())
            .max_by(|&a, &b| weights[a].total_cmp(&weights[b]))
            .expect("non-empty");
        let s_ref = waves[ip].s;
        let sampler = Sampler::new(weights);
        // The drawn pairs of draw stream `salt` of two different waves whose sum (`sign`
        // = 1) or difference (−1) falls on the grid, with the split of their kernel.
        let (waves, sampler) = (&waves[..], &sampler);
        let pairs = move |salt: u64, sign: f64, chunk: usize| {
            let per = FIT_PAIRS.div_ceil(FIT_CHUNKS);
            (chunk * per..((chunk + 1) * per).min(FIT_PAIRS)).filter_map(move |t| {
                let (u, v) = uniform(t as u64, salt);
                let (i, j) = (sampler.pick(u), sampler.pick(v));
                if i == j {
                    return None;
                }
                let (a, b) = (&waves[i], &waves[j]);
                let sp = split(a, b, sign, depth);
                bounds.contains(sp.qx, sp.qy).then_some((a, b, sp))
            })
        };
        // The two terms' normal equations, each a sum of FIT_CHUNKS partial sums in their
        // draws' order (a task a chunk of draws, added in chunk order: the same sums at any
        // thread count).
        let solve = |term: usize, sign: f64| {
            let nb = bases.len(term);
            let dim = qn_count * na * nb;
            let normal = |chunk: usize| {
                let mut ata = vec![0.0; dim * dim];
                let mut atb = vec![0.0; dim];
                for (a, b, sp) in pairs(2 * term as u64, sign, chunk) {
                    let phi = bases.eval(a, b, s_ref, term, resonance_t(sp.qn, depth));
                    let h = hats2(&nodes, na, sp.qn, sp.qx, sp.qy);
                    // The functions of the output's nodes (one or two adjacent nodes of
                    // √|q|, a single angle node: the unknowns start .. start + n, in
                    // order).
                    const { assert!(ANGLE_NODES == 1, "adjacent nodes: one angle node") };
                    let mut val = [0.0f64; 2 * MAX_NB];
                    let (mut start, mut n) = (0, 0);
                    for &(node, hw) in h.iter().filter(|h| h.1 != 0.0) {
                        if n == 0 {
                            start = node * nb;
                        }
                        debug_assert_eq!(start + n, node * nb);
                        for &p in phi.iter().take(nb) {
                            val[n] = hw * p * sp.num;
                            n += 1;
                        }
                    }
                    // The lower triangle only: all that the Cholesky solve reads.
                    for x in 0..n {
                        atb[start + x] += val[x] * sp.ns;
                        let row = (start + x) * dim + start;
                        let vx = val[x];
                        for (a, &vy) in ata[row..=row + x].iter_mut().zip(&val[..=x]) {
                            *a += vx * vy;
                        }
                    }
                }
                (ata, atb)
            };
            let (mut ata, mut atb) = in_chunks(normal, |(ata, atb), (pa, pb)| {
                ata.iter_mut().zip(&pa).for_each(|(a, p)| *a += p);
                atb.iter_mut().zip(&pb).for_each(|(a, p)| *a += p);
            });
            let sol = solve_ridge(&mut ata, &mut atb, dim);
            let mut c = empty();
            for (node, row) in c.iter_mut().enumerate() {
                row[..nb].copy_from_slice(&sol[node * nb..(node + 1) * nb]);
            }
            c
        };
        let (sum_c, diff_c) = rayon::join(|| solve(0, 1.0), || solve(1, -1.0));
        let coef = [sum_c, diff_c];
        let mut fit = Self {
            s_ref,
            nodes,
            coef,
            bases,
            na,
            rel_rms_error: 0.0,
            depth,
        };
        // The error estimate from draws independent of the fit's (a task a chunk of a
        // term's draws, each summed in its draws' order, the chunks added in order).
        let estimate = |term: usize, sign: f64| {
            let chunk = |c: usize| {
                let (mut err2, mut tot2) = (0.0, 0.0);
                for (a, b, sp) in pairs(2 * term as u64 + 1, sign, c) {
                    let approx = fit.g(term, a, b, &sp) * sp.num;
                    let k = 0.25 * (sp.sep + sp.ns);
                    err2 += (0.25 * (sp.ns - approx)).powi(2);
                    tot2 += k * k;
                }
                (err2, tot2)
            };
            in_chunks(chunk, |acc, p| {
                acc.0 += p.0;
                acc.1 += p.1;
            })
        };
        let (s, d) = rayon::join(|| estimate(0, 1.0), || estimate(1, -1.0));
        let (err2, tot2) = (s.0 + d.0, s.1 + d.1);
        fit.rel_rms_error = if tot2 > 0.0 {
            (err2 / tot2).sqrt()
        } else {
            0.0
        };
        fit
    }

    /// G̃ of the sum (term 0) or difference (term 1) of two waves of split `sp` (its
    /// output q and |q|).
    pub fn g(&self, term: usize, a: &Component, b: &Component, sp: &Split) -> f64 {
        let t = resonance_t(sp.qn, self.depth);
        let phi = self.bases.eval(a, b, self.s_ref, term, t);
        let c = self.coefficients(term, self.hats(sp.qn, sp.qx, sp.qy));
        (0..self.bases.len(term)).map(|l| c[l] * phi[l]).sum()
    }

    /// The nodes of output q (of norm `qn`) and their weights.
    #[inline]
    fn hats(&self, qn: f64, qx: f64, qy: f64) -> [(usize, f64); 4] {
        hats2(&self.nodes, self.na, qn, qx, qy)
    }

    /// The fitted coefficients of a term's basis at an output of nodes `hats` (beyond
    /// the term's count zero).
    fn coefficients(&self, term: usize, hats: [(usize, f64); 4]) -> [f64; MAX_NB] {
        let mut c = [0.0; MAX_NB];
        // (A node of weight 0 adds nothing.)
        for (node, hw) in hats.into_iter().filter(|h| h.1 != 0.0) {
            for (v, &k) in c.iter_mut().zip(&self.coef[term][node]) {
                *v += hw * k;
            }
        }
        c
    }

    /// What multiplies the two terms' product fields at output q = (qx, qy) of norm `qn`
    /// and T = `t` once transformed: the coefficients times the basis's function of the
    /// output, (T/s_p²)^t of a sum function, (s_p²/T)^m / T of the difference power m (0
    /// at q = 0).
    pub fn output_coefficients(
        &self,
        qn: f64,
        qx: f64,
        qy: f64,
        t: f64,
    ) -> ([f64; MAX_NB], [f64; MAX_NB]) {
        let hats = self.hats(qn, qx, qy);
        let mut sum = self.coefficients(0, hats);
        let tt = t / (self.s_ref * self.s_ref);
        for (v, f) in sum.iter_mut().zip(&self.bases.sum) {
            if f.t_power != 0 {
                *v *= powi(tt, f.t_power);
            }
        }
        let mut diff = self.coefficients(1, hats);
        let mut scale = 1.0 / t;
        for v in diff.iter_mut().take(self.bases.diff_powers + 1) {
            *v = if t > 0.0 { *v * scale } else { 0.0 };
            scale *= self.s_ref * self.s_ref / t;
        }
        (sum, diff)
    }

    /// The approximate kernel ¼[sep + num·G̃] of two different waves.
    pub fn kernel(
        &self,
        a: &Component,
        b: &Component,
        sign: f64,
        depth: Option<f64>,
    ) -> (f64, Split) {
        let sp = split(a, b, sign, depth);
        let term = usize::from(sign < 0.0);
        (0.25 * (sp.sep + sp.num * self.g(term, a, b, &sp)), sp)
    }
}

/// The sum over the FIT_CHUNKS chunks of a term's draws of `part(chunk)`, the parts made
/// in parallel and added by `add` in chunk order (the same sum at any thread count).
fn in_chunks<T: Send>(part: impl Fn(usize) -> T + Sync, add: impl Fn(&mut T, T)) -> T {
    let parts: Vec<T> = (0..FIT_CHUNKS).into_par_iter().map(&part).collect();
    let mut parts = parts.into_iter();
    let mut sum = parts.next().expect("at least one chunk");
    for p in parts {
        add(&mut sum, p);
    }
    sum
}

/// Solves (AᵀA + λI)x = Aᵀb by Cholesky, λ a small fraction of the mean diagonal (rows
/// without data get x = 0); reads AᵀA's lower triangle and diagonal only.
fn solve_ridge(ata: &mut [f64], atb: &mut [f64], dim: usize) -> Vec<f64> {
    let mean_diag = (0..dim).map(|i| ata[i * dim + i]).sum::<f64>() / dim as f64;
    let lambda = 1e-9 * mean_diag.max(1e-300);
    for i in 0..dim {
        ata[i * dim + i] += lambda;
    }
    // Cholesky in place (lower).
    for j in 0..dim {
        let mut d = ata[j * dim + j];
        for k in 0..j {
            d -= ata[j * dim + k] * ata[j * dim + k];
        }
        let d = d.max(1e-300).sqrt();
        ata[j * dim + j] = d;
        for i in j + 1..dim {
            let mut s = ata[i * dim + j];
            for k in 0..j {
                s -= ata[i * dim + k] * ata[j * dim + k];
            }
            ata[i * dim + j] = s / d;
        }
    }
    let mut y = atb.to_vec();
    for i in 0..dim {
        let mut s = y[i];
        for k in 0..i {
            s -= ata[i * dim + k] * y[k];
        }
        y[i] = s / ata[i * dim + i];
    }
    for i in (0..dim).rev() {
        let mut s = y[i];
        for k in i + 1..dim {
            s -= ata[k * dim + i] * y[k];
        }
        y[i] = s / ata[i * dim + i];
    }
    y
}

mod bases;
mod sample;
#[cfg(test)]
mod tests;
