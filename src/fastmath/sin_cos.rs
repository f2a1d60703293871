//! sin x and cos x together (see the parent module for the algorithm and its accuracy).

use super::{ROUND_MAGIC, SIGN_MASK};

/// 2/π.
pub(super) const FRAC_2_PI: f64 = std::f64::consts::FRAC_2_PI;
/// π/2 = PIO2_1 + PIO2_2 + PIO2_3 (+ 4e-35): the first two have 27 significant bits, so
/// `k·PIO2_1` and `k·PIO2_2` are exact for `|k| < 2^26`.
pub(super) const PIO2_1: f64 = f64::from_bits(0x3FF9_21FB_5400_0000); // 1.570796325802803
pub(super) const PIO2_2: f64 = f64::from_bits(0x3E11_0B46_1000_0000); // 9.920935739593517e-10
pub(super) const PIO2_3: f64 = f64::from_bits(0x3C5A_6263_3145_C06E); // 5.721188726109832e-18
/// π/2 as a double-double (for the large-argument reduction).
pub(super) const PIO2_HI: f64 = f64::from_bits(0x3FF9_21FB_5444_2D18);
const PIO2_LO: f64 = f64::from_bits(0x3C91_A626_3314_5C07);
/// Cody–Waite reduction is used below this (|k| ≤ 6.4e7 < 2^26); Payne–Hanek above.
pub(crate) const SIN_COS_CW_LIMIT: f64 = 1.0e8;
/// fdlibm `__kernel_sin` `S1..S6`: sin r ≈ r + r³·(S1 + r²·S2 + … + r¹⁰·S6) on |r| ≤ π/4.
const SIN_S: [f64; 6] = [
    f64::from_bits(0xBFC5_5555_5555_5549), // -1.66666666666666324348e-01
    f64::from_bits(0x3F81_1111_1110_F8A6), // 8.33333333332248946124e-03
    f64::from_bits(0xBF2A_01A0_19C1_61D5), // -1.98412698298579493134e-04
    f64::from_bits(0x3EC7_1DE3_57B1_FE7D), // 2.75573137070700676789e-06
    f64::from_bits(0xBE5A_E5E6_8A2B_9CEB), // -2.50507602534068634195e-08
    f64::from_bits(0x3DE5_D93A_5ACF_D57C), // 1.58969099521155010221e-10
];
/// fdlibm `__kernel_cos` `C1..C6`: cos r ≈ 1 − r²/2 + r⁴·(C1 + r²·C2 + … + r¹⁰·C6).
const COS_C: [f64; 6] = [
    f64::from_bits(0x3FA5_5555_5555_554C), // 4.16666666666666019037e-02
    f64::from_bits(0xBF56_C16C_16C1_5177), // -1.38888888888741095749e-03
    f64::from_bits(0x3EFA_01A0_19CB_1590), // 2.48015872894767294178e-05
    f64::from_bits(0xBE92_7E4F_809C_52AD), // -2.75573143513906633035e-07
    f64::from_bits(0x3E21_EE9E_BDB4_B1C4), // 2.08757232129817482790e-09
    f64::from_bits(0xBDA8_FAE9_BE88_38D4), // -1.13596475577881948265e-11
];
/// Bits of 2/π after the binary point, preceded by 63 zero bits: bit `j` of this
/// big-endian bit string (bit 0 = most significant bit of word 0) is the bit of weight
/// `2^-(j-63)`. Enough for the largest finite double.
pub(super) const TWO_OVER_PI_BITS: [u64; 19] = [
    0x0000_0000_0000_0000,
    0xA2F9_836E_4E44_1529,
    0xFC27_57D1_F534_DDC0,
    0xDB62_9599_3C43_9041,
    0xFE51_63AB_DEBB_C561,
    0xB724_6E3A_424D_D2E0,
    0x0649_2EEA_09D1_921C,
    0xFE1D_EB1C_B129_A73E,
    0xE882_35F5_2EBB_4484,
    0xE99C_7026_B45F_7E41,
    0x3991_D639_8353_39F4,
    0x9C84_5F8B_BDF9_283B,
    0x1FF8_97FF_DE05_980F,
    0xEF2F_118B_5A0A_6D1F,
    0x6D36_7ECF_27CB_09B7,
    0x4F46_3F66_9E5F_EA2D,
    0x7527_BAC7_EBE5_F17B,
    0x3D07_39F7_8A52_92EA,
    0x6BFB_5FB1_1F8D_5D08,
];

/// (sin x, cos x) for finite x, accurate for |x| ≤ 1e8 (Cody–Waite reduction by π/2 with a
/// 3-part constant); NaN for non-finite x.
///
/// Beyond 1e8 a (slower, exact) Payne–Hanek reduction keeps the result accurate for every
/// finite x. Absolute error ≈ 1e-16; `sin_cos(±0) = (±0, 1)`, and
/// `sin_cos(−x)` is exactly `(−sin x, cos x)`.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if sin_cos_is_large(x) {
        return sin_cos_large(x);
    }
    sin_cos_cody_waite(x)
}

/// True for the `x` that [`sin_cos`] hands to its cold path: `|x| ≥ SIN_COS_CW_LIMIT`,
/// infinities and NaNs.
#[inline(always)]
pub(crate) fn sin_cos_is_large(x: f64) -> bool {
    x.abs() >= SIN_COS_CW_LIMIT || x.is_nan()
}

