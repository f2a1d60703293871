//! Portable elementary functions: [`exp`], [`ln`] and [`sin_cos`], and a single-precision
//! base-2 logarithm and power of two for the directional spectra's grid values
//! (`log2_f32`, `exp2_parts_f32`, `scale_f64`).
//!
//! # Why
//!
//! Spectrum synthesis evaluates a Box–Muller pair (`ln`, `sqrt`, `sin_cos`), a Phillips
//! spectrum (`exp`) and a time phase (`sin_cos`) for every wavevector, some 17 million
//! of them at 4096². The system libm's results differ between platforms and libm versions
//! (and `f64::sin_cos` is two calls), so height maps were not bit-reproducible across
//! machines.
//!
//! The functions here use only IEEE 754 basic operations (`+ − ×`, comparisons) and bit
//! manipulation of `f64`s: no division, no fused multiply–add, no libm, no tables beyond a
//! few dozen constants. Rust does not contract `a * b + c` into an FMA, so every result is
//! bit-identical on every target with IEEE binary64 arithmetic (all 64-bit targets, and
//! x86 with SSE2; not x87 extended-precision builds), whatever the compiler version or
//! optimisation level. Hot paths have no data-dependent branches (one predictable range
//! check each), which keeps them fast on random input.
//!
//! # Algorithms and accuracy
//!
//! * [`exp`]: `k = round(32x/ln2)` (by adding 1.5·2^52), `a = x − k·hi` with `hi` = ln2/32
//!   to 36 bits (so `k·hi` and the difference are exact) and `lo` = `k·(ln2/32 − hi)`,
//!   `|lo| < 2e-9`; then `e^x = 2^(k>>5) · 2^((k&31)/32) · (1 − lo) · e^a` with `2^(j/32)`
//!   from a 32-entry table and `e^a − 1` a degree-6 polynomial (`|a| ≤ ln2/64`, Chebyshev
//!   fit, Estrin's scheme). For `|x| < 690` the power of two is added to the exponent bits;
//!   beyond, a cold path clamps `x` and applies it as two power-of-two factors, so that
//!   overflow and gradual underflow come out right. Relative error ≈ 1 ulp (sweeps: max 2.2e-16).
//! * [`ln`]: `x = 2^k·z`, `z ∈ [0.703125, 1.40625)` by integer operations on the bits;
//!   `c` = `z` rounded to 4 mantissa bits, one of 16 centres (`c = 1` for z near 1, so
//!   there is no cancellation there); `ln x = k·ln2 + ln c + ln(1 + r)` with
//!   `r = (z − c)·(1/c)` (`z − c` exact, `|r| ≤ 1/32`), `(1/c, ln c)` from a 16-entry table
//!   and `ln(1 + r) = r + r²·Q(r)`, `Q` of degree 7 (Chebyshev fit, Estrin's scheme).
//!   Subnormal inputs are scaled by 2^54 on a cold path. Relative error ≤ 2 ulp
//!   (sweeps: max 4.4e-16).
//! * [`sin_cos`]: quadrant `k = round(x·2/π)` and `r = x − k·π/2` by Cody–Waite reduction
//!   with a 3-part `π/2` (27 + 27 + 53 bits, so `k·p1` and `k·p2` are exact for
//!   `|k| < 2^26`) for `|x| < 1e8`; beyond that, an exact Payne–Hanek reduction with 2/π to
//!   1150 bits (a 19-word table) on a cold path, so results stay accurate for every finite
//!   `x`. The kernels use fdlibm's `__kernel_sin`/`__kernel_cos` minimax coefficients
//!   (degrees 13 and 14 on `[−π/4, π/4]`), evaluated by Estrin's scheme; the quadrant is
//!   applied with bit masks. Absolute error ≈ 1e-16 for every finite `x` (sweeps: max
//!   2.2e-16).
//!
//! * `log2_f32`, `log2_unit_f32`, `exp2_parts_f32`, `exp2_f32`, `scale_f64`: log2 x
//!   from the bits and `u = (m − 1)/(m + 1)` (one division, a fitted cubic in u²), 2^t
//!   as `p·2^n` (a fitted degree-6 polynomial), and `p·2^n` as an exact double; ~1e-7
//!   relative, straight-line code for passes sixteen lanes wide.
//!
//! The accuracy targets are relative error ≤ 1e-14 for `exp`/`ln` and absolute error
//! ≤ 1e-15 (`|x| ≤ 16π`) and ≤ 1e-12 (`|x| ≤ 1e8`) for `sin_cos`; the tests check tighter
//! bounds against std.

