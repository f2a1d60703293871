//! The command line (clap). Values are kept as typed and turned into parameters in one
//! place (`config::layers`), so flags, `--set` and presets share one parser and one set of
//! error messages.

use std::path::PathBuf;

use clap::{ArgMatches, Args, CommandFactory, FromArgMatches, Parser, Subcommand};

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
    about = "Ocean-wave and terrain height maps from wave spectra and Perlin noise",
    args_override_self = true
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
    /// [default: li-tian]
    #[arg(long, value_name = "NAME|FILE")]
    pub preset: Option<String>,
    /// Set any parameter: a preset key (wind.speed_mps) or a flag name (wind-speed); repeatable.
    /// --set and the flags apply in the order given, over the preset: the last one wins
    /// [default: none]
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// hybrid, fft, filtered-noise, perlin, trochoid [default: the preset's; hybrid in li-tian]
    #[arg(long)]
    pub method: Option<String>,
    /// Spectrum model: phillips, pierson-moskowitz, jonswap, tma, fractal [default: the
    /// preset's; phillips in li-tian]
    #[arg(long)]
    pub spectrum: Option<String>,
    /// Directional spreading: cos2, hasselmann, mitsuyasu, donelan-banner [default: the
    /// preset's; hasselmann in li-tian]
    #[arg(long)]
    pub spreading: Option<String>,
    /// Fetch for JONSWAP/TMA, km [default: the preset's; 100 in li-tian]
    #[arg(long, value_name = "KM", allow_hyphen_values = true)]
    pub fetch_km: Option<String>,
    /// Water depth, m (finite-depth dispersion; required by tma) [default: the preset's;
    /// deep water in li-tian]
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    pub depth: Option<String>,
    /// Significant wave height, m (with --tp, instead of wind and fetch) [default: the
    /// preset's; none in li-tian]
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    pub hs: Option<String>,
    /// Peak period, s (with --hs) [default: the preset's; none in li-tian]
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub tp: Option<String>,
    /// JONSWAP peak enhancement γ [default: the preset's; 3.3 in li-tian]
    #[arg(long, value_name = "G", allow_hyphen_values = true)]
    pub gamma: Option<String>,
    /// Samples: N (square) or NxM [default: the preset's; 512 in li-tian]
    #[arg(long, value_name = "N|NxM", allow_hyphen_values = true)]
    pub size: Option<String>,
    /// Extent in meters: L (square) or LXxLY [default: the preset's; 512 in li-tian]
    #[arg(long, value_name = "L|LXxLY", allow_hyphen_values = true)]
    pub extent: Option<String>,
    /// Wind speed, m/s [default: the preset's; 7 in li-tian]
    #[arg(long, value_name = "MPS", allow_hyphen_values = true)]
    pub wind_speed: Option<String>,
    /// Direction the wind blows toward, degrees (0: +x, 90: +y) [default: the preset's; 0 in
    /// li-tian]
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub wind_dir: Option<String>,
    /// Random seed (0 … 2^63−1) [default: the preset's; 1 in li-tian]
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub seed: Option<String>,
    /// Time of the frame, seconds [default: the preset's; 0 in li-tian]
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub time: Option<String>,
    /// Heights mapped to 0 and 65535 in 16-bit outputs, meters [default: the field's min:max]
    #[arg(long, value_name = "MIN:MAX", allow_hyphen_values = true)]
    pub height_range: Option<String>,
    /// Seamless loop period, s: every ω becomes the nearest non-zero multiple of 2π/T
    /// [default: the preset's; none (no loop) in li-tian]
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub loop_period: Option<String>,
    /// Sea theory of the FFT sea (--method fft or hybrid): linear or second-order (adds the
    /// bound waves) [default: the preset's; linear in li-tian]
    #[arg(long, value_name = "ORDER")]
    pub nonlinear: Option<String>,
    /// Choppy waves: horizontal displacement factor λ (0: none; 1: trochoid-like) [default:
    /// the preset's; 0 in li-tian]
    #[arg(long, value_name = "L", allow_hyphen_values = true)]
    pub choppiness: Option<String>,
    /// Foam where the Jacobian of the choppy displacement is below this; auto: on the
    /// most compressed part of the sea equal to the wind's whitecap coverage (Monahan), or
    /// J < 0.3 without a wind-driven spectrum [default: the preset's; auto in li-tian]
    #[arg(long, value_name = "auto|J", allow_hyphen_values = true)]
    pub foam_threshold: Option<String>,
    /// animate: seconds foam takes to fade after the surface stops compressing it (0: each
    /// frame's own foam; 1–3 s lingers like a host's foam fade) [default: the preset's; 0
    /// in li-tian]
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub foam_fade: Option<String>,
    /// Frames per second (animate; the per-frame filtered-noise phase modes) [default: the
    /// preset's; 30 in li-tian]
    #[arg(long, value_name = "F", allow_hyphen_values = true)]
    pub fps: Option<String>,
    /// Filtered-noise motion: dispersion, translate, hot-air [default: the preset's;
    /// dispersion in li-tian]
    #[arg(long, value_name = "MODE")]
    pub phase_mode: Option<String>,
    /// Where samples sit: corners (sample (i, j) at (i·dx, j·dy)) or centers (((i + ½)·dx,
    /// (j + ½)·dy), where image-based displacement samples a texture) [default: the
    /// preset's; corners in li-tian]
    #[arg(long, value_name = "corners|centers")]
    pub sample_at: Option<String>,
    /// Run even when the estimated peak memory exceeds the available memory
    #[arg(long)]
    pub force: bool,
    /// `--set` and the flags as (`set` or the flag's name, value), in command-line order;
    /// filled by [`Cli::parse_ordered`] (empty: `--set` first, then the flags).
    #[arg(skip)]
    pub order: Vec<(String, String)>,
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

    /// `--set` (as `("set", "KEY=VALUE")`) and the flags, in the order they apply: the
    /// command line's when it was recorded, else every `--set`, then the flags.
    pub fn in_order(&self) -> Vec<(&str, &str)> {
        if !self.order.is_empty() {
            return self
                .order
                .iter()
                .map(|(k, v)| (k.as_str(), v.as_str()))
                .collect();
        }
        self.set
            .iter()
            .map(|s| ("set", s.as_str()))
            .chain(self.flags())
            .collect()
    }

    /// Records the command-line order of `--set` and the flags from `matches`.
    fn record_order(&mut self, matches: &ArgMatches) {
        let mut order: Vec<(usize, String, String)> = Vec::new();
        if let (Some(values), Some(indices)) =
            (matches.get_many::<String>("set"), matches.indices_of("set"))
        {
            for (v, i) in values.zip(indices) {
                order.push((i, "set".into(), v.clone()));
            }
        }
        for (flag, value) in self.flags() {
            if let Some(i) = matches.index_of(&flag.replace('-', "_")) {
                order.push((i, flag.into(), value.into()));
            }
        }
        order.sort_by_key(|o| o.0);
        self.order = order.into_iter().map(|(_, k, v)| (k, v)).collect();
    }
}

