use super::*;
use crate::field::fft::{InverseFft2, OneComponent};
use crate::grid::GridSpec;

/// The parameters of `KEY=VALUE` assignments over the defaults.
pub(super) fn params_of(sets: &[&str]) -> crate::config::Params {
    use crate::config::layers::{Assignment, apply};
    let a: Vec<Assignment> = sets
        .iter()
        .map(|s| Assignment::parse_set(s).unwrap())
        .collect();
    apply(crate::config::Params::default(), &a).unwrap()
}

/// A small physical sea for the exact checks: PM 12 m/s, Hasselmann, over 480 × 400 m
/// on `size` (e.g. "size=40x36"), deep or at `depth` m.
pub(super) fn small_sea(size: &str, depth: Option<f64>) -> crate::config::Params {
    let depth = depth.map(|d| format!("depth={d}"));
    let mut sets = vec![
        "method=fft",
        "spectrum=pierson-moskowitz",
        "wind-speed=12",
        "spectrum.spreading=hasselmann",
        size,
        "extent=480x400",
    ];
    sets.extend(depth.as_deref());
    params_of(&sets)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

fn wave(kx: f64, ky: f64, depth: Option<f64>) -> Component {
    Component::new(kx, ky, 1.0, 0.0, depth)
}

/// The unidirectional (collinear) kernels in their frequency form (Longuet-Higgins &
/// Stewart; the form of WAFO's spec2nlsdat), halved to this module's convention of a
/// double sum over ordered pairs; k1 ≠ k2, waves travelling the same way.
fn collinear_reference(k1: f64, k2: f64, h: f64) -> (f64, f64) {
    let w = |k: f64| (G * k * (k * h).tanh()).sqrt();
    let (w1, w2) = (w(k1), w(k2));
    let t1 = G * (k1 / w1) * (k2 / w2);
    let t2 = 0.5 / G * (w1 * w1 + w2 * w2 + w1 * w2);
    let t3 = 0.5 * G * (w1 * k2 * k2 + w2 * k1 * k1) / (w1 * w2 * (w1 + w2));
    let t4 = 1.0 - G * (k1 + k2) / (w1 + w2).powi(2) * ((k1 + k2) * h).tanh();
    let ep = (t1 - t2 + t3) / t4 + t2 - 0.5 * t1;
    let t2 = 0.5 / G * (w1 * w1 + w2 * w2 - w1 * w2);
    let t3 = -0.5 * G * (w1 * k2 * k2 - w2 * k1 * k1) / (w1 * w2 * (w1 - w2));
    let t4 = 1.0 - G * (k1 - k2) / (w1 - w2).powi(2) * ((k1 - k2) * h).tanh();
    let ed = (t1 - t2 + t3) / t4 + t2 - 0.5 * t1;
    (0.5 * ep, 0.5 * ed)
}

#[test]
fn deep_water_collinear_limits() {
    // K⁺ = (k_i + k_j)/4 (the pair's ½(k_i + k_j) once both orders are summed) and
    // K⁻ = −|k_i − k_j|/4 (the set-down under the group), for waves along any direction.
    const TOL: f64 = 1e-12;
    for (k1, k2) in [(0.05, 0.03), (0.03, 0.07), (0.1, 0.02), (0.2, 0.19)] {
        for dir in [0.0f64, 0.7, 2.5] {
            let (c, s) = (dir.cos(), dir.sin());
            let a = wave(k1 * c, k1 * s, None);
            let b = wave(k2 * c, k2 * s, None);
            let (kp, km) = kernels(&a, &b, None);
            assert!(rel(kp, 0.25 * (k1 + k2)) < TOL, "K⁺({k1}, {k2}) = {kp}");
            assert!(
                rel(km, -0.25 * (k1 - k2).abs()) < 1e-9,
                "K⁻({k1}, {k2}) = {km}"
            );
            let (kp2, km2) = kernels(&b, &a, None);
            assert!(rel(kp, kp2) < TOL && rel(km, km2) < TOL, "symmetric");
        }
    }
    // Stokes: K⁺_ii = k/2, K⁻_ii = 0.
    let (kp, km) = self_kernels(&wave(0.04, 0.03, None), None);
    assert!(rel(kp, 0.025) < TOL && km == 0.0);
    // Opposing waves of equal length (a standing wave) have no bound elevation at q = 0
    // in deep water.
    let (kp, _) = kernels(&wave(0.05, 0.0, None), &wave(-0.05, 0.0, None), None);
    assert!(kp.abs() < TOL, "{kp}");
}

#[test]
fn finite_depth_kernels_match_the_collinear_forms_and_stokes() {
    const TOL: f64 = 1e-9;
    for h in [200.0, 20.0, 8.0] {
        for (k1, k2) in [(0.05, 0.03), (0.03, 0.07), (0.1, 0.02)] {
            let d = Some(h);
            let (kp, km) = kernels(&wave(k1, 0.0, d), &wave(k2, 0.0, d), d);
            let (rp, rm) = collinear_reference(k1, k2, h);
            assert!(rel(kp, rp) < TOL, "h {h}: K⁺ {kp} vs {rp}");
            assert!(rel(km, rm) < TOL, "h {h}: K⁻ {km} vs {rm}");
        }
        // Stokes' second order in depth h: ¼ k a² cosh kh (2 + cosh 2kh)/sinh³ kh.
        let k: f64 = 0.05;
        let c = wave(k, 0.0, Some(h));
        let (kp, km) = self_kernels(&c, Some(h));
        let kh = k * h;
        let stokes = 0.25 * k * kh.cosh() * (2.0 + (2.0 * kh).cosh()) / kh.sinh().powi(3);
        assert!(rel(kp, stokes) < TOL, "h {h}: {kp} vs Stokes {stokes}");
        // The set-down is the limit of the collinear difference kernel.
        // (The pair formula cancels near the diagonal; a step of 1e-4 keeps 1e-3.)
        let near = kernels(&c, &wave(k * (1.0 + 1e-4), 0.0, Some(h)), Some(h)).1;
        assert!(rel(km, near) < 1e-3, "h {h}: K⁻_ii {km} vs limit {near}");
        assert!(km < 0.0);
    }
}

fn setup_of<'a>(
    spec: GridSpec,
    spectrum: &'a OneComponent,
    depth: Option<f64>,
    t: f64,
) -> SpectrumSetup<'a> {
    SpectrumSetup {
        spec,
        spectrum,
        dispersion: Dispersion::for_depth(depth),
        seed: 1,
        time_s: t,
        loop_period_s: None,
    }
}

