//! The cells near the peak of a line of wavevectors, integrated in whole-line passes.
//!
//! A line's cells that are not far from the peak ([`Kernel::is_far`]) take the
//! n_x × n_y Gauss–Legendre rule of [`DirectionalSpectrum::cell_integral`] (up to
//! 16 × 16 nodes each; 4 × 4 at the peak of a 4096² grid 1 m apart). Rather than Ψ node
//! by node, every node of every such cell of the line, in both half-planes (the cell at (kx, ky[j]) and the one at (−kx, −ky[j])), goes
//! into one set of arrays: their radial parts come from [`Kernel::radial_line`], once
//! per distinct k² (the nodes of the −k cell are those of the +k cell reflected, and in
//! FFT order the cells at ky and −ky mirror each other, so most k² come four times; the
//! nodes are laid out so that a block and its mirror image list the same k² in the same
//! order, and a block reuses its image's radial parts only where all of them are equal
//! bit for bit), their directional parts from
//! a pass compiled for each instruction set (`simd::multiversion`) with `fastmath`'s
//! branch-free ln and exp, whose flagged lanes the scalar [`Kernel::angular`] redoes.
//! Each cell's sum is then formed exactly as `cell_integral` forms it, so every value
//! equals `0.5 * cell_integral(..)` bit for bit. Cells whose rule is the midpoint (1 × 1)
//! keep the value the grid passes gave them (see `grid`), as `cell_integral` does;
//! Donelan–Banner's directional part (an arctangent per node) is the scalar `angular` on
//! the batched radial parts.
//!
//! [`DirectionalSpectrum::cell_integral`]: super::DirectionalSpectrum::cell_integral

use super::line::{RadialLine, RadialScratch};
use super::{FrequencySpectrum, Kernel, POWER_EXPONENT_MIN, Radial, SpreadKind, half_one_plus};
use crate::fastmath::{exp_fast, exp_is_special, ln_is_special, ln_positive_normal};
use crate::simd::{Isa, multiversion};
use crate::spectrum::{LineQuery, PairOut};

/// Line entries tested together for a near cell.
const BLOCK: usize = 32;

/// Where a block of nodes (the +k or the −k cell's) takes its radial parts.
#[derive(Debug, Clone, Copy)]
enum Source {
    /// The computed radial parts from this index on.
    Computed(usize),
    /// The block that starts at this node, whose k² are the same in the same order.
    Copy(usize),
}

/// One cell of the batch: its index in the line, its orders, where its nodes start and
/// where each block's radial parts come from. The +k cell's n_x·n_y nodes come first,
/// x-row by x-row, its y-nodes in the rule's order or reversed (`y_rev`); then the −k
/// cell's, both axes the other way round, so that each node of the −k block sits where
/// its reflection −k sits in the +k block. With `y_rev` the +k block is laid out as the
/// reflection in y of the block of the cell at −ky[j] (FFT order).
#[derive(Debug, Clone, Copy)]
struct Cell {
    j: usize,
    nx: usize,
    ny: usize,
    start: usize,
    y_rev: bool,
    plus: Source,
    minus: Source,
}

impl Cell {
    /// The two blocks: (first node, x-nodes reversed, y-nodes reversed).
    fn blocks(&self) -> [(usize, bool, bool); 2] {
        [
            (self.start, false, self.y_rev),
            (self.start + self.nx * self.ny, true, !self.y_rev),
        ]
    }
}

/// Buffers of one thread (reused from line to line).
#[derive(Debug, Default)]
pub(super) struct CellScratch {
    cells: Vec<Cell>,
    /// The batch slot of line index j (meaningful where `cells[slot[j]].j == j`).
    slot: Vec<usize>,
    x: Vec<f64>,
    y: Vec<f64>,
    k2: Vec<f64>,
    /// The k² whose radial parts are computed.
    unique: Vec<f64>,
    radial_scratch: RadialScratch,
    radial: RadialLine,
    /// The radial parts per node.
    nodes: RadialLine,
    psi: Vec<f64>,
    flags: Vec<u8>,
}

