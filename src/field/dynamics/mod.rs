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
//! with x0 solving x0 + λD(x0) = x, found by Newton's method on the bilinear, periodic
//! interpolant of λD. Each row is solved in sixteen segments from left to right; a
//! segment's first point starts from x0 = x − λD(x), every other point from its left
//! neighbour's solution moved by one sample along x through the inverse Jacobian there
//! (x0 − x changes by J⁻¹(1, 0) − (1, 0) per sample), which is within ~|∇²D| of the root.
//! The step is (I + λ∇D)⁻¹(x0 + λD(x0) − x) with the interpolant's own gradient (twice
//! on the same cell where the first step stays in it), or the fixed-point step
//! x0 ← x − λD(x0) where det(I + λ∇D) < 0.05 (near folds). At most `CHOPPY_ITERATIONS`
//! steps, fewer once Newton's step moves x0 by less than 1e-3 of a sample (it converges
//! quadratically) or leaves it within 1e-5 samples of its cell's root, or a fixed-point
//! step moves it by less than 1e-4. Then h(x0) by bilinear interpolation. Single
//! precision, vectorized: see [`resample_choppy`]. Normal, foam and displacement maps
//! stay on the undisplaced grid (vertex i, j of a displacement-mapped mesh), as engines
//! apply them.

use std::f64::consts::TAU;
use std::mem::MaybeUninit;

use rayon::prelude::*;
use rustfft::num_complex::Complex32;

use super::fft::{HalfSpectrum, InverseFft2, signed_index};
use crate::grid::GridSpec;
use crate::simd::Isa;

pub(crate) mod resample;
pub use resample::{CHOPPY_ITERATIONS, resample_choppy};

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
    /// Whether the factor divides by |k|.
    fn needs_inv_k(self) -> bool {
        !matches!(self, Derivative::SlopeX | Derivative::SlopeY)
    }

    /// Writes one kx line of h̃ times this factor to `out`, given the line's kx, the ky of
    /// each entry and 1/|k| (0 at k = 0, so every factor vanishes there; only read by the
    /// factors that divide by |k|). One branch-free loop per factor.
    fn apply(
        self,
        src: &[Complex32],
        out: &mut [MaybeUninit<Complex32>],
        kx: f64,
        ky: &[f64],
        inv_k: &[f64],
    ) {
        let n = src.len();
        let out = &mut out[..n];
        // h̃·f for a real f(k), and h̃·i f.
        fn real(src: &[Complex32], out: &mut [MaybeUninit<Complex32>], f: impl Fn(usize) -> f64) {
            for (j, (o, v)) in out.iter_mut().zip(src).enumerate() {
                let f = f(j) as f32;
                o.write(Complex32::new(v.re * f, v.im * f));
            }
        }
        fn imag(src: &[Complex32], out: &mut [MaybeUninit<Complex32>], f: impl Fn(usize) -> f64) {
            for (j, (o, v)) in out.iter_mut().zip(src).enumerate() {
                let f = f(j) as f32;
                o.write(Complex32::new(-v.im * f, v.re * f));
            }
        }
        match self {
            Derivative::SlopeX => imag(src, out, |_| kx),
            Derivative::SlopeY => {
                let ky = &ky[..n];
                imag(src, out, |j| ky[j])
            }
            Derivative::DispX => {
                let inv_k = &inv_k[..n];
                imag(src, out, |j| kx * inv_k[j])
            }
            Derivative::DispY => {
                let (ky, inv_k) = (&ky[..n], &inv_k[..n]);
                imag(src, out, |j| ky[j] * inv_k[j])
            }
            Derivative::DxX => {
                let inv_k = &inv_k[..n];
                real(src, out, |j| -kx * kx * inv_k[j])
            }
            Derivative::DyY => {
                let (ky, inv_k) = (&ky[..n], &inv_k[..n]);
                real(src, out, |j| -ky[j] * ky[j] * inv_k[j])
            }
            Derivative::DxY => {
                let (ky, inv_k) = (&ky[..n], &inv_k[..n]);
                real(src, out, |j| -kx * ky[j] * inv_k[j])
            }
        }
    }
}

