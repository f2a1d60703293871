//! Height fields: each method computes a [`Grid`] of heights in meters. The methods are
//! one type each behind [`HeightMethod`] (in [`method`]), built by [`method_for`];
//! [`Synthesizer`] prepares one for its frames and [`synthesize`] computes one field.

pub mod dynamics;
pub mod fft;
pub mod filtered_noise;
pub mod hybrid;
pub mod method;
pub mod noise3;
pub mod perlin;
pub mod trochoid;
pub mod weight;

use serde::Serialize;

pub use method::{HeightMethod, method_for};

use crate::config::{Params, SpectrumModel, SpreadingName};
use crate::error::Result;
use crate::grid::Grid;
use crate::rng::{Stream, sub_seed};
use crate::spectrum::{
    DirectionalSpectrum, Dispersion, Fractal, FrequencySpectrum, Jonswap, Phillips,
    PiersonMoskowitz, Spectrum, Spreading, SpreadingModel, Tma,
};

/// What a synthesis found out along the way, recorded in the sidecar.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SynthesisInfo {
    /// max |h̃0(k)| over the resolved wavevectors, meters (FFT methods).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub h0max_m: Option<f64>,
    /// The physical model's significant wave height 4√m0, meters.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_hs_m: Option<f64>,
    /// The physical model's peak period 1/fp, seconds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_tp_s: Option<f64>,
    /// How the physical model's level was set (from the wind, or to --hs with the depth
    /// factor included).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spectrum_scaling: Option<String>,
    /// Phillips' largest wave L = V²/g, meters.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phillips_largest_wave_m: Option<f64>,
    /// The b of β = (1 − α)·b used by the hybrid blend, meters.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beta_m: Option<f64>,
    /// Perlin lattice spacing per octave actually used, meters (x, y).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub perlin_wavelengths_m: Vec<(f64, f64)>,
    /// The second-order pairs of `--nonlinear second-order`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub second_order: Option<fft::second_order::SecondOrderInfo>,
    /// The trochoid method's components and fitted turbulence.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trochoid: Option<trochoid::TrochoidInfo>,
}

impl SynthesisInfo {
    /// Records the physical model's Hs and Tp (none for Phillips and fractal spectra).
    pub(crate) fn record_model(&mut self, sea: Option<&SeaModel>) {
        if let Some(sea) = sea {
            self.model_hs_m = Some(sea.freq.hs_m());
            self.model_tp_s = Some(1.0 / sea.freq.peak_hz());
            self.spectrum_scaling = Some(sea.freq.scaling().to_string());
        }
    }

    /// What the trochoid method records: its components and fitted turbulence, and the
    /// physical model's Hs and Tp (the same whether the field is in memory or streamed).
    pub(crate) fn of_trochoid(params: &Params, sea: &trochoid::TrochoidSea) -> Result<Self> {
        let mut info = SynthesisInfo {
            trochoid: Some(sea.info().clone()),
            ..SynthesisInfo::default()
        };
        info.record_model(sea_model(params)?.as_ref());
        Ok(info)
    }
}

