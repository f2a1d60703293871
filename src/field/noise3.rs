//! 3D gradient noise (Perlin's improved noise, 2002) for the trochoid method's turbulence,
//! evaluated a row at a time.
//!
//! `noise(x, y, z)` interpolates, with the quintic fade 6t⁵ − 15t⁴ + 10t³, the dot
//! products of the offsets from the eight corners of the lattice cell with their
//! gradients: one of the twelve cube-edge directions (four of them twice, as Perlin's 16
//! entry table), picked by a 32-bit integer hash of (key, ix, iy, iz). Values lie in
//! about [−1, 1]; the mean is 0 and the field is isotropic enough that a plane slice has
//! the same radial spectrum in every direction.
//!
//! **Rows.** Along a row (y and z fixed) the y and z fractions, fades and the lattice
//! rows are constants, so the noise within the cell of lattice column ix is
//! lerp(s(fx), A(ix)·fx + B(ix), A(ix+1)·(fx − 1) + B(ix+1)), with A and B the y–z
//! interpolated gradient x components and constant parts of the four corners of that
//! column. [`row_context`] gives the constants, [`RowCtx::column`] the coefficients of a
//! column, and [`add_row`] fills a row from a table of columns with a branch-free loop
//! that the compiler vectorizes (compiled for each instruction set by
//! `simd::multiversion`, the one of the run chosen when a [`Scratch`] is made; the same
//! IEEE operations in the same order on all, no fused multiply–add, so the bits do not
//! depend on the processor). A single point is a row of one sample: [`noise()`] gives the
//! very bits [`add_row`] gives at that point.

use crate::simd::{Isa, multiversion};

/// The 16 gradients (x, y, z components): the 12 cube edges, then (1,1,0), (−1,1,0),
/// (0,−1,1), (0,−1,−1) again.
const GX: [f32; 16] = [
    1., -1., 1., -1., 1., -1., 1., -1., 0., 0., 0., 0., 1., -1., 0., 0.,
];
const GY: [f32; 16] = [
    1., 1., -1., -1., 0., 0., 0., 0., 1., -1., 1., -1., 1., 1., -1., -1.,
];
const GZ: [f32; 16] = [
    0., 0., 0., 0., 1., 1., -1., -1., 1., 1., -1., -1., 0., 0., 1., -1.,
];

/// 2^52 + 2^51: adding and subtracting it rounds an f64 of magnitude < 2^51 to an integer
/// (round half to even) with two exact IEEE operations, which vectorize.
const ROUND_MAGIC: f64 = 6_755_399_441_055_744.0;

/// floor(u) for |u| < 2^51, by IEEE operations only (the same bits in every path).
#[inline(always)]
pub(crate) fn floor_f64(u: f64) -> f64 {
    let r = (u + ROUND_MAGIC) - ROUND_MAGIC;
    if r > u { r - 1.0 } else { r }
}

/// Quintic fade 6t⁵ − 15t⁴ + 10t³.
#[inline(always)]
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// lowbias32 (Wellons): a well-mixing bijection of 32-bit words.
#[inline(always)]
fn mix32(mut h: u32) -> u32 {
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^ (h >> 16)
}

/// The hash of lattice point (ix, iy, iz) under `key`, from the y–z part `yz`
/// ([`yz_part`]) and ix (indices wrap modulo 2^32: the lattice repeats after 2^32 cells).
#[inline(always)]
fn corner_hash(yz: u32, ix: i64) -> u32 {
    mix32(yz ^ (ix as u32).wrapping_mul(0x8da6_b343))
}

#[inline(always)]
fn yz_part(key: u32, iy: i64, iz: i64) -> u32 {
    mix32(key ^ (iy as u32).wrapping_mul(0xd816_3841) ^ (iz as u32).wrapping_mul(0xcb1a_b31f))
}

/// The constants of one row (fixed lattice y and z) of one noise.
#[derive(Debug, Clone, Copy)]
pub struct RowCtx {
    /// y–z hash parts of the four corner rows (iy, iz), (iy+1, iz), (iy, iz+1), (iy+1, iz+1).
    yz: [u32; 4],
    fy: f32,
    fz: f32,
    sy: f32,
    sz: f32,
    /// Lattice period along x (0: none); used to measure the noise's spectrum on a
    /// periodic tile.
    period: i64,
}