/// kx of the spectrum's line n, rad/m.
fn line_kx(spec: &GridSpec, n: usize) -> f64 {
    TAU * n as f64 / spec.extent_x_m
}

/// h̃(k) times the factor of each of `ds`, for every stored wavevector. Each result is
/// still Hermitian: every factor has f(−k) = conj f(k); the k = 0 entry of each is 0.
///
/// One parallel pass over the kx lines of h̃ writes every result: each task reads its
/// line once, computes 1/|k| once (only when a factor needs it) and writes that line of
/// each result, so the results' memory is first touched by all threads at once (no serial
/// copy of h̃ per factor).
pub fn derivative_spectra(
    half: &HalfSpectrum,
    spec: &GridSpec,
    ds: &[Derivative],
) -> Vec<HalfSpectrum> {
    let (nx, ny) = (half.nx, half.ny);
    let len = half.data.len();
    let tau = TAU;
    let ky: Vec<f64> = (0..ny)
        .map(|j| tau * signed_index(j, ny) as f64 / spec.extent_y_m)
        .collect();
    let with_inv_k = ds.iter().any(|d| d.needs_inv_k());
    let mut outs: Vec<Vec<Complex32>> = ds.iter().map(|_| Vec::with_capacity(len)).collect();
    // Line n of every result, side by side.
    let mut lines: Vec<Vec<&mut [MaybeUninit<Complex32>]>> = (0..len / ny)
        .map(|_| Vec::with_capacity(ds.len()))
        .collect();
    for out in outs.iter_mut() {
        for (line, chunk) in lines
            .iter_mut()
            .zip(out.spare_capacity_mut()[..len].chunks_mut(ny))
        {
            line.push(chunk);
        }
    }
    lines
        .into_par_iter()
        .zip(half.data.par_chunks(ny))
        .enumerate()
        .for_each_init(
            || vec![0.0f64; ny],
            |inv_k, (n, (mut targets, src))| {
                let kx = line_kx(spec, n);
                if with_inv_k {
                    for (o, &ky) in inv_k.iter_mut().zip(&ky) {
                        let k2 = kx * kx + ky * ky;
                        let inv = 1.0 / k2.sqrt();
                        *o = if k2 > 0.0 { inv } else { 0.0 };
                    }
                }
                for (d, target) in ds.iter().zip(targets.iter_mut()) {
                    d.apply(src, target, kx, &ky, inv_k);
                }
            },
        );
    outs.into_iter()
        .map(|mut data| {
            // SAFETY: the pass above wrote every one of the `len` elements (the lines of
            // h̃ tile 0..len, and `apply` writes each entry of its line).
            unsafe { data.set_len(len) };
            HalfSpectrum {
                nx,
                ny,
                data,
                h0max_m: half.h0max_m,
            }
        })
        .collect()
}

/// Which derived fields a run needs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Extras {
    pub slopes: bool,
    pub displacement: bool,
    pub jacobian: bool,
    /// No output reads the heights of a choppy frame, only its maps: the frame keeps the
    /// undisplaced heights (what displacement maps hold) and skips the resampling.
    pub maps_only: bool,
}

impl Extras {
    /// Every derived field, and the heights resampled.
    pub const ALL: Self = Self {
        slopes: true,
        displacement: true,
        jacobian: true,
        maps_only: false,
    };

    /// Whether any derived field is asked for (`maps_only` asks for none).
    pub fn any(&self) -> bool {
        self.slopes || self.displacement || self.jacobian
    }
}

/// The Jacobian J of a state's displacement.
#[derive(Debug, Clone, PartialEq)]
pub enum Jacobian {
    /// J = 1 exactly at every point: no displacement (λ = 0), so no field is stored.
    One,
    /// J at every grid point, row-major.
    Field(Vec<f32>),
}

