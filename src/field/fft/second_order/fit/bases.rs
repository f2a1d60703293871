//! The fit's bases: the functions of the two waves whose fitted coefficients make G̃, the
//! sum term's (products of powers of |s|/s_p in deep water, the terms of the Neumann
//! series at finite depth) and the difference term's powers (δ²/T)^m / T.

use super::super::Component;
use super::{MAX_NB, POWERS};

/// The deep-water sum basis: the exponents u of w_u(s) = (|s|/s_p)^u whose symmetric
/// products (u ≤ v) it takes.
const DEEP_EXPONENTS: [i32; 3] = [-1, 0, 1];
/// The powers m ≤ M of the difference term's basis (δ²/T)^m / T: deep water, finite depth
/// (the fuller basis), and finite depth where the fit's estimate with it is within what
/// `auto` accepts ([`crate::config::AUTO_MAX_ESTIMATE`]; two fields a factor fewer).
const DEEP_DIFF_POWERS: usize = 3;
const FINITE_DIFF_POWERS: usize = 4;
pub(super) const FINITE_LIGHT_DIFF_POWERS: usize = 3;
/// The order of the finite-depth sum basis (the terms of its Neumann series, m ≤ M).
pub(super) const FINITE_NEUMANN_ORDER: usize = 3;

/// One function of the sum term's basis: (T/s_p²)^`t_power` · Σ w·½[x_i^u x_j^v +
/// x_i^v x_j^u] over its `monomials` (w, u, v), x = |s|/s_p.
#[derive(Debug, Clone, PartialEq)]
pub struct SumTerm {
    pub t_power: i32,
    pub monomials: Vec<(f64, i32, i32)>,
}

/// The sum-term basis of deep water: the symmetric products ½[w_u(s_i)w_v(s_j) +
/// w_v(s_i)w_u(s_j)], u ≤ v ∈ [`DEEP_EXPONENTS`]. In deep water collinear pairs have
/// G = 1/(2 s_i s_j) exactly (u = v = −1), the far pairs tend to it.
fn product_basis() -> Vec<SumTerm> {
    let e = DEEP_EXPONENTS;
    let mut v = Vec::new();
    for a in 0..e.len() {
        for b in a..e.len() {
            v.push(SumTerm {
                t_power: 0,
                monomials: vec![(1.0, e[a], e[b])],
            });
        }
    }
    v
}

/// The binomial coefficient C(n, k) (exact in f64 for the small n of the bases).
pub fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

/// The sum-term basis of finite depth: the terms of the Neumann series of
/// G = 1/(2 s_i s_j + P − T), P = R_i + R_j = s_i² + s_j²,
///
/// G = Σ_m (T − P)^m / (2 s_i s_j)^{m+1} = Σ_m Σ_{a ≤ m} C(m, a) (−P)^a T^{m−a} / (2 s_i s_j)^{m+1},
///
/// each (m, a) a function of the basis with its own fitted coefficient:
/// (T/s_p²)^{m−a} (x_i² + x_j²)^a / (x_i x_j)^{m+1} = (T/s_p²)^{m−a} Σ_b C(a, b)
/// x_i^{2b−m−1} x_j^{2(a−b)−m−1}. In shallow water the collinear pairs come near the
/// sum-frequency resonance (2 s_i s_j + P − T → 2 s_i s_j·2 tanh²kd/(1 + tanh²kd) for two
/// equal waves), where products of plain powers of s cannot follow G; the series in
/// (T − P)/(2 s_i s_j) (−0.53 there at 0.1 λp) can. The monomials b and a − b are
/// one another's mirror (u ↔ v) with the same weight, and a monomial is symmetric in
/// u ↔ v: each pair is one monomial of twice the weight (b < a/2; b = a/2 alone), so
/// that the transforms form each product once.
fn neumann_basis(order: usize) -> Vec<SumTerm> {
    let mut v = Vec::new();
    for m in 0..=order {
        for a in 0..=m {
            let (m_i, a_i) = (m as i32, a as i32);
            let monomials = (0..=a / 2)
                .map(|b| {
                    let b_i = b as i32;
                    let w = binomial(a, b) * if 2 * b < a { 2.0 } else { 1.0 };
                    (w, 2 * b_i - m_i - 1, 2 * (a_i - b_i) - m_i - 1)
                })
                .collect();
            v.push(SumTerm {
                t_power: m_i - a_i,
                monomials,
            });
        }
    }
    v
}

