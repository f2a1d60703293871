use super::*;
use crate::field::fft::InverseFft2;
use crate::field::fft::second_order::SecondOrder;
use crate::field::fft::second_order::add_plane;
use crate::field::fft::second_order::tests::params_of;
use rustfft::num_complex::Complex32;

/// The setup of one frame of `spectrum` on `spec` (no loop).
fn setup_at<'a>(
    spec: crate::grid::GridSpec,
    spectrum: &'a dyn crate::spectrum::Spectrum,
    dispersion: crate::spectrum::Dispersion,
    seed: u64,
    time_s: f64,
) -> SpectrumSetup<'a> {
    SpectrumSetup {
        spec,
        spectrum,
        dispersion,
        seed,
        time_s,
        loop_period_s: None,
    }
}

fn field_of(spec: crate::grid::GridSpec, fill: impl FnOnce(&mut HalfSpectrum)) -> Vec<f32> {
    let mut half = HalfSpectrum {
        nx: spec.nx,
        ny: spec.ny,
        data: vec![Complex32::new(0.0, 0.0); (spec.nx / 2 + 1) * spec.ny],
        h0max_m: 0.0,
    };
    fill(&mut half);
    InverseFft2::new(spec.nx, spec.ny).process(half)
}

#[test]
fn the_transforms_equal_the_pair_sum_of_the_fitted_kernels() {
    // Every component of a small physical sea: the padded products and transforms give
    // the pair sum of the same kernels (sum and difference terms, the self-pairs, the
    // exact set-down, the dropped outputs), deep and finite depth, at two times.
    const TOL: f64 = 1e-5;
    for depth in [None, Some(8.0)] {
        let mut sets = vec![
            "method=fft",
            "spectrum=pierson-moskowitz",
            "wind-speed=12",
            "spectrum.spreading=hasselmann",
            "size=40x36",
            "extent=480x400",
        ];
        if depth.is_some() {
            sets.push("depth=8");
        }
        let params = params_of(&sets);
        let (model, dispersion) = crate::field::spectrum_model(&params).unwrap();
        let spec = params.grid_spec();
        for t in [0.0, 3.7] {
            let setup = setup_at(spec, model.as_ref(), dispersion, 3, t);
            let so = SecondOrder::new(&setup, 1.0);
            let (dkx, dky) = setup.dk();
            let bounds = Box2::of(&setup);
            let kf = KernelFit::new(model.as_ref(), dispersion, bounds, (dkx, dky));
            let pairs = so.bound_plane_by(
                &setup,
                |a, b, _| kf.kernel(a, b, 1.0, depth).0,
                |a, b| kf.kernel(a, b, -1.0, depth).0,
            );
            let want = field_of(spec, |h| add_plane(&pairs.0, h));
            let tb = TransformBound::new(so.components().to_vec(), spec.nx, spec.ny, depth, kf);
            let got = field_of(spec, |h| tb.add_to(&setup, h));
            let scale = want.iter().fold(0.0f64, |m, v| m.max(f64::from(v.abs())));
            assert!(scale > 0.0);
            for (i, (&g, &w)) in got.iter().zip(&want).enumerate() {
                assert!(
                    (f64::from(g) - f64::from(w)).abs() <= TOL * scale,
                    "depth {depth:?} t {t} sample {i}: {g} vs {w}"
                );
            }
        }
    }
}

/// The bound waves of a physical sea, every component, by the fitted method's transforms
/// and by the exact pair sum: the relative rms and max errors (to the exact rms) and the
/// fit's own estimate.
fn fitted_against_the_pair_sum(sets: &[&str]) -> (f64, f64, f64) {
    let params = params_of(sets);
    let (model, dispersion) = crate::field::spectrum_model(&params).unwrap();
    let spec = params.grid_spec();
    let setup = setup_at(spec, model.as_ref(), dispersion, 7, 0.0);
    let exact = SecondOrder::new(&setup, 1.0);
    let exact = field_of(spec, |h| add_plane(&exact.bound_plane(&setup).0, h));
    let (tb, info) = TransformBound::for_setup(&setup);
    let fitted = field_of(spec, |h| tb.add_to(&setup, h));
    let n = exact.len() as f64;
    let rms = (exact.iter().map(|&v| f64::from(v).powi(2)).sum::<f64>() / n).sqrt();
    let d: Vec<f64> = exact
        .iter()
        .zip(&fitted)
        .map(|(&a, &b)| f64::from(a) - f64::from(b))
        .collect();
    let drms = (d.iter().map(|v| v * v).sum::<f64>() / n).sqrt();
    let dmax = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let estimate = info
        .estimated_rel_rms_error
        .expect("the fitted method's estimate");
    (drms / rms, dmax / rms, estimate)
}