impl Jacobian {
    /// J at each of the `len` grid points: the stored field, or `len` ones.
    pub fn values(&self, len: usize) -> std::borrow::Cow<'_, [f32]> {
        match self {
            Jacobian::One => std::borrow::Cow::Owned(vec![1.0; len]),
            Jacobian::Field(j) => std::borrow::Cow::Borrowed(j),
        }
    }
}

/// The derived fields of one state, each on the undisplaced grid, row-major.
#[derive(Debug, Clone, Default)]
pub struct Surface {
    /// ∂h/∂x, ∂h/∂y.
    pub slopes: Option<[Vec<f32>; 2]>,
    /// λ·Dx, λ·Dy in meters.
    pub displacement: Option<[Vec<f32>; 2]>,
    /// λ·∂Dx/∂x, λ·∂Dy/∂y, λ·∂Dx/∂y: the gradient of the displacement, kept with the
    /// slopes when λ ≠ 0 so the normals are those of the displaced surface.
    pub displacement_gradient: Option<[Vec<f32>; 3]>,
    /// J of the displacement λD.
    pub jacobian: Option<Jacobian>,
    /// The heights before the choppy resampling (the z of a displacement map), when
    /// λ ≠ 0 and the displacement was asked for.
    pub undisplaced_height: Option<Vec<f32>>,
}

impl Surface {
    /// Unit normals of the (displaced) surface at every grid point, when the slopes were
    /// computed.
    pub fn normals(&self) -> Option<Vec<[f32; 3]>> {
        let slopes = self.slopes.as_ref()?;
        let gradient = self
            .displacement_gradient
            .as_ref()
            .map(|[a, b, c]| [a.as_slice(), b.as_slice(), c.as_slice()]);
        Some(normals(slopes, gradient))
    }
}

/// The height field of h̃ (consumed) and the fields `extras` asks for (the displacement
/// only when λ ≠ 0, where the choppy height needs it too, and the displacement gradient
/// when λ ≠ 0 and the slopes are asked for, which the normals need): all factors in one
/// pass over h̃, then one complex-to-real transform per field. ∂h/∂x shares the
/// height's transform along y (its factor i·kx is constant on a kx line, so it is
/// applied between the two passes): three fields of a still sea cost two and a half
/// transforms.
pub fn surface_and_height(
    half: HalfSpectrum,
    spec: &GridSpec,
    plan: &InverseFft2,
    extras: Extras,
    lambda: f64,
) -> (Vec<f32>, Surface) {
    use Derivative::*;
    let choppy = lambda != 0.0;
    let gradient = choppy && (extras.jacobian || extras.slopes);
    let mut wanted = Vec::new();
    if extras.slopes {
        wanted.push(SlopeY);
    }
    // λD is zero without choppiness: no transform for it (a displacement map of a
    // still sea writes zeros).
    if choppy {
        wanted.extend([DispX, DispY]);
    }
    if gradient {
        wanted.extend([DxX, DyY, DxY]);
    }
    let spectra = derivative_spectra(&half, spec, &wanted);
    let (height, slope_x) = if extras.slopes {
        let i_kx: Vec<Complex32> = (0..half.lines())
            .map(|n| Complex32::new(0.0, line_kx(spec, n) as f32))
            .collect();
        let (h, sx) = plan.process_with_line_factor(half, &i_kx);
        (h, Some(sx))
    } else {
        (plan.process(half), None)
    };
    let l = lambda as f32;
    // λ times each displacement field (scaled row by row inside the transform).
    let mut fields = spectra
        .into_iter()
        .zip(&wanted)
        .map(|(s, d)| plan.process_scaled(s, (!matches!(d, SlopeX | SlopeY)).then_some(l)));
    let mut next = || fields.next().expect("one field per wanted factor");
    let slopes = slope_x.map(|sx| [sx, next()]);
    let displacement = choppy.then(|| [next(), next()]);
    let displacement_gradient = gradient.then(|| [next(), next(), next()]);
    let jacobian = extras.jacobian.then(|| match &displacement_gradient {
        None => Jacobian::One,
        Some([xx, yy, xy]) => Jacobian::Field(
            xx.par_iter()
                .zip(yy)
                .zip(xy)
                .map(|((&a, &b), &c)| (1.0 + a) * (1.0 + b) - c * c)
                .collect(),
        ),
    });
    let surface = Surface {
        slopes,
        displacement_gradient: displacement_gradient.filter(|_| extras.slopes),
        displacement,
        jacobian,
        undisplaced_height: None,
    };
    (height, surface)
}

