//! The bound waves of the fitted kernels ([`super::fit`]) by transforms: each term of
//! K̃ = ¼[B + R_i + R_j + (S·A + 2T·B)·G̃] is a product of two weighted linear fields in
//! physical space, one forward transform and a multiplication by a function of the output
//! wavevector. Exactly the pair sum of K̃ (up to rounding) over the same components as the
//! pair sum's (the strongest, carrying `nonlinear_fraction` of the variance), at the cost
//! of a few dozen transforms of a grid that covers only their box |n| ≤ k_x, |m| ≤ k_y,
//! padded to more than 2k + min(2k, the grid's edge) per axis so that no sum or
//! difference of two of them wraps onto a kept output (3/2 of the grid when they fill
//! it). `spectrum.nonlinear_method = "fitted"`, and the default `auto`'s choice in deep
//! water and down to about 0.1 λp of depth (see docs/methods.md for its error and cost).
//!
//! With A_f(x) = Σ_i f(k_i) b_i e^{ik_i·x} over the components (b_i = a_i e^{i(φ_i − ω_i t)})
//! the sum terms are Re(A_f A_g) and the difference terms Re(A_f conj A_g); those nearest
//! q = 0 are their exact pair sums (`exact.rs`; the set-down Σ a_i² K⁻_ii at q = 0).

use std::f64::consts::TAU;

use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use exact::Exact;
use grid::{Plan, Pool, Reach};
use outputs::Outputs;
use products::{Acc, Layout, Real, expansion, part, power_term};

use super::fit::{Box2, KernelFit, MAX_NB, POWERS, Region};
use super::{
    C64, Component, Cutoff, HalfSpectrum, SecondOrder, SecondOrderInfo, SpectrumSetup, on_grid,
    self_kernels,
};
use crate::fastmath;
use crate::grid::{GridSpec, signed_index};

/// The most first-stage fields of a factor: the bases' exponents and one more (the S·A
/// terms' fields of Q and 1 reach one below and one above them).
const FIELDS: usize = POWERS + 1;

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
    /// The inverse transform of `len`.
    inv: &'a dyn Fft<f64>,
}

impl<'a> Pass<'a> {
    fn new(p: usize, passes: usize, py: usize, inv: &'a dyn Fft<f64>) -> Self {
        let twiddle = match passes {
            1 => Vec::new(),
            _ => (0..py)
                .map(|m| C64::from_polar(1.0, TAU * ((m * p) % py) as f64 / py as f64))
                .collect(),
        };
        Self {
            len: py / passes,
            twiddle,
            inv,
        }
    }
}

/// A factor's first-stage fields: its exponents lo ..= hi.
type Fields = (Factor, (i32, i32));

/// The single-wave factors of the products.
#[derive(Clone, Copy, PartialEq)]
enum Factor {
    /// k_x/s, k_y/s, s (the B terms).
    X,
    Y,
    V,
    /// Q, 1 (the S·A terms of finite depth; Q/s and s are theirs at the exponent below
    /// and above).
    W1,
    W0,
}

/// What a frame reads of a component (56 bytes instead of a [`Component`]'s 88: the
/// components are held for the sequence).
struct Wave {
    n: i32,
    m: i32,
    kx: f64,
    ky: f64,
    s: f64,
    q: f64,
    rho: f64,
    phi: f64,
}

impl From<&Component> for Wave {
    fn from(c: &Component) -> Self {
        Self {
            n: i32::try_from(c.n).expect("a grid index"),
            m: i32::try_from(c.m).expect("a grid index"),
            kx: c.kx,
            ky: c.ky,
            s: c.s,
            q: c.q,
            rho: c.rho,
            phi: c.phi,
        }
    }
}

impl Factor {
    fn of(self, c: &Wave) -> f64 {
        match self {
            Factor::X => c.kx / c.s,
            Factor::Y => c.ky / c.s,
            Factor::V => c.s,
            Factor::W1 => c.q,
            Factor::W0 => 1.0,
        }
    }
}

