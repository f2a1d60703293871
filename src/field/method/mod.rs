//! One type per `--method`, all behind [`HeightMethod`], built by [`method_for`].
//!
//! | method | type | computes with |
//! |---|---|---|
//! | `fft` | [`FftSea`] | `field::fft`, `field::dynamics` |
//! | `filtered-noise` | [`FilteredNoise`] | `field::filtered_noise`, `field::dynamics` |
//! | `perlin` | [`PerlinNoise`] | `field::perlin` |
//! | `hybrid` | [`Hybrid`] | an [`FftSea`], a [`PerlinNoise`] and α (`field::weight`, `field::hybrid`) |
//! | `trochoid` | [`TrochoidMethod`] | `field::trochoid` |

mod fft_sea;
mod filtered_noise;
mod hybrid;
mod perlin_noise;
mod spectral;
mod trochoid;

pub use fft_sea::FftSea;
pub use filtered_noise::FilteredNoise;
pub use hybrid::Hybrid;
pub use perlin_noise::PerlinNoise;
pub use trochoid::TrochoidMethod;

use super::dynamics::{Extras, Jacobian, Surface};
use super::{Synthesis, SynthesisInfo};
use crate::config::{Method, Params};
use crate::error::Result;
use crate::grid::Grid;

/// A way of computing height fields (one `--method`) for one set of parameters.
///
/// A method is built in two steps: [`method_for`] reads the parameters (cheap: no work
/// that grows with the grid, so a caller can ask the questions below before deciding to
/// run), then [`prepare`](Self::prepare) does the work every frame shares (noise fields,
/// fits, kept random draws), once. [`frame`](Self::frame) then gives the field at any
/// time: frames equal [`super::synthesize`] at their time bit for bit.
///
/// Adding a method: one file under `field/method/` with a type implementing this trait,
/// and one line in [`method_for`] (with its name in `config::Method`).
pub trait HeightMethod: Send + Sync {
    /// Does the time-independent work, once, before the first [`frame`](Self::frame).
    /// `keep_draws`: keep the random amplitudes between frames, where the method has them
    /// (memory: 32 bytes per wavevector of the half plane).
    fn prepare(&mut self, keep_draws: bool) -> Result<()>;

    /// The field at `time_s` with the derived fields `extras`, and what the sidecar
    /// records of it ([`SynthesisInfo`]). Panics before [`prepare`](Self::prepare).
    fn frame(&self, time_s: f64, extras: Extras) -> Synthesis;

    /// Peak bytes per grid sample of one field of this method in memory with its height
    /// outputs (measured peaks plus about a quarter; see `pipeline::memory::Footprint`,
    /// which adds choppiness, derived fields and outputs).
    fn bytes_per_sample(&self) -> u64;

    /// True when the field is periodic over the extent (tileable: meshes and tiles may
    /// wrap, slopes are taken across the edges).
    fn is_periodic(&self) -> bool;

    /// True when PNG and TIFF outputs may be computed and written a batch of rows at a
    /// time (`pipeline::stream`), so that they may exceed memory.
    fn streams_rows(&self) -> bool {
        false
    }

    /// True when the slopes of [`frame`](Self::frame) are the exact (spectral) slopes of
    /// its height map; otherwise they are central differences of the heights.
    fn exact_slopes(&self) -> bool {
        false
    }

    /// True when the whole field follows the spectrum model, so that a measured spectrum
    /// can be compared with it (`seasynth analyze`).
    fn follows_spectrum(&self) -> bool {
        false
    }
}

/// The method validated `params` ask for, not yet prepared.
pub fn method_for(params: &Params) -> Box<dyn HeightMethod> {
    match params.method {
        Method::Fft => Box::new(FftSea::new(params)),
        Method::FilteredNoise => Box::new(FilteredNoise::new(params)),
        Method::Perlin => Box::new(PerlinNoise::new(params)),
        Method::Hybrid => Box::new(Hybrid::new(params)),
        Method::Trochoid => Box::new(TrochoidMethod::new(params)),
    }
}

/// A frame from its heights and the derived fields the method computed: the slopes by
/// central differences of the heights where `extras` asks for them and the method has
/// none that are the heights' own (`exact`: the surface's slopes are; heights already
/// resampled when choppy, so their normals need no displacement gradient), and J = 1
/// where there is no displacement.
fn finish(
    grid: Grid,
    info: SynthesisInfo,
    mut surface: Surface,
    extras: Extras,
    periodic: bool,
    exact: bool,
) -> Synthesis {
    if extras.slopes && (!exact || surface.slopes.is_none()) {
        let s = crate::measure::slopes::slopes_central(&grid, periodic);
        surface.slopes = Some([s.dhdx, s.dhdy]);
        surface.displacement_gradient = None;
    }
    if extras.jacobian && surface.jacobian.is_none() {
        surface.jacobian = Some(Jacobian::One);
    }
    Synthesis {
        grid,
        info,
        surface,
    }
}
