//! Parameters: what a preset file, `--set` and the flags can say, their defaults (the
//! `li-tian` setting) and their validation. Units are in the names; angles are degrees
//! here and become radians only when the parameters are turned into models.

pub mod layers;
mod motion;
pub mod presets;
pub mod trochoid;
pub mod validate;
pub mod values;

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

pub use motion::{FoamThreshold, MotionParams, PhaseMode};
pub use trochoid::TrochoidParams;
pub use validate::{MAX_SAMPLES, MAX_SIDE};
pub use values::{Beta, Extent2, Range2, Size2};

/// Which field to synthesize.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// α·h_fft + β·h_perlin (Li Tian eq. 10).
    Hybrid,
    /// Tessendorf's FFT ocean alone (Li Tian Fig. 2b).
    Fft,
    /// Multi-octave Perlin noise alone (Li Tian Fig. 2a), in [−1, 1] times `perlin.amplitude_m`.
    Perlin,
    /// Mastin et al.: white noise filtered by the spectrum in the Fourier domain.
    FilteredNoise,
    /// Thon et al.: trochoids from the strongest spectral components plus fitted turbulence;
    /// continuous, evaluated anywhere (no FFT grid).
    Trochoid,
}

impl Method {
    /// Every method, in the order `--method` lists them.
    pub const ALL: [Method; 5] = [
        Method::Hybrid,
        Method::Fft,
        Method::FilteredNoise,
        Method::Perlin,
        Method::Trochoid,
    ];

    pub fn name(&self) -> &'static str {
        match self {
            Method::Hybrid => "hybrid",
            Method::Fft => "fft",
            Method::Perlin => "perlin",
            Method::FilteredNoise => "filtered-noise",
            Method::Trochoid => "trochoid",
        }
    }
}

/// Spectrum models.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpectrumModel {
    /// Tessendorf's Phillips spectrum, discrete convention.
    Phillips,
    /// Fully developed sea (Mastin eq. 1–2), heights in meters.
    PiersonMoskowitz,
    /// Fetch-limited sea, peak enhancement γ.
    Jonswap,
    /// JONSWAP in water of finite depth (Kitaigorodskii factor).
    Tma,
    /// Isotropic 1/k^β power law for terrain, set by the fractal dimension.
    Fractal,
}

impl SpectrumModel {
    /// The physical (meters) frequency spectra.
    pub fn is_physical_sea(&self) -> bool {
        matches!(
            self,
            SpectrumModel::PiersonMoskowitz | SpectrumModel::Jonswap | SpectrumModel::Tma
        )
    }
}

/// Directional spreading models of the physical spectra.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpreadingName {
    /// Phillips' |k̂·ŵ|², normalized.
    Cos2,
    /// cos^{2p}(θ/2), p = 9.77 (f/fm)^μ (Mastin eq. 4–6).
    Hasselmann,
    /// cos^{2s}(θ/2), s from U10/c_p (Mitsuyasu 1975).
    Mitsuyasu,
    /// sech²(βθ) (Donelan, Hamilton & Hui 1985).
    DonelanBanner,
}

/// The order of the sea's theory (`fft` method only).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Nonlinear {
    /// Free waves only: Gaussian statistics.
    #[default]
    Linear,
    /// Free waves plus their second-order bound waves (Sharma–Dean kernels).
    SecondOrder,
}

impl Nonlinear {
    pub fn is_linear(&self) -> bool {
        *self == Nonlinear::Linear
    }
}

/// How the bound waves of a second-order sea are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NonlinearMethod {
    /// The fitted method where its estimated error is within [`AUTO_MAX_ESTIMATE`] and the
    /// sea does not loop; the exact pair sum otherwise (binned once when looping).
    #[default]
    Auto,
    /// The exact pair sum over the components of `nonlinear_fraction` of the variance.
    Pairs,
    /// The same components, by transforms of weighted linear fields, with fitted
    /// low-rank resonance terms: an approximation (below 1 % of the bound waves' rms in
    /// deep water; the sidecar records the estimate).
    Fitted,
}

/// The fitted kernels' estimated relative rms error up to which `auto` takes the fitted
/// method: 0.85 %, a margin under the 1 % it is held to (the estimate has been 0.7–1.5×
/// the measured error of broad seas, above it at finite depth; where it was within
/// 0.85 % the measured error was at most 0.66 %).
pub const AUTO_MAX_ESTIMATE: f64 = 0.0085;

impl NonlinearMethod {
    pub fn is_pairs(&self) -> bool {
        *self == NonlinearMethod::Pairs
    }

    pub fn is_auto(&self) -> bool {
        *self == NonlinearMethod::Auto
    }
}

