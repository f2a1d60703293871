//! Tests of the derived fields: spectral slopes and displacement against closed forms, the Jacobian, the choppy resampling and the normals.

use super::*;

/// The derived fields of `half` (a copy of it is consumed).
fn surface(
    half: &HalfSpectrum,
    spec: &GridSpec,
    plan: &InverseFft2,
    extras: Extras,
    lambda: f64,
) -> Surface {
    let copy = HalfSpectrum {
        data: half.data.clone(),
        ..*half
    };
    surface_and_height(copy, spec, plan, extras, lambda).1
}
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
    let all = Extras::ALL;
    let s0 = surface(&half, &spec, &plan, all, 0.0);
    let j0 = s0.jacobian.unwrap();
    assert_eq!(j0, Jacobian::One, "no field stored for J = 1");
    assert!(j0.values(spec.len()).iter().all(|&j| j == 1.0));
    let lambda = 0.5;
    let s = surface(&half, &spec, &plan, all, lambda);
    let d = s.displacement.unwrap();
    let Some(Jacobian::Field(j)) = s.jacobian else {
        panic!("a choppy sea has a Jacobian field");
    };
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
fn choppy_normals_are_those_of_the_trochoid_and_still_ones_ignore_no_term() {
    // Trochoid x = x0 − λA sin(kx0 + φ), z = A cos(kx0 + φ): the tangent along x0 is
    // (1 − λAk cos, 0, −Ak sin), so the unit normal is ∝ (Ak sin, 0, 1 − λAk cos).
    const TOLERANCE: f64 = 1e-4;
    let (a, phase, k, spec, half) = cosine(3, 256, 100.0);
    let plan = InverseFft2::new(spec.nx, spec.ny);
    let slopes_only = Extras {
        slopes: true,
        ..Default::default()
    };
    for lambda in [0.0, 0.5] {
        let s = surface(&half, &spec, &plan, slopes_only, lambda);
        assert_eq!(s.displacement_gradient.is_some(), lambda != 0.0);
        let n = s.normals().expect("slopes asked for");
        for (i, got) in n.iter().enumerate().take(spec.nx) {
            let u = k * i as f64 * spec.dx_m() + phase;
            let (nx, nz) = (a * k * u.sin(), 1.0 - lambda * a * k * u.cos());
            let len = (nx * nx + nz * nz).sqrt();
            let want = [nx / len, 0.0, nz / len];
            for c in 0..3 {
                assert!(
                    (got[c] as f64 - want[c]).abs() < TOLERANCE,
                    "λ = {lambda}, normal[{i}][{c}] = {} vs {}",
                    got[c],
                    want[c]
                );
            }
        }
    }
}

