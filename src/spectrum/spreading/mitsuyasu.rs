//! Mitsuyasu (1975) spreading: s_max and s(f).

use super::{G, TWO_PI};
use crate::fastmath::{exp, ln};

/// Mitsuyasu's s_max = 11.5 (U10/c_p)^{−2.5} = 11.5 (ω_p U10/g)^{−2.5}, c_p = g/(2π fp):
/// older seas (small U10/c_p) spread narrower. 0 for U10 ≤ 0 (no wind: isotropic).
pub fn mitsuyasu_s_max(u10_mps: f64, fp_hz: f64) -> f64 {
    if u10_mps.is_nan() || u10_mps <= 0.0 {
        return 0.0;
    }
    let cp = G / (TWO_PI * fp_hz);
    11.5 * exp(-2.5 * ln(u10_mps / cp))
}

/// Mitsuyasu's s = s_max (f/fp)⁵ for f < fp, s_max (f/fp)^{−2.5} from fp up.
pub fn mitsuyasu_s(f_hz: f64, fp_hz: f64, s_max: f64) -> f64 {
    if f_hz.is_nan() || f_hz <= 0.0 {
        return 0.0;
    }
    let x = ln(f_hz / fp_hz);
    s_max * exp(if x < 0.0 { 5.0 } else { -2.5 } * x)
}
