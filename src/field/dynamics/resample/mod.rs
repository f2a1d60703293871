//! The choppy resampling: the height of the displaced surface (x0 + λD(x0), h(x0)) at each
//! grid point (see the docs of [`super`]).
//!
//! Single precision, with the unknown kept as x0 = (i + ex, j + ey): a grid point's integer
//! index plus a small offset e = x0 − x, so the precision does not depend on the grid's
//! size (the cell of x0 and the weights in it are the exact integer and fractional parts
//! of e). Each row is cut into [`LANES`] segments solved independently, each point of a
//! segment starting from its left neighbour's solution; the vector kernel (`avx2`) solves
//! the sixteen segments side by side, one lane each, a lane that has converged keeping its
//! value while the others step on. It performs the scalar kernel's IEEE operations in the
//! same order, without fused multiply–add, so both give the same bits.

#[cfg(target_arch = "x86_64")]
mod avx2;

use rayon::prelude::*;

use crate::grid::GridSpec;
use crate::simd::Isa;

/// Segments per row, solved side by side (two vectors of eight).
pub(super) const LANES: usize = 16;
/// Largest number of steps toward one point's x0.
pub const CHOPPY_ITERATIONS: usize = 8;
/// Below this det J a step is a fixed-point step instead of Newton's (where the surface
/// nearly folds, Newton's step is unbounded).
const NEWTON_MIN_DET: f32 = 0.05;
/// A fixed-point step shorter than this along both axes, in samples, ends the point's
/// solve (a height error below 1e-4·dx·|slope|) …
const FIXED_POINT_CONVERGED: f32 = 1e-4;
/// … and so does a Newton step shorter than this: Newton converges quadratically, so the
/// point is then within ~(|∇J|/2)·(1e-3)² ≪ 1e-4 samples of the root …
const NEWTON_CONVERGED: f32 = 1e-3;
/// … or a Newton step of any length that stays in its cell, where the interpolant is
/// bilinear: F(x0 − s) = F(x0) − J s + τ sx sy exactly (τ: the cell's twist, the
/// coefficient of tx·ty), so after the step the point is J⁻¹τ sx sy from the root, which
/// must be below this many samples (bounded by (|τx| + |τy|)·|sx sy|·Σ|Jij| / det J).
const NEWTON_RESIDUAL: f32 = 1e-5;

/// λD in samples, x and y side by side (one load per corner), on the periodic grid
/// padded with one more column and row (copies of the first), so a cell's corners are
/// always p, p + 1, p + w, p + w + 1 (w = nx + 1); and the heights, unpadded.
pub(super) struct Table<'a> {
    pub nx: usize,
    pub ny: usize,
    pub d: &'a [[f32; 2]],
    pub h: &'a [f32],
}

/// The height of the displaced surface at every grid point; `displacement` is λD in
/// meters.
pub fn resample_choppy(h: &[f32], displacement: &[Vec<f32>; 2], spec: &GridSpec) -> Vec<f32> {
    resample_choppy_on(Isa::detect(), h, displacement, spec)
}

/// [`resample_choppy`] with the kernel of `isa` (every one gives the same bits).
pub(crate) fn resample_choppy_on(
    isa: Isa,
    h: &[f32],
    displacement: &[Vec<f32>; 2],
    spec: &GridSpec,
) -> Vec<f32> {
    let (nx, ny) = (spec.nx, spec.ny);
    let d = padded_samples(displacement, spec);
    let table = Table {
        nx,
        ny,
        d: &d,
        h: &h[..nx * ny],
    };
    let mut out = vec![0.0f32; nx * ny];
    // The vector kernel's gathers take 32-bit indices.
    let vector = isa != Isa::Plain && (nx + 1) * (ny + 1) <= i32::MAX as usize;
    out.par_chunks_mut(nx).enumerate().for_each(|(j, row)| {
        #[cfg(target_arch = "x86_64")]
        if vector {
            // SAFETY: every Isa other than Plain has AVX2; the padded grid has fewer than
            // 2^31 points.
            unsafe { avx2::row(&table, j, row) };
            return;
        }
        let _ = vector;
        row_scalar(&table, j, row);
    });
    out
}

/// λD in samples, padded (see [`Table`]).
fn padded_samples(displacement: &[Vec<f32>; 2], spec: &GridSpec) -> Vec<[f32; 2]> {
    let (nx, ny) = (spec.nx, spec.ny);
    let (sx, sy) = ((1.0 / spec.dx_m()) as f32, (1.0 / spec.dy_m()) as f32);
    let mut d = vec![[0.0f32; 2]; (nx + 1) * (ny + 1)];
    d.par_chunks_mut(nx + 1).enumerate().for_each(|(y, out)| {
        let r = (y % ny) * nx..(y % ny + 1) * nx;
        let (u, v) = (&displacement[0][r.clone()], &displacement[1][r]);
        for (o, (&u, &v)) in out.iter_mut().zip(u.iter().zip(v)) {
            *o = [u * sx, v * sy];
        }
        out[nx] = out[0];
    });
    d
}

