//! The sampling grid and the height field stored on it.
//!
//! Axes are defined once, here: a grid has `nx` samples along x and `ny` along y,
//! covering `extent_x_m` × `extent_y_m` meters. Sample `(i, j)` sits at
//! `x = i·extent_x_m/nx`, `y = j·extent_y_m/ny`. Data is row-major: row `j` holds the
//! `nx` samples with `y = y_j`, so `data[j * nx + i]` is the height at `(x_i, y_j)`.
//! Every exporter writes rows in this order (row 0 is y = 0).

use rayon::prelude::*;

/// Size and extent of a regular grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridSpec {
    /// Samples along x (columns).
    pub nx: usize,
    /// Samples along y (rows).
    pub ny: usize,
    /// Length covered along x, in meters (the period of FFT fields).
    pub extent_x_m: f64,
    /// Length covered along y, in meters.
    pub extent_y_m: f64,
}

impl GridSpec {
    pub fn new(nx: usize, ny: usize, extent_x_m: f64, extent_y_m: f64) -> Self {
        Self {
            nx,
            ny,
            extent_x_m,
            extent_y_m,
        }
    }

    /// Sample spacing along x, in meters.
    pub fn dx_m(&self) -> f64 {
        self.extent_x_m / self.nx as f64
    }

    /// Sample spacing along y, in meters.
    pub fn dy_m(&self) -> f64 {
        self.extent_y_m / self.ny as f64
    }

    /// x coordinate of column `i`, in meters.
    pub fn x_m(&self, i: usize) -> f64 {
        i as f64 * self.dx_m()
    }

    /// y coordinate of row `j`, in meters.
    pub fn y_m(&self, j: usize) -> f64 {
        j as f64 * self.dy_m()
    }

    /// The wavevector of FFT indices (n, m), rad/m: 2π·(n/L_x, m/L_y).
    #[inline]
    pub fn wavevector(&self, n: i64, m: i64) -> (f64, f64) {
        let tau = 2.0 * std::f64::consts::PI;
        (
            tau * n as f64 / self.extent_x_m,
            tau * m as f64 / self.extent_y_m,
        )
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// True for a grid without samples (never produced by validated parameters).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A real field sampled on a [`GridSpec`], row-major (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    pub spec: GridSpec,
    pub data: Vec<f32>,
}

/// Summary statistics of a height field, in meters.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Stats {
    pub min_m: f64,
    pub max_m: f64,
    pub mean_m: f64,
    pub std_m: f64,
    /// Significant wave height estimate, 4·std.
    pub hs_m: f64,
}

impl Grid {
    pub fn new(spec: GridSpec, data: Vec<f32>) -> Self {
        assert_eq!(data.len(), spec.len(), "grid data length must be nx·ny");
        Self { spec, data }
    }

    pub fn zeros(spec: GridSpec) -> Self {
        Self::new(spec, vec![0.0; spec.len()])
    }

    /// Height at column `i`, row `j`.
    pub fn get(&self, i: usize, j: usize) -> f32 {
        self.data[j * self.spec.nx + i]
    }

    /// Row `j` (all samples with y = y_j).
    pub fn row(&self, j: usize) -> &[f32] {
        &self.data[j * self.spec.nx..(j + 1) * self.spec.nx]
    }

    /// Statistics of the field. Sums are formed per row in f64 and added in row order,
    /// so the result does not depend on the number of threads.
    pub fn stats(&self) -> Stats {
        Stats::of_rows(&self.data, self.spec.nx)
    }
}

