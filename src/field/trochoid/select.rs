//! Component selection (Thon et al. §2.2): the directional spectrum sampled on a small
//! matrix of wavevectors, and its n strongest cells as trochoid components.
//!
//! The matrix is the Fourier grid of a virtual square tile of side L (`matrix_extent_m`):
//! cell (n, m), n, m ∈ [−M/2, M/2), holds the wavevector k = 2π(n, m)/L and the model's
//! E|h̃0(k)|² = P(k) for that spacing (the [`Spectrum`](crate::spectrum::Spectrum) trait,
//! as the FFT methods use it).
//! In the FFT sum, the cell's wave has amplitude 2|h̃0(k)| and travels along +k, so the
//! component gets the expected amplitude A = 2√P(k) (its variance A²/2 = 2P(k) is the
//! cell's share of the field's) and a random phase hashed from (seed, n, m). Cells are
//! ranked by P, ties by (n, m).
//!
//! **Placement inside the cell.** On the cell centres 2π(n, m)/L every component repeats
//! over the tile, so the whole sum would repeat every L (3 peak wavelengths by default: a
//! regular lattice of look-alike patches in any window larger than the tile). Thon et al.
//! sample the spectrum cell by cell, so a cell's energy may sit anywhere in it: each
//! component's wavevector is the centre plus (u, v)·(Δkx, Δky) with u, v uniform in
//! [−½, ½) hashed from (seed, n, m) apart from the phase, ω from the dispersion relation
//! at that wavevector. The sum then has no period and its autocorrelation no secondary
//! peak (tested in the parent module).

use crate::field::fft::SpectrumSetup;
use crate::rng;
use crate::spectrum::LineQuery;

/// One trochoid: h = amplitude·v(k·x − ωt + phase).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Component {
    /// Matrix indices (n, m).
    pub index: (i64, i64),
    /// Wavevector, rad/m.
    pub k: (f64, f64),
    /// Angular frequency, rad/s (rounded for a loop when one is set).
    pub omega: f64,
    /// Amplitude A = 2√P, m.
    pub amplitude_m: f64,
    /// Phase at t = 0, rad.
    pub phase: f64,
}

impl Component {
    pub fn wavenumber(&self) -> f64 {
        self.k.0.hypot(self.k.1)
    }
}

/// The matrix: P(k) of every cell, row n = −M/2.. (outer), column m = −M/2.. (inner).
pub fn sample_matrix(setup: &SpectrumSetup, size: usize) -> Vec<((i64, i64), f64)> {
    let half = size as i64 / 2;
    let (dkx, dky) = setup.dk();
    let ms: Vec<i64> = (-half..half).collect();
    let ky: Vec<f64> = ms.iter().map(|&m| setup.wavevector(0, m).1).collect();
    let mut p = vec![0.0; size];
    let mut cells = Vec::with_capacity(size * size);
    for n in -half..half {
        let kx = setup.wavevector(n, 0).0;
        let q = LineQuery {
            kx,
            ky: &ky,
            dkx,
            dky,
        };
        setup.spectrum.amplitude_variance_line(&q, &mut p);
        for (&m, &v) in ms.iter().zip(&p) {
            let v = if n == 0 && m == 0 { 0.0 } else { v };
            cells.push(((n, m), v));
        }
    }
    cells
}

/// The `count` strongest cells of the matrix as components, strongest first.
pub fn select(setup: &SpectrumSetup, size: usize, count: usize, seed: u64) -> Vec<Component> {
    let mut cells = sample_matrix(setup, size);
    cells.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    cells
        .into_iter()
        .take(count)
        .filter(|&(_, p)| p > 0.0)
        .map(|((n, m), p)| {
            let (kx, ky) = in_cell(setup, seed, n, m);
            let bits = rng::hash_words(&[seed, n as u64, m as u64]);
            let phase = (bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64) * std::f64::consts::TAU;
            Component {
                index: (n, m),
                k: (kx, ky),
                omega: setup.omega(kx, ky),
                amplitude_m: 2.0 * p.sqrt(),
                phase,
            }
        })
        .collect()
}

