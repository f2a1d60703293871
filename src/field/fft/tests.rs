//! Tests of the FFT sea: the spectrum lines, the kept draws and the inverse transform.

use super::*;
use crate::spectrum::Phillips;

/// A spectrum with energy at the wavevector `k` only (E|h̃0(k)|² = `variance`), for tests.
pub(crate) struct OneComponent {
    pub k: (f64, f64),
    pub variance: f64,
}

impl Spectrum for OneComponent {
    fn amplitude_variance(&self, kx: f64, ky: f64, _: f64, _: f64) -> f64 {
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        if close(kx, self.k.0) && close(ky, self.k.1) {
            self.variance
        } else {
            0.0
        }
    }
}

fn phillips_setup(
    spec: GridSpec,
    spectrum: &Phillips,
    seed: u64,
    time_s: f64,
) -> SpectrumSetup<'_> {
    SpectrumSetup {
        spec,
        spectrum,
        dispersion: Dispersion::Deep,
        seed,
        time_s,
        loop_period_s: None,
    }
}

/// Naive synthesis over the full k plane, in f64, keeping the imaginary part.
fn naive_field(setup: &SpectrumSetup) -> Vec<Complex<f64>> {
    let (nx, ny) = (setup.spec.nx, setup.spec.ny);
    let mut out = vec![Complex::new(0.0, 0.0); nx * ny];
    for jm in 0..ny {
        for in_ in 0..nx {
            let (n, m) = (signed_index(in_, nx), signed_index(jm, ny));
            if !is_resolved(n, m, nx, ny) {
                continue;
            }
            let (h, _) = setup.amplitude(n, m);
            let (kx, ky) = setup.wavevector(n, m);
            for j in 0..ny {
                for i in 0..nx {
                    let phase = kx * setup.spec.x_m(i) + ky * setup.spec.y_m(j);
                    out[j * nx + i] += h * Complex::from_polar(1.0, phase);
                }
            }
        }
    }
    out
}

#[test]
fn fast_transform_matches_a_naive_sum_and_the_field_is_real() {
    // Odd and even sizes, non-square extents, a non-zero time.
    const TOL: f64 = 2e-5;
    let ph = Phillips::new(1e-3, 9.0, 0.4, 0.0);
    for (nx, ny) in [(16, 12), (9, 10), (15, 7)] {
        let spec = GridSpec::new(nx, ny, 40.0, 31.0);
        let setup = phillips_setup(spec, &ph, 11, 2.5);
        let naive = naive_field(&setup);
        let (fast, _) = fft_field(&setup);
        let scale = naive.iter().map(|c| c.re.abs()).fold(0.0, f64::max);
        assert!(scale > 0.0);
        for (idx, (a, b)) in naive.iter().zip(&fast.data).enumerate() {
            assert!(
                a.im.abs() <= TOL * scale,
                "{nx}x{ny}: imaginary part {} at {idx}",
                a.im
            );
            assert!(
                (a.re - *b as f64).abs() <= TOL * scale,
                "{nx}x{ny}: sample {idx}: naive {} fast {}",
                a.re,
                b
            );
        }
    }
}

#[test]
fn the_line_kernels_give_the_reference_amplitudes_bit_for_bit() {
    let ph = Phillips::new(2e-4, 11.0, 2.2, 0.3);
    let cases = [
        (32, 24, 0.0, None, Dispersion::Deep),
        (33, 17, 12.5, None, Dispersion::Deep),
        (8, 64, 1e3, None, Dispersion::Deep),
        (32, 24, 17.3, Some(9.0), Dispersion::Deep),
        (16, 15, 4.0, Some(60.0), Dispersion::Finite { depth_m: 3.0 }),
        (16, 16, 2.5, None, Dispersion::Finite { depth_m: 3.0 }),
    ];
    for (nx, ny, t, loop_period_s, dispersion) in cases {
        let spec = GridSpec::new(nx, ny, 70.0, 50.0);
        let setup = SpectrumSetup {
            loop_period_s,
            dispersion,
            ..phillips_setup(spec, &ph, 21, t)
        };
        let half = synthesize_spectrum(&setup);
        for n in 0..=(nx / 2) {
            for idx in 0..ny {
                let m = signed_index(idx, ny);
                let got = half.data[n * ny + idx];
                let want = if is_resolved(n as i64, m, nx, ny) {
                    let (h, _) = setup.amplitude(n as i64, m);
                    Complex32::new(h.re as f32, h.im as f32)
                } else {
                    Complex32::new(0.0, 0.0)
                };
                assert!(
                    got.re.to_bits() == want.re.to_bits() && got.im.to_bits() == want.im.to_bits(),
                    "{nx}x{ny} t={t}: (n, m) = ({n}, {m}): {got} vs {want}"
                );
            }
        }
    }
}

