//! The command line (clap). Values are kept as typed and turned into parameters in one
//! place (`config::layers`), so flags, `--set` and presets share one parser and one set of
//! error messages.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

mod analyze;
mod animate;
mod batch;
mod export;
mod spectrum;

pub use analyze::AnalyzeArgs;
pub use animate::AnimateArgs;
pub use batch::BatchArgs;
pub use export::{ExportArgs, ExrArgs};
pub use spectrum::SpectrumArgs;

#[derive(Debug, Parser)]
#[command(
    name = "seasynth",
    version,
    about = "Ocean-wave and terrain height maps from wave spectra and Perlin noise"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Synthesize a height field and write it (format by extension of each -o)
    Generate(Box<GenerateArgs>),
    /// List the built-in presets, or print one as TOML
    Presets {
        /// Preset to print
        name: Option<String>,
    },
    /// A numbered frame sequence of one sea (frame k at t = time + k/fps), one 16-bit mapping for all
    Animate(Box<AnimateArgs>),
    /// Many fields: sweeps (cartesian product) or a manifest, one 16-bit mapping, parallel, resumable, shardable
    Batch(Box<BatchArgs>),
    /// Statistics and the measured spectrum of a height map (TIFF in meters, or PNG with its sidecar)
    Analyze(AnalyzeArgs),
    /// Time each stage (spectrum, FFT, Perlin, blend, writers) against a bare 2D real FFT
    Bench(BenchArgs),
    /// The model spectrum: F(f) at given frequencies (--json, --csv), or plots of F(f) and Ψ(kx, ky)
    Spectrum(SpectrumArgs),
    /// A shaded perspective preview of a field (synthesized, or --from a height map), 8-bit PNG
    Render(Box<RenderArgs>),
}

/// Parameters of one field: a preset, then `--set` and flags over it.
#[derive(Debug, Args, Clone, Default)]
pub struct FieldArgs {
    /// Built-in preset name or a .toml/.json parameter file (a sidecar regenerates its output)
    #[arg(long, value_name = "NAME|FILE")]
    pub preset: Option<String>,
    /// Set any parameter: a preset key (wind.speed_mps) or a flag name (wind-speed)
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// hybrid (default), fft, filtered-noise, perlin, trochoid
    #[arg(long)]
    pub method: Option<String>,
    /// Spectrum model: phillips, pierson-moskowitz, jonswap, tma, fractal
    #[arg(long)]
    pub spectrum: Option<String>,
    /// Directional spreading: cos2, hasselmann, mitsuyasu, donelan-banner
    #[arg(long)]
    pub spreading: Option<String>,
    /// Fetch for JONSWAP/TMA, km
    #[arg(long, value_name = "KM", allow_hyphen_values = true)]
    pub fetch_km: Option<String>,
    /// Water depth, m (finite-depth dispersion; required by tma)
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    pub depth: Option<String>,
    /// Significant wave height, m (with --tp, instead of wind and fetch)
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    pub hs: Option<String>,
    /// Peak period, s (with --hs)
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub tp: Option<String>,
    /// JONSWAP peak enhancement γ (default 3.3)
    #[arg(long, value_name = "G", allow_hyphen_values = true)]
    pub gamma: Option<String>,
    /// Samples: N (square) or NxM
    #[arg(long, value_name = "N|NxM", allow_hyphen_values = true)]
    pub size: Option<String>,
    /// Extent in meters: L (square) or LXxLY
    #[arg(long, value_name = "L|LXxLY", allow_hyphen_values = true)]
    pub extent: Option<String>,
    /// Wind speed, m/s
    #[arg(long, value_name = "MPS", allow_hyphen_values = true)]
    pub wind_speed: Option<String>,
    /// Direction the wind blows toward, degrees (0: +x, 90: +y)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub wind_dir: Option<String>,
    /// Random seed (0 … 2^63−1)
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub seed: Option<String>,
    /// Time of the frame, seconds
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub time: Option<String>,
    /// Heights mapped to 0 and 65535 in 16-bit outputs, meters (default: the field's min:max)
    #[arg(long, value_name = "MIN:MAX", allow_hyphen_values = true)]
    pub height_range: Option<String>,
    /// Seamless loop period, s: every ω becomes the nearest non-zero multiple of 2π/T
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub loop_period: Option<String>,
    /// Sea theory of --method fft: linear (default) or second-order (adds the bound waves)
    #[arg(long, value_name = "ORDER")]
    pub nonlinear: Option<String>,
    /// Choppy waves: horizontal displacement factor λ (0: none; 1: trochoid-like)
    #[arg(long, value_name = "L", allow_hyphen_values = true)]
    pub choppiness: Option<String>,
    /// Foam where the Jacobian of the choppy displacement is below this; auto (default):
    /// on the most compressed part of the sea equal to the wind's whitecap coverage
    /// (Monahan), or J < 0.3 without a wind-driven spectrum
    #[arg(long, value_name = "auto|J", allow_hyphen_values = true)]
    pub foam_threshold: Option<String>,
    /// animate: seconds foam takes to fade after the surface stops compressing it
    /// (default 0: each frame's own foam; 1–3 s lingers like a host's foam fade)
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub foam_fade: Option<String>,
    /// Frames per second (animate; the per-frame filtered-noise phase modes)
    #[arg(long, value_name = "F", allow_hyphen_values = true)]
    pub fps: Option<String>,
    /// Filtered-noise motion: dispersion (default), translate, hot-air
    #[arg(long, value_name = "MODE")]
    pub phase_mode: Option<String>,
    /// Where samples sit: corners (default; sample (i, j) at (i·dx, j·dy)) or centers
    /// (((i + ½)·dx, (j + ½)·dy), where image-based displacement samples a texture)
    #[arg(long, value_name = "corners|centers")]
    pub sample_at: Option<String>,
    /// Run even when the estimated peak memory exceeds the available memory
    #[arg(long)]
    pub force: bool,
}

