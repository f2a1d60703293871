//! Reading height maps that seasynth (or another tool) wrote.

pub mod heightmap;

pub use heightmap::{ImageKind, Loaded, load, load_detailed};
