//! Slopes of a height field by central differences (one-sided at the edges of a
//! field that does not wrap around).

use rayon::prelude::*;

use crate::grid::Grid;

/// Slopes ∂h/∂x and ∂h/∂y of a field, per sample, row-major like the field.
#[derive(Debug, Clone, PartialEq)]
pub struct Slopes {
    pub dhdx: Vec<f32>,
    pub dhdy: Vec<f32>,
}

/// Central differences of `grid` at every sample: (h[i+1] − h[i−1])/(2·dx), wrapping
/// around when `periodic`, else one-sided `(h[1] − h[0])/dx` and `(h[n−1] − h[n−2])/dx` at
/// the edges; likewise along y.
pub fn slopes_central(grid: &Grid, periodic: bool) -> Slopes {
    let xs: Vec<usize> = (0..grid.spec.nx).collect();
    let ys: Vec<usize> = (0..grid.spec.ny).collect();
    slopes_at(grid, periodic, &xs, &ys)
}

/// The central differences of [`slopes_central`] at the samples `xs` × `ys` only (indices
/// taken modulo the grid size, so sample n is sample 0), row-major: `ys.len()` rows of
/// `xs.len()`. The same arithmetic on the same neighbours gives the same bits.
pub fn slopes_at(grid: &Grid, periodic: bool, xs: &[usize], ys: &[usize]) -> Slopes {
    let (nx, ny) = (grid.spec.nx, grid.spec.ny);
    let (dx, dy) = (grid.spec.dx_m(), grid.spec.dy_m());
    // The neighbours of index k along an axis of n, and the distance between them.
    let around = move |k: usize, n: usize, d: f64| -> (usize, usize, f64) {
        if periodic {
            ((k + n - 1) % n, (k + 1) % n, 2.0 * d)
        } else if k == 0 {
            (0, 1, d)
        } else if k == n - 1 {
            (n - 2, n - 1, d)
        } else {
            (k - 1, k + 1, 2.0 * d)
        }
    };
    let w = xs.len();
    let mut dhdx = vec![0.0f32; w * ys.len()];
    let mut dhdy = vec![0.0f32; w * ys.len()];
    dhdx.par_chunks_mut(w)
        .zip(dhdy.par_chunks_mut(w))
        .zip(ys)
        .for_each(|((sx, sy), &y)| {
            let j = y % ny;
            let (jm, jp, span_y) = around(j, ny, dy);
            let (row, below, above) = (grid.row(j), grid.row(jm), grid.row(jp));
            for (k, &x) in xs.iter().enumerate() {
                let i = x % nx;
                let (im, ip, span_x) = around(i, nx, dx);
                sx[k] = ((row[ip] as f64 - row[im] as f64) / span_x) as f32;
                sy[k] = ((above[i] as f64 - below[i] as f64) / span_y) as f32;
            }
        });
    Slopes { dhdx, dhdy }
}