/// The bound waves of a set of components through the fitted kernels, by transforms.
pub struct TransformBound {
    comps: Vec<Wave>,
    depth: Option<f64>,
    /// The reach of the waves on each axis (the padded grid and the outputs kept).
    reach: (Reach, Reach),
    plan: Plan<f64>,
    /// The forward transforms of single-precision accumulators (deep water).
    plan32: Plan<f32>,
    /// The padded arrays given back within a frame, reused by its later steps.
    pool: Pool<f64>,
    pool32: Pool<f32>,
    /// The transforms' first stages (py rows of the components' 2k_x + 1 kx columns).
    ones: Pool<f64>,
    /// Where each kx row's waves start (row n + k_x): row r's are `comps[rows[r] ..
    /// rows[r + 1]]`.
    rows: Vec<usize>,
    fit: KernelFit,
    /// What multiplies the product fields at each output kept, the same at every time:
    /// tabulated once for a sequence of frames ([`Self::keep_outputs`]), else computed
    /// at each output of the frame.
    outputs: Option<Outputs>,
    /// The outputs nearest q = 0, whose difference terms are their pair sums.
    exact: Exact,
    spec: GridSpec,
}

/// The reach of `comps` on a grid of nx × ny.
fn reach_of(comps: &[Component], nx: usize, ny: usize) -> (Reach, Reach) {
    let kx = comps.iter().map(|c| c.n.abs()).max().unwrap_or(0);
    let ky = comps.iter().map(|c| c.m.abs()).max().unwrap_or(0);
    (Reach::of(kx, nx), Reach::of(ky, ny))
}

impl TransformBound {
    pub fn new(comps: Vec<Component>, spec: GridSpec, depth: Option<f64>, fit: KernelFit) -> Self {
        let (nx, ny) = (spec.nx, spec.ny);
        let (lo, hi) = fit.bases.exponents();
        assert!(
            (hi - lo + 2) as usize <= FIELDS && fit.bases.len(0).max(fit.bases.len(1)) <= MAX_NB,
            "the fit's bases exceed the arrays of a row's fields or a cell's groups"
        );
        let reach = reach_of(&comps, nx, ny);
        let setdown = comps
            .iter()
            .map(|c| 4.0 * c.rho * c.rho * self_kernels(c, depth).1)
            .sum();
        let w = (2 * reach.0.k + 1) as usize;
        // The waves by kx row (a stable sort: each row's in the order given).
        let mut comps: Vec<Wave> = comps.iter().map(Wave::from).collect();
        comps.sort_by_key(|c| c.n);
        let mut rows = vec![0usize; w + 1];
        for c in &comps {
            rows[(i64::from(c.n) + reach.0.k) as usize + 1] += 1;
        }
        for r in 0..w {
            rows[r + 1] += rows[r];
        }
        let exact = Exact::new(&comps, reach, (spec, depth), (fit.s_ref, setdown));
        Self {
            outputs: None,
            exact,
            spec,
            comps,
            depth,
            reach,
            plan: Plan::new(reach.0.len, reach.1.len),
            plan32: Plan::new(reach.0.len, reach.1.len),
            pool: Pool::default(),
            pool32: Pool::default(),
            rows,
            ones: Pool::default(),
            fit,
        }
    }

    /// The region of the fit for `comps` of `setup`: their box, the box of the outputs
    /// kept and, below the whole variance, the least E|h̃0|² among them.
    pub fn region(setup: &SpectrumSetup, comps: &[Component], fraction: f64) -> Region {
        let (nx, ny) = (setup.spec.nx, setup.spec.ny);
        let (rx, ry) = reach_of(comps, nx, ny);
        let (dkx, dky) = setup.dk();
        let grid = Box2::of(setup);
        let boxed = |ix: i64, iy: i64| Box2 {
            kx_max: rx.edge(ix, dkx, grid.kx_max, nx),
            ky_max: ry.edge(iy, dky, grid.ky_max, ny),
        };
        let floor = if fraction < 1.0 {
            comps.iter().map(|c| c.p).fold(f64::INFINITY, f64::min)
        } else {
            0.0
        };
        Region {
            waves: boxed(rx.k, ry.k),
            outputs: boxed(rx.o, ry.o),
            floor: if floor.is_finite() { floor } else { 0.0 },
        }
    }

