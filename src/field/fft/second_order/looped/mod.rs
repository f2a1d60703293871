//! The exact pair sum of a looping sea, summed once for every time.
//!
//! With a loop period T every ω_i is a whole multiple ν_i of 2π/T ([`super::super::loop_omega`]),
//! so the pair (i, j) turns with (ν_i ± ν_j)·2π/T and the bound spectrum at any time is
//!
//! ```text
//! Z_q(t) = Σ_ν Z_q,ν e^{−iν·2π t/T},   Z_q,ν = Σ_{pairs on q with ν_i ± ν_j = ν} b_i(0) b_j′(0) 2K
//! ```
//!
//! The Z_q,ν do not depend on the time: the pair sum runs once (the same pairs, kernels
//! and order as [`SecondOrder::bound_plane`]), binned by ν, and each frame costs one
//! sum over ν per output. A sequence of F frames pays one pair sum instead of F.
//! Every frame, whichever command computes it, goes through these bins, so `animate`
//! frames equal `generate --time t` bit for bit.
//!
//! The bins of output line n_q cover the ky indices and multiples its pairs can reach (from
//! each kx line's ranges of m and ν); when the loop is so long that they would exceed
//! [`MAX_BINS_PER_CELL`] times the grid, the sea keeps the per-frame pair sum.

use std::f64::consts::TAU;

use rayon::prelude::*;
use rustfft::num_complex::Complex32;

use super::pairs::Amps;
use super::{C64, SecondOrder, SecondOrderInfo, SpectrumSetup, add_plane, on_grid, resolved_span};
use crate::field::fft::HalfSpectrum;
use crate::grid::signed_index;

/// The bins' limit, in complex values per cell of the grid (8 bytes each: the bins are
/// summed in f64 and kept in f32, the precision of the spectrum they join).
pub const MAX_BINS_PER_CELL: usize = 16;

/// The bins of one output kx line: multiples ν_lo ..= ν_lo + count − 1 by ky indices
/// m_lo ..= m_lo + width − 1 (signed, on the grid).
#[derive(Default)]
struct Row {
    m_lo: i64,
    width: usize,
    nu_lo: i64,
    count: usize,
    /// [(ν − ν_lo)·width + (m − m_lo)]: consecutive partners (neighbours in k, so mostly
    /// of one ν) add to consecutive bins.
    z: Vec<Complex32>,
}

/// An inclusive range of integers, empty when lo > hi.
#[derive(Clone, Copy)]
struct Span {
    lo: i64,
    hi: i64,
}

impl Span {
    const EMPTY: Span = Span {
        lo: i64::MAX,
        hi: i64::MIN,
    };

