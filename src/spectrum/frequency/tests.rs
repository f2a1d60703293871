use super::*;

const REL_FORMULA: f64 = 1e-13;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn gauss_legendre_integrates_polynomials_exactly() {
    const TOL: f64 = 1e-14;
    for n in 1..=20 {
        let rule = gauss_legendre(n);
        let wsum: f64 = rule.iter().map(|r| r.1).sum();
        assert!((wsum - 2.0).abs() < TOL, "n = {n}: Σw = {wsum}");
        for deg in 0..2 * n {
            let q: f64 = rule.iter().map(|&(x, w)| w * x.powi(deg as i32)).sum();
            let want = if deg % 2 == 1 {
                0.0
            } else {
                2.0 / (deg as f64 + 1.0)
            };
            assert!((q - want).abs() < TOL, "n = {n}, x^{deg}: {q} vs {want}");
        }
    }
}

#[test]
fn pierson_moskowitz_matches_the_formula_by_hand() {
    // Mastin eq. 1 evaluated with std's powf/exp, independently of the shape code.
    for u in [5.0, 10.0, 15.0, 25.0] {
        let pm = PiersonMoskowitz::from_wind(u).unwrap();
        let fm = 0.13 * G / u;
        assert!(rel(pm.fm_hz(), fm) < REL_FORMULA, "fm at U = {u}");
        for ratio in [0.5, 0.8, 1.0, 1.3, 2.0, 5.0] {
            let f = ratio * fm;
            let want = 0.0081
                * G
                * G
                * (2.0 * std::f64::consts::PI).powf(-4.0)
                * f.powf(-5.0)
                * (-1.25 * (fm / f).powf(4.0)).exp();
            let got = pm.density(f);
            assert!(
                rel(got, want) < REL_FORMULA,
                "U {u}, f/fm {ratio}: {got} vs {want}"
            );
        }
    }
    // Literal values (computed separately): U = 15 m/s → fm = 0.08502 Hz,
    // F(fm) = 0.0081·9.81²/(2π)⁴·fm⁻⁵·e^{−5/4} = 32.2574 m²/Hz.
    let pm = PiersonMoskowitz::from_wind(15.0).unwrap();
    assert!(rel(pm.peak_hz(), 0.08502) < 1e-12, "fm {}", pm.peak_hz());
    let fm: f64 = 0.08502;
    let want = 0.0081 * 96.2361 / 1_558.545_456_544_039 / fm.powi(5) * (-1.25f64).exp();
    assert!(
        rel(pm.density(fm), want) < 1e-9,
        "F(fm) {} vs {want}",
        pm.density(fm)
    );
    assert!(
        rel(pm.density(fm), 32.2574) < 1e-5,
        "F(fm) {}",
        pm.density(fm)
    );
}

#[test]
fn pierson_moskowitz_hs_closed_form() {
    const REL_NUM: f64 = 1e-10;
    for u in [3.0, 10.0, 20.0, 40.0] {
        let pm = PiersonMoskowitz::from_wind(u).unwrap();
        let fm = 0.13 * G / u;
        let m0 = 0.0081 * G * G / (5.0 * (2.0 * std::f64::consts::PI).powi(4) * fm.powi(4));
        assert!(rel(pm.m0(), m0) < REL_FORMULA, "m0 at U = {u}");
        // Hs = 0.2413 U²/g: 0.0246 U².
        let hs = pm.hs_m();
        assert!(rel(hs, 0.24130 * u * u / G) < 1e-4, "Hs {hs} at U = {u}");
        // The classic Hs = 0.21 U19.5²/g, with U19.5 = 1.074 U10 (the ratio that makes
        // PM's ωp = 0.877 g/U19.5 equal fm = 0.13 g/U10).
        let u195 = 1.074 * u;
        assert!(
            rel(hs, 0.21 * u195 * u195 / G) < 0.01,
            "Hs {hs} vs 0.21 U19.5²/g"
        );
        // The numerical integral agrees with the closed form.
        let num = pm.shape.m0_numeric();
        assert!(rel(num, m0) < REL_NUM, "numeric m0 {num} vs {m0}");
    }
}

