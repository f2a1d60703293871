//! The padded grid of the fitted method's transforms: its size on each axis (the reach
//! of the paired waves), the arrays reused within a frame, and its 2D transforms.

use std::sync::Arc;

use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::num_traits::Zero;
use rustfft::{Fft, FftNum, FftPlanner};

use super::super::resolved_span;

/// The smallest even length ≥ n with no prime factor above 5 (a fast transform).
fn smooth_even(n: usize) -> usize {
    let smooth = |mut v: usize| {
        for p in [2, 3, 5] {
            while v % p == 0 {
                v /= p;
            }
        }
        v == 1
    };
    let mut v = n.max(2);
    while v % 2 == 1 || !smooth(v) {
        v += 1;
    }
    v
}

/// The reach of one axis of the paired waves: their largest |index| k, the outputs kept
/// (|index| ≤ o, o = min(2k, the grid's last resolved index)), and the padded length,
/// above 2k + o, so that no sum or difference of two waves (|index| ≤ 2k) wraps onto a
/// kept output (3/2 of the grid when the waves fill it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Reach {
    pub(super) k: i64,
    pub(super) o: i64,
    pub(super) len: usize,
}

impl Reach {
    pub(super) fn of(k: i64, grid: usize) -> Self {
        let hi = resolved_span(grid).1;
        let o = (2 * k).min(hi);
        Self {
            k,
            o,
            len: smooth_even((2 * k + o + 1) as usize),
        }
    }

    /// Every sum and difference of two waves lands on the grid.
    pub(super) fn all_on_grid(&self) -> bool {
        self.o == 2 * self.k
    }

    /// The box edge (rad/m) of indices ≤ `i` on an axis of cell `dk`, or the grid's own
    /// edge `grid_max` when they reach the grid's last resolved index.
    pub(super) fn edge(&self, i: i64, dk: f64, grid_max: f64, grid: usize) -> f64 {
        if i >= resolved_span(grid).1 {
            grid_max
        } else {
            (i as f64 + 0.5) * dk
        }
    }
}

/// Padded arrays given back for reuse (fresh large allocations each cost their page
/// faults).
pub(super) struct Pool<T>(std::sync::Mutex<Vec<Vec<Complex<T>>>>);

impl<T> Default for Pool<T> {
    fn default() -> Self {
        Self(std::sync::Mutex::new(Vec::new()))
    }
}

impl<T: FftNum> Pool<T> {
    /// An array of `len` zeros.
    pub(super) fn take(&self, len: usize) -> Vec<Complex<T>> {
        let mut v = self.take_any(len);
        v.fill(Complex::zero());
        v
    }

    /// An array of `len` whose values the caller overwrites (a reused one keeps its old
    /// values).
    pub(super) fn take_any(&self, len: usize) -> Vec<Complex<T>> {
        let reused = self
            .0
            .lock()
            .expect("no panics while holding the lock")
            .pop();
        let mut v = reused.unwrap_or_default();
        v.resize(len, Complex::zero());
        v
    }

    pub(super) fn give(&self, v: Vec<Complex<T>>) {
        self.0
            .lock()
            .expect("no panics while holding the lock")
            .push(v);
    }

    pub(super) fn give_all(&self, vs: impl IntoIterator<Item = Vec<Complex<T>>>) {
        for v in vs {
            self.give(v);
        }
    }

    /// Frees the arrays given back.
    pub(super) fn clear(&self) {
        self.0
            .lock()
            .expect("no panics while holding the lock")
            .clear();
    }
}

/// 2D transforms of a px × py grid (rows of py).
pub(super) struct Plan<T> {
    pub(super) px: usize,
    pub(super) py: usize,
    pub(super) inv_x: Arc<dyn Fft<T>>,
    pub(super) inv_y: Arc<dyn Fft<T>>,
    fwd_x: Arc<dyn Fft<T>>,
    fwd_y: Arc<dyn Fft<T>>,
}

impl<T: FftNum> Plan<T> {
    pub(super) fn new(px: usize, py: usize) -> Self {
        let mut p = FftPlanner::new();
        Self {
            px,
            py,
            inv_x: p.plan_fft_inverse(px),
            inv_y: p.plan_fft_inverse(py),
            fwd_x: p.plan_fft_forward(px),
            fwd_y: p.plan_fft_forward(py),
        }
    }

    /// Rows of `b` transformed by `fb` (rows of zeros stay zero), transposed, the rows of
    /// `a` transformed by `fa`: `data` (a rows of b) becomes b rows of a.
    fn two_d(
        data: &mut Vec<Complex<T>>,
        (a, b): (usize, usize),
        (fa, fb): (&dyn Fft<T>, &dyn Fft<T>),
        pool: &Pool<T>,
    ) {
        let zero = Complex::zero();
        data.par_chunks_mut(b).for_each(|row| {
            if row.iter().any(|v| *v != zero) {
                fb.process(row);
            }
        });
        let src = &*data;
        let mut t = pool.take_any(a * b);
        // Blocked: each task writes TILE rows of t, reading TILE consecutive values of
        // every row of `data`.
        const TILE: usize = 8;
        t.par_chunks_mut(a * TILE)
            .enumerate()
            .for_each(|(c, rows)| {
                let j0 = c * TILE;
                let tile = rows.len() / a;
                for i in 0..a {
                    let from = &src[i * b + j0..i * b + j0 + tile];
                    for (jj, &v) in from.iter().enumerate() {
                        rows[jj * a + i] = v;
                    }
                }
            });
        t.par_chunks_mut(a).for_each(|row| fa.process(row));
        pool.give(std::mem::replace(data, t));
    }

    /// Spectrum (px rows of py, kx by row) → field (py rows of px, y by row).
    pub(super) fn inverse(&self, data: &mut Vec<Complex<T>>, pool: &Pool<T>) {
        let (fa, fb) = (&*self.inv_x, &*self.inv_y);
        Self::two_d(data, (self.px, self.py), (fa, fb), pool);
    }

    /// Field (py rows of px) → spectrum (px rows of py).
    pub(super) fn forward(&self, data: &mut Vec<Complex<T>>, pool: &Pool<T>) {
        let (fa, fb) = (&*self.fwd_y, &*self.fwd_x);
        Self::two_d(data, (self.py, self.px), (fa, fb), pool);
    }

    /// The forward transform along x of one row of px (`scratch` its scratch).
    pub(super) fn forward_x(&self, row: &mut [Complex<T>], scratch: &mut Vec<Complex<T>>) {
        scratch.resize(self.fwd_x.get_inplace_scratch_len(), Complex::zero());
        self.fwd_x.process_with_scratch(row, scratch);
    }

    /// The forward transform along y (py values).
    pub(super) fn forward_y(&self) -> &dyn Fft<T> {
        &*self.fwd_y
    }
}
