//! The first and second stages of the product fields' inverse transforms: each factor's
//! fields built on the kx rows of the components and transformed along ky (the first
//! stage, a share of the rows of y at a time), then along kx a few rows of y at a time,
//! just before their products ([`TransformBound::each_cell`]), so that no whole field is
//! held.

use std::f64::consts::TAU;
use std::sync::Arc;

use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::super::C64;
use super::super::fit::POWERS;
use super::products::{Acc, Real};
use super::{TransformBound, Wave};
use crate::fastmath::powi;
use crate::grid::{GridSpec, bin_index};

/// The most first-stage fields of a factor: the bases' exponents and one more (the S·A
/// terms' fields of Q and 1 reach one below and one above them).
pub(super) const FIELDS: usize = POWERS + 1;

/// The bytes of the accumulators a pass over y holds an output cell, at most: above it,
/// they are built a share of the rows of y at a time ([`Passes`]), each share's
/// transforms gathered at the outputs. The 19 m storm over 2048 m has about 31 at 1024²
/// (two shares; in one the frame took as long and 1.35 times the memory), over 4096 m
/// 125 (eight shares, which keep it within 3 times the linear field's peak).
pub(super) const ACC_BYTES_PER_CELL: usize = 20;

/// The bytes of first-stage fields a pass over y holds an output cell (the linear field
/// holds about 17 at its peak; see [`TransformBound::passes`]).
const PASS_BYTES_PER_CELL: usize = 8;

/// Pass p of P over the rows of y of the first stages (P a divisor of py): the values
/// at y = P·j + p, j < py/P, X[Pj + p] = Σ_m (x_m e^{2πi m p/py}) e^{2πi m j/(py/P)}: the
/// components twiddled, folded onto m mod py/P and transformed at that length (one pass:
/// the whole transform, untwiddled).
struct Pass<'a> {
    len: usize,
    /// e^{2πi m p/py} of each column m (empty in one pass).
    twiddle: Vec<C64>,
    /// m mod `len` of each column m < py (where a component folds to; no division a
    /// component).
    fold: Vec<u32>,
    /// The inverse transform of `len`.
    inv: &'a dyn Fft<f64>,
}

impl<'a> Pass<'a> {
    fn new(p: usize, passes: usize, py: usize, inv: &'a dyn Fft<f64>) -> Self {
        let len = py / passes;
        Self {
            len,
            twiddle: twiddles(py, p, passes, 1.0),
            fold: folds(py, len),
            inv,
        }
    }
}

/// The twiddles of part p of a transform of length `py` split in parts (the rows of y
/// P·j + p): e^{sign·2πi k p/py} of each k < py; none (empty) for a whole transform.
pub(super) fn twiddles(py: usize, p: usize, parts: usize, sign: f64) -> Vec<C64> {
    match parts {
        1 => Vec::new(),
        _ => (0..py)
            .map(|k| C64::from_polar(1.0, sign * TAU * ((k * p) % py) as f64 / py as f64))
            .collect(),
    }
}

/// k mod `len` of each k < `py`: where index k folds to in a part's transform of `len`
/// (a table, so that no division is made a wave or an output).
pub(super) fn folds(py: usize, len: usize) -> Vec<u32> {
    (0..py).map(|k| (k % len) as u32).collect()
}

/// A row of y of every accumulator of a share: the B terms', the S·A terms'.
pub(super) type AccRows<'a, 'r, B, S> = (
    &'a mut [&'r mut [Complex<B>]],
    &'a mut [&'r mut [Complex<S>]],
);

/// A row of y of every accumulator of a set.
type Rows<'a, T> = Vec<&'a mut [Complex<T>]>;

/// Row j of each accumulator of `accs` (rows of px) at j: its rows t + r·j, j < `len`.
fn rows_by_j<T>(
    accs: &mut [Vec<Complex<T>>],
    px: usize,
    (t, r, len): (usize, usize, usize),
) -> Vec<Rows<'_, T>> {
    let mut by_j: Vec<Rows<T>> = (0..len).map(|_| Vec::with_capacity(accs.len())).collect();
    for a in accs.iter_mut() {
        for (j, row) in a.chunks_exact_mut(px).skip(t).step_by(r).enumerate() {
            by_j[j].push(row);
        }
    }
    by_j
}

