//! The per-frequency spreading quantities [s, ln Z, β] of a directional sea: their exact
//! formulas, and the cubic table the kernel evaluates them from.

use rayon::prelude::*;

use super::SpreadKind;
use super::{
    DB_R_1, DB_R_2, DB_R_MIN, PI, db_beta_branch, donelan_banner_norm, ln_np, ln_z_cos2, tanh,
};
use crate::fastmath::{exp, ln};

/// The exact per-frequency spreading quantities [s, ln Z, β] at x = ln(f/fp), piece by
/// piece (`branch` selects the formula, so table nodes past a breakpoint continue the
/// piece's own formula).
#[derive(Debug, Clone, Copy)]
pub(super) struct SpreadExact {
    pub(super) kind: SpreadKind,
    /// Family: s_model = coef·exp(μ x), μ = mu_lo below the peak, mu_hi from it up.
    pub(super) coef: f64,
    pub(super) mu_lo: f64,
    pub(super) mu_hi: f64,
    /// 16 ξ².
    pub(super) swell16: f64,
}

impl SpreadExact {
    /// Breakpoints in x (where a formula changes), ascending.
    pub(super) fn edges(&self) -> Vec<f64> {
        match self.kind {
            SpreadKind::Family => vec![0.0],
            SpreadKind::DonelanBanner => vec![ln(DB_R_MIN), ln(DB_R_1), ln(DB_R_2)],
            _ => vec![],
        }
    }

    pub(super) fn branch(&self, x: f64) -> usize {
        self.edges().iter().filter(|&&e| x >= e).count()
    }

    pub(super) fn cols(&self, x: f64, branch: usize) -> [f64; 3] {
        let swell = if self.swell16 == 0.0 {
            0.0
        } else {
            self.swell16 * tanh(exp(-x))
        };
        match self.kind {
            SpreadKind::Cos2Plain => [0.0, ln(PI), 0.0],
            SpreadKind::Cos2Swell => [swell, ln_z_cos2(swell), 0.0],
            SpreadKind::Family => {
                let mu = if branch == 0 { self.mu_lo } else { self.mu_hi };
                let s = self.coef * exp(mu * x) + swell;
                [s, ln_np(s), 0.0]
            }
            SpreadKind::DonelanBanner => {
                // Branch 0 (r < 0.56) holds β at r = 0.56.
                let beta = if branch == 0 {
                    db_beta_branch(0, ln(DB_R_MIN))
                } else {
                    db_beta_branch(branch - 1, x)
                };
                let ln_z = if swell == 0.0 {
                    ln(2.0 * tanh(beta * PI) / beta)
                } else {
                    ln(donelan_banner_norm(beta, swell))
                };
                [swell, ln_z, beta]
            }
        }
    }
}

/// [s, ln Z, β] tabulated on x = ln(f/fp) ∈ [X_LO, X_HI] with 256 nodes per unit of x,
/// one cubic table per piece between breakpoints (interpolation error of the exponent
/// s·ln cos²(θ/2) − ln Z below ~1e-8 of itself); exact outside. At most 3 breakpoints;
/// the pieces' intervals share one array. Each interval holds its cubic (the Lagrange
/// interpolant of its four surrounding nodes) as power-series coefficients in the
/// position u ∈ [0, 1) within it: one row of 12 numbers, so an evaluation is one row and
/// three short Horner schemes.
#[derive(Debug, Clone)]
pub(super) struct SpreadTable {
    pub(super) exact: SpreadExact,
    /// Breakpoints, padded with +∞.
    pub(super) edges: [f64; 3],
    pub(super) segs: [Seg; 4],
    /// Per interval, per column [s, ln Z, β]: c0 + u·(c1 + u·(c2 + u·c3)).
    pub(super) rows: Vec<[[f64; 4]; 3]>,
}

/// One piece: intervals [x0 + j/inv_h, x0 + (j + 1)/inv_h), j = 0..n, at rows[offset..].
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Seg {
    pub(super) x0: f64,
    pub(super) inv_h: f64,
    /// n − 1 (the last interval), as f64 for clamping.
    pub(super) last: f64,
    pub(super) offset: usize,
}

