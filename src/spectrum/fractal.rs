//! Fractal (1/f) terrain spectrum (Mastin Figs. 2–3, after Voss): an isotropic power law
//! in the wavenumber, without dispersion.
//!
//! A 2D fBm surface of Hurst exponent H has fractal dimension D = 3 − H and spectral
//! density Ψ(k) ∝ k^{−(2H+2)} = k^{−β}, β = 8 − 2D (2 < D < 3, so 2 < β < 4).
//!
//! Optional low-frequency attenuation (Mastin Fig. 3, "Gaussian attenuation of the lower
//! frequencies ... forced to fit at the peak"): a Gaussian in wavelength,
//!
//! Ψ(k) ∝ k^{−β} · exp(−(β/2)(k_r/k)²),  k_r = 2π / rolloff_m,
//!
//! whose maximum is exactly at k = k_r (d ln Ψ/dk = −β/k + β k_r²/k³), i.e. at the
//! wavelength `rolloff_m`, and which is the pure power law for k ≫ k_r. (A factor
//! 1 − exp(−(k/k0)²) would not do: for β > 2 the product has no interior maximum.)
//!
//! Scale: the expected variance of the field, Σ over the resolved wavevectors of
//! P(k) + P(−k), is relief_m². It depends on the grid, so the normalized spectrum is
//! [`FractalOnGrid`], made by [`Fractal::normalized_for`].

use rayon::prelude::*;

use super::{LineQuery, Spectrum};
use crate::error::ParamError;
use crate::fastmath::{exp, ln};

/// A validated fractal spectrum (not yet scaled to a grid).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fractal {
    dimension: f64,
    relief_m: f64,
    rolloff_m: Option<f64>,
    /// β/2.
    half_beta: f64,
    /// k_r² (0 without roll-off).
    kr2: f64,
}

impl Fractal {
    /// `dimension` in (2, 3), `relief_m` > 0 (the expected standard deviation of the
    /// heights), `rolloff_m` > 0 if given (the wavelength of the spectral peak).
    pub fn new(dimension: f64, relief_m: f64, rolloff_m: Option<f64>) -> Result<Self, ParamError> {
        let err = |name: &str, allowed: &str, got: f64| ParamError {
            name: name.into(),
            allowed: allowed.into(),
            got: got.to_string(),
        };
        if !(dimension > 2.0 && dimension < 3.0) {
            return Err(err("fractal.dimension", "> 2 and < 3", dimension));
        }
        if !(relief_m > 0.0 && relief_m.is_finite()) {
            return Err(err("fractal.relief_m", "> 0 m", relief_m));
        }
        let mut kr2 = 0.0;
        if let Some(r) = rolloff_m {
            if !(r > 0.0 && r.is_finite()) {
                return Err(err("fractal.rolloff_m", "> 0 m", r));
            }
            let kr = 2.0 * std::f64::consts::PI / r;
            kr2 = kr * kr;
        }
        Ok(Self {
            dimension,
            relief_m,
            rolloff_m,
            half_beta: 4.0 - dimension,
            kr2,
        })
    }

    pub fn dimension(&self) -> f64 {
        self.dimension
    }
    pub fn relief_m(&self) -> f64 {
        self.relief_m
    }
    pub fn rolloff_m(&self) -> Option<f64> {
        self.rolloff_m
    }
    /// The spectral exponent β = 8 − 2D.
    pub fn beta(&self) -> f64 {
        2.0 * self.half_beta
    }

    /// k^{−β}·exp(−(β/2)(k_r/k)²) (the second factor only with a roll-off); 0 at k = 0.
    #[inline]
    pub fn psi_unnormalized(&self, kx: f64, ky: f64) -> f64 {
        let k2 = kx * kx + ky * ky;
        if k2.is_nan() || k2 <= 0.0 {
            return 0.0;
        }
        exp(-self.half_beta * (ln(k2) + self.kr2 / k2))
    }