impl Cli {
    /// Parses the process's command line, as `Cli::parse`, and records the order of each
    /// command's `--set` and parameter flags (they apply in that order).
    pub fn parse_ordered() -> Self {
        Self::try_parse_ordered_from(std::env::args_os()).unwrap_or_else(|e| e.exit())
    }

    /// [`parse_ordered`](Self::parse_ordered) of the given arguments (the first is the
    /// program's name).
    pub fn try_parse_ordered_from<I, T>(args: I) -> Result<Self, clap::Error>
    where
        I: IntoIterator<Item = T>,
        T: Into<std::ffi::OsString> + Clone,
    {
        let matches = Self::command().try_get_matches_from(args)?;
        let mut cli = Self::from_arg_matches(&matches)?;
        if let (Some((_, sub)), Some(field)) = (matches.subcommand(), cli.command.field_mut()) {
            field.record_order(sub);
        }
        Ok(cli)
    }
}

impl Command {
    /// The field parameters of a command that has them.
    pub fn field_mut(&mut self) -> Option<&mut FieldArgs> {
        match self {
            Command::Generate(a) => Some(&mut a.field),
            Command::Animate(a) => Some(&mut a.field),
            Command::Batch(a) => Some(&mut a.field),
            Command::Spectrum(a) => Some(&mut a.field),
            Command::Render(a) => Some(&mut a.field),
            _ => None,
        }
    }
}

