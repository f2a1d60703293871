//! Portable elementary functions: [`exp`], [`ln`] and [`sin_cos`].
//!
//! # Why
//!
//! Spectrum synthesis evaluates a Box–Muller pair (`ln`, `sqrt`, `sin_cos`), a Phillips
//! spectrum (`exp`) and a time phase (`sin_cos`) for every wavevector, some 17 million
//! of them at 4096². The system libm is comparatively slow for that (a call each, ~10 ns
//! for `ln`/`exp` and ~29 ns for `f64::sin_cos`, which is two calls) and, more importantly,
//! its results differ between platforms and libm versions, so height maps were not
//! bit-reproducible across machines.
//!
//! The functions here use only IEEE 754 basic operations (`+ − × ÷`, comparisons) and bit
//! manipulation of `f64`s; no fused multiply–add, no libm, no tables beyond a few dozen
//! constants. Rust does not contract `a * b + c` into an FMA, so every result is
//! bit-identical on every target with IEEE binary64 arithmetic (all 64-bit targets, and
//! x86 with SSE2; not x87 extended-precision builds). They contain no data-dependent
//! branches on their hot paths, which keeps them fast on random input.
//!
//! # Algorithms and accuracy
//!
//! * [`exp`]: `x = k·ln2 + r`, `|r| ≤ ln2/2`, with `ln2` split in two (Cody–Waite; the
//!   product `k·ln2_hi` is exact) and the rounding error of `r` carried as a correction;
//!   `e^r = 1 + r + r²·q(r)` with `q` a degree-9 Chebyshev fit of `(e^r − 1 − r)/r²`
//!   evaluated by Estrin's scheme; `2^k` applied as two exact power-of-two factors so that
//!   overflow to `+inf` and gradual underflow (one rounding) come out right without
//!   branches. Relative error ≈ 1 ulp (≤ 1e-14 is the tested bound, sweeps find ~2.2e-16).
//! * [`ln`]: the FreeBSD msun / fdlibm `__ieee754_log` scheme: `x = 2^k·(1+f)` with
//!   `√2/2 ≤ 1+f < √2`, `s = f/(2+f)`, `ln(1+f) = f − hfsq + s·(hfsq + R(s²))` with
//!   fdlibm's degree-14 minimax `R` (Estrin-like split into two halves). Subnormal inputs are
//!   scaled by 2^54 on a cold path. Relative error < 1 ulp.
//! * [`sin_cos`]: quadrant `k = round(x·2/π)` and `r = x − k·π/2` by Cody–Waite reduction
//!   with a 3-part `π/2` (27 + 27 + 53 bits, so `k·p1` and `k·p2` are exact for
//!   `|k| < 2^26`) for `|x| < 1e8`; beyond that, an exact Payne–Hanek reduction with 2/π to
//!   1150 bits (a 19-word table) on a cold path, so results stay accurate for every finite
//!   `x`. The kernels are fdlibm's `__kernel_sin`/`__kernel_cos` minimax polynomials on
//!   `[−π/4, π/4]`; the quadrant is applied with bit masks (no branches). Absolute error
//!   ≈ 1e-16 for all finite `x` (tested bounds: 1e-15 for `|x| ≤ 16π`, 1e-12 up to 1e8).

/// `1.5·2^52`: adding and subtracting it rounds a double with `|v| < 2^51` to the nearest
/// integer (ties to even), and the integer sits in the low mantissa bits of the sum.
const ROUND_MAGIC: f64 = 6_755_399_441_055_744.0;
const SIGN_MASK: u64 = 0x8000_0000_0000_0000;

// ---------------------------------------------------------------------------------------
// exp
// ---------------------------------------------------------------------------------------