/// The fraction of the variance (within the convergence limits) the exact pair sum's
/// components carry, when not given; the fitted method pairs every component.
pub const DEFAULT_NONLINEAR_FRACTION: f64 = 0.99;

/// The convergence criterion C of the waves paired to second order (k·A_max ≤ C, in the
/// form of Nestegaard & Stokka 1995 that WAFO's second-order simulation applies), when
/// not given; `inf` pairs every wave.
pub const DEFAULT_NONLINEAR_CUTOFF: f64 = 2.0;

/// Every parameter of a run. Missing keys take the defaults of the `li-tian` preset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Params {
    pub method: Method,
    /// One seed per job; sub-seeds for each random stream derive from it by a fixed rule.
    pub seed: u64,
    /// Time of the frame, seconds.
    pub time_s: f64,
    pub grid: GridParams,
    pub wind: WindParams,
    pub spectrum: SpectrumParams,
    pub fractal: FractalParams,
    pub perlin: PerlinConfig,
    pub blend: BlendParams,
    pub motion: MotionParams,
    pub output: OutputParams,
    pub trochoid: TrochoidParams,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GridParams {
    /// Samples [N along x, M along y].
    pub size: Size2,
    /// Extent [Lx, Ly] in meters; FFT fields repeat with this period.
    pub extent_m: Extent2,
    /// Where sample (i, j) sits: at the corner (i·dx, j·dy) (default) or at the texel
    /// centre ((i + ½)·dx, (j + ½)·dy). Left out of files when at its default.
    #[serde(skip_serializing_if = "SampleAt::is_corners")]
    pub sample_at: SampleAt,
}

/// Where the samples of a grid sit (`--sample-at`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SampleAt {
    /// Sample (i, j) at (i·dx, j·dy): texel corners.
    #[default]
    Corners,
    /// Sample (i, j) at ((i + ½)·dx, (j + ½)·dy): texel centres, where image-based
    /// displacement samples a texture.
    Centers,
}

impl SampleAt {
    pub fn is_corners(&self) -> bool {
        *self == SampleAt::Corners
    }

