//! The midpoint amplitude variances of the grid, in single-precision base-2 exponents.
//!
//! A 4096² spectrum has 16.7 million amplitude variances, nearly all of them midpoint
//! cells: P = ½·dkx·dky·a(|k|)·m(θ)·cos^{2s}(θ/2). Here each is computed as one power of
//! two, P = 2^(n₀ + l + s·log2((1 + c)/2))·m with c = cos θ:
//! - n₀ (an integer, per grid) and the constant in l put the exponent of the grid's peak
//!   cell near 0, so that the single-precision exponent keeps its relative precision
//!   where the energy is ([`Kernel::grid_scale`]);
//! - l(|k|) = log2(½·dkx·dky·a) − n₀ and s(|k|) come once per distinct k² (k and −k share
//!   them, and so do ky and −ky of a line in FFT order). For deep water, the JONSWAP family
//!   and the cos^{2s} family without swell or plain cos² (the common seas) they are computed
//!   in single precision from v = (ω/ωp)⁴ = G²k²/ωp⁴ alone: log2 a = const − 2 log2 v
//!   − log2 e·(5/4 v⁻¹ − ln γ·exp(−(v^¼ − 1)²/2σ²) + ln N_s), s = s₀·2^(μ·log2(f/fp))
//!   and log2 N_s by `log2_np_f32` (`fast_radial`); every other sea takes the
//!   double-precision radial part ([`Kernel::radial`]) and its logarithm;
//! - the power and the factor 2^(n₀ + …) are one `exp2_parts_f32` and an exact scaling to a
//!   double ([`crate::fastmath::scale_f64`]).
//!
//! Every pass is written once per lane ([`fast_lane`], [`value`]) and used both by the
//! scalar function ([`Kernel::grid_variance`]) and by the line passes (compiled for the
//! baseline, AVX2 and AVX-512 by `simd::multiversion`), so a line equals the single
//! values bit for bit. Against the double-precision Ψ, P is within 1e-6·(1 + |exponent|)
//! relative, where the exponent is log2 of P relative to the peak cell (tested: worst
//! 7.9e-7·(1 + |exponent|) over every model and spreading; within an octave of the peak
//! ~1e-7 for the seas on the double-precision radial part, up to 5e-7 for PM and 1.4e-6
//! for JONSWAP γ = 7 on the single-precision lane, whose exponent sums several terms of
//! a few units each); P below 2^−300 of the peak cell is 0.

use super::fast_radial::{fast_core_pass_on, fast_inv_k_pass_on, fast_lane, fast_v_pass_on};
use super::line::{RadialLine, RadialScratch};
use super::{FrequencySpectrum, Kernel, SpreadKind, half_one_plus_f32, power_f32};
use crate::fastmath::{
    exp2_parts_f32, ln, ln_is_special, ln_positive_normal, log2_unit_f32, scale_f64,
};
use crate::simd::{Isa, multiversion};
use crate::spectrum::mirror::{fft_mirrored, mirror_f32_on, mirror_f64_on};
use crate::spectrum::{LineQuery, PairOut};

const LOG2_E: f64 = std::f64::consts::LOG2_E;

/// Values whose exponent is below this (relative to the grid's peak cell, ≈ 1e-90) are 0.
const FLOOR_LOG2: f32 = -300.0;
/// The power of two of values below the floor (p·2^(this + n₀) is 0 for every n₀).
const BELOW_FLOOR: i32 = -(1 << 30);
/// Exponents are capped here (a value 2^(2^20) beyond the peak is +∞ anyway).
const CAP_LOG2: f32 = 1_048_576.0;

/// The per-|k| parts of a grid value: exponent l, spreading exponent s, 1/|k| and
/// Donelan–Banner's β.
#[derive(Debug, Clone, Copy)]
pub(super) struct GridLane {
    l: f32,
    s: f32,
    inv_k: f64,
    beta: f64,
}

/// The grid exponent of a double-precision radial value `a` (0 and subnormals: −∞).
#[inline(always)]
fn log2_relative(a: f64, l0: f64, frac: f64) -> f32 {
    if ln_is_special(a) {
        f32::NEG_INFINITY
    } else {
        ((ln_positive_normal(a) * LOG2_E - l0) + frac) as f32
    }
}