/// The length of each of a row's [`LANES`] segments (the last may be shorter, or empty).
#[inline(always)]
pub(super) fn segment_length(nx: usize) -> usize {
    nx.div_ceil(LANES)
}

/// One row, segment after segment.
fn row_scalar(t: &Table, j: usize, row: &mut [f32]) {
    let seg = segment_length(t.nx);
    for l in 0..LANES {
        let start = l * seg;
        let end = (start + seg).min(t.nx);
        let (mut ex, mut ey) = (0.0f32, 0.0f32);
        let mut slope = [0.0f32; 2];
        for (i, out) in row.iter_mut().enumerate().take(end).skip(start) {
            if i == start {
                // The displacement at the grid point itself.
                let [u, v] = t.d[j * (t.nx + 1) + i];
                (ex, ey) = (-u, -v);
            } else {
                // The left neighbour's solution, moved by one sample through J⁻¹ there.
                (ex, ey) = (ex + slope[0], ey + slope[1]);
            }
            for _ in 0..CHOPPY_ITERATIONS {
                let s = step(t, i, j, ex, ey);
                (ex, ey) = (s.ex, s.ey);
                slope = s.slope;
                if s.converged {
                    break;
                }
            }
            *out = height(t, i, j, ex, ey);
        }
    }
}

/// ⌊x⌋ as an integer (i32::MIN where it is not one, as the vector conversion gives) and
/// x − ⌊x⌋, both exact.
#[inline(always)]
pub(super) fn split(x: f32) -> (i32, f32) {
    let f = x.floor();
    let i = if (-2147483648.0..2147483648.0).contains(&f) {
        f as i32
    } else {
        i32::MIN
    };
    (i, x - f)
}

/// An index wrapped into 0..n.
#[inline(always)]
pub(super) fn wrap(c: i32, n: i32) -> i32 {
    if (0..n).contains(&c) {
        c
    } else {
        c.rem_euclid(n)
    }
}

/// The cell of the periodic grid that holds (i + ex, j + ey): its first corner (x0, y0)
/// and the weights.
#[inline(always)]
fn locate(nx: usize, ny: usize, i: usize, j: usize, ex: f32, ey: f32) -> (usize, usize, f32, f32) {
    let (fx, tx) = split(ex);
    let (fy, ty) = split(ey);
    let x0 = wrap((i as i32).wrapping_add(fx), nx as i32);
    let y0 = wrap((j as i32).wrapping_add(fy), ny as i32);
    (x0 as usize, y0 as usize, tx, ty)
}

/// The height at (i + ex, j + ey), interpolated bilinearly.
#[inline(always)]
fn height(t: &Table, i: usize, j: usize, ex: f32, ey: f32) -> f32 {
    let (x0, y0, tx, ty) = locate(t.nx, t.ny, i, j, ex, ey);
    let x1 = if x0 + 1 == t.nx { 0 } else { x0 + 1 };
    let y1 = if y0 + 1 == t.ny { 0 } else { y0 + 1 };
    let (r0, r1) = (y0 * t.nx, y1 * t.nx);
    let h = [t.h[r0 + x0], t.h[r0 + x1], t.h[r1 + x0], t.h[r1 + x1]];
    let a = h[0] + (h[1] - h[0]) * tx;
    let b = h[2] + (h[3] - h[2]) * tx;
    a + (b - a) * ty
}

/// One step of a point's solve.
pub(super) struct Step {
    /// The new x0 − x.
    pub ex: f32,
    pub ey: f32,
    /// d(x0 − x)/dx = J⁻¹·(1, 0) − (1, 0) at the last Newton iterate: how the solution
    /// moves from one grid point to the next along x (zero after a fixed-point step).
    pub slope: [f32; 2],
    /// Whether the step ends the solve.
    pub converged: bool,
}

/// The bilinear interpolant of one component of λD in a cell: its corner value `v0`, its
/// differences along x on the cell's two rows, and its value at the first corner of the
/// second row.
#[derive(Clone, Copy)]
struct Patch {
    v0: f32,
    v2: f32,
    d01: f32,
    d23: f32,
    /// d23 − d01: the coefficient of tx·ty.
    twist: f32,
}