    /// The offset of the samples from the corners, in samples (0 or ½).
    pub fn offset(&self) -> f64 {
        match self {
            SampleAt::Corners => 0.0,
            SampleAt::Centers => 0.5,
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            SampleAt::Corners => "corners",
            SampleAt::Centers => "centers",
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WindParams {
    /// Wind speed, m/s (10 m above the sea).
    pub speed_mps: f64,
    /// Direction the wind blows toward, degrees: 0 toward +x, 90 toward +y.
    pub direction_deg: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SpectrumParams {
    pub model: SpectrumModel,
    /// Phillips amplitude A (discrete convention: multiplies |h̃0|² directly).
    pub phillips_a: f64,
    /// Small-wave cutoff l of Li Tian eq. 8, meters (0: none).
    pub small_wave_m: f64,
    /// Directional spreading of the physical spectra.
    pub spreading: SpreadingName,
    /// Swell parameter ξ ≥ 0 narrowing the spreading (0: none).
    pub swell: f64,
    /// Fetch for JONSWAP and TMA from wind, km.
    pub fetch_km: f64,
    /// Water depth, m: finite-depth dispersion for every spectrum, and TMA's depth.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub depth_m: Option<f64>,
    /// Significant wave height, m: with `tp_s`, sets PM/JONSWAP/TMA instead of wind and fetch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hs_m: Option<f64>,
    /// Peak period, s (with `hs_m`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tp_s: Option<f64>,
    /// JONSWAP peak enhancement γ ≥ 1.
    pub gamma: f64,
    /// `linear` (free waves) or `second-order` (free and bound waves; `fft` method).
    #[serde(skip_serializing_if = "Nonlinear::is_linear")]
    pub nonlinear: Nonlinear,
    /// The linear components of the second-order pairs: the strongest ones that carry
    /// this fraction of the variance within the convergence limits (0 < q ≤ 1; default
    /// 1 for the fitted method, 0.99 for the exact pair sum).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nonlinear_fraction: Option<f64>,
    /// The convergence criterion C of the paired waves: only waves with ω² ≤ C g
    /// tanh(k̄d)/A_max (A_max = √(2 ln 1000)·Hs/4) are paired, the shorter ones stay
    /// linear (C > 0; default 2; `inf`: every wave).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nonlinear_cutoff: Option<f64>,
    /// `auto` (default: `fitted` where its estimated error is within 0.85 % and the sea
    /// does not loop, `pairs` otherwise), `pairs` (the exact pair sum) or `fitted` (by
    /// transforms, fitted resonance terms: approximate).
    #[serde(skip_serializing_if = "NonlinearMethod::is_auto")]
    pub nonlinear_method: NonlinearMethod,
}

/// The `fractal` spectrum (terrain).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FractalParams {
    /// Fractal dimension D, 2 < D < 3 (spectral slope k^−(8−2D)).
    pub dimension: f64,
    /// Expected standard deviation of the heights, m.
    pub relief_m: f64,
    /// Wavelength where Mastin's Gaussian low-frequency attenuation peaks, m (none: pure power law).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rolloff_m: Option<f64>,
}

impl Default for FractalParams {
    fn default() -> Self {
        Self {
            dimension: 2.2,
            relief_m: 50.0,
            rolloff_m: None,
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PerlinConfig {
    /// Number of octaves P.
    pub octaves: u32,
    /// Amplitude ratio a between octaves, 0 < a < 1.
    pub persistence: f64,
    /// Frequency ratio between octaves.
    pub lacunarity: f64,
    /// Base wavelength λ0 of the first octave, meters.
    pub wavelength_m: f64,
    /// Make the noise periodic over the extent (λ0 is then rounded to divide it).
    pub tileable: bool,
    /// Height of the normalized noise for `--method perlin`, meters (the field is in [−1, 1]·amplitude_m).
    pub amplitude_m: f64,
    /// The noise: `builtin` (seasynth's periodic gradient noise) or a noise-rs source.
    #[serde(skip_serializing_if = "NoiseBasis::is_builtin")]
    pub basis: NoiseBasis,
    /// How octaves combine (noise-rs bases only; `builtin` is fBm).
    #[serde(skip_serializing_if = "NoiseFractal::is_fbm")]
    pub fractal: NoiseFractal,
}

/// The noise of the Perlin field.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NoiseBasis {
    /// seasynth's own periodic 2D gradient noise (Li Tian eq. 9).
    #[default]
    Builtin,
    /// noise-rs `Perlin` (gradient noise).
    Perlin,
    /// noise-rs `OpenSimplex`.
    OpenSimplex,
    /// noise-rs `SuperSimplex` (2D only: not tileable).
    SuperSimplex,
    /// noise-rs `Value` (interpolated lattice values).
    Value,
    /// noise-rs `Worley` (cellular: the value of the nearest feature point's cell).
    Worley,
}

impl NoiseBasis {
    pub const ALL: [NoiseBasis; 6] = [
        NoiseBasis::Builtin,
        NoiseBasis::Perlin,
        NoiseBasis::OpenSimplex,
        NoiseBasis::SuperSimplex,
        NoiseBasis::Value,
        NoiseBasis::Worley,
    ];

    fn is_builtin(&self) -> bool {
        *self == NoiseBasis::Builtin
    }

    pub fn name(self) -> &'static str {
        match self {
            NoiseBasis::Builtin => "builtin",
            NoiseBasis::Perlin => "perlin",
            NoiseBasis::OpenSimplex => "open-simplex",
            NoiseBasis::SuperSimplex => "super-simplex",
            NoiseBasis::Value => "value",
            NoiseBasis::Worley => "worley",
        }
    }
}

/// How the octaves of a noise-rs basis combine (noise-rs's fractal combinators).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NoiseFractal {
    /// Fractal Brownian motion: the sum of the octaves.
    #[default]
    Fbm,
    /// The sum of |octave| (billowy: rounded crests, sharp troughs).
    Billow,
    /// Ridged multifractal: 1 − |octave|, each octave weighted by the last (sharp ridges).
    RidgedMulti,
    /// Hybrid multifractal: smooth valleys, rough peaks.
    HybridMulti,
}

impl NoiseFractal {
    pub const ALL: [NoiseFractal; 4] = [
        NoiseFractal::Fbm,
        NoiseFractal::Billow,
        NoiseFractal::RidgedMulti,
        NoiseFractal::HybridMulti,
    ];

    fn is_fbm(&self) -> bool {
        *self == NoiseFractal::Fbm
    }

    pub fn name(self) -> &'static str {
        match self {
            NoiseFractal::Fbm => "fbm",
            NoiseFractal::Billow => "billow",
            NoiseFractal::RidgedMulti => "ridged-multi",
            NoiseFractal::HybridMulti => "hybrid-multi",
        }
    }
}

/// Which axis a ramp runs along.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    X,
    Y,
}

/// The FFT weight α(x, y) of the hybrid blend, in [0, 1].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum AlphaConfig {
    /// α = value everywhere (default 1).
    Constant {
        #[serde(default = "one")]
        value: f64,
    },
    /// α = 1 − (c/L)^power, c the x or y coordinate, L the extent along it (default, as in
    /// the paper: y, 3).
    Ramp {
        #[serde(default = "axis_y")]
        axis: Axis,
        #[serde(default = "three")]
        power: f64,
    },
    /// α = 1 − min(r/radius, 1)^power, r the distance from `center_m`
    /// (default: the middle of the extent; radius default: half the smaller extent).
    Radial {
        #[serde(default = "two")]
        power: f64,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        center_m: Option<[f64; 2]>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        radius_m: Option<f64>,
    },
    /// α from an image (PNG, JPEG, TIFF, OpenEXR, BMP or WebP; gray, or color by its
    /// luma; white = 1, float samples as stored and clamped to [0, 1]), resampled
    /// bilinearly to the grid; image row 0 is y = 0, as in every output. An image whose
    /// aspect ratio differs from the extent's is refused unless `fit = "stretch"`.
    Image {
        path: PathBuf,
        #[serde(default, skip_serializing_if = "AlphaFit::is_match")]
        fit: AlphaFit,
    },
}