/// `1.5·2^52`: adding and subtracting it rounds a double with `|v| < 2^51` to the nearest
/// integer (ties to even), and the integer sits in the low mantissa bits of the sum.
const ROUND_MAGIC: f64 = 6_755_399_441_055_744.0;
const SIGN_MASK: u64 = 0x8000_0000_0000_0000;

// ---------------------------------------------------------------------------------------
// exp
// ---------------------------------------------------------------------------------------

/// The exp table has `2^EXP_TABLE_BITS` entries `2^(j/32)`.
const EXP_TABLE_BITS: u32 = 5;
/// 32/ln 2.
const EXP_N_INV_LN2: f64 = f64::from_bits(0x4047_1547_652B_82FE);
/// ln2/32 rounded to 36 significant bits (so `k·EXP_LN2_N_HI` is exact for `|k| < 2^17`),
/// and the rest (|k·EXP_LN2_N_LO| < 2e-9, small enough to be applied as a factor `1 − lo`).
const EXP_LN2_N_HI: f64 = f64::from_bits(0x3F96_2E42_FEFA_0000);
const EXP_LN2_N_LO: f64 = f64::from_bits(0x3D2C_F79A_BC9E_3B3A);
/// Below this |x| the result and every intermediate is a normal number far from overflow,
/// and the scale factor can be built by adding to the exponent bits.
const EXP_FAST_LIMIT: f64 = 690.0;
/// Beyond these the result is 0 or +inf; the cold path clamps its input to them.
const EXP_MAX_ARG: f64 = 710.0;
const EXP_MIN_ARG: f64 = -746.0;
/// `q(r) ≈ (e^r − 1 − r)/r²` on `|r| ≤ ln2/64`, degree 4 (Chebyshev fit; the error of
/// `r²·q` is below 3e-19 relative to `e^r`). Coefficients of `r^0..r^4`.
const EXP_Q: [f64; 5] = [
    f64::from_bits(0x3FE0_0000_0000_0000), // 0.5
    f64::from_bits(0x3FC5_5555_5554_DC4E), // 0.1666666666658067
    f64::from_bits(0x3FA5_5555_5555_18D2), // 0.041666666666559174
    f64::from_bits(0x3F81_1114_FCA8_2E8E), // 0.00833336254165509
    f64::from_bits(0x3F56_C170_0258_740F), // 0.0013888925399279139
];
/// Bits of `2^(j/32)`, `j = 0..32`, correctly rounded.
const EXP_TABLE: [u64; 1 << EXP_TABLE_BITS] = [
    0x3FF0_0000_0000_0000,
    0x3FF0_59B0_D315_8574,
    0x3FF0_B558_6CF9_890F,
    0x3FF1_1301_D012_5B51,
    0x3FF1_72B8_3C7D_517B,
    0x3FF1_D487_3168_B9AA,
    0x3FF2_387A_6E75_6238,
    0x3FF2_9E9D_F51F_DEE1,
    0x3FF3_06FE_0A31_B715,
    0x3FF3_71A7_373A_A9CB,
    0x3FF3_DEA6_4C12_3422,
    0x3FF4_4E08_6061_892D,
    0x3FF4_BFDA_D536_2A27,
    0x3FF5_342B_569D_4F82,
    0x3FF5_AB07_DD48_5429,
    0x3FF6_247E_B03A_5585,
    0x3FF6_A09E_667F_3BCD,
    0x3FF7_1F75_E8EC_5F74,
    0x3FF7_A114_73EB_0187,
    0x3FF8_2589_994C_CE13,
    0x3FF8_ACE5_422A_A0DB,
    0x3FF9_3737_B0CD_C5E5,
    0x3FF9_C491_82A3_F090,
    0x3FFA_5503_B23E_255D,
    0x3FFA_E89F_995A_D3AD,
    0x3FFB_7F76_F2FB_5E47,
    0x3FFC_199B_DD85_529C,
    0x3FFC_B720_DCEF_9069,
    0x3FFD_5818_DCFB_A487,
    0x3FFD_FC97_337B_9B5F,
    0x3FFE_A4AF_A2A4_90DA,
    0x3FFF_5076_5B6E_4540,
];

