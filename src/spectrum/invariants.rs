//! Invariants every frequency spectrum and every spreading model must satisfy, checked by
//! one shared checker over all models and a spread of parameters (test only).

use super::frequency::{FrequencySpectrum, Jonswap, PiersonMoskowitz, Tma};
use super::spreading::{Spreading, SpreadingModel};

/// Frequencies of the wide grid: 1e-3 … 1e2 Hz.
const WIDE_LO: f64 = 1e-3;
const WIDE_HI: f64 = 1e2;
const WIDE_POINTS: usize = 20_000;
/// The maximum of a fine grid must be within this of `peak_hz`.
const PEAK_REL: f64 = 0.01;
/// ∫F df = Hs²/16 to this.
const M0_REL: f64 = 1e-4;
/// ∫D dθ = 1 to this.
const NORM_REL: f64 = 1e-6;
/// D(θ) = D(−θ) to this (relative).
const SYM_REL: f64 = 1e-15;

/// Checks one frequency spectrum: F ≥ 0 and finite on a wide log grid, 0 for f ≤ 0, the
/// maximum of a fine grid at `peak_hz`, and ∫F df = Hs²/16 by an independent quadrature
/// (composite Simpson in ln f from 0.02 fp to 1e4 fp, step 1e-4).
pub(crate) fn check_frequency_spectrum(name: &str, s: &dyn FrequencySpectrum) {
    let peak = s.peak_hz();
    assert!(peak > 0.0 && peak.is_finite(), "{name}: peak_hz {peak}");
    let ratio = (WIDE_HI / WIDE_LO).ln();
    let mut best = (0.0, -1.0);
    for i in 0..=WIDE_POINTS {
        let f = WIDE_LO * (ratio * i as f64 / WIDE_POINTS as f64).exp();
        let v = s.density(f);
        assert!(v.is_finite() && v >= 0.0, "{name}: F({f}) = {v}");
        if v > best.1 {
            best = (f, v);
        }
    }
    for f in [0.0, -0.0, -1e-3, -1.0, -1e6, f64::NEG_INFINITY] {
        assert_eq!(s.density(f), 0.0, "{name}: F({f}) must be 0");
    }
    // Fine grid around the peak (±1e-4 in ln f), and the wide grid's maximum.
    let mut fine = (0.0, -1.0);
    for i in -20_000..=20_000 {
        let f = peak * (i as f64 * 1e-4).exp();
        let v = s.density(f);
        if v > fine.1 {
            fine = (f, v);
        }
    }
    assert!(
        (fine.0 / peak - 1.0).abs() < PEAK_REL,
        "{name}: fine-grid maximum at {} Hz, peak_hz {peak}",
        fine.0
    );
    assert!(
        best.1 <= fine.1 * (1.0 + 1e-9),
        "{name}: wide-grid maximum {} at {} Hz above the peak's {}",
        best.1,
        best.0,
        fine.1
    );
    assert!(
        (best.0 / peak - 1.0).abs() < 0.05,
        "{name}: wide-grid maximum at {} Hz, peak_hz {peak}",
        best.0
    );
    // ∫F df by Simpson in u = ln f.
    let (a, b) = ((0.02 * peak).ln(), (1e4 * peak).ln());
    let n = (((b - a) / 1e-4) as usize) & !1;
    let h = (b - a) / n as f64;
    let g = |i: usize| {
        let f = (a + h * i as f64).exp();
        s.density(f) * f
    };
    let mut sum = g(0) + g(n);
    for i in 1..n {
        sum += if i % 2 == 1 { 4.0 } else { 2.0 } * g(i);
    }
    let m0 = sum * h / 3.0;
    let want = s.hs_m() * s.hs_m() / 16.0;
    assert!(
        (m0 - want).abs() <= M0_REL * want,
        "{name}: ∫F df = {m0}, Hs²/16 = {want} (Hs {})",
        s.hs_m()
    );
}

