//! The product fields of the fitted frame: the expansion of the difference powers, where
//! each weighted real product field goes (two to a complex accumulator), and the
//! precision of the accumulators and their forward transforms.

use rustfft::FftNum;
use rustfft::num_complex::Complex;

use super::super::C64;
use super::super::fit::binomial;
use super::TransformBound;
use super::grid::{Plan, Pool};

/// δ^{2m} = (x_i − x_j)^{2m} = Σ_a w_a x_i^a x_j^{2m−a}: the terms (a, w_a).
pub(super) fn expansion(m: usize) -> impl Iterator<Item = (usize, f64)> {
    let n = 2 * m;
    (0..=n).map(move |a| {
        let c = binomial(n, a);
        (a, if a % 2 == 0 { c } else { -c })
    })
}

/// The accumulators of a share of the padded cells (rows of px), one array an
/// accumulator, each then transformed in place: the B terms' (the separable part, then
/// each group; precision `B`) and, at finite depth, the S·A terms' (each group; `S`).
pub(super) struct Acc<B, S> {
    pub(super) b: Vec<Vec<Complex<B>>>,
    pub(super) sa: Vec<Vec<Complex<S>>>,
}

/// The precision of the accumulators and their forward transforms
/// ([`TransformBound::b_single`]): the S·A terms' double, since they cancel to within
/// single precision's rounding (and the difference powers' expansion of δ^{2m} amplifies
/// it at small |q|); the B terms' single, except where the fit needs the fuller
/// difference basis (shallow water, where that amplification is largest). The products
/// are formed in double precision either way; tested against the pair sum of the same
/// kernels.
pub(super) trait Real: FftNum + std::ops::AddAssign {
    fn of(x: f64) -> Self;
    fn wide(self) -> f64;
    /// The forward transforms and the arrays of this precision.
    fn forward(tb: &TransformBound) -> (&Plan<Self>, &Pool<Self>);
}

impl Real for f64 {
    #[inline]
    fn of(x: f64) -> Self {
        x
    }
    #[inline]
    fn wide(self) -> f64 {
        self
    }
    fn forward(tb: &TransformBound) -> (&Plan<Self>, &Pool<Self>) {
        (&tb.plan, &tb.pool)
    }
}

impl Real for f32 {
    #[inline]
    fn of(x: f64) -> Self {
        x as f32
    }
    #[inline]
    fn wide(self) -> f64 {
        f64::from(self)
    }
    fn forward(tb: &TransformBound) -> (&Plan<Self>, &Pool<Self>) {
        (&tb.plan32, &tb.pool32)
    }
}

/// The real (`im` false) or imaginary part of `c`.
#[inline]
pub(super) fn part<T>(c: &mut Complex<T>, im: bool) -> &mut T {
    if im { &mut c.im } else { &mut c.re }
}

/// A real product field: the sum term's basis function l or the difference power m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Part {
    Sum(usize),
    Diff(usize),
}

/// Where the weighted real product fields go, two to a complex accumulator (its real and
/// imaginary parts, told apart after the forward transform by Hermitian symmetry): sum
/// function l beside difference power l while both bases have one, the rest of the
/// longer basis two by two.
pub(super) struct Layout {
    /// The parts of each weighted accumulator.
    pub(super) slots: Vec<[Option<Part>; 2]>,
    /// Accumulator and part (imaginary?) of each sum function, of each difference power.
    pub(super) sum: Vec<(usize, bool)>,
    pub(super) diff: Vec<(usize, bool)>,
}

impl Layout {
    pub(super) fn new(n_sum: usize, n_diff: usize) -> Self {
        let mut slots: Vec<[Option<Part>; 2]> = (0..n_sum.min(n_diff))
            .map(|l| [Some(Part::Sum(l)), Some(Part::Diff(l))])
            .collect();
        let rest: Vec<Part> = (n_diff..n_sum)
            .map(Part::Sum)
            .chain((n_sum..n_diff).map(Part::Diff))
            .collect();
        slots.extend(rest.chunks(2).map(|p| [Some(p[0]), p.get(1).copied()]));
        let (mut sum, mut diff) = (vec![(0, false); n_sum], vec![(0, false); n_diff]);
        for (g, slot) in slots.iter().enumerate() {
            for (k, p) in slot.iter().enumerate() {
                match p {
                    Some(Part::Sum(l)) => sum[*l] = (g, k == 1),
                    Some(Part::Diff(m)) => diff[*m] = (g, k == 1),
                    None => {}
                }
            }
        }
        Self { slots, sum, diff }
    }
}

/// A value of `T` in double precision.
#[inline]
pub(super) fn wide<T: Real>(v: Complex<T>) -> C64 {
    C64::new(v.re.wide(), v.im.wide())
}

/// `out`'s real (`im` false) or imaginary part += Σ_a w_a Re(f_a conj g_{2m−a}) at each
/// cell of a row, over the terms of [`expansion`] (f, g the rows of the fields of
/// exponents 0, 1, …), summed in the terms' order, then scaled (`sum` a row of scratch).
#[inline]
pub(super) fn power_term<T: Real>(
    out: &mut [Complex<T>],
    f: &[&[C64]],
    g: &[&[C64]],
    terms: &[(usize, f64)],
    m: usize,
    (scale, im): (f64, bool),
    sum: &mut Vec<f64>,
) {
    sum.clear();
    sum.resize(out.len(), 0.0);
    for &(a, w) in terms {
        for ((d, x), y) in sum.iter_mut().zip(f[a]).zip(g[2 * m - a]) {
            *d += w * (x * y.conj()).re;
        }
    }
    for (o, d) in out.iter_mut().zip(sum.iter()) {
        *part(o, im) += T::of(scale * d);
    }
}