/// The bound field of `so` on its grid through the half spectrum and the inverse FFT.
fn bound_field(so: &SecondOrder, setup: &SpectrumSetup) -> (Vec<f32>, SecondOrderInfo) {
    let (nx, ny) = (setup.spec.nx, setup.spec.ny);
    let mut half = HalfSpectrum {
        nx,
        ny,
        data: vec![Complex32::new(0.0, 0.0); (nx / 2 + 1) * ny],
        h0max_m: 0.0,
    };
    let info = so.add_to(setup, &mut half);
    // Hermitian on the self-conjugate line n = 0.
    for idx in 0..ny {
        let m = signed_index(idx, ny);
        let j = (-m).rem_euclid(ny as i64) as usize;
        let (a, b) = (half.data[idx], half.data[j].conj());
        assert!((a - b).norm() <= 1e-6 * a.norm().max(1e-30), "H2(0, {m})");
    }
    (InverseFft2::new(nx, ny).process(half), info)
}

/// η2 at (x, y), t by the double sum over ordered pairs, term by term.
fn naive(comps: &[Component], depth: Option<f64>, x: f64, y: f64, t: f64) -> f64 {
    let d = Dispersion::for_depth(depth);
    let psi = |c: &Component| c.kx * x + c.ky * y - d.omega(c.k) * t + c.phi;
    let mut eta = 0.0;
    for (i, a) in comps.iter().enumerate() {
        for (j, b) in comps.iter().enumerate() {
            let (kp, km) = if i == j {
                self_kernels(a, depth)
            } else {
                kernels(a, b, depth)
            };
            let amp = 4.0 * a.rho * b.rho;
            eta += amp * (kp * (psi(a) + psi(b)).cos() + km * (psi(a) - psi(b)).cos());
        }
    }
    eta
}