    /// The components of `setup` (its draws; the time is not used) within `cutoff` that
    /// carry `fraction` of the variance there (the pair sum's), the kernels fitted to
    /// their part of the spectrum, and what the sidecar records (the dropped pairs
    /// counted).
    pub fn for_setup(
        setup: &SpectrumSetup,
        fraction: f64,
        cutoff: Option<Cutoff>,
    ) -> (Self, SecondOrderInfo) {
        let all = SecondOrder::within(setup, fraction, cutoff);
        let fit = Self::fit_for(setup, &all);
        Self::with_fit(setup, all, fit)
    }

    /// The kernels fitted to the part of `setup`'s spectrum that `so` pairs.
    pub fn fit_for(setup: &SpectrumSetup, so: &SecondOrder) -> KernelFit {
        let region = Self::region(setup, &so.comps, so.info.fraction);
        KernelFit::new(setup.spectrum, setup.dispersion, region, setup.dk())
    }

    /// The components of `all` through the kernels `fit`, and what the sidecar records.
    pub fn with_fit(
        setup: &SpectrumSetup,
        all: SecondOrder,
        fit: KernelFit,
    ) -> (Self, SecondOrderInfo) {
        let mut info = all.info.clone();
        let depth = all.depth;
        let me = Self::new(all.comps, setup.spec, depth, fit);
        let (sums, diffs) = me.dropped_pairs();
        info.sum_pairs_dropped = sums;
        info.difference_pairs_dropped = diffs;
        info.estimated_rel_rms_error = Some(me.fit.rel_rms_error);
        (me, info)
    }

    /// The occupancy field Σ_i e^{ik_i·x} of the components on the padded grid (py rows
    /// of px).
    fn occupancy(&self, pool: &Pool<f64>) -> Vec<C64> {
        let (px, py) = (self.plan.px, self.plan.py);
        let mut data = pool.take(px * py);
        for c in &self.comps {
            let row = i64::from(c.n).rem_euclid(px as i64) as usize;
            let col = i64::from(c.m).rem_euclid(py as i64) as usize;
            data[row * py + col] += C64::new(1.0, 0.0);
        }
        self.plan.inverse(&mut data, pool);
        data
    }

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
                    let col = i64::from(c.m).rem_euclid(py as i64) as usize;
                    let bi = match pass.twiddle.get(col) {
                        Some(&t) => bi * t,
                        None => bi,
                    };
                    // f(k_i)·x^e·b_i of e = lo, lo + 1, …: one multiplication by x an
                    // exponent.
                    let x = c.s.abs() / self.fit.s_ref;
                    let mut w = bi * (f.of(c) * x.powi(lo));
                    let at = col % len;
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