/// 1/ln 2.
const INV_LN2: f64 = f64::from_bits(0x3FF7_1547_652B_82FE);
/// ln 2 to 32 significant bits (so `k·LN2_HI` is exact for `|k| < 2^21`).
const LN2_HI: f64 = f64::from_bits(0x3FE6_2E42_FEE0_0000);
/// ln 2 − `LN2_HI`.
const LN2_LO: f64 = f64::from_bits(0x3DEA_39EF_3579_3C76);
/// Inputs are clamped to `[EXP_MIN_ARG, EXP_MAX_ARG]`: beyond these the result is 0 or
/// +inf anyway, and the clamp keeps `k` within the range the scaling handles.
const EXP_MAX_ARG: f64 = 710.0;
const EXP_MIN_ARG: f64 = -746.0;
/// `q(r) ≈ (e^r − 1 − r)/r²` on `|r| ≤ ln2/2`, degree 9 (Chebyshev fit; the error of
/// `r²·q` is below 2e-17 relative to `e^r`). Coefficients of `r^0..r^9`.
const EXP_Q: [f64; 10] = [
    f64::from_bits(0x3FE0_0000_0000_0001), // 0.5000000000000001
    f64::from_bits(0x3FC5_5555_5555_5556), // 0.16666666666666669
    f64::from_bits(0x3FA5_5555_5555_3D63), // 0.04166666666662413
    f64::from_bits(0x3F81_1111_1111_09B3), // 0.008333333333330062
    f64::from_bits(0x3F56_C16C_1788_BD90), // 0.0013888888917213717
    f64::from_bits(0x3F2A_01A0_1A7C_41D5), // 0.00019841269863053618
    f64::from_bits(0x3EFA_019B_90D2_AE7A), // 2.4801521295954376e-5
    f64::from_bits(0x3EC7_1DE0_DAE6_3BB3), // 2.7557268459997064e-6
    f64::from_bits(0x3E92_8918_5613_A3D6), // 2.7620088445409746e-7
    f64::from_bits(0x3E5A_F38A_9B0E_C855), // 2.510038549551032e-8
];

/// e^x for all finite x; returns 0 for x < −745.2 and +inf for x > 709.78; NaN → NaN.
///
/// More precisely the result underflows gradually (subnormal results are correctly
/// scaled with a single rounding) and is 0 below about −745.13, where e^x is less than
/// half the smallest subnormal; it overflows to +inf above about 709.7827.
/// `exp(±0) = 1`, `exp(+inf) = +inf`, `exp(−inf) = 0`. Relative error ≈ 1 ulp for normal
/// results.
#[inline]
pub fn exp(x: f64) -> f64 {
    // Clamp (a NaN fails both comparisons and propagates through the arithmetic).
    let x = if x > EXP_MAX_ARG {
        EXP_MAX_ARG
    } else if x < EXP_MIN_ARG {
        EXP_MIN_ARG
    } else {
        x
    };
    // k = round(x / ln2), |k| ≤ 1077.
    let t = x * INV_LN2 + ROUND_MAGIC;
    let kf = t - ROUND_MAGIC;
    let k = (t.to_bits() as i64).wrapping_sub(ROUND_MAGIC.to_bits() as i64);
    // r = x − k·ln2 = hi − lo; hi is exact, `corr` is the rounding error of r.
    let hi = x - kf * LN2_HI;
    let lo = kf * LN2_LO;
    let r = hi - lo;
    let corr = (hi - r) - lo;
    // e^(r + corr) ≈ 1 + r + (r²·q(r) + corr·(1 + r)).
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let c = &EXP_Q;
    let q01 = c[0] + c[1] * r;
    let q23 = c[2] + c[3] * r;
    let q45 = c[4] + c[5] * r;
    let q67 = c[6] + c[7] * r;
    let q89 = c[8] + c[9] * r;
    let q = (q01 + q23 * r2) + (q45 + q67 * r2) * r4 + q89 * r8;
    let y = 1.0 + (r + (r2 * q + (corr + corr * r)));
    // y·2^k as y·2^k1·2^k2 with k1 + k2 = k: both factors are normal for every clamped k,
    // the first product is exact and the second rounds once (to +inf, or to a subnormal).
    let k1 = k >> 1;
    let k2 = k.wrapping_sub(k1);
    let s1 = f64::from_bits((k1.wrapping_add(1023) as u64) << 52);
    let s2 = f64::from_bits((k2.wrapping_add(1023) as u64) << 52);
    y * s1 * s2
}

// ---------------------------------------------------------------------------------------
// ln
// ---------------------------------------------------------------------------------------

