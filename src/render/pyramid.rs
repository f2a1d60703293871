//! Mip pyramids of a height field for ray casting.
//!
//! - **Mean levels** (the distance-dependent low-pass): level 0 holds the field's samples
//!   with their slopes (h, ∂h/∂x, ∂h/∂y); level l + 1 is level l filtered by the separable
//!   tent [1 2 1]/4 and decimated by 2, so sample i of level l + 1 sits exactly on sample
//!   2i of level l, at x = i·2^(l+1)·dx. The surface of level l, S_l(x, y), is the
//!   bilinear interpolation of its samples. Past the last level comes a virtual level:
//!   the flat plane at the field's mean height (what any level tends to).
//! - **Max levels** (Mastin's quadtree of maximum heights): node (i, j) of level l covers
//!   the level-0 cells i·2^l … (i+1)·2^l − 1 (and likewise in y) and stores an upper bound
//!   of every surface the tracer may intersect there: S_k for k ≤ l + 1 (the tracer blends
//!   S_L with S_L+1 and only tests nodes of level ≥ L). The root bounds the whole field.
//!
//! Cells: with `wrap` (a periodic field, sample N equals sample 0) there are nx × ny cells,
//! the last joining sample nx − 1 to sample 0; otherwise (nx − 1) × (ny − 1) cells cover
//! [0, (nx − 1)·dx] × [0, (ny − 1)·dy], and indices past an edge are clamped.
//!
//! Periodic levels halve while both sizes are even (a 1024² field has 11 levels, the last
//! 1×1); other fields halve while both sizes exceed 2 (n ↦ ⌈(n − 1)/2⌉ + 1 samples, so
//! level l + 1 still covers level l).

use rayon::prelude::*;

use crate::grid::Grid;

/// Height and slopes of one sample: (h, ∂h/∂x, ∂h/∂y), meters and m/m.
pub type Sample = [f32; 3];

/// One mean level: `nx` × `ny` samples, row-major.
pub struct Level {
    pub nx: usize,
    pub ny: usize,
    pub data: Vec<Sample>,
}

/// The mean and max pyramids of one field (see the module docs).
pub struct Pyramid {
    /// The field repeats (periodic indices) instead of ending at its edges.
    pub wrap: bool,
    /// Sample spacing of level 0, meters.
    pub dx_m: f64,
    pub dy_m: f64,
    /// Mean levels, level 0 first.
    pub mean: Vec<Level>,
    /// Mean height of the field: the surface beyond the last mean level, meters.
    pub mean_m: f64,
    /// Lowest height of the field: no surface the tracer sees goes below it, meters.
    pub min_m: f64,
    /// Level-0 cells along x and y.
    pub cells_x: usize,
    pub cells_y: usize,
    /// Max levels: (cells along x, cells along y, upper bounds row-major), level 0 first,
    /// the last one a single root node.
    pub max: Vec<(usize, usize, Vec<f32>)>,
}

/// Slopes of `grid` by central differences (one-sided at the edges unless `wrap`).
pub fn central_slopes(grid: &Grid, wrap: bool) -> (Vec<f32>, Vec<f32>) {
    let (nx, ny) = (grid.spec.nx, grid.spec.ny);
    let (dx, dy) = (grid.spec.dx_m(), grid.spec.dy_m());
    let neighbours = |i: usize, n: usize| -> (usize, usize, f64) {
        if n == 1 {
            (0, 0, 1.0)
        } else if i == 0 {
            if wrap { (n - 1, 1, 2.0) } else { (0, 1, 1.0) }
        } else if i == n - 1 {
            if wrap {
                (n - 2, 0, 2.0)
            } else {
                (n - 2, n - 1, 1.0)
            }
        } else {
            (i - 1, i + 1, 2.0)
        }
    };
    let mut sx = vec![0.0f32; nx * ny];
    let mut sy = vec![0.0f32; nx * ny];
    sx.par_chunks_mut(nx)
        .zip(sy.par_chunks_mut(nx))
        .enumerate()
        .for_each(|(j, (rx, ry))| {
            let (jm, jp, wy) = neighbours(j, ny);
            let (below, row, above) = (grid.row(jm), grid.row(j), grid.row(jp));
            let (sdx, sdy) = (1.0 / (2.0 * dx), 1.0 / (wy * dy));
            for i in 0..nx {
                let (im, ip, wx) = neighbours(i, nx);
                let sdx = if wx == 2.0 { sdx } else { 1.0 / dx };
                rx[i] = ((row[ip] as f64 - row[im] as f64) * sdx) as f32;
                ry[i] = ((above[i] as f64 - below[i] as f64) * sdy) as f32;
            }
        });
    (sx, sy)
}