#[test]
fn a_single_wave_gives_stokes_second_order() {
    // a cos ψ with a = 2ρ: η2 = ½ k a² cos 2ψ in deep water.
    let spec = GridSpec::new(64, 32, 640.0, 320.0);
    let one = OneComponent {
        k: (0.0, 0.0),
        variance: 0.0,
    };
    let setup = setup_of(spec, &one, None, 0.0);
    let (kx, ky) = setup.wavevector(5, 2);
    let mut c = Component::new(kx, ky, 0.6, 0.4, None);
    (c.n, c.m) = (5, 2);
    let so = SecondOrder::from_components(vec![c], 64, 32, None);
    let (eta, info) = bound_field(&so, &setup);
    let (a, k) = (1.2, c.k);
    for j in 0..32 {
        for i in 0..64 {
            let (x, y) = (spec.x_m(i), spec.y_m(j));
            let psi = kx * x + ky * y + 0.4;
            let want = 0.5 * k * a * a * (2.0 * psi).cos();
            let got = f64::from(eta[j * 64 + i]);
            assert!((got - want).abs() < 1e-6, "({i}, {j}): {got} vs {want}");
        }
    }
    assert_eq!(
        (info.sum_pairs_dropped, info.difference_pairs_dropped),
        (0, 0)
    );
}

/// A handful of components with pseudo-random amplitudes and phases on low indices.
fn some_components(spec: GridSpec, depth: Option<f64>, setup: &SpectrumSetup) -> Vec<Component> {
    let idx = [
        (3, 1),
        (4, -2),
        (-2, 5),
        (5, 0),
        (0, 3),
        (1, -4),
        (-3, -3),
        (2, 2),
        (6, 1),
    ];
    idx.iter()
        .enumerate()
        .map(|(t, &(n, m))| {
            let (kx, ky) = setup.wavevector(n, m);
            let rho = 0.2 + 0.1 * ((t * 7) % 5) as f64;
            let phi = 0.9 * t as f64;
            let mut c = Component::new(kx, ky, rho, phi, depth);
            (c.n, c.m) = (n, m);
            let _ = spec;
            c
        })
        .collect()
}

#[test]
fn the_grid_sum_equals_the_double_sum_in_deep_and_shallow_water_at_any_time() {
    // The accumulation onto the grid (sum and difference cells, the factor 2 of pairs,
    // the Hermitian half, one inverse FFT) against the naive double sum.
    let spec = GridSpec::new(32, 32, 320.0, 320.0);
    let one = OneComponent {
        k: (0.0, 0.0),
        variance: 0.0,
    };
    for depth in [None, Some(6.0)] {
        for t in [0.0, 3.7] {
            let setup = setup_of(spec, &one, depth, t);
            let comps = some_components(spec, depth, &setup);
            let so = SecondOrder::from_components(comps.clone(), 32, 32, depth);
            let (eta, info) = bound_field(&so, &setup);
            assert_eq!(info.sum_pairs_dropped + info.difference_pairs_dropped, 0);
            let scale = eta.iter().fold(0.0f64, |m, v| m.max(f64::from(v.abs())));
            for (i, j) in [(0, 0), (3, 7), (17, 2), (31, 31), (10, 20)] {
                let want = naive(&comps, depth, spec.x_m(i), spec.y_m(j), t);
                let got = f64::from(eta[j * 32 + i]);
                assert!(
                    (got - want).abs() < 1e-5 * scale,
                    "depth {depth:?} t {t} ({i}, {j}): {got} vs {want}"
                );
            }
            // The mean is the set-down: Σ a_i² K⁻_ii (no pair of opposite waves here).
            let mean = eta.iter().map(|&v| f64::from(v)).sum::<f64>() / eta.len() as f64;
            let setdown: f64 = comps
                .iter()
                .map(|c| 4.0 * c.rho * c.rho * self_kernels(c, depth).1)
                .sum();
            assert!(
                (mean - setdown).abs() < 1e-5 * scale,
                "mean {mean} vs {setdown}"
            );
            if depth.is_none() {
                assert!(mean.abs() < 1e-6 * scale, "deep mean {mean}");
            } else {
                assert!(setdown < 0.0);
            }
        }
    }
}

