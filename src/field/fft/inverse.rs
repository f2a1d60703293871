//! The inverse transform of a [`HalfSpectrum`]: complex inverse FFTs along y of the
//! N/2 + 1 kx lines (contiguous), then complex-to-real inverse FFTs along x of rows
//! gathered a block at a time (no transposed copy of the whole spectrum).

use std::mem::MaybeUninit;
use std::sync::Arc;

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner};
use rustfft::num_complex::Complex32;
use rustfft::{Fft, FftPlanner};

use super::HalfSpectrum;

/// A planned 2D inverse transform from a [`HalfSpectrum`] to a real N×M field.
pub struct InverseFft2 {
    nx: usize,
    ny: usize,
    columns: Arc<dyn Fft<f32>>,
    rows: Arc<dyn ComplexToReal<f32>>,
}

/// Lines per parallel task in the column pass, and rows per block in the transpose.
const LINES_PER_TASK: usize = 8;
const TRANSPOSE_BLOCK: usize = 32;

impl InverseFft2 {
    pub fn new(nx: usize, ny: usize) -> Self {
        let columns = FftPlanner::<f32>::new().plan_fft_inverse(ny);
        let rows = RealFftPlanner::<f32>::new().plan_fft_inverse(nx);
        Self {
            nx,
            ny,
            columns,
            rows,
        }
    }

    /// h(x) = Σ_k h̃(k)·e^{ik·x} on the grid. The spectrum is consumed (its buffer is
    /// transformed in place; the rows go through small per-task buffers).
    pub fn process(&self, half: HalfSpectrum) -> Vec<f32> {
        self.process_scaled(half, None)
    }

    /// [`process`](Self::process), every sample then multiplied by `scale` (the same
    /// product as scaling the returned field, done while each row is in the cache).
    pub fn process_scaled(&self, mut half: HalfSpectrum, scale: Option<f32>) -> Vec<f32> {
        self.columns(&mut half);
        self.rows_into_new(&half, None, scale)
    }

    /// [`process`](Self::process), and with it the field of the spectrum times a
    /// constant factor per kx line (`line_factor[n]` for line n: i·kx for ∂/∂x), which
    /// shares the transform along y: the factor is applied between the two passes.
    pub fn process_with_line_factor(
        &self,
        mut half: HalfSpectrum,
        line_factor: &[Complex32],
    ) -> (Vec<f32>, Vec<f32>) {
        assert_eq!(line_factor.len(), self.nx / 2 + 1, "one factor per kx line");
        self.columns(&mut half);
        let out = self.rows_into_new(&half, None, None);
        let scaled = self.rows_into_new(&half, Some(line_factor), None);
        (out, scaled)
    }

    /// The rows pass into a new field, whose memory is written once by [`rows`](Self::rows)
    /// and not zeroed first (a serial `memset` of the whole field where freed memory is
    /// reused).
    fn rows_into_new(
        &self,
        half: &HalfSpectrum,
        factor: Option<&[Complex32]>,
        scale: Option<f32>,
    ) -> Vec<f32> {
        let len = self.nx * self.ny;
        let mut out = Vec::with_capacity(len);
        self.rows(half, factor, scale, &mut out.spare_capacity_mut()[..len]);
        // SAFETY: `rows` initialized every element of the `len` it was given.
        unsafe { out.set_len(len) };
        out
    }

    /// 1. inverse FFT along y of every kx line, in place.
    fn columns(&self, half: &mut HalfSpectrum) {
        assert_eq!((half.nx, half.ny), (self.nx, self.ny), "plan/spectrum size");
        let scratch_len = self.columns.get_inplace_scratch_len();
        half.data
            .par_chunks_mut(self.ny * LINES_PER_TASK)
            .for_each_init(
                || vec![Complex32::new(0.0, 0.0); scratch_len],
                |scratch, chunk| self.columns.process_with_scratch(chunk, scratch),
            );
    }

    /// 2–3. complex-to-real inverse FFT along x of the column-transformed lines (each
    /// line n times `factor[n]` when given) into `out`, TRANSPOSE_BLOCK rows at a time:
    /// each task gathers its rows of constant y from the kx lines into a small buffer
    /// (no full transposed copy) and transforms them into the output. The DC bin (and
    /// the Nyquist bin for even N) of every row is real up to round-off because the
    /// spectrum is Hermitian (and every factor keeps it so).
    /// Each row is transformed into a row buffer in the cache, multiplied by `scale` when
    /// given, and copied out: every element of `out` is written once and never read, so
    /// `out` need not be initialized (no `memset` of the field first).
    fn rows(
        &self,
        half: &HalfSpectrum,
        factor: Option<&[Complex32]>,
        scale: Option<f32>,
        out: &mut [MaybeUninit<f32>],
    ) {
        let (nx, ny) = (self.nx, self.ny);
        let nh = nx / 2 + 1;
        let scratch_len = self.rows.get_scratch_len();
        let src = &half.data;
        out.par_chunks_mut(nx * TRANSPOSE_BLOCK)
            .enumerate()
            .for_each_init(
                || {
                    (
                        vec![Complex32::new(0.0, 0.0); nh * TRANSPOSE_BLOCK],
                        vec![Complex32::new(0.0, 0.0); scratch_len],
                        vec![0.0f32; nx],
                    )
                },
                |(block, scratch, row), (b, outs)| {
                    let j0 = b * TRANSPOSE_BLOCK;
                    let nrows = outs.len() / nx;
                    for n in 0..nh {
                        let col = &src[n * ny + j0..n * ny + j0 + nrows];
                        match factor {
                            None => {
                                for (jj, v) in col.iter().enumerate() {
                                    block[jj * nh + n] = *v;
                                }
                            }
                            Some(f) => {
                                let f = f[n];
                                for (jj, v) in col.iter().enumerate() {
                                    block[jj * nh + n] = *v * f;
                                }
                            }
                        }
                    }
                    for (input, output) in block.chunks_mut(nh).zip(outs.chunks_mut(nx)) {
                        input[0].im = 0.0;
                        if nx % 2 == 0 {
                            input[nh - 1].im = 0.0;
                        }
                        self.rows
                            .process_with_scratch(input, row, scratch)
                            .expect("buffer lengths come from the plan");
                        let pairs = output.iter_mut().zip(row.iter());
                        match scale {
                            Some(s) => pairs.for_each(|(o, &v)| _ = o.write(v * s)),
                            None => pairs.for_each(|(o, &v)| _ = o.write(v)),
                        }
                    }
                },
            );
    }
}