/// Checks one spreading model at r = f/fp ∈ {0.3, 0.7, 1, 1.5, 3, 8}: ∫_{−π}^{π} D dθ = 1
/// (composite 10-point Gauss–Legendre, 400 panels on each quarter turn, the one next to
/// ±π with the substitution that smooths cos^{2s}(θ/2)), D ≥ 0, D(θ) = D(−θ), finite.
pub(crate) fn check_spreading(name: &str, sp: Spreading, fp: f64, u10: f64) {
    let pi = std::f64::consts::PI;
    for r in [0.3, 0.7, 1.0, 1.5, 3.0, 8.0] {
        let f = r * fp;
        let even = |t: f64| 0.5 * (sp.density(f, fp, u10, t) + sp.density(f, fp, u10, -t));
        let total = super::spreading::integrate_circle_even(even, 0.0, 400);
        assert!(
            (total - 1.0).abs() <= NORM_REL,
            "{name} {sp:?} at f/fp {r}: ∫D dθ = {total}"
        );
        for i in 0..=720 {
            let t = pi * i as f64 / 720.0;
            let (a, b) = (sp.density(f, fp, u10, t), sp.density(f, fp, u10, -t));
            assert!(
                a.is_finite() && a >= 0.0,
                "{name} {sp:?}: D({f}, {t}) = {a}"
            );
            assert!(
                (a - b).abs() <= SYM_REL * a,
                "{name} {sp:?}: D({t}) = {a}, D(−θ) = {b}"
            );
        }
    }
}

fn all_frequency_spectra() -> Vec<(String, Box<dyn FrequencySpectrum>)> {
    let mut v: Vec<(String, Box<dyn FrequencySpectrum>)> = Vec::new();
    for u in [3.0, 7.0, 15.0, 30.0] {
        v.push((
            format!("PM {u} m/s"),
            Box::new(PiersonMoskowitz::from_wind(u).unwrap()),
        ));
    }
    for (hs, tp) in [(0.5, 3.0), (2.0, 8.0), (9.0, 15.0)] {
        v.push((
            format!("PM Hs {hs} Tp {tp}"),
            Box::new(PiersonMoskowitz::from_hs_tp(hs, tp).unwrap()),
        ));
    }
    for gamma in [1.0, 3.3, 7.0] {
        for u in [5.0, 10.0, 20.0] {
            for fetch in [5e3, 100e3, 1000e3] {
                v.push((
                    format!("JONSWAP {u} m/s {fetch} m γ {gamma}"),
                    Box::new(Jonswap::from_wind_fetch(u, fetch, gamma).unwrap()),
                ));
            }
        }
        for (hs, tp) in [(1.0, 5.0), (4.0, 11.0)] {
            v.push((
                format!("JONSWAP Hs {hs} Tp {tp} γ {gamma}"),
                Box::new(Jonswap::from_hs_tp(hs, tp, gamma).unwrap()),
            ));
            v.push((
                format!("JONSWAP exact Hs {hs} Tp {tp} γ {gamma}"),
                Box::new(Jonswap::from_hs_tp_exact(hs, tp, gamma).unwrap()),
            ));
        }
        for depth in [1e4, 30.0, 8.0, 3.0] {
            for u in [7.0, 18.0] {
                v.push((
                    format!("TMA {u} m/s 50 km γ {gamma} depth {depth}"),
                    Box::new(Tma::from_wind_fetch(u, 50e3, gamma, depth).unwrap()),
                ));
            }
            v.push((
                format!("TMA Hs 2 Tp 9 γ {gamma} depth {depth}"),
                Box::new(Tma::from_hs_tp(2.0, 9.0, gamma, depth).unwrap()),
            ));
        }
    }
    v
}

#[test]
fn every_frequency_spectrum_satisfies_the_invariants() {
    let all = all_frequency_spectra();
    assert!(all.len() > 60);
    for (name, s) in &all {
        check_frequency_spectrum(name, s.as_ref());
    }
}

#[test]
fn every_spreading_model_satisfies_the_invariants() {
    for model in [
        SpreadingModel::Cos2,
        SpreadingModel::Hasselmann,
        SpreadingModel::Mitsuyasu,
        SpreadingModel::DonelanBanner,
    ] {
        for swell in [0.0, 0.3, 1.0, 4.0, 10.0] {
            let sp = Spreading::new(model, swell).unwrap();
            for (fp, u10) in [(0.1, 10.0), (0.3, 5.0), (0.06, 30.0), (0.5, 25.0)] {
                check_spreading("spreading", sp, fp, u10);
            }
        }
    }
}
