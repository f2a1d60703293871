//! e^x (see the parent module for the algorithm and its accuracy).

use super::ROUND_MAGIC;

/// The exp table has `2^EXP_TABLE_BITS` entries `2^(j/32)`.
const EXP_TABLE_BITS: u32 = 5;
/// 32/ln 2.
pub(super) const EXP_N_INV_LN2: f64 = f64::from_bits(0x4047_1547_652B_82FE);
/// ln2/32 rounded to 36 significant bits (so `k·EXP_LN2_N_HI` is exact for `|k| < 2^17`),
/// and the rest (|k·EXP_LN2_N_LO| < 2e-9, small enough to be applied as a factor `1 − lo`).
pub(super) const EXP_LN2_N_HI: f64 = f64::from_bits(0x3F96_2E42_FEFA_0000);
pub(super) const EXP_LN2_N_LO: f64 = f64::from_bits(0x3D2C_F79A_BC9E_3B3A);
/// Below this |x| the result and every intermediate is a normal number far from overflow,
/// and the scale factor can be built by adding to the exponent bits.
pub(super) const EXP_FAST_LIMIT: f64 = 690.0;
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