impl Stats {
    /// Statistics of row-major samples with rows of `nx`: sums are formed per row in f64
    /// and added in row order, so the result does not depend on the number of threads.
    pub fn of_rows(data: &[f32], nx: usize) -> Stats {
        let rows: Vec<(f64, f32, f32)> = data
            .par_chunks(nx)
            .map(|row| {
                let mut s = 0.0f64;
                let mut lo = f32::INFINITY;
                let mut hi = f32::NEG_INFINITY;
                for &v in row {
                    s += v as f64;
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
                (s, lo, hi)
            })
            .collect();
        let n = data.len() as f64;
        let mean = rows.iter().map(|r| r.0).sum::<f64>() / n;
        let sq: Vec<f64> = data
            .par_chunks(nx)
            .map(|row| {
                row.iter()
                    .map(|&v| {
                        let d = v as f64 - mean;
                        d * d
                    })
                    .sum::<f64>()
            })
            .collect();
        let var = sq.iter().sum::<f64>() / n;
        let std = var.sqrt();
        Stats {
            min_m: rows.iter().map(|r| r.1).fold(f32::INFINITY, f32::min) as f64,
            max_m: rows.iter().map(|r| r.2).fold(f32::NEG_INFINITY, f32::max) as f64,
            mean_m: mean,
            std_m: std,
            hs_m: 4.0 * std,
        }
    }
}

/// Signed wavevector index of FFT bin `idx` of a transform of length `len`.
#[inline]
pub fn signed_index(idx: usize, len: usize) -> i64 {
    if idx < len.div_ceil(2) {
        idx as i64
    } else {
        idx as i64 - len as i64
    }
}

/// FFT bin of signed index `n` (|n| < `len`) of a transform of length `len`: the inverse
/// of [`signed_index`] (`n.rem_euclid(len)` without its division, for indices in hot
/// loops).
#[inline(always)]
pub fn bin_index(n: i64, len: usize) -> usize {
    debug_assert!(n.unsigned_abs() < len as u64);
    (if n < 0 { n + len as i64 } else { n }) as usize
}

/// True when the wavevector `(n, m)` takes part in the synthesis (DC and the Nyquist lines are left out: see `field::fft`).
#[inline]
pub fn is_resolved(n: i64, m: i64, nx: usize, ny: usize) -> bool {
    let nyquist_x = nx % 2 == 0 && n.unsigned_abs() as usize == nx / 2;
    let nyquist_y = ny % 2 == 0 && m.unsigned_abs() as usize == ny / 2;
    let dc = n == 0 && m == 0;
    !(dc || nyquist_x || nyquist_y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinates_follow_the_documented_axes() {
        let s = GridSpec::new(4, 2, 8.0, 3.0);
        assert_eq!(s.dx_m(), 2.0);
        assert_eq!(s.dy_m(), 1.5);
        assert_eq!(s.x_m(3), 6.0);
        assert_eq!(s.y_m(1), 1.5);
        let g = Grid::new(s, (0..8).map(|v| v as f32).collect());
        assert_eq!(g.get(1, 1), 5.0, "row-major: (i=1, j=1) is element 1·4+1");
        assert_eq!(g.row(1), &[4.0, 5.0, 6.0, 7.0]);
    }

    #[test]
    fn bin_index_is_rem_euclid_and_inverts_signed_index() {
        for len in [1usize, 2, 7, 8, 1536] {
            for n in 1 - len as i64..len as i64 {
                assert_eq!(
                    bin_index(n, len),
                    n.rem_euclid(len as i64) as usize,
                    "{n} of {len}"
                );
            }
            for idx in 0..len {
                assert_eq!(
                    bin_index(signed_index(idx, len), len),
                    idx,
                    "bin {idx} of {len}"
                );
            }
        }
    }

    #[test]
    fn stats_match_a_direct_computation() {
        let s = GridSpec::new(3, 2, 1.0, 1.0);
        let g = Grid::new(s, vec![1.0, 2.0, 3.0, 4.0, 5.0, 9.0]);
        let st = g.stats();
        let mean = 24.0 / 6.0;
        let var = [1.0f64, 2.0, 3.0, 4.0, 5.0, 9.0]
            .iter()
            .map(|v| (v - mean) * (v - mean))
            .sum::<f64>()
            / 6.0;
        assert_eq!(st.min_m, 1.0);
        assert_eq!(st.max_m, 9.0);
        assert!((st.mean_m - mean).abs() < 1e-12);
        assert!((st.std_m - var.sqrt()).abs() < 1e-12);
        assert!((st.hs_m - 4.0 * var.sqrt()).abs() < 1e-12);
    }
}
