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