#[derive(Debug, Args)]
pub struct GenerateArgs {
    #[command(flatten)]
    pub field: FieldArgs,
    /// Output file, its kind by its name; repeat for several outputs of one field. Heights:
    /// .png (16-bit), .tif/.tiff/.exr (float meters), .r16/.raw/.r32 (raw), .obj/.glb
    /// (mesh). Maps: NAME.normal.png/.normal.exr, NAME.foam.png/.foam.exr,
    /// NAME.jacobian.tif/.jacobian.tiff/.jacobian.exr, NAME.disp.tif/.disp.tiff/.disp.exr;
    /// a view: NAME.preview.png/.preview.jpg/.preview.jpeg/.preview.webp. A missing folder
    /// is created. [default: out/STEM.png and out/STEM.tif, STEM the --preset's name (or
    /// file stem + "-regenerated") when no flag or --set changes it, else STEM-custom]
    #[arg(short = 'o', long = "output", value_name = "PATH")]
    pub outputs: Vec<PathBuf>,
    /// How meshes, raw height maps and tiles are written
    #[command(flatten)]
    pub export: ExportArgs,
    /// Print nothing but errors
    #[arg(short, long)]
    pub quiet: bool,
    /// Worker threads; results do not depend on it [default: all cores]
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
    /// integer images without a mapping, --extent for the spacing) [default: none, the
    /// field is synthesized]
    #[arg(long, value_name = "FILE")]
    pub from: Option<PathBuf>,
    /// The image to write, 8-bit sRGB: .png, .jpg (quality 90) or .webp (lossless)
    #[arg(short = 'o', long = "output", value_name = "PNG")]
    pub output: PathBuf,
    /// Image size in pixels [default: 1280x720]
    #[arg(long, value_name = "WxH", allow_hyphen_values = true)]
    pub image: Option<String>,
    /// Rays per pixel, 1 … 256 [default: 4]
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub spp: Option<String>,
    /// Camera placement: grazing, aerial, top [default: grazing]
    #[arg(long, value_name = "NAME")]
    pub view: Option<String>,
    /// Camera position in meters (x, y as the field's axes, z as its heights) [default:
    /// placed by --view]
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub camera: Option<String>,
    /// Camera height above the field's mean level, meters [default: placed by --view]
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    pub camera_height: Option<String>,
    /// Look direction, degrees from +x toward +y [default: down-wind]
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub yaw: Option<String>,
    /// Look direction above the horizontal, degrees (negative: down) [default: placed by
    /// --view]
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub pitch: Option<String>,
    /// Look at this point instead of --yaw/--pitch, meters [default: none]
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub look_at: Option<String>,
    /// Horizontal field of view, degrees [default: 60; top view 50]
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub fov: Option<String>,
    /// Sun azimuth (from +x toward +y) and elevation, degrees [default: 20° left of the
    /// view, 14° up]
    #[arg(long, value_name = "AZ,EL", allow_hyphen_values = true)]
    pub sun: Option<String>,
    /// Haze distance in meters, 0 for none [default: 4 field sizes or 10 camera heights]
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    pub haze: Option<String>,
    /// Sky reflection weight: fresnel (Schlick, n = 1.33) or pseudo, pseudo:C (1 − (n·v)^C,
    /// C = 0.3 by default) [default: fresnel]
    #[arg(long, value_name = "fresnel|pseudo[:C]")]
    pub reflection: Option<String>,
    /// Repeat the field to the horizon [default: on for periodic fields]
    #[arg(long, overrides_with = "no_repeat")]
    pub repeat: bool,
    /// Do not repeat: the field lies in a flat sea at its mean height [default: on for
    /// fields that are not periodic]
    #[arg(long, overrides_with = "repeat")]
    pub no_repeat: bool,
    /// Turn off the distance low-pass of the surface (mean mip levels chosen by ray
    /// footprint) [default: low-pass on]
    #[arg(long)]
    pub no_lod: bool,
    /// Print nothing but errors
    #[arg(short, long)]
    pub quiet: bool,
    /// Worker threads; images do not depend on it [default: all cores]
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
    /// Also time second-order seas beside the linear one at each size (Pierson–Moskowitz
    /// 15 m/s over 2048 m): the exact pair sum of the strongest waves carrying 0.99 of
    /// the variance within the convergence limit and the fitted method of every wave
    /// within it, as ratios to the linear field; and 48 frames of the sea (medians of
    /// three runs), unlooped (the default method) and looping (T = 20 s, the pair sum
    /// binned), linear and second order, with their ratios; and the fitted method where
    /// the paired waves' box fills the grid (the same storm in 4 m cells, n² over 4n m),
    /// deep and at 19 m
    #[arg(long)]
    pub second_order: bool,
    /// Worker threads [default: all cores]
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Where samples sit: corners (sample (i, j) at (i·dx, j·dy)) or centers (((i + ½)·dx,
    /// (j + ½)·dy), where image-based displacement samples a texture) [default: corners]
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

    fn parse(args: &[&str]) -> Cli {
        Cli::try_parse_ordered_from(std::iter::once("seasynth").chain(args.iter().copied()))
            .unwrap_or_else(|e| panic!("{args:?}: {e}"))
    }

    fn field(cli: &mut Cli) -> &FieldArgs {
        cli.command.field_mut().expect("a field command")
    }

    #[test]
    fn set_and_flags_keep_their_command_line_order_and_a_repeated_flag_its_last_value() {
        let mut cli = parse(&[
            "generate",
            "--wind-speed",
            "10",
            "--set",
            "wind-speed=12",
            "--seed",
            "3",
            "--set",
            "seed=4",
        ]);
        assert_eq!(
            field(&mut cli).in_order(),
            [
                ("wind-speed", "10"),
                ("set", "wind-speed=12"),
                ("seed", "3"),
                ("set", "seed=4")
            ]
        );
        let mut cli = parse(&["spectrum", "--set", "wind-speed=12", "--wind-speed", "10"]);
        assert_eq!(
            field(&mut cli).in_order(),
            [("set", "wind-speed=12"), ("wind-speed", "10")]
        );
        // A flag given twice: the last value, at the place of its last occurrence.
        let mut cli = parse(&[
            "batch",
            "--wind-speed",
            "10",
            "--set",
            "wind-speed=11",
            "--wind-speed",
            "12",
            "-o",
            "b",
            "-o",
            "c",
        ]);
        assert_eq!(
            field(&mut cli).in_order(),
            [("set", "wind-speed=11"), ("wind-speed", "12")]
        );
        // -o, --set, --sweep stay repeatable.
        let cli = parse(&[
            "generate", "-o", "a.png", "-o", "b.tif", "--quiet", "--quiet",
        ]);
        let Command::Generate(g) = cli.command else {
            panic!("generate")
        };
        assert_eq!(g.outputs.len(), 2);
        let cli = parse(&[
            "batch",
            "--sweep",
            "seed=1,2",
            "--sweep",
            "size=8,16",
            "-o",
            "b",
        ]);
        let Command::Batch(b) = cli.command else {
            panic!("batch")
        };
        assert_eq!(b.sweep.len(), 2);
        // Without a recorded order (a FieldArgs made in code): every --set, then the flags.
        let f = FieldArgs {
            set: vec!["seed=2".into()],
            seed: Some("5".into()),
            ..Default::default()
        };
        assert_eq!(f.in_order(), [("set", "seed=2"), ("seed", "5")]);
    }

    #[test]
    fn every_flag_says_its_default() {
        let cmd = Cli::command();
        let mut missing = Vec::new();
        for sub in cmd.get_subcommands() {
            for arg in sub.get_arguments() {
                let switch = matches!(
                    arg.get_action(),
                    clap::ArgAction::SetTrue | clap::ArgAction::SetFalse
                );
                if arg.is_positional()
                    || switch
                    || arg.is_required_set()
                    || !arg.get_default_values().is_empty()
                {
                    continue;
                }
                let help = format!(
                    "{} {}",
                    arg.get_help().map(|h| h.to_string()).unwrap_or_default(),
                    arg.get_long_help()
                        .map(|h| h.to_string())
                        .unwrap_or_default()
                );
                if !help.to_lowercase().contains("default") {
                    missing.push(format!("{} --{}", sub.get_name(), arg.get_id()));
                }
            }
        }
        assert!(missing.is_empty(), "help without a default: {missing:?}");
    }

    #[test]
    fn the_output_help_lists_every_output_the_file_name_table_knows() {
        let mut cmd = Cli::command();
        let help = cmd
            .find_subcommand_mut("generate")
            .expect("generate")
            .render_long_help()
            .to_string();
        let suffixes = crate::export::format::all_suffixes();
        assert!(suffixes.len() > 20, "{suffixes:?}");
        for s in suffixes {
            assert!(help.contains(&s), "`generate --help` does not name {s}");
        }
    }
}