#[test]
fn jonswap_with_gamma_one_is_pierson_moskowitz() {
    let pm = PiersonMoskowitz::new(0.01, 0.12).unwrap();
    let j = Jonswap::new(0.01, 0.12, 1.0).unwrap();
    for i in 0..200 {
        let f = 0.01 * 1.04f64.powi(i);
        assert_eq!(j.density(f), pm.density(f), "f = {f}");
    }
    assert!(
        rel(j.hs_m(), pm.hs_m()) < 1e-10,
        "{} vs {}",
        j.hs_m(),
        pm.hs_m()
    );
}

#[test]
fn jonswap_fetch_laws_by_hand() {
    // U = 10 m/s, F = 100 km: g²/(U F) = 9.6236e-5, ω_p = 22·(9.6236e-5)^{1/3}
    // = 1.00817 rad/s (fp = 0.160456 Hz); α = 0.076·(100/(1e5·9.81))^0.22 = 0.0100611.
    const REL_HAND: f64 = 1e-5;
    let j = Jonswap::from_wind_fetch(10.0, 100e3, 3.3).unwrap();
    assert!(
        rel(j.fp_hz() * TWO_PI, 1.008_17) < REL_HAND,
        "ω_p {}",
        j.fp_hz() * TWO_PI
    );
    assert!(rel(j.fp_hz(), 0.160_456) < REL_HAND, "fp {}", j.fp_hz());
    assert!(rel(j.alpha(), 0.010_061_1) < REL_HAND, "α {}", j.alpha());
    assert_eq!(j.peak_hz(), j.fp_hz());
    assert_eq!(j.effective_fetch_m(), Some(100e3));
    // Peak enhancement: F(fp) = γ·F_PM(fp).
    let pm = PiersonMoskowitz::new(j.alpha(), j.fp_hz()).unwrap();
    assert!(rel(j.density(j.fp_hz()), 3.3 * pm.density(j.fp_hz())) < 1e-13);
}

#[test]
fn jonswap_fetch_is_capped_at_the_fully_developed_peak() {
    for u in [5.0, 10.0, 20.0] {
        let full = Jonswap::fully_developed_fetch_m(u);
        let pm_peak = 0.13 * G / u;
        // Beyond the cap the spectrum no longer changes, and its peak is PM's.
        let a = Jonswap::from_wind_fetch(u, full, 3.3).unwrap();
        let b = Jonswap::from_wind_fetch(u, 1e9, 3.3).unwrap();
        assert_eq!(a, b, "U {u}");
        assert!(
            rel(b.fp_hz(), pm_peak) < 1e-12,
            "U {u}: fp {} vs {pm_peak}",
            b.fp_hz()
        );
        // Continuity below the cap.
        let c = Jonswap::from_wind_fetch(u, full * (1.0 - 1e-9), 3.3).unwrap();
        assert!(rel(c.fp_hz(), pm_peak) < 1e-8);
        // Shorter fetch: a higher peak, always finite and positive.
        let d = Jonswap::from_wind_fetch(u, 0.1 * full, 3.3).unwrap();
        assert!(d.fp_hz() > pm_peak);
    }
    assert!(rel(Jonswap::fully_developed_fetch_m(10.0), 199_172.5) < 1e-6);
}

#[test]
fn hs_tp_forms_give_the_requested_hs() {
    // PM: exact. JONSWAP (DNV's A_γ): documented tolerance per γ.
    let pm = PiersonMoskowitz::from_hs_tp(3.0, 9.0).unwrap();
    assert!(rel(pm.hs_m(), 3.0) < 1e-13, "PM Hs {}", pm.hs_m());
    assert!(rel(pm.shape.m0_numeric().sqrt() * 4.0, 3.0) < 1e-10);
    assert!(rel(pm.peak_hz(), 1.0 / 9.0) < 1e-15);
    for (gamma, tol) in [
        (1.0, 1e-9),
        (2.0, 0.0015),
        (3.3, 0.0015),
        (5.0, 0.0015),
        (7.0, 0.01),
        (10.0, 0.037),
        (20.0, 0.23),
    ] {
        let j = Jonswap::from_hs_tp(2.0, 8.0, gamma).unwrap();
        assert!(
            rel(j.hs_m(), 2.0) < tol,
            "γ {gamma}: Hs {} (tolerance {tol})",
            j.hs_m()
        );
        let e = Jonswap::from_hs_tp_exact(2.0, 8.0, gamma).unwrap();
        assert!(
            rel(e.hs_m(), 2.0) < 1e-9,
            "exact γ {gamma}: Hs {}",
            e.hs_m()
        );
        assert!(rel(e.density(0.2) / j.density(0.2), e.alpha() / j.alpha()) < 1e-12);
    }
}

