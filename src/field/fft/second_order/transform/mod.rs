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

use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

use exact::Exact;
use grid::{Plan, Pool, Reach};
use outputs::{Outputs, Put};
use products::{Acc, Layout, Real, expansion, part, power_term};
use stages::{AccRows, FIELDS, Factor};

use super::fit::{Box2, KernelFit, MAX_NB, Region};
use super::{
    C64, Component, Cutoff, HalfSpectrum, SecondOrder, SecondOrderInfo, SpectrumSetup, on_grid,
    self_kernels,
};
use crate::fastmath;
use crate::grid::{GridSpec, bin_index, signed_index};

/// What a frame reads of a component (40 bytes instead of a [`Component`]'s 88: the
/// components are held for the sequence; the wavevector is its indices').
struct Wave {
    n: i32,
    m: i32,
    s: f64,
    q: f64,
    rho: f64,
    phi: f64,
}

impl Wave {
    /// The wavevector (k_x, k_y) on the grid of `spec` (the component's, to the bit).
    #[inline]
    fn k(&self, spec: GridSpec) -> (f64, f64) {
        spec.wavevector(i64::from(self.n), i64::from(self.m))
    }
}

impl From<&Component> for Wave {
    fn from(c: &Component) -> Self {
        Self {
            n: i32::try_from(c.n).expect("a grid index"),
            m: i32::try_from(c.m).expect("a grid index"),
            s: c.s,
            q: c.q,
            rho: c.rho,
            phi: c.phi,
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
    /// The accumulators' bytes an output cell a pass over y may hold
    /// ([`stages::ACC_BYTES_PER_CELL`]; the tests set others).
    acc_budget: usize,
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
        let mut waves: Vec<Wave> = comps.iter().map(Wave::from).collect();
        // (The components are done with: not held beside the waves for the rest.)
        drop(comps);
        waves.sort_by_key(|c| c.n);
        let mut rows = vec![0usize; w + 1];
        for c in &waves {
            rows[(i64::from(c.n) + reach.0.k) as usize + 1] += 1;
        }
        for r in 0..w {
            rows[r + 1] += rows[r];
        }
        let exact = Exact::new(&waves, reach, (spec, depth), (fit.s_ref, setdown));
        Self {
            outputs: None,
            exact,
            spec,
            comps: waves,
            depth,
            reach,
            plan: Plan::new(reach.0.len, reach.1.len),
            plan32: Plan::new(reach.0.len, reach.1.len),
            pool: Pool::default(),
            pool32: Pool::default(),
            rows,
            ones: Pool::default(),
            fit,
            acc_budget: stages::ACC_BYTES_PER_CELL,
        }
    }

    /// The region of the fit for `comps` of `setup`: their box, the box of the outputs
    /// kept, below the whole variance the least E|h̃0|² among them, and their largest |k|.
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
            k_max: comps.iter().map(|c| c.k).fold(0.0, f64::max),
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
        info.difference_powers = Some(me.fit.bases.diff_powers);
        (me, info)
    }

