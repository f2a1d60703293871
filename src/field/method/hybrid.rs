//! The `hybrid` method (the default): Li Tian's blend of an FFT sea and Perlin noise under
//! the weight α (eq. 10), h = α·h_fft + (1 − α)·b·h_perlin; h_fft second-order where
//! asked (the [`FftSea`]'s bound waves, recorded in the sidecar).

use super::{FftSea, HeightMethod, PerlinNoise, finish};
use crate::config::{AlphaConfig, Beta, Params};
use crate::error::Result;
use crate::field::Synthesis;
use crate::field::dynamics::Extras;
use crate::field::hybrid::blend_in_place;
use crate::field::weight::AlphaMap;
use crate::grid::Stats;

/// An [`FftSea`] and a [`PerlinNoise`] blended under α.
pub struct Hybrid {
    params: Params,
    sea: FftSea,
    noise: PerlinNoise,
    alpha: Option<AlphaMap>,
}

impl Hybrid {
    pub fn new(params: &Params) -> Self {
        Self {
            params: params.clone(),
            sea: FftSea::new(params),
            noise: PerlinNoise::new(params),
            alpha: None,
        }
    }

    /// The b of β = (1 − α)·b, meters, for the FFT field `fft` of max |h̃0| `h0max_m`.
    fn beta_m(&self, fft: &crate::grid::Grid, h0max_m: f64) -> f64 {
        let blend = &self.params.blend;
        let b = match blend.beta {
            Beta::Paper => h0max_m,
            Beta::Matched => {
                let pstd = Stats::of_rows(self.noise.noise(), fft.spec.nx).std_m;
                if pstd > 0.0 {
                    fft.stats().std_m / pstd
                } else {
                    0.0
                }
            }
            Beta::Meters(b) => b,
        };
        b * blend.beta_scale
    }
}

impl HeightMethod for Hybrid {
    fn prepare(&mut self, keep_draws: bool) -> Result<()> {
        // Inputs that can fail (an α image) are read before the expensive work.
        self.alpha = Some(AlphaMap::with_offset(
            &self.params.blend.alpha,
            &self.params.grid_spec(),
            self.params.grid.sample_at.offset(),
        )?);
        self.sea.prepare(keep_draws)?;
        self.noise.prepare(keep_draws)
    }

    fn frame(&self, time_s: f64, extras: Extras) -> Synthesis {
        let alpha = self
            .alpha
            .as_ref()
            .expect("prepared before the first frame");
        // The blend's weight and the slopes come from the choppy heights: always resampled.
        let sea_extras = Extras {
            maps_only: false,
            ..extras
        };
        let (mut grid, surface, h0max_m, bound) = self.sea.field(time_s, sea_extras);
        let mut info = self.sea.info().clone();
        info.second_order = bound;
        info.perlin_wavelengths_m = self.noise.info().perlin_wavelengths_m.clone();
        info.h0max_m = Some(h0max_m);
        let b = self.beta_m(&grid, h0max_m);
        info.beta_m = Some(b);
        blend_in_place(&mut grid, self.noise.noise(), alpha, b as f32);
        finish(grid, info, surface, extras, self.is_periodic(), false)
    }

    fn bytes_per_sample(&self) -> u64 {
        // The linear sea's 10 bytes a sample, the noise's 4, and what a second-order sea
        // adds to the first.
        self.sea.bytes_per_sample() + 4
    }

    /// Periodic when both fields are and α is constant (a ramp, radial or image α breaks
    /// the period).
    fn is_periodic(&self) -> bool {
        self.sea.is_periodic()
            && self.noise.is_periodic()
            && matches!(self.params.blend.alpha, AlphaConfig::Constant { .. })
    }
}