pub(super) const X_LO: f64 = -3.0;
pub(super) const X_HI: f64 = 6.0;
pub(super) const NODES_PER_UNIT: f64 = 256.0;

/// The power-series coefficients in u of the cubic through (−1, v[0]), (0, v[1]),
/// (1, v[2]), (2, v[3]).
pub(super) fn cubic_row(v: [f64; 4]) -> [f64; 4] {
    [
        v[1],
        -v[0] / 3.0 - v[1] / 2.0 + v[2] - v[3] / 6.0,
        v[0] / 2.0 - v[1] + v[2] / 2.0,
        (v[3] - v[0]) / 6.0 + (v[1] - v[2]) / 2.0,
    ]
}

impl SpreadTable {
    pub(super) fn empty(exact: SpreadExact) -> Self {
        Self {
            exact,
            edges: [f64::INFINITY; 3],
            segs: [Seg::default(); 4],
            rows: Vec::new(),
        }
    }

    pub(super) fn new(exact: SpreadExact) -> Self {
        let inner = exact.edges();
        assert!(inner.len() <= 3);
        let mut t = Self::empty(exact);
        for (e, &x) in t.edges.iter_mut().zip(&inner) {
            *e = x;
        }
        let mut bounds = vec![X_LO];
        bounds.extend(inner.iter().copied());
        bounds.push(X_HI);
        for (b, w) in bounds.windows(2).enumerate() {
            let n = (((w[1] - w[0]) * NODES_PER_UNIT).ceil() as usize).max(8);
            let h = (w[1] - w[0]) / n as f64;
            t.segs[b] = Seg {
                x0: w[0],
                inv_h: 1.0 / h,
                last: (n - 1) as f64,
                offset: t.rows.len(),
            };
            // Nodes x0 + (j − 1)·h, j = 0..n+3: interval j uses nodes j..j+4.
            let nodes: Vec<[f64; 3]> = (0..n + 3)
                .into_par_iter()
                .map(|j| exact.cols(w[0] + (j as f64 - 1.0) * h, b))
                .collect();
            t.rows.extend(
                nodes
                    .windows(4)
                    .take(n)
                    .map(|v| [0, 1, 2].map(|c| cubic_row([v[0][c], v[1][c], v[2][c], v[3][c]]))),
            );
        }
        t
    }

    #[inline(always)]
    pub(super) fn eval(&self, x: f64) -> [f64; 3] {
        if !Self::in_range(x) {
            return self.eval_exact(x);
        }
        self.eval_in_range(x, true)
    }

    /// True where [`SpreadTable::eval`] interpolates (false for NaN).
    #[inline(always)]
    pub(super) fn in_range(x: f64) -> bool {
        (X_LO..X_HI).contains(&x)
    }

    /// [`SpreadTable::eval`] for `in_range(x)` (β only `with_beta`, else 0); free of
    /// branches on x, and meaningless (but within the table) elsewhere.
    #[inline(always)]
    pub(super) fn eval_in_range(&self, x: f64, with_beta: bool) -> [f64; 3] {
        let seg = (x >= self.edges[0]) as usize
            + (x >= self.edges[1]) as usize
            + (x >= self.edges[2]) as usize;
        let sg = &self.segs[seg & 3];
        let t = ((x - sg.x0) * sg.inv_h).max(0.0);
        let fi = t.floor().min(sg.last);
        let u = t - fi;
        // (NaN or out-of-range x: the piece's first interval.)
        let row = &self.rows[(sg.offset + fi as usize).min(self.rows.len() - 1)];
        let horner = |c: &[f64; 4]| c[0] + u * (c[1] + u * (c[2] + u * c[3]));
        [
            horner(&row[0]),
            horner(&row[1]),
            if with_beta { horner(&row[2]) } else { 0.0 },
        ]
    }

    #[cold]
    #[inline(never)]
    pub(super) fn eval_exact(&self, x: f64) -> [f64; 3] {
        if x.is_nan() {
            return [0.0, 0.0, 0.0];
        }
        self.exact.cols(x, self.exact.branch(x))
    }
}
