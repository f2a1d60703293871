//! Periodic multi-octave Perlin noise (fBm), Li Tian eq. 9.
//!
//! The height is the fractal sum
//!
//! ```text
//! h(x, y) = Σ_{i<P} a^i · noise(lac^i · x/λ0, lac^i · y/λ0) / (√2/2 · Σ_{i<P} a^i)
//! ```
//!
//! where `noise` is classic 2D gradient noise (Perlin 2002 "improved" noise: quintic fade
//! `6t⁵ − 15t⁴ + 10t³`, one unit-length gradient per lattice point). Coordinates are in
//! meters, so the field does not depend on the grid resolution: two grids over the same
//! extent agree exactly at the points they share.
//!
//! **Normalization.** 2D gradient noise with unit gradients lies in `[−√2/2, √2/2]` (the
//! bound is reached at a cell centre when all four gradients point along the diagonals).
//! Dividing the octave sum by `√2/2 · Σ a^i` therefore guarantees `h ∈ [−1, 1]`; the result
//! is additionally clamped to `[−1, 1]` to absorb f32 rounding of the gradients.
//!
//! **Tileability.** With `tileable`, octave `i` uses an integer number of lattice cells across
//! the extent, `cx_i = max(1, round(extent_x_m · lac^i / λ0))` (same for y), and lattice indices
//! wrap modulo that count, so the field is exactly periodic over `extent_x_m × extent_y_m`.
//! The wavelength actually used is `extent_x_m / cx_i` (resp. y): the nominal `λ0 / lac^i` is
//! adjusted to the nearest value that divides the extent (see [`octave_cells`] and
//! [`octave_wavelengths`]). Without `tileable` the exact `λ0 / lac^i` is used and the field is
//! not periodic.
//!
//! **Determinism.** Gradients are picked from a fixed table (built at compile time with basic
//! IEEE arithmetic only) by a splitmix64-style hash of (seed, octave, ix, iy); no RNG and no
//! transcendental libm call.
//! Every sample is computed by the same sequence of floating-point operations whatever the
//! thread count, so output is bit-identical with 1 or many threads and on every platform.
//! [`perlin_at`] uses the very same operations as [`perlin_field`], so they agree exactly at
//! grid points.

pub mod noise_rs;
mod params;

pub use params::{PerlinParams, octave_cells, octave_wavelengths};

/// The noise field of `basis` under `fractal`: the builtin kernel ([`perlin_field`], fBm
/// only) or a noise-rs generator ([`noise_rs::noise_rs_field`]); in [−1, 1] either way.
pub fn noise_field(
    spec: &GridSpec,
    p: &PerlinParams,
    offset: f64,
    basis: crate::config::NoiseBasis,
    fractal: crate::config::NoiseFractal,
) -> Vec<f32> {
    match basis {
        crate::config::NoiseBasis::Builtin => perlin_field_offset(spec, p, offset),
        _ => noise_rs::noise_rs_field(spec, p, offset, basis, fractal),
    }
}

/// The wavelengths of the octaves (x, y) in meters: the builtin kernel's, rounded to
/// divide the extent when tileable, or λ0/lacunarity^i of a noise-rs basis (whose
/// tileable form is periodic without rounding).
pub fn basis_wavelengths(
    spec: &GridSpec,
    p: &PerlinParams,
    basis: crate::config::NoiseBasis,
) -> Vec<(f64, f64)> {
    match basis {
        crate::config::NoiseBasis::Builtin => octave_wavelengths(spec, p),
        _ => octave_wavelengths(
            spec,
            &PerlinParams {
                tileable: false,
                ..*p
            },
        ),
    }
}

use crate::grid::GridSpec;
use crate::simd::{Isa, multiversion};
use params::{check, lacunarity_powers};
use rayon::prelude::*;

// ---------------------------------------------------------------------------------------------
// Hashing and gradients

const GOLDEN: u64 = 0x9E37_79B9_7F4A_7C15;
const K_ROW: u64 = 0xD6E8_FEB8_6659_FD93;
const K_COL: u64 = 0xA076_1D64_78BD_642F;

