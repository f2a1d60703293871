//! The `trochoid` method: Thon et al.'s sea of trochoids chosen from a spectrum, with
//! spectrum-fitted turbulence; continuous, so its images may be streamed by rows.

use super::{HeightMethod, finish};
use crate::config::Params;
use crate::error::Result;
use crate::field::dynamics::{Extras, Surface};
use crate::field::trochoid::TrochoidSea;
use crate::field::{Synthesis, SynthesisInfo};

/// Thon et al.'s procedural sea on the grid of the parameters.
pub struct TrochoidMethod {
    params: Params,
    ready: Option<(TrochoidSea, SynthesisInfo)>,
}

impl TrochoidMethod {
    pub fn new(params: &Params) -> Self {
        Self {
            params: params.clone(),
            ready: None,
        }
    }
}

impl HeightMethod for TrochoidMethod {
    fn prepare(&mut self, _keep_draws: bool) -> Result<()> {
        crate::config::validate::check_in_memory(&self.params)?;
        let sea = TrochoidSea::new(&self.params)?;
        let info = SynthesisInfo::of_trochoid(&self.params, &sea)?;
        self.ready = Some((sea, info));
        Ok(())
    }

    fn frame(&self, time_s: f64, extras: Extras) -> Synthesis {
        let (sea, info) = self
            .ready
            .as_ref()
            .expect("prepared before the first frame");
        let grid = sea.grid(&self.params.grid_spec(), time_s);
        finish(grid, info.clone(), Surface::default(), extras, false, true)
    }

    fn bytes_per_sample(&self) -> u64 {
        // Held in memory only when not streamed (the field and its outputs).
        8
    }

    fn is_periodic(&self) -> bool {
        false
    }

    fn streams_rows(&self) -> bool {
        true
    }
}
