//! The `fft` method: Tessendorf's FFT sea (Li Tian eq. 1–8), with exact spectral slopes,
//! choppy displacement and its Jacobian.

use super::spectral::Spectral;
use super::{HeightMethod, finish};
use crate::config::{DEFAULT_NONLINEAR_FRACTION, Nonlinear, NonlinearMethod, Params};
use crate::error::Result;
use crate::field::Synthesis;
use crate::field::dynamics::{Extras, Surface};
use crate::field::fft::second_order::looped::{LoopedBound, MAX_BINS_PER_CELL};
use crate::field::fft::second_order::transform::TransformBound;
use crate::field::fft::second_order::{SecondOrder, SecondOrderInfo};
use crate::field::fft::{self, Amplitudes};
use crate::grid::Grid;

/// Tessendorf's FFT sea: Gaussian random amplitudes of the spectrum, dispersion in time,
/// one inverse FFT.
pub struct FftSea {
    params: Params,
    ready: Option<Ready>,
}

struct Ready {
    spectral: Spectral,
    /// The random draws, when kept between frames.
    amplitudes: Option<Amplitudes>,
    /// The bound waves of a second-order sea.
    second_order: Option<Bound>,
}

/// How the bound waves are evaluated (`spectrum.nonlinear_method`).
enum Bound {
    /// The exact pair sum of the strongest components.
    Pairs(Box<SecondOrder>),
    /// The same pair sum of a looping sea, binned once by the pairs' multiples of 2π/T.
    Looped(Box<LoopedBound>),
    /// Every component, fitted kernels, by transforms (with what the sidecar records).
    Fitted(Box<TransformBound>, SecondOrderInfo),
}

impl FftSea {
    pub fn new(params: &Params) -> Self {
        Self {
            params: params.clone(),
            ready: None,
        }
    }

    /// The heights (resampled when choppy), the derived fields `extras` asks for, and
    /// h0max = max |h̃0(k)|, meters.
    pub(super) fn field(
        &self,
        time_s: f64,
        extras: Extras,
    ) -> (Grid, Surface, f64, Option<SecondOrderInfo>) {
        let ready = self
            .ready
            .as_ref()
            .expect("prepared before the first frame");
        let setup = ready.spectral.setup(time_s);
        let mut half = match &ready.amplitudes {
            Some(a) => a.frame(&setup),
            None => fft::synthesize_spectrum(&setup),
        };
        let bound = ready.second_order.as_ref().map(|b| match b {
            Bound::Pairs(so) => so.add_to(&setup, &mut half),
            Bound::Looped(lb) => lb.add_to(&setup, &mut half),
            Bound::Fitted(tb, info) => {
                tb.add_to(&setup, &mut half);
                info.clone()
            }
        });
        let h0max_m = half.h0max_m;
        let (grid, surface) = ready.spectral.heights(half, extras);
        (grid, surface, h0max_m, bound)
    }

    /// What the sidecar records of the spectrum model (after `prepare`).
    pub(super) fn info(&self) -> &crate::field::SynthesisInfo {
        let ready = self
            .ready
            .as_ref()
            .expect("prepared before the first frame");
        &ready.spectral.info
    }
}

impl HeightMethod for FftSea {
    fn prepare(&mut self, keep_draws: bool) -> Result<()> {
        let spectral = Spectral::new(&self.params)?;
        let amplitudes = keep_draws.then(|| Amplitudes::new(&spectral.setup(0.0)));
        let s = &self.params.spectrum;
        let second_order = (s.nonlinear == Nonlinear::SecondOrder).then(|| {
            let setup = spectral.setup(0.0);
            match s.nonlinear_method {
                NonlinearMethod::Pairs => {
                    let q = s.nonlinear_fraction.unwrap_or(DEFAULT_NONLINEAR_FRACTION);
                    let so = SecondOrder::new(&setup, q);
                    match LoopedBound::new(&so, &setup) {
                        Some(lb) => Bound::Looped(Box::new(lb)),
                        None => Bound::Pairs(Box::new(so)),
                    }
                }
                NonlinearMethod::Fitted => {
                    let (tb, info) = TransformBound::for_setup(&setup);
                    Bound::Fitted(Box::new(tb), info)
                }
            }
        });
        self.ready = Some(Ready {
            spectral,
            amplitudes,
            second_order,
        });
        Ok(())
    }

    fn frame(&self, time_s: f64, extras: Extras) -> Synthesis {
        let (grid, surface, h0max_m, bound) = self.field(time_s, extras);
        let mut info = self.info().clone();
        info.h0max_m = Some(h0max_m);
        info.second_order = bound;
        finish(grid, info, surface, extras, true, true)
    }

    fn bytes_per_sample(&self) -> u64 {
        // A second-order sea adds its full-plane bound spectrum (complex f64), a looping
        // one at most MAX_BINS_PER_CELL complex f32 bins a cell; the fitted method its
        // components and about a dozen complex f64 arrays of the grid padded by 3/2 per
        // axis.
        let s = &self.params.spectrum;
        if s.nonlinear.is_linear() {
            10
        } else if s.nonlinear_method.is_pairs() {
            let bins = match self.params.motion.loop_period_s {
                Some(_) => 8 * MAX_BINS_PER_CELL as u64,
                None => 0,
            };
            26 + bins
        } else {
            10 + 88 + 12 * 16 * 9 / 4
        }
    }

    fn is_periodic(&self) -> bool {
        true
    }

    fn exact_slopes(&self) -> bool {
        self.params.motion.choppiness == 0.0
    }

    fn follows_spectrum(&self) -> bool {
        true
    }
}