/// A factor's first-stage fields: its exponents lo ..= hi.
pub(super) type Fields = (Factor, (i32, i32));

/// The single-wave factors of the products.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Factor {
    /// k_x/s, k_y/s, s (the B terms).
    X,
    Y,
    V,
    /// Q, 1 (the S·A terms of finite depth; Q/s and s are theirs at the exponent below
    /// and above).
    W1,
    W0,
}

impl Factor {
    fn of(self, c: &Wave, spec: GridSpec) -> f64 {
        match self {
            Factor::X => c.k(spec).0 / c.s,
            Factor::Y => c.k(spec).1 / c.s,
            Factor::V => c.s,
            Factor::W1 => c.q,
            Factor::W0 => 1.0,
        }
    }
}

impl TransformBound {
    /// The first stages of a factor's fields' inverse transforms, one field for each
    /// exponent e of `lo ..= hi` (index e − lo): Σ over the components of
    /// f(k_i)·(|s_i|/s_p)^e·b_i on the kx rows they occupy (|n| ≤ k_x, row n + k_x), each
    /// row transformed along ky where it lies (rows of zeros stay zero): 2k_x + 1 rows of
    /// [`Self::row_stride`], every exponent's row of a kx row built at once (each
    /// component read once), of the rows of y of `pass` ([`Pass`]). The second stage
    /// reads them across the rows, a few values of j at a time.
    fn stage_one(&self, b: &[C64], f: Factor, (lo, hi): (i32, i32), pass: &Pass) -> Vec<Vec<C64>> {
        let py = self.plan.py;
        let (len, inv) = (pass.len, pass.inv);
        let stride = self.row_stride(len);
        let w = self.rows.len() - 1;
        let ne = (hi - lo + 1).max(0) as usize;
        let zero = C64::new(0.0, 0.0);
        let mut fields: Vec<Vec<C64>> = (0..ne).map(|_| self.ones.take_any(w * stride)).collect();
        // Each kx row of every field, a task a kx row.
        let mut tasks: Vec<Vec<&mut [C64]>> = (0..w).map(|_| Vec::with_capacity(ne)).collect();
        for field in fields.iter_mut() {
            for (row, task) in field.chunks_exact_mut(stride).zip(tasks.iter_mut()) {
                task.push(&mut row[..len]);
            }
        }
        tasks.into_par_iter().enumerate().for_each_init(
            || vec![zero; inv.get_inplace_scratch_len()],
            |scratch, (r, mut rows)| {
                for row in rows.iter_mut() {
                    row.fill(zero);
                }
                let row_of = self.rows[r]..self.rows[r + 1];
                for (c, &bi) in self.comps[row_of.clone()].iter().zip(&b[row_of]) {
                    let col = bin_index(i64::from(c.m), py);
                    let bi = match pass.twiddle.get(col) {
                        Some(&t) => bi * t,
                        None => bi,
                    };
                    // f(k_i)·x^e·b_i of e = lo, lo + 1, …: one multiplication by x an
                    // exponent.
                    let x = c.s.abs() / self.fit.s_ref;
                    let mut w = bi * (f.of(c, self.spec) * powi(x, lo));
                    let at = pass.fold[col] as usize;
                    for row in rows.iter_mut() {
                        row[at] += w;
                        w *= x;
                    }
                }
                for row in rows {
                    if row.iter().any(|v| *v != zero) {
                        inv.process_with_scratch(row, scratch);
                    }
                }
            },
        );
        fields
    }

    /// The distance between the kx rows of a first stage of `len` columns: `len` and a
    /// cache line, so that the second stage's reads down a column of them do not share
    /// one cache set.
    fn row_stride(&self, len: usize) -> usize {
        len + 4
    }