#[test]
fn the_fitted_method_against_the_pair_sum_of_every_component() {
    // 128² over 1024 m, 15 m/s, every component. In deep water, broad and narrow, short-
    // and long-crested, the bound waves are within 1 % rms and 5 % max of the pair sum's
    // (of its rms). At 10 m and 19 m (0.05 and 0.1 λp) the sum term's near-resonance is not
    // resolved: FINITE_RMS holds today's errors with a margin. The estimate the sidecar records must
    // be within ESTIMATE_BAND of the truth.
    const DEEP_RMS: f64 = 0.01;
    const DEEP_MAX: f64 = 0.05;
    const FINITE_RMS: f64 = 0.04;
    const ESTIMATE_BAND: (f64, f64) = (0.5, 2.0);
    let base = ["method=fft", "wind-speed=15", "size=128", "extent=1024"];
    let cases: [(&[&str], bool); 5] = [
        (
            &[
                "spectrum=pierson-moskowitz",
                "spectrum.spreading=hasselmann",
            ],
            true,
        ),
        (
            &[
                "spectrum=jonswap",
                "gamma=7",
                "fetch-km=100",
                "spectrum.spreading=mitsuyasu",
            ],
            true,
        ),
        (
            &[
                "spectrum=jonswap",
                "gamma=7",
                "fetch-km=100",
                "spectrum.spreading=mitsuyasu",
                "spectrum.swell=8",
            ],
            true,
        ),
        (
            &[
                "spectrum=pierson-moskowitz",
                "spectrum.spreading=hasselmann",
                "depth=10",
            ],
            false,
        ),
        (
            &[
                "spectrum=pierson-moskowitz",
                "spectrum.spreading=hasselmann",
                "depth=19",
            ],
            false,
        ),
    ];
    for (case, deep) in cases {
        let sets: Vec<&str> = base.iter().chain(case).copied().collect();
        let (rms, max, estimate) = fitted_against_the_pair_sum(&sets);
        eprintln!(
            "{case:?}: rms error {rms:.4}, max {max:.4} (of the rms), estimate {estimate:.4}"
        );
        if deep {
            assert!(
                rms <= DEEP_RMS && max <= DEEP_MAX,
                "{case:?}: rms {rms}, max {max}"
            );
        } else {
            assert!(rms <= FINITE_RMS, "{case:?}: rms error {rms}");
        }
        let ratio = estimate / rms;
        assert!(
            ratio >= ESTIMATE_BAND.0 && ratio <= ESTIMATE_BAND.1,
            "{case:?}: estimate {estimate} vs {rms}"
        );
    }
}

#[test]
#[ignore = "a measurement, not a check: \
            cargo test --release --lib transform_timing -- --ignored --nocapture"]
fn transform_timing() {
    // Wall times of the linear half spectrum with its inverse transform, of the fit and
    // of the transform evaluation of the bound waves, every component, PM 15 m/s.
    for n in [1024usize, 2048] {
        let size = format!("size={n}");
        let sets = [
            "method=fft",
            "spectrum=pierson-moskowitz",
            "wind-speed=15",
            "spectrum.spreading=hasselmann",
            &size,
            "extent=2048",
        ];
        let params = params_of(&sets);
        let (model, dispersion) = crate::field::spectrum_model(&params).unwrap();
        let spec = params.grid_spec();
        let setup = setup_at(spec, model.as_ref(), dispersion, 3, 0.0);
        let t0 = std::time::Instant::now();
        let half = crate::field::fft::synthesize_spectrum(&setup);
        let _ = InverseFft2::new(spec.nx, spec.ny).process(half);
        let linear = t0.elapsed().as_secs_f64();
        let t1 = std::time::Instant::now();
        let so = SecondOrder::new(&setup, 1.0);
        let (dkx, dky) = setup.dk();
        let bounds = Box2::of(&setup);
        let kf = KernelFit::new(model.as_ref(), dispersion, bounds, (dkx, dky));
        let comps = so.components().len();
        let tb = TransformBound::new(so.components().to_vec(), spec.nx, spec.ny, None, kf);
        let prepare = t1.elapsed().as_secs_f64();
        let t2 = std::time::Instant::now();
        let mut half = crate::field::fft::synthesize_spectrum(&setup);
        tb.add_to(&setup, &mut half);
        let _ = InverseFft2::new(spec.nx, spec.ny).process(half);
        let frame = t2.elapsed().as_secs_f64();
        eprintln!(
            "{n}²: {comps} components; linear {linear:.3} s; prepare (components, fit) \
             {prepare:.3} s; second-order frame {frame:.3} s ({:.1}× the linear)",
            frame / linear
        );
    }
}
