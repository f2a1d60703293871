//! Mastin et al.'s Fourier synthesis (`--method filtered-noise`): white noise filtered by
//! the sea spectrum in the Fourier domain.
//!
//! The Fourier transform of a white-noise image has independent complex Gaussian
//! coefficients (exactly for Gaussian noise, by the central limit theorem for Mastin's
//! uniform noise) with Hermitian symmetry W(−k) = conj W(k). seasynth draws them directly,
//! one per wavevector from `(seed, n, m)` like the FFT method, so the field does not change
//! with resolution, then multiplies each by the filter magnitude and keeps its phase:
//! h̃(k) = W(k)·√(P(k) + P(−k)), E|W|² = 1. The filter is the spectrum symmetrized over ±k,
//! which keeps h̃ Hermitian (the field real) and gives the field the same expected variance
//! Σ_k (P(k) + P(−k)) as the FFT method.
//!
//! # Motion (Mastin et al., "Ocean scene animation")
//! At time t each coefficient turns by a phase: h̃(k, t) = h̃(k)·e^{−iφ(k, t)} with
//! φ(−k) = −φ(k), so the field stays real. With s = sign(k·ŵ) (waves run downwind):
//! - `dispersion`: φ = s·ω(k)·t, ω from the dispersion relation of the depth (and rounded
//!   to the loop period when one is set) — Mastin's c = √(g/k) converted with the image
//!   scale and the frame rate;
//! - `translate`: φ = (k·ŵ)·v·t, the whole image moves downwind at v (the translation
//!   property, his eq. 9);
//! - `hot-air`: φ = s·r(k)·t·fps, r = `hot_air_dominant_rad` per frame for the dominant
//!   components and `hot_air_other_rad` for the rest. Dominant: |k| in the band around
//!   the peak of the filter along the wind where the filter power P(kŵ) + P(−kŵ) is at
//!   least two-thirds of its peak value (his "frequencies bounded by two-thirds of the
//!   energy of the peak frequency").

use rustfft::num_complex::Complex32;

use super::fft::{SpectrumSetup, build_lines, is_resolved, signed_index};
use crate::config::PhaseMode;
use crate::fastmath::sin_cos;
use crate::rng::gaussian_pair;

/// How a filtered-noise field moves; see the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    pub mode: PhaseMode,
    /// Unit wind direction (toward).
    pub wind: (f64, f64),
    pub fps: f64,
    pub dominant_rad: f64,
    pub other_rad: f64,
    /// Translate speed, m/s.
    pub speed_mps: f64,
    /// The dominant band of |k|, rad/m.
    pub band: (f64, f64),
}

impl Motion {
    /// The phase φ(k, t) of wavevector (kx, ky).
    pub fn phase(&self, setup: &SpectrumSetup, kx: f64, ky: f64) -> f64 {
        let t = setup.time_s;
        let along = kx * self.wind.0 + ky * self.wind.1;
        let s = if along > 0.0 {
            1.0
        } else if along < 0.0 {
            -1.0
        } else {
            0.0
        };
        match self.mode {
            PhaseMode::Dispersion => s * setup.omega_t(kx, ky),
            PhaseMode::Translate => along * self.speed_mps * t,
            PhaseMode::HotAir => {
                let k = (kx * kx + ky * ky).sqrt();
                let rate = if k >= self.band.0 && k <= self.band.1 {
                    self.dominant_rad
                } else {
                    self.other_rad
                };
                s * rate * t * self.fps
            }
        }
    }
}

/// Filter power along the wind ray: the k of its peak and the band where it is at least
/// `fraction` of the peak, rad/m.
pub fn peak_band(setup: &SpectrumSetup, wind: (f64, f64), fraction: f64) -> (f64, (f64, f64)) {
    let (dkx, dky) = setup.dk();
    let k_min = dkx.min(dky);
    let k_max = std::f64::consts::PI
        * (setup.spec.nx as f64 / setup.spec.extent_x_m)
            .max(setup.spec.ny as f64 / setup.spec.extent_y_m);
    const SAMPLES: usize = 4000;
    let ks: Vec<f64> = (0..SAMPLES)
        .map(|i| k_min * (k_max / k_min).powf(i as f64 / (SAMPLES - 1) as f64))
        .collect();
    let power: Vec<f64> = ks
        .iter()
        .map(|&k| {
            let (x, y) = (k * wind.0, k * wind.1);
            setup.spectrum.amplitude_variance(x, y, dkx, dky)
                + setup.spectrum.amplitude_variance(-x, -y, dkx, dky)
        })
        .collect();
    let (imax, pmax) = power
        .iter()
        .enumerate()
        .fold((0, 0.0f64), |b, (i, &p)| if p > b.1 { (i, p) } else { b });
    let (mut lo, mut hi) = (imax, imax);
    while lo > 0 && power[lo - 1] >= fraction * pmax {
        lo -= 1;
    }
    while hi + 1 < SAMPLES && power[hi + 1] >= fraction * pmax {
        hi += 1;
    }
    (ks[imax], (ks[lo], ks[hi]))
}

