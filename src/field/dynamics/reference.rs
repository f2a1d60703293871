//! The f64 Newton step of the choppy resampling before it moved to single precision: the
//! reference the tests solve each point with.

/// Below this det J a step is a fixed-point step instead of Newton's.
const NEWTON_MIN_DET: f64 = 0.05;

/// A sample index wrapped into 0..n (no division for the usual in-range values).
#[inline(always)]
fn wrap(i: i64, n: usize) -> usize {
    let n = n as i64;
    if (0..n).contains(&i) {
        i as usize
    } else {
        i.rem_euclid(n) as usize
    }
}

/// ⌊x⌋ for |x| < 2^52, without a library call.
#[inline(always)]
fn floor_i64(x: f64) -> i64 {
    let t = x as i64;
    t - ((t as f64) > x) as i64
}

/// Where a point falls in a periodic grid: the four corner offsets and the weights.
#[derive(Clone, Copy)]
pub(super) struct Cell {
    pub at: [usize; 4],
    pub tx: f64,
    pub ty: f64,
}

impl Cell {
    #[inline(always)]
    pub fn new(nx: usize, ny: usize, x: f64, y: f64) -> Self {
        let (fx, fy) = (floor_i64(x), floor_i64(y));
        let (tx, ty) = (x - fx as f64, y - fy as f64);
        let (i0, j0) = (wrap(fx, nx), wrap(fy, ny));
        let i1 = if i0 + 1 == nx { 0 } else { i0 + 1 };
        let j1 = if j0 + 1 == ny { 0 } else { j0 + 1 };
        Self {
            at: [j0 * nx + i0, j0 * nx + i1, j1 * nx + i0, j1 * nx + i1],
            tx,
            ty,
        }
    }

    /// Bilinear interpolation of `f` in this cell.
    #[inline(always)]
    pub fn of(&self, f: &[f32]) -> f64 {
        let v = self.at.map(|p| f[p] as f64);
        let a = v[0] + (v[1] - v[0]) * self.tx;
        let b = v[2] + (v[3] - v[2]) * self.tx;
        a + (b - a) * self.ty
    }
}

/// One step of the choppy resampling.
pub(super) struct Step {
    pub dx: f64,
    pub dy: f64,
    /// Whether it was Newton's step (else a fixed-point step).
    pub newton: bool,
    /// d(x0 − x)/dx = J⁻¹·(1, 0) − (1, 0) here (zero after a fixed-point step).
    pub slope: [f64; 2],
}

/// One step toward the root of F(x0) = x0 + λD(x0) − x, given x0 − x = (`ex`, `ey`) in
/// samples, with D interpolated bilinearly in `cell`: Newton's step J⁻¹F with the
/// gradient of the bilinear interpolant, or the plain fixed-point step F where
/// J = I + λ∇D is nearly singular or folded (det J < `NEWTON_MIN_DET`).
#[inline(always)]
pub(super) fn newton_step(cell: &Cell, d: &[[f32; 2]], ex: f64, ey: f64) -> Step {
    let v = cell.at.map(|p| d[p]);
    let (tx, ty) = (cell.tx, cell.ty);
    let mut value = [0.0; 2];
    let mut grad = [[0.0; 2]; 2];
    for c in 0..2 {
        let [v0, v1, v2, v3] = [v[0][c], v[1][c], v[2][c], v[3][c]].map(f64::from);
        let a = v0 + (v1 - v0) * tx;
        let b = v2 + (v3 - v2) * tx;
        value[c] = a + (b - a) * ty;
        grad[c] = [(v1 - v0) + ((v3 - v2) - (v1 - v0)) * ty, b - a];
    }
    let (fx, fy) = (ex + value[0], ey + value[1]);
    let (j00, j01, j10, j11) = (1.0 + grad[0][0], grad[0][1], grad[1][0], 1.0 + grad[1][1]);
    let det = j00 * j11 - j01 * j10;
    if det < NEWTON_MIN_DET {
        return Step {
            dx: fx,
            dy: fy,
            newton: false,
            slope: [0.0; 2],
        };
    }
    let inv = 1.0 / det;
    Step {
        dx: (j11 * fx - j01 * fy) * inv,
        dy: (j00 * fy - j10 * fx) * inv,
        newton: true,
        slope: [j11 * inv - 1.0, -j10 * inv],
    }
}

/// The f64 resampling the single-precision kernel replaced (four segments per row, the
/// same predictor and stopping rule): for measuring how far the heights moved.
pub(super) fn resample_choppy_f64(h: &[f32], d: &[[f32; 2]], nx: usize, ny: usize) -> Vec<f32> {
    const LANES: usize = 4;
    let seg = nx.div_ceil(LANES);
    let mut out = vec![0.0f32; nx * ny];
    for (j, row) in out.chunks_mut(nx).enumerate() {
        let y = j as f64;
        for l in 0..LANES {
            let (mut e, mut slope) = ([0.0f64; 2], [0.0f64; 2]);
            for i in l * seg..((l + 1) * seg).min(nx) {
                e = if i == l * seg {
                    let [u, v] = d[j * nx + i];
                    [-(u as f64), -(v as f64)]
                } else {
                    [e[0] + slope[0], e[1] + slope[1]]
                };
                for _ in 0..super::CHOPPY_ITERATIONS {
                    let cell = Cell::new(nx, ny, i as f64 + e[0], y + e[1]);
                    let s = newton_step(&cell, d, e[0], e[1]);
                    e = [e[0] - s.dx, e[1] - s.dy];
                    slope = s.slope;
                    let limit = if s.newton { 1e-3 } else { 1e-4 };
                    if s.dx.abs().max(s.dy.abs()) < limit {
                        break;
                    }
                }
                row[i] = Cell::new(nx, ny, i as f64 + e[0], y + e[1]).of(h) as f32;
            }
        }
    }
    out
}