/// Index `i` of a level with `n` samples: periodic, or clamped to the edges.
#[inline]
pub fn index(i: i64, n: usize, wrap: bool) -> usize {
    if wrap {
        i.rem_euclid(n as i64) as usize
    } else {
        i.clamp(0, n as i64 - 1) as usize
    }
}

/// One [1 2 1]/4 step with decimation of a line of `n` samples read through `at`.
fn tent_line(n_out: usize, n_in: usize, wrap: bool, at: impl Fn(usize) -> Sample) -> Vec<Sample> {
    (0..n_out)
        .map(|i| {
            let c = 2 * i as i64;
            let a = at(index(c - 1, n_in, wrap));
            let b = at(index(c, n_in, wrap));
            let d = at(index(c + 1, n_in, wrap));
            [0, 1, 2].map(|k| 0.25 * a[k] + 0.5 * b[k] + 0.25 * d[k])
        })
        .collect()
}

/// The index after `i` (< `n`): periodic, or held at the last sample.
#[inline]
pub fn next(i: usize, n: usize, wrap: bool) -> usize {
    if i + 1 < n {
        i + 1
    } else if wrap {
        0
    } else {
        n - 1
    }
}

impl Level {
    #[inline]
    pub fn at(&self, i: i64, j: i64, wrap: bool) -> Sample {
        self.data[index(j, self.ny, wrap) * self.nx + index(i, self.nx, wrap)]
    }

    /// The four corners (00, 10, 01, 11) of cell (i, j), i < nx and j < ny.
    #[inline]
    pub fn corners(&self, i: usize, j: usize, wrap: bool) -> [Sample; 4] {
        let (i1, j1) = (next(i, self.nx, wrap), next(j, self.ny, wrap));
        let (r0, r1) = (j * self.nx, j1 * self.nx);
        [
            self.data[r0 + i],
            self.data[r0 + i1],
            self.data[r1 + i],
            self.data[r1 + i1],
        ]
    }

    /// Largest height at the corners of each of the `cx` × `cy` cells: bounds of S.
    fn cell_maxima(&self, cx: usize, cy: usize, wrap: bool) -> Vec<f32> {
        let mut out = vec![0.0f32; cx * cy];
        out.par_chunks_mut(cx).enumerate().for_each(|(j, o)| {
            let j = j.min(self.ny - 1);
            let (r0, r1) = (
                &self.data[j * self.nx..(j + 1) * self.nx],
                &self.data[next(j, self.ny, wrap) * self.nx..][..self.nx],
            );
            for (i, m) in o.iter_mut().enumerate() {
                let i = i.min(self.nx - 1);
                let i1 = next(i, self.nx, wrap);
                *m = r0[i][0].max(r0[i1][0]).max(r1[i][0]).max(r1[i1][0]);
            }
        });
        out
    }

    /// The next coarser level, or `None` when this one cannot be halved.
    fn halve(&self, wrap: bool) -> Option<Level> {
        let next = |n: usize| -> Option<usize> {
            if wrap {
                (n % 2 == 0).then_some(n / 2)
            } else {
                (n > 2).then(|| (n - 1).div_ceil(2) + 1)
            }
        };
        let (nx, ny) = (next(self.nx)?, next(self.ny)?);
        if wrap && self.nx == 1 && self.ny == 1 {
            return None;
        }
        // Along x, every input row; then along y, every output row.
        let rows: Vec<Vec<Sample>> = (0..self.ny)
            .into_par_iter()
            .map(|j| {
                let row = &self.data[j * self.nx..(j + 1) * self.nx];
                tent_line(nx, self.nx, wrap, |i| row[i])
            })
            .collect();
        let data: Vec<Sample> = (0..ny)
            .into_par_iter()
            .flat_map_iter(|j| {
                let c = 2 * j as i64;
                let (a, b, d) = (
                    &rows[index(c - 1, self.ny, wrap)],
                    &rows[index(c, self.ny, wrap)],
                    &rows[index(c + 1, self.ny, wrap)],
                );
                (0..nx).map(move |i| {
                    [0, 1, 2].map(|k| 0.25 * a[i][k] + 0.5 * b[i][k] + 0.25 * d[i][k])
                })
            })
            .collect();
        Some(Level { nx, ny, data })
    }
}

