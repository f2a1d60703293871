//! Fields derived from the spectrum h̃(k, t): exact slopes, choppy displacement and its
//! Jacobian (Tessendorf, as written up by Li, He and Gong), and the choppy height map.
//!
//! Every derived field is the inverse transform of h̃ times a factor of k, so it costs one
//! real (complex-to-real) transform and no finite differences:
//!
//! | field | factor | |
//! |---|---|---|
//! | slopes ∂h/∂x, ∂h/∂y | i kx, i ky | exact spectral derivatives |
//! | displacement Dx, Dy | i kx/k, i ky/k | D = Σ i k̂ h̃ e^{ik·x} |
//! | ∂Dx/∂x, ∂Dy/∂y, ∂Dx/∂y = ∂Dy/∂x | −kx²/k, −ky²/k, −kx ky/k | for the Jacobian |
//!
//! # The sign of the displacement
//! A point x of the still surface moves to x + λD(x). The published form
//! D = Σ −i k̂ h̃ e^{ik·x} moves points *away* from the crests (for h = A cos kx it gives
//! D = A sin kx), flattening crests and sharpening troughs. seasynth uses
//! D = Σ +i k̂ h̃ e^{ik·x}: for h = A cos kx, D = −A sin kx, so x = x0 − λA sin kx0,
//! z = A cos kx0 is exactly Gerstner's trochoid and λ > 0 sharpens crests.
//!
//! # Jacobian and foam
//! J = (1 + λ ∂Dx/∂x)(1 + λ ∂Dy/∂y) − λ² (∂Dx/∂y)²: the area change of the displacement;
//! J < 0 where the surface folds over. Foam is where J < the threshold.
//!
//! # Choppy height map
//! The displaced surface is (x0 + λD(x0), h(x0)). Its height at a grid point x is h(x0)
//! with x0 solving x0 + λD(x0) = x, found by the fixed-point iteration
//! x0 ← x − λD(x0) (bilinear, periodic interpolation of D; at most `CHOPPY_ITERATIONS`
//! steps, fewer once a step moves x0 by less than 1e-4 of a sample; it converges wherever
//! the surface does not fold, λ|∂D| < 1), then h(x0) by bilinear interpolation. Normal, foam and displacement maps stay on the undisplaced grid
//! (vertex i, j of a displacement-mapped mesh), as engines apply them.

use rayon::prelude::*;
use rustfft::num_complex::Complex32;

use super::fft::{HalfSpectrum, InverseFft2, signed_index};
use crate::grid::GridSpec;

/// Largest number of fixed-point steps of the choppy resampling …
pub const CHOPPY_ITERATIONS: usize = 8;
/// … which stops early once a step moves the point less than this, in samples (a height
/// error below 1e-4·dx·|slope|).
const CHOPPY_CONVERGED: f64 = 1e-4;

/// A derived field: the factor that multiplies h̃(k).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Derivative {
    SlopeX,
    SlopeY,
    DispX,
    DispY,
    DxX,
    DyY,
    DxY,
}

impl Derivative {
    /// The factor at (kx, ky): (re, im).
    #[inline]
    fn factor(self, kx: f64, ky: f64) -> (f64, f64) {
        let k = (kx * kx + ky * ky).sqrt();
        if k == 0.0 {
            return (0.0, 0.0);
        }
        match self {
            Derivative::SlopeX => (0.0, kx),
            Derivative::SlopeY => (0.0, ky),
            Derivative::DispX => (0.0, kx / k),
            Derivative::DispY => (0.0, ky / k),
            Derivative::DxX => (-kx * kx / k, 0.0),
            Derivative::DyY => (-ky * ky / k, 0.0),
            Derivative::DxY => (-kx * ky / k, 0.0),
        }
    }
}

/// h̃(k) times the factor of `d`, for every stored wavevector (still Hermitian: every
/// factor has f(−k) = conj f(k)).
pub fn derivative_spectrum(half: &HalfSpectrum, spec: &GridSpec, d: Derivative) -> HalfSpectrum {
    let (nx, ny) = (half.nx, half.ny);
    let tau = std::f64::consts::TAU;
    let mut data = half.data.clone();
    data.par_chunks_mut(ny).enumerate().for_each(|(n, line)| {
        let kx = tau * n as f64 / spec.extent_x_m;
        for (idx, v) in line.iter_mut().enumerate() {
            let ky = tau * signed_index(idx, ny) as f64 / spec.extent_y_m;
            let (fr, fi) = d.factor(kx, ky);
            let (fr, fi) = (fr as f32, fi as f32);
            *v = Complex32::new(v.re * fr - v.im * fi, v.re * fi + v.im * fr);
        }
    });
    HalfSpectrum {
        nx,
        ny,
        data,
        h0max_m: half.h0max_m,
    }
}

