//! ln x (see the parent module for the algorithm and its accuracy).

/// ln 2 to 32 significant bits (so `k·LN2_HI` is exact for `|k| < 2^21`), and the rest.
pub(super) const LN2_HI: f64 = f64::from_bits(0x3FE6_2E42_FEE0_0000);
pub(super) const LN2_LO: f64 = f64::from_bits(0x3DEA_39EF_3579_3C76);
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
