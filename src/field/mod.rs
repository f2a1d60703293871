//! Height fields: each method computes a [`Grid`](crate::grid::Grid) of heights in meters.

pub mod fft;
pub mod perlin;