/// [`sin_cos`] for `|x| < SIN_COS_CW_LIMIT`, without the range check: straight-line,
/// branch-free code for loops that the compiler vectorizes. Bit-identical to [`sin_cos`]
/// for such `x`; for other `x` ([`sin_cos_is_large`]) the result is meaningless (but
/// computing it is harmless), and callers must use [`sin_cos`] instead.
#[inline(always)]
pub(crate) fn sin_cos_cody_waite(x: f64) -> (f64, f64) {
    let t = x * FRAC_2_PI + ROUND_MAGIC;
    let kf = t - ROUND_MAGIC;
    // The low bits of t hold k in two's complement; only k mod 4 matters.
    let quadrant = t.to_bits() & 3;
    // x − k·p1 and k·p2 are exact; the total error of r is below 2^-53.
    let r = (x - kf * PIO2_1) - (kf * PIO2_2 + kf * PIO2_3);
    sin_cos_kernel(r, quadrant)
}

/// sin and cos of `r + quadrant·π/2` for `|r| ≲ π/4`.
#[inline(always)]
pub(super) fn sin_cos_kernel(r: f64, quadrant: u64) -> (f64, f64) {
    let z = r * r;
    let w = z * z;
    let rz = r * z;
    // Estrin's scheme, grouped for short dependency chains.
    let s = &SIN_S;
    let sin_r =
        (r + rz * (s[0] + z * s[1])) + (rz * w) * ((s[2] + z * s[3]) + w * (s[4] + z * s[5]));
    // cos r = (1 − z/2) + z²·pc(z), with the rounding error of 1 − z/2 recovered.
    let c = &COS_C;
    let hz = 0.5 * z;
    let one_minus_hz = 1.0 - hz;
    let cos_tail = (((1.0 - one_minus_hz) - hz) + w * (c[0] + z * c[1]))
        + (w * w) * ((c[2] + z * c[3]) + w * (c[4] + z * c[5]));
    let cos_r = one_minus_hz + cos_tail;
    // sin r has the sign of r; this only matters for r = −0, where sin_r is +0.
    let sin_bits = sin_r.to_bits() | (r.to_bits() & SIGN_MASK);
    let cos_bits = cos_r.to_bits();
    // Quadrant n: (sin, cos) = (s, c), (c, −s), (−s, −c), (−c, s) for n = 0, 1, 2, 3,
    // selected with bit masks.
    let swap = (quadrant & 1).wrapping_neg();
    let sin_out = (sin_bits & !swap) | (cos_bits & swap);
    let cos_out = (cos_bits & !swap) | (sin_bits & swap);
    let sin_sign = (quadrant & 2) << 62;
    let cos_sign = (quadrant.wrapping_add(1) & 2) << 62;
    (
        f64::from_bits(sin_out ^ sin_sign),
        f64::from_bits(cos_out ^ cos_sign),
    )
}

/// sin_cos for |x| ≥ `SIN_COS_CW_LIMIT` and for non-finite x.
#[cold]
#[inline(never)]
fn sin_cos_large(x: f64) -> (f64, f64) {
    if !x.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let (r, quadrant) = reduce_payne_hanek(x);
    sin_cos_kernel(r, quadrant)
}

/// Exact reduction `x = (4m + quadrant)·π/2 + r`, `|r| ≤ π/4`, for finite `|x| ≥ 2^-9`.
///
/// With `|x| = m·2^e` (`m` a 53-bit integer), the bits of 2/π of weight `2^-i` for
/// `i ≤ e − 2` contribute multiples of 4 to `x·2/π` and are skipped; the next 128 bits
/// give `x·2/π mod 4` to 2^-73, in fixed point with 126 fraction bits.
pub(super) fn reduce_payne_hanek(x: f64) -> (f64, u64) {
    let ix = x.to_bits() & !SIGN_MASK;
    let e = ((ix >> 52) as i64) - 1075;
    let m = (ix & ((1 << 52) - 1)) | (1 << 52);
    // Bit of weight 2^-(e-1) sits at j0 = e + 62 in the table.
    let j0 = (e + 62) as usize;
    let (word, shift) = (j0 / 64, j0 % 64);
    let t = &TWO_OVER_PI_BITS;
    let top = ((t[word] as u128) << 64) | t[word + 1] as u128;
    let window = (top << shift) | ((t[word + 2] as u128) >> (64 - shift));
    // m·window mod 2^128 = (x·2/π mod 4)·2^126; round to the nearest quadrant.
    let p = (m as u128).wrapping_mul(window).wrapping_add(1 << 125);
    let mut quadrant = (p >> 126) as u64 & 3;
    let frac = (p & ((1 << 126) - 1)) as i128 - (1 << 125); // in [-2^125, 2^125)
    // r = frac·2^-126·π/2, with frac as a double-double.
    let f_hi = frac as f64;
    let f_lo = (frac - f_hi as i128) as f64;
    const SCALE: f64 = 1.0 / (1u128 << 126) as f64;
    let (f_hi, f_lo) = (f_hi * SCALE, f_lo * SCALE);
    let mut r = f_hi * PIO2_HI + (f_hi * PIO2_LO + f_lo * PIO2_HI);
    if x < 0.0 {
        r = -r;
        quadrant = quadrant.wrapping_neg() & 3;
    }
    (r, quadrant)
}

// ---------------------------------------------------------------------------------------
