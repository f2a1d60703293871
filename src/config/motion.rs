//! How a sea moves: the time-dependent parameters (`motion.*`) — loops, frame rate,
//! choppiness, foam and the phase mode of filtered noise.

use serde::{Deserialize, Serialize};

/// How filtered-noise fields move (Mastin et al., "Ocean scene animation").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PhaseMode {
    /// Each component advances by ω(k)·t, ω from the dispersion relation (the default).
    Dispersion,
    /// A linear phase: the whole image translates along the wind.
    Translate,
    /// "Hot Air": components near the peak advance `hot_air_dominant_rad` per frame, the
    /// rest `hot_air_other_rad`.
    HotAir,
}

/// Waves in motion: looping, choppiness, foam and the filtered-noise phase modes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MotionParams {
    /// Seamless loop period T, s: every ω becomes the nearest non-zero multiple of 2π/T.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub loop_period_s: Option<f64>,
    /// Horizontal displacement factor λ of choppy waves (0: none).
    pub choppiness: f64,
    /// Foam where the Jacobian J < this: `"auto"` (the whitecap coverage of the wind,
    /// `measure::foam`) or a number.
    pub foam_threshold: FoamThreshold,
    /// Animations: seconds a sample's foam takes to fade from full to none after the
    /// surface stops compressing it (0: no persistence, each frame's own foam).
    pub foam_fade_s: f64,
    /// Frame rate, frames per second (animation, and the per-frame phase modes).
    pub fps: f64,
    /// Phase animation of `filtered-noise`.
    pub phase_mode: PhaseMode,
    /// Hot Air: radians per frame of the dominant components.
    pub hot_air_dominant_rad: f64,
    /// Hot Air: radians per frame of the other components.
    pub hot_air_other_rad: f64,
    /// Translate: speed along the wind, m/s (default: the phase speed of the peak wave).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub translate_speed_mps: Option<f64>,
}

impl Default for MotionParams {
    fn default() -> Self {
        Self {
            loop_period_s: None,
            choppiness: 0.0,
            foam_threshold: FoamThreshold::Auto,
            foam_fade_s: 0.0,
            fps: 30.0,
            phase_mode: PhaseMode::Dispersion,
            hot_air_dominant_rad: 0.05,
            hot_air_other_rad: 0.003,
            translate_speed_mps: None,
        }
    }
}

/// Where foam starts (`motion.foam_threshold`): written `"auto"` or a number.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum FoamThreshold {
    /// Foam on the most compressed part of the surface equal to the whitecap coverage of
    /// the wind (Monahan & O'Muircheartaigh 1980), or J < 0.3 without a wind-driven
    /// spectrum (`measure::foam`).
    #[default]
    Auto,
    /// Foam where J < this.
    Jacobian(f64),
}

impl FoamThreshold {
    /// The fixed threshold, `None` for `"auto"`.
    pub fn fixed(&self) -> Option<f64> {
        match self {
            FoamThreshold::Auto => None,
            FoamThreshold::Jacobian(t) => Some(*t),
        }
    }
}

impl std::fmt::Display for FoamThreshold {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FoamThreshold::Auto => f.write_str("auto"),
            FoamThreshold::Jacobian(t) => write!(f, "{t}"),
        }
    }
}

impl Serialize for FoamThreshold {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            FoamThreshold::Auto => s.serialize_str("auto"),
            FoamThreshold::Jacobian(t) => s.serialize_f64(*t),
        }
    }
}

impl<'de> Deserialize<'de> for FoamThreshold {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Repr {
            Number(f64),
            Text(String),
        }
        let bad = |got: &str| {
            serde::de::Error::custom(format!(
                "foam_threshold: expected \"auto\" or a number (the Jacobian J below which foam starts), got `{got}`"
            ))
        };
        match Repr::deserialize(d).map_err(|_| bad("a value of another type"))? {
            Repr::Number(t) => Ok(FoamThreshold::Jacobian(t)),
            Repr::Text(t) if t == "auto" => Ok(FoamThreshold::Auto),
            Repr::Text(t) => Err(bad(&t)),
        }
    }
}