#[test]
fn pairs_beyond_nyquist_are_dropped_and_counted() {
    // Two waves at n = 10 on a 32-wide grid: their sum (20) is beyond Nyquist (16), so
    // the sum pairs (the two self-pairs and the cross pair) drop; the difference stays.
    let spec = GridSpec::new(32, 8, 320.0, 80.0);
    let one = OneComponent {
        k: (0.0, 0.0),
        variance: 0.0,
    };
    let setup = setup_of(spec, &one, None, 0.0);
    let comps: Vec<Component> = [(10, 0), (10, 1)]
        .iter()
        .map(|&(n, m)| {
            let (kx, ky) = setup.wavevector(n, m);
            let mut c = Component::new(kx, ky, 0.5, 0.0, None);
            (c.n, c.m) = (n, m);
            c
        })
        .collect();
    let so = SecondOrder::from_components(comps, 32, 8, None);
    let (_, info) = bound_field(&so, &setup);
    assert_eq!(info.pairs, 3);
    assert_eq!(info.sum_pairs_dropped, 3);
    assert_eq!(info.difference_pairs_dropped, 0);
}

#[test]
fn the_components_within_the_limit_are_those_of_every_line_that_it_admits() {
    // The components within the convergence limit are drawn on the kx lines below its k_up
    // only, each line on its ky indices below k_up only: the same components (indices, draws, in order) as every line's components
    // that the limit admits, deep and at finite depth (where it also has a lower bound),
    // with a limit far inside the grid and one beyond it.
    for (sets, c) in [
        (vec![], 2.0),
        (vec!["depth=12"], 2.0),
        (vec!["depth=12"], 0.5),
        (vec![], 500.0),
    ] {
        let mut all = vec![
            "method=fft",
            "spectrum=pierson-moskowitz",
            "wind-speed=15",
            "spectrum.spreading=hasselmann",
            "size=128",
            "extent=512",
        ];
        all.extend(sets.iter().copied());
        let params = params_of(&all);
        let (model, dispersion) = crate::field::spectrum_model(&params).unwrap();
        let setup = SpectrumSetup {
            spec: params.grid_spec(),
            spectrum: model.as_ref(),
            dispersion,
            seed: 5,
            time_s: 0.0,
            loop_period_s: None,
        };
        let cut = Cutoff::of(&setup, c);
        // The limit inside the grid skips lines and the ends of each line (drawn from a
        // window of it); beyond it, none.
        let (lines, cols) = lines_within(&setup, Some(cut));
        assert_eq!((lines < 65, cols < 65), (c < 100.0, c < 100.0), "C = {c}");
        let within = SecondOrder::within(&setup, 1.0, Some(cut));
        let every = SecondOrder::within(&setup, 1.0, None);
        let admitted: Vec<&Component> = every
            .components()
            .iter()
            .filter(|c| cut.admits(c.r))
            .collect();
        assert!(!admitted.is_empty() && admitted.len() < every.components().len() || c > 100.0);
        let key = |c: &Component| (c.n, c.m, c.rho.to_bits(), c.phi.to_bits());
        let got: Vec<_> = within.components().iter().map(key).collect();
        let want: Vec<_> = admitted.into_iter().map(key).collect();
        assert_eq!(got, want, "{sets:?}, C = {c}");
    }
}