    /// `add(rows, f, g)` on every row of padded cells of pass `pass` (the rows of y
    /// P·j + p, j < py/P, [`Passes`]): the accumulators' row of y (`acc`: the py/P_a rows
    /// of px of the accumulators' pass p mod P_a), and the row of each field of `fs` and
    /// `gs` (the fields of the terms' factors, each of its exponents lo ..= hi, index
    /// e − lo): the transforms' first stage
    /// ([`Self::stage_one`]), the second (along kx) a few rows of y at a time, just
    /// before their products, so that no whole field is held. The same values as the
    /// whole fields' transforms (to rounding; the same bits in one pass). With `last`,
    /// the terms' last products: each row of the accumulators is then transformed along
    /// x (the first stage of their forward transforms, while the row is at hand).
    pub(super) fn each_cell<B: Real, S: Real>(
        &self,
        b: &[C64],
        (fs, gs): (Fields, Fields),
        (pass, acc): ((usize, &Passes), &mut Acc<B, S>),
        last: bool,
        add: impl Fn(AccRows<B, S>, &[&[C64]], &[&[C64]]) + Sync,
    ) {
        let (plan_b, plan_s) = (B::forward(self).0, S::forward(self).0);
        const ROWS: usize = 4;
        let (p, passes) = pass;
        let px = self.plan.px;
        let kx = self.reach.0.k;
        let same = gs == fs;
        let len = passes.len;
        let zero = C64::new(0.0, 0.0);
        let inv_x = &*self.plan.inv_x;
        // The pass's tasks (ROWS rows of j each), each row holding the row of every
        // accumulator: row i = j·r + t of the accumulators' pass.
        let (r, t) = (passes.count / passes.acc, p / passes.acc);
        let at = (t, r, len);
        let by_j = rows_by_j(&mut acc.b, px, at)
            .into_iter()
            .zip(rows_by_j(&mut acc.sa, px, at));
        let mut tasks: Vec<Vec<(Rows<B>, Rows<S>)>> = (0..len.div_ceil(ROWS))
            .map(|_| Vec::with_capacity(ROWS))
            .collect();
        for (j, rows) in by_j.enumerate() {
            tasks[j / ROWS].push(rows);
        }
        // The kx columns of the components (|n| ≤ k_x, wrapped) and those between them,
        // zero before the second stage.
        let gap = (kx + 1) as usize..(px as i64 - kx) as usize;
        // Kx row r = n + k_x (n = −k_x ..= k_x) goes to column n, wrapped (px > 2k_x +
        // o_x: the wrapped indices never meet).
        let cols: Vec<usize> = (0..self.rows.len() - 1)
            .map(|r| bin_index(r as i64 - kx, px))
            .collect();
        // The rows j0 .. j0 + nj of each field of `ones` into `rows` (a field's nj rows
        // after another's): gathered from its first stage, then transformed along kx.
        let rows_of = |ones: &[Vec<C64>],
                       (j0, nj): (usize, usize),
                       rows: &mut Vec<C64>,
                       scratch: &mut Vec<C64>| {
            rows.resize(ones.len() * nj * px, zero);
            scratch.resize(inv_x.get_inplace_scratch_len(), zero);
            for (l, one) in ones.iter().enumerate() {
                let block = &mut rows[l * nj * px..(l + 1) * nj * px];
                for row in block.chunks_exact_mut(px) {
                    row[gap.clone()].fill(zero);
                }
                for (&col, from) in cols.iter().zip(one.chunks_exact(self.row_stride(len))) {
                    for (jj, &v) in from[j0..j0 + nj].iter().enumerate() {
                        block[jj * px + col] = v;
                    }
                }
                for row in block.chunks_exact_mut(px) {
                    inv_x.process_with_scratch(row, scratch);
                }
            }
        };
        let pass = Pass::new(p, passes.count, self.plan.py, &*passes.inverse);
        let fields = |(f, e)| self.stage_one(b, f, e, &pass);
        let f_one = fields(fs);
        let g_one = if same { Vec::new() } else { fields(gs) };
        let g_src = if same { &f_one } else { &g_one };
        tasks.into_par_iter().enumerate().for_each_init(
            || (Vec::new(), Vec::new(), Vec::new(), (Vec::new(), Vec::new())),
            |(fr, gr, scratch, (scratch_b, scratch_s)), (c, mut out)| {
                let at_rows = (c * ROWS, out.len());
                rows_of(&f_one, at_rows, fr, scratch);
                if !same {
                    rows_of(g_src, at_rows, gr, scratch);
                }
                let gr = if same { &*fr } else { &*gr };
                let (nf, ng, nj) = (f_one.len(), g_src.len(), out.len());
                for (jj, (rb, rs)) in out.iter_mut().enumerate() {
                    let at = |l: usize| (l * nj + jj) * px..(l * nj + jj + 1) * px;
                    let fv: [&[C64]; FIELDS] =
                        std::array::from_fn(|l| if l < nf { &fr[at(l)] } else { &[] });
                    let gv: [&[C64]; FIELDS] =
                        std::array::from_fn(|l| if l < ng { &gr[at(l)] } else { &[] });
                    add((rb, rs), &fv, &gv);
                    if last {
                        for row in rb.iter_mut() {
                            plan_b.forward_x(row, scratch_b);
                        }
                        for row in rs.iter_mut() {
                            plan_s.forward_x(row, scratch_s);
                        }
                    }
                }
            },
        );
        self.ones.give_all(f_one.into_iter().chain(g_one));
    }