    fn join(self, o: Span) -> Span {
        Span {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    fn clip(self, lo: i64, hi: i64) -> Span {
        Span {
            lo: self.lo.max(lo),
            hi: self.hi.min(hi),
        }
    }

    fn len(self) -> usize {
        if self.lo > self.hi {
            0
        } else {
            (self.hi - self.lo + 1) as usize
        }
    }

    /// The values a ± b takes for a in self, b in o.
    fn plus(self, o: Span, sign: i64) -> Span {
        if self.len() == 0 || o.len() == 0 {
            return Span::EMPTY;
        }
        if sign > 0 {
            Span {
                lo: self.lo + o.lo,
                hi: self.hi + o.hi,
            }
        } else {
            Span {
                lo: self.lo - o.hi,
                hi: self.hi - o.lo,
            }
        }
    }
}

/// The bound waves of a looping sea's strongest components, binned by multiple.
pub struct LoopedBound {
    /// 2π/T, rad/s.
    base: f64,
    nx: usize,
    ny: usize,
    /// By output row (FFT order).
    rows: Vec<Row>,
    /// The multiples of every row: ν_lo ..= ν_lo + count − 1.
    nu: Span,
    pub info: SecondOrderInfo,
}

/// ν_i of every component of `so` (of `setup`, looping with period `period`), and of
/// every kx line (offset by nx) the spans of m and ν.
fn line_spans(
    so: &SecondOrder,
    setup: &SpectrumSetup,
    period: f64,
) -> (Vec<i64>, Vec<(Span, Span)>) {
    let base = TAU / period;
    // The looping ω of the linear sea ([`SpectrumSetup::omega`]) is ν·(2π/T) exactly.
    let nus: Vec<i64> = so
        .comps
        .iter()
        .map(|c| (setup.omega(c.kx, c.ky) / base).round() as i64)
        .collect();
    let spans = so
        .lines
        .iter()
        .map(|r| {
            if r.is_empty() {
                return (Span::EMPTY, Span::EMPTY);
            }
            let m = Span {
                lo: so.comps[r.start].m,
                hi: so.comps[r.end - 1].m,
            };
            let nu = nus[r.clone()]
                .iter()
                .fold(Span::EMPTY, |s, &v| s.join(Span { lo: v, hi: v }));
            (m, nu)
        })
        .collect();
    (nus, spans)
}

/// The spans of m and ν of output line nq (of the lines' spans `spans`).
fn row_window(so: &SecondOrder, spans: &[(Span, Span)], nq: i64) -> (Span, Span) {
    let of = |n: i64| {
        let i = n + so.nx as i64;
        if i < 0 || i as usize >= spans.len() {
            (Span::EMPTY, Span::EMPTY)
        } else {
            spans[i as usize]
        }
    };
    let (mut m, mut nu) = (Span::EMPTY, Span::EMPTY);
    for &na in &so.occupied {
        let (ma, va) = of(na);
        for (nb, sign) in [(nq - na, 1), (na - nq, -1)] {
            if sign < 0 && nq < 0 {
                continue;
            }
            let (mb, vb) = of(nb);
            m = m.join(ma.plus(mb, sign));
            nu = nu.join(va.plus(vb, sign));
        }
    }
    let (lo, hi) = resolved_span(so.ny);
    (m.clip(lo, hi), nu)
}

/// Adds the weighted pairs `v` of one wave (its cell and bin offsets `at`) with partners
/// of ky indices and multiples `mn` to the bins `z` of a row `width` cells wide.
#[inline]
fn add_binned(
    z: &mut [C64],
    width: usize,
    at: (i64, i64),
    sign: i64,
    mn: (&[i64], &[i64]),
    v: (&[f64], &[f64]),
) {
    let n = v.0.len();
    let (ms, nus, vre, vim) = (&mn.0[..n], &mn.1[..n], v.0, &v.1[..n]);
    for j in 0..n {
        let cell = at.0 + sign * ms[j];
        let bin = at.1 + sign * nus[j];
        z[bin as usize * width + cell as usize] += C64::new(vre[j], vim[j]);
    }
}

impl LoopedBound {
    /// The bins of `so` (components of `setup`, its time not used) for `setup`'s loop
    /// period; None without one, or when they would exceed [`MAX_BINS_PER_CELL`] per cell.
    pub fn new(so: &SecondOrder, setup: &SpectrumSetup) -> Option<Self> {
        let period = setup.loop_period_s?;
        let (nx, ny) = (so.nx, so.ny);
        let (nus, spans) = line_spans(so, setup, period);
        let windows: Vec<(Span, Span)> = (0..nx)
            .map(|row| {
                let nq = signed_index(row, nx);
                if on_grid(nq, nx) {
                    row_window(so, &spans, nq)
                } else {
                    (Span::EMPTY, Span::EMPTY)
                }
            })
            .collect();
        let total: usize = windows.iter().map(|(m, v)| m.len() * v.len()).sum();
        if total > MAX_BINS_PER_CELL * nx * ny {
            return None;
        }
        let at_zero = SpectrumSetup {
            time_s: 0.0,
            ..*setup
        };
        let amps = Amps::new(so.amplitudes(&at_zero));
        let ms: Vec<i64> = so.comps.iter().map(|c| c.m).collect();
        let built: Vec<(Row, (u64, u64))> = windows
            .par_iter()
            .enumerate()
            .map(|(row, &(m, nu))| {
                if m.len() == 0 || nu.len() == 0 {
                    return (Row::default(), (0, 0));
                }
                let (m_lo, width, nu_lo, count) = (m.lo, m.len(), nu.lo, nu.len());
                let mut z = vec![C64::new(0.0, 0.0); width * count];
                let mut add =
                    |i: usize, sign: i64, js: std::ops::Range<usize>, v: (&[f64], &[f64])| {
                        let at = (ms[i] - m_lo, nus[i] - nu_lo);
                        add_binned(&mut z, width, at, sign, (&ms[js.clone()], &nus[js]), v);
                    };
                let counts = so.row_pairs(signed_index(row, nx), &amps, so.columns(), &mut add);
                let z = z
                    .iter()
                    .map(|v| Complex32::new(v.re as f32, v.im as f32))
                    .collect();
                let r = Row {
                    m_lo,
                    width,
                    nu_lo,
                    count,
                    z,
                };
                (r, counts)
            })
            .collect();
        let (sums, diffs) = built
            .iter()
            .fold((0, 0), |(s, d), (_, (a, b))| (s + a, d + b));
        let rows: Vec<Row> = built.into_iter().map(|(r, _)| r).collect();
        let nu = rows
            .iter()
            .filter(|r| r.count > 0)
            .fold(Span::EMPTY, |s, r| {
                s.join(Span {
                    lo: r.nu_lo,
                    hi: r.nu_lo + r.count as i64 - 1,
                })
            });
        let info = SecondOrderInfo {
            sum_pairs_dropped: so.info.pairs - sums,
            difference_pairs_dropped: so.info.pairs - diffs,
            loop_multiples: Some(nu.len()),
            ..so.info.clone()
        };
        Some(Self {
            base: TAU / period,
            nx,
            ny,
            rows,
            nu,
            info,
        })
    }

    /// The full-plane Z of the bound waves at `setup`'s time (as
    /// [`SecondOrder::bound_plane`] gives it).
    pub fn bound_plane(&self, setup: &SpectrumSetup) -> Vec<C64> {
        let theta = self.base * setup.phase_time();
        // e^{−iνθ} of every multiple.
        let turn: Vec<C64> = (self.nu.lo..=self.nu.hi)
            .map(|nu| {
                let (s, c) = (nu as f64 * theta).sin_cos();
                C64::new(c, -s)
            })
            .collect();
        let ny = self.ny;
        let mut z = vec![C64::new(0.0, 0.0); self.nx * ny];
        z.par_chunks_mut(ny)
            .zip(self.rows.par_iter())
            .for_each(|(zline, r)| {
                if r.count == 0 {
                    return;
                }
                let turn = &turn[(r.nu_lo - self.nu.lo) as usize..][..r.count];
                let mut v = vec![C64::new(0.0, 0.0); r.width];
                for (plane, w) in r.z.chunks_exact(r.width).zip(turn) {
                    for (v, b) in v.iter_mut().zip(plane) {
                        *v += C64::new(f64::from(b.re), f64::from(b.im)) * w;
                    }
                }
                for (x, v) in v.into_iter().enumerate() {
                    let m = r.m_lo + x as i64;
                    zline[m.rem_euclid(ny as i64) as usize] = v;
                }
            });
        z
    }

    /// Adds the bound waves at `setup`'s time to `half`; what the sidecar records.
    pub fn add_to(&self, setup: &SpectrumSetup, half: &mut HalfSpectrum) -> SecondOrderInfo {
        add_plane(&self.bound_plane(setup), half);
        self.info.clone()
    }

    /// The bins held, complex values.
    #[cfg(test)]
    pub fn bins(&self) -> usize {
        self.rows.iter().map(|r| r.z.len()).sum()
    }
}

#[cfg(test)]
mod tests;