/// 2^(l + s·log2 b) as (p, n), p·2^n (n far below any double's range under the floor);
/// d = 1 − b (see [`log2_unit_f32`]).
#[inline(always)]
fn power_parts(l: f32, s: f32, b: f32, d: f32) -> (f32, i32) {
    let t = l + s * log2_unit_f32(b, d);
    let (p, n) = exp2_parts_f32(t.clamp(FLOOR_LOG2, CAP_LOG2));
    (p, if t >= FLOOR_LOG2 { n } else { BELOW_FLOOR })
}

/// P = 2^(n0 + l + s·log2((1 + c)/2))·m, 0 below the floor.
#[inline(always)]
fn value(l: f32, s: f32, c: f64, m: f64, n0: i32) -> f64 {
    let (p, n) = power_parts(l, s, half_one_plus_f32(c), half_one_plus_f32(-c));
    scale_f64(p, n + n0) * m
}

multiversion! {
    @on
    /// The grid exponents of double-precision radial values, and s in single precision.
    fn log2_pass_on(isa: Isa, l0: f64, frac: f64, r: &RadialLine, l: &mut [f32], s: &mut [f32]) {
        let n = l.len();
        let (a, rs, s) = (&r.a[..n], &r.s[..n], &mut s[..n]);
        for i in 0..n {
            l[i] = log2_relative(a[i], l0, frac);
            s[i] = power_f32(rs[i]);
        }
    }
}

multiversion! {
    @on
    /// The powers' arguments (1 + c)/2 in single precision at (kx, ky[j]) into `b.a[j]`
    /// and (1 − c)/2 (the argument at (−kx, −ky[j]), whose cosine is exactly −c) into
    /// `b.b[j]`, and c into `c` if `keep_c`; the wind direction is the kernel's.
    fn cos_pass_on(
        isa: Isa,
        keep_c: bool,
        kern: &Kernel,
        q: &LineQuery,
        inv_k: &[f64],
        c: &mut [f64],
        b: PairOut<f32>,
    ) {
        #[inline(always)]
        fn run<const KEEP_C: bool>(
            (wx, wy): (f64, f64),
            q: &LineQuery,
            inv_k: &[f64],
            c: &mut [f64],
            b: PairOut<f32>,
        ) {
            let (kx, ky) = (q.kx, q.ky);
            let n = ky.len();
            let (inv_k, c) = (&inv_k[..n], &mut c[..n]);
            let (ba, bb) = (&mut b.a[..n], &mut b.b[..n]);
            for j in 0..n {
                let ca = (kx * wx + ky[j] * wy) * inv_k[j];
                if KEEP_C {
                    c[j] = ca;
                }
                ba[j] = half_one_plus_f32(ca);
                bb[j] = half_one_plus_f32(-ca);
            }
        }
        let wind = (kern.wx, kern.wy);
        if keep_c {
            run::<true>(wind, q, inv_k, c, b)
        } else {
            run::<false>(wind, q, inv_k, c, b)
        }
    }
}

multiversion! {
    @on
    /// `(p[j], e[j]) = power_parts(l[j], s[j], b[j], d[j])`: single precision only, so
    /// sixteen lanes wide with AVX-512.
    fn power_pass_on(
        isa: Isa,
        l: &[f32],
        s: &[f32],
        b: &[f32],
        d: &[f32],
        p: &mut [f32],
        e: &mut [i32],
    ) {
        let n = b.len();
        let (l, s, d, p, e) = (&l[..n], &s[..n], &d[..n], &mut p[..n], &mut e[..n]);
        for j in 0..n {
            (p[j], e[j]) = power_parts(l[j], s[j], b[j], d[j]);
        }
    }
}

multiversion! {
    @on
    /// `out[j] = scale_f64(p[j], e[j] + n0) · m`, m = c[j]² for the cos² kinds, else 1.
    fn scale_pass_on(
        isa: Isa,
        cos2: bool,
        n0: i32,
        p: &[f32],
        e: &[i32],
        c: &[f64],
        out: &mut [f64],
    ) {
        let n = out.len();
        let (p, e) = (&p[..n], &e[..n]);
        if cos2 {
            let c = &c[..n];
            for j in 0..n {
                out[j] = scale_f64(p[j], e[j] + n0) * (c[j] * c[j]);
            }
        } else {
            for j in 0..n {
                out[j] = scale_f64(p[j], e[j] + n0);
            }
        }
    }
}

/// Entries per chunk of the value passes (their buffers stay in the L1 cache).
const CHUNK: usize = 512;