/// The wavevector of cell (n, m): its centre moved by a uniform draw within ±½ cell on
/// each axis, hashed from (seed, n, m) (see the module docs).
pub fn in_cell(setup: &SpectrumSetup, seed: u64, n: i64, m: i64) -> (f64, f64) {
    let (kx, ky) = setup.wavevector(n, m);
    let (dkx, dky) = setup.dk();
    let bits = rng::hash_words(&[seed, n as u64, m as u64, JITTER_WORD]);
    let unit = |w: u64| (w & 0xffff_ffff) as f64 / (1u64 << 32) as f64 - 0.5;
    (kx + unit(bits) * dkx, ky + unit(bits >> 32) * dky)
}

/// Keeps the jitter's draws apart from the phase's (a fourth hashed word).
const JITTER_WORD: u64 = 1;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{
        DirectionalSpectrum, Dispersion, PiersonMoskowitz, Spreading, SpreadingModel,
    };

    #[test]
    fn the_selected_components_are_the_n_largest_cells_of_the_matrix() {
        let pm = PiersonMoskowitz::from_wind(12.0).unwrap();
        let spreading = Spreading::new(SpreadingModel::Hasselmann, 0.0).unwrap();
        let spectrum =
            DirectionalSpectrum::new(Box::new(pm), spreading, 0.3, 12.0, Dispersion::Deep).unwrap();
        let setup = SpectrumSetup {
            spec: crate::grid::GridSpec::new(64, 64, 400.0, 400.0),
            spectrum: &spectrum,
            dispersion: Dispersion::Deep,
            seed: 0,
            time_s: 0.0,
            loop_period_s: None,
        };
        let matrix = sample_matrix(&setup, 64);
        assert_eq!(matrix.len(), 64 * 64);
        let n = 40;
        let chosen = select(&setup, 64, n, 7);
        assert_eq!(chosen.len(), n);
        // A naive reference: every cell's P, sorted, the n-th largest is the threshold.
        let mut ps: Vec<f64> = matrix.iter().map(|c| c.1).collect();
        ps.sort_by(|a, b| b.total_cmp(a));
        let threshold = ps[n - 1];
        for c in &chosen {
            let p = matrix.iter().find(|m| m.0 == c.index).unwrap().1;
            assert!(
                p >= threshold,
                "cell {:?} with P {p} below the n-th largest {threshold}",
                c.index
            );
            let want = 2.0 * p.sqrt();
            assert!(
                (c.amplitude_m - want).abs() <= 1e-15 * want,
                "amplitude of {:?}",
                c.index
            );
            // Inside its cell, not on the centre, ω at the wavevector used.
            let (kx, ky) = setup.wavevector(c.index.0, c.index.1);
            let (dkx, dky) = setup.dk();
            assert!(
                (c.k.0 - kx).abs() <= 0.5 * dkx && (c.k.1 - ky).abs() <= 0.5 * dky,
                "{:?} leaves its cell",
                c.index
            );
            assert_ne!(c.k, (kx, ky));
            assert_eq!(
                c.omega,
                Dispersion::Deep.omega((c.k.0 * c.k.0 + c.k.1 * c.k.1).sqrt())
            );
            assert!((0.0..std::f64::consts::TAU).contains(&c.phase));
        }
        let sum_chosen: f64 = chosen.iter().map(|c| c.amplitude_m.powi(2) / 4.0).sum();
        let sum_top: f64 = ps[..n].iter().sum();
        assert!(
            (sum_chosen - sum_top).abs() <= 1e-12 * sum_top,
            "the n largest, no other"
        );
        // Strongest first, and the phases depend on the seed.
        assert!(
            chosen
                .windows(2)
                .all(|w| w[0].amplitude_m >= w[1].amplitude_m)
        );
        assert_ne!(chosen[0].phase, select(&setup, 64, n, 8)[0].phase);
    }
}