#[test]
fn parseval_the_variance_equals_the_summed_power() {
    const REL_TOL: f64 = 1e-4;
    let ph = Phillips::new(3e-7, 20.0, 0.3, 0.0);
    let spec = GridSpec::new(128, 96, 800.0, 600.0);
    let setup = phillips_setup(spec, &ph, 5, 7.0);
    let half = synthesize_spectrum(&setup);
    let power = half.total_power();
    let field = InverseFft2::new(128, 96).process(half);
    let n = field.len() as f64;
    let mean = field.iter().map(|&v| v as f64).sum::<f64>() / n;
    let ms = field.iter().map(|&v| (v as f64) * (v as f64)).sum::<f64>() / n;
    assert!(
        mean.abs() < 1e-5 * ms.sqrt(),
        "mean {mean} should vanish (no k = 0)"
    );
    assert!(
        (ms - power).abs() <= REL_TOL * power,
        "variance {ms} vs Σ|h̃|² {power}"
    );
}

#[test]
fn mean_variance_over_seeds_approaches_the_expected_value() {
    // E[var] = Σ_k (P(k) + P(−k)) over resolved k. 200 seeds: the spread of one
    // field's variance here is ~10 %, so the mean's standard error is below 1 %.
    const REL_TOL: f64 = 0.03;
    let ph = Phillips::new(1e-4, 8.0, 1.0, 0.0);
    let spec = GridSpec::new(32, 32, 100.0, 100.0);
    let setup = phillips_setup(spec, &ph, 0, 0.0);
    let mut expected = 0.0;
    for j in 0..32 {
        for i in 0..32 {
            let (n, m) = (signed_index(i, 32), signed_index(j, 32));
            if is_resolved(n, m, 32, 32) {
                let (kx, ky) = setup.wavevector(n, m);
                expected += ph.value(kx, ky) + ph.value(-kx, -ky);
            }
        }
    }
    let seeds = 200;
    let mut mean_var = 0.0;
    for seed in 0..seeds {
        let (g, _) = fft_field(&phillips_setup(spec, &ph, seed, 0.0));
        mean_var += g.stats().std_m.powi(2) / seeds as f64;
    }
    assert!(
        (mean_var - expected).abs() <= REL_TOL * expected,
        "mean variance {mean_var} vs expected {expected}"
    );
}

#[test]
fn one_component_is_a_cosine_travelling_along_k_at_the_phase_speed() {
    const TOL: f64 = 1e-4;
    let spec = GridSpec::new(64, 32, 128.0, 64.0);
    let (n, m) = (3i64, 2i64);
    let tau = 2.0 * std::f64::consts::PI;
    let k = (tau * n as f64 / 128.0, tau * m as f64 / 64.0);
    let one = OneComponent { k, variance: 0.5 };
    let kk = (k.0 * k.0 + k.1 * k.1).sqrt();
    let omega = (crate::spectrum::G * kk).sqrt();
    let probe = SpectrumSetup {
        spec,
        spectrum: &one,
        dispersion: Dispersion::Deep,
        seed: 42,
        time_s: 0.0,
        loop_period_s: None,
    };
    let h0 = probe.h0(n, m);
    for t in [0.0, 1.3, 4.0] {
        let setup = SpectrumSetup { time_s: t, ..probe };
        let (g, _) = fft_field(&setup);
        // h = 2|h̃0| cos(k·x − ωt + arg h̃0): crests move along +k at c = ω/k = √(g/k).
        for j in 0..spec.ny {
            for i in 0..spec.nx {
                let phase = k.0 * spec.x_m(i) + k.1 * spec.y_m(j) - omega * t + h0.arg();
                let want = 2.0 * h0.norm() * phase.cos();
                let got = g.get(i, j) as f64;
                assert!((got - want).abs() < TOL, "t={t} ({i},{j}): {got} vs {want}");
            }
        }
    }
    assert!(((omega / kk) - (crate::spectrum::G / kk).sqrt()).abs() < 1e-12);
}

