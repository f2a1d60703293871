//! The `filtered-noise` method: Mastin et al.'s Fourier synthesis, white noise filtered by
//! the spectrum, moving by one of its phase modes.

use super::spectral::Spectral;
use super::{HeightMethod, finish};
use crate::config::Params;
use crate::error::Result;
use crate::field::Synthesis;
use crate::field::dynamics::Extras;
use crate::field::filtered_noise::{Motion, filtered_spectrum, peak_band};

/// Mastin et al.'s filtered white noise.
pub struct FilteredNoise {
    params: Params,
    ready: Option<(Spectral, Motion)>,
}

impl FilteredNoise {
    pub fn new(params: &Params) -> Self {
        Self {
            params: params.clone(),
            ready: None,
        }
    }
}

impl HeightMethod for FilteredNoise {
    fn prepare(&mut self, _keep_draws: bool) -> Result<()> {
        let params = &self.params;
        let spectral = Spectral::new(params)?;
        let dir = params.wind.direction_deg.to_radians();
        let wind = (dir.cos(), dir.sin());
        let (k_peak, band) = peak_band(&spectral.setup(0.0), wind, 2.0 / 3.0);
        let m = &params.motion;
        let motion = Motion {
            mode: m.phase_mode,
            wind,
            fps: m.fps,
            dominant_rad: m.hot_air_dominant_rad,
            other_rad: m.hot_air_other_rad,
            speed_mps: m
                .translate_speed_mps
                .unwrap_or_else(|| (crate::spectrum::G / k_peak).sqrt()),
            band,
        };
        self.ready = Some((spectral, motion));
        Ok(())
    }

    fn frame(&self, time_s: f64, extras: Extras) -> Synthesis {
        let (spectral, motion) = self
            .ready
            .as_ref()
            .expect("prepared before the first frame");
        let half = filtered_spectrum(&spectral.setup(time_s), Some(motion));
        let (grid, surface) = spectral.heights(half, extras);
        let info = spectral.info.clone();
        finish(grid, info, surface, extras, true, true)
    }

    fn bytes_per_sample(&self) -> u64 {
        10
    }

    fn is_periodic(&self) -> bool {
        true
    }

    fn exact_slopes(&self) -> bool {
        self.params.motion.choppiness == 0.0
    }

    fn follows_spectrum(&self) -> bool {
        true
    }
}
