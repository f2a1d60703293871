//! The fit's draws: a polar sample of the spectrum, pairs drawn from it by their expected
//! variance (a guide table over the cumulative weights), from a fixed hash.

use rayon::prelude::*;

use super::super::{Component, depth_of};
use super::Region;
use crate::rng::mix64;
use crate::spectrum::{Dispersion, Spectrum};

/// The polar sample of the spectrum the pairs are drawn from.
const SAMPLE_RADII: usize = 96;
const SAMPLE_ANGLES: usize = 72;

/// The polar sample of the spectrum in `region` (inside its waves' box, within its k_max,
/// at or above its floor): waves and their weights (∝ expected variance).
pub(super) fn spectrum_sample(
    spectrum: &dyn Spectrum,
    dispersion: Dispersion,
    region: Region,
    dk: (f64, f64),
) -> (Vec<Component>, Vec<f64>) {
    let bounds = region.waves;
    let depth = depth_of(dispersion);
    let k_lo = dk.0.min(dk.1);
    let k_hi = bounds.kx_max.hypot(bounds.ky_max);
    let ratio = (k_hi / k_lo).ln();
    // A ring of radii a task (the spectrum's values are the costly part), in ring order.
    let rings: Vec<Vec<(Component, f64)>> = (0..SAMPLE_RADII)
        .into_par_iter()
        .map(|ir| {
            let u0 = ir as f64 / SAMPLE_RADII as f64;
            let u1 = (ir + 1) as f64 / SAMPLE_RADII as f64;
            let (r0, r1) = (k_lo * (u0 * ratio).exp(), k_lo * (u1 * ratio).exp());
            let k = 0.5 * (r0 + r1);
            let mut ring = Vec::new();
            for it in 0..SAMPLE_ANGLES {
                let th = std::f64::consts::TAU * (it as f64 + 0.5) / SAMPLE_ANGLES as f64;
                let (kx, ky) = (k * th.cos(), k * th.sin());
                if !bounds.contains(kx, ky) || k > region.k_max {
                    continue;
                }
                let cell = spectrum.amplitude_variance(kx, ky, dk.0, dk.1);
                if cell < region.floor {
                    continue;
                }
                let density = cell / (dk.0 * dk.1);
                let area = k * (r1 - r0) * std::f64::consts::TAU / SAMPLE_ANGLES as f64;
                let w = density * area;
                if w > 0.0 && w.is_finite() {
                    ring.push((Component::new(kx, ky, 1.0, 0.0, depth), w));
                }
            }
            ring
        })
        .collect();
    rings.into_iter().flatten().unzip()
}

/// Draws from a discrete distribution by its cumulative weights: the first index whose
/// cumulative weight exceeds u·total, found from a guide table of where each of
/// `GUIDES` equal steps of u starts (a step or two instead of a binary search).
pub(super) struct Sampler {
    pub(super) cum: Vec<f64>,
    guide: Vec<usize>,
}

/// The guide table's steps of u.
pub(super) const GUIDES: usize = 8192;

impl Sampler {
    pub(super) fn new(w: &[f64]) -> Self {
        let mut acc = 0.0;
        let cum: Vec<f64> = w
            .iter()
            .map(|&x| {
                acc += x;
                acc
            })
            .collect();
        let total = cum.last().copied().unwrap_or(0.0);
        let guide = (0..GUIDES)
            .map(|b| {
                let x = b as f64 / GUIDES as f64 * total;
                cum.partition_point(|&c| c <= x)
            })
            .collect();
        Self { cum, guide }
    }

    /// The index of u ∈ [0, 1): the first whose cumulative weight exceeds u·total (the
    /// last index if none does).
    pub(super) fn pick(&self, u: f64) -> usize {
        let cum = &self.cum;
        let total = *cum.last().expect("a non-empty sample");
        let x = u * total;
        let b = ((u * GUIDES as f64) as usize).min(GUIDES - 1);
        // From the step's start: back while the one before also exceeds x (rounding of
        // the step's bound), then on while this one does not.
        let mut i = self.guide[b];
        while i > 0 && cum[i - 1] > x {
            i -= 1;
        }
        while i < cum.len() && cum[i] <= x {
            i += 1;
        }
        i.min(cum.len() - 1)
    }
}

/// Two uniform numbers in [0, 1) of draw `t` of stream `salt` (a fixed hash: the fit
/// depends on the spectrum only, not on the sea's seed).
pub(super) fn uniform(t: u64, salt: u64) -> (f64, f64) {
    let h = mix64(t.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ mix64(salt + 0x5151));
    let g = mix64(h ^ 0xd1b5_4a32_d192_ed03);
    let unit = |x: u64| (x >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
    (unit(h), unit(g))
}
