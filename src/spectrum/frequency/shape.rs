//! The parametric form every frequency model here shares, and its moments.

use super::quadrature::{gauss_legendre, integrate};
use super::{G, SIGMA_HIGH, SIGMA_LOW, TWO_PI};
use crate::fastmath::{exp, ln};

/// Kitaigorodskii's depth factor Φ(ω_h), ω_h = ω·√(d/g): ½ω_h² for ω_h ≤ 1,
/// 1 − ½(2 − ω_h)² for 1 < ω_h < 2, 1 above (continuous with a continuous slope).
#[inline]
pub fn kitaigorodskii(omega_h: f64) -> f64 {
    if omega_h <= 1.0 {
        0.5 * omega_h * omega_h
    } else if omega_h < 2.0 {
        let d = 2.0 - omega_h;
        1.0 - 0.5 * d * d
    } else {
        1.0
    }
}

/// F(f) = A f⁻⁵ exp(−5/4 (fp/f)⁴) · γ^r · Φ(ω_h): the form shared by every model here.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JonswapShape {
    pub(super) a: f64,
    pub(super) fp_hz: f64,
    pub(super) gamma: f64,
    pub(super) depth_m: f64,
    // Derived.
    pub(super) a_over_fp5: f64,
    pub(super) ln_gamma: f64,
    /// 2π·√(d/g): ω_h = f·this (∞ in deep water).
    pub(super) omega_h_per_hz: f64,
}

/// 1/(2σ²) below and above the peak.
pub(crate) const C_LOW: f64 = 1.0 / (2.0 * SIGMA_LOW * SIGMA_LOW);
pub(crate) const C_HIGH: f64 = 1.0 / (2.0 * SIGMA_HIGH * SIGMA_HIGH);

impl JonswapShape {
    /// `a` > 0 (m²·Hz⁴), `fp_hz` > 0, γ ≥ 1, `depth_m` > 0 or +∞ (no depth factor).
    /// Callers validate.
    pub(crate) fn new(a: f64, fp_hz: f64, gamma: f64, depth_m: f64) -> Self {
        let fp5 = fp_hz * fp_hz * fp_hz * fp_hz * fp_hz;
        Self {
            a,
            fp_hz,
            gamma,
            depth_m,
            a_over_fp5: a / fp5,
            ln_gamma: if gamma == 1.0 { 0.0 } else { ln(gamma) },
            omega_h_per_hz: if depth_m.is_finite() {
                TWO_PI * (depth_m / G).sqrt()
            } else {
                f64::INFINITY
            },
        }
    }

    /// The coefficient A of f⁻⁵, m²·Hz⁴ (A = α g² (2π)⁻⁴).
    pub fn a(&self) -> f64 {
        self.a
    }
    /// Phillips' α equivalent to A.
    pub fn alpha(&self) -> f64 {
        self.a * TWO_PI.powi(4) / (G * G)
    }
    /// The peak frequency of the PM/JONSWAP part, Hz.
    pub fn fp_hz(&self) -> f64 {
        self.fp_hz
    }
    pub fn gamma(&self) -> f64 {
        self.gamma
    }
    pub(crate) fn ln_gamma(&self) -> f64 {
        self.ln_gamma
    }
    /// Depth of the TMA factor, m (+∞: none).
    pub fn depth_m(&self) -> f64 {
        self.depth_m
    }

    /// F(f) in m²/Hz.
    #[inline]
    pub fn density(&self, f_hz: f64) -> f64 {
        if f_hz.is_nan() || f_hz <= 0.0 || f_hz == f64::INFINITY {
            return 0.0;
        }
        let iq = self.fp_hz / f_hz;
        let iq2 = iq * iq;
        let u = iq2 * iq2;
        // exp(−1.25·u) underflows to 0 (and f⁻⁵ would overflow far below here).
        if u > 640.0 {
            return 0.0;
        }
        let mut e = -1.25 * u;
        if self.ln_gamma != 0.0 {
            let d = f_hz / self.fp_hz - 1.0;
            let a = d * d * if d <= 0.0 { C_LOW } else { C_HIGH };
            // Far from the peak γ^r = 1 (and exp would take its slow path).
            if a < 700.0 {
                e += self.ln_gamma * exp(-a);
            }
        }
        let phi = if self.omega_h_per_hz.is_finite() {
            kitaigorodskii(f_hz * self.omega_h_per_hz)
        } else {
            1.0
        };
        self.a_over_fp5 * (iq2 * iq2 * iq) * exp(e) * phi
    }

