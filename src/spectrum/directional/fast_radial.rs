//! The grid's single-precision radial lane: the per-|k| parts of a grid value for the
//! common deep-water seas (the JONSWAP family with the cos^{2s} family without swell, or
//! plain cos²), from v = (ω/ωp)⁴ alone (see the `grid` module's docs).

use super::{G, Kernel, PI, SpreadKind, U_MAX};
use crate::fastmath::{exp2_f32, log2_f32};
use crate::simd::multiversion;
use crate::spectrum::spreading::log2_np_f32;

const LOG2_E: f64 = std::f64::consts::LOG2_E;
const LOG2_E_F32: f32 = std::f32::consts::LOG2_E;

/// The fast radial lane takes v = (ω/ωp)⁴ below this and k² within [1/this, this]; other
/// lanes go through the double-precision radial part.
const FAST_RANGE: f64 = 1.2676506002282294e30; // 2^100
/// Largest spreading coefficient (s at the peak) of the fast lane (`log2_np_f32`'s range).
const FAST_S_MAX: f64 = 1e6;

/// The single-precision radial part of deep-water JONSWAP-family seas with the cos^{2s}
/// family (no swell) or plain cos² spreading.
#[derive(Debug, Clone, Copy)]
pub(super) struct FastRadial {
    /// G²/ωp⁴ (v = k²·this), and in single precision.
    c_v: f64,
    c_v32: f32,
    /// log2(A(2π)⁴·½·c_v²/G²) (− log2 π for plain cos²) minus the grid reference l₀.
    pub(super) base: f64,
    /// ln γ·log2 e (0: Pierson–Moskowitz, no γ term).
    ln_gamma2: f32,
    /// 1/(2σ²)·log2 e below and above the peak.
    c_low2: f32,
    c_high2: f32,
    /// cos^{2s} family: s = s0·2^(μ·y), y = ¼ log2 v − y_shift, μ = mu_lo (y < 0) or mu_hi.
    family: bool,
    s0: f32,
    mu_lo: f32,
    mu_hi: f32,
    y_shift: f32,
}

impl FastRadial {
    /// The fast lane's constants, if this kernel's sea is one it covers (see the module
    /// docs), relative to its grid reference [`Kernel::grid_l0`].
    pub(super) fn new(kern: &Kernel) -> Option<FastRadial> {
        let sh = kern.shape.as_ref()?;
        let exact = &kern.table.exact;
        let family = match kern.kind {
            SpreadKind::Family if exact.swell16 == 0.0 => true,
            SpreadKind::Cos2Plain => false,
            _ => return None,
        };
        if kern.depth != f64::INFINITY
            || sh.tma_h != f64::INFINITY
            || (family && !(exact.coef >= 0.0 && exact.coef <= FAST_S_MAX))
        {
            return None;
        }
        let c_v = G * G * sh.inv_wp4;
        let mut base = (sh.coef * 0.5 * c_v * c_v / (G * G)).log2();
        if !family {
            base -= PI.log2();
        }
        Some(FastRadial {
            c_v,
            c_v32: c_v as f32,
            base: base - kern.grid_l0,
            ln_gamma2: (sh.ln_gamma * LOG2_E) as f32,
            c_low2: (super::C_LOW * LOG2_E) as f32,
            c_high2: (super::C_HIGH * LOG2_E) as f32,
            family,
            s0: exact.coef as f32,
            mu_lo: exact.mu_lo as f32,
            mu_hi: exact.mu_hi as f32,
            y_shift: (sh.x_shift * LOG2_E) as f32,
        })
    }
}

/// `if c { a } else { b }` by bit masks (a select the compiler keeps in registers; a
/// plain `if` between two fields can become a gather from memory).
#[inline(always)]
fn select(c: bool, a: f32, b: f32) -> f32 {
    let m = (c as u32).wrapping_neg();
    f32::from_bits((a.to_bits() & m) | (b.to_bits() & !m))
}

/// The fast radial part's first stage: v = (ω/ωp)⁴ in single precision, and whether the
/// lane is in the fast range (else it takes the double-precision radial part).
#[inline(always)]
fn fast_v(fr: &FastRadial, k2: f64) -> (f32, bool) {
    let v = k2 * fr.c_v;
    let in_range = (v < FAST_RANGE) & (k2 < FAST_RANGE) & (k2 * FAST_RANGE > 1.0);
    (v as f32, in_range)
}