/// splitmix64 finalizer: a bijective, well-mixing 64-bit hash.
#[inline(always)]
fn fmix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// sin and cos by Taylor series using only +, ×, ÷ (exactly reproducible, usable in const).
const fn sin_cos(t: f64) -> (f64, f64) {
    let mut s = 0.0;
    let mut c = 0.0;
    let mut term = 1.0; // t^n / n!
    let mut n = 0u32;
    while n < 40 {
        match n % 4 {
            0 => c += term,
            1 => s += term,
            2 => c -= term,
            _ => s -= term,
        }
        n += 1;
        term = term * t / n as f64;
    }
    (s, c)
}

const N_GRAD: usize = 256;

/// 256 unit vectors at angles −π + 2πk/256.
const fn make_gradients() -> [[f32; 2]; N_GRAD] {
    let mut g = [[0.0f32; 2]; N_GRAD];
    let mut k = 0;
    while k < N_GRAD {
        let t = -std::f64::consts::PI + 2.0 * std::f64::consts::PI * k as f64 / N_GRAD as f64;
        let (s, c) = sin_cos(t);
        g[k] = [c as f32, s as f32];
        k += 1;
    }
    g
}

static GRADIENTS: [[f32; 2]; N_GRAD] = make_gradients();

// ---------------------------------------------------------------------------------------------
// Per-octave constants and the shared per-sample arithmetic

/// Everything one octave needs, derived once from the grid and the parameters.
#[derive(Debug, Clone, Copy)]
struct Octave {
    /// Lattice cells per meter along x and y.
    freq_x: f64,
    freq_y: f64,
    /// Wrap counts for tileable fields; 0 = no wrapping.
    wrap_x: i64,
    wrap_y: i64,
    /// Hash key of (seed, octave).
    key: u64,
    /// a^i / (√2/2 · Σ a^j).
    amp: f32,
}

fn octaves(spec: &GridSpec, p: &PerlinParams) -> Vec<Octave> {
    let powers = lacunarity_powers(p);
    let cells = octave_cells(spec, p);
    let mut a_pow = Vec::with_capacity(powers.len());
    let mut a = 1.0f64;
    for _ in 0..p.octaves {
        a_pow.push(a);
        a *= p.persistence;
    }
    let bound = std::f64::consts::FRAC_1_SQRT_2 * a_pow.iter().sum::<f64>();
    let seed_key = fmix(p.seed);
    (0..p.octaves as usize)
        .map(|i| {
            let key = fmix(seed_key ^ (i as u64 + 1).wrapping_mul(GOLDEN));
            let amp = (a_pow[i] / bound) as f32;
            if p.tileable {
                let (cx, cy) = cells[i];
                Octave {
                    freq_x: cx as f64 / spec.extent_x_m,
                    freq_y: cy as f64 / spec.extent_y_m,
                    wrap_x: i64::try_from(cx).unwrap_or(i64::MAX),
                    wrap_y: i64::try_from(cy).unwrap_or(i64::MAX),
                    key,
                    amp,
                }
            } else {
                let f = powers[i] / p.wavelength_m;
                Octave {
                    freq_x: f,
                    freq_y: f,
                    wrap_x: 0,
                    wrap_y: 0,
                    key,
                    amp,
                }
            }
        })
        .collect()
}

/// 2^52: beyond this every f64 is an integer.
const EXACT_INT: f64 = 4_503_599_627_370_496.0;

/// Splits a lattice coordinate into its cell index (floor) and the f32 fraction in [0, 1].
#[inline(always)]
fn split(u: f64) -> (i64, f32) {
    if u.abs() < EXACT_INT {
        let t = u as i64;
        let t = if (t as f64) > u { t - 1 } else { t };
        (t, (u - t as f64) as f32)
    } else {
        // Huge (already integral), infinite or NaN: saturating index, fraction 0 or NaN.
        (u as i64, (u - u.floor()) as f32)
    }
}

#[inline(always)]
fn wrap(i: i64, n: i64) -> i64 {
    if n > 0 { i.rem_euclid(n) } else { i }
}

/// Quintic fade 6t⁵ − 15t⁴ + 10t³.
#[inline(always)]
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// Constants of one lattice row pair (iy, iy+1) for one output row.
#[derive(Debug, Clone, Copy)]
struct RowCtx {
    hash0: u64,
    hash1: u64,
    fy: f32,
    sy: f32,
    wrap_x: i64,
}

impl RowCtx {
    #[inline(always)]
    fn new(o: &Octave, y_m: f64) -> Self {
        let (iy, fy) = split(y_m * o.freq_y);
        let row_hash = |iy: i64| fmix(o.key ^ (wrap(iy, o.wrap_y) as u64).wrapping_mul(K_ROW));
        Self {
            hash0: row_hash(iy),
            hash1: row_hash(iy.wrapping_add(1)),
            fy,
            sy: fade(fy),
            wrap_x: o.wrap_x,
        }
    }

