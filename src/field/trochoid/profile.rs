//! The trochoid profile v(·) of Thon et al. eq. 2–3 as a look-up table.
//!
//! A Gerstner particle circles with radius r around (x0, z0): x = x0 + r sin(k x0 − ωt),
//! z = z0 − r cos(k x0 − ωt). Shifting the parameter by π so the crest sits at phase 0,
//! the profile over one period is the curve
//!
//! ```text
//! φ(θ) = θ − kr·sin θ,   v(θ) = cos θ + kr/2,   θ ∈ [−π, π]
//! ```
//!
//! (φ = k x is the phase along the wave; Kepler's equation gives θ of φ). v replaces cos in
//! h = A·v(k·x − ωt + φ0): kr = 0 is exactly a cosine; as kr → 1 the crests sharpen to a
//! cusp and the troughs flatten. The kr/2 removes the mean level of the trochoid
//! (⟨cos θ⟩ over φ is −kr/2), so every component has zero mean; its crest is 1 + kr/2 and
//! its trough −1 + kr/2 above the mean, and its variance 1/2 − (kr)²/4.
//!
//! The table holds v at `LUT_SIZE` phases evenly spread over one period (solved by Newton's
//! method to round-off) and is read with linear interpolation: the error is at most
//! max|v''|·h²/8 with h = 2π/LUT_SIZE: 2.9e-7 for a cosine, more near a sharp crest
//! (measured in the tests).

use crate::fastmath;

/// Table entries per period.
pub const LUT_SIZE: usize = 4096;

/// v over one period, for one sharpness.
#[derive(Debug, Clone)]
pub struct Profile {
    sharpness: f64,
    /// v at phase turns t_j = −1/2 + j/LUT_SIZE, j = 0..=LUT_SIZE + 1 (wrapping: the last
    /// two repeat the first two, so an interpolation never reads past the end).
    table: Box<Table>,
}

/// The table with its two wrapped entries: a fixed length, so reads need no bounds checks
/// and the lookup loop vectorizes.
pub type Table = [f32; LUT_SIZE + 2];

/// θ of φ ∈ [−π, π] on the trochoid of sharpness kr < 1: θ − kr sin θ = φ (Newton).
pub fn solve_theta(phi: f64, kr: f64) -> f64 {
    // θ − kr sin θ is increasing; start from φ + kr sin φ (one fixed-point step).
    let mut theta = phi + kr * fastmath::sin_cos(phi).0;
    for _ in 0..60 {
        let (s, c) = fastmath::sin_cos(theta);
        let f = theta - kr * s - phi;
        let step = f / (1.0 - kr * c);
        theta -= step;
        if step.abs() <= 1e-15 {
            break;
        }
    }
    theta
}

impl Profile {
    /// The table of sharpness `kr` (0 ≤ kr < 1, checked by validation).
    pub fn new(kr: f64) -> Self {
        assert!(
            (0.0..1.0).contains(&kr),
            "trochoid sharpness kr = {kr} outside [0, 1)"
        );
        let tau = std::f64::consts::TAU;
        let mut table: Vec<f32> = (0..LUT_SIZE)
            .map(|j| {
                let phi = tau * (j as f64 / LUT_SIZE as f64 - 0.5);
                let theta = solve_theta(phi, kr);
                (fastmath::sin_cos(theta).1 + 0.5 * kr) as f32
            })
            .collect();
        table.push(table[0]);
        table.push(table[1]);
        Self {
            sharpness: kr,
            table: table
                .into_boxed_slice()
                .try_into()
                .expect("LUT_SIZE + 2 entries"),
        }
    }

    pub fn sharpness(&self) -> f64 {
        self.sharpness
    }

    pub(crate) fn table(&self) -> &Table {
        &self.table
    }

    /// v at phase φ = 2π·u (u in turns, any value).
    #[inline]
    pub fn value_turns(&self, u: f64) -> f32 {
        lookup(&self.table, u)
    }

    /// The exact profile at phase `phi` (radians, any value), for tests and plots.
    pub fn exact(&self, phi: f64) -> f64 {
        let tau = std::f64::consts::TAU;
        let p = phi - tau * (phi / tau).round();
        fastmath::sin_cos(solve_theta(p, self.sharpness)).1 + 0.5 * self.sharpness
    }
}

/// 2^52 + 2^51: x + ROUND_MAGIC − ROUND_MAGIC rounds x (|x| < 2^51) to an integer, and
/// the low bits of x + ROUND_MAGIC hold that integer in two's complement.
const ROUND_MAGIC: f64 = 6_755_399_441_055_744.0;

