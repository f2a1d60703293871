//! The cells near the peak of a line of wavevectors, integrated in whole-line passes.
//!
//! A line's cells that are not far from the peak ([`Kernel::is_far`]) take the
//! n_x × n_y Gauss–Legendre rule of [`DirectionalSpectrum::cell_integral`] (4 × 4 to
//! 16 × 16 nodes each). Rather than Ψ node by node, every node of every such cell of the
//! line, in both half-planes (the cell at (kx, ky[j]) and the one at (−kx, −ky[j])), goes
//! into one set of arrays: their radial parts come from [`Kernel::radial_line`], once
//! per distinct k² (the nodes of the −k cell are those of the +k cell reflected, and in
//! FFT order the cells at ky and −ky mirror each other, so most k² come four times; a
//! reuse is taken only where the k² are equal bit for bit), their directional parts from
//! a pass compiled for each instruction set (`lines::multiversion`) with `fastmath`'s
//! branch-free ln and exp, whose flagged lanes the scalar [`Kernel::angular`] redoes.
//! Each cell's sum is then formed exactly as `cell_integral` forms it, so every value
//! equals `0.5 * cell_integral(..)` bit for bit. Cells whose rule is the midpoint (1 × 1)
//! take `Kernel::psi_grid` as `cell_integral` does; Donelan–Banner's directional part
//! (an arctangent per node) is the scalar `angular` on the batched radial parts.
//!
//! [`DirectionalSpectrum::cell_integral`]: super::DirectionalSpectrum::cell_integral

use super::line::{RadialLine, RadialScratch};
use super::{FrequencySpectrum, Kernel, POWER_EXPONENT_MIN, Radial, SpreadKind, half_one_plus};
use crate::fastmath::{exp_fast, exp_is_special, ln_is_special, ln_positive_normal};
use crate::field::lines::{Isa, multiversion};

/// Line entries tested together for a near cell.
const BLOCK: usize = 32;

/// One cell of the batch: its index in the line, its orders and where its nodes start
/// (the +k cell's n_x·n_y nodes, x-node major, then the −k cell's).
#[derive(Debug, Clone, Copy)]
struct Cell {
    j: usize,
    nx: usize,
    ny: usize,
    start: usize,
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
    /// Per node, the index of its k² in `unique`.
    src: Vec<usize>,
    unique: Vec<f64>,
    radial_scratch: RadialScratch,
    radial: RadialLine,
    /// The radial parts per node.
    inv_k: Vec<f64>,
    a: Vec<f64>,
    s: Vec<f64>,
    psi: Vec<f64>,
    flags: Vec<u8>,
}

thread_local! {
    /// Buffers of the near-peak cells, one set per thread.
    static CELL_SCRATCH: std::cell::RefCell<CellScratch> =
        std::cell::RefCell::new(CellScratch::default());
}

