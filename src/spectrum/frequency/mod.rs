//! One-sided frequency spectra F(f) in m²/Hz (f in Hz): Pierson–Moskowitz (Mastin eq. 1–2,
//! Thon eq. 5–6), JONSWAP and TMA.
//!
//! All three share one parametric form (a [`JonswapShape`]):
//!
//! F(f) = A · f⁻⁵ · exp(−5/4 (fp/f)⁴) · γ^r(f) · Φ(ω_h),
//! r = exp(−(f − fp)² / (2 σ² fp²)), σ = 0.07 for f ≤ fp, 0.09 above,
//!
//! with A = α g² (2π)⁻⁴ (Phillips' α), γ = 1 for Pierson–Moskowitz, and Kitaigorodskii's
//! depth factor Φ (TMA only, else 1). γ^r is computed as exp(r·ln γ), so the density stays
//! finite and positive for every valid input.
//!
//! Significant wave height Hs = 4·√m0, m0 = ∫F df: closed form for Pierson–Moskowitz,
//! otherwise a composite Gauss–Legendre integral in ln f computed once at construction
//! (relative error below 1e-9; see [`JonswapShape::m0_numeric`]).
//!
//! Elementary functions are `fastmath`'s, so values are bit-identical on every
//! platform.

use super::G;
use crate::error::ParamError;

const TWO_PI: f64 = 2.0 * std::f64::consts::PI;

/// Phillips' constant of the Pierson–Moskowitz spectrum (Mastin eq. 1).
pub const PM_ALPHA: f64 = 0.0081;
/// fm = 0.13 g / U10 (Mastin eq. 2).
pub const PM_PEAK_COEF: f64 = 0.13;
/// JONSWAP peak width below and above the peak.
pub const SIGMA_LOW: f64 = 0.07;
pub const SIGMA_HIGH: f64 = 0.09;
/// Allowed peak enhancement γ.
pub const GAMMA_MIN: f64 = 1.0;
pub const GAMMA_MAX: f64 = 20.0;

/// One-sided frequency spectrum F(f) in m²/Hz, f in Hz.
pub trait FrequencySpectrum: Send + Sync + std::fmt::Debug {
    /// F(f) ≥ 0, finite; 0 for f ≤ 0 (and for NaN).
    fn density(&self, f_hz: f64) -> f64;
    /// The frequency where F is largest, Hz.
    fn peak_hz(&self) -> f64;
    /// 4·√m0 of the model, m: closed form where it exists (PM), else a numerical integral
    /// computed once at construction.
    fn hs_m(&self) -> f64;
    /// The JONSWAP-family parameters, when the model is one: lets
    /// [`DirectionalSpectrum`](super::DirectionalSpectrum) evaluate F inline, without a
    /// virtual call per wavevector. `density` must equal `shape().density` bit for bit.
    fn shape(&self) -> Option<JonswapShape> {
        None
    }
    /// How the model's level was set (one of the `SCALED_*` texts), for the sidecar.
    fn scaling(&self) -> &'static str {
        SCALED_GIVEN
    }
}

/// The level (α) was given directly.
pub const SCALED_GIVEN: &str = "alpha and peak frequency given";
/// The level and peak came from the wind (and fetch) laws.
pub const SCALED_WIND: &str = "alpha and peak from the wind (and fetch) laws";
/// α was set so that 4·√m0 of the spectrum used equals --hs.
pub const SCALED_HS: &str = "alpha set so that 4*sqrt(m0) = hs";
/// TMA from wind and fetch: the JONSWAP of the fetch laws times the depth factor (Hs is
/// the model's, below the deep-water sea's).
pub const SCALED_WIND_DEPTH: &str =
    "alpha and peak from the wind and fetch laws, then times the depth factor";
/// TMA from --hs: α set with the depth factor included, so 4·√m0 = hs in the shallow sea.
pub const SCALED_HS_DEPTH: &str = "alpha set so that 4*sqrt(m0) = hs, depth factor included";
/// DNV-RP-C205's A_γ: 4·√m0 only approximately hs.
pub const SCALED_DNV: &str = "DNV A_gamma = 1 - 0.287 ln(gamma): 4*sqrt(m0) approximately hs";

fn param(name: &str, allowed: &str, got: impl std::fmt::Display) -> ParamError {
    ParamError {
        name: name.to_string(),
        allowed: allowed.to_string(),
        got: got.to_string(),
    }
}

fn positive(name: &str, unit: &str, v: f64) -> Result<f64, ParamError> {
    if v > 0.0 && v.is_finite() {
        Ok(v)
    } else {
        Err(param(name, &format!("> 0{unit}"), v))
    }
}

pub(crate) const WIND_SPEED: &str = "--wind-speed (wind.speed_mps)";
const HS: &str = "--hs (spectrum.hs_m)";
const TP: &str = "--tp (spectrum.tp_s)";
const GAMMA: &str = "--gamma (spectrum.gamma)";
const FETCH: &str = "--fetch-km (spectrum.fetch_km)";
pub(crate) const DEPTH: &str = "--depth (spectrum.depth_m)";

fn check_gamma(gamma: f64) -> Result<f64, ParamError> {
    if (GAMMA_MIN..=GAMMA_MAX).contains(&gamma) {
        Ok(gamma)
    } else {
        Err(param(GAMMA, "between 1 and 20", gamma))
    }
}

mod jonswap;
mod pierson_moskowitz;
mod quadrature;
mod shape;
mod tma;

pub use jonswap::Jonswap;
pub use pierson_moskowitz::PiersonMoskowitz;
pub use quadrature::gauss_legendre;
pub(crate) use quadrature::integrate;
pub(crate) use shape::{C_HIGH, C_LOW};
pub use shape::{JonswapShape, kitaigorodskii};
pub use tma::Tma;

#[cfg(test)]
mod tests;
