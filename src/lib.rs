//! seasynth: ocean-wave and terrain height maps from wave spectra and Perlin noise.

pub mod cli;
pub mod commands;
pub mod config;
pub mod error;
pub mod export;
pub mod fastmath;
pub mod field;
pub mod grid;
pub mod io;
pub mod limits;
pub mod measure;
pub mod pipeline;
pub mod plot;
pub mod render;
pub mod rng;
pub mod simd;
pub mod spectrum;
pub mod units;

pub use config::Params;
pub use error::{Error, Result};
pub use field::trochoid::TrochoidSea;
pub use field::{Synthesis, synthesize};
pub use grid::{Grid, GridSpec, Stats};
pub use spectrum::Spectrum;

/// Writes `field`, synthesized from `params`, to every path (the format by each path's
/// extension), each with its JSON sidecar: the files `seasynth generate -o PATH…` writes.
/// Every file is staged first and renamed into place when complete.
pub fn write_field(
    params: &Params,
    paths: &[std::path::PathBuf],
    field: Synthesis,
) -> anyhow::Result<pipeline::write::Written> {
    pipeline::write::write_field(
        params,
        paths,
        &export::options::ExportOptions::default(),
        &pipeline::write::SidecarExtras::default(),
        Some(field),
        false,
    )
}
