use super::*;
use crate::grid::GridSpec;
use crate::measure::analyze;

/// η(x) = a cos(kx) + b cos(2kx) along x on an n × rows grid of 1 m spacing, `period`
/// samples per wave.
fn stokes_rows(n: usize, rows: usize, period: usize, a: f64, b: f64) -> Grid {
    let spec = GridSpec::new(n, rows, n as f64, rows as f64);
    let k = 2.0 * std::f64::consts::PI / period as f64;
    let mut data = Vec::with_capacity(n * rows);
    for _ in 0..rows {
        for i in 0..n {
            let t = k * i as f64;
            data.push((a * t.cos() + b * (2.0 * t).cos()) as f32);
        }
    }
    Grid::new(spec, data)
}

fn stats_of(g: &Grid, sea: SeaContext) -> WaveStats {
    let a = analyze(g, None);
    wave_statistics(g, &a, &sea)
}

#[test]
fn a_pure_sine_has_known_heights_crests_and_moments() {
    // 256 samples, 16 per wave: 16 up-crossings per row, 15 whole waves and 15 crests
    // closed by a down-crossing; every sampled wave has H = 2a, crest a (samples fall on
    // the crest and trough).
    const TOL: f64 = 1e-6;
    let (a, rows) = (1.5, 32);
    let s = stats_of(&stokes_rows(256, rows, 16, a, 0.0), SeaContext::default());
    assert!(s.skewness.abs() < TOL, "skewness {}", s.skewness);
    assert!((s.kurtosis - 1.5).abs() < TOL, "kurtosis {}", s.kurtosis);
    assert!(s.transect_direction_deg.abs() < TOL);
    assert_eq!(s.transects, rows);
    assert_eq!(s.waves.count, 15 * rows);
    assert_eq!(s.crests.count, 15 * rows);
    let h3 = s.waves.h_third_m.unwrap();
    assert!((h3 - 2.0 * a).abs() < TOL * a, "H1/3 {h3}");
    assert!((s.waves.h_max_m.unwrap() - 2.0 * a).abs() < TOL * a);
    assert!((s.crests.c_max_m.unwrap() - a).abs() < TOL * a);
    // Hs = 4σ = 4a/√2: every wave is above 0.7 Hs (2a = 0.707·4σ... above 0.7·Hs).
    let hs = 4.0 * a / 2f64.sqrt();
    assert!((h3 / hs - 1.0 / 2f64.sqrt()).abs() < TOL);
    // A sine's mean-square slope is (ka)²/2.
    let k = 2.0 * std::f64::consts::PI / 16.0;
    let mss = 0.5 * (k * a).powi(2);
    assert!(
        (s.mean_square_slope / mss - 1.0).abs() < 1e-6,
        "mss {} vs {mss}",
        s.mean_square_slope
    );
}

#[test]
fn a_stokes_wave_has_its_skewness_and_raised_crests() {
    // η = a cos θ + b cos 2θ, b = ½ k a²: E[η³] = ¾ a² b, σ² = (a² + b²)/2, so the
    // skewness is ¾a²b/σ³ (≈ 1.06·ka for small ka). Crests a + b, troughs −(a − b).
    const TOL: f64 = 1e-6;
    let period = 32;
    let k = 2.0 * std::f64::consts::PI / period as f64;
    let a = 0.1 / k;
    let b = 0.5 * k * a * a;
    let s = stats_of(&stokes_rows(512, 8, period, a, b), SeaContext::default());
    let sigma = ((a * a + b * b) / 2.0).sqrt();
    let want = 0.75 * a * a * b / sigma.powi(3);
    assert!(
        (s.skewness - want).abs() < TOL,
        "skewness {} vs {want}",
        s.skewness
    );
    assert!(s.skewness > 0.1, "{}", s.skewness);
    assert!((s.crests.c_max_m.unwrap() - (a + b)).abs() < 1e-5 * a);
    assert!((s.waves.h_max_m.unwrap() - 2.0 * a).abs() < 1e-5 * a);
}

#[test]
fn a_transect_at_an_angle_measures_the_oblique_sine() {
    // A cosine at 30° on a square grid: the transects follow the peak direction and
    // every wave has H ≈ 2a (bilinear sampling loses at most a little of the crest).
    let g = crate::measure::spectrum::tests::cosine(256, 256.0, 16.0, 30.0, 1.0);
    let s = stats_of(&g, SeaContext::default());
    assert!((s.transect_direction_deg - 30.0).abs() < 1.0);
    let h3 = s.waves.h_third_m.unwrap();
    // Bilinear sampling between the grid points lowers crests by about 1 %.
    assert!((h3 - 2.0).abs() < 0.04, "H1/3 {h3}");
    assert!(s.waves.count > 1000);
}