#[test]
fn the_field_is_periodic_over_the_extent() {
    // Evaluate the naive sum one extent away and compare with the grid.
    const TOL: f64 = 1e-9;
    let ph = Phillips::new(1e-3, 6.0, 0.9, 0.0);
    let spec = GridSpec::new(8, 6, 20.0, 15.0);
    let setup = phillips_setup(spec, &ph, 3, 1.0);
    let at = |x: f64, y: f64| {
        let mut s = Complex::new(0.0, 0.0);
        for jm in 0..6 {
            for in_ in 0..8 {
                let (n, m) = (signed_index(in_, 8), signed_index(jm, 6));
                if is_resolved(n, m, 8, 6) {
                    let (kx, ky) = setup.wavevector(n, m);
                    s += setup.amplitude(n, m).0 * Complex::from_polar(1.0, kx * x + ky * y);
                }
            }
        }
        s.re
    };
    for (x, y) in [(0.3, 0.7), (5.0, 2.0), (13.1, 9.9)] {
        let h = at(x, y);
        assert!((at(x + 20.0, y) - h).abs() < TOL, "x-period at ({x},{y})");
        assert!((at(x, y + 15.0) - h).abs() < TOL, "y-period at ({x},{y})");
        assert!(
            (at(x + 20.0, y - 30.0) - h).abs() < TOL,
            "both at ({x},{y})"
        );
    }
}

#[test]
fn resolution_independent_long_waves() {
    // The 512² field at even samples = the 256² field + only the waves the coarse grid
    // cannot hold. Their energy is the fine spectrum's power beyond the coarse band.
    let ph = Phillips::new(3e-7, 10.0, 0.2, 0.0);
    let coarse_spec = GridSpec::new(256, 256, 512.0, 512.0);
    let fine_spec = GridSpec::new(512, 512, 512.0, 512.0);
    let (coarse, _) = fft_field(&phillips_setup(coarse_spec, &ph, 9, 0.0));
    let (fine, _) = fft_field(&phillips_setup(fine_spec, &ph, 9, 0.0));
    let mut diff2 = 0.0;
    for j in 0..256 {
        for i in 0..256 {
            let d = fine.get(2 * i, 2 * j) as f64 - coarse.get(i, j) as f64;
            diff2 += d * d;
        }
    }
    let diff_var = diff2 / (256.0 * 256.0);
    let coarse_var = coarse.stats().std_m.powi(2);
    // Expected extra variance: power at wavevectors resolved at 512 but not at 256
    // (which alias onto the coarse grid when sub-sampled).
    let setup = phillips_setup(fine_spec, &ph, 9, 0.0);
    let mut extra = 0.0;
    for m in -256..256i64 {
        for n in -256..256i64 {
            if is_resolved(n, m, 512, 512) && !is_resolved_in(n, m, 256) {
                extra += setup.amplitude(n, m).0.norm_sqr();
            }
        }
    }
    assert!(
        diff_var < 0.05 * coarse_var,
        "difference variance {diff_var} is not small next to {coarse_var}"
    );
    assert!(
        (diff_var - extra).abs() < 0.25 * extra + 1e-9 * coarse_var,
        "the difference {diff_var} should be the short waves' energy {extra}"
    );
    // A different seed shares nothing: the difference is then as large as the field.
    let (other, _) = fft_field(&phillips_setup(coarse_spec, &ph, 10, 0.0));
    let d2: f64 = (0..256 * 256)
        .map(|p| (other.data[p] as f64 - coarse.data[p] as f64).powi(2))
        .sum::<f64>()
        / 65536.0;
    assert!(d2 > 1.0 * coarse_var, "different seeds must differ ({d2})");
}

fn is_resolved_in(n: i64, m: i64, size: i64) -> bool {
    n >= -size / 2
        && n < size / 2
        && m >= -size / 2
        && m < size / 2
        && is_resolved(n, m, size as usize, size as usize)
}

#[test]
fn h0max_is_the_largest_initial_amplitude() {
    let ph = Phillips::new(1e-5, 7.0, 0.0, 0.0);
    let spec = GridSpec::new(16, 16, 64.0, 64.0);
    let setup = phillips_setup(spec, &ph, 1, 0.0);
    let half = synthesize_spectrum(&setup);
    let mut want = 0.0f64;
    for m in -8..8i64 {
        for n in -8..8i64 {
            if is_resolved(n, m, 16, 16) {
                want = want.max(setup.h0(n, m).norm());
            }
        }
    }
    assert!(want > 0.0);
    assert!(
        (half.h0max_m - want).abs() <= 1e-14 * want,
        "h0max {} is not the largest |h̃0| {want}",
        half.h0max_m
    );
}

#[test]
fn same_result_with_one_thread_and_two() {
    let ph = Phillips::new(3e-7, 12.0, 0.5, 0.0);
    let spec = GridSpec::new(256, 128, 300.0, 150.0);
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| fft_field(&phillips_setup(spec, &ph, 77, 3.0)).0)
    };
    assert!(
        run(1).data == run(2).data,
        "bit-identical across thread counts"
    );
}
