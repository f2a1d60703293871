//! `seasynth analyze`.

use std::path::PathBuf;

/// Command-line arguments of `seasynth analyze`.
#[derive(Debug, clap::Args)]
pub struct AnalyzeArgs {
    /// Height map: a float TIFF in meters, a 16-bit PNG with its sidecar NAME.json, or any
    /// PNG, JPEG, TIFF, OpenEXR, BMP or WebP image (float samples in meters, color by luma)
    pub file: PathBuf,
    /// Heights in meters of an integer image's darkest and brightest values, for images
    /// without a sidecar or seasynth text chunk (default: none, such images are refused)
    #[arg(long, value_name = "MIN:MAX", allow_hyphen_values = true)]
    pub height_range: Option<String>,
    /// Extent in meters, L (square) or LXxLY: the spacing is extent / samples (default:
    /// the sidecar's spacing, else 1 m)
    #[arg(long, value_name = "L|LXxLY", allow_hyphen_values = true)]
    pub extent: Option<String>,
    /// Print one JSON object on stdout instead of the report
    #[arg(long)]
    pub json: bool,
    /// Write a log-log plot of the measured (and target) radial spectrum S(k), 800×500 PNG
    /// (a missing folder is created) [default: none]
    #[arg(long, value_name = "PNG")]
    pub plot: Option<PathBuf>,
    /// Write the crest and wave-height exceedance against Rayleigh and Forristall (2000),
    /// 800×500 PNG (default: none)
    #[arg(long, value_name = "PNG")]
    pub plot_waves: Option<PathBuf>,
    /// A second height map whose crest exceedance --plot-waves draws beside the first
    /// (e.g. the linear sea of the same seed; default: none)
    #[arg(long, value_name = "FILE", requires = "plot_waves")]
    pub compare: Option<PathBuf>,
}
