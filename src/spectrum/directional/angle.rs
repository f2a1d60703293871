//! The angle of a wavevector from the wind: a portable arctangent.

use super::PI;

/// atan2(y, x) for y ≥ 0, in [0, π]: fdlibm's atan (basic operations only, so the same
/// on every platform; error < 1 ulp).
#[inline]
pub(crate) fn atan2_pos(y: f64, x: f64) -> f64 {
    const PI_LO: f64 = 1.224_646_799_147_353_2e-16;
    if y == 0.0 {
        return if x >= 0.0 { 0.0 } else { PI };
    }
    if x == 0.0 {
        return 0.5 * PI;
    }
    if x > 0.0 {
        atan_pos(y / x)
    } else {
        PI - (atan_pos(y / -x) - PI_LO)
    }
}

/// atan x for x ≥ 0 (fdlibm s_atan.c; its constants as published).
#[inline]
#[allow(clippy::excessive_precision, clippy::approx_constant)]
fn atan_pos(x: f64) -> f64 {
    const ATANHI: [f64; 4] = [
        4.636_476_090_008_060_935_15e-01,
        7.853_981_633_974_482_789_99e-01,
        9.827_937_232_473_290_540_82e-01,
        1.570_796_326_794_896_558_00e+00,
    ];
    const ATANLO: [f64; 4] = [
        2.269_877_745_296_168_709_24e-17,
        3.061_616_997_868_383_017_93e-17,
        1.390_331_103_123_099_845_16e-17,
        6.123_233_995_736_766_035_87e-17,
    ];
    const AT: [f64; 11] = [
        3.333_333_333_333_293_180_27e-01,
        -1.999_999_999_987_648_324_76e-01,
        1.428_571_427_250_346_637_11e-01,
        -1.111_111_040_546_235_578_80e-01,
        9.090_887_133_436_506_561_96e-02,
        -7.691_876_205_044_829_994_95e-02,
        6.661_073_137_387_531_206_69e-02,
        -5.833_570_133_790_573_486_45e-02,
        4.976_877_994_615_932_360_17e-02,
        -3.653_157_274_421_691_552_70e-02,
        1.628_582_011_536_578_236_23e-02,
    ];
    if x >= 7.378_697_629_483_821e19 {
        // 2^66: atan x = π/2 to double precision.
        return ATANHI[3] + ATANLO[3];
    }
    let (id, x) = if x < 0.4375 {
        if x < 1.862_645_149_230_957e-9 {
            return x;
        }
        (usize::MAX, x)
    } else if x < 1.1875 {
        if x < 0.6875 {
            (0, (2.0 * x - 1.0) / (2.0 + x))
        } else {
            (1, (x - 1.0) / (x + 1.0))
        }
    } else if x < 2.4375 {
        (2, (x - 1.5) / (1.0 + 1.5 * x))
    } else {
        (3, -1.0 / x)
    };
    let z = x * x;
    let w = z * z;
    let s1 = z * (AT[0] + w * (AT[2] + w * (AT[4] + w * (AT[6] + w * (AT[8] + w * AT[10])))));
    let s2 = w * (AT[1] + w * (AT[3] + w * (AT[5] + w * (AT[7] + w * AT[9]))));
    if id == usize::MAX {
        x - x * (s1 + s2)
    } else {
        ATANHI[id] - ((x * (s1 + s2) - ATANLO[id]) - x)
    }
}