/// The values of the line's cells in both half-planes (see [`PairOut`]) for every
/// spreading but Donelan–Banner (m = c² for the cos² kinds, else 1), chunk by chunk, from
/// the per-|k| parts of the line.
fn value_passes(
    isa: Isa,
    kern: &Kernel,
    n0: i32,
    q: &LineQuery,
    lanes: LineLanes,
    out: PairOut<f64>,
    buf: &mut ValueBuffers,
) {
    let LineLanes { l, s, inv_k } = lanes;
    let PairOut { a: pa, b: pb } = out;
    let cos2 = kern.kind != SpreadKind::Family;
    let ValueBuffers { c, ba, bb, p, e } = buf;
    c.resize(CHUNK, 0.0);
    for v in [&mut *ba, &mut *bb, &mut *p] {
        v.resize(CHUNK, 0.0);
    }
    e.resize(CHUNK, 0);
    let n = q.ky.len();
    for start in (0..n).step_by(CHUNK) {
        let r = start..(start + CHUNK).min(n);
        let m = r.len();
        let (c, ba, bb, p, e) = (
            &mut c[..m],
            &mut ba[..m],
            &mut bb[..m],
            &mut p[..m],
            &mut e[..m],
        );
        let (part, inv_k, l, s) = (
            q.part(r.clone()),
            &inv_k[r.clone()],
            &l[r.clone()],
            &s[r.clone()],
        );
        cos_pass_on(isa, cos2, kern, &part, inv_k, c, PairOut { a: ba, b: bb });
        // (1 − c)/2 of one half-plane is (1 + c)/2 of the other; m = c² is the same.
        power_pass_on(isa, l, s, ba, bb, p, e);
        scale_pass_on(isa, cos2, n0, p, e, c, &mut pa[r.clone()]);
        power_pass_on(isa, l, s, bb, ba, p, e);
        scale_pass_on(isa, cos2, n0, p, e, c, &mut pb[r]);
    }
}

/// The per-|k| parts of every entry of a line: grid exponent l, spreading exponent s and
/// 1/|k|.
#[derive(Debug, Clone, Copy)]
struct LineLanes<'a> {
    l: &'a [f32],
    s: &'a [f32],
    inv_k: &'a [f64],
}

/// Chunk buffers of [`value_passes`].
#[derive(Debug, Default)]
pub(super) struct ValueBuffers {
    c: Vec<f64>,
    ba: Vec<f32>,
    bb: Vec<f32>,
    p: Vec<f32>,
    e: Vec<i32>,
}

/// Buffers of the grid passes, one set per thread.
#[derive(Debug, Default)]
pub(super) struct GridScratch {
    k2: Vec<f64>,
    /// The fast radial stages' v and single-precision 1/|k|.
    v: Vec<f32>,
    y0: Vec<f32>,
    flags: Vec<u8>,
    /// Per entry of the line: l, s, 1/|k|, β (computed for the distinct k², then mirrored).
    l: Vec<f32>,
    s: Vec<f32>,
    inv_k: Vec<f64>,
    beta: Vec<f64>,
    radial: RadialScratch,
    double: RadialLine,
    values: ValueBuffers,
}

impl Kernel {
    /// (n₀, frac) of a grid with cells dkx × dky: log2(½·dkx·dky) + l₀ = n₀ + frac, n₀ an
    /// integer (clamped to ±10⁴: beyond, every value is 0 or +∞ anyway), |frac| ≤ ½.
    pub(super) fn grid_scale(&self, dkx: f64, dky: f64) -> (i32, f64) {
        let b = ln(0.5 * dkx * dky) * LOG2_E + self.grid_l0;
        let n = b.round();
        (n.clamp(-1e4, 1e4) as i32, b - n)
    }

    /// The per-|k| parts of the grid value at k² (`frac` from [`Kernel::grid_scale`]).
    fn grid_lane(&self, k2: f64, frac: f64, freq: &dyn FrequencySpectrum) -> GridLane {
        if let Some(fr) = &self.fast {
            let off = (fr.base + frac) as f32;
            let (l, s, inv_k, special) = fast_lane(fr, off, k2);
            if !special {
                return GridLane {
                    l,
                    s,
                    inv_k,
                    beta: 0.0,
                };
            }
        }
        let r = self.radial(k2, freq);
        GridLane {
            l: log2_relative(r.a, self.grid_l0, frac),
            s: power_f32(r.s),
            inv_k: r.inv_k,
            beta: r.beta,
        }
    }

