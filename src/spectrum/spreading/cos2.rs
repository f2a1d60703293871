//! Phillips' cos²θ spreading with swell: its normalizer.

use super::ln_np;
use crate::fastmath::ln;

/// ln ∫cos²θ cos^{2s}(θ/2) dθ = ln N_s + ln(1 − 2(2s+1)/((2s+2)(s+2))) (Wallis).
pub(crate) fn ln_z_cos2(s: f64) -> f64 {
    ln_np(s) + ln(1.0 - 2.0 * (2.0 * s + 1.0) / ((2.0 * s + 2.0) * (s + 2.0)))
}
