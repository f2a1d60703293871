//! `seasynth spectrum`.

use std::path::PathBuf;

/// Command-line arguments of `seasynth spectrum`.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("format").args(["json", "csv"]).multiple(false)))]
pub struct SpectrumArgs {
    /// The field parameters, as for `generate` (boxed: keeps the `Command` enum small).
    #[command(flatten)]
    pub field: Box<super::FieldArgs>,
    /// Frequencies in Hz where F(f) is printed, comma-separated (each > 0); with --json or --csv
    /// [default: none]
    #[arg(
        long,
        value_name = "F1,F2,…",
        allow_hyphen_values = true,
        requires = "format"
    )]
    pub freq: Option<String>,
    /// Print one JSON object: {spectrum, points:[{f_hz, s_m2_per_hz}], hs_m, fp_hz, tp_s,
    /// m0_m2, kp_rad_per_m, peak_wavelength_m, params (every parameter, as in a preset)}
    #[arg(long, requires = "freq")]
    pub json: bool,
    /// Print CSV: the header f_hz,s_m2_per_hz and one row per frequency
    #[arg(long, requires = "freq")]
    pub csv: bool,
    /// Write F(f) on log–log axes, peak marked (800×500 PNG; a missing folder is created)
    /// [default: none]
    #[arg(long, value_name = "FILE.png")]
    pub plot: Option<PathBuf>,
    /// Write the directional wavenumber spectrum Ψ(kx, ky) over ±3 kp as a color map (600×600
    /// PNG) [default: none]
    #[arg(long, value_name = "FILE.png")]
    pub plot2d: Option<PathBuf>,
}
