//! Hasselmann spreading: the exponent p(f) and the normalizer N_p of the cos^{2p}(θ/2)
//! family (shared by Mitsuyasu and the swell factor).

use super::{LN_2_SQRT_PI, PI, TWO_PI};
use crate::fastmath::{exp, ln, sin_cos};

/// Hasselmann's p = 9.77 (f/fm)^μ, μ = 4.06 for f < fm, −2.34 for f ≥ fm.
pub fn p_hasselmann(f_hz: f64, fm_hz: f64) -> f64 {
    if f_hz.is_nan() || f_hz <= 0.0 {
        return 0.0;
    }
    let x = ln(f_hz / fm_hz);
    9.77 * exp(if x < 0.0 { 4.06 } else { -2.34 } * x)
}

/// N_p = 2^{1−2p} π Γ(2p+1)/Γ(p+1)² = ∫_{−π}^{π} cos^{2p}(θ/2) dθ, p ≥ 0.
pub fn np_hasselmann(p: f64) -> f64 {
    exp(ln_np(p))
}

/// ln N_p, evaluated as ln(2√π) + ln Γ(p+½) − ln Γ(p+1) (the duplication formula turns
/// Mastin's eq. 6 into this), by Lanczos below p = 64 and a Stirling expansion of the
/// ratio above, so that large p neither overflows nor cancels. Accurate to ~1e-15.
pub fn ln_np(p: f64) -> f64 {
    if p < 64.0 {
        LN_2_SQRT_PI + ln_gamma(p + 0.5) - ln_gamma(p + 1.0)
    } else {
        ln_np_large(p)
    }
}

/// log2 N_s in single precision for s ≥ 0 (s ≤ 1e6): straight-line code (one division,
/// one `log2_f32`) for the grid's vectorized passes. By the recurrence
/// Γ(x + 1) = x Γ(x) four times and the asymptotic series of the ratio,
/// ln Γ(s+½) − ln Γ(s+1) = −½ ln(z·r²) − 1/(8z) + 1/(192z³) − 1/(640z⁵) + 17/(14336z⁷)
/// (truncation below 7e-9 at z ≥ 4), z = s + 4, r = Π_{i<4} (s+½+i)/(s+1+i).
/// Error below 5e-7·(1 + |log2 N_s|) (the rounding of the single-precision products and
/// logarithm; tested against [`ln_np`]).
#[inline(always)]
pub(crate) fn log2_np_f32(s: f32) -> f32 {
    const LOG2_E: f32 = std::f32::consts::LOG2_E;
    const LOG2_2_SQRT_PI: f32 = (LN_2_SQRT_PI * std::f64::consts::LOG2_E) as f32;
    let z = s + 4.0;
    let p1 = ((s + 0.5) * (s + 1.5)) * ((s + 2.5) * (s + 3.5));
    let q3 = (s + 1.0) * (s + 2.0) * (s + 3.0);
    // One division: r = p1/p2 and 1/z = q3/p2, p2 = q3·z.
    let inv_p2 = 1.0 / (q3 * z);
    let r = p1 * inv_p2;
    let iz = q3 * inv_p2;
    let iz2 = iz * iz;
    let series =
        iz * (-1.0 / 8.0 + iz2 * (1.0 / 192.0 + iz2 * (-1.0 / 640.0 + iz2 * (17.0 / 14336.0))));
    LOG2_2_SQRT_PI - 0.5 * crate::fastmath::log2_f32(z * (r * r)) + LOG2_E * series
}

/// ln N_p for p ≥ 64: ln Γ(p+½) − ln Γ(p+1) = s ln(s+½) − (s+½) ln(s+1) + ½ + Δ_Stirling,
/// with s ln(s+½) − (s+½) ln(s+1) = −½ ln(s+1) + s·ln(1 − 1/(2s+2)) (series for the log1p).
pub(super) fn ln_np_large(s: f64) -> f64 {
    let y = -0.5 / (s + 1.0);
    // ln(1 + y), |y| ≤ 1/130: the series to y^10 is exact to double precision.
    let mut term = y;
    let mut l1p = 0.0;
    for n in 1..=10 {
        l1p += term / n as f64;
        term *= -y;
    }
    let stirling = |z: f64| {
        let iz = 1.0 / z;
        let iz2 = iz * iz;
        iz * (1.0 / 12.0 - iz2 * (1.0 / 360.0 - iz2 * (1.0 / 1260.0 - iz2 / 1680.0)))
    };
    LN_2_SQRT_PI - 0.5 * ln(s + 1.0) + s * l1p + 0.5 + stirling(s + 0.5) - stirling(s + 1.0)
}

/// ln Γ(x) for x > 0: Lanczos (g = 7, 9 terms) for x ≥ ½, reflection below.
/// Absolute error ≲ 1e-14 for x ≤ 100 (relative ≲ 1e-15 away from the zeros at 1 and 2).
pub fn ln_gamma(x: f64) -> f64 {
    const COEF: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Γ(x)Γ(1−x) = π / sin(πx).
        return ln(PI / sin_cos(PI * x).0) - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = COEF[0];
    for (i, c) in COEF.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    let t = x + 7.5;
    0.5 * ln(TWO_PI) + (x + 0.5) * ln(t) - t + ln(a)
}
