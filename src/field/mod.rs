//! Height fields: each method computes a [`Grid`] of heights in meters.

pub mod fft;
pub mod filtered_noise;
pub mod hybrid;
pub mod perlin;
pub mod weight;

use serde::Serialize;

use crate::config::{Beta, Method, Params, SpectrumModel};
use crate::error::Result;
use crate::grid::Grid;
use crate::rng::{Stream, sub_seed};
use crate::spectrum::{Dispersion, Phillips, Spectrum};

/// What a synthesis found out along the way, recorded in the sidecar.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SynthesisInfo {
    /// max |h̃0(k)| over the resolved wavevectors, meters (FFT methods).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub h0max_m: Option<f64>,
    /// Phillips' largest wave L = V²/g, meters.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phillips_largest_wave_m: Option<f64>,
    /// The b of β = (1 − α)·b used by the hybrid blend, meters.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beta_m: Option<f64>,
    /// Perlin lattice spacing per octave actually used, meters (x, y).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub perlin_wavelengths_m: Vec<(f64, f64)>,
}

/// A computed field and what was learned computing it.
pub struct Synthesis {
    pub grid: Grid,
    pub info: SynthesisInfo,
}

/// The Perlin parameters of `params`, with their sub-seed.
pub fn perlin_params(params: &Params) -> perlin::PerlinParams {
    let p = &params.perlin;
    perlin::PerlinParams {
        octaves: p.octaves,
        persistence: p.persistence,
        lacunarity: p.lacunarity,
        wavelength_m: p.wavelength_m,
        tileable: p.tileable,
        seed: sub_seed(params.seed, Stream::Perlin),
    }
}

/// The Phillips spectrum of `params`.
pub fn phillips(params: &Params) -> Phillips {
    Phillips::new(
        params.spectrum.phillips_a,
        params.wind.speed_mps,
        params.wind.direction_deg.to_radians(),
        params.spectrum.small_wave_m,
    )
}

/// The spectrum model of validated `params` (E|h̃0(k)|² per wavevector), and the
/// dispersion relation waves follow.
pub fn spectrum_model(params: &Params) -> Result<(Box<dyn Spectrum>, Dispersion)> {
    Ok(match params.spectrum.model {
        SpectrumModel::Phillips => (Box::new(phillips(params)), Dispersion::Deep),
        other => {
            return Err(crate::error::ParamError {
                name: "--spectrum (spectrum.model)".into(),
                allowed: "phillips (the other models are being added)".into(),
                got: crate::config::validate::model_name(other),
            }
            .into());
        }
    })
}

/// Computes the field that validated `params` describe.
pub fn synthesize(params: &Params) -> Result<Synthesis> {
    let spec = params.grid_spec();
    let mut info = SynthesisInfo::default();
    // Inputs that can fail are read before the expensive work.
    let alpha = match params.method {
        Method::Hybrid => Some(weight::AlphaMap::new(&params.blend.alpha, &spec)?),
        _ => None,
    };
    let fft = match params.method {
        Method::Fft | Method::Hybrid | Method::FilteredNoise => {
            if params.spectrum.model == SpectrumModel::Phillips {
                info.phillips_largest_wave_m = Some(phillips(params).largest_wave_m());
            }
            let (model, dispersion) = spectrum_model(params)?;
            let setup = fft::SpectrumSetup {
                spec,
                spectrum: model.as_ref(),
                dispersion,
                seed: sub_seed(params.seed, Stream::SpectrumAmplitude),
                time_s: params.time_s,
            };
            let half = if params.method == Method::FilteredNoise {
                filtered_noise::filtered_spectrum(&setup)
            } else {
                fft::synthesize_spectrum(&setup)
            };
            if params.method != Method::FilteredNoise {
                info.h0max_m = Some(half.h0max_m);
            }
            let data = fft::InverseFft2::new(spec.nx, spec.ny).process(half);
            Some(Grid::new(spec, data))
        }
        Method::Perlin => None,
    };
    let noise = match params.method {
        Method::Perlin | Method::Hybrid => {
            let pp = perlin_params(params);
            info.perlin_wavelengths_m = perlin::octave_wavelengths(&spec, &pp);
            Some(perlin::perlin_field(&spec, &pp))
        }
        Method::Fft | Method::FilteredNoise => None,
    };
    let grid = match (fft, noise, alpha) {
        (Some(mut f), Some(p), Some(alpha)) => {
            let b = match params.blend.beta {
                Beta::Paper => info.h0max_m.unwrap_or(0.0),
                Beta::Matched => {
                    let pstd = Grid::new(spec, p.clone()).stats().std_m;
                    if pstd > 0.0 {
                        f.stats().std_m / pstd
                    } else {
                        0.0
                    }
                }
                Beta::Meters(b) => b,
            } * params.blend.beta_scale;
            info.beta_m = Some(b);
            hybrid::blend_in_place(&mut f, &p, &alpha, b as f32);
            f
        }
        (Some(f), None, _) => f,
        (None, Some(mut p), _) => {
            let amp = params.perlin.amplitude_m as f32;
            p.iter_mut().for_each(|v| *v *= amp);
            Grid::new(spec, p)
        }
        _ => unreachable!("every method computes at least one field"),
    };
    Ok(Synthesis { grid, info })
}