impl FieldArgs {
    /// The flags given, as (flag name, value) in a fixed order.
    pub fn flags(&self) -> Vec<(&'static str, &str)> {
        [
            ("method", &self.method),
            ("spectrum", &self.spectrum),
            ("spreading", &self.spreading),
            ("fetch-km", &self.fetch_km),
            ("depth", &self.depth),
            ("hs", &self.hs),
            ("tp", &self.tp),
            ("gamma", &self.gamma),
            ("size", &self.size),
            ("extent", &self.extent),
            ("wind-speed", &self.wind_speed),
            ("wind-dir", &self.wind_dir),
            ("seed", &self.seed),
            ("time", &self.time),
            ("height-range", &self.height_range),
            ("loop-period", &self.loop_period),
            ("nonlinear", &self.nonlinear),
            ("choppiness", &self.choppiness),
            ("foam-threshold", &self.foam_threshold),
            ("foam-fade", &self.foam_fade),
            ("fps", &self.fps),
            ("phase-mode", &self.phase_mode),
            ("sample-at", &self.sample_at),
        ]
        .into_iter()
        .filter_map(|(k, v)| v.as_deref().map(|v| (k, v)))
        .collect()
    }
}

#[derive(Debug, Args)]
pub struct GenerateArgs {
    #[command(flatten)]
    pub field: FieldArgs,
    /// Output file; repeat for several formats of one field (.png 16-bit, .tif/.exr float
    /// meters, .r16/.raw/.r32 raw, .obj/.glb mesh). Default: out/PRESET.png and out/PRESET.tif
    #[arg(short = 'o', long = "output", value_name = "PATH")]
    pub outputs: Vec<PathBuf>,
    /// How meshes, raw height maps and tiles are written
    #[command(flatten)]
    pub export: ExportArgs,
    /// Print nothing but errors
    #[arg(short, long)]
    pub quiet: bool,
    /// Worker threads (default: all cores); results do not depend on it
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
}