    /// The passes over y of [`Self::each_cell`] for `ne` first-stage fields and
    /// accumulators of `acc_bytes` a padded cell (all of them): the accumulators' P_a, the least
    /// divisor of py that holds at most `acc_budget` ([`ACC_BYTES_PER_CELL`]) bytes an
    /// output cell of them at once, and the first stages' P, the least multiple of P_a
    /// dividing py that holds at most [`PASS_BYTES_PER_CELL`] (each pass folds the
    /// components onto its share of the columns and transforms that: the passes together
    /// cost about one whole transform).
    pub(super) fn passes(&self, ne: usize, acc_bytes: usize) -> Passes {
        let py = self.plan.py;
        let cells = self.spec.nx * self.spec.ny;
        // The least divisor of py, a multiple of `of`, at or above `least`.
        let divisor = |least: usize, of: usize| {
            (least.clamp(1, py)..=py)
                .find(|d| py % d == 0 && d % of == 0)
                .unwrap_or(py)
        };
        let bytes = acc_bytes * self.plan.px * py;
        let acc = divisor(bytes.div_ceil((self.acc_budget * cells).max(1)), 1);
        let held = ne * (self.rows.len() - 1) * self.row_stride(py) * size_of::<C64>();
        let cap = PASS_BYTES_PER_CELL * cells;
        let count = divisor(held.div_ceil(cap.max(1)), acc);
        let len = py / count;
        // The transform of a pass's share of the columns, planned once (one pass: the
        // whole transform).
        let inverse = match count {
            1 => Arc::clone(&self.plan.inv_y),
            _ => FftPlanner::new().plan_fft_inverse(len),
        };
        Passes {
            count,
            len,
            acc,
            acc_len: py / acc,
            inverse,
        }
    }
}

/// The passes over y of the first stages ([`TransformBound::passes`]): `count` (P, a
/// divisor of py) passes of `len` = py/P rows of y each, and the inverse transform of a
/// pass's folded columns.
pub(super) struct Passes {
    pub(super) count: usize,
    pub(super) len: usize,
    /// The accumulators' passes (P_a, a divisor of P): pass a holds the rows of y
    /// P_a·i + a (i < `acc_len` = py/P_a), those of the first stages' passes a + P_a·t,
    /// t < P/P_a (row j of pass a + P_a·t is row i = j·P/P_a + t).
    pub(super) acc: usize,
    pub(super) acc_len: usize,
    inverse: Arc<dyn Fft<f64>>,
}
