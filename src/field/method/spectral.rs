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
    /// Offset of the samples from the grid corners, in samples (`--sample-at`).
    sample_offset: f64,
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
            sample_offset: params.grid.sample_at.offset(),
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

    /// The heights of `half` (resampled when choppy, unless `extras.maps_only`) and the
    /// derived fields `extras` asks for, at the samples `--sample-at` places.
    pub fn heights(&self, mut half: HalfSpectrum, extras: Extras) -> (Grid, Surface) {
        let spec = self.spec;
        if self.sample_offset != 0.0 {
            let o = self.sample_offset;
            crate::field::fft::shift_samples(&mut half, &spec, [o, o]);
        }
        let lambda = self.choppiness;
        let mut surface = Surface::default();
        let mut data = if extras.any() || lambda != 0.0 {
            let (data, s) = dynamics::surface_and_height(half, &spec, &self.plan, extras, lambda);
            surface = s;
            data
        } else {
            self.plan.process(half)
        };
        // Without `maps_only` the heights are those of the displaced surface; with it they
        // stay undisplaced, which is what every map reads.
        if let Some(d) = surface
            .displacement
            .as_ref()
            .filter(|_| lambda != 0.0 && !extras.maps_only)
        {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{Method, SampleAt};
    use crate::field::fft::{self, is_resolved, signed_index};
    use rustfft::num_complex::Complex;

    /// `--sample-at centers` moves every sample of a spectral field to the texel centre
    /// exactly: the field equals the naive sum Σ h̃(k)·e^{ik·x} at x = ((i + ½)·dx,
    /// (j + ½)·dy), and the corner grid is unchanged.
    #[test]
    fn centers_equal_a_naive_dft_at_the_shifted_points() {
        let mut p = Params {
            method: Method::Fft,
            ..Params::default()
        };
        p.grid.size = crate::config::Size2([12, 10]);
        p.grid.extent_m = crate::config::Extent2([96.0, 70.0]);
        p.wind.speed_mps = 12.0;
        p.wind.direction_deg = 30.0;
        p.time_s = 1.7;
        p.validate().unwrap();
        let corners = Spectral::new(&p).unwrap();
        let mut q = p.clone();
        q.grid.sample_at = SampleAt::Centers;
        let centers = Spectral::new(&q).unwrap();
        let setup = corners.setup(p.time_s);
        let spec = corners.spec;
        let field = |s: &Spectral| {
            let half = fft::synthesize_spectrum(&s.setup(p.time_s));
            s.heights(half, Extras::default()).0
        };
        let (at_corners, at_centers) = (field(&corners), field(&centers));
        for (offset, grid) in [(0.0, &at_corners), (0.5, &at_centers)] {
            let scale = grid.data.iter().fold(0.0f32, |m, v| m.max(v.abs())) as f64;
            assert!(scale > 0.0, "a field with waves");
            for j in 0..spec.ny {
                for i in 0..spec.nx {
                    let (x, y) = (
                        (i as f64 + offset) * spec.dx_m(),
                        (j as f64 + offset) * spec.dy_m(),
                    );
                    let mut sum = Complex::new(0.0, 0.0);
                    for a in 0..spec.nx {
                        for b in 0..spec.ny {
                            let (n, m) = (signed_index(a, spec.nx), signed_index(b, spec.ny));
                            if is_resolved(n, m, spec.nx, spec.ny) {
                                let (kx, ky) = setup.wavevector(n, m);
                                let e = Complex::from_polar(1.0, kx * x + ky * y);
                                sum += setup.amplitude(n, m).0 * e;
                            }
                        }
                    }
                    assert!(sum.im.abs() < 1e-9 * scale, "a real field at ({i}, {j})");
                    let got = grid.data[j * spec.nx + i] as f64;
                    assert!(
                        (got - sum.re).abs() < 2e-6 * scale,
                        "offset {offset}, sample ({i}, {j}): {got} vs naive {}",
                        sum.re
                    );
                }
            }
        }
    }

    /// `maps_only` leaves a choppy frame's heights undisplaced (the resampling skipped)
    /// and every derived field as it is without it.
    #[test]
    fn maps_only_keeps_the_undisplaced_heights_and_the_same_maps() {
        let mut p = Params {
            method: Method::Fft,
            ..Params::default()
        };
        p.grid.size = crate::config::Size2([32, 24]);
        p.grid.extent_m = crate::config::Extent2([120.0, 90.0]);
        p.wind.speed_mps = 14.0;
        p.motion.choppiness = 0.9;
        p.validate().unwrap();
        let s = Spectral::new(&p).unwrap();
        let half = || fft::synthesize_spectrum(&s.setup(0.4));
        let extras = Extras::ALL;
        let (choppy, full) = s.heights(half(), extras);
        let (still, maps) = s.heights(
            half(),
            Extras {
                maps_only: true,
                ..extras
            },
        );
        let undisplaced = full.undisplaced_height.expect("kept beside a displacement");
        assert_eq!(still.data, undisplaced, "the heights stay undisplaced");
        assert_ne!(
            choppy.data, still.data,
            "the full frame's heights are resampled"
        );
        assert!(
            maps.undisplaced_height.is_none(),
            "the heights are the undisplaced ones"
        );
        assert_eq!(maps.displacement, full.displacement);
        assert_eq!(maps.jacobian, full.jacobian);
        assert_eq!(maps.slopes, full.slopes);
        assert_eq!(maps.displacement_gradient, full.displacement_gradient);
    }
}