    /// The noise restricted to this row is, in cell `ix`, a function of the x fraction only:
    /// lerp over y of the two gradients' dot products gives `A·fx + B`. Returns `[A, B]` for
    /// lattice column `ix`.
    #[inline(always)]
    fn column(&self, ix: i64) -> [f32; 2] {
        let ck = col_key(ix, self.wrap_x);
        column_coefs(
            gradient(self.hash0, ck),
            gradient(self.hash1, ck),
            self.fy,
            self.sy,
        )
    }
}

/// Hash key of lattice column `ix` (wrapped when `wrap_x > 0`).
#[inline(always)]
fn col_key(ix: i64, wrap_x: i64) -> u64 {
    (wrap(ix, wrap_x) as u64).wrapping_mul(K_COL)
}

/// Gradient of the lattice point with row hash `row_hash` and column key `col_key`.
#[inline(always)]
fn gradient(row_hash: u64, col_key: u64) -> [f32; 2] {
    GRADIENTS[(fmix(row_hash.wrapping_add(col_key)) >> 56) as usize]
}

/// `[A, B]` of one lattice column from its gradients `g0` (row iy) and `g1` (row iy+1), the
/// y fraction `fy` and its fade `sy` (see [`RowCtx::column`]).
#[inline(always)]
fn column_coefs(g0: [f32; 2], g1: [f32; 2], fy: f32, sy: f32) -> [f32; 2] {
    let b0 = g0[1] * fy;
    let b1 = g1[1] * (fy - 1.0);
    [g0[0] + sy * (g1[0] - g0[0]), b0 + sy * (b1 - b0)]
}

/// Noise value from the coefficients of the cell's left column `c[0..2]` and right column
/// `c[2..4]`, the x fraction and its fade `sx = fade(fx)`.
#[inline(always)]
fn combine_faded(c: &[f32; 4], fx: f32, sx: f32) -> f32 {
    let v0 = c[0] * fx + c[1];
    let v1 = c[2] * (fx - 1.0) + c[3];
    v0 + sx * (v1 - v0)
}

/// [`combine_faded`] computing the fade itself.
#[inline(always)]
fn combine(c: &[f32; 4], fx: f32) -> f32 {
    combine_faded(c, fx, fade(fx))
}

#[inline(always)]
fn cell(row: &RowCtx, ix: i64) -> [f32; 4] {
    let [a0, b0] = row.column(ix);
    let [a1, b1] = row.column(ix.wrapping_add(1));
    [a0, b0, a1, b1]
}

/// Accumulates `amp · noise` into `v`: `0.0 + x` for the first octave (written without
/// reading the freshly allocated output, which would fault every page twice), `v + x` after.
#[inline(always)]
fn accumulate<const FIRST: bool>(v: &mut f32, x: f32) {
    *v = if FIRST { 0.0 + x } else { *v + x };
}

// ---------------------------------------------------------------------------------------------
// The grid: per-octave x tables shared by all rows, per-band caches of lattice-row gradients

/// Samples `start..end` of a row share the cell whose left column is `cols[left]` (see
/// [`XTable`]).
#[derive(Debug, Clone, Copy)]
struct Run {
    start: usize,
    end: usize,
    left: usize,
}

/// Where the samples of a row fall along x for one octave. Every row has the same x
/// positions, so this is computed once per octave for the whole grid.
struct XTable {
    /// The lattice columns the row touches, as hash keys ([`col_key`]): the cell of a run with
    /// left column `cols[l]` has its right column at `cols[l + 1]`. Columns skipped between
    /// samples (lattice finer than the grid) are not listed.
    cols: Vec<u64>,
    /// Per sample: the fraction `fx` given by [`split`] and `fade(fx)`.
    fx: Vec<f32>,
    sx: Vec<f32>,
    /// Maximal runs of consecutive samples in one cell, in order, covering the row.
    runs: Vec<Run>,
}

