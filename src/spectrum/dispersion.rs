//! Dispersion relations ω(k): angular frequency (rad/s) of a wave of wavenumber k (rad/m).

use super::G;

/// How wave frequency depends on wavenumber.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Dispersion {
    /// Deep water, ω² = g·k.
    Deep,
}

impl Dispersion {
    /// Angular frequency ω(k) in rad/s for wavenumber `k` ≥ 0 in rad/m.
    pub fn omega(&self, k: f64) -> f64 {
        match self {
            Dispersion::Deep => (G * k).sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deep_water_phase_speed_is_sqrt_g_over_k() {
        for k in [0.01, 0.1, 1.0, 10.0] {
            let c = Dispersion::Deep.omega(k) / k;
            assert!((c - (G / k).sqrt()).abs() < 1e-12, "k = {k}");
        }
    }
}