impl Patch {
    #[inline(always)]
    fn new(v0: f32, v1: f32, v2: f32, v3: f32) -> Self {
        let (d01, d23) = (v1 - v0, v3 - v2);
        Self {
            v0,
            v2,
            d01,
            d23,
            twist: d23 - d01,
        }
    }

    /// The value and the gradient at (tx, ty).
    #[inline(always)]
    fn at(&self, tx: f32, ty: f32) -> (f32, [f32; 2]) {
        let a = self.v0 + self.d01 * tx;
        let b = self.v2 + self.d23 * tx;
        let ba = b - a;
        (a + ba * ty, [self.d01 + self.twist * ty, ba])
    }
}

/// Newton's step at (tx, ty) of a cell with offset e: J = I + ∇λD, det J, the step J⁻¹F
/// and the slope J⁻¹(1, 0) − (1, 0); None where det J < [`NEWTON_MIN_DET`].
struct Newton {
    f: [f32; 2],
    norm: f32,
    det: f32,
    step: [f32; 2],
    slope: [f32; 2],
    newton: bool,
}

#[inline(always)]
fn newton(p: &[Patch; 2], tx: f32, ty: f32, ex: f32, ey: f32) -> Newton {
    let (vx, gx) = p[0].at(tx, ty);
    let (vy, gy) = p[1].at(tx, ty);
    let (fx, fy) = (ex + vx, ey + vy);
    let (j00, j01, j10, j11) = (1.0 + gx[0], gx[1], gy[0], 1.0 + gy[1]);
    let det = j00 * j11 - j01 * j10;
    let inv = 1.0 / det;
    Newton {
        f: [fx, fy],
        norm: ((j00.abs() + j01.abs()) + j10.abs()) + j11.abs(),
        det,
        step: [(j11 * fx - j01 * fy) * inv, (j00 * fy - j10 * fx) * inv],
        slope: [j11 * inv - 1.0, -j10 * inv],
        newton: det >= NEWTON_MIN_DET,
    }
}

/// 0 ≤ x < 1.
#[inline(always)]
fn in_unit(x: f32) -> bool {
    (0.0..1.0).contains(&x)
}

/// Whether Newton's step `n` from (tx, ty) ends the solve: it is short, or it stays in
/// the cell and leaves the point within [`NEWTON_RESIDUAL`] of the root.
#[inline(always)]
fn newton_done(p: &[Patch; 2], n: &Newton, tx: f32, ty: f32) -> bool {
    let [dx, dy] = n.step;
    let short = dx.abs() < NEWTON_CONVERGED && dy.abs() < NEWTON_CONVERGED;
    let inside = in_unit(tx - dx) && in_unit(ty - dy);
    let residual = (p[0].twist.abs() + p[1].twist.abs()) * (dx * dy).abs();
    short || (inside && residual * n.norm < NEWTON_RESIDUAL * n.det)
}

/// One step toward the root of F(x0) = x0 + λD(x0) − x from x0 = (i + ex, j + ey), with λD
/// interpolated bilinearly: Newton's step J⁻¹F with the interpolant's own gradient, and
/// where it stays in the cell a second Newton step on the same cell's interpolant (no new
/// loads); or the fixed-point step F where J = I + λ∇D is nearly singular or folded.
#[inline(always)]
pub(super) fn step(t: &Table, i: usize, j: usize, ex: f32, ey: f32) -> Step {
    let (x0, y0, tx, ty) = locate(t.nx, t.ny, i, j, ex, ey);
    let w = t.nx + 1;
    let p = y0 * w + x0;
    let v = [t.d[p], t.d[p + 1], t.d[p + w], t.d[p + w + 1]];
    let patch = [0, 1].map(|c| Patch::new(v[0][c], v[1][c], v[2][c], v[3][c]));
    let first = newton(&patch, tx, ty, ex, ey);
    if !first.newton {
        let [fx, fy] = first.f;
        return Step {
            ex: ex - fx,
            ey: ey - fy,
            slope: [0.0; 2],
            converged: fx.abs() < FIXED_POINT_CONVERGED && fy.abs() < FIXED_POINT_CONVERGED,
        };
    }
    let (ex1, ey1) = (ex - first.step[0], ey - first.step[1]);
    let (ux, uy) = (tx - first.step[0], ty - first.step[1]);
    if in_unit(ux) && in_unit(uy) {
        let second = newton(&patch, ux, uy, ex1, ey1);
        if second.newton {
            return Step {
                ex: ex1 - second.step[0],
                ey: ey1 - second.step[1],
                slope: second.slope,
                converged: newton_done(&patch, &second, ux, uy),
            };
        }
    }
    Step {
        ex: ex1,
        ey: ey1,
        slope: first.slope,
        converged: newton_done(&patch, &first, tx, ty),
    }
}
