//! The `fft` method: Tessendorf's FFT sea (Li Tian eq. 1–8), with exact spectral slopes,
//! choppy displacement and its Jacobian.

use super::spectral::Spectral;
use super::{HeightMethod, finish};
use crate::config::{
    AUTO_MAX_ESTIMATE, DEFAULT_NONLINEAR_CUTOFF, DEFAULT_NONLINEAR_FRACTION, Nonlinear,
    NonlinearMethod, Params,
};
use crate::error::Result;
use crate::field::Synthesis;
use crate::field::dynamics::{Extras, Surface};
use crate::field::fft::second_order::looped::{LoopedBound, MAX_BINS_PER_CELL};
use crate::field::fft::second_order::transform::TransformBound;
use crate::field::fft::second_order::{Cutoff, SecondOrder, SecondOrderInfo};
use crate::field::fft::{self, Amplitudes};
use crate::grid::Grid;
use crate::spectrum::Dispersion;

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
    /// The bound waves of a second-order sea, the method's name and why `auto` chose it.
    second_order: Option<(Bound, &'static str, Option<String>)>,
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
        let bound = ready.second_order.as_ref().map(|(b, method, reason)| {
            let info = match b {
                Bound::Pairs(so) => so.add_to(&setup, &mut half),
                Bound::Looped(lb) => lb.add_to(&setup, &mut half),
                Bound::Fitted(tb, info) => {
                    tb.add_to(&setup, &mut half);
                    info.clone()
                }
            };
            SecondOrderInfo {
                method: Some((*method).into()),
                method_reason: reason.clone(),
                ..info
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
            let c = s.nonlinear_cutoff.unwrap_or(DEFAULT_NONLINEAR_CUTOFF);
            let cut = c.is_finite().then(|| Cutoff::of(&setup, c));
            // The exact pair sum's components: the strongest within the limits (its cost
            // grows with their square); the fitted method's: every one within them.
            let pairs_of = || {
                let q = s.nonlinear_fraction.unwrap_or(DEFAULT_NONLINEAR_FRACTION);
                SecondOrder::within(&setup, q, cut)
            };
            let fitted_of = || SecondOrder::within(&setup, s.nonlinear_fraction.unwrap_or(1.0), cut);
            // The exact pair sum, binned once when the sea loops.
            let pairs = |so: SecondOrder| match LoopedBound::new(&so, &setup) {
                Some(lb) => Bound::Looped(Box::new(lb)),
                None => Bound::Pairs(Box::new(so)),
            };
            let fitted = |so: SecondOrder, fit| {
                let (mut tb, info) = TransformBound::with_fit(&setup, so, fit);
                if keep_draws {
                    // A sequence: its output coefficients once for every frame.
                    tb.keep_outputs();
                }
                Bound::Fitted(Box::new(tb), info)
            };
            match s.nonlinear_method {
                NonlinearMethod::Pairs => (pairs(pairs_of()), "pairs", None),
                NonlinearMethod::Fitted => {
                    let so = fitted_of();
                    let fit = TransformBound::fit_for(&setup, &so);
                    (fitted(so, fit), "fitted", None)
                }
                NonlinearMethod::Auto if self.params.motion.loop_period_s.is_some() => {
                    let bound = pairs(pairs_of());
                    let why = match bound {
                        Bound::Looped(_) => "a looping sea: its pairs summed once for every time",
                        _ => "a looping sea: the exact pairs at every time (the loop is too long to bin)",
                    };
                    (bound, "pairs", Some(format!("auto: {why}")))
                }
                NonlinearMethod::Auto => {
                    let so = fitted_of();
                    let fit = TransformBound::fit_for(&setup, &so);
                    let e = fit.rel_rms_error;
                    let pct = |x: f64| format!("{:.2} %", 100.0 * x);
                    if e <= AUTO_MAX_ESTIMATE {
                        let why = format!(
                            "auto: the fitted kernels' estimated error {} is within {}",
                            pct(e),
                            pct(AUTO_MAX_ESTIMATE)
                        );
                        (fitted(so, fit), "fitted", Some(why))
                    } else {
                        // Why a fit falls short: at finite depth, the near-resonant pairs.
                        let cause = match setup.dispersion {
                            Dispersion::Finite { .. } => " (shallow water's near-resonant pairs)",
                            Dispersion::Deep => "",
                        };
                        let why = format!(
                            "auto: the fitted kernels' estimated error {} exceeds {}{cause}: \
                             the exact pairs",
                            pct(e),
                            pct(AUTO_MAX_ESTIMATE)
                        );
                        (pairs(pairs_of()), "pairs", Some(why))
                    }
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
        // A second-order sea by the pair sum adds its full-plane bound spectrum (complex
        // f64), a looping one at most MAX_BINS_PER_CELL complex f32 bins a cell. The fitted
        // method of every wave of the grid adds its components and about a dozen complex
        // f64 arrays of the grid padded by 3/2 per axis (`nonlinear_cutoff = inf`, q = 1);
        // within the convergence limit (or below q = 1) its padded arrays cover the box
        // of the paired components, which the sea sets, not the grid, and its
        // accumulators and first stages hold at most 32 and 8 bytes an output cell (a
        // share of the rows at a time beyond: `transform::stages`). `auto` may take
        // either.
        let s = &self.params.spectrum;
        if s.nonlinear.is_linear() {
            return 10;
        }
        let bins = match self.params.motion.loop_period_s {
            Some(_) => 8 * MAX_BINS_PER_CELL as u64,
            None => 0,
        };
        let pairs = 26 + bins;
        let every_wave = s.nonlinear_cutoff.is_some_and(f64::is_infinite)
            && s.nonlinear_fraction.is_none_or(|q| q >= 1.0);
        let fitted = if every_wave {
            10 + 88 + 12 * 16 * 9 / 4
        } else {
            10 + 32 + 8
        };
        match s.nonlinear_method {
            NonlinearMethod::Pairs => pairs,
            NonlinearMethod::Fitted => fitted,
            NonlinearMethod::Auto => pairs.max(fitted),
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