#[test]
fn the_x_slope_sharing_the_height_transform_equals_its_own_transform() {
    // The factor i·kx applied after the transform along y instead of before: the same
    // field up to single-precision rounding; the height is the plain transform's, bit
    // for bit.
    const REL_TOL: f64 = 1e-5;
    let ph = Phillips::new(3e-7, 8.0, 0.4, 0.5);
    let spec = GridSpec::new(128, 96, 64.0, 48.0);
    let half = synthesize_spectrum(&setup(spec, &ph, 0.0));
    let plan = InverseFft2::new(spec.nx, spec.ny);
    let copy = || HalfSpectrum {
        data: half.data.clone(),
        ..half
    };
    let alone = plan.process(
        derivative_spectra(&half, &spec, &[Derivative::SlopeX])
            .pop()
            .expect("one asked for"),
    );
    let slopes = Extras {
        slopes: true,
        ..Default::default()
    };
    let (h, s) = surface_and_height(copy(), &spec, &plan, slopes, 0.0);
    assert_eq!(
        h,
        plan.process(copy()),
        "the height is the plain transform's"
    );
    let [shared, _] = s.slopes.expect("asked for");
    let scale = alone.iter().fold(0.0f64, |m, &v| m.max(v.abs() as f64));
    assert!(scale > 0.0);
    let worst = shared
        .iter()
        .zip(&alone)
        .fold(0.0f64, |m, (&a, &b)| m.max((a - b).abs() as f64));
    assert!(
        worst < REL_TOL * scale,
        "∂h/∂x: largest difference {worst:e} of {scale:e}"
    );
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
    let crate::measure::slopes::Slopes { dhdx: cx, dhdy: cy } =
        crate::measure::slopes::slopes_central(&grid, true);
    let rms =
        |v: &[f32]| (v.iter().map(|&x| (x as f64).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
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

/// The straightforward normal: the f64 cross product, each component divided by its
/// length.
fn reference_normal(hx: f64, hy: f64, a: f64, b: f64, c: f64) -> [f64; 3] {
    let n = [
        c * hy - hx * (1.0 + b),
        hx * c - (1.0 + a) * hy,
        (1.0 + a) * (1.0 + b) - c * c,
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len == 0.0 {
        [0.0, 0.0, 1.0]
    } else {
        n.map(|v| v / len)
    }
}

#[test]
fn normals_with_one_reciprocal_square_root_agree_with_the_f64_divisions() {
    // Slopes up to ±8 (steeper than any sea) and displacement gradients up to ±0.9,
    // from a fixed sequence; more points than one parallel block, an odd count.
    let n = 40_001;
    let field = |stream: u64, scale: f64| -> Vec<f32> {
        (0..n as u64)
            .map(|i| {
                let u = (crate::rng::mix64(stream << 32 | i) >> 11) as f64 / (1u64 << 53) as f64;
                ((u * 2.0 - 1.0) * scale) as f32
            })
            .collect()
    };
    let slopes = [field(1, 8.0), field(2, 8.0)];
    let d = [field(3, 0.9), field(4, 0.9), field(5, 0.9)];
    for ddisp in [None, Some([&d[0][..], &d[1][..], &d[2][..]])] {
        let got = normals(&slopes, ddisp);
        assert_eq!(got.len(), n);
        let mut worst: f64 = 0.0;
        for (p, g) in got.iter().enumerate() {
            let [a, b, c] = ddisp.map_or([0.0; 3], |d| d.map(|f| f[p] as f64));
            let want = reference_normal(slopes[0][p] as f64, slopes[1][p] as f64, a, b, c);
            for k in 0..3 {
                let e = (g[k] as f64 - want[k]).abs();
                assert!(
                    e <= NORMAL_F32_TOL,
                    "choppy = {}, normal[{p}][{k}] = {} vs {}",
                    ddisp.is_some(),
                    g[k],
                    want[k]
                );
                worst = worst.max(e);
            }
        }
        eprintln!(
            "normals (choppy = {}): worst difference {worst:.2e}",
            ddisp.is_some()
        );
    }
    // Parallel tangents (a fold edge): the normal points up, as documented.
    let up = normals(&[vec![0.0], vec![0.0]], Some([&[-1.0], &[-1.0], &[0.0]]));
    assert_eq!(up[0], [0.0, 0.0, 1.0]);
}

/// A periodic 2D displacement in samples (a few oblique waves, |∇λD| up to ~0.8, no
/// folds) and heights, on a `nx` × `ny` grid of 1 m.
fn oblique_waves(nx: usize, ny: usize) -> (Vec<f32>, [Vec<f32>; 2], GridSpec) {
    let spec = GridSpec::new(nx, ny, nx as f64, ny as f64);
    let waves = [
        (3.0, 1.0, 0.9, 0.3),
        (-2.0, 5.0, 0.5, 1.1),
        (7.0, -4.0, 0.12, 2.0),
    ];
    let (mut h, mut dx, mut dy) = (vec![0.0; nx * ny], vec![0.0; nx * ny], vec![0.0; nx * ny]);
    for j in 0..ny {
        for i in 0..nx {
            let p = j * nx + i;
            for &(mx, my, amp, phase) in &waves {
                let (kx, ky) = (TAU * mx / nx as f64, TAU * my / ny as f64);
                let k = (kx * kx + ky * ky).sqrt();
                // Amplitude in samples such that |∇D| stays about 0.8 at most together.
                let a = amp * 0.3 / k;
                let arg = kx * i as f64 + ky * j as f64 + phase;
                h[p] += (a * arg.cos()) as f32;
                dx[p] -= (a * kx / k * arg.sin()) as f32;
                dy[p] -= (a * ky / k * arg.sin()) as f32;
            }
        }
    }
    (h, [dx, dy], spec)
}

#[test]
fn choppy_resampling_solves_each_point_as_a_long_newton_solve() {
    // Reference: from the plain first guess x − λD(x), 60 Newton steps on the same
    // bilinear interpolant, then h there. The resampling's continuation and early stop
    // must land within 1e-4 samples · max|∇h| of it.
    let (nx, ny) = (96, 80);
    let (h, d, spec) = oblique_waves(nx, ny);
    let got = resample_choppy(&h, &d, &spec);
    let ds: Vec<[f32; 2]> = d[0].iter().zip(&d[1]).map(|(&u, &v)| [u, v]).collect();
    let mut worst: f64 = 0.0;
    let mut max_slope: f64 = 0.0;
    for j in 0..ny {
        for i in 0..nx {
            let p = j * nx + i;
            let (x, y) = (i as f64, j as f64);
            let (mut ex, mut ey) = (-(ds[p][0] as f64), -(ds[p][1] as f64));
            for _ in 0..60 {
                let cell = Cell::new(nx, ny, x + ex, y + ey);
                let s = newton_step(&cell, &ds, ex, ey);
                assert!(s.newton, "no folds in this field");
                ex -= s.dx;
                ey -= s.dy;
            }
            let want = Cell::new(nx, ny, x + ex, y + ey).of(&h);
            worst = worst.max((got[p] as f64 - want).abs());
            let i1 = (i + 1) % nx;
            max_slope = max_slope.max((h[j * nx + i1] as f64 - h[p] as f64).abs());
        }
    }
    eprintln!("resampling vs long Newton: {worst:.2e} m (max slope {max_slope:.3} m/sample)");
    assert!(
        worst <= 1e-4 * max_slope + 2e-7,
        "resampled height off by {worst:.2e} m"
    );
}

#[test]
fn choppy_resampling_is_the_same_on_one_and_four_threads() {
    let (h, d, spec) = oblique_waves(203, 64);
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| resample_choppy(&h, &d, &spec))
    };
    let (one, four) = (on(1), on(4));
    assert!(
        one.iter()
            .zip(&four)
            .all(|(a, b)| a.to_bits() == b.to_bits()),
        "bit-identical across thread counts"
    );
}

#[test]
fn choppy_resampling_vector_kernels_equal_the_scalar_one_bit_for_bit() {
    use crate::simd::Isa;
    // Without folds (203 columns: segments of 13, the last one short), with folds (the same
    // waves' displacement tripled: fixed-point steps), on a grid narrower than the sixteen
    // segments, and with a displacement of more than a grid period (the indices of the
    // rare far lanes wrapped one by one).
    let (h, d, spec) = oblique_waves(203, 64);
    let folded = [
        d[0].iter().map(|v| v * 3.0).collect::<Vec<f32>>(),
        d[1].iter().map(|v| v * 3.0).collect(),
    ];
    let (hs, ds, small) = oblique_waves(11, 9);
    let far = [
        ds[0].iter().map(|v| v * 40.0).collect::<Vec<f32>>(),
        ds[1].iter().map(|v| v * 40.0).collect(),
    ];
    let cases = [
        ("no folds", &h, &d, spec, false),
        ("folds", &h, &folded, spec, true),
        ("narrow", &hs, &ds, small, false),
        ("far", &hs, &far, small, true),
    ];
    for (name, h, d, spec, folds) in cases {
        // Whether the field folds somewhere (det J < 0.05 at a grid point).
        let pairs: Vec<[f32; 2]> = d[0].iter().zip(&d[1]).map(|(&u, &v)| [u, v]).collect();
        let fixed_point = (0..spec.len()).any(|p| {
            let (x, y) = ((p % spec.nx) as f64, (p / spec.nx) as f64);
            !newton_step(&Cell::new(spec.nx, spec.ny, x, y), &pairs, 0.0, 0.0).newton
        });
        assert_eq!(fixed_point, folds, "{name}: folds");
        let scalar = resample::resample_choppy_on(Isa::Plain, h, d, &spec);
        assert!(scalar.iter().all(|v| v.is_finite()), "{name}: finite");
        for isa in Isa::available() {
            let got = resample::resample_choppy_on(isa, h, d, &spec);
            let same = got
                .iter()
                .zip(&scalar)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{name}: {isa:?} differs from the scalar kernel");
        }
    }
}

/// Height std, largest and RMS difference of `a` and `b` over the std of `h`.
fn moved(a: &[f32], b: &[f32], h: &[f32]) -> (f64, f64) {
    let n = h.len() as f64;
    let mean = h.iter().map(|&v| v as f64).sum::<f64>() / n;
    let std = (h.iter().map(|&v| (v as f64 - mean).powi(2)).sum::<f64>() / n).sqrt();
    let (mut max, mut sum2) = (0.0f64, 0.0f64);
    for (&x, &y) in a.iter().zip(b) {
        let e = (x as f64 - y as f64).abs();
        max = max.max(e);
        sum2 += e * e;
    }
    (max / std, (sum2 / n).sqrt() / std)
}

#[test]
fn choppy_heights_moved_little_from_the_f64_resampling() {
    // The bench's choppy sea (Pierson–Moskowitz, 15 m/s, at 1 m; 1024² here): the single-
    // precision kernel against the f64 one it replaced. Both stop within ~1e-4 samples of
    // the root where Newton's method converges, so they differ by a few 1e-4 samples ·
    // slope there; in folds (several roots, fixed-point steps that stop after
    // `CHOPPY_ITERATIONS`) they may pick different points of the folded sheet.
    // At 4096² the bench's sea moved by max 8e-6, rms 4e-8 of the height std.
    const RMS_TOL: f64 = 1e-6;
    const MAX_TOL: f64 = 1e-3;
    let n = 1024;
    for lambda in [0.8, 1.0] {
        let params = crate::config::Params {
            grid: crate::config::GridParams {
                size: crate::config::Size2([n, n]),
                extent_m: crate::config::Extent2([n as f64, n as f64]),
                ..Default::default()
            },
            spectrum: crate::config::SpectrumParams {
                model: crate::config::SpectrumModel::PiersonMoskowitz,
                ..Default::default()
            },
            wind: crate::config::WindParams {
                speed_mps: 15.0,
                direction_deg: 30.0,
            },
            method: crate::config::Method::Fft,
            motion: crate::config::MotionParams {
                choppiness: lambda,
                ..Default::default()
            },
            ..Default::default()
        };
        let extras = Extras {
            displacement: true,
            ..Default::default()
        };
        let frame = crate::field::Synthesizer::new(&params, extras, true)
            .unwrap()
            .frame(1.0);
        let spec = frame.grid.spec;
        let d = frame.surface.displacement.as_ref().unwrap();
        let h = frame.surface.undisplaced_height.as_ref().unwrap();
        let (sx, sy) = ((1.0 / spec.dx_m()) as f32, (1.0 / spec.dy_m()) as f32);
        let pairs: Vec<[f32; 2]> = d[0]
            .iter()
            .zip(&d[1])
            .map(|(&u, &v)| [u * sx, v * sy])
            .collect();
        let old = reference::resample_choppy_f64(h, &pairs, spec.nx, spec.ny);
        let new = resample_choppy(h, d, &spec);
        assert_eq!(new, frame.grid.data, "the frame's heights are the kernel's");
        let (max, rms) = moved(&new, &old, h);
        eprintln!(
            "λ = {lambda}: choppy heights moved by max {max:.2e}, rms {rms:.2e} of the height std"
        );
        assert!(rms < RMS_TOL, "λ = {lambda}: rms {rms:.2e}");
        assert!(max < MAX_TOL, "λ = {lambda}: max {max:.2e}");
    }
}