/// e^x for all finite x; returns 0 for x < −745.2 and +inf for x > 709.78; NaN → NaN.
///
/// More precisely the result underflows gradually (subnormal results are correctly
/// scaled) and is 0 below about −745.13, where e^x is less than half the smallest
/// subnormal; it overflows to +inf above about 709.7827. `exp(±0) = 1`,
/// `exp(+inf) = +inf`, `exp(−inf) = 0`. Relative error ≈ 1 ulp for normal results.
#[inline]
pub fn exp(x: f64) -> f64 {
    if exp_is_special(x) {
        return exp_special(x);
    }
    exp_fast(x)
}

/// True where [`exp`] leaves the branch-free path (|x| ≥ the fast limit, or NaN).
#[inline(always)]
pub(crate) fn exp_is_special(x: f64) -> bool {
    x.abs() >= EXP_FAST_LIMIT || x.is_nan()
}

/// [`exp`] without the special-value branch: equal to it where `!exp_is_special(x)`,
/// meaningless elsewhere (but free of undefined behaviour), so it vectorizes.
#[inline(always)]
pub(crate) fn exp_fast(x: f64) -> f64 {
    let (k, table_bits, lo, p) = exp_reduce(x);
    // 2^(k/32) = 2^(j/32)·2^(k >> 5), normal here: add to the exponent field.
    let scale = f64::from_bits(table_bits.wrapping_add(((k >> EXP_TABLE_BITS) as u64) << 52));
    let scale = scale - scale * lo;
    scale + scale * p
}

/// `x = (32m + j)·ln2/32 + a − lo`: returns `k = 32m + j`, the bits of `2^(j/32)`,
/// `lo` and `e^a − 1`; `e^x = 2^m·2^(j/32)·(1 − lo)·e^a` to within 2e-18.
#[inline(always)]
fn exp_reduce(x: f64) -> (i64, u64, f64, f64) {
    // k = round(x·32/ln2), |k| < 2^16.
    let t = x * EXP_N_INV_LN2 + ROUND_MAGIC;
    let kf = t - ROUND_MAGIC;
    let k = (t.to_bits() as i64).wrapping_sub(ROUND_MAGIC.to_bits() as i64);
    // a = x − k·hi is exact, |a| ≤ ln2/64 + 2e-9.
    let a = x - kf * EXP_LN2_N_HI;
    let lo = kf * EXP_LN2_N_LO;
    let table_bits = EXP_TABLE[(k & ((1 << EXP_TABLE_BITS) - 1)) as usize];
    // e^a − 1 ≈ a + a²·q(a), by Estrin's scheme (short dependency chains).
    let a2 = a * a;
    let a4 = a2 * a2;
    let c = &EXP_Q;
    let p = (a + a2 * (c[0] + c[1] * a)) + a4 * ((c[2] + c[3] * a) + a2 * c[4]);
    (k, table_bits, lo, p)
}