/// How an α image meets the grid.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AlphaFit {
    /// The image's aspect ratio must be the extent's (within a pixel).
    #[default]
    Match,
    /// The image is stretched over the extent whatever its aspect ratio.
    Stretch,
}

impl AlphaFit {
    fn is_match(&self) -> bool {
        *self == AlphaFit::Match
    }
}

fn one() -> f64 {
    1.0
}
fn two() -> f64 {
    2.0
}
fn three() -> f64 {
    3.0
}
fn axis_y() -> Axis {
    Axis::Y
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BlendParams {
    pub alpha: AlphaConfig,
    /// β = (1 − α)·b·beta_scale; b from `beta` ("paper", "matched" or meters).
    pub beta: Beta,
    pub beta_scale: f64,
}

#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputParams {
    /// Fixed heights mapped to 0 and 65535 in 16-bit outputs (default: the field's min..max).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height_range: Option<Range2>,
}

/// Phillips A of the default preset: gives the `li-tian` setting (512 m, 1 m grid,
/// 7 m/s) an expected std of 0.30 m, i.e. Hs ≈ 1.2 m, the Hs of seasynth's fully
/// developed Pierson–Moskowitz sea at 7 m/s (4√m0 with fm = 0.13 g/U).
pub const DEFAULT_PHILLIPS_A: f64 = 1.75e-7;

impl Default for Params {
    fn default() -> Self {
        Self {
            method: Method::Hybrid,
            seed: 1,
            time_s: 0.0,
            grid: GridParams::default(),
            wind: WindParams::default(),
            spectrum: SpectrumParams::default(),
            fractal: FractalParams::default(),
            perlin: PerlinConfig::default(),
            blend: BlendParams::default(),
            motion: MotionParams::default(),
            output: OutputParams::default(),
            trochoid: TrochoidParams::default(),
        }
    }
}

impl Default for GridParams {
    fn default() -> Self {
        Self {
            size: Size2([512, 512]),
            extent_m: Extent2([512.0, 512.0]),
            sample_at: SampleAt::Corners,
        }
    }
}

impl Default for WindParams {
    fn default() -> Self {
        Self {
            speed_mps: 7.0,
            direction_deg: 0.0,
        }
    }
}

impl Default for SpectrumParams {
    fn default() -> Self {
        Self {
            model: SpectrumModel::Phillips,
            phillips_a: DEFAULT_PHILLIPS_A,
            small_wave_m: 0.0,
            spreading: SpreadingName::Hasselmann,
            swell: 0.0,
            fetch_km: 100.0,
            depth_m: None,
            hs_m: None,
            tp_s: None,
            gamma: 3.3,
            nonlinear: Nonlinear::Linear,
            nonlinear_fraction: None,
            nonlinear_cutoff: None,
            nonlinear_method: NonlinearMethod::Auto,
        }
    }
}

impl Default for PerlinConfig {
    fn default() -> Self {
        Self {
            octaves: 6,
            persistence: 0.5,
            lacunarity: 2.0,
            wavelength_m: 64.0,
            tileable: true,
            amplitude_m: 1.0,
            basis: NoiseBasis::Builtin,
            fractal: NoiseFractal::Fbm,
        }
    }
}

impl Default for AlphaConfig {
    fn default() -> Self {
        AlphaConfig::Ramp {
            axis: Axis::Y,
            power: 3.0,
        }
    }
}

impl Default for BlendParams {
    fn default() -> Self {
        Self {
            alpha: AlphaConfig::default(),
            beta: Beta::Paper,
            beta_scale: 1.0,
        }
    }
}

#[cfg(test)]
mod tests;
