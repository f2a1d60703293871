//! seasynth: ocean-wave and terrain height maps from wave spectra and Perlin noise.

pub mod analyze;
pub mod animate;
pub mod app;
pub mod batch;
pub mod bench;
pub mod cli;
pub mod config;
pub mod error;
pub mod export;
pub mod fastmath;
pub mod field;
pub mod grid;
pub mod limits;
pub mod pipeline;
pub mod simd;
pub mod units;
pub mod jobs;
pub mod render;
pub mod rng;
pub mod spectrum;
pub mod spectrum_cmd;
pub mod stream;
