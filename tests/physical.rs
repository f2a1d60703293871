//! Physical scaling: heights in meters whose significant wave height matches the model.

use seasynth::config::Params;
use seasynth::config::layers::{Assignment, apply};
use seasynth::field::fft::{SpectrumSetup, is_resolved, signed_index};
use seasynth::field::{sea_model, spectrum_model, synthesize};

fn params(sets: &[&str]) -> Params {
    let a: Vec<Assignment> = sets
        .iter()
        .map(|s| Assignment::parse_set(s).unwrap())
        .collect();
    apply(Params::default(), &a).unwrap()
}

/// Σ over resolved wavevectors of P(k) + P(−k): the expected variance of the field.
fn expected_variance(p: &Params) -> f64 {
    let (model, dispersion) = spectrum_model(p).unwrap();
    let spec = p.grid_spec();
    let setup = SpectrumSetup {
        spec,
        spectrum: model.as_ref(),
        dispersion,
        seed: 0,
        time_s: 0.0,
        loop_period_s: None,
    };
    let (dkx, dky) = setup.dk();
    let mut sum = 0.0;
    for j in 0..spec.ny {
        for i in 0..spec.nx {
            let (n, m) = (signed_index(i, spec.nx), signed_index(j, spec.ny));
            if is_resolved(n, m, spec.nx, spec.ny) {
                let (kx, ky) = setup.wavevector(n, m);
                sum += model.amplitude_variance(kx, ky, dkx, dky)
                    + model.amplitude_variance(-kx, -ky, dkx, dky);
            }
        }
    }
    sum
}

/// Mean over `seeds` of the field variance.
fn mean_variance(p: &Params, seeds: u64) -> f64 {
    (0..seeds)
        .map(|s| {
            let q = Params {
                seed: 1000 + s,
                ..p.clone()
            };
            synthesize(&q).unwrap().grid.stats().std_m.powi(2)
        })
        .sum::<f64>()
        / seeds as f64
}

/// Checks 4·std against the model's Hs: the grid resolves the spectrum (peak several
/// times over, ≥ 5 fp), so ∫Ψ over the resolved wavevectors is m0 within `RESOLVED_TOL`,
/// and the mean variance over seeds is that within `SEED_TOL` (the spread of one field's
/// variance is a few percent; averaged over the seeds, ~1 %).
fn check_hs(name: &str, p: &Params, seeds: u64) {
    const RESOLVED_TOL: f64 = 0.02;
    const SEED_TOL: f64 = 0.04;
    let sea = sea_model(p).unwrap().expect("a physical model");
    let hs = sea.freq.hs_m();
    let m0 = hs * hs / 16.0;
    let expected = expected_variance(p);
    assert!(
        (expected - m0).abs() <= RESOLVED_TOL * m0,
        "{name}: ∫Ψ over the grid {expected} m² vs m0 {m0} m²"
    );
    let measured = mean_variance(p, seeds);
    assert!(
        (measured - expected).abs() <= SEED_TOL * expected,
        "{name}: mean variance over {seeds} seeds {measured} m² vs expected {expected} m²"
    );
    let hs_measured = 4.0 * measured.sqrt();
    eprintln!(
        "{name}: model Hs {hs:.4} m, 4·sqrt(expected var) {:.4} m, 4·sqrt(mean var over {seeds} seeds) {hs_measured:.4} m",
        4.0 * expected.sqrt()
    );
    assert!(
        (hs_measured - hs).abs() <= (RESOLVED_TOL + SEED_TOL) * hs,
        "{name}: 4·std {hs_measured} m vs model Hs {hs} m"
    );
}

#[test]
fn pierson_moskowitz_at_15_mps_has_the_model_significant_wave_height() {
    // fm = 0.085 Hz, peak wavelength 216 m: 1024 m holds it ~5 times; a 4 m grid
    // resolves up to 0.44 Hz ≈ 5.2 fm.
    let p = params(&[
        "method=fft",
        "spectrum=pierson-moskowitz",
        "wind-speed=15",
        "size=256",
        "extent=1024",
    ]);
    check_hs("PM 15 m/s", &p, 16);
}

#[test]
fn jonswap_and_tma_have_the_model_significant_wave_height() {
    // 15 m/s over 100 km: fp ≈ 0.14 Hz (≈ 80 m waves); a 2 m grid resolves ≈ 0.62 Hz.
    for (name, extra) in [
        ("JONSWAP", vec![]),
        ("TMA 20 m", vec!["spectrum=tma", "depth=20"]),
    ] {
        let mut sets = vec![
            "method=fft",
            "spectrum=jonswap",
            "wind-speed=15",
            "fetch-km=100",
            "size=512",
            "extent=1024",
        ];
        sets.extend(extra);
        check_hs(name, &params(&sets), 8);
    }
}

