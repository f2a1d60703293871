//! The difference terms at the outputs nearest q = 0, by their pairs (finite depth).
//!
//! There the fitted difference basis (δ²/T)^m / T grows as T(|q|)^−(m+1), while the
//! products' transforms hold those outputs as a small remainder of much larger sums: the
//! output coefficients multiply the accumulators' rounding. At 19 m, a relative change of
//! 10⁻¹² in the accumulators moved the outputs of the first ring (|q| = Δk) by their own
//! size over 2048 m, and at 4096 and 8192 m the rounding alone did (the sea's Hs 9.0 m
//! instead of the pair sum's 5.4 m). The change fell below 10⁻⁶ of an output from
//! T(|q|) ≈ 0.06 s_p² on at 10, 19 and 40 m over 2048 to 8192 m. So where T(|q|) ≤
//! [`EXACT_T`]·s_p² the difference term is the pair sum itself: output q has at most one
//! partner j for each wave i (k_j = k_i − q), M pairs an output. At q = 0 that sum is
//! the set-down of each wave. In deep water the fitted outputs keep their accuracy down
//! to the first ring (0.59 % rms against the pair sum at 8192 m, measured), and only
//! q = 0 is exact (the set-down, 0).

use rayon::prelude::*;

use super::super::{C64, kernel_minus_at};
use super::Wave;
use super::grid::Reach;
use super::outputs::output_t;
use crate::grid::GridSpec;

/// T(|q|) / s_p² at or below which a finite-depth difference output is its pair sum.
pub(super) const EXACT_T: f64 = 0.1;

/// The waves [`Exact::values`] reads at a time for a share of the outputs.
pub(super) const WAVE_BLOCK: usize = 2048;

/// The outputs whose difference term is the pair sum, and where the waves lie.
pub(super) struct Exact {
    /// T at or below which an output is exact: [`EXACT_T`]·s_p², 0 in deep water (q = 0).
    pub(super) t_max: f64,
    /// The set-down Σ |b_i|² K⁻_ii = Σ 4ρ_i² K⁻_ii, the exact value at q = 0 (the same at
    /// every time).
    setdown: f64,
    /// The exact outputs kept (n ≥ 0, m): n, m, T.
    outputs: Vec<(i64, i64, f64)>,
    /// The index of the wave at (n, m) of the waves' box |n| ≤ k_x, |m| ≤ k_y (row
    /// n + k_x of 2k_y + 1), `u32::MAX` where there is none; empty in deep water.
    at: Vec<u32>,
    k: (i64, i64),
}

impl Exact {
    /// The exact outputs among those kept (|n|, |m| ≤ o of `reach`) of a grid `spec` at
    /// `depth`, s_p = `s_ref`, the index of the waves `comps` (within k of `reach`), and
    /// their set-down.
    pub(super) fn new(
        comps: &[Wave],
        reach: (Reach, Reach),
        (spec, depth): (GridSpec, Option<f64>),
        (s_ref, setdown): (f64, f64),
    ) -> Self {
        let (kx, ky) = (reach.0.k, reach.1.k);
        let t_max = match depth {
            Some(_) => EXACT_T * s_ref * s_ref,
            None => 0.0,
        };
        // T grows with |q|: the outputs within the last n (and m) on an axis within it.
        let t_of = |n, m| output_t(spec, depth, n, m).3;
        let last = |along: &dyn Fn(i64) -> f64, o: i64| {
            (0..=o)
                .take_while(|&i| along(i) <= t_max)
                .last()
                .unwrap_or(0)
        };
        let nx = last(&|n| t_of(n, 0), reach.0.o);
        let ny = last(&|m| t_of(0, m), reach.1.o);
        let mut outputs = Vec::new();
        for n in 0..=nx {
            for m in -ny..=ny {
                let t = t_of(n, m);
                if t <= t_max {
                    outputs.push((n, m, t));
                }
            }
        }
        let mut at = Vec::new();
        if depth.is_some() {
            let w = (2 * ky + 1) as usize;
            at = vec![u32::MAX; (2 * kx + 1) as usize * w];
            for (i, c) in comps.iter().enumerate() {
                let (n, m) = (i64::from(c.n) + kx, i64::from(c.m) + ky);
                at[n as usize * w + m as usize] = u32::try_from(i).expect("fewer waves than 2³²");
            }
        }
        Self {
            t_max,
            setdown,
            outputs,
            at,
            k: (kx, ky),
        }
    }

    /// The wave at (n, m), if any.
    #[inline]
    fn wave(&self, n: i64, m: i64) -> Option<usize> {
        let (kx, ky) = self.k;
        if n.abs() > kx || m.abs() > ky {
            return None;
        }
        let w = (2 * ky + 1) as usize;
        let i = self.at[(n + kx) as usize * w + (m + ky) as usize];
        (i != u32::MAX).then_some(i as usize)
    }

    /// The exact difference term at each exact output, (n, m, value) with the half
    /// spectrum's weight: Σ over the ordered pairs (i, j) of k_i − k_j = q of
    /// b_i conj(b_j) K⁻_ij, and at q = 0 the set-down Σ |b_i|² K⁻_ii (held). Each
    /// output's sum in the waves' order (the same bits at any thread count). The waves are
    /// read a block at a time for a share of the outputs (each output's partners lie
    /// within its |q| of the wave, near it in the waves' order by kx row), so that they
    /// are read from memory once a share and not once an output: over long extents the
    /// exact outputs are many (their |q| is set by the depth, their count by the extent²).
    pub(super) fn values(&self, comps: &[Wave], b: &[C64], spec: GridSpec) -> Vec<(i64, i64, C64)> {
        let setdown = (0, 0, C64::new(self.setdown, 0.0));
        if self.at.is_empty() {
            // Deep water: the exact output is q = 0 alone, its set-down held (no pairs).
            debug_assert!(self.outputs.iter().all(|o| (o.0, o.1) == (0, 0)));
            return vec![setdown; self.outputs.len()];
        }
        // Each wave's input to the kernel, once (not twice a pair).
        let inputs: Vec<[f64; 5]> = comps
            .par_iter()
            .map(|c| {
                let (kx, ky) = c.k(spec);
                [kx, ky, c.s * c.s, c.s, c.q]
            })
            .collect();
        let zero = C64::new(0.0, 0.0);
        let mut sums = vec![zero; self.outputs.len()];
        let share = self
            .outputs
            .len()
            .div_ceil(2 * rayon::current_num_threads())
            .max(1);
        sums.par_chunks_mut(share)
            .zip(self.outputs.par_chunks(share))
            .for_each(|(sums, outputs)| {
                for (block, i0) in comps.chunks(WAVE_BLOCK).zip((0..).step_by(WAVE_BLOCK)) {
                    for (sum, &(n, m, t)) in sums.iter_mut().zip(outputs) {
                        if n == 0 && m == 0 {
                            continue;
                        }
                        for (i, c) in (i0..).zip(block) {
                            let Some(j) = self.wave(i64::from(c.n) - n, i64::from(c.m) - m) else {
                                continue;
                            };
                            let k = kernel_minus_at(inputs[i], inputs[j], t);
                            *sum += b[i] * b[j].conj() * k;
                        }
                    }
                }
            });
        self.outputs
            .iter()
            .zip(sums)
            .map(|(&(n, m, _), sum)| match (n, m) {
                (0, 0) => setdown,
                _ => (n, m, sum),
            })
            .collect()
    }
}