impl Pyramid {
    /// Builds both pyramids of `grid` with its slopes `sx`, `sy` (∂h/∂x, ∂h/∂y, row-major
    /// like the grid). The grid needs at least 2 × 2 samples.
    pub fn new(grid: &Grid, sx: &[f32], sy: &[f32], wrap: bool) -> Pyramid {
        let (nx, ny) = (grid.spec.nx, grid.spec.ny);
        assert!(nx >= 2 && ny >= 2, "a surface needs at least 2 × 2 samples");
        assert!(
            sx.len() == nx * ny && sy.len() == nx * ny,
            "one slope per sample"
        );
        let base = Level {
            nx,
            ny,
            data: (0..nx * ny)
                .into_par_iter()
                .map(|k| [grid.data[k], sx[k], sy[k]])
                .collect(),
        };
        let mut mean = vec![base];
        while let Some(next) = mean.last().expect("level 0").halve(wrap) {
            mean.push(next);
        }
        let stats = grid.stats();
        let (mean_m, min_m) = (stats.mean_m, stats.min_m);
        let (cells_x, cells_y) = if wrap { (nx, ny) } else { (nx - 1, ny - 1) };
        let top = mean.len() - 1;
        let plane = mean_m as f32;
        let mut max: Vec<(usize, usize, Vec<f32>)> = Vec::new();
        // Cell maxima of the mean level l (and then l + 1) of the max level being built.
        let shape = |l: usize| {
            let s = 1usize << l.min(63);
            (cells_x.div_ceil(s), cells_y.div_ceil(s))
        };
        let maxima = |l: usize| -> Option<Vec<f32>> {
            let (cx, cy) = shape(l);
            (l <= top).then(|| mean[l].cell_maxima(cx, cy, wrap))
        };
        let mut this = maxima(0);
        let mut l = 0usize;
        loop {
            let (cx, cy) = shape(l);
            let above = maxima(l + 1);
            let (ax, _) = shape(l + 1);
            let below = max.last().map(|(bx, by, b)| (*bx, *by, b));
            let mut values = vec![0.0f32; cx * cy];
            values.par_chunks_mut(cx).enumerate().for_each(|(j, row)| {
                for (i, v) in row.iter_mut().enumerate() {
                    let mut m = if l >= top { plane } else { f32::NEG_INFINITY };
                    if let Some((bx, by, b)) = below {
                        for (ci, cj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                            let (ci, cj) = (2 * i + ci, 2 * j + cj);
                            if ci < bx && cj < by {
                                m = m.max(b[cj * bx + ci]);
                            }
                        }
                    }
                    if let Some(t) = &this {
                        m = m.max(t[j * cx + i]);
                    }
                    if let Some(a) = &above {
                        m = m.max(a[(j >> 1) * ax + (i >> 1)]);
                    }
                    *v = m;
                }
            });
            max.push((cx, cy, values));
            if cx == 1 && cy == 1 {
                break;
            }
            this = above;
            l += 1;
        }
        Pyramid {
            wrap,
            dx_m: grid.spec.dx_m(),
            dy_m: grid.spec.dy_m(),
            mean,
            mean_m,
            min_m,
            cells_x,
            cells_y,
            max,
        }
    }

    /// Index of the last mean level.
    pub fn top_mean(&self) -> usize {
        self.mean.len() - 1
    }

    /// Index of the root max level.
    pub fn top_max(&self) -> usize {
        self.max.len() - 1
    }

    /// An upper bound of every surface the tracer intersects.
    pub fn global_max(&self) -> f32 {
        self.max[self.top_max()].2[0]
    }

    /// Upper bound stored at node (i, j) of max level `l`.
    #[inline]
    pub fn node_max(&self, l: usize, i: usize, j: usize) -> f32 {
        let (cx, _, v) = &self.max[l];
        v[j * cx + i]
    }

    /// Sample (h, ∂h/∂x, ∂h/∂y) of the surface of mean level `l` at (x, y), by bilinear
    /// interpolation (`l` past the last level: the mean plane). Outside a non-periodic
    /// field the edge samples continue.
    pub fn surface(&self, l: usize, x_m: f64, y_m: f64) -> [f64; 3] {
        if l > self.top_mean() {
            return [self.mean_m, 0.0, 0.0];
        }
        let lv = &self.mean[l];
        let scale = (1u64 << l) as f64;
        let u = x_m / (self.dx_m * scale);
        let v = y_m / (self.dy_m * scale);
        let (i, j) = (u.floor(), v.floor());
        let (fu, fv) = (u - i, v - j);
        bilinear(
            [
                lv.at(i as i64, j as i64, self.wrap),
                lv.at(i as i64 + 1, j as i64, self.wrap),
                lv.at(i as i64, j as i64 + 1, self.wrap),
                lv.at(i as i64 + 1, j as i64 + 1, self.wrap),
            ]
            .map(widen),
            fu,
            fv,
        )
    }
}

/// A sample in f64.
#[inline]
pub fn widen(s: Sample) -> [f64; 3] {
    s.map(f64::from)
}