impl XTable {
    fn new(o: &Octave, nx: usize, dx: f64, offset: f64) -> Self {
        let mut cols = Vec::new();
        let mut fx = Vec::with_capacity(nx);
        let mut sx = Vec::with_capacity(nx);
        let mut runs: Vec<Run> = Vec::new();
        let mut prev: Option<i64> = None;
        for i in 0..nx {
            // Exactly the lattice coordinate `perlin_at` computes at x = (i + offset)·dx
            // (spec.x_m(i) for offset 0).
            let (k, f) = split((i as f64 + offset) * dx * o.freq_x);
            fx.push(f);
            sx.push(fade(f));
            match (prev, runs.last_mut()) {
                (Some(p), Some(r)) if p == k => r.end = i + 1,
                _ => {
                    // When this cell follows the previous one, the previous cell's right
                    // column is this cell's left column.
                    if prev.is_none_or(|p| p.wrapping_add(1) != k) {
                        cols.push(col_key(k, o.wrap_x));
                    }
                    let left = cols.len() - 1;
                    cols.push(col_key(k.wrapping_add(1), o.wrap_x));
                    runs.push(Run {
                        start: i,
                        end: i + 1,
                        left,
                    });
                }
            }
            prev = Some(k);
        }
        Self { cols, fx, sx, runs }
    }
}

/// Gradients of one lattice row at the columns of an [`XTable`].
struct GradRow {
    /// Row hash these gradients belong to, `None` while unfilled.
    hash: Option<u64>,
    g: Vec<[f32; 2]>,
}

/// Per-band working storage of one octave: the gradients of the last two lattice rows used
/// (consecutive output rows mostly share their lattice rows, so each lattice row is hashed
/// about once per band instead of once per output row) and the current row's column
/// coefficients. The cache only skips recomputation; it changes no value.
struct OctaveScratch {
    rows: [GradRow; 2],
    coefs: Vec<[f32; 2]>,
}

impl OctaveScratch {
    fn new(t: &XTable) -> Self {
        let n = t.cols.len();
        let row = || GradRow {
            hash: None,
            g: vec![[0.0; 2]; n],
        };
        Self {
            rows: [row(), row()],
            coefs: vec![[0.0; 2]; n],
        }
    }

    /// Index of the slot holding the gradients of row hash `h` (the hash is a bijection of the
    /// wrapped row index), filling the slot other than `keep` when absent.
    #[inline(always)]
    fn slot(&mut self, t: &XTable, h: u64, keep: Option<usize>) -> usize {
        if let Some(s) = self.rows.iter().position(|r| r.hash == Some(h)) {
            return s;
        }
        let s = if keep == Some(0) { 1 } else { 0 };
        let r = &mut self.rows[s];
        for (g, &ck) in r.g.iter_mut().zip(&t.cols) {
            *g = gradient(h, ck);
        }
        r.hash = Some(h);
        s
    }

    /// Fills `coefs` with `[A, B]` ([`RowCtx::column`]) of every column of `t` for `row`.
    #[inline(always)]
    fn fill_coefs(&mut self, t: &XTable, row: &RowCtx) {
        let s0 = self.slot(t, row.hash0, None);
        let s1 = self.slot(t, row.hash1, Some(s0));
        let (g0, g1) = (&self.rows[s0].g, &self.rows[s1].g);
        let (fy, sy) = (row.fy, row.sy);
        for ((c, &a), &b) in self.coefs.iter_mut().zip(g0).zip(g1) {
            *c = column_coefs(a, b, fy, sy);
        }
    }
}

/// Adds octave `o` to one output row at y = `y_m`.
///
/// The row is walked cell by cell: over a run the coefficients of the cell's two columns are
/// constant, and `fx`, `fade(fx)` come from the table, so the inner loop has no conversion,
/// no branch and no table look-up, and vectorizes. Small cells (a few samples each) cost one
/// short run each; precomputed tables and coefficients keep that overhead small.
#[inline(always)]
fn add_octave_row<const FIRST: bool>(
    o: &Octave,
    t: &XTable,
    s: &mut OctaveScratch,
    y_m: f64,
    out: &mut [f32],
) {
    s.fill_coefs(t, &RowCtx::new(o, y_m));
    let coefs = &s.coefs;
    let amp = o.amp;
    for r in &t.runs {
        let [a0, b0] = coefs[r.left];
        let [a1, b1] = coefs[r.left + 1];
        let c = [a0, b0, a1, b1];
        let span = r.start..r.end;
        for ((v, &fx), &sx) in out[span.clone()]
            .iter_mut()
            .zip(&t.fx[span.clone()])
            .zip(&t.sx[span])
        {
            accumulate::<FIRST>(v, amp * combine_faded(&c, fx, sx));
        }
    }
}