/// The filtered-noise half spectrum at `setup.time_s` (moving by `motion`, if given);
/// `h0max_m` is the largest |h̃(k)|.
pub fn filtered_spectrum(
    setup: &SpectrumSetup,
    motion: Option<&Motion>,
) -> super::fft::HalfSpectrum {
    let (nx, ny) = (setup.spec.nx, setup.spec.ny);
    let moving = motion.filter(|_| setup.time_s != 0.0);
    build_lines(setup, |n, kx, buf, line| {
        let mut peak = 0.0f64;
        for (idx, out) in line.iter_mut().enumerate() {
            let m = signed_index(idx, ny);
            if !is_resolved(n, m, nx, ny) {
                continue;
            }
            let power = buf.pa[idx] + buf.pb[idx];
            if power <= 0.0 {
                continue;
            }
            // One draw per ±k pair, keyed by the member of the upper half plane.
            let (re, im) = if n > 0 || m > 0 {
                gaussian_pair(setup.seed, n, m)
            } else {
                let (re, im) = gaussian_pair(setup.seed, -n, -m);
                (re, -im)
            };
            let a = (power * 0.5).sqrt();
            let mut h = (re * a, im * a);
            peak = peak.max(h.0 * h.0 + h.1 * h.1);
            if let Some(mo) = moving {
                // h̃·e^{−iφ}.
                let (s, c) = sin_cos(mo.phase(setup, kx, buf.ky[idx]));
                h = (h.0 * c + h.1 * s, h.1 * c - h.0 * s);
            }
            *out = Complex32::new(h.0 as f32, h.1 as f32);
        }
        peak
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::fft::InverseFft2;
    use crate::grid::GridSpec;
    use crate::spectrum::{Dispersion, Phillips};

    #[test]
    fn the_spectrum_is_hermitian_on_the_kx_zero_line_and_the_field_matches_its_power() {
        let ph = Phillips::new(1e-4, 9.0, 0.6, 0.0);
        let spec = GridSpec::new(32, 24, 100.0, 75.0);
        let setup = SpectrumSetup {
            spec,
            spectrum: &ph,
            dispersion: Dispersion::Deep,
            seed: 4,
            time_s: 0.0,
            loop_period_s: None,
        };
        let half = filtered_spectrum(&setup, None);
        for idx in 1..24 {
            let m = signed_index(idx, 24);
            let mirror = (24 - idx) % 24;
            let (a, b) = (half.data[idx], half.data[mirror]);
            if is_resolved(0, m, 32, 24) {
                assert_eq!(a, b.conj(), "h̃(0, {m}) must be conj h̃(0, {})", -m);
            }
        }
        let power = half.total_power();
        let field = InverseFft2::new(32, 24).process(half);
        let ms = field.iter().map(|&v| (v as f64).powi(2)).sum::<f64>() / field.len() as f64;
        assert!(
            (ms - power).abs() < 1e-4 * power,
            "Parseval: {ms} vs {power}"
        );
    }

    #[test]
    fn each_phase_mode_turns_exactly_the_components_it_should() {
        use crate::config::PhaseMode;
        let ph = Phillips::new(1e-4, 9.0, 0.6, 0.0);
        let spec = GridSpec::new(64, 64, 200.0, 200.0);
        let at = |t: f64| SpectrumSetup {
            spec,
            spectrum: &ph,
            dispersion: Dispersion::Deep,
            seed: 4,
            time_s: t,
            loop_period_s: None,
        };
        let wind = (0.6f64.cos(), 0.6f64.sin());
        let (k_peak, band) = peak_band(&at(0.0), wind, 2.0 / 3.0);
        assert!(
            band.0 < k_peak && k_peak < band.1,
            "{band:?} around {k_peak}"
        );
        let fps = 30.0;
        let still = filtered_spectrum(&at(0.0), None);
        let (mut dominant, mut other) = (0, 0);
        for mode in [
            PhaseMode::HotAir,
            PhaseMode::Dispersion,
            PhaseMode::Translate,
        ] {
            let motion = Motion {
                mode,
                wind,
                fps,
                dominant_rad: 0.05,
                other_rad: 0.003,
                speed_mps: 2.5,
                band,
            };
            let t = 1.0 / fps;
            let moved = filtered_spectrum(&at(t), Some(&motion));
            for n in 0..=32usize {
                for idx in 0..64 {
                    let (a, b) = (still.data[n * 64 + idx], moved.data[n * 64 + idx]);
                    if a.norm() < 1e-12 {
                        continue;
                    }
                    let (kx, ky) = at(0.0).wavevector(n as i64, signed_index(idx, 64));
                    let along = kx * wind.0 + ky * wind.1;
                    let s = along.signum() * (along != 0.0) as i32 as f64;
                    let k = (kx * kx + ky * ky).sqrt();
                    let want = match mode {
                        PhaseMode::HotAir => {
                            let in_band = k >= band.0 && k <= band.1;
                            if in_band {
                                dominant += 1;
                            } else {
                                other += 1;
                            }
                            s * if in_band { 0.05 } else { 0.003 }
                        }
                        PhaseMode::Dispersion => s * (9.81 * k).sqrt() * t,
                        PhaseMode::Translate => along * 2.5 * t,
                    };
                    // b = a·e^{−iφ}: the phase turned by −φ (f32 storage: 1e-5 rad).
                    let turned = (b * a.conj()).arg() as f64;
                    let diff = (turned + want + std::f64::consts::PI)
                        .rem_euclid(std::f64::consts::TAU)
                        - std::f64::consts::PI;
                    assert!(
                        diff.abs() < 2e-5,
                        "{mode:?} at ({n}, {idx}): turned {turned}, want {}",
                        -want
                    );
                    assert!((b.norm() - a.norm()).abs() <= 1e-5 * a.norm());
                }
            }
        }
        assert!(
            dominant > 10 && other > 100,
            "{dominant} dominant, {other} other"
        );
    }
}
