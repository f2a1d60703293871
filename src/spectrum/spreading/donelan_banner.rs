//! Donelan–Banner (1985) spreading: β(f/fp) and the normalizer with swell.

use super::{integrate_circle_even, ln_half_one_plus, sech2};
use crate::fastmath::{exp, ln, sin_cos};

/// Donelan–Banner β at r = f/fp (r < 0.56 is held at 0.56).
pub fn donelan_banner_beta(r: f64) -> f64 {
    let r = r.max(DB_R_MIN);
    db_beta_branch(db_branch(r), ln(r))
}

pub(crate) const DB_R_MIN: f64 = 0.56;
pub(crate) const DB_R_1: f64 = 0.95;
pub(crate) const DB_R_2: f64 = 1.6;

/// 0: r < 0.95, 1: 0.95 ≤ r < 1.6, 2: r ≥ 1.6.
#[inline]
fn db_branch(r: f64) -> usize {
    if r < DB_R_1 {
        0
    } else if r < DB_R_2 {
        1
    } else {
        2
    }
}

/// The formula of branch `b` at x = ln r (extends analytically past the branch ends).
#[inline]
pub(crate) fn db_beta_branch(b: usize, x: f64) -> f64 {
    match b {
        0 => 2.61 * exp(1.3 * x),
        1 => 2.28 * exp(-1.3 * x),
        _ => exp(std::f64::consts::LN_10 * (-0.4 + 0.8393 * exp(-1.134 * x))),
    }
}

/// ∫_{−π}^{π} sech²(βθ) cos^{2s}(θ/2) dθ, numerically: 8 panels per quarter turn
/// (relative error < 1e-9, see the tests).
pub(crate) fn donelan_banner_norm(beta: f64, s: f64) -> f64 {
    integrate_circle_even(
        |t| sech2(beta * t) * exp(s * ln_half_one_plus(sin_cos(t).1)),
        s,
        8,
    )
}
