//! The convergence limit of the second-order series: which free waves are paired.

use super::draws::{every_line, lines_of};
use super::{G, Isa, depth_of, r_of, tanh};
use crate::field::fft::SpectrumSetup;
use crate::spectrum::Dispersion;

/// Nestegaard & Stokka's (1995) convergence limit of the second-order series, as WAFO's
/// second-order simulation applies it: only waves of ω_lo ≤ ω ≤ ω_up are paired, with
/// ω_up² = C g tanh(k̄d)/A_max and ω_lo² = g tanh(k̄d) A_max/d³ (finite depth), A_max =
/// √(2 ln 1000)·Hs/4 the expected largest amplitude of a thousand waves and k̄ the
/// wavenumber of the mean period Tm02. Above ω_up a wave's Eulerian expansion about the
/// long waves' surface fails (k·A_max > C: the short waves are carried further than their
/// length, and their pair terms grow with the resolution without converging); those waves
/// stay linear. C = 2 is the convergence criterion, ½ the "no bump in the trough" one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cutoff {
    /// ω_up and ω_lo, rad/s (ω_lo 0 in deep water).
    pub omega_up: f64,
    pub omega_lo: f64,
    /// The linear sea's Hs (4√m0) and Tm02 (2π√(m0/m2)) the limits were taken from.
    pub hs_m: f64,
    pub tm02_s: f64,
}

impl Cutoff {
    /// The limits of criterion `c` for the expected spectrum of `setup`'s draws.
    pub fn of(setup: &SpectrumSetup, c: f64) -> Self {
        let isa = Isa::detect();
        let depth = depth_of(setup.dispersion);
        let lines = lines_of(setup, isa, every_line(setup), false, &|draws| {
            let (mut m0, mut m2) = (0.0, 0.0);
            for d in draws {
                m0 += 2.0 * d.p;
                m2 += 2.0 * d.p * G * r_of(setup, depth, d.n, d.m);
            }
            (m0, m2)
        });
        let (m0, m2) = lines
            .into_iter()
            .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1));
        Self::from_moments(m0, m2, setup.dispersion, c)
    }

    /// The limits of criterion `c` for a sea of variance `m0` (m²) and second frequency
    /// moment `m2` (m²/s²).
    pub fn from_moments(m0: f64, m2: f64, dispersion: Dispersion, c: f64) -> Self {
        let hs_m = 4.0 * m0.sqrt();
        let a_max = (2.0 * 1000f64.ln()).sqrt() * hs_m / 4.0;
        let omega_bar = if m0 > 0.0 { (m2 / m0).sqrt() } else { 0.0 };
        let k_bar = dispersion.wavenumber(omega_bar);
        let (t, lo) = match dispersion {
            Dispersion::Deep => (1.0, 0.0),
            Dispersion::Finite { depth_m } => {
                let t = tanh(k_bar * depth_m);
                (t, (G * t * a_max / depth_m.powi(3)).sqrt())
            }
        };
        let up = if a_max > 0.0 {
            (c * G * t / a_max).sqrt()
        } else {
            f64::INFINITY
        };
        Self {
            omega_up: up,
            omega_lo: lo,
            hs_m,
            tm02_s: if omega_bar > 0.0 {
                2.0 * std::f64::consts::PI / omega_bar
            } else {
                0.0
            },
        }
    }

    /// The wave of R = ω²/g lies within the limits.
    #[inline]
    pub(super) fn admits(&self, r: f64) -> bool {
        let w2 = G * r;
        w2 <= self.omega_up * self.omega_up && w2 >= self.omega_lo * self.omega_lo
    }
}