    /// The spectrum scaled for an `nx` × `ny` grid over `extent_x_m` × `extent_y_m`:
    /// Σ over the resolved wavevectors (k ≠ 0, no Nyquist row or column, as
    /// [`crate::field::fft::is_resolved`]) of P(k) + P(−k) equals relief_m².
    pub fn normalized_for(
        &self,
        nx: usize,
        ny: usize,
        extent_x_m: f64,
        extent_y_m: f64,
    ) -> FractalOnGrid {
        assert!(
            nx >= 1 && ny >= 1 && extent_x_m > 0.0 && extent_y_m > 0.0,
            "grid {nx}×{ny} over {extent_x_m}×{extent_y_m}"
        );
        let tau = 2.0 * std::f64::consts::PI;
        let (dkx, dky) = (tau / extent_x_m, tau / extent_y_m);
        // The resolved set is |n| ≤ (nx−1)/2, |m| ≤ (ny−1)/2 without (0, 0), symmetric in
        // each sign, and Ψ is even in kx and ky: sum the quadrant n, m ≥ 0 with weight 2
        // for each non-zero index. Rows are summed in parallel and added in order, so the
        // result does not depend on the thread count.
        let (nmax, mmax) = ((nx - 1) / 2, (ny - 1) / 2);
        let rows: Vec<f64> = (0..=mmax)
            .into_par_iter()
            .map(|m| {
                let ky = m as f64 * dky;
                let mut s = 0.0;
                for n in 0..=nmax {
                    let w = if n == 0 { 1.0 } else { 2.0 };
                    s += w * self.psi_unnormalized(n as f64 * dkx, ky);
                }
                if m == 0 { s } else { 2.0 * s }
            })
            .collect();
        let sum: f64 = rows.iter().sum();
        // Σ_k (P(k) + P(−k)) = 2·scale·Σ_k Ψ.
        let scale = if sum > 0.0 {
            self.relief_m * self.relief_m / (2.0 * sum)
        } else {
            0.0
        };
        FractalOnGrid {
            fractal: *self,
            scale,
            nx,
            ny,
            extent_x_m,
            extent_y_m,
        }
    }
}

/// A [`Fractal`] scaled to one grid (see [`Fractal::normalized_for`]); valid for that grid
/// only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FractalOnGrid {
    fractal: Fractal,
    /// P(k) = scale·Ψ(k).
    scale: f64,
    nx: usize,
    ny: usize,
    extent_x_m: f64,
    extent_y_m: f64,
}

impl FractalOnGrid {
    pub fn fractal(&self) -> &Fractal {
        &self.fractal
    }
    /// P(k) = scale · k^{−β}… , m²·(rad/m)^β.
    pub fn scale(&self) -> f64 {
        self.scale
    }
    /// The grid it was scaled for: (nx, ny, extent_x_m, extent_y_m).
    pub fn grid(&self) -> (usize, usize, f64, f64) {
        (self.nx, self.ny, self.extent_x_m, self.extent_y_m)
    }
}

impl Spectrum for FractalOnGrid {
    /// The point value scale·Ψ(k) (the grid spacing is the one of `normalized_for`).
    #[inline]
    fn amplitude_variance(&self, kx: f64, ky: f64, _dkx: f64, _dky: f64) -> f64 {
        self.scale * self.fractal.psi_unnormalized(kx, ky)
    }

