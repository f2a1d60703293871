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
//! Σ_k (P(k) + P(−k)) as the FFT method. It is a still image: no time evolution.

use rustfft::num_complex::Complex32;

use super::fft::{SpectrumSetup, build_lines, is_resolved, signed_index};
use crate::rng::gaussian_pair;

/// The filtered-noise half spectrum; `h0max_m` is the largest |h̃(k)|.
pub fn filtered_spectrum(setup: &SpectrumSetup) -> super::fft::HalfSpectrum {
    let (nx, ny) = (setup.spec.nx, setup.spec.ny);
    build_lines(setup, |n, _kx, buf, line| {
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
            let h = (re * a, im * a);
            peak = peak.max(h.0 * h.0 + h.1 * h.1);
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
        };
        let half = filtered_spectrum(&setup);
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
}
