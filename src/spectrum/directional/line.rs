//! The double-precision radial part of Ψ for a whole line of wavevectors, in passes the
//! compiler vectorizes: the same operations as [`Kernel::radial`], in the same order, on
//! arrays (for the seas the grid's single-precision lane does not cover, see `grid`).
//! Each pass is compiled for the baseline, AVX2 and AVX-512 (`simd::multiversion`), uses
//! `fastmath`'s branch-free cores, and flags lanes outside their fast range, which the
//! scalar function then redoes; so every value equals the scalar one bit for bit.

use super::{
    C_HIGH, C_LOW, FrequencySpectrum, G, Kernel, PI, Radial, ShapeK, SpreadKind, SpreadTable,
    U_MAX, kitaigorodskii, tanh,
};
use crate::fastmath::{exp_fast, exp_is_special, ln_is_special, ln_positive_normal};
use crate::simd::{Isa, multiversion};

/// Largest γ-exponent argument the fast path takes (the scalar path uses exp(−a) up to
/// 700; the lanes in between are redone by it).
const GAMMA_ARG_FAST: f64 = 689.0;

/// The radial parts of a line, as arrays.
#[derive(Debug, Default)]
pub(super) struct RadialLine {
    pub inv_k: Vec<f64>,
    pub a: Vec<f64>,
    pub s: Vec<f64>,
    pub beta: Vec<f64>,
}

impl RadialLine {
    /// Length n (the contents are overwritten by every user).
    fn resize(&mut self, n: usize) {
        for v in [&mut self.inv_k, &mut self.a, &mut self.s, &mut self.beta] {
            v.resize(n, 0.0);
        }
    }

    fn set(&mut self, i: usize, r: Radial) {
        self.inv_k[i] = r.inv_k;
        self.a[i] = r.a;
        self.s[i] = r.s;
        self.beta[i] = r.beta;
    }
}

/// One wavevector's dispersion quantities: k², k, ω² and c_g/(kω⁵).
#[derive(Debug, Clone, Copy)]
struct Dispersed {
    k2: f64,
    k: f64,
    w2: f64,
    geo: f64,
}

multiversion! {
    @on
    /// The radial part before the spreading table: 1/k, the amplitude factor
    /// A(2π)⁴·c_g/(kω⁵)·Φ (into `out.a`), the exponent −5/4 u + r ln γ (into `scratch.e`)
    /// and the table's argument x (into `scratch.x`), for every k² of `k2` (`out` and
    /// `scratch` at least as long). Lanes that need the scalar function get a flag in
    /// `scratch.flags`; true if there is one.
    fn radial_first(
        isa: Isa,
        sh: &ShapeK,
        depth: f64,
        plain: bool,
        k2: &[f64],
        out: &mut RadialLine,
        scratch: &mut RadialScratch,
    ) -> bool {
        let deep = depth == f64::INFINITY;
        let peaked = sh.ln_gamma != 0.0;
        let tma = sh.tma_h != f64::INFINITY;
        let mut special = false;
        // One lane from ω², c_g/(kω⁵), k and the depth factor Φ(q): (1/k, amplitude factor,
        // exponent, x, needs the scalar function).
        #[inline(always)]
        fn lane(
            sh: &ShapeK,
            peaked: bool,
            plain: bool,
            d: Dispersed,
            phi_of: impl Fn(f64) -> f64,
        ) -> (f64, f64, f64, f64, bool) {
            let Dispersed { k2, k, w2, geo } = d;
            let v = w2 * w2 * sh.inv_wp4;
            let u = 1.0 / v;
            let q = v.sqrt().sqrt();
            let d = q - 1.0;
            let ga = d * d * if d <= 0.0 { C_LOW } else { C_HIGH };
            // ln γ · exp(−a) for a < 700 (the scalar rule), by a 0/1 factor so that nothing
            // branches (+0 is exact where it is absent; the fast range is redone beyond).
            let g = exp_fast(-ga.min(GAMMA_ARG_FAST));
            let on = (peaked & (ga < 700.0)) as u8 as f64;
            let add = on * (sh.ln_gamma * g);
            // ln computed on every lane (a table load inside a branch would stop the
            // compiler from vectorizing the loop).
            let lv = ln_positive_normal(v);
            let x = if plain { 0.0 } else { 0.25 * lv - sh.x_shift };
            let special = (peaked & (GAMMA_ARG_FAST..700.0).contains(&ga))
                | (k2 <= 0.0)
                | (k2 == f64::INFINITY)
                | (u > U_MAX)
                | ln_is_special(v);
            (1.0 / k, sh.coef * geo * phi_of(q), -1.25 * u + add, x, special)
        }
        // Deep water without the depth factor: a loop per value of `peaked`, so that
        // without a γ peak (Pierson–Moskowitz) its exponential is not computed at all.
        #[inline(always)]
        fn deep_run(
            sh: &ShapeK,
            peaked: bool,
            plain: bool,
            k2: &[f64],
            out: &mut RadialLine,
            scratch: &mut RadialScratch,
        ) -> bool {
            let n = k2.len();
            let (inv_k, a) = (&mut out.inv_k[..n], &mut out.a[..n]);
            let (e, x) = (&mut scratch.e[..n], &mut scratch.x[..n]);
            let flags = &mut scratch.flags[..n];
            let mut any = 0u8;
            for i in 0..n {
                let k = k2[i].sqrt();
                let geo = 0.5 / (G * G * k2[i] * k2[i]);
                let d = Dispersed {
                    k2: k2[i],
                    k,
                    w2: G * k,
                    geo,
                };
                let sp;
                (inv_k[i], a[i], e[i], x[i], sp) = lane(sh, peaked, plain, d, |_| 1.0);
                flags[i] = sp as u8;
                any |= sp as u8;
            }
            any != 0
        }
        if deep && !tma {
            special |= if peaked {
                deep_run(sh, true, plain, k2, out, scratch)
            } else {
                deep_run(sh, false, plain, k2, out, scratch)
            };
        } else {
            let phi_of = |q: f64| if tma { kitaigorodskii(q * sh.tma_h) } else { 1.0 };
            let n = k2.len();
            let (inv_k, a) = (&mut out.inv_k[..n], &mut out.a[..n]);
            let (e, x) = (&mut scratch.e[..n], &mut scratch.x[..n]);
            let flags = &mut scratch.flags[..n];
            for i in 0..n {
                let k = k2[i].sqrt();
                let (w2, geo) = if deep {
                    (G * k, 0.5 / (G * G * k2[i] * k2[i]))
                } else {
                    let kd = k * depth;
                    let t = tanh(kd);
                    let w2 = G * k * t;
                    (w2, G * (t + kd * (1.0 - t * t)) / (2.0 * k * w2 * w2 * w2))
                };
                let d = Dispersed {
                    k2: k2[i],
                    k,
                    w2,
                    geo,
                };
                let sp;
                (inv_k[i], a[i], e[i], x[i], sp) = lane(sh, peaked, plain, d, phi_of);
                flags[i] = sp as u8;
                special |= sp;
            }
        }
        special
    }
}