#[test]
fn sea_states_given_by_hs_and_tp_have_that_hs() {
    let p = params(&[
        "method=fft",
        "spectrum=jonswap",
        "hs=3",
        "tp=9",
        "size=512",
        "extent=1536",
    ]);
    check_hs("JONSWAP Hs 3 m Tp 9 s", &p, 8);
    let sea = sea_model(&p).unwrap().unwrap();
    assert!((sea.freq.peak_hz() - 1.0 / 9.0).abs() < 1e-9, "fp = 1/Tp");
}

#[test]
fn shallow_water_slows_the_waves_and_the_field_follows_finite_depth_dispersion() {
    // The same sea at t = 0 and t = 5 s: in 5 m of water the waves move slower than in
    // deep water, so the field changes less between the two times at the long waves.
    let base = [
        "method=fft",
        "spectrum=jonswap",
        "wind-speed=10",
        "size=128",
        "extent=512",
    ];
    let change = |extra: &[&str]| {
        let mut s0: Vec<&str> = base.to_vec();
        s0.extend(extra);
        let p0 = params(&s0);
        let mut s1 = s0.clone();
        s1.push("time=5");
        let p1 = params(&s1);
        let a = synthesize(&p0).unwrap().grid;
        let b = synthesize(&p1).unwrap().grid;
        let d: f64 = a
            .data
            .iter()
            .zip(&b.data)
            .map(|(x, y)| ((x - y) as f64).powi(2))
            .sum();
        let v: f64 = a.data.iter().map(|x| (*x as f64).powi(2)).sum();
        d / v
    };
    let deep = change(&[]);
    let shallow = change(&["depth=5"]);
    assert!(
        shallow < deep,
        "relative change in 5 s: shallow {shallow} should be below deep {deep}"
    );
}

#[test]
fn the_sidecar_records_the_model_hs_and_peak_period() {
    let p = params(&[
        "method=fft",
        "spectrum=pierson-moskowitz",
        "wind-speed=15",
        "size=64",
        "extent=1024",
    ]);
    let s = synthesize(&p).unwrap();
    let hs = s.info.model_hs_m.expect("model Hs recorded");
    let tp = s.info.model_tp_s.expect("model Tp recorded");
    // PM: m0 = α g² / (5 (2π)⁴ fm⁴), fm = 0.13 g/U.
    let fm: f64 = 0.13 * 9.81 / 15.0;
    let m0 = 0.0081 * 9.81f64.powi(2) / (5.0 * (2.0 * std::f64::consts::PI).powi(4) * fm.powi(4));
    assert!((hs - 4.0 * m0.sqrt()).abs() < 1e-9 * hs, "Hs {hs}");
    assert!((tp - 1.0 / fm).abs() < 1e-9 * tp, "Tp {tp}");
}

/// Mastin's method: the measured spectrum has the target's shape, and the long crests
/// run across the wind (the energy's direction is the wind's, modulo 180°).
#[test]
fn filtered_noise_has_the_target_spectrum_and_crests_across_the_wind() {
    use seasynth::measure::{Target, analyze};
    // Bins hold hundreds of wavevectors at this size: one field's binned spectrum is
    // within ~10 % of its expectation, i.e. ~0.05 in log10.
    const LOG10_RMS_TOL: f64 = 0.08;
    const VARIANCE_TOL: f64 = 0.1;
    const DIRECTION_TOL_DEG: f64 = 10.0;
    for dir in [0.0, 45.0, 120.0] {
        let p = params(&[
            "method=filtered-noise",
            "spectrum=pierson-moskowitz",
            "wind-speed=15",
            &format!("wind-dir={dir}"),
            "size=512",
            "extent=2048",
        ]);
        let grid = synthesize(&p).unwrap().grid;
        let (spectrum, _) = spectrum_model(&p).unwrap();
        let target = Target {
            spectrum,
            spec: p.grid_spec(),
            method: "filtered-noise".into(),
            model: "pierson-moskowitz".into(),
        };
        let a = analyze(&grid, Some(&target));
        let t = a.target.as_ref().expect("a target summary");
        let rms = t.log10_rms_difference.expect("bins compared");
        eprintln!(
            "wind {dir}°: log10 RMS {rms:.4} over {} bins, variance ratio {:.4}, peak direction {:?}°, peak wavelength {:?} m (target {:?} m)",
            t.bins_compared,
            t.variance_ratio.unwrap(),
            a.peak_direction_deg,
            a.peak_wavelength_m,
            t.target_peak_wavelength_m
        );
        assert!(
            t.bins_compared >= 10,
            "too few bins compared: {}",
            t.bins_compared
        );
        assert!(
            rms <= LOG10_RMS_TOL,
            "wind {dir}°: spectrum shape off by {rms} in log10 RMS"
        );
        let ratio = t.variance_ratio.unwrap();
        assert!(
            (ratio - 1.0).abs() <= VARIANCE_TOL,
            "wind {dir}°: variance ratio {ratio}"
        );
        let measured = a.peak_direction_deg.expect("a peak direction");
        let diff = (measured - dir).rem_euclid(180.0);
        let diff = diff.min(180.0 - diff);
        assert!(
            diff <= DIRECTION_TOL_DEG,
            "wind {dir}°: energy direction {measured}° — the crests do not run across the wind"
        );
    }
}