#[test]
fn a_gaussian_sea_is_symmetric_with_near_rayleigh_heights_and_crests() {
    // Linear FFT seas, 512² over 4096 m: skewness within SKEW of 0, kurtosis within KURT
    // of 3, the 3σ exceedance near the Gaussian's. Against Rayleigh: a narrow sea
    // (JONSWAP γ 20, swell-narrowed spreading) has P(H > Hs) and P(C > Hs/2) within
    // NARROW of exp(−2); a broad one (γ 3.3, Hasselmann) sits below Rayleigh, as a sea
    // of finite bandwidth does (Longuet-Higgins 1980; transects through a short-crested
    // sea meet many small waves), within the band BROAD allows.
    const SKEW: f64 = 0.04;
    const KURT: f64 = 0.12;
    const NARROW: (f64, f64) = (0.7, 1.15);
    const BROAD: (f64, f64) = (0.4, 1.1);
    for (gamma, swell, band) in [(20.0, 3.0, NARROW), (3.3, 0.0, BROAD)] {
        let mut p = crate::config::Params {
            method: crate::config::Method::Fft,
            seed: 3,
            ..crate::config::Params::default()
        };
        p.spectrum.model = crate::config::SpectrumModel::Jonswap;
        p.spectrum.gamma = gamma;
        p.spectrum.swell = swell;
        p.wind.speed_mps = 15.0;
        p.grid.size = crate::config::Size2([512, 512]);
        p.grid.extent_m = crate::config::Extent2([4096.0, 4096.0]);
        let g = crate::field::synthesize(&p).unwrap().grid;
        let s = stats_of(
            &g,
            SeaContext {
                wind_speed_mps: Some(15.0),
                depth_m: None,
            },
        );
        let (c, h) = (&s.crests.exceedance[4], &s.waves.exceedance[9]);
        eprintln!(
            "γ {gamma}: skew {:.4} kurt {:.4} p3σ {:.5} H1/3/Hs {:.3} P(C > Hs/2) {:.4} P(H > Hs) {:.4} S1 {:?} mss {:.4} Cox-Munk {:?}",
            s.skewness,
            s.kurtosis,
            s.exceed_3sigma,
            s.waves.h_third_over_hs.unwrap(),
            c.measured,
            h.measured,
            s.crests.steepness_s1,
            s.mean_square_slope,
            s.cox_munk_mss
        );
        assert!(s.skewness.abs() < SKEW, "skewness {}", s.skewness);
        assert!((s.kurtosis - 3.0).abs() < KURT, "kurtosis {}", s.kurtosis);
        assert!(s.exceed_3sigma < 2.0 * GAUSSIAN_P_3SIGMA);
        assert!((c.level_hs - 0.5).abs() < 1e-12 && (h.level_hs - 1.0).abs() < 1e-12);
        for (what, e) in [("P(C > Hs/2)", c), ("P(H > Hs)", h)] {
            let r = e.measured / e.rayleigh;
            assert!(
                r > band.0 && r < band.1,
                "γ {gamma}: {what} {} vs Rayleigh {}",
                e.measured,
                e.rayleigh
            );
        }
        assert!(s.mean_square_slope < s.cox_munk_mss.unwrap());
    }
}

#[test]
fn forristall_reduces_to_rayleigh_for_linear_deep_water() {
    let (a, b) = forristall_params(0.0, 0.0);
    assert!((a - 0.3536).abs() < 1e-12 && (b - 2.0).abs() < 1e-12);
    // exp(−(c/(αHs))^β) with α = 1/√8, β = 2 is exp(−8c²/Hs²) to the rounding of α.
    let x: f64 = 0.6;
    assert!(((-(x / a).powf(b)).exp() / (-8.0 * x * x).exp() - 1.0).abs() < 2e-3);
    // Steeper seas: larger α, smaller β (higher crests).
    let (a1, b1) = forristall_params(0.05, 0.0);
    assert!(a1 > a && b1 < b);
    assert!((cox_munk_mss(10.0) - 0.0542).abs() < 1e-12);
}