/// Bilinear interpolation of corners (00, 10, 01, 11) at (u, v) ∈ [0, 1]².
#[inline]
pub fn bilinear(c: [[f64; 3]; 4], u: f64, v: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| {
        let a = c[0][k] + (c[1][k] - c[0][k]) * u;
        let b = c[2][k] + (c[3][k] - c[2][k]) * u;
        a + (b - a) * v
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::GridSpec;

    fn field(nx: usize, ny: usize, f: impl Fn(usize, usize) -> f32) -> Grid {
        let spec = GridSpec::new(nx, ny, nx as f64 * 0.5, ny as f64 * 0.5);
        Grid::new(spec, (0..nx * ny).map(|k| f(k % nx, k / nx)).collect())
    }

    fn noise(i: usize, j: usize) -> f32 {
        let h = crate::rng::mix64((i as u64) << 32 | j as u64);
        (h >> 40) as f32 / (1u64 << 24) as f32 - 0.5
    }

    #[test]
    fn periodic_levels_halve_to_one_sample_holding_the_mean() {
        let g = field(16, 8, noise);
        let (sx, sy) = central_slopes(&g, true);
        let p = Pyramid::new(&g, &sx, &sy, true);
        let sizes: Vec<(usize, usize)> = p.mean.iter().map(|l| (l.nx, l.ny)).collect();
        assert_eq!(sizes, vec![(16, 8), (8, 4), (4, 2), (2, 1)]);
        // The tent filter keeps the mean of a periodic field (to f32 rounding).
        const MEAN_TOL: f64 = 1e-6;
        for (l, lv) in p.mean.iter().enumerate() {
            let m = lv.data.iter().map(|s| s[0] as f64).sum::<f64>() / lv.data.len() as f64;
            assert!(
                (m - p.mean_m).abs() < MEAN_TOL,
                "level {l}: mean {m} vs {}",
                p.mean_m
            );
        }
    }

    #[test]
    fn non_periodic_levels_keep_covering_the_field() {
        let g = field(10, 7, noise);
        let (sx, sy) = central_slopes(&g, false);
        let p = Pyramid::new(&g, &sx, &sy, false);
        for (l, lv) in p.mean.iter().enumerate() {
            let span = |n: usize| (n - 1) << l;
            assert!(
                span(lv.nx) >= 9 && span(lv.ny) >= 6,
                "level {l} is {}×{}",
                lv.nx,
                lv.ny
            );
        }
        assert_eq!((p.cells_x, p.cells_y), (9, 6));
        assert_eq!(p.max.last().map(|m| (m.0, m.1)), Some((1, 1)));
    }

    #[test]
    fn max_nodes_bound_every_surface_they_are_used_for() {
        for wrap in [true, false] {
            let g = field(32, 16, noise);
            let (sx, sy) = central_slopes(&g, wrap);
            let p = Pyramid::new(&g, &sx, &sy, wrap);
            // Sample S_k densely over each node of level l, for k ≤ l + 1.
            for l in 0..p.max.len() {
                let (cx, cy, _) = p.max[l];
                for j in 0..cy {
                    for i in 0..cx {
                        let bound = p.node_max(l, i, j) as f64;
                        let size = 1usize << l;
                        let x0 = (i * size) as f64 * p.dx_m;
                        let y0 = (j * size) as f64 * p.dy_m;
                        let w = (size.min(p.cells_x - i * size)) as f64 * p.dx_m;
                        let h = (size.min(p.cells_y - j * size)) as f64 * p.dy_m;
                        for k in 0..=(l + 1).min(p.top_mean() + 1) {
                            for a in 0..=8 {
                                for b in 0..=8 {
                                    let x = x0 + w * a as f64 / 8.0;
                                    let y = y0 + h * b as f64 / 8.0;
                                    let s = p.surface(k, x, y)[0];
                                    assert!(
                                        s <= bound + 1e-6,
                                        "wrap {wrap}, level {l} node ({i}, {j}): S_{k}({x}, {y}) = {s} > {bound}"
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn central_slopes_of_a_plane_are_exact() {
        let g = field(6, 5, |i, j| 0.3 * i as f32 * 0.5 - 0.2 * j as f32 * 0.5);
        let (sx, sy) = central_slopes(&g, false);
        const SLOPE_TOL: f32 = 1e-5;
        for k in 0..30 {
            assert!(
                (sx[k] - 0.3).abs() < SLOPE_TOL,
                "sample {k}: ∂h/∂x = {}",
                sx[k]
            );
            assert!(
                (sy[k] + 0.2).abs() < SLOPE_TOL,
                "sample {k}: ∂h/∂y = {}",
                sy[k]
            );
        }
    }
}