/// Bits of √2/2: mantissas are normalised into `[√2/2, √2)`.
const SQRT1_2_BITS: u64 = 0x3FE6_A09E_667F_3BCD;
/// fdlibm's `Lg1..Lg7`: `R(z) = z·(Lg1 + z·(Lg2 + … + z·Lg7))` ≈ `2·atanh(s)/s − 2`
/// with `z = s²`, minimax on `[0, 0.1716]` (error < 2^-58.45).
const LG: [f64; 7] = [
    f64::from_bits(0x3FE5_5555_5555_5593), // 6.666666666666735130e-01
    f64::from_bits(0x3FD9_9999_9997_FA04), // 3.999999999940941908e-01
    f64::from_bits(0x3FD2_4924_9422_9359), // 2.857142874366239149e-01
    f64::from_bits(0x3FCC_71C5_1D8E_78AF), // 2.222219843214978396e-01
    f64::from_bits(0x3FC7_4664_96CB_03DE), // 1.818357216161805012e-01
    f64::from_bits(0x3FC3_9A09_D078_C69F), // 1.531383769920937332e-01
    f64::from_bits(0x3FC2_F112_DF3E_5244), // 1.479819860511658591e-01
];
/// 2^54, to scale subnormal inputs into the normal range.
const TWO54: f64 = 18_014_398_509_481_984.0;

/// Natural log for x > 0 (subnormals too), −inf at 0, NaN for x < 0 or NaN, +inf at +inf.
///
/// `ln(±0) = −inf`, `ln(1) = +0`. Relative error < 1 ulp.
#[inline]
pub fn ln(x: f64) -> f64 {
    let ix = x.to_bits();
    // One unsigned comparison selects positive, normal, finite x.
    if ix.wrapping_sub(0x0010_0000_0000_0000) >= 0x7FE0_0000_0000_0000 {
        return ln_special(x);
    }
    ln_normal(ix, 0)
}

/// ln for zeros, negatives, subnormals, infinities and NaNs.
#[cold]
#[inline(never)]
fn ln_special(x: f64) -> f64 {
    if x.is_nan() {
        x
    } else if x == 0.0 {
        f64::NEG_INFINITY
    } else if x < 0.0 {
        f64::NAN
    } else if x == f64::INFINITY {
        x
    } else {
        // Positive subnormal: x·2^54 is normal and exact.
        ln_normal((x * TWO54).to_bits(), -54)
    }
}

/// ln of the positive normal double with bits `ix`, plus `k_bias·ln 2`.
#[inline(always)]
fn ln_normal(ix: u64, k_bias: i64) -> f64 {
    // x = 2^k·z with z in [√2/2, √2): k is the exponent of x/(√2/2).
    let tmp = ix.wrapping_sub(SQRT1_2_BITS);
    let k = ((tmp as i64) >> 52) + k_bias;
    let z = f64::from_bits(ix.wrapping_sub(tmp & (0xFFF << 52)));
    let f = z - 1.0; // exact (Sterbenz)
    let s = f / (2.0 + f);
    let dk = k as f64;
    let z = s * s;
    let w = z * z;
    let t1 = w * (LG[1] + w * (LG[3] + w * LG[5]));
    let t2 = z * (LG[0] + w * (LG[2] + w * (LG[4] + w * LG[6])));
    let r = t2 + t1;
    let hfsq = 0.5 * f * f;
    dk * LN2_HI - ((hfsq - (s * (hfsq + r) + dk * LN2_LO)) - f)
}

// ---------------------------------------------------------------------------------------
// sin_cos
// ---------------------------------------------------------------------------------------

/// 2/π.
const FRAC_2_PI: f64 = std::f64::consts::FRAC_2_PI;
/// π/2 = PIO2_1 + PIO2_2 + PIO2_3 (+ 4e-35): the first two have 27 significant bits, so
/// `k·PIO2_1` and `k·PIO2_2` are exact for `|k| < 2^26`.
const PIO2_1: f64 = f64::from_bits(0x3FF9_21FB_5400_0000); // 1.570796325802803
const PIO2_2: f64 = f64::from_bits(0x3E11_0B46_1000_0000); // 9.920935739593517e-10
const PIO2_3: f64 = f64::from_bits(0x3C5A_6263_3145_C06E); // 5.721188726109832e-18
/// π/2 as a double-double (for the large-argument reduction).
const PIO2_HI: f64 = f64::from_bits(0x3FF9_21FB_5444_2D18);
const PIO2_LO: f64 = f64::from_bits(0x3C91_A626_3314_5C07);
/// Cody–Waite reduction is used below this (|k| ≤ 6.4e7 < 2^26); Payne–Hanek above.
const SIN_COS_CW_LIMIT: f64 = 1.0e8;
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
const TWO_OVER_PI_BITS: [u64; 19] = [
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
    if !(x.abs() < SIN_COS_CW_LIMIT) {
        return sin_cos_large(x);
    }
    let t = x * FRAC_2_PI + ROUND_MAGIC;
    let kf = t - ROUND_MAGIC;
    // The low bits of t hold k in two's complement; only k mod 4 matters.
    let quadrant = t.to_bits() & 3;
    // x − k·p1 and k·p2 are exact; the total error of r is below 2^-53.
    let r = ((x - kf * PIO2_1) - kf * PIO2_2) - kf * PIO2_3;
    sin_cos_kernel(r, quadrant)
}

