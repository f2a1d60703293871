//! `seasynth animate`.

use std::path::PathBuf;

use clap::Args;

use super::{ExrArgs, FieldArgs};

#[derive(Debug, Args)]
pub struct AnimateArgs {
    #[command(flatten)]
    pub field: FieldArgs,
    /// Number of frames
    #[arg(long, default_value_t = 30)]
    pub frames: usize,
    /// Output folder (created if missing)
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    pub dir: PathBuf,
    /// Files per frame: png (16-bit height), tif or exr (float height), normal, foam,
    /// jacobian, disp (maps; disp.exr, normal.exr, foam.exr, jacobian.exr as float EXR),
    /// preview (a rendered view)
    #[arg(long, value_delimiter = ',', default_value = "png")]
    pub format: Vec<String>,
    /// Number in the first frame's file names; frame files are numbered on from it
    /// (default: 1 when an EXR is written, as image-sequence readers expect, else 0)
    #[arg(long, value_name = "N")]
    pub start_frame: Option<usize>,
    /// Axis convention of disp.exr: y (R, G, B = x, height, −y) or z (x, y, height) [default: y]
    #[arg(long, value_name = "y|z")]
    pub up: Option<String>,
    /// How .exr frames are written
    #[command(flatten)]
    pub exr: ExrArgs,
    /// Skip frames whose files are all there (files appear only when complete)
    #[arg(long)]
    pub resume: bool,
    /// Frames computed at once [default: cores, limited by memory]
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
    /// Print nothing but errors
    #[arg(short, long)]
    pub quiet: bool,
    /// Worker threads; results do not depend on it [default: all cores]
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
}
