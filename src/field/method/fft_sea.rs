//! The `fft` method: Tessendorf's FFT sea (Li Tian eq. 1–8), with exact spectral slopes,
//! choppy displacement and its Jacobian.

use super::spectral::Spectral;
use super::{HeightMethod, finish};
use crate::config::Params;
use crate::error::Result;
use crate::field::Synthesis;
use crate::field::dynamics::{Extras, Surface};
use crate::field::fft::{self, Amplitudes};
use crate::grid::Grid;

/// Tessendorf's FFT sea: Gaussian random amplitudes of the spectrum, dispersion in time,
/// one inverse FFT.
pub struct FftSea {
    params: Params,
    ready: Option<Ready>,
}

struct Ready {
    spectral: Spectral,
    /// The random draws, when kept between frames.
    amplitudes: Option<Amplitudes>,
}

impl FftSea {
    pub fn new(params: &Params) -> Self {
        Self {
            params: params.clone(),
            ready: None,
        }
    }

    /// The heights (resampled when choppy), the derived fields `extras` asks for, and
    /// h0max = max |h̃0(k)|, meters.
    pub(super) fn field(&self, time_s: f64, extras: Extras) -> (Grid, Surface, f64) {
        let ready = self
            .ready
            .as_ref()
            .expect("prepared before the first frame");
        let setup = ready.spectral.setup(time_s);
        let half = match &ready.amplitudes {
            Some(a) => a.frame(&setup),
            None => fft::synthesize_spectrum(&setup),
        };
        let h0max_m = half.h0max_m;
        let (grid, surface) = ready.spectral.heights(half, extras);
        (grid, surface, h0max_m)
    }

    /// What the sidecar records of the spectrum model (after `prepare`).
    pub(super) fn info(&self) -> &crate::field::SynthesisInfo {
        let ready = self
            .ready
            .as_ref()
            .expect("prepared before the first frame");
        &ready.spectral.info
    }
}

impl HeightMethod for FftSea {
    fn prepare(&mut self, keep_draws: bool) -> Result<()> {
        let spectral = Spectral::new(&self.params)?;
        let amplitudes = keep_draws.then(|| Amplitudes::new(&spectral.setup(0.0)));
        self.ready = Some(Ready {
            spectral,
            amplitudes,
        });
        Ok(())
    }

    fn frame(&self, time_s: f64, extras: Extras) -> Synthesis {
        let (grid, surface, h0max_m) = self.field(time_s, extras);
        let mut info = self.info().clone();
        info.h0max_m = Some(h0max_m);
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