/// The row constants of the noise `key` at lattice coordinates y = `v`, z = `w`;
/// `period` > 0 wraps the lattice (every axis) with that period.
pub fn row_context(key: u32, v: f64, w: f64, period: i64) -> RowCtx {
    let (iy, iz) = (floor_f64(v), floor_f64(w));
    let (fy, fz) = ((v - iy) as f32, (w - iz) as f32);
    let wrap = |i: i64| if period > 0 { i.rem_euclid(period) } else { i };
    let (iy, iz) = (iy as i64, iz as i64);
    let (y0, y1, z0, z1) = (wrap(iy), wrap(iy + 1), wrap(iz), wrap(iz + 1));
    RowCtx {
        yz: [
            yz_part(key, y0, z0),
            yz_part(key, y1, z0),
            yz_part(key, y0, z1),
            yz_part(key, y1, z1),
        ],
        fy,
        fz,
        sy: fade(fy),
        sz: fade(fz),
        period,
    }
}

impl RowCtx {
    /// [A, B] of lattice column `ix`: the noise in the cell to its right is
    /// lerp(fade(fx), A·fx + B, A'·(fx − 1) + B') with [A', B'] of column ix + 1.
    #[inline(always)]
    pub fn column(&self, ix: i64) -> [f32; 2] {
        let ix = if self.period > 0 {
            ix.rem_euclid(self.period)
        } else {
            ix
        };
        let g = |yz: u32| (corner_hash(yz, ix) >> 28) as usize;
        let (g00, g10, g01, g11) = (g(self.yz[0]), g(self.yz[1]), g(self.yz[2]), g(self.yz[3]));
        let (fy0, fy1, fz0, fz1) = (self.fy, self.fy - 1.0, self.fz, self.fz - 1.0);
        let c = |gi: usize, fy: f32, fz: f32| GY[gi] * fy + GZ[gi] * fz;
        let lerp = |s: f32, a: f32, b: f32| a + s * (b - a);
        let a_z0 = lerp(self.sy, GX[g00], GX[g10]);
        let a_z1 = lerp(self.sy, GX[g01], GX[g11]);
        let b_z0 = lerp(self.sy, c(g00, fy0, fz0), c(g10, fy1, fz0));
        let b_z1 = lerp(self.sy, c(g01, fy0, fz1), c(g11, fy1, fz1));
        [lerp(self.sz, a_z0, a_z1), lerp(self.sz, b_z0, b_z1)]
    }
}

/// The noise from the columns' coefficients `l` (column ix) and `r` (ix + 1) and the
/// x fraction `fx`.
#[inline(always)]
fn combine(l: [f32; 2], r: [f32; 2], fx: f32) -> f32 {
    let v0 = l[0] * fx + l[1];
    let v1 = r[0] * (fx - 1.0) + r[1];
    v0 + fade(fx) * (v1 - v0)
}

/// The noise `key` at lattice point (u, v, w), with the lattice wrapped by `period` (0:
/// none): the same bits as [`add_row`] gives for a sample at u.
pub fn noise(key: u32, u: f64, v: f64, w: f64, period: i64) -> f32 {
    let ctx = row_context(key, v, w, period);
    let fl = floor_f64(u);
    let ix = fl as i64;
    combine(ctx.column(ix), ctx.column(ix + 1), (u - fl) as f32)
}

/// Per-thread buffers of [`add_row`].
#[derive(Debug)]
pub struct Scratch {
    /// The instruction set of the row passes, chosen when the scratch is made.
    isa: Isa,
    cols: Vec<[f32; 2]>,
    index: Vec<i32>,
    frac: Vec<f32>,
}

impl Default for Scratch {
    /// Empty buffers, and the processor's instruction set.
    fn default() -> Self {
        Scratch {
            isa: Isa::detect(),
            cols: Vec::new(),
            index: Vec::new(),
            frac: Vec::new(),
        }
    }
}

/// `out[i] += amp · noise(key, scale·xs[i] + offset, v, w)` for every sample, where the
/// xs are increasing. Lattice columns are hashed once per row (a cell spanning several
/// samples is hashed once); a row finer than its samples hashes two columns per sample.
pub fn add_row(
    ctx: &RowCtx,
    xs: &[f64],
    scale: f64,
    offset: f64,
    amp: f32,
    out: &mut [f32],
    scratch: &mut Scratch,
) {
    let n = xs.len();
    assert_eq!(out.len(), n, "add_row: xs and out differ in length");
    if n == 0 {
        return;
    }
    let first = floor_f64(xs[0] * scale + offset);
    let last = floor_f64(xs[n - 1] * scale + offset);
    let span = last - first;
    let Scratch {
        isa,
        cols,
        index,
        frac,
    } = scratch;
    let isa = *isa;
    index.resize(n, 0);
    frac.resize(n, 0.0);
    if span.is_finite() && span >= 0.0 && span <= (2 * n) as f64 {
        let count = span as usize + 2;
        cols.clear();
        cols.extend((0..count as i64).map(|j| ctx.column(first as i64 + j)));
        split_run(isa, xs, scale, offset, first, index, frac);
        gather_run(isa, cols, index, frac, amp, out);
    } else {
        // A lattice much finer than the samples (or a non-monotone row): two columns per
        // sample.
        for ((o, &x), (ix, fx)) in out
            .iter_mut()
            .zip(xs)
            .zip(index.iter_mut().zip(frac.iter_mut()))
        {
            let u = x * scale + offset;
            let fl = floor_f64(u);
            *ix = 0;
            *fx = (u - fl) as f32;
            let i = fl as i64;
            *o += amp * combine(ctx.column(i), ctx.column(i + 1), *fx);
        }
    }
}

