use super::*;
use crate::config::Params;
use crate::config::layers::{Assignment, apply};
use crate::field::fft::second_order::{
    C64, SecondOrder, add_plane, kernel_minus, kernel_plus, self_kernels,
};
use crate::field::fft::{HalfSpectrum, InverseFft2, SpectrumSetup};
use rustfft::num_complex::Complex32;

#[test]
fn the_split_reproduces_the_pair_kernels() {
    // K = ¼[sep + ns] is the kernel of the pair sum, deep and finite depth, sum and
    // difference, over waves of many lengths and directions (and the sum self-pair).
    const TOL: f64 = 1e-10;
    for depth in [None, Some(30.0), Some(6.0)] {
        for (k1, t1) in [(0.05, 0.0), (0.013, 0.4), (0.21, 2.0)] {
            for (k2, t2) in [(0.04, 0.1), (0.09, -1.3), (0.3, 3.0), (0.013, 0.4)] {
                let a = Component::new(k1 * f64::cos(t1), k1 * f64::sin(t1), 1.0, 0.0, depth);
                let b = Component::new(k2 * f64::cos(t2), k2 * f64::sin(t2), 1.0, 0.0, depth);
                let same = k1 == k2 && t1 == t2;
                let kp = if same {
                    self_kernels(&a, depth).0
                } else {
                    kernel_plus(&a, &b, depth)
                };
                let sp = split(&a, &b, 1.0, depth);
                let got = 0.25 * (sp.sep + sp.ns);
                assert!(
                    (got - kp).abs() <= TOL * kp.abs().max(k1),
                    "{depth:?} K⁺({k1}, {k2}): {got} vs {kp}"
                );
                if !same {
                    let km = kernel_minus(&a, &b, depth);
                    let sm = split(&a, &b, -1.0, depth);
                    let got = 0.25 * (sm.sep + sm.ns);
                    assert!(
                        (got - km).abs() <= TOL * km.abs().max(k1),
                        "{depth:?} K⁻({k1}, {k2}): {got} vs {km}"
                    );
                }
            }
        }
    }
}

/// The bound waves of a physical sea (every component) by the pair sum with the exact
/// kernels and with the fitted ones: the relative rms and max errors (to the exact rms)
/// and the fit's own estimate.
fn fitted_against_exact(sets: &[&str]) -> (f64, f64, f64) {
    let a: Vec<Assignment> = sets
        .iter()
        .map(|s| Assignment::parse_set(s).unwrap())
        .collect();
    let params = apply(Params::default(), &a).unwrap();
    let (model, dispersion) = crate::field::spectrum_model(&params).unwrap();
    let spec = params.grid_spec();
    let setup = SpectrumSetup {
        spec,
        spectrum: model.as_ref(),
        dispersion,
        seed: 7,
        time_s: 0.0,
        loop_period_s: None,
    };
    let so = SecondOrder::new(&setup, 1.0);
    let depth = params.spectrum.depth_m;
    let (dkx, dky) = setup.dk();
    let bounds = Box2::of(&setup);
    let kf = KernelFit::new(model.as_ref(), dispersion, bounds, (dkx, dky));
    let field = |z: Vec<C64>| {
        let mut half = HalfSpectrum {
            nx: spec.nx,
            ny: spec.ny,
            data: vec![Complex32::new(0.0, 0.0); (spec.nx / 2 + 1) * spec.ny],
            h0max_m: 0.0,
        };
        add_plane(&z, &mut half);
        InverseFft2::new(spec.nx, spec.ny).process(half)
    };
    let exact = field(so.bound_plane(&setup).0);
    let approx = field(
        so.bound_plane_by(
            &setup,
            |a, b, _| kf.kernel(a, b, 1.0, depth).0,
            |a, b| kf.kernel(a, b, -1.0, depth).0,
        )
        .0,
    );
    let n = exact.len() as f64;
    let rms = (exact.iter().map(|&v| f64::from(v).powi(2)).sum::<f64>() / n).sqrt();
    let d: Vec<f64> = exact
        .iter()
        .zip(&approx)
        .map(|(&a, &b)| f64::from(a) - f64::from(b))
        .collect();
    let drms = (d.iter().map(|v| v * v).sum::<f64>() / n).sqrt();
    let dmax = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    (drms / rms, dmax / rms, kf.rel_rms_error)
}

#[test]
#[ignore = "slow: pair sums of every component at 128²; \
            cargo test --release --lib fitted_kernels -- --ignored --nocapture"]
fn the_fitted_kernels_error_and_its_estimate_against_the_pair_sum() {
    // The fitted kernels in the pair sum itself (so the error is the kernels' alone),
    // every component, 128² over 1024 m. Today's basis reaches a few percent, not the
    // 1 % a default method needs: RMS_BOUND holds the measured figures with a margin, and
    // the estimate the sidecar would record must be within ESTIMATE_BAND of the truth.
    const RMS_BOUND: f64 = 0.10;
    const ESTIMATE_BAND: (f64, f64) = (0.5, 2.0);
    let base = [
        "method=fft",
        "wind-speed=15",
        "size=128",
        "extent=1024",
        "spectrum.nonlinear_fraction=1",
    ];
    let cases: [&[&str]; 3] = [
        &[
            "spectrum=pierson-moskowitz",
            "spectrum.spreading=hasselmann",
        ],
        &[
            "spectrum=jonswap",
            "gamma=7",
            "fetch-km=100",
            "spectrum.spreading=mitsuyasu",
        ],
        &[
            "spectrum=pierson-moskowitz",
            "spectrum.spreading=hasselmann",
            "depth=10",
        ],
    ];
    for case in cases {
        let sets: Vec<&str> = base.iter().chain(case).copied().collect();
        let (rms, max, estimate) = fitted_against_exact(&sets);
        eprintln!(
            "{case:?}: rms error {rms:.4}, max {max:.4} (of the rms), estimate {estimate:.4}"
        );
        assert!(rms <= RMS_BOUND, "{case:?}: rms error {rms}");
        let ratio = estimate / rms;
        assert!(
            ratio >= ESTIMATE_BAND.0 && ratio <= ESTIMATE_BAND.1,
            "{case:?}: estimate {estimate} vs {rms}"
        );
    }
}