#[test]
fn tma_deep_is_jonswap_and_shallow_has_less_low_frequency_energy() {
    let j = Jonswap::from_wind_fetch(12.0, 50e3, 3.3).unwrap();
    let inf = Tma::new(j, f64::INFINITY).unwrap();
    let deep = Tma::new(j, 1e4).unwrap();
    for i in 0..300 {
        let f = 0.02 * 1.02f64.powi(i);
        assert_eq!(inf.density(f), j.density(f), "∞ depth at f = {f}");
        assert_eq!(deep.density(f), j.density(f), "10 km depth at f = {f}");
    }
    assert_eq!(inf.peak_hz(), j.peak_hz());
    assert!(rel(deep.hs_m(), j.hs_m()) < 1e-9);
    let shallow = Tma::new(j, 5.0).unwrap();
    let fp = j.fp_hz();
    for ratio in [0.6, 0.8, 0.95, 1.0] {
        let f = ratio * fp;
        assert!(
            shallow.density(f) < j.density(f),
            "f/fp {ratio}: {} !< {}",
            shallow.density(f),
            j.density(f)
        );
    }
    assert!(shallow.hs_m() < j.hs_m());
    // Φ at hand-picked ω_h.
    assert_eq!(kitaigorodskii(0.5), 0.125);
    assert_eq!(kitaigorodskii(1.0), 0.5);
    assert_eq!(kitaigorodskii(1.5), 0.875);
    assert_eq!(kitaigorodskii(2.0), 1.0);
    let wh = TWO_PI * 0.1 * (5.0 / G).sqrt();
    assert!(rel(shallow.depth_factor(0.1), kitaigorodskii(wh)) < 1e-15);
}

#[test]
fn stays_finite_and_positive_for_extreme_valid_inputs() {
    let mut models: Vec<Box<dyn FrequencySpectrum>> = Vec::new();
    for u in [0.05, 1.0, 70.0, 300.0] {
        models.push(Box::new(PiersonMoskowitz::from_wind(u).unwrap()));
        for fetch in [1.0, 1e3, 1e9] {
            for gamma in [1.0, 20.0] {
                models.push(Box::new(Jonswap::from_wind_fetch(u, fetch, gamma).unwrap()));
                models.push(Box::new(
                    Tma::from_wind_fetch(u, fetch, gamma, 0.5).unwrap(),
                ));
            }
        }
    }
    for m in &models {
        assert!(
            m.hs_m().is_finite() && m.hs_m() > 0.0,
            "{m:?}: Hs {}",
            m.hs_m()
        );
        assert!(m.peak_hz().is_finite() && m.peak_hz() > 0.0, "{m:?}");
        assert!(m.density(m.peak_hz()) > 0.0, "{m:?}: F(peak) = 0");
        for e in -60..=60 {
            let f = 10f64.powf(e as f64 / 10.0);
            let v = m.density(f);
            assert!(v.is_finite() && v >= 0.0, "{m:?}: F({f}) = {v}");
        }
        for f in [
            0.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            f64::MIN_POSITIVE,
            5e-324,
        ] {
            assert_eq!(m.density(f), 0.0, "{m:?}: F({f})");
        }
    }
}

