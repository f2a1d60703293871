//! Dispersion relations ω(k): angular frequency (rad/s) of a wave of wavenumber k (rad/m).
//! tanh is the portable one of `spreading` (fastmath's exp), so finite-depth frequencies
//! and the time evolution they drive are the same bits on every platform.

use super::G;
use super::spreading::tanh;

/// How wave frequency depends on wavenumber.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Dispersion {
    /// Deep water, ω² = g·k.
    Deep,
    /// Water of finite depth d in meters, ω² = g·k·tanh(k·d).
    Finite { depth_m: f64 },
}

impl Dispersion {
    /// The relation for a depth: `None` (or infinite) is deep water.
    pub fn for_depth(depth_m: Option<f64>) -> Self {
        match depth_m {
            Some(d) if d.is_finite() => Dispersion::Finite { depth_m: d },
            _ => Dispersion::Deep,
        }
    }

    /// Angular frequency ω(k) in rad/s for wavenumber `k` ≥ 0 in rad/m.
    #[inline]
    pub fn omega(&self, k: f64) -> f64 {
        match self {
            Dispersion::Deep => (G * k).sqrt(),
            Dispersion::Finite { depth_m } => (G * k * tanh(k * depth_m)).sqrt(),
        }
    }

    /// Group velocity dω/dk in m/s at wavenumber `k` > 0.
    #[inline]
    pub fn group_velocity(&self, k: f64) -> f64 {
        match self {
            Dispersion::Deep => 0.5 * (G / k).sqrt(),
            Dispersion::Finite { depth_m } => {
                let kd = k * depth_m;
                let t = tanh(kd);
                let w = (G * k * t).sqrt();
                // d(ω²)/dk = g·(tanh kd + kd·sech² kd); dω/dk = that / 2ω.
                G * (t + kd * (1.0 - t * t)) / (2.0 * w)
            }
        }
    }

    /// The wavenumber k (rad/m) of angular frequency `omega` (rad/s): exact in deep water,
    /// Newton's method on ω² = g k tanh(k d) otherwise (to machine precision).
    pub fn wavenumber(&self, omega: f64) -> f64 {
        let deep = omega * omega / G;
        match self {
            Dispersion::Deep => deep,
            Dispersion::Finite { depth_m } => {
                if omega <= 0.0 {
                    return 0.0;
                }
                // Start from the larger of the deep and shallow (ω/√(g d)) answers: the
                // iteration then decreases monotonically to the root.
                let mut k = deep.max(omega / (G * depth_m).sqrt());
                for _ in 0..100 {
                    let t = tanh(k * depth_m);
                    let f = G * k * t - omega * omega;
                    let df = G * (t + k * depth_m * (1.0 - t * t));
                    let step = f / df;
                    k -= step;
                    if step.abs() <= 1e-15 * k {
                        break;
                    }
                }
                k
            }
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

    #[test]
    fn finite_depth_tends_to_deep_and_shallow_limits() {
        const REL: f64 = 1e-9;
        let deep = Dispersion::Finite { depth_m: 1e4 };
        for k in [0.01, 0.1, 1.0] {
            let w = Dispersion::Deep.omega(k);
            assert!(
                (deep.omega(k) - w).abs() <= REL * w,
                "deep limit at k = {k}"
            );
        }
        // Shallow: ω ≈ k·√(g d) when k d ≪ 1.
        let shallow = Dispersion::Finite { depth_m: 1.0 };
        let k = 1e-4;
        let c = shallow.omega(k) / k;
        assert!(
            (c - (G * 1.0f64).sqrt()).abs() < 1e-6 * c,
            "shallow limit {c}"
        );
    }

    #[test]
    fn wavenumber_inverts_omega_and_group_velocity_is_the_derivative() {
        for d in [
            Dispersion::Deep,
            Dispersion::Finite { depth_m: 3.0 },
            Dispersion::Finite { depth_m: 50.0 },
        ] {
            for k in [0.003, 0.05, 0.4, 2.0, 30.0] {
                let w = d.omega(k);
                let back = d.wavenumber(w);
                assert!(
                    (back - k).abs() <= 1e-12 * k,
                    "{d:?}: k {k} → ω {w} → {back}"
                );
                let h = 1e-6 * k;
                let numeric = (d.omega(k + h) - d.omega(k - h)) / (2.0 * h);
                let cg = d.group_velocity(k);
                assert!(
                    (cg - numeric).abs() <= 1e-6 * cg,
                    "{d:?}: cg {cg} vs {numeric} at k {k}"
                );
            }
        }
    }
}