    fn amplitude_variance_line(&self, q: &LineQuery, out: &mut [f64]) {
        for (o, &y) in out.iter_mut().zip(q.ky) {
            *o = self.scale * self.fractal.psi_unnormalized(q.kx, y);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::fft::{is_resolved, signed_index};

    #[test]
    fn log_log_slope_is_minus_eight_minus_two_d() {
        const REL_TOL: f64 = 1e-9;
        for d in [2.05, 2.2, 2.5, 2.8, 2.95] {
            let f = Fractal::new(d, 10.0, None).unwrap();
            let want = -(8.0 - 2.0 * d);
            for (k1, k2) in [(0.01, 0.02), (0.3, 7.0), (1.0, 1000.0)] {
                for a in [0.0, 0.7, 2.0] {
                    let (c, s) = (f64::cos(a), f64::sin(a));
                    let p1 = f.psi_unnormalized(k1 * c, k1 * s);
                    let p2 = f.psi_unnormalized(k2 * c, k2 * s);
                    let slope = (p2.ln() - p1.ln()) / (k2 / k1).ln();
                    assert!(
                        (slope - want).abs() <= REL_TOL * want.abs(),
                        "D {d}: slope {slope} vs {want} over [{k1}, {k2}]"
                    );
                }
            }
        }
    }

    #[test]
    fn rolloff_puts_the_peak_at_the_rolloff_wavelength() {
        for (d, r) in [(2.2, 50.0), (2.9, 7.0), (2.01, 300.0)] {
            let f = Fractal::new(d, 1.0, Some(r)).unwrap();
            let kr = 2.0 * std::f64::consts::PI / r;
            let peak = f.psi_unnormalized(kr, 0.0);
            for e in [1e-3, 1e-2, 0.1, 0.5] {
                assert!(
                    f.psi_unnormalized(kr * (1.0 + e), 0.0) < peak,
                    "D {d}: above the peak by {e}"
                );
                assert!(
                    f.psi_unnormalized(kr * (1.0 - e), 0.0) < peak,
                    "D {d}: below the peak by {e}"
                );
            }
            // Far above the peak the power law returns.
            let k = 1000.0 * kr;
            let pure = Fractal::new(d, 1.0, None).unwrap();
            let ratio = f.psi_unnormalized(k, 0.0) / pure.psi_unnormalized(k, 0.0);
            assert!((ratio - 1.0).abs() < 1e-5, "D {d}: ratio {ratio}");
        }
    }

    #[test]
    fn normalized_variance_is_relief_squared() {
        const REL_TOL: f64 = 1e-9;
        for (nx, ny, lx, ly, roll) in [
            (64, 64, 1000.0, 1000.0, None),
            (65, 48, 300.0, 700.0, Some(40.0)),
            (32, 33, 50.0, 20.0, Some(500.0)),
            (2, 3, 10.0, 10.0, None),
        ] {
            let f = Fractal::new(2.3, 12.0, roll).unwrap();
            let g = f.normalized_for(nx, ny, lx, ly);
            let tau = 2.0 * std::f64::consts::PI;
            let (dkx, dky) = (tau / lx, tau / ly);
            let mut var = 0.0;
            for i in 0..nx {
                for j in 0..ny {
                    let (n, m) = (signed_index(i, nx), signed_index(j, ny));
                    if is_resolved(n, m, nx, ny) {
                        let (kx, ky) = (n as f64 * dkx, m as f64 * dky);
                        var += g.amplitude_variance(kx, ky, dkx, dky)
                            + g.amplitude_variance(-kx, -ky, dkx, dky);
                    }
                }
            }
            assert!(
                (var - 144.0).abs() <= REL_TOL * 144.0,
                "{nx}×{ny}: variance {var} vs 144"
            );
        }
        // Nothing resolved: a zero spectrum, not NaN.
        let g = Fractal::new(2.3, 1.0, None)
            .unwrap()
            .normalized_for(2, 2, 1.0, 1.0);
        assert_eq!(g.scale(), 0.0);
    }

    #[test]
    fn invalid_parameters_name_the_parameter() {
        assert_eq!(
            Fractal::new(3.0, 1.0, None).unwrap_err().name,
            "fractal.dimension"
        );
        assert_eq!(
            Fractal::new(2.0, 1.0, None).unwrap_err().allowed,
            "> 2 and < 3"
        );
        assert_eq!(
            Fractal::new(2.5, 0.0, None).unwrap_err().name,
            "fractal.relief_m"
        );
        assert_eq!(
            Fractal::new(2.5, 1.0, Some(-4.0)).unwrap_err().name,
            "fractal.rolloff_m"
        );
    }
}
