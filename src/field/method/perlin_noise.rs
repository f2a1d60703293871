//! The `perlin` method: multi-octave Perlin fBm alone (Li Tian eq. 9), or a noise-rs
//! basis and fractal (`perlin.basis`, `perlin.fractal`), scaled to meters.

use super::{HeightMethod, finish};
use crate::config::Params;
use crate::error::Result;
use crate::field::dynamics::{Extras, Surface};
use crate::field::{Synthesis, SynthesisInfo, perlin, perlin_params};
use crate::grid::{Grid, GridSpec};

/// Perlin fBm, in [−1, 1] before scaling: the same field at every time.
pub struct PerlinNoise {
    params: Params,
    /// The normalized noise and the octaves' wavelengths, once prepared.
    ready: Option<(Vec<f32>, SynthesisInfo)>,
}

impl PerlinNoise {
    pub fn new(params: &Params) -> Self {
        Self {
            params: params.clone(),
            ready: None,
        }
    }

    /// The normalized noise, row-major (after `prepare`).
    pub(super) fn noise(&self) -> &[f32] {
        &self
            .ready
            .as_ref()
            .expect("prepared before the first frame")
            .0
    }

    /// The octaves' wavelengths the sidecar records (after `prepare`).
    pub(super) fn info(&self) -> &SynthesisInfo {
        &self
            .ready
            .as_ref()
            .expect("prepared before the first frame")
            .1
    }

    fn spec(&self) -> GridSpec {
        self.params.grid_spec()
    }
}

impl HeightMethod for PerlinNoise {
    fn prepare(&mut self, _keep_draws: bool) -> Result<()> {
        let spec = self.spec();
        let pp = perlin_params(&self.params);
        let cfg = &self.params.perlin;
        let info = SynthesisInfo {
            perlin_wavelengths_m: perlin::basis_wavelengths(&spec, &pp, cfg.basis),
            ..SynthesisInfo::default()
        };
        let offset = self.params.grid.sample_at.offset();
        let noise = perlin::noise_field(&spec, &pp, offset, cfg.basis, cfg.fractal);
        self.ready = Some((noise, info));
        Ok(())
    }

    fn frame(&self, _time_s: f64, extras: Extras) -> Synthesis {
        let amp = self.params.perlin.amplitude_m as f32;
        let grid = Grid::new(self.spec(), self.noise().iter().map(|v| v * amp).collect());
        let info = self.info().clone();
        finish(
            grid,
            info,
            Surface::default(),
            extras,
            self.is_periodic(),
            false,
        )
    }

    fn bytes_per_sample(&self) -> u64 {
        10
    }

    fn is_periodic(&self) -> bool {
        self.params.perlin.tileable
    }
}