multiversion! {
    @on
    /// Ψ at the nodes (x[i], y[i]) from their radial parts (1/k, a, s), for the cos^{2s}
    /// family, plain cos² and cos² with swell (the kernel's): bit for bit
    /// [`Kernel::angular`] on every lane whose flag stays 0. Lanes where ln or exp leave
    /// their fast range get a flag; true if there is one.
    fn angular_nodes(
        isa: Isa,
        kern: &Kernel,
        x: &[f64],
        y: &[f64],
        nodes: &RadialLine,
        psi: &mut [f64],
        flags: &mut [u8],
    ) -> bool {
        let (wx, wy, kind) = (kern.wx, kern.wy, kern.kind);
        let n = x.len();
        let (y, inv_k, a, s) = (&y[..n], &nodes.inv_k[..n], &nodes.a[..n], &nodes.s[..n]);
        let (psi, flags) = (&mut psi[..n], &mut flags[..n]);
        let plain = kind == SpreadKind::Cos2Plain;
        let cos2 = kind != SpreadKind::Family;
        let mut any = 0u8;
        for i in 0..n {
            // `before_power`, then the power, every branch computed and one selected.
            let c = (x[i] * wx + y[i] * wy) * inv_k[i];
            let (ai, si) = (a[i], s[i]);
            let m = if cos2 { ai * (c * c) } else { ai };
            let half = half_one_plus(c);
            let e = si * ln_positive_normal(half);
            let powered = m * exp_fast(e);
            let takes_power = !plain & (ai != 0.0) & (si != 0.0);
            let below = e < POWER_EXPONENT_MIN;
            psi[i] = if ai == 0.0 {
                0.0
            } else if !takes_power {
                m
            } else if below {
                0.0
            } else {
                powered
            };
            let special = takes_power & (ln_is_special(half) | (!below & exp_is_special(e)));
            flags[i] = special as u8;
            any |= special as u8;
        }
        any != 0
    }
}