multiversion! {
    @on
    /// Splits each sample's lattice coordinate into the column index relative to `first`
    /// and the fraction.
    fn split_run(
        isa: Isa,
        xs: &[f64],
        scale: f64,
        offset: f64,
        first: f64,
        index: &mut [i32],
        frac: &mut [f32],
    ) {
        for ((&x, i), f) in xs.iter().zip(index.iter_mut()).zip(frac.iter_mut()) {
            let u = x * scale + offset;
            let fl = floor_f64(u);
            *i = (fl - first) as i32;
            *f = (u - fl) as f32;
        }
    }
}

multiversion! {
    @on
    /// `out[i] += amp · combine(cols[index[i]], cols[index[i] + 1], frac[i])`.
    fn gather_run(
        isa: Isa,
        cols: &[[f32; 2]],
        index: &[i32],
        frac: &[f32],
        amp: f32,
        out: &mut [f32],
    ) {
        let last = cols.len() - 2;
        for ((o, &i), &fx) in out.iter_mut().zip(index).zip(frac) {
            let i = (i.max(0) as usize).min(last);
            *o += amp * combine(cols[i], cols[i + 1], fx);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_equal_points_bit_for_bit_on_every_instruction_set() {
        let xs: Vec<f64> = (0..777).map(|i| -13.7 + i as f64 * 0.173).collect();
        for (scale, offset) in [(0.05, 0.3), (0.9, -2.1), (7.5, 0.25)] {
            let ctx = row_context(42, 3.3, -1.7, 0);
            for isa in Isa::available() {
                let mut out = vec![0.0f32; xs.len()];
                let mut s = Scratch {
                    isa,
                    ..Scratch::default()
                };
                let first = floor_f64(xs[0] * scale + offset);
                let last = floor_f64(xs[xs.len() - 1] * scale + offset);
                if last - first <= (2 * xs.len()) as f64 {
                    s.index.resize(xs.len(), 0);
                    s.frac.resize(xs.len(), 0.0);
                    s.cols = (0..(last - first) as i64 + 2)
                        .map(|j| ctx.column(first as i64 + j))
                        .collect();
                    split_run(isa, &xs, scale, offset, first, &mut s.index, &mut s.frac);
                    gather_run(isa, &s.cols, &s.index, &s.frac, 1.0, &mut out);
                } else {
                    add_row(&ctx, &xs, scale, offset, 1.0, &mut out, &mut s);
                }
                for (i, (&o, &x)) in out.iter().zip(&xs).enumerate() {
                    let p = 0.0 + noise(42, x * scale + offset, 3.3, -1.7, 0);
                    assert_eq!(
                        o.to_bits(),
                        p.to_bits(),
                        "{isa:?} scale {scale}: sample {i}"
                    );
                }
            }
        }
    }

    #[test]
    fn noise_is_zero_on_the_lattice_continuous_and_bounded() {
        for ix in -3..3 {
            assert_eq!(noise(7, ix as f64, 2.0, -5.0, 0), 0.0, "lattice point {ix}");
        }
        // Continuity across a cell wall, and |noise| ≤ √3/2·… ≤ 1.1 over many points.
        let eps = 1e-7;
        for k in 0..200 {
            let (v, w) = (k as f64 * 0.37, k as f64 * 0.11);
            let a = noise(9, 5.0 - eps, v, w, 0);
            let b = noise(9, 5.0 + eps, v, w, 0);
            assert!((a - b).abs() < 1e-5, "jump {a} vs {b} at row {k}");
            for j in 0..50 {
                let x = noise(9, j as f64 * 0.29, v, w, 0);
                assert!(x.abs() <= 1.1, "noise {x} out of bounds");
            }
        }
    }

    #[test]
    fn a_wrapped_lattice_repeats() {
        for k in 0..50 {
            let (u, v, w) = (k as f64 * 0.31, k as f64 * 0.17 + 0.5, 0.4);
            let a = noise(3, u, v, w, 8);
            assert_eq!(a, noise(3, u + 8.0, v, w, 8));
            assert_eq!(a, noise(3, u, v + 16.0, w, 8));
            assert_eq!(a, noise(3, u, v, w - 8.0, 8));
        }
    }
}