/// The bases of the two terms: the sum term's functions, the difference term's powers
/// (δ²/T)^m / T, m ≤ `diff_powers`.
#[derive(Debug, Clone, PartialEq)]
pub struct Bases {
    pub sum: Vec<SumTerm>,
    pub diff_powers: usize,
    /// The least and largest exponent of the sum basis's monomials.
    sum_exponents: (i32, i32),
}

impl Bases {
    /// Deep water: the products of the exponents −1, 0, 1, powers m ≤ 3; finite depth: the
    /// Neumann series of order 3, powers m ≤ 4.
    pub fn for_depth(depth: Option<f64>) -> Self {
        let (sum, diff_powers) = match depth {
            None => (product_basis(), DEEP_DIFF_POWERS),
            Some(_) => (neumann_basis(FINITE_NEUMANN_ORDER), FINITE_DIFF_POWERS),
        };
        let each = sum.iter().flat_map(|t| t.monomials.iter());
        let lo = each.clone().map(|&(_, u, v)| u.min(v)).min().unwrap_or(0);
        let hi = each.map(|&(_, u, v)| u.max(v)).max().unwrap_or(0);
        Self {
            sum,
            diff_powers,
            sum_exponents: (lo, hi),
        }
    }

    /// The same sum basis with the difference powers m ≤ `diff_powers`.
    pub fn with_diff_powers(self, diff_powers: usize) -> Self {
        Self {
            diff_powers,
            ..self
        }
    }

    /// The difference powers reach no further than the lighter finite-depth basis's
    /// (taken where its estimate serves): where the amplification of the powers'
    /// expansion at small |q| is smallest.
    pub fn light_difference(&self) -> bool {
        self.diff_powers <= FINITE_LIGHT_DIFF_POWERS
    }

    /// The number of functions of term 0 (sum) or 1 (difference).
    pub fn len(&self, term: usize) -> usize {
        if term == 0 {
            self.sum.len()
        } else {
            self.diff_powers + 1
        }
    }

    /// The least and largest exponent e of the fields (|s|/s_p)^e the two bases read
    /// (−1 and 1 at least: they also give the separable part's R_i + R_j).
    pub fn exponents(&self) -> (i32, i32) {
        let (lo, hi) = self.sum_exponents;
        (lo.min(-1), hi.max(0).max(2 * self.diff_powers as i32))
    }

    /// The basis of the sum term (`term` 0) or the difference term (1) of two waves, T
    /// of the output (the functions beyond the term's count zero).
    #[inline]
    pub(super) fn eval(
        &self,
        a: &Component,
        b: &Component,
        s_ref: f64,
        term: usize,
        t: f64,
    ) -> [f64; MAX_NB] {
        let mut out = [0.0; MAX_NB];
        if term == 1 {
            // (δ²/T)^m / T, δ = s_i − s_j: the difference term's G depends on δ and T only.
            let d = a.s.abs() - b.s.abs();
            let x2 = d * d / t;
            let mut v = 1.0 / t;
            for o in out.iter_mut().take(self.diff_powers + 1) {
                *o = v;
                v *= x2;
            }
            return out;
        }
        let (xa, xb) = (a.s.abs() / s_ref, b.s.abs() / s_ref);
        let tt = t / (s_ref * s_ref);
        // x^e of both waves for the exponents lo ..= hi of the monomials, each once (the
        // same values as powi of each monomial's own).
        let (lo, hi) = self.sum_exponents;
        let (mut pa, mut pb) = ([0.0; POWERS], [0.0; POWERS]);
        for e in lo..=hi {
            let i = (e - lo) as usize;
            (pa[i], pb[i]) = (xa.powi(e), xb.powi(e));
        }
        let at = |e: i32| (e - lo) as usize;
        for (o, f) in out.iter_mut().zip(&self.sum) {
            let mut v = 0.0;
            for &(w, u, e) in &f.monomials {
                let (u, e) = (at(u), at(e));
                v += w * (0.5 * (pa[u] * pb[e] + pa[e] * pb[u]));
            }
            *o = if f.t_power == 0 {
                v
            } else {
                v * tt.powi(f.t_power)
            };
        }
        out
    }
}