impl Kernel {
    /// `0.5 * cell_integral(..)` of every cell of the line that takes a Gauss–Legendre
    /// rule, in both half-planes (see [`PairOut`]), with the directional pass on `isa`;
    /// the midpoint cells (far or 1 × 1) are left as they are.
    pub(super) fn near_cells_pair_line_on(
        &self,
        isa: Isa,
        freq: &dyn FrequencySpectrum,
        q: &LineQuery,
        out: PairOut<f64>,
        scratch: &mut CellScratch,
    ) {
        let LineQuery { kx, ky, dkx, dky } = *q;
        let n = ky.len().min(out.a.len()).min(out.b.len());
        let (ky, pa, pb) = (&ky[..n], &mut out.a[..n], &mut out.b[..n]);
        let h = dkx.max(dky);
        let CellScratch {
            cells,
            slot,
            x,
            y,
            k2,
            unique,
            radial_scratch,
            radial,
            nodes,
            psi,
            flags,
        } = scratch;
        // The cells, their orders (as `cell_integral` takes them) and their nodes.
        cells.clear();
        x.clear();
        y.clear();
        slot.resize(n, 0);
        // Most of a line is far: blocks of it are passed over after a test that
        // vectorizes.
        let near = |y: f64| !self.is_far(kx * kx + y * y, h);
        for (b, block) in ky.chunks(BLOCK).enumerate() {
            if !block.iter().fold(false, |any, &y| any | near(y)) {
                continue;
            }
            for j in b * BLOCK..b * BLOCK + block.len() {
                if !near(ky[j]) {
                    continue;
                }
                let k = (kx * kx + ky[j] * ky[j]).sqrt();
                let (nx, ny) = (self.order(k, dkx), self.order(k, dky));
                if nx == 1 && ny == 1 {
                    // The midpoint: the grid passes already hold it.
                    continue;
                }
                // The cell at −ky[j] of this line, if it came earlier with the same rule.
                let mirror = (j > 0)
                    .then(|| n - j)
                    .filter(|&jm| jm < j && ky[jm] == -ky[j])
                    .and_then(|jm| cells.get(slot[jm]).copied())
                    .filter(|m| m.j == n - j && m.nx == nx && m.ny == ny && !m.y_rev);
                let start = x.len();
                let cell = Cell {
                    j,
                    nx,
                    ny,
                    start,
                    y_rev: mirror.is_some(),
                    plus: mirror.map_or(Source::Computed(0), |m| Source::Copy(m.start)),
                    minus: Source::Copy(start),
                };
                slot[j] = cells.len();
                cells.push(cell);
                for ((first, x_rev, y_rev), (cx, cy)) in
                    cell.blocks().into_iter().zip([(kx, ky[j]), (-kx, -ky[j])])
                {
                    debug_assert_eq!(first, x.len());
                    let (rx, ry) = (&self.rules[nx - 1], &self.rules[ny - 1]);
                    for ix in 0..nx {
                        let xn = cx + rx[if x_rev { nx - 1 - ix } else { ix }].0 * dkx;
                        x.extend(std::iter::repeat_n(xn, ny));
                        y.extend(
                            (0..ny).map(|iy| cy + ry[if y_rev { ny - 1 - iy } else { iy }].0 * dky),
                        );
                    }
                }
            }
        }
        if cells.is_empty() {
            return;
        }
        k2.clear();
        k2.extend(x.iter().zip(y.iter()).map(|(&x, &y)| x * x + y * y));
        // The k² to compute: a block takes the radial parts of its image where all their
        // k² are equal bit for bit (so always, as the rules are symmetric).
        unique.clear();
        for c in cells.iter_mut() {
            let nn = c.nx * c.ny;
            for (source, first) in [(&mut c.plus, c.start), (&mut c.minus, c.start + nn)] {
                let block = &k2[first..first + nn];
                let same = |from: usize| {
                    let image = &k2[from..from + nn];
                    block
                        .iter()
                        .zip(image)
                        .all(|(p, q)| p.to_bits() == q.to_bits())
                };
                if !matches!(*source, Source::Copy(from) if same(from)) {
                    *source = Source::Computed(unique.len());
                    unique.extend_from_slice(block);
                }
            }
        }
        self.radial_line(isa, unique, freq, radial_scratch, radial);
        // The radial parts of every node.
        let count = x.len();
        let with_beta = self.kind == SpreadKind::DonelanBanner;
        let fill = |to: &mut Vec<f64>, from: &[f64]| {
            to.resize(count, 0.0);
            for c in cells.iter() {
                let nn = c.nx * c.ny;
                for (source, first) in [(c.plus, c.start), (c.minus, c.start + nn)] {
                    match source {
                        Source::Computed(at) => {
                            to[first..first + nn].copy_from_slice(&from[at..at + nn])
                        }
                        Source::Copy(image) => to.copy_within(image..image + nn, first),
                    }
                }
            }
        };
        fill(&mut nodes.inv_k, &radial.inv_k);
        fill(&mut nodes.a, &radial.a);
        fill(&mut nodes.s, &radial.s);
        if with_beta {
            fill(&mut nodes.beta, &radial.beta);
        }
        // Ψ at every node.
        psi.resize(count, 0.0);
        let node = |i: usize| Radial {
            inv_k: nodes.inv_k[i],
            a: nodes.a[i],
            s: nodes.s[i],
            beta: if with_beta { nodes.beta[i] } else { 0.0 },
        };
        if with_beta {
            for i in 0..count {
                psi[i] = self.angular(&node(i), x[i], y[i]);
            }
        } else {
            flags.resize(count, 0);
            if angular_nodes(isa, self, x, y, nodes, psi, flags) {
                for i in 0..count {
                    if flags[i] != 0 {
                        psi[i] = self.angular(&node(i), x[i], y[i]);
                    }
                }
            }
        }
        // Each cell's sums in the order of `cell_integral`: x-nodes, then y-nodes, each
        // in the rule's order.
        for c in cells.iter() {
            let nn = c.nx * c.ny;
            let (rx, ry) = (&self.rules[c.nx - 1], &self.rules[c.ny - 1]);
            let [plus, minus] = c.blocks().map(|(first, x_rev, y_rev)| {
                let vals = &psi[first..first + nn];
                let mut sum = 0.0;
                for (ix, &(_, wx)) in rx.iter().enumerate() {
                    let r = if x_rev { c.nx - 1 - ix } else { ix };
                    let row = &vals[r * c.ny..(r + 1) * c.ny];
                    let mut line = 0.0;
                    if y_rev {
                        for (&v, &(_, wy)) in row.iter().rev().zip(ry) {
                            line += wy * v;
                        }
                    } else {
                        for (&v, &(_, wy)) in row.iter().zip(ry) {
                            line += wy * v;
                        }
                    }
                    sum += wx * line;
                }
                0.5 * (sum * dkx * dky)
            });
            pa[c.j] = plus;
            pb[c.j] = minus;
        }
    }
}