/// The real field of `d` on the grid.
pub fn derived_field(
    half: &HalfSpectrum,
    spec: &GridSpec,
    plan: &InverseFft2,
    d: Derivative,
) -> Vec<f32> {
    plan.process(derivative_spectrum(half, spec, d))
}

/// Which derived fields a run needs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Extras {
    pub slopes: bool,
    pub displacement: bool,
    pub jacobian: bool,
}

impl Extras {
    pub fn any(&self) -> bool {
        self.slopes || self.displacement || self.jacobian
    }
}

/// The derived fields of one state, each on the undisplaced grid, row-major.
#[derive(Debug, Clone, Default)]
pub struct Surface {
    /// ∂h/∂x, ∂h/∂y.
    pub slopes: Option<[Vec<f32>; 2]>,
    /// λ·Dx, λ·Dy in meters.
    pub displacement: Option<[Vec<f32>; 2]>,
    /// J of the displacement λD.
    pub jacobian: Option<Vec<f32>>,
    /// The heights before the choppy resampling (the z of a displacement map), when
    /// λ ≠ 0 and the displacement was asked for.
    pub undisplaced_height: Option<Vec<f32>>,
}

/// Computes the fields `extras` asks for (plus the displacement when λ ≠ 0, which the
/// choppy height needs) from h̃.
pub fn surface(
    half: &HalfSpectrum,
    spec: &GridSpec,
    plan: &InverseFft2,
    extras: Extras,
    lambda: f64,
) -> Surface {
    let field = |d| derived_field(half, spec, plan, d);
    let scaled = |d| {
        let mut v = field(d);
        let l = lambda as f32;
        v.par_iter_mut().for_each(|x| *x *= l);
        v
    };
    let slopes = extras
        .slopes
        .then(|| [field(Derivative::SlopeX), field(Derivative::SlopeY)]);
    let displacement = (extras.displacement || lambda != 0.0)
        .then(|| [scaled(Derivative::DispX), scaled(Derivative::DispY)]);
    let jacobian = extras.jacobian.then(|| {
        if lambda == 0.0 {
            return vec![1.0; spec.len()];
        }
        let (xx, yy, xy) = (
            scaled(Derivative::DxX),
            scaled(Derivative::DyY),
            scaled(Derivative::DxY),
        );
        xx.par_iter()
            .zip(&yy)
            .zip(&xy)
            .map(|((&a, &b), &c)| (1.0 + a) * (1.0 + b) - c * c)
            .collect()
    });
    Surface {
        slopes,
        displacement,
        jacobian,
        undisplaced_height: None,
    }
}

/// A sample index wrapped into 0..n (no division for the usual in-range values).
#[inline(always)]
fn wrap(i: i64, n: usize) -> usize {
    let n = n as i64;
    if (0..n).contains(&i) {
        i as usize
    } else {
        i.rem_euclid(n) as usize
    }
}

/// ⌊x⌋ for |x| < 2^52, without a library call.
#[inline(always)]
fn floor_i64(x: f64) -> i64 {
    let t = x as i64;
    t - ((t as f64) > x) as i64
}

/// Where a point falls in a periodic grid: the four corner offsets and the weights.
#[derive(Clone, Copy)]
struct Cell {
    at: [usize; 4],
    tx: f64,
    ty: f64,
}

impl Cell {
    #[inline(always)]
    fn new(nx: usize, ny: usize, x: f64, y: f64) -> Self {
        let (fx, fy) = (floor_i64(x), floor_i64(y));
        let (tx, ty) = (x - fx as f64, y - fy as f64);
        let (i0, j0) = (wrap(fx, nx), wrap(fy, ny));
        let i1 = if i0 + 1 == nx { 0 } else { i0 + 1 };
        let j1 = if j0 + 1 == ny { 0 } else { j0 + 1 };
        Self {
            at: [j0 * nx + i0, j0 * nx + i1, j1 * nx + i0, j1 * nx + i1],
            tx,
            ty,
        }
    }

