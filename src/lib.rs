//! seasynth: ocean-wave and terrain height maps from wave spectra and Perlin noise.

pub mod field;
pub mod grid;
pub mod rng;
pub mod spectrum;
pub mod config;
pub mod error;