/// sin and cos of `r + quadrant·π/2` for `|r| ≲ π/4`.
#[inline(always)]
fn sin_cos_kernel(r: f64, quadrant: u64) -> (f64, f64) {
    let z = r * r;
    let w = z * z;
    let s = &SIN_S;
    let ps = (s[0] + z * s[1]) + w * (s[2] + z * s[3]) + (w * w) * (s[4] + z * s[5]);
    let sin_r = r + (r * z) * ps;
    let c = &COS_C;
    let pc = (c[0] + z * c[1]) + w * (c[2] + z * c[3]) + (w * w) * (c[4] + z * c[5]);
    // cos r = (1 − z/2) + z²·pc, with the rounding error of 1 − z/2 recovered.
    let hz = 0.5 * z;
    let one_minus_hz = 1.0 - hz;
    let cos_r = one_minus_hz + (((1.0 - one_minus_hz) - hz) + w * pc);
    // sin r has the sign of r; this only matters for r = −0, where sin_r is +0.
    let sin_bits = sin_r.to_bits() | (r.to_bits() & SIGN_MASK);
    let cos_bits = cos_r.to_bits();
    // Quadrant n: (sin, cos) = (s, c), (c, −s), (−s, −c), (−c, s) for n = 0, 1, 2, 3.
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
fn reduce_payne_hanek(x: f64) -> (f64, u64) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

    /// Tested bounds (the targets of the module; measured errors are far below).
    const EXP_REL_TOL: f64 = 1e-14;
    const LN_REL_TOL: f64 = 1e-14;
    /// sin/cos absolute error for |x| ≤ 16π and up to 1e8.
    const SIN_COS_ABS_TOL_SMALL: f64 = 1e-15;
    const SIN_COS_ABS_TOL_LARGE: f64 = 1e-12;
    /// Beyond 1e8 (Payne–Hanek path): the reduction is exact, so as accurate as below.
    const SIN_COS_ABS_TOL_HUGE: f64 = 1e-15;

    /// SplitMix64, for reproducible pseudo-random test points.
    struct Rng(u64);
    impl Rng {
        fn next_u64(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        }
        /// Uniform in [lo, hi).
        fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
            let u = (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
            lo + (hi - lo) * u
        }
    }

    /// Evenly spaced points of [lo, hi], both ends included.
    fn grid(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
        (0..n).map(move |i| lo + (hi - lo) * (i as f64 / (n - 1) as f64))
    }

    /// Distance in units in the last place between two finite doubles of the same sign.
    fn ulp_diff(a: f64, b: f64) -> u64 {
        (a.to_bits() as i64).abs_diff(b.to_bits() as i64)
    }

    fn rel_err(got: f64, want: f64) -> f64 {
        if got == want {
            0.0
        } else {
            ((got - want) / want).abs()
        }
    }

    /// Tracks the largest error and its argument.
    struct MaxErr {
        err: f64,
        at: f64,
    }
    impl MaxErr {
        fn new() -> Self {
            MaxErr { err: 0.0, at: 0.0 }
        }
        fn add(&mut self, err: f64, at: f64) {
            if err > self.err {
                self.err = err;
                self.at = at;
            }
        }
    }

    fn check_exp(x: f64, worst: &mut MaxErr) {
        let got = exp(x);
        let want = x.exp();
        if want.is_infinite() || want == 0.0 {
            assert_eq!(got, want, "exp({x:e}) = {got:e}, std gives {want:e}");
        } else if want < f64::MIN_POSITIVE {
            // Subnormal result: absolute precision is 1 subnormal ulp.
            assert!(
                ulp_diff(got, want) <= 1,
                "exp({x:e}) = {got:e}, std gives {want:e} (subnormal)"
            );
        } else {
            let err = rel_err(got, want);
            assert!(
                err <= EXP_REL_TOL,
                "exp({x:e}) = {got:e}, std gives {want:e}, relative error {err:e}"
            );
            worst.add(err, x);
        }
    }

    #[test]
    fn exp_matches_std_over_dense_sweeps() {
        let mut worst = MaxErr::new();
        // The whole domain, with the grid offset so that it does not hit only round numbers.
        for x in grid(-746.0, 710.0, 400_001) {
            check_exp(x + 1.234e-4, &mut worst);
        }
        // Around zero, where Box–Muller and Phillips arguments live.
        for x in grid(-40.0, 5.0, 300_001) {
            check_exp(x, &mut worst);
        }
        // Tiny arguments and both signs.
        let mut rng = Rng(1);
        for _ in 0..100_000 {
            let x = f64::from_bits(rng.next_u64() & 0x3FEF_FFFF_FFFF_FFFF) * 0.5;
            check_exp(x, &mut worst);
            check_exp(-x, &mut worst);
        }
        // Around the overflow and underflow limits, including subnormal results.
        for x in grid(705.0, 709.9, 50_001).chain(grid(-745.3, -700.0, 100_001)) {
            check_exp(x, &mut worst);
        }
        // Near the reduction boundaries (k ± 1/2)·ln2, where the quadrant switches.
        for k in -1075..=1024 {
            let b = (k as f64 + 0.5) * std::f64::consts::LN_2;
            for d in [-1e-9, -1e-15, 0.0, 1e-15, 1e-9] {
                check_exp(b + d, &mut worst);
            }
        }
        println!(
            "exp: max relative error {:e} at x = {:e}",
            worst.err, worst.at
        );
    }

    #[test]
    fn exp_special_values() {
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-0.0), 1.0);
        assert_eq!(exp(1e-300), 1.0);
        assert_eq!(exp(-1e-300), 1.0);
        assert_eq!(exp(f64::INFINITY), f64::INFINITY);
        assert_eq!(exp(f64::NEG_INFINITY), 0.0);
        assert!(exp(f64::NAN).is_nan());
        assert!(exp(-f64::NAN).is_nan());
        assert_eq!(exp(709.79), f64::INFINITY);
        assert_eq!(exp(710.0), f64::INFINITY);
        assert_eq!(exp(f64::MAX), f64::INFINITY);
        assert!(exp(709.78).is_finite());
        assert_eq!(exp(709.782_712_893_384), f64::MAX);
        assert_eq!(exp(-745.2), 0.0);
        assert_eq!(exp(-746.0), 0.0);
        assert_eq!(exp(-f64::MAX), 0.0);
        assert_eq!(exp(-745.13), 5e-324);
        assert_eq!(exp(-744.5), 5e-324);
        let e = exp(1.0);
        assert!(rel_err(e, std::f64::consts::E) <= 2.3e-16, "exp(1) = {e}");
        for k in -1022..=1023 {
            // Exact powers of two are reproduced to within an ulp.
            let x = k as f64 * std::f64::consts::LN_2;
            let want = x.exp();
            assert!(rel_err(exp(x), want) <= EXP_REL_TOL, "exp({x})");
        }
    }

    fn check_ln(x: f64, worst: &mut MaxErr) {
        let got = ln(x);
        let want = x.ln();
        let err = rel_err(got, want);
        assert!(
            err <= LN_REL_TOL,
            "ln({x:e}) = {got:e}, std gives {want:e}, relative error {err:e}"
        );
        worst.add(err, x);
    }

    #[test]
    fn ln_matches_std_over_dense_sweeps() {
        let mut worst = MaxErr::new();
        let mut rng = Rng(2);
        // Every positive finite double, subnormals included, log-uniformly.
        for _ in 0..300_000 {
            let x = f64::from_bits(rng.next_u64() % 0x7FF0_0000_0000_0000);
            if x > 0.0 {
                check_ln(x, &mut worst);
            }
        }
        // Box–Muller's (0, 1].
        for _ in 0..300_000 {
            check_ln(1.0 - rng.uniform(0.0, 1.0), &mut worst);
        }
        // Around 1, where ln x ≈ x − 1 is small (relative accuracy matters most here).
        for x in grid(0.5, 2.0, 200_001) {
            check_ln(x, &mut worst);
        }
        for _ in 0..100_000 {
            let d = f64::from_bits(rng.next_u64() & 0x3F8F_FFFF_FFFF_FFFF); // < 2^-6
            check_ln(1.0 + d, &mut worst);
            check_ln(1.0 - d, &mut worst);
        }
        // Around the normalisation boundary √2/2·2^k.
        for k in -1022..1023 {
            let b = std::f64::consts::FRAC_1_SQRT_2 * 2f64.powi(k);
            let mut x = b;
            for _ in 0..4 {
                x = f64::from_bits(x.to_bits() - 1);
            }
            for _ in 0..8 {
                check_ln(x, &mut worst);
                x = f64::from_bits(x.to_bits() + 1);
            }
        }
        // Exact powers of two, normal and subnormal.
        for k in -1074..=1023 {
            check_ln(2f64.powi(k), &mut worst);
            check_ln(f64::from_bits(2f64.powi(k).to_bits() + 1), &mut worst);
        }
        // Subnormals of every magnitude, and the extremes.
        for bits in [1u64, 2, 3, 0xF_FFFF_FFFF_FFFF, 0x10_0000_0000_0000] {
            check_ln(f64::from_bits(bits), &mut worst);
        }
        check_ln(f64::MAX, &mut worst);
        println!(
            "ln: max relative error {:e} at x = {:e}",
            worst.err, worst.at
        );
    }

    #[test]
    fn ln_special_values() {
        assert_eq!(ln(1.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(ln(0.0), f64::NEG_INFINITY);
        assert_eq!(ln(-0.0), f64::NEG_INFINITY);
        assert_eq!(ln(f64::INFINITY), f64::INFINITY);
        assert!(ln(f64::NEG_INFINITY).is_nan());
        assert!(ln(-1.0).is_nan());
        assert!(ln(-5e-324).is_nan());
        assert!(ln(f64::NAN).is_nan());
        assert!(rel_err(ln(2.0), std::f64::consts::LN_2) <= 1.2e-16);
        assert!(rel_err(ln(10.0), std::f64::consts::LN_10) <= 2.3e-16);
        assert!(rel_err(ln(std::f64::consts::E), 1.0) <= 2.3e-16);
        // ln of the smallest subnormal, −1074·ln 2.
        assert!(rel_err(ln(5e-324), -744.440_071_921_381_3) <= 2.3e-16);
    }

    #[test]
    fn exp_and_ln_are_inverse() {
        let mut rng = Rng(3);
        for _ in 0..200_000 {
            // x over the normal range: exp(ln x) has relative error ≈ |ln x|·ulp.
            let x = f64::from_bits(rng.next_u64() % 0x7FE0_0000_0000_0000 + (1 << 52));
            let l = ln(x);
            let back = exp(l);
            let tol = (l.abs() + 2.0) * 2.3e-16;
            assert!(rel_err(back, x) <= tol, "exp(ln({x:e})) = {back:e}");
            // y = ln(exp(y)) for y where exp is normal.
            let y = rng.uniform(-708.0, 709.0);
            let back = ln(exp(y));
            assert!(
                (back - y).abs() <= 4.5e-16 * y.abs().max(1.0),
                "ln(exp({y}))"
            );
        }
    }

    fn check_sin_cos(x: f64, tol: f64, worst: &mut MaxErr) {
        let (s, c) = sin_cos(x);
        let (ws, wc) = x.sin_cos();
        let err = (s - ws).abs().max((c - wc).abs());
        assert!(
            err <= tol,
            "sin_cos({x:e}) = ({s:e}, {c:e}), std gives ({ws:e}, {wc:e}), abs error {err:e}"
        );
        worst.add(err, x);
    }

    #[test]
    fn sin_cos_matches_std_for_moderate_arguments() {
        let mut worst = MaxErr::new();
        let lim = 16.0 * PI;
        for x in grid(-lim, lim, 600_001) {
            check_sin_cos(x, SIN_COS_ABS_TOL_SMALL, &mut worst);
        }
        let mut rng = Rng(4);
        for _ in 0..100_000 {
            check_sin_cos(
                rng.uniform(0.0, 2.0 * PI),
                SIN_COS_ABS_TOL_SMALL,
                &mut worst,
            );
        }
        // Multiples of π/4 (zeros, extrema and the quadrant boundaries) and their
        // neighbouring doubles; tiny arguments.
        for k in -64..=64 {
            let x = k as f64 * FRAC_PI_4;
            for d in [-2i64, -1, 0, 1, 2] {
                let y = f64::from_bits((x.to_bits() as i64 + d) as u64);
                check_sin_cos(y, SIN_COS_ABS_TOL_SMALL, &mut worst);
            }
        }
        for e in -1074..0 {
            let x = 2f64.powi(e);
            check_sin_cos(x, SIN_COS_ABS_TOL_SMALL, &mut worst);
            check_sin_cos(-x, SIN_COS_ABS_TOL_SMALL, &mut worst);
        }
        println!(
            "sin_cos, |x| <= 16π: max abs error {:e} at x = {:e}",
            worst.err, worst.at
        );
    }

    #[test]
    fn sin_cos_matches_std_for_large_arguments() {
        let mut worst = MaxErr::new();
        let mut rng = Rng(5);
        for _ in 0..150_000 {
            check_sin_cos(rng.uniform(-1e8, 1e8), SIN_COS_ABS_TOL_LARGE, &mut worst);
            // Log-uniform magnitudes 1..1e8.
            let x = 10f64.powf(rng.uniform(0.0, 8.0));
            check_sin_cos(x, SIN_COS_ABS_TOL_LARGE, &mut worst);
        }
        // Multiples of π/2 up to the Cody–Waite limit, where r is tiny.
        for k in (1..64_000_000i64).step_by(6_421) {
            check_sin_cos(k as f64 * FRAC_PI_2, SIN_COS_ABS_TOL_LARGE, &mut worst);
            check_sin_cos(-(k as f64) * FRAC_PI_2, SIN_COS_ABS_TOL_LARGE, &mut worst);
        }
        for x in [1e8, -1e8, 99_999_999.999_999_99, 1.0e8 + 1e-8] {
            check_sin_cos(x, SIN_COS_ABS_TOL_LARGE, &mut worst);
        }
        println!(
            "sin_cos, |x| <= 1e8: max abs error {:e} at x = {:e}",
            worst.err, worst.at
        );
        // Beyond: the Payne–Hanek path, up to f64::MAX.
        let mut worst = MaxErr::new();
        for _ in 0..100_000 {
            let x = 10f64.powf(rng.uniform(8.0, 308.25));
            let x = if rng.next_u64() & 1 == 0 { x } else { -x };
            check_sin_cos(x, SIN_COS_ABS_TOL_HUGE, &mut worst);
        }
        for x in [f64::MAX, -f64::MAX, 2f64.powi(1023), 1e22, 2f64.powi(60)] {
            check_sin_cos(x, SIN_COS_ABS_TOL_HUGE, &mut worst);
        }
        println!(
            "sin_cos, |x| > 1e8: max abs error {:e} at x = {:e}",
            worst.err, worst.at
        );
    }

    #[test]
    fn payne_hanek_agrees_with_cody_waite() {
        // Both reductions are accurate where both apply; compare them directly.
        let mut rng = Rng(6);
        for _ in 0..100_000 {
            let x = 10f64.powf(rng.uniform(-2.0, 8.0));
            let x = if rng.next_u64() & 1 == 0 { x } else { -x };
            let (r, q) = reduce_payne_hanek(x);
            let (s1, c1) = sin_cos_kernel(r, q);
            let (s2, c2) = sin_cos(x);
            let err = (s1 - s2).abs().max((c1 - c2).abs());
            assert!(err <= 4e-16, "reductions differ at x = {x:e} by {err:e}");
        }
    }

    #[test]
    fn sin_cos_special_values_and_identities() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        let (s, c) = sin_cos(-0.0);
        assert!(s == 0.0 && s.is_sign_negative() && c == 1.0, "sin_cos(-0)");
        assert_eq!(sin_cos(1e-300), (1e-300, 1.0));
        assert_eq!(sin_cos(-5e-324), (-5e-324, 1.0));
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let (s, c) = sin_cos(x);
            assert!(s.is_nan() && c.is_nan(), "sin_cos({x})");
        }
        let mut rng = Rng(7);
        for _ in 0..200_000 {
            let x = rng.uniform(-1e4, 1e4);
            let (s, c) = sin_cos(x);
            // Odd/even symmetry holds exactly.
            let (sn, cn) = sin_cos(-x);
            assert!(sn == -s && cn == c, "sin_cos(-{x}) is not (-sin, cos)");
            let norm = s * s + c * c;
            assert!((norm - 1.0).abs() <= 4.5e-16, "sin² + cos² = {norm} at {x}");
            assert!(s.abs() <= 1.0 && c.abs() <= 1.0, "|sin_cos({x})| > 1");
        }
    }

    #[test]
    fn constants_are_what_they_claim() {
        assert_eq!(LN2_HI + LN2_LO, std::f64::consts::LN_2);
        assert_eq!(LN2_HI.to_bits() & 0x1F_FFFF, 0, "LN2_HI has 32 bits");
        assert_eq!(INV_LN2, std::f64::consts::LOG2_E);
        assert_eq!(PIO2_HI, FRAC_PI_2);
        assert_eq!(PIO2_1 + PIO2_2, PIO2_1 + PIO2_2 + PIO2_3 - PIO2_3);
        assert_eq!(PIO2_1.to_bits() & 0x3FF_FFFF, 0, "PIO2_1 has 27 bits");
        assert_eq!(PIO2_2.to_bits() & 0x3FF_FFFF, 0, "PIO2_2 has 27 bits");
        assert_eq!(PIO2_1 + (PIO2_2 + PIO2_3), FRAC_PI_2);
        // The 2/π table starts with the bits of FRAC_2_PI.
        let lead = f64::from_bits(
            0x3FE0_0000_0000_0000 | (TWO_OVER_PI_BITS[1] >> 12) & 0xF_FFFF_FFFF_FFFF,
        );
        assert!((lead * 0.5 - FRAC_2_PI).abs() < 1e-16);
    }

    /// `cargo test --release --lib fastmath -- --ignored --nocapture`
    #[test]
    #[ignore]
    fn speed_vs_std() {
        use std::hint::black_box;
        use std::time::Instant;
        const N: usize = 1 << 16;
        const ROUNDS: usize = 15;
        const REPS: usize = 8;
        let mut rng = Rng(8);
        let exp_in: Vec<f64> = (0..N).map(|_| rng.uniform(-30.0, 5.0)).collect();
        let ln_in: Vec<f64> = (0..N).map(|_| 1.0 - rng.uniform(0.0, 1.0)).collect();
        let angle_in: Vec<f64> = (0..N).map(|_| rng.uniform(0.0, 2.0 * PI)).collect();
        let phase_in: Vec<f64> = (0..N).map(|_| rng.uniform(0.0, 3000.0)).collect();

        fn time(inputs: &[f64], f: impl Fn(f64) -> f64) -> f64 {
            let start = Instant::now();
            let mut acc = 0.0;
            for _ in 0..REPS {
                for &x in inputs {
                    acc += f(black_box(x));
                }
            }
            black_box(acc);
            start.elapsed().as_secs_f64() * 1e9 / (REPS * inputs.len()) as f64
        }
        fn median(mut v: Vec<f64>) -> f64 {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        }
        macro_rules! compare {
            ($name:expr, $inputs:expr, $ours:expr, $theirs:expr) => {{
                let (mut a, mut b) = (Vec::new(), Vec::new());
                for _ in 0..ROUNDS {
                    a.push(time($inputs, $ours));
                    b.push(time($inputs, $theirs));
                }
                let (a, b) = (median(a), median(b));
                println!(
                    "{:>18}: fastmath {a:6.2} ns/call, std {b:6.2} ns/call, speed-up {:.2}x",
                    $name,
                    b / a
                );
            }};
        }
        compare!("exp", &exp_in, exp, f64::exp);
        compare!("ln", &ln_in, ln, f64::ln);
        let ours = |x| {
            let (s, c) = sin_cos(x);
            s + c
        };
        let theirs = |x: f64| {
            let (s, c) = x.sin_cos();
            s + c
        };
        compare!("sin_cos [0, 2π)", &angle_in, ours, theirs);
        compare!("sin_cos [0, 3000)", &phase_in, ours, theirs);
    }
}