/// The table at table position `pos` = (u + 1/2)·LUT_SIZE for a phase of u turns (node j at
/// pos ≡ j mod LUT_SIZE), read with linear interpolation. The floor of pos and its residue
/// modulo LUT_SIZE come from the bits of pos + 2^52 + 2^51, so the loop is IEEE
/// operations and integer masks only: the same bits in every path, and it vectorizes.
#[inline(always)]
pub(crate) fn lookup_pos(table: &Table, pos: f64) -> f32 {
    let t = pos + ROUND_MAGIC;
    let r = t - ROUND_MAGIC;
    let below = (r > pos) as u64;
    let j = (t.to_bits().wrapping_sub(below) as usize) & (LUT_SIZE - 1);
    let w = (pos - (r - below as f64)) as f32;
    let (a, b) = (table[j], table[j + 1]);
    a + w * (b - a)
}

/// The table at phase `u` turns.
#[inline(always)]
pub(crate) fn lookup(table: &Table, u: f64) -> f32 {
    lookup_pos(table, u * LUT_SIZE as f64 + (LUT_SIZE / 2) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sharpness_zero_is_a_cosine() {
        // Linear interpolation of cos between nodes h = 2π/4096 apart: error ≤ h²/8 = 2.9e-7,
        // plus the f32 rounding of the table (≤ 6e-8).
        const TOL: f64 = 3.6e-7;
        let p = Profile::new(0.0);
        let mut worst = 0.0f64;
        for i in 0..100_003 {
            let u = -3.0 + i as f64 * 6.0 / 100_003.0;
            let got = p.value_turns(u) as f64;
            let want = (std::f64::consts::TAU * u).cos();
            worst = worst.max((got - want).abs());
        }
        assert!(worst <= TOL, "kr = 0: |v − cos| up to {worst:e} > {TOL:e}");
        for j in 0..LUT_SIZE {
            let phi = std::f64::consts::TAU * (j as f64 / LUT_SIZE as f64 - 0.5);
            let node = p.table()[j] as f64;
            assert!(
                (node - phi.cos()).abs() <= 6e-8,
                "node {j}: {node} vs cos {}",
                phi.cos()
            );
        }
    }

    #[test]
    fn the_table_follows_the_parametric_curve() {
        // Points (φ(θ), v(θ)) of the curve, θ on a fine grid, against the table. Linear
        // interpolation error ≈ max|v''|·h²/8; |v''| grows like 1/(1 − kr)³ at the crest.
        for (kr, tol) in [(0.3, 1e-6), (0.6, 5e-6), (0.9, 6e-4)] {
            let p = Profile::new(kr);
            let mut worst = 0.0f64;
            for i in 0..20_000 {
                let theta = -std::f64::consts::PI + i as f64 * std::f64::consts::TAU / 20_000.0;
                let phi = theta - kr * theta.sin();
                let want = theta.cos() + kr / 2.0;
                let got = p.value_turns(phi / std::f64::consts::TAU) as f64;
                worst = worst.max((got - want).abs());
                let exact = p.exact(phi);
                assert!((exact - want).abs() < 1e-12, "kr {kr}: Newton at θ {theta}");
            }
            assert!(
                worst <= tol,
                "kr = {kr}: table off the curve by {worst:e} > {tol:e}"
            );
        }
    }

    #[test]
    fn the_profile_has_zero_mean_a_sharp_crest_and_a_flat_trough() {
        let kr = 0.7;
        let p = Profile::new(kr);
        let mean: f64 =
            p.table()[..LUT_SIZE].iter().map(|&v| v as f64).sum::<f64>() / LUT_SIZE as f64;
        assert!(mean.abs() < 1e-6, "mean {mean}");
        let crest = p.value_turns(0.0) as f64;
        let trough = p.value_turns(0.5) as f64;
        assert!((crest - (1.0 + kr / 2.0)).abs() < 1e-6, "crest {crest}");
        assert!((trough - (-1.0 + kr / 2.0)).abs() < 1e-6, "trough {trough}");
        // Half-height width: narrower around the crest than around the trough.
        let above = p.table()[..LUT_SIZE]
            .iter()
            .filter(|&&v| v as f64 > kr / 2.0)
            .count();
        assert!(above < LUT_SIZE / 2, "crest region {above} of {LUT_SIZE}");
    }
}
