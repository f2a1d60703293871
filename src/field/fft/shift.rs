//! Samples moved off the grid corners, for `--sample-at centers`: with the synthesis
//! h(x) = Σ_k h̃(k)·e^{ik·x}, the field sampled at x + s is the transform of
//! h̃(k)·e^{ik·s}. A phase factor on every amplitude moves all samples by s exactly (no
//! interpolation), and keeps the spectrum Hermitian (the factors of k and −k are
//! conjugate), so the field stays real. Slopes, displacement and the Jacobian, derived
//! from the same amplitudes, move with it.

use rayon::prelude::*;
use rustfft::num_complex::Complex;

use super::HalfSpectrum;
use crate::grid::{GridSpec, signed_index};

/// Multiplies the amplitudes of `half` by e^{i(kx·sx + ky·sy)} with s = (ox·dx, oy·dy),
/// `offset` = (ox, oy) in samples: its samples then sit at ((i + ox)·dx, (j + oy)·dy).
pub fn shift_samples(half: &mut HalfSpectrum, spec: &GridSpec, offset: [f64; 2]) {
    let (nx, ny) = (half.nx, half.ny);
    let tau = std::f64::consts::TAU;
    // kx·sx = 2π·n/Lx · o·Lx/nx = 2π·n·o/nx, and the same along y.
    debug_assert_eq!((nx, ny), (spec.nx, spec.ny));
    let ay: Vec<f64> = (0..ny)
        .map(|idx| tau * signed_index(idx, ny) as f64 * offset[1] / ny as f64)
        .collect();
    half.data
        .par_chunks_mut(ny)
        .enumerate()
        .for_each(|(n, line)| {
            let ax = tau * n as f64 * offset[0] / nx as f64;
            for (c, a) in line.iter_mut().zip(&ay) {
                let f = Complex::from_polar(1.0, ax + a);
                let v = Complex::new(c.re as f64, c.im as f64) * f;
                *c = Complex::new(v.re as f32, v.im as f32);
            }
        });
}