    /// Bilinear interpolation of `f` in this cell.
    #[inline(always)]
    fn of(&self, f: &[f32]) -> f64 {
        let v = self.at.map(|p| f[p] as f64);
        let a = v[0] + (v[1] - v[0]) * self.tx;
        let b = v[2] + (v[3] - v[2]) * self.tx;
        a + (b - a) * self.ty
    }
}

/// The height of the displaced surface (x0 + λD(x0), h(x0)) at every grid point (see the
/// module docs). `displacement` is λD in meters.
pub fn resample_choppy(h: &[f32], displacement: &[Vec<f32>; 2], spec: &GridSpec) -> Vec<f32> {
    let (nx, ny) = (spec.nx, spec.ny);
    let (sx, sy) = (1.0 / spec.dx_m(), 1.0 / spec.dy_m());
    let mut out = vec![0.0f32; nx * ny];
    const LANES: usize = 4;
    out.par_chunks_mut(nx).enumerate().for_each(|(j, row)| {
        // LANES points at a time: their iterations are independent, so the processor
        // overlaps their memory loads.
        for (c, chunk) in row.chunks_mut(LANES).enumerate() {
            let y = j as f64;
            let mut x = [0.0; LANES];
            let mut x0 = [0.0; LANES];
            let mut y0 = [0.0; LANES];
            let mut done = [true; LANES];
            for l in 0..chunk.len() {
                let i = c * LANES + l;
                let p = j * nx + i;
                x[l] = i as f64;
                // First guess: the displacement at the grid point itself.
                x0[l] = x[l] - displacement[0][p] as f64 * sx;
                y0[l] = y - displacement[1][p] as f64 * sy;
                done[l] = false;
            }
            for _ in 0..CHOPPY_ITERATIONS {
                if done.iter().all(|&d| d) {
                    break;
                }
                for l in 0..LANES {
                    if done[l] {
                        continue;
                    }
                    let cell = Cell::new(nx, ny, x0[l], y0[l]);
                    let (nx0, ny0) = (
                        x[l] - cell.of(&displacement[0]) * sx,
                        y - cell.of(&displacement[1]) * sy,
                    );
                    let step = (nx0 - x0[l]).abs().max((ny0 - y0[l]).abs());
                    (x0[l], y0[l]) = (nx0, ny0);
                    done[l] = step < CHOPPY_CONVERGED;
                }
            }
            for (l, o) in chunk.iter_mut().enumerate() {
                *o = Cell::new(nx, ny, x0[l], y0[l]).of(h) as f32;
            }
        }
    });
    out
}

