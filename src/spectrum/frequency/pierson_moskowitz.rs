//! The Pierson–Moskowitz spectrum of a fully developed sea.

use super::{
    FrequencySpectrum, G, HS, JonswapShape, PM_ALPHA, PM_PEAK_COEF, SCALED_GIVEN, SCALED_HS,
    SCALED_WIND, TP, TWO_PI, WIND_SPEED, positive,
};
use crate::error::ParamError;

/// Fully developed sea (Mastin eq. 1–2): F(f) = α g² (2π)⁻⁴ f⁻⁵ exp(−5/4 (fm/f)⁴).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PiersonMoskowitz {
    pub(super) shape: JonswapShape,
    scaling: &'static str,
}

impl PiersonMoskowitz {
    /// General form: α > 0, fm > 0 Hz.
    pub fn new(alpha: f64, fm_hz: f64) -> Result<Self, ParamError> {
        positive("spectrum α", "", alpha)?;
        positive("spectrum peak frequency", " Hz", fm_hz)?;
        Ok(Self {
            shape: JonswapShape::new(alpha * G * G / TWO_PI.powi(4), fm_hz, 1.0, f64::INFINITY),
            scaling: SCALED_GIVEN,
        })
    }

    /// α = 0.0081, fm = 0.13 g / U10; U10 > 0 m/s.
    pub fn from_wind(u10_mps: f64) -> Result<Self, ParamError> {
        positive(WIND_SPEED, " m/s", u10_mps)?;
        let pm = Self::new(PM_ALPHA, PM_PEAK_COEF * G / u10_mps)?;
        Ok(Self {
            scaling: SCALED_WIND,
            ..pm
        })
    }

    /// The PM shape with fm = 1/Tp and α such that 4√m0 = Hs exactly (DNV-RP-C205:
    /// S(ω) = 5/16 Hs² ωp⁴ ω⁻⁵ exp(−5/4 (ω/ωp)⁻⁴), F(f) = 2π S(2πf), i.e.
    /// A = 5/16 Hs² fp⁴).
    pub fn from_hs_tp(hs_m: f64, tp_s: f64) -> Result<Self, ParamError> {
        positive(HS, " m", hs_m)?;
        positive(TP, " s", tp_s)?;
        let fp = 1.0 / tp_s;
        let fp2 = fp * fp;
        Ok(Self {
            shape: JonswapShape::new(5.0 / 16.0 * hs_m * hs_m * fp2 * fp2, fp, 1.0, f64::INFINITY),
            scaling: SCALED_HS,
        })
    }

    pub fn alpha(&self) -> f64 {
        self.shape.alpha()
    }
    pub fn fm_hz(&self) -> f64 {
        self.shape.fp_hz
    }
    /// m0 = α g² / (5 (2π)⁴ fm⁴), m².
    pub fn m0(&self) -> f64 {
        self.shape.m0_pm()
    }
}

impl FrequencySpectrum for PiersonMoskowitz {
    fn density(&self, f_hz: f64) -> f64 {
        self.shape.density(f_hz)
    }
    fn peak_hz(&self) -> f64 {
        self.shape.fp_hz
    }
    fn hs_m(&self) -> f64 {
        4.0 * self.m0().sqrt()
    }
    fn shape(&self) -> Option<JonswapShape> {
        Some(self.shape)
    }
    fn scaling(&self) -> &'static str {
        self.scaling
    }
}