/// Computes the rows of `band`, the first being row `y0` of the grid.
#[inline(always)]
fn fill_band(
    spec: &GridSpec,
    octs: &[Octave],
    tables: &[XTable],
    (y0, offset): (usize, f64),
    band: &mut [f32],
) {
    let mut scratch: Vec<OctaveScratch> = tables.iter().map(OctaveScratch::new).collect();
    for (r, row) in band.chunks_mut(spec.nx).enumerate() {
        // spec.y_m(y0 + r) for offset 0.
        let y = ((y0 + r) as f64 + offset) * spec.dy_m();
        add_octave_row::<true>(&octs[0], &tables[0], &mut scratch[0], y, row);
        for ((o, t), s) in octs.iter().zip(tables).zip(&mut scratch).skip(1) {
            add_octave_row::<false>(o, t, s, y, row);
        }
        for v in row.iter_mut() {
            *v = v.clamp(-1.0, 1.0);
        }
    }
}

multiversion! {
    @on
    /// [`fill_band`] compiled for each instruction set. Bit-identical on all of them: the
    /// same Rust code, only IEEE add/sub/mul/min/max, and Rust never contracts a multiply
    /// and an add into an FMA.
    fn fill_band_on(
        isa: Isa,
        spec: &GridSpec,
        octs: &[Octave],
        tables: &[XTable],
        rows: (usize, f64),
        band: &mut [f32],
    ) {
        fill_band(spec, octs, tables, rows, band)
    }
}

/// Target number of samples per parallel band of rows (rows of a band share gradient caches).
const BAND_SAMPLES: usize = 1 << 16;

/// The fBm over the grid, normalized by the theoretical bound so every value lies in [-1, 1].
///
/// Sample `(i, j)` is the noise at `x = i·dx`, `y = j·dy` in meters (see [`crate::grid`]);
/// `data[j * nx + i]`. Bands of rows are computed in parallel; every sample goes through the
/// same floating-point operations as in [`perlin_at`], so the result does not depend on the
/// number of threads. Panics on invalid parameters (see [`PerlinParams::validate`]).
pub fn perlin_field(spec: &GridSpec, p: &PerlinParams) -> Vec<f32> {
    perlin_field_on(Isa::detect(), spec, p, 0.0)
}

/// [`perlin_field`] with sample (i, j) at ((i + offset)·dx, (j + offset)·dy): offset ½
/// puts the samples at texel centres (`--sample-at centers`), 0 gives [`perlin_field`].
pub fn perlin_field_offset(spec: &GridSpec, p: &PerlinParams, offset: f64) -> Vec<f32> {
    perlin_field_on(Isa::detect(), spec, p, offset)
}

/// [`perlin_field_offset`], its row passes on `isa`.
fn perlin_field_on(isa: Isa, spec: &GridSpec, p: &PerlinParams, offset: f64) -> Vec<f32> {
    check(spec, p);
    if spec.is_empty() {
        return Vec::new();
    }
    let octs = octaves(spec, p);
    let nx = spec.nx;
    let tables: Vec<XTable> = octs
        .iter()
        .map(|o| XTable::new(o, nx, spec.dx_m(), offset))
        .collect();
    let band_rows = (BAND_SAMPLES / nx).clamp(1, 64);
    let mut out = vec![0.0f32; spec.len()];
    out.par_chunks_mut(nx * band_rows)
        .enumerate()
        .for_each(|(b, band)| {
            fill_band_on(isa, spec, &octs, &tables, (b * band_rows, offset), band)
        });
    out
}

/// The same value at one arbitrary point (x_m, y_m) in meters; agrees exactly with
/// [`perlin_field`] at grid points (`x_m = spec.x_m(i)`, `y_m = spec.y_m(j)`).
/// Panics on invalid parameters (see [`PerlinParams::validate`]).
pub fn perlin_at(spec: &GridSpec, p: &PerlinParams, x_m: f64, y_m: f64) -> f32 {
    check(spec, p);
    let mut v = 0.0f32;
    for o in &octaves(spec, p) {
        let row = RowCtx::new(o, y_m);
        let (ix, fx) = split(x_m * o.freq_x);
        v += o.amp * combine(&cell(&row, ix), fx);
    }
    v.clamp(-1.0, 1.0)
}
#[cfg(test)]
mod tests;