/// Arguments of `seasynth render`; values are kept as typed and checked in
/// `commands::render`, so every bad value gets the same one-line error.
#[derive(Debug, Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub field: FieldArgs,
    /// Render this height map instead: a float TIFF in meters, a 16-bit PNG with its sidecar,
    /// or any PNG, JPEG, TIFF, OpenEXR, BMP or WebP image (with --height-range MIN:MAX for
    /// integer images without a mapping, --extent for the spacing)
    #[arg(long, value_name = "FILE")]
    pub from: Option<PathBuf>,
    /// The image to write, 8-bit sRGB: .png, .jpg (quality 90) or .webp (lossless)
    #[arg(short = 'o', long = "output", value_name = "PNG")]
    pub output: PathBuf,
    /// Image size in pixels (default 1280x720)
    #[arg(long, value_name = "WxH", allow_hyphen_values = true)]
    pub image: Option<String>,
    /// Rays per pixel, 1 … 256 (default 4)
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub spp: Option<String>,
    /// Camera placement: grazing (default), aerial, top
    #[arg(long, value_name = "NAME")]
    pub view: Option<String>,
    /// Camera position in meters (x, y as the field's axes, z as its heights)
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub camera: Option<String>,
    /// Camera height above the field's mean level, meters
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    pub camera_height: Option<String>,
    /// Look direction, degrees from +x toward +y (default: down-wind)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub yaw: Option<String>,
    /// Look direction above the horizontal, degrees (negative: down)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub pitch: Option<String>,
    /// Look at this point instead of --yaw/--pitch, meters
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub look_at: Option<String>,
    /// Horizontal field of view, degrees (default 60; top view 50)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub fov: Option<String>,
    /// Sun azimuth (from +x toward +y) and elevation, degrees (default: 20° left of the view, 14° up)
    #[arg(long, value_name = "AZ,EL", allow_hyphen_values = true)]
    pub sun: Option<String>,
    /// Haze distance in meters, 0 for none (default: 4 field sizes or 10 camera heights)
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    pub haze: Option<String>,
    /// Sky reflection weight: fresnel (Schlick, n = 1.33; default) or pseudo, pseudo:C (1 − (n·v)^C, C = 0.3 by default)
    #[arg(long, value_name = "fresnel|pseudo[:C]")]
    pub reflection: Option<String>,
    /// Repeat the field to the horizon (the default for periodic fields)
    #[arg(long, overrides_with = "no_repeat")]
    pub repeat: bool,
    /// Do not repeat: the field lies in a flat sea at its mean height
    #[arg(long, overrides_with = "repeat")]
    pub no_repeat: bool,
    /// Turn off the distance low-pass of the surface (mean mip levels chosen by ray footprint)
    #[arg(long)]
    pub no_lod: bool,
    /// Print nothing but errors
    #[arg(short, long)]
    pub quiet: bool,
    /// Worker threads (default: all cores); images do not depend on it
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
}

#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Grid sizes to time (square)
    #[arg(long, value_delimiter = ',', default_values_t = [1024usize, 4096])]
    pub sizes: Vec<usize>,
    /// Repetitions per stage; the median is reported
    #[arg(long, default_value_t = 5)]
    pub repeats: usize,
    /// Folder for the writers' files
    #[arg(long, default_value = "out/bench")]
    pub dir: PathBuf,
    /// Also time the mesh exports: 2048² OBJ and GLB, a 4×4 OBJ tile set at 4096²
    /// (writes files of up to 3.7 GB in --dir, each removed after timing)
    #[arg(long)]
    pub exports: bool,
    /// Also time 48-frame `animate` sequences at 1024² (choppy displacement + foam, the
    /// same as half-float ZIP EXR, height PNG + normal + foam), with Blender's ocean bake
    /// of the same frames beside them when `blender` is on the PATH
    #[arg(long)]
    pub sequence: bool,
    /// Worker threads (default: all cores)
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Where samples sit: corners (default; sample (i, j) at (i·dx, j·dy)) or centers
    /// (((i + ½)·dx, (j + ½)·dy), where image-based displacement samples a texture)
    #[arg(long, value_name = "corners|centers")]
    pub sample_at: Option<String>,
    /// Run even when the estimated peak memory exceeds the available memory
    #[arg(long)]
    pub force: bool,
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn the_command_line_definition_is_consistent() {
        Cli::command().debug_assert();
    }
}
