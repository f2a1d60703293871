//! What the two methods that are one spectrum (`fft`, `filtered-noise`) share: the
//! spectrum model, the inverse transform, and the heights and derived fields of a half
//! spectrum (the choppy resampling when λ ≠ 0).

use crate::config::{Params, SpectrumModel};
use crate::error::Result;
use crate::field::dynamics::{self, Extras, Surface};
use crate::field::fft::{HalfSpectrum, InverseFft2, SpectrumSetup};
use crate::field::{SynthesisInfo, model_from, phillips, sea_model};
use crate::grid::{Grid, GridSpec};
use crate::rng::{Stream, sub_seed};
use crate::spectrum::{Dispersion, Spectrum};

/// A spectrum on a grid and its transform: the time-independent part of a spectral field.
pub(super) struct Spectral {
    pub spec: GridSpec,
    seed: u64,
    loop_period_s: Option<f64>,
    choppiness: f64,
    model: Box<dyn Spectrum>,
    dispersion: Dispersion,
    plan: InverseFft2,
    /// What the sidecar records of the model (Phillips' largest wave, or the physical
    /// model's Hs and Tp).
    pub info: SynthesisInfo,
}

impl Spectral {
    pub fn new(params: &Params) -> Result<Self> {
        let spec = params.grid_spec();
        let mut info = SynthesisInfo::default();
        if params.spectrum.model == SpectrumModel::Phillips {
            info.phillips_largest_wave_m = Some(phillips(params).largest_wave_m());
        }
        // The sea model is built once: its Hs and Tp for the sidecar, then the spectrum.
        let sea = sea_model(params)?;
        info.record_model(sea.as_ref());
        let (model, dispersion) = model_from(params, sea)?;
        Ok(Self {
            spec,
            seed: sub_seed(params.seed, Stream::SpectrumAmplitude),
            loop_period_s: params.motion.loop_period_s,
            choppiness: params.motion.choppiness,
            model,
            dispersion,
            plan: InverseFft2::new(spec.nx, spec.ny),
            info,
        })
    }

    /// The random spectrum at `time_s`.
    pub fn setup(&self, time_s: f64) -> SpectrumSetup<'_> {
        SpectrumSetup {
            spec: self.spec,
            spectrum: self.model.as_ref(),
            dispersion: self.dispersion,
            seed: self.seed,
            time_s,
            loop_period_s: self.loop_period_s,
        }
    }

    /// The heights of `half` (resampled when choppy) and the derived fields `extras` asks
    /// for.
    pub fn heights(&self, half: HalfSpectrum, extras: Extras) -> (Grid, Surface) {
        let spec = self.spec;
        let lambda = self.choppiness;
        let mut surface = Surface::default();
        let mut data = if extras.any() || lambda != 0.0 {
            let (data, s) = dynamics::surface_and_height(half, &spec, &self.plan, extras, lambda);
            surface = s;
            data
        } else {
            self.plan.process(half)
        };
        if let Some(d) = surface.displacement.as_ref().filter(|_| lambda != 0.0) {
            let choppy = dynamics::resample_choppy(&data, d, &spec);
            let still = std::mem::replace(&mut data, choppy);
            if extras.displacement {
                surface.undisplaced_height = Some(still);
            }
        }
        if !extras.displacement {
            surface.displacement = None;
        }
        (Grid::new(spec, data), surface)
    }
}