/// Unit normals (x, y, z) of the surface (x0 + λD, h) at every grid point, z up: the
/// cross product of the tangents (1 + λDx,x, λDy,x, hx) × (λDx,y, 1 + λDy,y, hy). Needs
/// the slopes; the displacement derivatives are taken as zero when `ddisp` is None.
pub fn normals(slopes: &[Vec<f32>; 2], ddisp: Option<[&[f32]; 3]>) -> Vec<[f32; 3]> {
    let n = slopes[0].len();
    (0..n)
        .into_par_iter()
        .map(|p| {
            let (hx, hy) = (slopes[0][p] as f64, slopes[1][p] as f64);
            let (a, b, c) = match ddisp {
                Some([xx, yy, xy]) => (xx[p] as f64, yy[p] as f64, xy[p] as f64),
                None => (0.0, 0.0, 0.0),
            };
            // Tangents tx = (1 + a, c, hx), ty = (c, 1 + b, hy).
            let nxv = c * hy - hx * (1.0 + b);
            let nyv = hx * c - (1.0 + a) * hy;
            let nzv = (1.0 + a) * (1.0 + b) - c * c;
            let len = (nxv * nxv + nyv * nyv + nzv * nzv).sqrt();
            if len == 0.0 {
                [0.0, 0.0, 1.0]
            } else {
                [(nxv / len) as f32, (nyv / len) as f32, (nzv / len) as f32]
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::fft::{OneComponent, SpectrumSetup, synthesize_spectrum};
    use crate::spectrum::{Dispersion, Phillips, Spectrum};

    fn setup(spec: GridSpec, s: &dyn Spectrum, t: f64) -> SpectrumSetup<'_> {
        SpectrumSetup {
            spec,
            spectrum: s,
            dispersion: Dispersion::Deep,
            seed: 3,
            time_s: t,
            loop_period_s: None,
        }
    }

    /// A cosine along x: h = A cos(k x + φ); returns (A, φ, k, grid, spectrum).
    fn cosine(n: i64, size: usize, extent: f64) -> (f64, f64, f64, GridSpec, HalfSpectrum) {
        let spec = GridSpec::new(size, 8, extent, extent * 8.0 / size as f64);
        let k = std::f64::consts::TAU * n as f64 / extent;
        let one = OneComponent {
            k: (k, 0.0),
            variance: 2.0,
        };
        let half = synthesize_spectrum(&setup(spec, &one, 0.0));
        // E|h̃0|² = p: h̃(k) = ρ e^{iφ}, h = 2ρ cos(kx + φ), A = 2ρ.
        let c = half.data[n as usize * 8];
        (2.0 * c.norm() as f64, c.arg() as f64, k, spec, half)
    }

    const FIELD_TOL: f64 = 2e-5;

    #[test]
    fn choppy_displacement_of_one_component_is_the_trochoid() {
        let (a, phi, k, spec, half) = cosine(3, 256, 100.0);
        let plan = InverseFft2::new(spec.nx, spec.ny);
        let h = plan.process(HalfSpectrum {
            data: half.data.clone(),
            ..half
        });
        // Steep but not folding: λAk = 0.6.
        let lambda = 0.6 / (a * k);
        let s = surface(
            &half,
            &spec,
            &plan,
            Extras {
                displacement: true,
                ..Default::default()
            },
            lambda,
        );
        let d = s.displacement.unwrap();
        // h = A cos(kx + φ) ⇒ λDx = −λA sin(kx + φ).
        for i in 0..spec.nx {
            let arg = k * spec.x_m(i) + phi;
            let want_h = a * arg.cos();
            let want_d = -lambda * a * arg.sin();
            assert!(
                (h[i] as f64 - want_h).abs() < FIELD_TOL * a * 10.0,
                "h[{i}]"
            );
            assert!(
                (d[0][i] as f64 - want_d).abs() < FIELD_TOL * a * 10.0,
                "λDx[{i}] = {} vs {want_d}",
                d[0][i]
            );
            assert!(d[1][i].abs() < 1e-6, "no displacement across the wave");
        }
        // The resampled height is the trochoid x = x0 − λA sin(kx0 + φ), z = A cos(kx0 + φ):
        // solve for x0 by Newton at each grid x and compare.
        let hc = resample_choppy(&h, &d, &spec);
        let mut worst: f64 = 0.0;
        for (i, &got) in hc.iter().enumerate().take(spec.nx) {
            let x = spec.x_m(i);
            let mut x0 = x;
            for _ in 0..50 {
                let f = x0 - lambda * a * (k * x0 + phi).sin() - x;
                let df = 1.0 - lambda * a * k * (k * x0 + phi).cos();
                x0 -= f / df;
            }
            let want = a * (k * x0 + phi).cos();
            worst = worst.max((got as f64 - want).abs() / a);
        }
        // Bilinear interpolation of a wave sampled 85 times per wavelength.
        const TROCHOID_TOL: f64 = 2e-3;
        eprintln!("choppy height vs trochoid: {worst:.2e} of A");
        assert!(worst < TROCHOID_TOL, "trochoid mismatch {worst:.2e} of A");
        // λ > 0: crests sharper and troughs flatter. The trochoid is above its mean level
        // where |kx0 + φ| < π/2, i.e. over π/k − 2λA of each wavelength 2π/k.
        let above = hc.iter().take(spec.nx).filter(|&&v| v > 0.0).count() as f64;
        let want = 0.5 - lambda * a * k / std::f64::consts::PI;
        assert!(
            (above / spec.nx as f64 - want).abs() <= 2.0 / spec.nx as f64,
            "crest fraction {} vs {want}",
            above / spec.nx as f64
        );
        assert!(
            hc.iter().cloned().fold(f32::MIN, f32::max) as f64 > 0.99 * a,
            "crest height kept"
        );
    }

    #[test]
    fn jacobian_is_one_without_choppiness_and_matches_the_trochoid_with_it() {
        let (a, _, k, spec, half) = cosine(3, 256, 100.0);
        let plan = InverseFft2::new(spec.nx, spec.ny);
        let all = Extras {
            slopes: true,
            displacement: true,
            jacobian: true,
        };
        let s0 = surface(&half, &spec, &plan, all, 0.0);
        assert!(s0.jacobian.unwrap().iter().all(|&j| j == 1.0));
        let lambda = 0.5;
        let s = surface(&half, &spec, &plan, all, lambda);
        let d = s.displacement.unwrap();
        let j = s.jacobian.unwrap();
        // J = 1 − λAk cos(kx + φ) = 1 + k·(λDx)' ... = 1 − λk·h(x) for the trochoid.
        let h = plan.process(HalfSpectrum {
            data: half.data.clone(),
            ..half
        });
        for i in 0..spec.nx {
            let want = 1.0 - lambda * k * h[i] as f64;
            assert!(
                (j[i] as f64 - want).abs() < 1e-4,
                "J[{i}] = {} vs {want}",
                j[i]
            );
        }
        assert!(d[0].iter().any(|&v| v.abs() as f64 > 0.4 * lambda * a));
    }

    #[test]
    fn spectral_slopes_match_finite_differences_and_integrate_back_to_the_height() {
        let ph = Phillips::new(3e-7, 8.0, 0.4, 0.5);
        let spec = GridSpec::new(512, 512, 128.0, 128.0);
        let half = synthesize_spectrum(&setup(spec, &ph, 0.0));
        let plan = InverseFft2::new(spec.nx, spec.ny);
        let h = plan.process(HalfSpectrum {
            data: half.data.clone(),
            ..half
        });
        let s = surface(
            &half,
            &spec,
            &plan,
            Extras {
                slopes: true,
                ..Default::default()
            },
            0.0,
        );
        let [sx, sy] = s.slopes.unwrap();
        let grid = crate::grid::Grid::new(spec, h.clone());
        let crate::export::mesh::Slopes { dhdx: cx, dhdy: cy } =
            crate::export::mesh::slopes_central(&grid, true);
        let rms = |v: &[f32]| {
            (v.iter().map(|&x| (x as f64).powi(2)).sum::<f64>() / v.len() as f64).sqrt()
        };
        let diff = |a: &[f32], b: &[f32]| {
            let d: Vec<f32> = a.iter().zip(b).map(|(x, y)| x - y).collect();
            rms(&d)
        };
        // The small-wave cutoff (0.5 m) leaves little energy near the grid scale (0.25 m), so
        // central differences agree to a few percent of the slope.
        const FD_REL_TOL: f64 = 0.05;
        eprintln!(
            "spectral vs central-difference slopes: {:.2e}, {:.2e} of the RMS slope",
            diff(&sx, &cx) / rms(&sx),
            diff(&sy, &cy) / rms(&sy)
        );
        assert!(
            diff(&sx, &cx) < FD_REL_TOL * rms(&sx),
            "x: {}",
            diff(&sx, &cx) / rms(&sx)
        );
        assert!(
            diff(&sy, &cy) < FD_REL_TOL * rms(&sy),
            "y: {}",
            diff(&sy, &cy) / rms(&sy)
        );
        // Integrating ∂h/∂x along a row (trapezoid) gives back h − h(0).
        let nx = spec.nx;
        let mut worst: f64 = 0.0;
        for j in [0usize, 77, 300] {
            let row = &h[j * nx..(j + 1) * nx];
            let srow = &sx[j * nx..(j + 1) * nx];
            let mut acc = row[0] as f64;
            for i in 1..nx {
                acc += 0.5 * (srow[i - 1] + srow[i]) as f64 * spec.dx_m();
                worst = worst.max((acc - row[i] as f64).abs());
            }
        }
        const INTEGRAL_TOL: f64 = 0.03;
        eprintln!(
            "integrated slope vs height: {worst:.2e} m (height RMS {:.3} m)",
            rms(&h)
        );
        assert!(
            worst < INTEGRAL_TOL * rms(&h) * 4.0,
            "integral off by {worst}"
        );
    }

    #[test]
    fn normals_of_a_flat_field_point_up_and_tilt_against_the_slope() {
        let n = normals(&[vec![0.0, 0.5], vec![0.0, 0.0]], None);
        assert_eq!(n[0], [0.0, 0.0, 1.0]);
        let want = [-0.5 / 1.25f64.sqrt(), 0.0, 1.0 / 1.25f64.sqrt()];
        for c in 0..3 {
            assert!((n[1][c] as f64 - want[c]).abs() < 1e-6);
        }
    }
}
