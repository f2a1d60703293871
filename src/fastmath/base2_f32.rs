//! log2 x and 2^t in single precision, and `p·2^n` as an exact double.

/// integer, which sits in the low mantissa bits of the sum.
const ROUND_MAGIC_F32: f32 = 12_582_912.0;

/// log2 x for a positive, normal, finite `f32` (meaningless, but harmless, for other `x`):
/// straight-line code (one division) that the compiler vectorizes.
///
/// `x = 2^e·m`, `m ∈ [√½, √2)` from the bits; `log2 m = u·Q(u²)`, `u = (m − 1)/(m + 1)`,
/// `|u| ≤ 0.172`, with `Q` of degree 3 fitted to `2·atanh(u)/(u ln 2)` (error below 4e-10).
/// The result is within 1e-7·(1 + |log2 x|) (tested), the rounding of single precision.
#[inline(always)]
pub(crate) fn log2_f32(x: f32) -> f32 {
    log2_parts(x, None)
}

/// log2 b for `b ∈ [f32::MIN_POSITIVE, 1]` given also `d ≈ 1 − b` (both rounded from a
/// more precise value): for b ≥ √½ it takes `m − 1 = −d`, so that log2 b keeps the
/// relative precision of d near b = 1, where the rounding of b itself would cost up to
/// 9e-8 absolute (which a power b^s multiplies by s). Else as [`log2_f32`].
#[inline(always)]
pub(crate) fn log2_unit_f32(b: f32, d: f32) -> f32 {
    log2_parts(b, Some(d))
}

/// [`log2_f32`], with `1 − x` given for `x ∈ [√½, √2)` (see [`log2_unit_f32`]).
#[inline(always)]
#[allow(clippy::excessive_precision)]
fn log2_parts(x: f32, one_minus: Option<f32>) -> f32 {
    const SQRT_HALF_BITS: i32 = 0x3f35_04f3;
    const ONE_BITS: i32 = 0x3f80_0000;
    const Q: [f32; 4] = [2.885_39, 0.961_798_85, 0.576_714_5, 0.431_733];
    // x = 2^e·m: shifting the bits by bits(1) − bits(√½) moves the exponent boundary to √½.
    let shifted = (x.to_bits() as i32).wrapping_add(ONE_BITS - SQRT_HALF_BITS);
    let ei = (shifted >> 23) - 127;
    let e = ei as f32;
    let m = f32::from_bits(((shifted & 0x007f_ffff) + SQRT_HALF_BITS) as u32);
    let (num, den) = match one_minus {
        Some(d) if ei == 0 => (-d, 2.0 - d),
        _ => (m - 1.0, m + 1.0),
    };
    let u = num / den;
    let z = u * u;
    // Estrin's scheme (short dependency chains).
    e + u * ((Q[0] + z * Q[1]) + (z * z) * (Q[2] + z * Q[3]))
}

/// 2^t as `(p, n)`, `2^t = p·2^n`: `n = round(t)`, `p = 2^(t − n) ∈ [2^−½, 2^½]` by a
/// polynomial of degree 6 fitted on [−½, ½] (error below 3e-9), for `|t| < 2^22`;
/// straight-line code. `t − n` is exact, so p is within ~1e-7 relative of 2^(t − n).
#[inline(always)]
#[allow(clippy::excessive_precision, clippy::approx_constant)]
pub(crate) fn exp2_parts_f32(t: f32) -> (f32, i32) {
    const P: [f32; 7] = [
        1.0,
        0.693_147_2,
        0.240_226_51,
        0.055_503_272,
        0.009_618_026,
        0.001_340_043_2,
        0.000_154_697_32,
    ];
    let rounded = t + ROUND_MAGIC_F32;
    let n = rounded - ROUND_MAGIC_F32;
    let r = t - n;
    // Estrin's scheme (short dependency chains).
    let r2 = r * r;
    let p =
        ((P[0] + r * P[1]) + r2 * (P[2] + r * P[3])) + (r2 * r2) * ((P[4] + r * P[5]) + r2 * P[6]);
    let ni = (rounded.to_bits() as i32).wrapping_sub(ROUND_MAGIC_F32.to_bits() as i32);
    (p, ni)
}

/// 2^t in single precision for `t ≥ −126` (normal results); 0 below. Relative error ~1e-7.
#[inline(always)]
pub(crate) fn exp2_f32(t: f32) -> f32 {
    let (p, n) = exp2_parts_f32(t.max(-126.0));
    let v = p * f32::from_bits(((n.clamp(-126, 127) + 127) << 23) as u32);
    if t < -126.0 { 0.0 } else { v }
}

/// `p·2^e` as a double for `p ∈ [½, 2)`: exact for `e ∈ [−1022, 1023]` (a normal power of
/// two); 0 below (results under ~2e-308) and +∞ above. Straight-line code.
#[inline(always)]
pub(crate) fn scale_f64(p: f32, e: i32) -> f64 {
    // Exponent field 0 is the factor 0, 2047 is +∞.
    let field = (e.clamp(-1023, 1024) + 1023) as u64;
    f64::from(p) * f64::from_bits(field << 52)
}