#[test]
fn invalid_parameters_name_the_parameter() {
    let e = PiersonMoskowitz::from_wind(-3.0).unwrap_err();
    assert_eq!(e.name, "--wind-speed (wind.speed_mps)");
    assert_eq!(e.allowed, "> 0 m/s");
    assert_eq!(e.got, "-3");
    assert_eq!(
        Jonswap::from_wind_fetch(10.0, 1e4, 0.5).unwrap_err().name,
        "--gamma (spectrum.gamma)"
    );
    assert_eq!(
        Jonswap::from_wind_fetch(10.0, 1e4, 21.0)
            .unwrap_err()
            .allowed,
        "between 1 and 20"
    );
    let f = Jonswap::from_wind_fetch(10.0, -2000.0, 3.3).unwrap_err();
    assert_eq!(
        (f.name.as_str(), f.got.as_str()),
        ("--fetch-km (spectrum.fetch_km)", "-2")
    );
    assert_eq!(
        Jonswap::from_hs_tp(0.0, 8.0, 3.3).unwrap_err().name,
        "--hs (spectrum.hs_m)"
    );
    assert_eq!(
        PiersonMoskowitz::from_hs_tp(1.0, f64::NAN)
            .unwrap_err()
            .name,
        "--tp (spectrum.tp_s)"
    );
    let j = Jonswap::from_wind_fetch(10.0, 1e4, 3.3).unwrap();
    assert_eq!(
        Tma::new(j, 0.0).unwrap_err().name,
        "--depth (spectrum.depth_m)"
    );
    assert!(Tma::new(j, f64::NAN).is_err());
}

/// 4·√m0 of `s` by a direct trapezoid integral of its density in ln f (independent of
/// the shape's own quadrature).
fn hs_direct(s: &dyn FrequencySpectrum) -> f64 {
    let fp = s.peak_hz();
    let (lo, hi, n) = ((fp / 20.0).ln(), (fp * 200.0).ln(), 200_000);
    let h = (hi - lo) / n as f64;
    let m0: f64 = (0..=n)
        .map(|i| {
            let x = lo + h * i as f64;
            let w = if i == 0 || i == n { 0.5 } else { 1.0 };
            w * s.density(x.exp()) * x.exp() * h
        })
        .sum();
    4.0 * m0.sqrt()
}

#[test]
fn hs_means_hs_for_every_spectrum_given_hs_and_tp() {
    // The spectrum actually used, the TMA's depth factor included, has 4·√m0 = --hs: the
    // model's own value to the numerical m0 (1e-9), a direct integral of its density to
    // HS_DIRECT (the truncated tail above 200 fp holds ~1e-9 of m0 and the trapezoid is
    // far finer).
    const HS_MODEL: f64 = 1e-9;
    const HS_DIRECT: f64 = 1e-6;
    let (hs, tp) = (2.5, 9.0);
    let mut seas: Vec<(String, Box<dyn FrequencySpectrum>)> = vec![
        (
            "pm".into(),
            Box::new(PiersonMoskowitz::from_hs_tp(hs, tp).unwrap()),
        ),
        (
            "jonswap".into(),
            Box::new(Jonswap::from_hs_tp_exact(hs, tp, 3.3).unwrap()),
        ),
    ];
    for depth in [2.0, 5.0, 15.0, 40.0, 200.0] {
        for gamma in [1.0, 3.3, 7.0] {
            seas.push((
                format!("tma d {depth} γ {gamma}"),
                Box::new(Tma::from_hs_tp(hs, tp, gamma, depth).unwrap()),
            ));
        }
    }
    for (name, s) in &seas {
        assert!(
            rel(s.hs_m(), hs) < HS_MODEL,
            "{name}: model Hs {}",
            s.hs_m()
        );
        let direct = hs_direct(s.as_ref());
        assert!(rel(direct, hs) < HS_DIRECT, "{name}: 4√m0 {direct}");
        assert!(s.scaling().contains("hs"), "{name}: {}", s.scaling());
    }
    // The depth factor is inside the scaling: at 15 m the TMA's α is above the deep
    // JONSWAP's (a user asking for 2.5 m no longer gets 1.72 m).
    let deep = Jonswap::from_hs_tp_exact(hs, tp, 3.3).unwrap();
    let shallow = Tma::from_hs_tp(hs, tp, 3.3, 15.0).unwrap();
    assert!(shallow.jonswap().alpha() > 1.5 * deep.alpha());
    assert_eq!(shallow.scaling(), SCALED_HS_DEPTH);
    // From the wind the depth factor still lowers Hs, and the sidecar text says so.
    let wind = Tma::from_wind_fetch(15.0, 100e3, 3.3, 15.0).unwrap();
    assert!(wind.hs_m() < wind.jonswap().hs_m());
    assert_eq!(wind.scaling(), SCALED_WIND_DEPTH);
}
