//! seasynth: ocean-wave and terrain height maps from wave spectra and Perlin noise.
//!
//! Heights are in meters on a grid of N×M samples over Lx×Ly meters, sample (i, j) at
//! x = i·Lx/N, y = j·Ly/M. [`Params`] holds everything that fixes a field (a preset,
//! then any change); [`synthesize`] computes it; [`write_field`] writes it as
//! `seasynth generate` does, format by extension, with a sidecar that regenerates it.
//!
//! ```
//! use seasynth::config::{Extent2, Size2};
//!
//! let mut params = seasynth::Params::preset("mastin-1987")?;
//! params.grid.size = Size2([64, 64]);
//! params.grid.extent_m = Extent2([256.0, 256.0]);
//! let field = seasynth::synthesize(&params)?;
//! let stats = field.grid.stats();
//! assert_eq!(field.grid.data.len(), 64 * 64);
//! assert!(stats.hs_m > 0.0 && (stats.hs_m - 4.0 * stats.std_m).abs() < 1e-9);
//! # Ok::<(), seasynth::Error>(())
//! ```
//!
//! The same seed and parameters give the same bits on any number of threads. The
//! layers, from the command line down to the numeric core, are described in
//! `docs/architecture.md`; each imports only the layers below it.

pub mod cli;
pub mod commands;
pub mod config;
pub mod error;
pub mod export;
mod fastmath;
pub mod field;
pub mod grid;
pub mod io;
pub mod limits;
pub mod measure;
pub mod pipeline;
#[cfg(feature = "plot")]
mod plot;
pub mod raster;
pub mod render;
pub mod rng;
mod simd;
pub mod spectrum;
mod units;

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