    /// The grid value at (kx, ky) from its per-|k| parts.
    fn grid_value(&self, g: &GridLane, kx: f64, ky: f64, n0: i32) -> f64 {
        let cu = kx * self.wx + ky * self.wy;
        let c = cu * g.inv_k;
        let m = match self.kind {
            SpreadKind::Family => 1.0,
            SpreadKind::Cos2Plain | SpreadKind::Cos2Swell => c * c,
            SpreadKind::DonelanBanner => {
                let su = (ky * self.wx - kx * self.wy).abs();
                super::sech2(g.beta * super::atan2_pos(su, cu))
            }
        };
        value(g.l, g.s, c, m, n0)
    }

    /// The midpoint amplitude variance ½·dkx·dky·Ψ(kx, ky) as the grid computes it (see
    /// the module docs).
    pub(super) fn grid_variance(
        &self,
        kx: f64,
        ky: f64,
        dkx: f64,
        dky: f64,
        freq: &dyn FrequencySpectrum,
    ) -> f64 {
        let (n0, frac) = self.grid_scale(dkx, dky);
        let g = self.grid_lane(kx * kx + ky * ky, frac, freq);
        self.grid_value(&g, kx, ky, n0)
    }

    /// [`Kernel::grid_variance`] of every cell of the line in both half-planes (see
    /// [`PairOut`]), bit for bit, in whole-line passes on `isa`.
    pub(super) fn grid_pair_line_on(
        &self,
        isa: Isa,
        freq: &dyn FrequencySpectrum,
        q: &LineQuery,
        out: PairOut<f64>,
        scratch: &mut GridScratch,
    ) {
        let LineQuery { kx, ky, dkx, dky } = *q;
        let n = ky.len();
        let GridScratch {
            k2,
            v,
            y0,
            flags,
            l,
            s,
            inv_k,
            beta,
            radial,
            double,
            values,
        } = scratch;
        // FFT order: ky[n − j] = −ky[j], so entries j and n − j share k².
        let mirrored = fft_mirrored(ky);
        let unique = if mirrored { n / 2 + 1 } else { n };
        k2.clear();
        k2.extend(ky[..unique].iter().map(|&y| kx * kx + y * y));
        let (n0, frac) = self.grid_scale(dkx, dky);
        let db = self.kind == SpreadKind::DonelanBanner;
        for v in [&mut *l, &mut *s] {
            v.resize(n, 0.0);
        }
        for v in [&mut *inv_k, &mut *beta] {
            v.resize(n, 0.0);
        }
        flags.resize(unique, 0);
        {
            let (l, s, inv_k) = (&mut l[..unique], &mut s[..unique], &mut inv_k[..unique]);
            match &self.fast {
                Some(fr) => {
                    let off = (fr.base + frac) as f32;
                    v.resize(unique, 0.0);
                    y0.resize(unique, 0.0);
                    let special = fast_v_pass_on(isa, fr, k2, v, flags);
                    fast_core_pass_on(isa, fr, off, v, l, s, y0);
                    fast_inv_k_pass_on(isa, k2, y0, inv_k);
                    if special {
                        for i in 0..unique {
                            if flags[i] != 0 {
                                let g = self.grid_lane(k2[i], frac, freq);
                                (l[i], s[i], inv_k[i]) = (g.l, g.s, g.inv_k);
                            }
                        }
                    }
                }
                None => {
                    self.radial_line(isa, k2, freq, radial, double);
                    log2_pass_on(isa, self.grid_l0, frac, double, l, s);
                    inv_k.copy_from_slice(&double.inv_k[..unique]);
                    if db {
                        beta[..unique].copy_from_slice(&double.beta[..unique]);
                    }
                }
            }
        }
        if mirrored {
            mirror_f32_on(isa, l, unique);
            mirror_f32_on(isa, s, unique);
            mirror_f64_on(isa, inv_k, unique);
            if db {
                mirror_f64_on(isa, beta, unique);
            }
        }
        let (l, s, inv_k, beta) = (&*l, &*s, &*inv_k, &*beta);
        if db {
            for j in 0..n {
                let g = GridLane {
                    l: l[j],
                    s: s[j],
                    inv_k: inv_k[j],
                    beta: beta[j],
                };
                out.a[j] = self.grid_value(&g, kx, ky[j], n0);
                out.b[j] = self.grid_value(&g, -kx, -ky[j], n0);
            }
            return;
        }
        let lanes = LineLanes { l, s, inv_k };
        value_passes(isa, self, n0, q, lanes, out, values);
    }
}
