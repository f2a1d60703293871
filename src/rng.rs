//! Counter-based random numbers keyed by integers.
//!
//! Spectral methods draw each wavevector's Gaussian pair from `(seed, stream, n, m)`,
//! where `(n, m)` are the wavevector's integer indices (k = 2π·(n/Lx, m/Ly)). The draw does
//! not depend on the grid size or on the order in which wavevectors are visited, so the same
//! seed over the same extent gives the same long waves at every resolution, and results
//! do not depend on threads. The hash is SplitMix64's finalizer applied to a combination
//! of the key words; it is fixed here and portable (integer arithmetic only), and the
//! Gaussian transform uses [`crate::fastmath`], so draws are the same on every platform.

use crate::fastmath;

/// Streams keep the draws of different uses of one seed apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u64)]
pub enum Stream {
    /// Complex Gaussian amplitudes of the height spectrum.
    SpectrumAmplitude = 1,
    /// Gradient hashes of Perlin noise.
    Perlin = 2,
}

/// SplitMix64's output function: a bijective 64-bit mixer.
#[inline(always)]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hash of a key of several words, each step a full avalanche.
#[inline(always)]
pub fn hash_words(words: &[u64]) -> u64 {
    let mut h = 0x9e37_79b9_7f4a_7c15u64;
    for &w in words {
        h = mix64(h ^ mix64(w.wrapping_add(0x9e37_79b9_7f4a_7c15)));
    }
    h
}

/// A seed derived from `seed` for one stream (the fixed sub-seed rule).
pub fn sub_seed(seed: u64, stream: Stream) -> u64 {
    hash_words(&[seed, stream as u64])
}

/// Uniform in (0, 1], from the top 53 bits.
#[inline]
fn unit_open0(bits: u64) -> f64 {
    ((bits >> 11) + 1) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A standard complex Gaussian ξr + iξi (each part N(0, 1)) for the integer wavevector
/// `(n, m)`, in polar form (r, φ): r = √(−2 ln u1) is Rayleigh distributed and φ = 2π·u2
/// uniform, from two hashed uniforms (the Box–Muller transform).
#[inline(always)]
pub fn gaussian_polar(seed: u64, n: i64, m: i64) -> (f64, f64) {
    let key = hash_words(&[seed, n as u64, m as u64]);
    let u1 = unit_open0(mix64(key ^ 0x1));
    let u2 = unit_open0(mix64(key ^ 0x2));
    (
        (-2.0 * fastmath::ln(u1)).sqrt(),
        2.0 * std::f64::consts::PI * u2,
    )
}

/// The same draw as [`gaussian_polar`] as the pair (ξr, ξi).
#[inline]
pub fn gaussian_pair(seed: u64, n: i64, m: i64) -> (f64, f64) {
    let (r, phi) = gaussian_polar(seed, n, m);
    let (s, c) = fastmath::sin_cos(phi);
    (r * c, r * s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_pairs_have_unit_variance_and_no_correlation() {
        // 200k draws: the standard error of a variance estimate is about sqrt(2/n) ≈ 0.003.
        const TOL: f64 = 0.015;
        let (mut s1, mut s2, mut s11, mut s22, mut s12) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let mut count = 0.0;
        for n in -250..250i64 {
            for m in -200..200i64 {
                let (a, b) = gaussian_pair(7, n, m);
                s1 += a;
                s2 += b;
                s11 += a * a;
                s22 += b * b;
                s12 += a * b;
                count += 1.0;
            }
        }
        assert!((s1 / count).abs() < TOL, "mean of first {}", s1 / count);
        assert!((s2 / count).abs() < TOL, "mean of second {}", s2 / count);
        assert!((s11 / count - 1.0).abs() < TOL, "variance {}", s11 / count);
        assert!((s22 / count - 1.0).abs() < TOL, "variance {}", s22 / count);
        assert!((s12 / count).abs() < TOL, "correlation {}", s12 / count);
    }

    #[test]
    fn draws_depend_on_seed_and_wavevector_only() {
        assert_eq!(gaussian_pair(3, 5, -2), gaussian_pair(3, 5, -2));
        assert_ne!(gaussian_pair(3, 5, -2), gaussian_pair(4, 5, -2));
        assert_ne!(gaussian_pair(3, 5, -2), gaussian_pair(3, -2, 5));
        assert_ne!(gaussian_pair(3, 5, -2), gaussian_pair(3, -5, 2));
    }

    #[test]
    fn the_hash_is_pinned() {
        // Outputs must never change between versions or platforms: a changed hash
        // silently changes every seeded result.
        assert_eq!(mix64(0), 0);
        assert_eq!(mix64(1), 0x5692_161d_100b_05e5);
        let (a, _) = gaussian_pair(1, 2, 3);
        assert!((a - gaussian_pair(1, 2, 3).0).abs() == 0.0);
    }
}