    /// The occupancy field Σ_i e^{ik_i·x} of the components on the padded grid (py rows
    /// of px).
    fn occupancy(&self, pool: &Pool<f64>) -> Vec<C64> {
        let (px, py) = (self.plan.px, self.plan.py);
        let mut data = pool.take(px * py);
        for c in &self.comps {
            let row = bin_index(i64::from(c.n), px);
            let col = bin_index(i64::from(c.m), py);
            data[row * py + col] += C64::new(1.0, 0.0);
        }
        self.plan.inverse(&mut data, pool);
        data
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
                let there = acc[bin_index(-n, px) * py + bin_index(-m, py)].conj();
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
                let (kx, ky) = c.k(self.spec);
                let wt = setup.omega_t(kx, ky);
                let (s, co) = fastmath::sin_cos(c.phi - wt);
                C64::new(2.0 * c.rho * co, 2.0 * c.rho * s)
            })
            .collect();
        if self.b_single() {
            self.add_as::<f32, f64>(&b, half);
        } else {
            self.add_as::<f64, f64>(&b, half);
        }
        // Nothing held between frames (the linear field's own arrays come next).
        self.pool.clear();
        self.pool32.clear();
        self.ones.clear();
    }

    /// The B terms' accumulators are single precision ([`products::Real`]): in deep
    /// water, and at finite depth where the lighter difference basis serves.
    fn b_single(&self) -> bool {
        self.depth.is_none() || self.fit.bases.light_difference()
    }

    /// The accumulators of a frame: the B terms' (the separable part and the groups of
    /// the bases' [`Layout`]), the S·A terms' (the groups, at finite depth), and the
    /// bytes of them all a padded cell (double precision 16 a complex value, single 8).
    fn accumulators(&self) -> (usize, usize, usize) {
        let bases = &self.fit.bases;
        let groups = Layout::new(bases.len(0), bases.len(1)).slots.len();
        let n_b = groups + 1;
        let n_sa = if self.depth.is_some() { groups } else { 0 };
        let b_cell = if self.b_single() { 8 } else { 16 };
        (n_b, n_sa, n_b * b_cell + n_sa * 16)
    }

    /// [`Self::add_to`] with the amplitudes `b` at the time, the B terms' accumulators of
    /// precision `B`, the S·A terms' of `S`.
    fn add_as<B: Real, S: Real>(&self, b: &[C64], half: &mut HalfSpectrum) {
        let (nx, ny) = (self.spec.nx, self.spec.ny);
        let (px, py) = (self.plan.px, self.plan.py);
        let finite = self.depth.is_some();
        let ((plan_b, pool_b), (plan_s, pool_s)) = (B::forward(self), S::forward(self));
        let ox = self.reach.0.o;
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
        // Products: re = sum term Re(A_f A_g), im = difference term Re(A_f conj A_g).
        // Accumulator 0: the separable part B + R_i + R_j (sum re, difference im); 1 + g:
        // the weighted parts of the B terms (multiplied by 2T c) in `layout`'s slot g, and
        // at finite depth those of the S·A terms (by c, in `sa`, slot g at g).
        // `scale` multiplies every product (the V fields read from those of W0: s_p²).
        let b_terms =
            |f: Factor, (sign, scale): (f64, f64), c: &mut [&mut [Complex<B>]], p: &[&[C64]]| {
                if f == Factor::V {
                    // The separable part's R_i + R_j: with x = |s|/s_p, R = s² is
                    // s_p·(s·x) and 1 is (s/x)/s_p, the V fields of exponents 1 and −1.
                    let rows = c[0].iter_mut().zip(p[at(1)]).zip(p[at(-1)]);
                    for ((c, r), o) in rows {
                        c.re += B::of(2.0 * scale * (r * o).re);
                        c.im += B::of(2.0 * scale * (r * o.conj()).re);
                    }
                }
                // The separable part's B.
                for (c, p0) in c[0].iter_mut().zip(p[at(0)]) {
                    c.re += B::of(sign * scale * (p0 * p0).re);
                    c.im += B::of(scale * (p0 * p0.conj()).re);
                }
                for (f, &(g, im)) in bases.sum.iter().zip(&layout.sum) {
                    for &(w, u, v) in &f.monomials {
                        let k = sign * scale * w;
                        for ((c, a), b) in c[1 + g].iter_mut().zip(p[at(u)]).zip(p[at(v)]) {
                            *part(c, im) += B::of(k * (a * b).re);
                        }
                    }
                }
                let mut sum = Vec::new();
                for (m, (t, &(g, im))) in halves.iter().zip(&layout.diff).enumerate() {
                    let p = &p[at(0)..];
                    power_term(c[1 + g], p, p, t, m, (scale, im), &mut sum);
                }
            };
        // The accumulators a share of the rows of y at a time ([`Passes`]): the B terms'
        // (`groups` + 1: the separable part and the weighted parts, multiplied by 2T c),
        // and at finite depth the S·A terms' (`groups`, by c). `run(a, acc)` adds the
        // products of the first stages' passes of share a, whose transforms along y (at
        // the share's length) are then gathered at the kept outputs.
        let (n_b, n_sa, acc_bytes) = self.accumulators();
        // The passes over y: in deep water those of a B factor's fields; at finite depth
        // those of the S·A terms' two factors, for the B terms' too (the first stages'
        // arrays, reused from pass to pass, then all of one length).
        let fields = if finite {
            2 * (hi - lo + 2)
        } else {
            hi - lo + 1
        };
        let passes = self.passes(fields as usize, acc_bytes);
        let len = passes.acc_len;
        let shares = passes.acc > 1;
        let short_b = shares.then(|| FftPlanner::<B>::new().plan_fft_forward(len));
        let short_s = shares.then(|| FftPlanner::<S>::new().plan_fft_forward(len));
        let fwd_b = short_b.as_deref().unwrap_or(plan_b.forward_y());
        let fwd_s = short_s.as_deref().unwrap_or(plan_s.forward_y());
        // The kept outputs (lines 0 ..= o_x, columns −o_y ..= o_y), each share's added: in
        // deep water straight to the half spectrum (single precision, as the B terms'
        // transforms are: no error beyond theirs); at finite depth in double precision
        // first (the S·A terms' shares cancel beyond single precision), made once the first
        // share's products are done (not held beside its first stages).
        let norm = 0.25 / (px * py) as f64;
        let oy = self.reach.1.o;
        let columns = (2 * oy + 1).max(0) as usize;
        let lines = (ox + 1).max(0) as usize;
        debug_assert!(on_grid(ox, nx));
        let mut kept = Vec::new();
        let mut add_share = |a: usize, acc: &Acc<B, S>| {
            let at = (a, &passes);
            if finite {
                kept.resize(lines * columns, C64::new(0.0, 0.0));
                let put: Put<C64> = &|t, h| *t += h;
                self.gather(
                    (&mut kept[..], columns, put),
                    acc,
                    &layout,
                    at,
                    (fwd_b, fwd_s),
                );
            } else {
                let put: Put<Complex<f32>> = &|t, h| {
                    let h = h * norm;
                    *t += Complex::new(h.re as f32, h.im as f32);
                };
                let to = (&mut half.data[..lines * ny], ny, put);
                self.gather(to, acc, &layout, at, (fwd_b, fwd_s));
            }
        };
        let mut in_shares = |run: &dyn Fn(usize, &mut Acc<B, S>)| {
            for a in 0..passes.acc {
                let mut acc = Acc {
                    b: (0..n_b).map(|_| pool_b.take(px * len)).collect(),
                    sa: (0..n_sa).map(|_| pool_s.take(px * len)).collect(),
                };
                run(a, &mut acc);
                if a + 1 == passes.acc {
                    // (The first stages are done with.)
                    self.ones.clear();
                }
                add_share(a, &acc);
                pool_b.give_all(acc.b);
                pool_s.give_all(acc.sa);
            }
        };
        // The passes of share a.
        let of_share = |a: usize| (a..passes.count).step_by(passes.acc);
        // The B terms of the fields of k_x/s and k_y/s, each factor's products in each
        // pass (never the last: those of s follow).
        let xy = |a: usize, acc: &mut Acc<B, S>| {
            for p in of_share(a) {
                for f in [Factor::X, Factor::Y] {
                    let fe = (f, (lo, hi));
                    self.each_cell(b, (fe, fe), ((p, &passes), acc), false, |(c, _), q, _| {
                        b_terms(f, (1.0, 1.0), c, q)
                    });
                }
            }
        };
        if !finite {
            // Deep water: the V fields (s) their own, the last products.
            in_shares(&|a, acc| {
                xy(a, acc);
                for p in of_share(a) {
                    let fe = (Factor::V, (lo, hi));
                    self.each_cell(b, (fe, fe), ((p, &passes), acc), true, |(c, _), q, _| {
                        b_terms(Factor::V, (-1.0, 1.0), c, q)
                    });
                }
            });
        } else {
            // S·A = Q_i + Q_j ± ((Q/s)_i s_j + s_i (Q/s)_j) (+ in the sum term, − in the
            // difference), each with its mirror (the expansion is symmetric in a ↔ 2m − a).
            // With x = |s|/s_p, (Q/s)·x^u is Q·x^{u−1}/s_p and s·x^v is s_p·x^{v+1}: the
            // fields of Q (W1) at the exponents lo − 1 ..= hi and of 1 (W0) at lo ..= hi + 1
            // give both products (the s_p cancel). The B terms' V fields are those of W0
            // at the exponent above, times s_p: their products are taken in the same pass.
            let (q_e, one_e) = ((Factor::W1, (lo - 1, hi)), (Factor::W0, (lo, hi + 1)));
            let s_p2 = self.fit.s_ref * self.fit.s_ref;
            let sa_terms = |(cb, c): AccRows<B, S>, q: &[&[C64]], one: &[&[C64]]| {
                b_terms(Factor::V, (-1.0, s_p2), cb, &one[1..]);
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
                            *part(cell, im) += S::of(w * p);
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
            };
            in_shares(&|a, acc| {
                xy(a, acc);
                for p in of_share(a) {
                    self.each_cell(b, (q_e, one_e), ((p, &passes), acc), true, sa_terms);
                }
            });
        }
        // (The accumulators are done with: freed before the exact outputs' inputs are made.)
        pool_b.clear();
        pool_s.clear();
        // Finite depth: the kept outputs into the half spectrum (column m at m mod ny).
        for (line, sums) in half.data.chunks_mut(ny).zip(kept.chunks(columns.max(1))) {
            for m in -oy..=oy {
                let h = sums[bin_index(m, columns)] * norm;
                line[bin_index(m, ny)] += Complex::new(h.re as f32, h.im as f32);
            }
        }
        // The exact difference terms nearest q = 0 (the set-down at 0).
        for (n, m, e) in self.exact.values(&self.comps, b, self.spec) {
            let at = n as usize * ny + bin_index(m, ny);
            half.data[at] += Complex::new(e.re as f32, e.im as f32);
        }
    }
}

mod exact;
mod grid;
mod outputs;
mod products;
mod stages;
#[cfg(test)]
mod tests;
