//! The JONSWAP spectrum of a fetch-limited sea.

use super::{
    FETCH, FrequencySpectrum, G, HS, JonswapShape, PM_PEAK_COEF, SCALED_DNV, SCALED_GIVEN,
    SCALED_HS, SCALED_WIND, TP, TWO_PI, WIND_SPEED, check_gamma, param, positive,
};
use crate::error::ParamError;
use crate::fastmath::{exp, ln};

/// Fetch-limited sea: the PM shape times the peak enhancement γ^r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jonswap {
    pub(super) shape: JonswapShape,
    pub(super) hs_m: f64,
    pub(super) fetch_m: Option<f64>,
    pub(super) scaling: &'static str,
}

impl Jonswap {
    /// General form: α > 0, fp > 0 Hz, 1 ≤ γ ≤ 20.
    pub fn new(alpha: f64, fp_hz: f64, gamma: f64) -> Result<Self, ParamError> {
        positive("spectrum α", "", alpha)?;
        positive("spectrum peak frequency", " Hz", fp_hz)?;
        check_gamma(gamma)?;
        Ok(Self::from_shape(
            JonswapShape::new(alpha * G * G / TWO_PI.powi(4), fp_hz, gamma, f64::INFINITY),
            None,
            SCALED_GIVEN,
        ))
    }

    pub(super) fn from_shape(
        shape: JonswapShape,
        fetch_m: Option<f64>,
        scaling: &'static str,
    ) -> Self {
        Self {
            shape,
            hs_m: 4.0 * shape.m0_numeric().sqrt(),
            fetch_m,
            scaling,
        }
    }

    /// The fetch beyond which the sea is fully developed: where the fetch law's peak
    /// 22 (g²/(U F))^{1/3} reaches the Pierson–Moskowitz peak 2π·0.13 g/U, i.e.
    /// F = g² / (U (2π·0.13 g/(22 U))³) ≈ 19 900 U²/g (199 km at 10 m/s).
    pub fn fully_developed_fetch_m(u10_mps: f64) -> f64 {
        let w = TWO_PI * PM_PEAK_COEF * G / (22.0 * u10_mps);
        G * G / (u10_mps * w * w * w)
    }

    /// Standard JONSWAP fetch laws (F in m): ω_p = 22 (g²/(U F))^{1/3},
    /// α = 0.076 (U²/(F g))^{0.22}. U > 0 m/s, F > 0, 1 ≤ γ ≤ 20.
    ///
    /// Cap: a fetch longer than [`fully_developed_fetch_m`](Self::fully_developed_fetch_m)
    /// is clamped to it, so the peak never falls below the fully developed PM peak
    /// 0.13 g/U (and α, continuous in the fetch, stays at its value there, ≈ 0.0086).
    pub fn from_wind_fetch(u10_mps: f64, fetch_m: f64, gamma: f64) -> Result<Self, ParamError> {
        positive(WIND_SPEED, " m/s", u10_mps)?;
        if !(fetch_m > 0.0 && fetch_m.is_finite()) {
            return Err(param(FETCH, "> 0 km", fetch_m / 1000.0));
        }
        check_gamma(gamma)?;
        let fetch = fetch_m.min(Self::fully_developed_fetch_m(u10_mps));
        let omega_p = 22.0 * exp(ln(G * G / (u10_mps * fetch)) / 3.0);
        let alpha = 0.076 * exp(0.22 * ln(u10_mps * u10_mps / (fetch * G)));
        let a = alpha * G * G / TWO_PI.powi(4);
        Ok(Self::from_shape(
            JonswapShape::new(a, omega_p / TWO_PI, gamma, f64::INFINITY),
            Some(fetch),
            SCALED_WIND,
        ))
    }

    /// DNV-RP-C205: S(ω) = A_γ · S_PM(ω; Hs, ωp = 2π/Tp) · γ^r, A_γ = 1 − 0.287 ln γ.
    /// A_γ makes 4√m0 only approximately Hs: within 0.15 % for γ ≤ 5, 1 % at γ = 7,
    /// 3.6 % at γ = 10 and 22 % low at γ = 20 ([`hs_m`](FrequencySpectrum::hs_m) reports
    /// the model's own value); [`from_hs_tp_exact`](Self::from_hs_tp_exact) rescales instead.
    pub fn from_hs_tp(hs_m: f64, tp_s: f64, gamma: f64) -> Result<Self, ParamError> {
        positive(HS, " m", hs_m)?;
        positive(TP, " s", tp_s)?;
        check_gamma(gamma)?;
        let fp = 1.0 / tp_s;
        let fp2 = fp * fp;
        let a_gamma = 1.0 - 0.287 * ln(gamma);
        let a = a_gamma * 5.0 / 16.0 * hs_m * hs_m * fp2 * fp2;
        Ok(Self::from_shape(
            JonswapShape::new(a, fp, gamma, f64::INFINITY),
            None,
            SCALED_DNV,
        ))
    }

    /// The JONSWAP shape of peak period Tp and enhancement γ, scaled so that 4√m0 = Hs
    /// (to the accuracy of the numerical m0, 1e-9).
    pub fn from_hs_tp_exact(hs_m: f64, tp_s: f64, gamma: f64) -> Result<Self, ParamError> {
        positive(HS, " m", hs_m)?;
        positive(TP, " s", tp_s)?;
        check_gamma(gamma)?;
        let fp = 1.0 / tp_s;
        let unit = JonswapShape::new(1.0, fp, gamma, f64::INFINITY);
        let a = hs_m * hs_m / 16.0 / unit.m0_numeric();
        Ok(Self::from_shape(
            JonswapShape::new(a, fp, gamma, f64::INFINITY),
            None,
            SCALED_HS,
        ))
    }

    pub fn alpha(&self) -> f64 {
        self.shape.alpha()
    }
    pub fn fp_hz(&self) -> f64 {
        self.shape.fp_hz
    }
    pub fn gamma(&self) -> f64 {
        self.shape.gamma
    }
    /// The fetch used by [`from_wind_fetch`](Self::from_wind_fetch) after the cap, m.
    pub fn effective_fetch_m(&self) -> Option<f64> {
        self.fetch_m
    }
}

impl FrequencySpectrum for Jonswap {
    fn density(&self, f_hz: f64) -> f64 {
        self.shape.density(f_hz)
    }
    fn peak_hz(&self) -> f64 {
        self.shape.fp_hz
    }
    fn hs_m(&self) -> f64 {
        self.hs_m
    }
    fn shape(&self) -> Option<JonswapShape> {
        Some(self.shape)
    }
    fn scaling(&self) -> &'static str {
        self.scaling
    }
}
