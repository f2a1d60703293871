//! Measuring a height field: statistics and the measured wavenumber spectrum, used by
//! `seasynth analyze` and by the trochoid sea's fit of its turbulence.

pub mod foam;
pub mod jacobian;
pub mod slopes;
pub mod spectrum;
pub mod waves;

pub use spectrum::{
    Analysis, COMPARE_FLOOR, NORMALIZATION, RadialBin, Target, TargetSummary, analyze, same_length,
};