/// The fast radial part from v (single precision only; `off` = the line's constant, see
/// [`Kernel::grid_scale`]): (l, s, a first 1/|k| in single precision); l = −∞ where Ψ is
/// 0 (u = 1/v beyond `U_MAX`). `FAMILY` and `PEAKED` must equal `fr.family` and
/// `fr.ln_gamma2 != 0`.
#[inline(always)]
fn fast_core<const FAMILY: bool, const PEAKED: bool>(
    fr: &FastRadial,
    off: f32,
    v: f32,
) -> (f32, f32, f32) {
    let lv = log2_f32(v);
    let u = 1.0 / v;
    let mut e = -1.25 * LOG2_E_F32 * u;
    if PEAKED {
        let q = exp2_f32(0.25 * lv);
        let d = q - 1.0;
        let c = select(d <= 0.0, fr.c_low2, fr.c_high2);
        e += fr.ln_gamma2 * exp2_f32(-(d * d) * c);
    }
    let (s, lz) = if FAMILY {
        let y = 0.25 * lv - fr.y_shift;
        let mu = select(y < 0.0, fr.mu_lo, fr.mu_hi);
        let s = fr.s0 * exp2_f32(mu * y);
        (s, log2_np_f32(s))
    } else {
        (0.0, 0.0)
    };
    // 1/k² = c_v·u.
    let y0 = (fr.c_v32 * u).sqrt();
    let l = off + ((e - lz) - 2.0 * lv);
    let zero = u > U_MAX as f32;
    (
        if zero { f32::NEG_INFINITY } else { l },
        if zero { 0.0 } else { s },
        if zero { 0.0 } else { y0 },
    )
}

/// 1/|k| in double precision from its single-precision value (one Newton step).
#[inline(always)]
fn fast_inv_k(k2: f64, y0: f32) -> f64 {
    let y = f64::from(y0);
    y * (1.5 - 0.5 * k2 * y * y)
}

/// One lane of the fast radial part at k²: (l, s, 1/|k|, needs the double-precision
/// radial part), the three stages in a row.
#[inline(always)]
pub(super) fn fast_lane(fr: &FastRadial, off: f32, k2: f64) -> (f32, f32, f64, bool) {
    let (v, in_range) = fast_v(fr, k2);
    let (l, s, y0) = match (fr.family, fr.ln_gamma2 != 0.0) {
        (true, false) => fast_core::<true, false>(fr, off, v),
        (true, true) => fast_core::<true, true>(fr, off, v),
        (false, false) => fast_core::<false, false>(fr, off, v),
        (false, true) => fast_core::<false, true>(fr, off, v),
    };
    (l, s, fast_inv_k(k2, y0), !in_range)
}

multiversion! {
    @on
    /// [`fast_v`] of every k²; true if a lane is out of the fast range (flagged).
    pub(super) fn fast_v_pass_on(isa: Isa, fr: &FastRadial, k2: &[f64], v: &mut [f32], flags: &mut [u8]) -> bool {
        let n = k2.len();
        let (v, flags) = (&mut v[..n], &mut flags[..n]);
        let mut any = 0u8;
        for i in 0..n {
            let ok;
            (v[i], ok) = fast_v(fr, k2[i]);
            flags[i] = !ok as u8;
            any |= !ok as u8;
        }
        any != 0
    }
}

multiversion! {
    @on
    /// [`fast_core`] of every v (single precision only: sixteen lanes with AVX-512).
    pub(super) fn fast_core_pass_on(
        isa: Isa,
        fr: &FastRadial,
        off: f32,
        v: &[f32],
        l: &mut [f32],
        s: &mut [f32],
        y0: &mut [f32],
    ) {
        #[inline(always)]
        fn run<const FAMILY: bool, const PEAKED: bool>(
            fr: &FastRadial,
            off: f32,
            v: &[f32],
            l: &mut [f32],
            s: &mut [f32],
            y0: &mut [f32],
        ) {
            let n = v.len();
            let (l, s, y0) = (&mut l[..n], &mut s[..n], &mut y0[..n]);
            for i in 0..n {
                (l[i], s[i], y0[i]) = fast_core::<FAMILY, PEAKED>(fr, off, v[i]);
            }
        }
        match (fr.family, fr.ln_gamma2 != 0.0) {
            (true, false) => run::<true, false>(fr, off, v, l, s, y0),
            (true, true) => run::<true, true>(fr, off, v, l, s, y0),
            (false, false) => run::<false, false>(fr, off, v, l, s, y0),
            (false, true) => run::<false, true>(fr, off, v, l, s, y0),
        }
    }
}

multiversion! {
    @on
    /// [`fast_inv_k`] of every lane.
    pub(super) fn fast_inv_k_pass_on(isa: Isa, k2: &[f64], y0: &[f32], inv_k: &mut [f64]) {
        let n = k2.len();
        let (y0, inv_k) = (&y0[..n], &mut inv_k[..n]);
        for i in 0..n {
            inv_k[i] = fast_inv_k(k2[i], y0[i]);
        }
    }
}