/// A computed field and what was learned computing it.
pub struct Synthesis {
    /// Heights in meters (the choppy surface resampled onto the grid when λ ≠ 0).
    pub grid: Grid,
    pub info: SynthesisInfo,
    /// Slopes, displacement and Jacobian, when asked for (see [`HeightMethod::frame`]).
    pub surface: dynamics::Surface,
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

/// A physical sea: its frequency spectrum, spreading, wind and dispersion relation.
pub struct SeaModel {
    pub freq: Box<dyn FrequencySpectrum>,
    pub spreading: Spreading,
    pub u10_mps: f64,
    pub wind_dir_rad: f64,
    pub dispersion: Dispersion,
}

impl SeaModel {
    /// The sea as a wavenumber spectrum.
    pub fn into_directional(self) -> Result<DirectionalSpectrum> {
        Ok(DirectionalSpectrum::new(
            self.freq,
            self.spreading,
            self.wind_dir_rad,
            self.u10_mps,
            self.dispersion,
        )?)
    }
}

/// The physical sea of validated `params` (`None` for `phillips` and `fractal`):
/// from `--hs/--tp` when given, else from the wind (and fetch for JONSWAP and TMA).
pub fn sea_model(params: &Params) -> Result<Option<SeaModel>> {
    let s = &params.spectrum;
    let u = params.wind.speed_mps;
    let fetch_m = s.fetch_km * 1000.0;
    let hs_tp = s.hs_m.zip(s.tp_s);
    let freq: Box<dyn FrequencySpectrum> = match (s.model, hs_tp) {
        (SpectrumModel::PiersonMoskowitz, None) => Box::new(PiersonMoskowitz::from_wind(u)?),
        (SpectrumModel::PiersonMoskowitz, Some((h, t))) => {
            Box::new(PiersonMoskowitz::from_hs_tp(h, t)?)
        }
        (SpectrumModel::Jonswap, None) => Box::new(Jonswap::from_wind_fetch(u, fetch_m, s.gamma)?),
        (SpectrumModel::Jonswap, Some((h, t))) => {
            Box::new(Jonswap::from_hs_tp_exact(h, t, s.gamma)?)
        }
        (SpectrumModel::Tma, hs_tp) => {
            let depth = s.depth_m.expect("validated: tma has a depth");
            Box::new(match hs_tp {
                None => Tma::from_wind_fetch(u, fetch_m, s.gamma, depth)?,
                Some((h, t)) => Tma::from_hs_tp(h, t, s.gamma, depth)?,
            })
        }
        (SpectrumModel::Phillips | SpectrumModel::Fractal, _) => return Ok(None),
    };
    crate::spectrum::directional::check_peak(freq.as_ref(), u)?;
    let model = match s.spreading {
        SpreadingName::Cos2 => SpreadingModel::Cos2,
        SpreadingName::Hasselmann => SpreadingModel::Hasselmann,
        SpreadingName::Mitsuyasu => SpreadingModel::Mitsuyasu,
        SpreadingName::DonelanBanner => SpreadingModel::DonelanBanner,
    };
    Ok(Some(SeaModel {
        freq,
        spreading: Spreading::new(model, s.swell)?,
        u10_mps: u,
        wind_dir_rad: params.wind.direction_deg.to_radians(),
        dispersion: Dispersion::for_depth(s.depth_m),
    }))
}

/// The spectrum model of validated `params` (E|h̃0(k)|² per wavevector), and the
/// dispersion relation waves follow (finite depth when `spectrum.depth_m` is set).
pub fn spectrum_model(params: &Params) -> Result<(Box<dyn Spectrum>, Dispersion)> {
    model_from(params, sea_model(params)?)
}

/// [`spectrum_model`] given the already built [`sea_model`] of `params`.
pub(crate) fn model_from(
    params: &Params,
    sea: Option<SeaModel>,
) -> Result<(Box<dyn Spectrum>, Dispersion)> {
    if let Some(sea) = sea {
        let dispersion = sea.dispersion;
        return Ok((Box::new(sea.into_directional()?), dispersion));
    }
    let dispersion = Dispersion::for_depth(params.spectrum.depth_m);
    Ok(match params.spectrum.model {
        SpectrumModel::Phillips => (Box::new(phillips(params)), dispersion),
        SpectrumModel::Fractal => {
            let f = &params.fractal;
            let spec = params.grid_spec();
            let model = Fractal::new(f.dimension, f.relief_m, f.rolloff_m)?;
            let on_grid = model.normalized_for(spec.nx, spec.ny, spec.extent_x_m, spec.extent_y_m);
            (Box::new(on_grid), dispersion)
        }
        _ => unreachable!("the physical spectra have a sea model"),
    })
}

/// Computes the field that validated `params` describe.
pub fn synthesize(params: &Params) -> Result<Synthesis> {
    let s = Synthesizer::new(params, dynamics::Extras::default(), false)?.frame(params.time_s);
    crate::limits::check_finite(&s.grid.stats(), "the synthesized field")?;
    Ok(s)
}

/// A prepared synthesis: the method of the parameters with everything that does not
/// depend on time done once (the spectrum, the weight map, the Perlin field and, when
/// kept, the random draws), so the frames of an animation redo only the time-dependent
/// part. Frames equal [`synthesize`] at their time bit for bit.
pub struct Synthesizer {
    method: Box<dyn HeightMethod>,
    extras: dynamics::Extras,
}

impl Synthesizer {
    /// `extras`: the derived fields each frame computes; `keep_draws`: keep the random
    /// amplitudes between frames (memory: 32 bytes per wavevector of the half plane).
    pub fn new(params: &Params, extras: dynamics::Extras, keep_draws: bool) -> Result<Self> {
        let mut method = method_for(params);
        method.prepare(keep_draws)?;
        Ok(Self { method, extras })
    }

    /// The field at `time_s`, with the derived fields of `new`'s `extras`.
    pub fn frame(&self, time_s: f64) -> Synthesis {
        self.method.frame(time_s, self.extras)
    }

    /// The heights alone at `time_s` (no derived fields beyond what a choppy height
    /// needs): the same grid as [`frame`](Self::frame).
    pub fn heights(&self, time_s: f64) -> Grid {
        self.method.frame(time_s, dynamics::Extras::default()).grid
    }
}
