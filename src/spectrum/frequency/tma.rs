//! The TMA spectrum: JONSWAP in water of finite depth.

use super::{
    DEPTH, FrequencySpectrum, Jonswap, JonswapShape, SCALED_HS_DEPTH, SCALED_WIND,
    SCALED_WIND_DEPTH, kitaigorodskii, param,
};
use crate::error::ParamError;

/// JONSWAP in water of depth d: F_TMA(f) = F_JONSWAP(f) · Φ(2πf √(d/g)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tma {
    pub(super) jonswap: Jonswap,
    pub(super) shape: JonswapShape,
    pub(super) peak_hz: f64,
    pub(super) hs_m: f64,
}

impl Tma {
    /// `depth_m` > 0 (+∞ allowed: exactly the JONSWAP).
    pub fn new(jonswap: Jonswap, depth_m: f64) -> Result<Self, ParamError> {
        if depth_m.is_nan() || depth_m <= 0.0 {
            return Err(param(DEPTH, "> 0 m", depth_m));
        }
        let j = jonswap.shape;
        let shape = JonswapShape::new(j.a, j.fp_hz, j.gamma, depth_m);
        Ok(Self {
            jonswap,
            shape,
            peak_hz: shape.peak_numeric(),
            hs_m: 4.0 * shape.m0_numeric().sqrt(),
        })
    }

    /// [`Jonswap::from_wind_fetch`] in water of depth `depth_m`.
    pub fn from_wind_fetch(
        u10_mps: f64,
        fetch_m: f64,
        gamma: f64,
        depth_m: f64,
    ) -> Result<Self, ParamError> {
        Self::new(Jonswap::from_wind_fetch(u10_mps, fetch_m, gamma)?, depth_m)
    }

    /// The TMA of JONSWAP shape (fp = 1/Tp, γ) in water of depth `depth_m` whose own
    /// 4·√m0, the depth factor included, is `hs_m`: α is set after the depth factor (m0 is
    /// linear in α), so the sea a user asks for by Hs has that Hs. (The TMA's peak moves a
    /// little above fp in shallow water; [`peak_hz`](FrequencySpectrum::peak_hz) reports it.)
    pub fn from_hs_tp(hs_m: f64, tp_s: f64, gamma: f64, depth_m: f64) -> Result<Self, ParamError> {
        let deep = Jonswap::from_hs_tp_exact(hs_m, tp_s, gamma)?;
        let shallow = Self::new(deep, depth_m)?;
        let j = deep.shape;
        let scale = (hs_m / shallow.hs_m).powi(2);
        let scaled = Jonswap::from_shape(
            JonswapShape::new(j.a * scale, j.fp_hz, j.gamma, f64::INFINITY),
            None,
            SCALED_HS_DEPTH,
        );
        Self::new(scaled, depth_m)
    }

    pub fn jonswap(&self) -> &Jonswap {
        &self.jonswap
    }
    pub fn depth_m(&self) -> f64 {
        self.shape.depth_m
    }
    /// Φ at frequency `f_hz`.
    pub fn depth_factor(&self, f_hz: f64) -> f64 {
        if self.shape.omega_h_per_hz.is_finite() {
            kitaigorodskii(f_hz * self.shape.omega_h_per_hz)
        } else {
            1.0
        }
    }
}

impl FrequencySpectrum for Tma {
    fn density(&self, f_hz: f64) -> f64 {
        self.shape.density(f_hz)
    }
    fn peak_hz(&self) -> f64 {
        self.peak_hz
    }
    fn hs_m(&self) -> f64 {
        self.hs_m
    }
    fn shape(&self) -> Option<JonswapShape> {
        Some(self.shape)
    }
    fn scaling(&self) -> &'static str {
        match self.jonswap.scaling {
            SCALED_WIND => SCALED_WIND_DEPTH,
            s => s,
        }
    }
}
