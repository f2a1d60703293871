//! The draws of the sea's components, line by line: every resolved draw with energy of
//! the kx lines (and the ky indices) within the convergence limit, their variance by
//! octave for the ranking, and the components taken from them.

use super::super::{P_FLOOR_M2, SpectrumSetup, draw_line_in, resolved_ranges, visit_lines, window};
use super::Cutoff;
use crate::grid::signed_index;
use crate::simd::Isa;

/// One resolved draw with energy: indices (n, m), E|h̃0|² and h̃0 = ρ e^{iφ}.
#[derive(Clone, Copy)]
pub(super) struct Draw {
    pub(super) n: i64,
    pub(super) m: i64,
    pub(super) p: f64,
    pub(super) rho: f64,
    pub(super) phi: f64,
}

impl Draw {
    /// The ranking key: E|h̃0|² and the indices packed in their order.
    pub(super) fn key(&self) -> (f64, u64) {
        let at = |i: i64| (i + (1 << 31)) as u64;
        (self.p, at(self.n) << 32 | at(self.m))
    }
}

/// Every resolved draw with energy of `setup` on the kx lines |n| < `lines`, at the ky
/// indices |m| < `cols` of each ([`every_line`]: all of them), line by line (kx index ≥ 0,
/// with its mirror line): what `line` makes of each line's draws, in line order. Without `draws` only E|h̃0|² is filled in (ρ and φ 0: the expected spectrum,
/// its cells above [`P_FLOOR_M2`], those whose draws have energy).
pub(super) fn lines_of<T: Send>(
    setup: &SpectrumSetup,
    isa: Isa,
    (lines, cols): (usize, usize),
    draws: bool,
    line: &(dyn Fn(&[Draw]) -> T + Sync),
) -> Vec<T> {
    let (nx, ny) = (setup.spec.nx, setup.spec.ny);
    let cols = window(ny, cols);
    visit_lines(setup, (lines, &cols), |n, buf| {
        if draws {
            draw_line_in(setup, isa, n, buf, &cols);
        }
        let mut out = Vec::new();
        // The resolved indices within the window.
        let within = resolved_ranges(n, nx, ny).into_iter().flat_map(|r| {
            cols.clone()
                .into_iter()
                .map(move |c| r.start.max(c.start)..r.end.min(c.end))
        });
        for r in within {
            for idx in r {
                let m = signed_index(idx, ny);
                let mut push = |n: i64, m: i64, p: f64, rho: f64, phi: f64| {
                    // (A draw has energy where E|h̃0|² is above the floor.)
                    let energy = if draws { rho > 0.0 } else { p > P_FLOOR_M2 };
                    if energy {
                        out.push(Draw { n, m, p, rho, phi });
                    }
                };
                let (ra, pha, rb, phb) = if draws {
                    (buf.ra[idx], buf.pha[idx], buf.rb[idx], buf.phb[idx])
                } else {
                    (0.0, 0.0, 0.0, 0.0)
                };
                push(n, m, buf.pa[idx], ra, pha);
                // On the kx = 0 line the a draws of ±m already cover both.
                if n > 0 {
                    push(-n, -m, buf.pb[idx], rb, phb);
                }
            }
        }
        line(&out)
    })
}

/// The kx lines (n ≥ 0) that can hold a wave within `cutoff` (None: every line): those
/// below its wavenumber k_up, with a line of margin; and the ky indices |m| < cols of
/// each line that can (the same bound along ky).
pub(super) fn lines_within(setup: &SpectrumSetup, cutoff: Option<Cutoff>) -> (usize, usize) {
    let every = every_line(setup);
    let Some(c) = cutoff else { return every };
    let k_up = setup.dispersion.wavenumber(c.omega_up);
    let (dkx, dky) = setup.dk();
    let bound = |dk: f64, every: usize| {
        let n = (k_up / dk).floor();
        if n.is_finite() && n + 2.0 < every as f64 {
            n as usize + 2
        } else {
            every
        }
    };
    (bound(dkx, every.0), bound(dky, every.1))
}

/// The kx lines (n ≥ 0) and the ky indices |m| < cols of [`lines_of`] that cover the
/// whole half spectrum.
pub(super) fn every_line(setup: &SpectrumSetup) -> (usize, usize) {
    (setup.spec.nx / 2 + 1, setup.spec.ny / 2 + 1)
}

/// Every resolved draw with energy of `setup`, line by line, as `keep` maps it (None:
/// left out).
pub(super) fn each_line<T: Send>(
    setup: &SpectrumSetup,
    isa: Isa,
    lines: (usize, usize),
    keep: &(dyn Fn(Draw) -> Option<T> + Sync),
) -> Vec<Vec<T>> {
    lines_of(setup, isa, lines, true, &|draws| {
        draws.iter().filter_map(|&d| keep(d)).collect()
    })
}

/// The octave of a positive E|h̃0|² (its binary exponent): the ranking's coarse buckets.
#[inline]
pub(super) fn octave(p: f64) -> usize {
    (p.to_bits() >> 52) as usize & 0x7ff
}

/// The variance E|h̃0|² of `setup`'s draws that `admit` lets in, by octave (sum and
/// count), and their total (summed line by line, in line order).
pub(super) fn octaves(
    setup: &SpectrumSetup,
    isa: Isa,
    lines: (usize, usize),
    admit: &(dyn Fn(&Draw) -> bool + Sync),
) -> (Vec<(f64, usize)>, f64) {
    let lines = lines_of(setup, isa, lines, true, &|draws| {
        let mut dense = vec![(0.0f64, 0usize); 0x800];
        let mut total = 0.0;
        for d in draws.iter().filter(|d| admit(d)) {
            let b = &mut dense[octave(d.p)];
            b.0 += d.p;
            b.1 += 1;
            total += d.p;
        }
        let sparse: Vec<(usize, f64, usize)> = dense
            .into_iter()
            .enumerate()
            .filter(|(_, b)| b.1 > 0)
            .map(|(o, b)| (o, b.0, b.1))
            .collect();
        (sparse, total)
    });
    let mut by_octave = vec![(0.0f64, 0usize); 0x800];
    let mut total = 0.0;
    for (sparse, line_total) in lines {
        for (o, sum, count) in sparse {
            by_octave[o].0 += sum;
            by_octave[o].1 += count;
        }
        total += line_total;
    }
    (by_octave, total)
}

/// The lines' items in one vector, each line freed once moved (no regrowth).
pub(super) fn flat<T>(lines: Vec<Vec<T>>) -> Vec<T> {
    let mut out = Vec::with_capacity(lines.iter().map(Vec::len).sum());
    for line in lines {
        out.extend(line);
    }
    out
}