/// exp for |x| ≥ `EXP_FAST_LIMIT` and NaN.
#[cold]
#[inline(never)]
fn exp_special(x: f64) -> f64 {
    if x.is_nan() {
        return x;
    }
    let x = x.clamp(EXP_MIN_ARG, EXP_MAX_ARG);
    let (k, table_bits, lo, p) = exp_reduce(x);
    let t = f64::from_bits(table_bits);
    let t = t - t * lo;
    let y = t + t * p;
    // y·2^m as y·2^m1·2^m2, m1 + m2 = m: both factors are normal for every clamped x, the
    // first product is exact and the second rounds once (to +inf or to a subnormal).
    let m = k >> EXP_TABLE_BITS;
    let m1 = m >> 1;
    let m2 = m - m1;
    let s1 = f64::from_bits(((m1 + 1023) as u64) << 52);
    let s2 = f64::from_bits(((m2 + 1023) as u64) << 52);
    y * s1 * s2
}

// ---------------------------------------------------------------------------------------
// ln
// ---------------------------------------------------------------------------------------

/// ln 2 to 32 significant bits (so `k·LN2_HI` is exact for `|k| < 2^21`), and the rest.
const LN2_HI: f64 = f64::from_bits(0x3FE6_2E42_FEE0_0000);
const LN2_LO: f64 = f64::from_bits(0x3DEA_39EF_3579_3C76);
/// Bits of 0.703125: mantissas are normalised into `z ∈ [0.703125, 1.40625)`, whose 16
/// subintervals (by the top 4 mantissa bits of `bits(x) − LN_OFF`) have the centres
/// `c = (i + 23)/32` for `i ≤ 9` and `c = (i + 7)/16` for `i ≥ 9`, i.e. `z` rounded to 4
/// mantissa bits; `c = 1` is the centre of subinterval 9.
const LN_OFF: u64 = 0x3FE6_8000_0000_0000;
/// Bits of `(1/c, ln c)` for the 16 subintervals, correctly rounded.
const LN_TABLE: [[u64; 2]; 16] = [
    [0x3FF6_42C8_590B_2164, 0xBFD5_22AE_0738_A3D8], // 23/32
    [0x3FF5_5555_5555_5555, 0xBFD2_6962_1134_DB92], // 24/32
    [0x3FF4_7AE1_47AE_147B, 0xBFCF_991C_6CB3_B379], // 25/32
    [0x3FF3_B13B_13B1_3B14, 0xBFCA_93ED_3C8A_D9E3], // 26/32
    [0x3FF2_F684_BDA1_2F68, 0xBFC5_BF40_6B54_3DB2], // 27/32
    [0x3FF2_4924_9249_2492, 0xBFC1_178E_8227_E47C], // 28/32
    [0x3FF1_A7B9_611A_7B96, 0xBFB9_335E_5D59_4989], // 29/32
    [0x3FF1_1111_1111_1111, 0xBFB0_8598_B59E_3A07], // 30/32
    [0x3FF0_8421_0842_1084, 0xBFA0_415D_89E7_4444], // 31/32
    [0x3FF0_0000_0000_0000, 0x0000_0000_0000_0000], // 1
    [0x3FEE_1E1E_1E1E_1E1E, 0x3FAF_0A30_C011_62A6], // 17/16
    [0x3FEC_71C7_1C71_C71C, 0x3FBE_2707_6E2A_F2E6], // 18/16
    [0x3FEA_F286_BCA1_AF28, 0x3FC5_FF30_70A7_93D4], // 19/16
    [0x3FE9_9999_9999_999A, 0x3FCC_8FF7_C79A_9A22], // 20/16
    [0x3FE8_6186_1861_8618, 0x3FD1_675C_ABAB_A60E], // 21/16
    [0x3FE7_45D1_745D_1746, 0x3FD4_618B_C21C_5EC2], // 22/16
];
/// `ln(1 + r) ≈ r + r²·Q(r)` on `|r| ≤ 1/32`, `Q(r) = −1/2 + r·P(r)` with `P` a degree-6
/// Chebyshev fit of `(ln(1+r) − r + r²/2)/r³` (relative error below 5e-17).
/// Coefficients of `r^0..r^7` of `Q`.
const LN_Q: [f64; 8] = [
    -0.5,
    f64::from_bits(0x3FD5_5555_5555_5555), // 0.3333333333333333
    f64::from_bits(0xBFD0_0000_0002_DAD9), // -0.25000000001038597
    f64::from_bits(0x3FC9_9999_999E_CA71), // 0.20000000000944199
    f64::from_bits(0xBFC5_5554_9FBB_519A), // -0.16666658210182278
    f64::from_bits(0x3FC2_4923_ED30_A0BA), // 0.1428570659784379
    f64::from_bits(0xBFC0_05A3_B118_B086), // -0.12517210147177965
    f64::from_bits(0x3FBC_7C08_0BEE_CDD4), // 0.11126756945923627
];
/// 2^54, to scale subnormal inputs into the normal range.
const TWO54: f64 = 18_014_398_509_481_984.0;