multiversion! {
    @on
    /// a ← a·exp(e − ln Z) (·1/π for plain cos²) for the first `n` lanes, with the
    /// table's [s, ln Z, β] at x (β only for Donelan–Banner, 0 otherwise), after
    /// [`radial_first`]. Lanes that need the scalar function get a flag; true if there
    /// is one.
    fn radial_second(
        isa: Isa,
        kern: &Kernel,
        plain: bool,
        n: usize,
        out: &mut RadialLine,
        scratch: &mut RadialScratch,
    ) -> bool {
        let (x, e, ln_z) = (&scratch.x[..n], &scratch.e[..n], &mut scratch.ln_z[..n]);
        let (a, s, beta) = (&mut out.a[..n], &mut out.s[..n], &mut out.beta[..n]);
        let flags = &mut scratch.flags[..n];
        let with_beta = kern.kind == SpreadKind::DonelanBanner;
        let mut any = 0u8;
        // The table (scalar loads), then the exponentials (vectorized).
        for i in 0..n {
            [s[i], ln_z[i], beta[i]] = if plain {
                [0.0, 0.0, 0.0]
            } else {
                kern.table.eval_in_range(x[i], with_beta)
            };
        }
        for i in 0..n {
            let arg = e[i] - ln_z[i];
            let sp = (!plain & !SpreadTable::in_range(x[i])) | exp_is_special(arg);
            let aa = a[i] * exp_fast(arg);
            a[i] = if plain { aa * (1.0 / PI) } else { aa };
            flags[i] |= sp as u8;
            any |= sp as u8;
        }
        any != 0
    }
}

/// Scratch of the radial passes: exponents, table arguments, ln Z, and the lanes the
/// scalar function redoes.
#[derive(Debug, Default)]
pub(super) struct RadialScratch {
    e: Vec<f64>,
    x: Vec<f64>,
    ln_z: Vec<f64>,
    flags: Vec<u8>,
}

impl RadialScratch {
    /// Length n (the contents are overwritten by the passes).
    fn resize(&mut self, n: usize) {
        for v in [&mut self.e, &mut self.x, &mut self.ln_z] {
            v.resize(n, 0.0);
        }
        self.flags.resize(n, 0);
    }
}

impl Kernel {
    /// The radial parts of every k² in `k2s` into `out`, bit for bit those of
    /// [`Kernel::radial`], with the passes on `isa`.
    pub(super) fn radial_line(
        &self,
        isa: Isa,
        k2s: &[f64],
        freq: &dyn FrequencySpectrum,
        scratch: &mut RadialScratch,
        out: &mut RadialLine,
    ) {
        let n = k2s.len();
        out.resize(n);
        let Some(sh) = &self.shape else {
            for (i, &k2) in k2s.iter().enumerate() {
                out.set(i, self.radial(k2, freq));
            }
            return;
        };
        let plain = self.kind == SpreadKind::Cos2Plain;
        scratch.resize(n);
        let first = radial_first(isa, sh, self.depth, plain, k2s, out, scratch);
        let second = radial_second(isa, self, plain, n, out, scratch);
        if first || second {
            // Lanes outside the fast ranges (k² = 0, u beyond the floor, huge γ
            // arguments, x outside the spreading table): the scalar function for those;
            // it is the reference.
            for (i, &k2) in k2s.iter().enumerate() {
                if scratch.flags[i] != 0 {
                    out.set(i, self.radial(k2, freq));
                }
            }
        }
    }
}