multiversion! {
    @on
    /// Ψ at the nodes (x[i], y[i]) from their radial parts (1/k, a, s), for the cos^{2s}
    /// family, plain cos² and cos² with swell: bit for bit [`Kernel::angular`] on every
    /// lane whose flag stays 0. Lanes where ln or exp leave their fast range get a flag;
    /// true if there is one.
    fn angular_nodes(
        isa: Isa,
        wx: f64,
        wy: f64,
        kind: SpreadKind,
        x: &[f64],
        y: &[f64],
        inv_k: &[f64],
        a: &[f64],
        s: &[f64],
        psi: &mut [f64],
        flags: &mut [u8],
    ) -> bool {
        let n = x.len();
        let (y, inv_k, a, s) = (&y[..n], &inv_k[..n], &a[..n], &s[..n]);
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
    /// `0.5 * cell_integral(..)` of every cell of the line that is not far, at
    /// (kx, ky[j]) into `pa[j]` and at (−kx, −ky[j]) into `pb[j]`; far cells are left as
    /// they are.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn near_cells_pair_line(
        &self,
        freq: &dyn FrequencySpectrum,
        kx: f64,
        ky: &[f64],
        dkx: f64,
        dky: f64,
        pa: &mut [f64],
        pb: &mut [f64],
    ) {
        let isa = Isa::detect();
        CELL_SCRATCH.with(|cell| match cell.try_borrow_mut() {
            Ok(mut scratch) => {
                self.near_cells_pair_line_on(isa, freq, kx, ky, dkx, dky, pa, pb, &mut scratch)
            }
            Err(_) => self.near_cells_pair_line_on(
                isa,
                freq,
                kx,
                ky,
                dkx,
                dky,
                pa,
                pb,
                &mut CellScratch::default(),
            ),
        });
    }

    /// [`Kernel::near_cells_pair_line`] with the directional pass on `isa`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn near_cells_pair_line_on(
        &self,
        isa: Isa,
        freq: &dyn FrequencySpectrum,
        kx: f64,
        ky: &[f64],
        dkx: f64,
        dky: f64,
        pa: &mut [f64],
        pb: &mut [f64],
        scratch: &mut CellScratch,
    ) {
        let n = ky.len().min(pa.len()).min(pb.len());
        let (ky, pa, pb) = (&ky[..n], &mut pa[..n], &mut pb[..n]);
        let h = dkx.max(dky);
        let CellScratch {
            cells,
            slot,
            x,
            y,
            k2,
            src,
            unique,
            radial_scratch,
            radial,
            inv_k,
            a,
            s,
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
                    // The midpoint, as `cell_integral` takes it.
                    pa[j] = 0.5 * (self.psi_grid(kx, ky[j], freq) * dkx * dky);
                    pb[j] = 0.5 * (self.psi_grid(-kx, -ky[j], freq) * dkx * dky);
                    continue;
                }
                slot[j] = cells.len();
                cells.push(Cell {
                    j,
                    nx,
                    ny,
                    start: x.len(),
                });
                for (cx, cy) in [(kx, ky[j]), (-kx, -ky[j])] {
                    for &(ox, _) in &self.rules[nx - 1] {
                        let xn = cx + ox * dkx;
                        for &(oy, _) in &self.rules[ny - 1] {
                            x.push(xn);
                            y.push(cy + oy * dky);
                        }
                    }
                }
            }
        }
        if cells.is_empty() {
            return;
        }
        // The distinct k²: a node takes the radial part of its mirror image where their
        // k² are equal bit for bit (the image in the cell at −ky of the line, reflected in
        // y, and the −k cell's node reflected through the cell's centre).
        k2.clear();
        k2.extend(x.iter().zip(y.iter()).map(|(&x, &y)| x * x + y * y));
        src.clear();
        unique.clear();
        let mut place = |i: usize, image: Option<usize>, src: &mut Vec<usize>| match image {
            Some(m) if k2[m].to_bits() == k2[i].to_bits() => src.push(src[m]),
            _ => {
                src.push(unique.len());
                unique.push(k2[i]);
            }
        };
        for c in cells.iter() {
            let nn = c.nx * c.ny;
            // The cell at −ky[j] of this line, if it came earlier with the same rule.
            let mirror = (c.j > 0)
                .then(|| n - c.j)
                .filter(|&jm| jm < c.j && ky[jm] == -ky[c.j])
                .and_then(|jm| cells.get(slot[jm]).copied())
                .filter(|m| m.j == n - c.j && m.nx == c.nx && m.ny == c.ny);
            for t in 0..nn {
                let image = mirror.map(|m| m.start + (t / c.ny) * c.ny + (c.ny - 1 - t % c.ny));
                place(c.start + t, image, src);
            }
            for t in 0..nn {
                place(c.start + nn + t, Some(c.start + nn - 1 - t), src);
            }
        }
        self.radial_line(unique, freq, radial_scratch, radial);
        // Ψ at every node.
        let nodes = x.len();
        psi.resize(nodes, 0.0);
        if self.kind == SpreadKind::DonelanBanner {
            for i in 0..nodes {
                psi[i] = self.angular(&radial_at(radial, src[i]), x[i], y[i]);
            }
        } else {
            inv_k.clear();
            a.clear();
            s.clear();
            inv_k.extend(src.iter().map(|&u| radial.inv_k[u]));
            a.extend(src.iter().map(|&u| radial.a[u]));
            s.extend(src.iter().map(|&u| radial.s[u]));
            flags.resize(nodes, 0);
            if angular_nodes(
                isa, self.wx, self.wy, self.kind, x, y, inv_k, a, s, psi, flags,
            ) {
                for i in 0..nodes {
                    if flags[i] != 0 {
                        psi[i] = self.angular(&radial_at(radial, src[i]), x[i], y[i]);
                    }
                }
            }
        }
        // Each cell's sum in the order of `cell_integral`.
        for c in cells.iter() {
            let nn = c.nx * c.ny;
            for (half, out) in [(c.start, &mut pa[c.j]), (c.start + nn, &mut pb[c.j])] {
                let vals = &psi[half..half + nn];
                let mut sum = 0.0;
                for (row, &(_, wx)) in vals.chunks_exact(c.ny).zip(&self.rules[c.nx - 1]) {
                    let mut line = 0.0;
                    for (&v, &(_, wy)) in row.iter().zip(&self.rules[c.ny - 1]) {
                        line += wy * v;
                    }
                    sum += wx * line;
                }
                *out = 0.5 * (sum * dkx * dky);
            }
        }
    }
}

/// Entry `u` of a line of radial parts.
#[inline(always)]
fn radial_at(r: &RadialLine, u: usize) -> Radial {
    Radial {
        inv_k: r.inv_k[u],
        a: r.a[u],
        s: r.s[u],
        beta: r.beta[u],
    }
}