    /// m0 = A/(5 fp⁴) of the Pierson–Moskowitz part alone (γ = 1, no depth factor).
    pub fn m0_pm(&self) -> f64 {
        let fp2 = self.fp_hz * self.fp_hz;
        self.a / (5.0 * fp2 * fp2)
    }

    /// ∫₀^∞ F df by composite 10-point Gauss–Legendre in u = ln f on panels of width
    /// ≤ 0.02, with panel breaks at the peak (σ switches) and at the kinks of Φ, from
    /// 0.05 fp (where F < e⁻²⁰⁰⁰⁰⁰ of its peak) to max(200 fp, 4 f(ω_h = 2)), plus the
    /// exact tail beyond (F = A f⁻⁵ exp(−5/4 (fp/f)⁴) there: γ^r = 1 and Φ = 1 to
    /// double precision). Relative error below 1e-9.
    pub fn m0_numeric(&self) -> f64 {
        let fp = self.fp_hz;
        let lo = 0.05 * fp;
        let mut hi = 200.0 * fp;
        let mut breaks = vec![lo, fp];
        if self.omega_h_per_hz.is_finite() {
            for wh in [1.0, 2.0] {
                let f = wh / self.omega_h_per_hz;
                if f > lo {
                    breaks.push(f);
                }
                hi = hi.max(4.0 * f);
            }
        }
        breaks.push(hi);
        breaks.sort_by(f64::total_cmp);
        let rule = gauss_legendre(10);
        let mut m0 = 0.0;
        for w in breaks.windows(2) {
            let (ua, ub) = (ln(w[0]), ln(w[1]));
            m0 += integrate(
                |u| {
                    let f = exp(u);
                    self.density(f) * f
                },
                ua,
                ub,
                ((ub - ua) / 0.02).ceil().max(1.0) as usize,
                &rule,
            );
        }
        // Tail: ∫_hi^∞ A f⁻⁵ exp(−b f⁻⁴) df = A/(4b)·(1 − exp(−b hi⁻⁴)), b = 5/4 fp⁴.
        let y = 1.25 * (fp / hi).powi(4);
        let one_minus = if y < 1e-4 {
            y * (1.0 - 0.5 * y)
        } else {
            1.0 - exp(-y)
        };
        m0 + self.m0_pm() * one_minus
    }

    /// The frequency of the maximum of F: fp without a depth factor; otherwise found
    /// numerically (a log grid from 0.3 fp to 6 fp, refined by golden-section search on
    /// ln F to 1e-12 relative).
    pub fn peak_numeric(&self) -> f64 {
        if !self.omega_h_per_hz.is_finite() {
            return self.fp_hz;
        }
        let n = 4000;
        let (a, b) = (ln(0.3 * self.fp_hz), ln(6.0 * self.fp_hz));
        let at = |i: usize| exp(a + (b - a) * i as f64 / n as f64);
        let mut best = 0;
        let mut best_v = -1.0;
        for i in 0..=n {
            let v = self.density(at(i));
            if v > best_v {
                best_v = v;
                best = i;
            }
        }
        let (mut lo, mut hi) = (at(best.saturating_sub(1)), at((best + 1).min(n)));
        let ratio = (5f64.sqrt() - 1.0) / 2.0;
        let mut x1 = hi - ratio * (hi - lo);
        let mut x2 = lo + ratio * (hi - lo);
        let (mut f1, mut f2) = (self.density(x1), self.density(x2));
        for _ in 0..200 {
            if hi - lo <= 1e-13 * hi {
                break;
            }
            if f1 < f2 {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + ratio * (hi - lo);
                f2 = self.density(x2);
            } else {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - ratio * (hi - lo);
                f1 = self.density(x1);
            }
        }
        0.5 * (lo + hi)
    }
}