/// Natural log for x > 0 (subnormals too), −inf at 0, NaN for x < 0 or NaN, +inf at +inf.
///
/// `ln(±0) = −inf`, `ln(1) = +0`. Relative error ≤ 2 ulp.
#[inline]
pub fn ln(x: f64) -> f64 {
    // One unsigned comparison selects positive, normal, finite x.
    if ln_is_special(x) {
        return ln_special(x);
    }
    ln_normal(x.to_bits(), 0)
}

/// True where [`ln`] leaves its straight-line path (`x` not positive, normal and finite).
#[inline(always)]
pub(crate) fn ln_is_special(x: f64) -> bool {
    x.to_bits().wrapping_sub(0x0010_0000_0000_0000) >= 0x7FE0_0000_0000_0000
}

/// [`ln`] of a positive, normal, finite `x`, without the range check: straight-line code
/// (one table lookup) for loops that the compiler vectorizes. Bit-identical to [`ln`]
/// for such `x`; for other `x` the result is meaningless (but computing it is harmless).
#[inline(always)]
pub(crate) fn ln_positive_normal(x: f64) -> f64 {
    ln_normal(x.to_bits(), 0)
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
    // x = 2^k·z, z in [0.703125, 1.40625); subinterval i of z, centre c.
    let tmp = ix.wrapping_sub(LN_OFF);
    let i = ((tmp >> 48) & 15) as usize;
    let k = ((tmp as i64) >> 52) + k_bias;
    let iz = ix.wrapping_sub(tmp & (0xFFF << 52));
    let z = f64::from_bits(iz);
    let c = f64::from_bits(iz.wrapping_add(1 << 47) & !((1 << 48) - 1));
    let [inv_c, ln_c] = LN_TABLE[i].map(f64::from_bits);
    // ln x = k·ln2 + ln c + ln(1 + r), r = (z − c)/c, |r| ≤ 1/32; z − c is exact.
    let r = (z - c) * inv_c;
    let dk = k as f64;
    // ln(1 + r) − r ≈ r²·Q(r), by Estrin's scheme (short dependency chains).
    let r2 = r * r;
    let r4 = r2 * r2;
    let r6 = r4 * r2;
    let q = &LN_Q;
    let tail = (r2 * (q[0] + q[1] * r) + r4 * (q[2] + q[3] * r))
        + (r6 * ((q[4] + q[5] * r) + r2 * (q[6] + q[7] * r)) + dk * LN2_LO);
    (dk * LN2_HI + (ln_c + r)) + tail
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
fn sin_cos_kernel(r: f64, quadrant: u64) -> (f64, f64) {
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

// ---------------------------------------------------------------------------------------
// log2 and 2^t in single precision
// ---------------------------------------------------------------------------------------

/// `1.5·2^23`: adding and subtracting it rounds an `f32` with `|v| < 2^22` to the nearest
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

    /// Tolerances against std. They are tighter than the module's targets (relative 1e-14
    /// for exp/ln; absolute 1e-15 up to 16π and 1e-12 up to 1e8 for sin_cos) so that
    /// regressions show, with room for a reference libm that is itself off by an ulp.
    const EXP_REL_TOL: f64 = 1e-15;
    const LN_REL_TOL: f64 = 1e-15;
    /// sin/cos absolute error for |x| ≤ 16π, for |x| ≤ 1e8 and beyond (Payne–Hanek path).
    const SIN_COS_ABS_TOL_SMALL: f64 = 1e-15;
    const SIN_COS_ABS_TOL_LARGE: f64 = 1e-15;
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
    fn single_precision_log2_and_exp2_are_within_their_bounds() {
        // log2: |Δ| ≤ LOG2_TOL·(1 + |log2 x|); 2^t: |Δ|/2^t ≤ EXP2_TOL (t exact in f32).
        const LOG2_TOL: f64 = 2e-7;
        const EXP2_TOL: f64 = 2e-7;
        let (mut worst_log, mut worst_exp) = (0.0f64, 0.0f64);
        let mut rng = Rng(7);
        for i in 0..200_000 {
            // x over the whole normal range, evenly in log2 x, and neighbours of 1.
            let x = if i % 10 == 0 {
                f32::from_bits(1.0f32.to_bits() - 50 + (i / 10 % 100) as u32)
            } else {
                rng.uniform(-126.0, 128.0).exp2() as f32
            };
            if !(x.is_normal()) {
                continue;
            }
            let want = f64::from(x).log2();
            let err = (f64::from(log2_f32(x)) - want).abs() / (1.0 + want.abs());
            worst_log = worst_log.max(err);
            assert!(
                err < LOG2_TOL,
                "log2_f32({x:e}) = {}, want {want}",
                log2_f32(x)
            );
            let t = rng.uniform(-1000.0, 1000.0) as f32;
            let (p, n) = exp2_parts_f32(t);
            assert_eq!(n as f32, t.round_ties_even(), "n of 2^{t}");
            let want = (f64::from(t) - f64::from(n)).exp2();
            let err = (f64::from(p) - want).abs() / want;
            worst_exp = worst_exp.max(err);
            assert!(err < EXP2_TOL, "2^{t}: p = {p}, want {want}");
        }
        eprintln!("log2_f32: largest |Δ|/(1 + |log2 x|) {worst_log:.2e}; 2^t: {worst_exp:.2e}");
        assert_eq!(log2_f32(1.0), 0.0);
        assert_eq!(log2_f32(0.5), -1.0);
        assert_eq!(log2_f32(1024.0), 10.0);
        assert_eq!(exp2_parts_f32(-3.0), (1.0, -3));
        // exp2_f32: normal results, 0 below 2^−126.
        assert_eq!(exp2_f32(3.0), 8.0);
        assert_eq!(exp2_f32(-126.5), 0.0);
        assert!(rel_err(f64::from(exp2_f32(-125.25)), (-125.25f64).exp2()) < EXP2_TOL);
    }

    #[test]
    fn scale_f64_is_exact_in_range_and_saturates_outside() {
        for (p, e) in [
            (1.25f32, 0),
            (0.75, -1022),
            (1.4, 1023),
            (0.9, -300),
            (1.0, 77),
        ] {
            assert_eq!(scale_f64(p, e), f64::from(p) * 2f64.powi(e), "{p}·2^{e}");
        }
        assert_eq!(scale_f64(1.0, -1023), 0.0);
        assert_eq!(scale_f64(1.0, -5000), 0.0);
        assert_eq!(scale_f64(1.0, 1024), f64::INFINITY);
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
        // Near the reduction boundaries (k + 1/2)·ln2/32, where the table index switches.
        for k in -34_440..=32_780 {
            let b = (k as f64 + 0.5) * (std::f64::consts::LN_2 / 32.0);
            for d in [-1e-12, 0.0, 1e-12] {
                check_exp(b + d, &mut worst);
            }
        }
        // Around the switch between the fast and the cold path.
        for x in grid(-EXP_FAST_LIMIT - 1e-9, -EXP_FAST_LIMIT + 1e-9, 1001).chain(grid(
            EXP_FAST_LIMIT - 1e-9,
            EXP_FAST_LIMIT + 1e-9,
            1001,
        )) {
            check_exp(x, &mut worst);
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
        // Just below the overflow threshold (fdlibm's o_threshold).
        let big = exp(709.782_712_893_383_9);
        assert!(
            big.is_finite() && big > 1.797e308,
            "exp(709.7827128933839) = {big}"
        );
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
                // Neighbouring doubles (of the same sign; 0 gives the smallest subnormals).
                let y = if x == 0.0 {
                    d as f64 * 5e-324
                } else {
                    f64::from_bits((x.to_bits() as i64 + d) as u64)
                };
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
        // Independent of std: correctly rounded values (from 2000-bit arithmetic).
        for (x, sin_x, cos_x) in [
            (1e22, -0.852_200_849_767_188_8, 0.523_214_785_395_139),
            (
                f64::MAX,
                0.004_961_954_789_184_062,
                -0.999_987_689_426_559_9,
            ),
            (1e8, 0.931_639_027_109_726, -0.363_385_089_355_690_5),
        ] {
            let (s, c) = sin_cos(x);
            let err = (s - sin_x).abs().max((c - cos_x).abs());
            assert!(err <= 2.3e-16, "sin_cos({x:e}) = ({s}, {c}), error {err:e}");
        }
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

    /// FNV-1a over the bits of the outputs for fixed inputs.
    fn output_hashes() -> [u64; 3] {
        fn fnv(h: &mut u64, bits: u64) {
            for byte in bits.to_le_bytes() {
                *h = (*h ^ byte as u64).wrapping_mul(0x0000_0100_0000_01B3);
            }
        }
        let mut h = [0xCBF2_9CE4_8422_2325u64; 3];
        let mut rng = Rng(9);
        for _ in 0..20_000 {
            fnv(&mut h[0], exp(rng.uniform(-750.0, 712.0)).to_bits());
            fnv(&mut h[1], ln(f64::from_bits(rng.next_u64() >> 1)).to_bits());
            let (s, c) = sin_cos(rng.uniform(-1e3, 1e3));
            fnv(&mut h[2], s.to_bits());
            fnv(&mut h[2], c.to_bits());
        }
        h
    }

    #[test]
    fn outputs_are_bit_stable() {
        // The point of this module: the same bits on every platform, compiler and
        // optimisation level. A change here changes generated height maps; update the
        // constants only for a deliberate change of algorithm.
        let h = output_hashes();
        println!(
            "output hashes: {:#018X} {:#018X} {:#018X}",
            h[0], h[1], h[2]
        );
        assert_eq!(
            h,
            [
                0xE3FC_AB2E_B25C_B200,
                0x7547_C8E2_CE34_44B5,
                0x8D29_28B2_EC68_21A5
            ]
        );
    }

    #[test]
    fn constants_are_what_they_claim() {
        assert_eq!(LN2_HI + LN2_LO, std::f64::consts::LN_2);
        assert_eq!(LN2_HI.to_bits() & 0x1F_FFFF, 0, "LN2_HI has 32 bits");
        assert_eq!(EXP_N_INV_LN2, 32.0 * std::f64::consts::LOG2_E);
        assert_eq!(EXP_LN2_N_HI + EXP_LN2_N_LO, std::f64::consts::LN_2 / 32.0);
        assert_eq!(
            EXP_LN2_N_HI.to_bits() & 0x1_FFFF,
            0,
            "EXP_LN2_N_HI has 36 bits"
        );
        assert_eq!(PIO2_HI, FRAC_PI_2);
        assert_eq!(PIO2_1 + PIO2_2, PIO2_1 + PIO2_2 + PIO2_3 - PIO2_3);
        assert_eq!(PIO2_1.to_bits() & 0x3FF_FFFF, 0, "PIO2_1 has 27 bits");
        assert_eq!(PIO2_2.to_bits() & 0x3FF_FFFF, 0, "PIO2_2 has 27 bits");
        assert_eq!(PIO2_1 + (PIO2_2 + PIO2_3), FRAC_PI_2);
        // The 2/π table starts with the bits of FRAC_2_PI (truncated rather than rounded).
        let mantissa = (TWO_OVER_PI_BITS[1] >> 11) & 0xF_FFFF_FFFF_FFFF;
        let lead = f64::from_bits(0x3FE0_0000_0000_0000 | mantissa);
        assert!(
            (lead - FRAC_2_PI).abs() <= 1.2e-16,
            "2/π table starts with {lead}"
        );
    }

    /// Prints ns per call, fastmath vs std, as medians of interleaved runs:
    /// *throughput* (independent calls, results stored) and *latency* (each argument
    /// depends on the previous result, as in `acc = f(x + acc·0)`); the harness's own
    /// cost is printed as `identity`.
    ///
    /// `cargo test --release --lib fastmath::tests::speed_vs_std -- --ignored --nocapture`
    #[test]
    #[ignore]
    fn speed_vs_std() {
        use std::hint::black_box;
        use std::time::Instant;
        const N: usize = 1 << 14;
        const ROUNDS: usize = 21;
        const REPS: usize = 16;

        fn throughput(inputs: &[f64], out: &mut [f64], f: impl Fn(f64) -> f64) -> f64 {
            let start = Instant::now();
            for _ in 0..REPS {
                for (o, &x) in out.iter_mut().zip(inputs) {
                    *o = f(black_box(x));
                }
                black_box(&mut *out);
            }
            start.elapsed().as_secs_f64() * 1e9 / (REPS * inputs.len()) as f64
        }
        fn latency(inputs: &[f64], f: impl Fn(f64) -> f64) -> f64 {
            let start = Instant::now();
            let mut acc = 0.0;
            for _ in 0..REPS {
                for &x in inputs {
                    acc = f(x + acc * 0.0);
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
                let inputs: &[f64] = $inputs;
                let mut out = vec![0.0; inputs.len()];
                let mut t = [(); 4].map(|_| Vec::with_capacity(ROUNDS));
                for _ in 0..ROUNDS {
                    t[0].push(throughput(inputs, &mut out, $ours));
                    t[1].push(throughput(inputs, &mut out, $theirs));
                    t[2].push(latency(inputs, $ours));
                    t[3].push(latency(inputs, $theirs));
                }
                let [a, b, c, d] = t.map(median);
                println!(
                    "{:<18} throughput {a:5.2} vs {b:5.2} ns ({:.2}x)   latency {c:5.2} vs {d:5.2} ns ({:.2}x)",
                    $name,
                    b / a,
                    d / c
                );
            }};
        }

        let mut rng = Rng(8);
        let exp_in: Vec<f64> = (0..N).map(|_| rng.uniform(-30.0, 5.0)).collect();
        let ln_in: Vec<f64> = (0..N).map(|_| 1.0 - rng.uniform(0.0, 1.0)).collect();
        let angle_in: Vec<f64> = (0..N).map(|_| rng.uniform(0.0, 2.0 * PI)).collect();
        let phase_in: Vec<f64> = (0..N).map(|_| rng.uniform(0.0, 3000.0)).collect();
        let ours = |x| {
            let (s, c) = sin_cos(x);
            s + c
        };
        let theirs = |x: f64| {
            let (s, c) = x.sin_cos();
            s + c
        };
        println!("fastmath vs std, ns per call (medians of {ROUNDS} interleaved runs)");
        compare!("identity", &exp_in, |x| x, |x| x);
        compare!("exp [-30, 5)", &exp_in, exp, f64::exp);
        compare!("ln (0, 1]", &ln_in, ln, f64::ln);
        compare!("sin_cos [0, 2π)", &angle_in, ours, theirs);
        compare!("sin_cos [0, 3000)", &phase_in, ours, theirs);
    }
}