#[cfg(test)]
mod reference;
#[cfg(test)]
use reference::{Cell, newton_step};

/// Unit normals (x, y, z) of the surface (x0 + λD, h) at every grid point, z up: the
/// cross product of the tangents (1 + λDx,x, λDy,x, hx) × (λDx,y, 1 + λDy,y, hy). Needs
/// the slopes; `ddisp` is (λDx,x, λDy,y, λDx,y), taken as zero when None (λ = 0).
///
/// Scaled by one reciprocal square root per point (in f32 for a still sea, in f64 for a
/// choppy one, where (1 + a)(1 + b) − c² cancels near folds), in parallel blocks; within
/// [`NORMAL_F32_TOL`] of the f64 formula with a division per component.
pub fn normals(slopes: &[Vec<f32>; 2], ddisp: Option<[&[f32]; 3]>) -> Vec<[f32; 3]> {
    const BLOCK: usize = 16384;
    let [hx, hy] = slopes;
    let isa = Isa::detect();
    // Zeroed by the allocator: the pages are first touched by the parallel writes.
    let mut out = vec![[0.0f32; 3]; hx.len()];
    out.par_chunks_mut(BLOCK).enumerate().for_each(|(b, out)| {
        let r = b * BLOCK..b * BLOCK + out.len();
        let (hx, hy) = (&hx[r.clone()], &hy[r.clone()]);
        match ddisp {
            None => still_normals(isa, hx, hy, out),
            Some([xx, yy, xy]) => {
                choppy_normals(isa, hx, hy, [&xx[r.clone()], &yy[r.clone()], &xy[r]], out)
            }
        }
    });
    out
}

/// Largest difference between a component of [`normals`] and the f64 cross product divided
/// by its length (a few f32 rounding errors of components ≤ 1).
pub const NORMAL_F32_TOL: f64 = 1e-6;

crate::simd::multiversion! {
    @on
    /// λ = 0: the normal (−hx, −hy, 1)/√(1 + hx² + hy²).
    fn still_normals(isa: Isa, hx: &[f32], hy: &[f32], out: &mut [[f32; 3]]) {
        for ((o, &x), &y) in out.iter_mut().zip(hx).zip(hy) {
            let r = 1.0 / (1.0 + x * x + y * y).sqrt();
            *o = [-x * r, -y * r, r];
        }
    }
}

crate::simd::multiversion! {
    @on
    /// The normal of the tangents (1 + a, c, hx) × (c, 1 + b, hy), (0, 0, 1) where they
    /// are parallel.
    fn choppy_normals(isa: Isa, hx: &[f32], hy: &[f32], d: [&[f32]; 3], out: &mut [[f32; 3]]) {
        let [da, db, dc] = d;
        let n = out.len();
        let (hx, hy, da, db, dc) = (&hx[..n], &hy[..n], &da[..n], &db[..n], &dc[..n]);
        for (i, o) in out.iter_mut().enumerate() {
            // f64: (1 + a)(1 + b) − c² cancels near folds.
            let [x, y, a, b, c] = [hx[i], hy[i], da[i], db[i], dc[i]].map(f64::from);
            let nxv = c * y - x * (1.0 + b);
            let nyv = x * c - (1.0 + a) * y;
            let nzv = (1.0 + a) * (1.0 + b) - c * c;
            let len2 = nxv * nxv + nyv * nyv + nzv * nzv;
            let r = 1.0 / len2.sqrt();
            *o = if len2 == 0.0 {
                [0.0, 0.0, 1.0]
            } else {
                [(nxv * r) as f32, (nyv * r) as f32, (nzv * r) as f32]
            };
        }
    }
}

#[cfg(test)]
mod tests;