    /// `add(rows, f, g)` on every row of padded cells (py rows of px): the accumulators'
    /// row, and the row of each field of `fs` and `gs` (the fields of the terms'
    /// factors, each of its exponents lo ..= hi, index e − lo): the transforms' first
    /// stage ([`Self::stage_one`]), the second (along kx) a few rows of y at a time, just
    /// before their products, so that no whole field is held. The first stages of every
    /// P-th row of y at a time ([`Self::passes`]). The same values as the whole fields'
    /// transforms (to rounding; the same bits in one pass). With `last`, the terms' last
    /// products: each row of the accumulators is then transformed along x (the first
    /// stage of their forward transforms, while the row is at hand).
    fn each_cell<T: Real>(
        &self,
        b: &[C64],
        (fs, gs): (Fields, Fields),
        acc: &mut Acc<T>,
        last: bool,
        add: impl Fn(&mut [&mut [Complex<T>]], &[&[C64]], &[&[C64]]) + Sync,
    ) {
        let (plan, _) = T::forward(self);
        const ROWS: usize = 4;
        let (px, py) = (self.plan.px, self.plan.py);
        let kx = self.reach.0.k;
        let same = gs == fs;
        let count = |(_, (lo, hi)): Fields| (hi - lo + 1).max(0) as usize;
        let passes = self.passes(count(fs) + if same { 0 } else { count(gs) });
        let len = py / passes;
        let zero = C64::new(0.0, 0.0);
        let inv_x = &*self.plan.inv_x;
        // Each pass's tasks (ROWS rows of y each, y = P·j + p), each row holding the row
        // of every accumulator.
        type Rows<'a, T> = Vec<&'a mut [Complex<T>]>;
        let mut by_y: Vec<Rows<T>> = (0..py).map(|_| Vec::with_capacity(acc.len())).collect();
        for a in acc.iter_mut() {
            for (y, row) in a.chunks_exact_mut(px).enumerate() {
                by_y[y].push(row);
            }
        }
        let mut work: Vec<Vec<Vec<Rows<T>>>> = (0..passes)
            .map(|_| {
                (0..len.div_ceil(ROWS))
                    .map(|_| Vec::with_capacity(ROWS))
                    .collect()
            })
            .collect();
        for (y, rows) in by_y.into_iter().enumerate() {
            work[y % passes][y / passes / ROWS].push(rows);
        }
        // The kx columns of the components (|n| ≤ k_x, wrapped) and those between them,
        // zero before the second stage.
        let gap = (kx + 1) as usize..(px as i64 - kx) as usize;
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
                // Kx row r = n + k_x (n = −k_x ..= k_x) into column n, wrapped (px >
                // 2k_x + o_x: the wrapped indices never meet).
                for (r, from) in one.chunks_exact(self.row_stride(len)).enumerate() {
                    let col = (r as i64 - kx).rem_euclid(px as i64) as usize;
                    for (jj, &v) in from[j0..j0 + nj].iter().enumerate() {
                        block[jj * px + col] = v;
                    }
                }
                for row in block.chunks_exact_mut(px) {
                    inv_x.process_with_scratch(row, scratch);
                }
            }
        };
        // The transform of a pass's share of the columns, planned once.
        let short = (passes > 1).then(|| FftPlanner::new().plan_fft_inverse(len));
        let inv = short.as_deref().unwrap_or(&*self.plan.inv_y);
        for (p, tasks) in work.into_iter().enumerate() {
            let pass = Pass::new(p, passes, py, inv);
            let fields = |(f, e)| self.stage_one(b, f, e, &pass);
            let f_one = fields(fs);
            let g_one = if same { Vec::new() } else { fields(gs) };
            let g_src = if same { &f_one } else { &g_one };
            tasks.into_par_iter().enumerate().for_each_init(
                || (Vec::new(), Vec::new(), Vec::new(), Vec::new()),
                |(fr, gr, scratch, scratch_t), (c, mut out)| {
                    let at_rows = (c * ROWS, out.len());
                    rows_of(&f_one, at_rows, fr, scratch);
                    if !same {
                        rows_of(g_src, at_rows, gr, scratch);
                    }
                    let gr = if same { &*fr } else { &*gr };
                    let (nf, ng, nj) = (f_one.len(), g_src.len(), out.len());
                    for (jj, rows) in out.iter_mut().enumerate() {
                        let at = |l: usize| (l * nj + jj) * px..(l * nj + jj + 1) * px;
                        let fv: [&[C64]; FIELDS] =
                            std::array::from_fn(|l| if l < nf { &fr[at(l)] } else { &[] });
                        let gv: [&[C64]; FIELDS] =
                            std::array::from_fn(|l| if l < ng { &gr[at(l)] } else { &[] });
                        add(rows, &fv, &gv);
                        if last {
                            for row in rows.iter_mut() {
                                plan.forward_x(row, scratch_t);
                            }
                        }
                    }
                },
            );
            self.ones.give_all(f_one.into_iter().chain(g_one));
        }
    }

    /// The passes over y of [`Self::each_cell`] for `ne` first-stage fields: the least
    /// divisor of py that holds at most [`PASS_BYTES_PER_CELL`] bytes an output cell of
    /// them at once (each pass folds the components onto its share of the columns and
    /// transforms that: the passes together cost about one whole transform).
    fn passes(&self, ne: usize) -> usize {
        let py = self.plan.py;
        let held = ne * (self.rows.len() - 1) * self.row_stride(py) * size_of::<C64>();
        let cap = PASS_BYTES_PER_CELL * self.spec.nx * self.spec.ny;
        let least = held.div_ceil(cap.max(1)).clamp(1, py);
        (least..=py).find(|d| py % d == 0).unwrap_or(py)
    }

    /// The unordered pairs (self-pairs included) whose sum, and whose difference, falls
    /// off the grid: the pair counts at every output, from the transform of the squared
    /// occupancy field (the outputs the transforms leave out).
    pub fn dropped_pairs(&self) -> (u64, u64) {
        if self.reach.0.all_on_grid() && self.reach.1.all_on_grid() {
            return (0, 0);
        }
        let (nx, ny) = (self.spec.nx as i64, self.spec.ny as i64);
        let (px, py) = (self.plan.px, self.plan.py);
        let pool = Pool::default();
        let a = self.occupancy(&pool);
        let mut acc: Vec<C64> = a
            .iter()
            .map(|x| C64::new((x * x).re, x.norm_sqr()))
            .collect();
        drop(a);
        self.plan.forward(&mut acc, &pool);
        let (mut sums, mut diffs) = (0.0f64, 0.0f64);
        for row in 0..px {
            let n = signed_index(row, px);
            for col in 0..py {
                let m = signed_index(col, py);
                if on_grid(n, nx as usize) && on_grid(m, ny as usize) {
                    continue;
                }
                let here = acc[row * py + col];
                let there = acc[(-n).rem_euclid(px as i64) as usize * py
                    + (-m).rem_euclid(py as i64) as usize]
                    .conj();
                sums += 0.5 * (here + there).re;
                diffs += (0.5 * (here - there) * C64::new(0.0, -1.0)).re;
            }
        }
        let norm = (px * py) as f64;
        let doubled_off = self
            .comps
            .iter()
            .filter(|c| {
                let (n, m) = (i64::from(c.n), i64::from(c.m));
                !(on_grid(2 * n, self.spec.nx) && on_grid(2 * m, self.spec.ny))
            })
            .count() as u64;
        let sums = (sums / norm).round() as u64;
        let diffs = (diffs / norm).round() as u64;
        ((sums + doubled_off) / 2, diffs / 2)
    }

    /// Adds the bound waves at `setup`'s time to `half`.
    pub fn add_to(&self, setup: &SpectrumSetup, half: &mut HalfSpectrum) {
        let b: Vec<C64> = self
            .comps
            .iter()
            .map(|c| {
                let wt = setup.omega_t(c.kx, c.ky);
                let (s, co) = fastmath::sin_cos(c.phi - wt);
                C64::new(2.0 * c.rho * co, 2.0 * c.rho * s)
            })
            .collect();
        match self.depth {
            Some(_) => self.add_as::<f64>(&b, half),
            None => self.add_as::<f32>(&b, half),
        }
        // Nothing held between frames (the linear field's own arrays come next).
        self.pool.clear();
        self.pool32.clear();
        self.ones.clear();
    }

    /// [`Self::add_to`] with the amplitudes `b` at the time, accumulators of precision `T`.
    fn add_as<T: Real>(&self, b: &[C64], half: &mut HalfSpectrum) {
        let (nx, ny) = (self.spec.nx, self.spec.ny);
        let (px, py) = (self.plan.px, self.plan.py);
        let finite = self.depth.is_some();
        let (plan, pool) = T::forward(self);
        // Only the kx rows of the outputs kept (|n| ≤ o_x) are transformed.
        let ox = self.reach.0.o;
        let kept_row = |row: usize| signed_index(row, px).abs() <= ox;
        let transform = |mut acc: Vec<Complex<T>>| {
            plan.forward_y_rows(&mut acc, &kept_row, pool);
            acc
        };
        // The fields of exponent e are at index e − lo.
        let bases = &self.fit.bases;
        let (lo, hi) = bases.exponents();
        let at = |e: i32| (e - lo) as usize;
        let terms: Vec<Vec<(usize, f64)>> = (0..=bases.diff_powers)
            .map(|m| expansion(m).collect())
            .collect();
        // A factor with itself (the B terms): Re(f_a conj f_b) = Re(f_b conj f_a), and the
        // expansion's weights are symmetric (w_a = w_{2m−a}), so the terms a < m are taken
        // twice and a > m left out.
        let halves: Vec<Vec<(usize, f64)>> = terms
            .iter()
            .enumerate()
            .map(|(m, t)| {
                t.iter()
                    .filter(|&&(a, _)| a <= m)
                    .map(|&(a, w)| (a, if a < m { 2.0 * w } else { w }))
                    .collect()
            })
            .collect();
        let layout = Layout::new(bases.len(0), bases.len(1));
        let groups = layout.slots.len();
        // Products: re = sum term Re(A_f A_g), im = difference term Re(A_f conj A_g).
        // Accumulator 0: the separable part B + R_i + R_j (sum re, difference im); 1 + g:
        // the weighted parts of the B terms (multiplied by 2T c) in `layout`'s slot g, and
        // at finite depth those of the S·A terms (by c, in `sa`, slot g at g).
        let mut acc: Acc<T> = (0..=groups).map(|_| pool.take(px * py)).collect();
        let types: &[(Factor, f64)] = &[(Factor::X, 1.0), (Factor::Y, 1.0), (Factor::V, -1.0)];
        for &(f, sign) in types {
            let fe = (f, (lo, hi));
            // (V's products are the last of the B terms.)
            self.each_cell(b, (fe, fe), &mut acc, f == Factor::V, |c, p, _| {
                if f == Factor::V {
                    // The separable part's R_i + R_j: with x = |s|/s_p, R = s² is
                    // s_p·(s·x) and 1 is (s/x)/s_p, the V fields of exponents 1 and −1.
                    let rows = c[0].iter_mut().zip(p[at(1)]).zip(p[at(-1)]);
                    for ((c, r), o) in rows {
                        c.re += T::of(2.0 * (r * o).re);
                        c.im += T::of(2.0 * (r * o.conj()).re);
                    }
                }
                // The separable part's B.
                for (c, p0) in c[0].iter_mut().zip(p[at(0)]) {
                    c.re += T::of(sign * (p0 * p0).re);
                    c.im += T::of((p0 * p0.conj()).re);
                }
                for (f, &(g, im)) in bases.sum.iter().zip(&layout.sum) {
                    for &(w, u, v) in &f.monomials {
                        let k = sign * w;
                        for ((c, a), b) in c[1 + g].iter_mut().zip(p[at(u)]).zip(p[at(v)]) {
                            *part(c, im) += T::of(k * (a * b).re);
                        }
                    }
                }
                let mut sum = Vec::new();
                for (m, (t, &(g, im))) in halves.iter().zip(&layout.diff).enumerate() {
                    let p = &p[at(0)..];
                    power_term(c[1 + g], p, p, t, m, (1.0, im), &mut sum);
                }
            });
        }
        // (The first stages are done with until the finite-depth terms.)
        self.ones.clear();
        // The B terms' transforms gathered at the kept outputs, then given back (the
        // finite-depth S·A terms reuse their arrays).
        let ox_oy = (ox, self.reach.1.o);
        let columns = (2 * ox_oy.1 + 1).max(0) as usize;
        let mut kept = vec![C64::new(0.0, 0.0); (ox + 1).max(0) as usize * columns];
        let transformed: Acc<T> = acc.into_iter().map(transform).collect();
        self.gather(&mut kept, &transformed, &layout, true);
        pool.give_all(transformed);
        if finite {
            let mut sa_acc: Acc<T> = (0..groups).map(|_| pool.take(px * py)).collect();
            // (The B terms' arrays left over are not held through the S·A terms.)
            pool.clear();
            // S·A = Q_i + Q_j ± ((Q/s)_i s_j + s_i (Q/s)_j) (+ in the sum term, − in the
            // difference), each with its mirror (the expansion is symmetric in a ↔ 2m − a).
            // With x = |s|/s_p, (Q/s)·x^u is Q·x^{u−1}/s_p and s·x^v is s_p·x^{v+1}: the
            // fields of Q (W1) at the exponents lo − 1 ..= hi and of 1 (W0) at lo ..= hi + 1
            // give both products (the s_p cancel).
            let (q_e, one_e) = ((Factor::W1, (lo - 1, hi)), (Factor::W0, (lo, hi + 1)));
            self.each_cell(b, (q_e, one_e), &mut sa_acc, true, |c, q, one| {
                // Q at exponent e is field e − lo + 1, 1 at e field e − lo.
                let q_at = |e: i32| q[(e - lo + 1) as usize];
                let one_at = |e: i32| one[(e - lo) as usize];
                for (f, &(g, im)) in bases.sum.iter().zip(&layout.sum) {
                    for &(w, u, v) in &f.monomials {
                        let plain =
                            (q_at(u).iter().zip(one_at(v))).zip(q_at(v).iter().zip(one_at(u)));
                        let shifted = (q_at(u - 1).iter().zip(one_at(v + 1)))
                            .zip(q_at(v - 1).iter().zip(one_at(u + 1)));
                        for (cell, (((a, b), (d, e)), ((f, g), (h, i)))) in
                            c[g].iter_mut().zip(plain.zip(shifted))
                        {
                            let p = (a * b).re + (d * e).re + (f * g).re + (h * i).re;
                            *part(cell, im) += T::of(w * p);
                        }
                    }
                }
                let mut sum = Vec::new();
                for (m, (t, &(g, im))) in terms.iter().zip(&layout.diff).enumerate() {
                    // Q_a 1_{2m−a}, then (Q/s)_a s_{2m−a}: Q_{a−1} 1_{2m−a+1}.
                    let (q0, q1) = (&q[at(0) + 1..], &q[at(0)..]);
                    power_term(c[g], q0, &one[at(0)..], t, m, (2.0, im), &mut sum);
                    power_term(c[g], q1, &one[at(1)..], t, m, (-2.0, im), &mut sum);
                }
            });
            self.ones.clear();
            let sa: Acc<T> = sa_acc.into_iter().map(transform).collect();
            self.gather(&mut kept, &sa, &layout, false);
        }
        // The kept outputs into the half spectrum: lines n ≤ o_x, columns |m| ≤ o_y (on
        // the grid), with the exact difference terms nearest q = 0 (the set-down at 0).
        let oy = ox_oy.1;
        let exact = self.exact.values(&self.comps, b);
        let norm = 0.25 / (px * py) as f64;
        half.data
            .par_chunks_mut(ny)
            .zip(kept.par_chunks(columns.max(1)))
            .enumerate()
            .for_each(|(n, (line, sums))| {
                debug_assert!(on_grid(n as i64, nx));
                // This line's exact outputs (in the order of n, then m).
                let from = exact.partition_point(|e| e.0 < n as i64);
                let to = exact.partition_point(|e| e.0 <= n as i64);
                let exact = &exact[from..to];
                for (j, &h) in sums.iter().enumerate() {
                    let m = j as i64 - oy;
                    let mut h = h * norm;
                    if let Some(&(_, _, e)) = exact.iter().find(|e| e.1 == m) {
                        h += e;
                    }
                    line[m.rem_euclid(ny as i64) as usize] +=
                        Complex::new(h.re as f32, h.im as f32);
                }
            });
    }
}

mod exact;
mod grid;
mod outputs;
mod products;
#[cfg(test)]
mod tests;
