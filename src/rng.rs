//! Counter-based random numbers keyed by integers.
//!
//! Spectral methods draw each wavevector's Gaussian pair from `(seed, stream, n, m)`,
//! where `(n, m)` are the wavevector's integer indices (k = 2π·(n/Lx, m/Ly)). The draw does
//! not depend on the grid size or on the order in which wavevectors are visited, so the same
//! seed over the same extent gives the same long waves at every resolution, and results
//! do not depend on threads. The hash is SplitMix64's finalizer applied to a combination
//! of the key words; it is fixed here and portable (integer arithmetic only), and the
//! Gaussian transform uses `fastmath` (portable `ln`, `sin_cos`), so draws are the same on every platform.

use crate::fastmath;

/// Streams keep the draws of different uses of one seed apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u64)]
pub enum Stream {
    /// Complex Gaussian amplitudes of the height spectrum.
    SpectrumAmplitude = 1,
    /// Gradient hashes of Perlin noise.
    Perlin = 2,
    /// Phases of the trochoid components.
    TrochoidPhase = 3,
    /// Gradient hashes of the trochoid method's turbulence.
    Turbulence = 4,
}

/// The multipliers of [`mix64`].
pub(crate) const MIX_K1: u64 = 0xbf58_476d_1ce4_e5b9;
pub(crate) const MIX_K2: u64 = 0x94d0_49bb_1331_11eb;

/// SplitMix64's output function: a bijective 64-bit mixer.
#[inline(always)]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(MIX_K1);
    z = (z ^ (z >> 27)).wrapping_mul(MIX_K2);
    z ^ (z >> 31)
}

/// The initial state of [`hash_words`], and the constant added to each word.
pub(crate) const HASH_INIT: u64 = 0x9e37_79b9_7f4a_7c15;

/// One step of [`hash_words`]: absorbs the word `w` into the state `h`.
#[inline(always)]
fn hash_step(h: u64, w: u64) -> u64 {
    mix64(h ^ mix64(w.wrapping_add(HASH_INIT)))
}

/// Hash of a key of several words, each step a full avalanche.
#[inline(always)]
pub fn hash_words(words: &[u64]) -> u64 {
    words.iter().fold(HASH_INIT, |h, &w| hash_step(h, w))
}

/// A seed derived from `seed` for one stream (the fixed sub-seed rule).
pub fn sub_seed(seed: u64, stream: Stream) -> u64 {
    hash_words(&[seed, stream as u64])
}

/// Uniform in (0, 1], from the top 53 bits: `((bits >> 11) + 1)·2^-53`, exactly.
///
/// Computed by bit manipulation and exact floating-point operations rather than an
/// integer conversion, which vector units lack for 64-bit integers (without AVX-512):
/// with `x = bits >> 11`, `1 + (x >> 1)·2^-52` is built from bits and loses its 1 exactly,
/// leaving `(x − (x & 1))·2^-53`; adding `((x & 1) + 1)·2^-53`, also built from bits, gives
/// `(x + 1)·2^-53 ≤ 1`, representable, so the sum is exact.
#[inline(always)]
fn unit_open0(bits: u64) -> f64 {
    let even = f64::from_bits(0x3FF0_0000_0000_0000 | (bits >> 12)) - 1.0;
    // 2^-53 (exponent field 0x3CA) or 2^-52.
    let low = f64::from_bits(0x3CA0_0000_0000_0000 + (((bits >> 11) & 1) << 52));
    even + low
}

/// A standard complex Gaussian ξr + iξi (each part N(0, 1)) for the integer wavevector
/// `(n, m)`, in polar form (r, φ): r = √(−2 ln u1) is Rayleigh distributed and φ = 2π·u2
/// uniform, from two hashed uniforms (the Box–Muller transform).
#[inline(always)]
pub fn gaussian_polar(seed: u64, n: i64, m: i64) -> (f64, f64) {
    let (u1, u2) = polar_units_from_word(polar_prefix(seed, n), polar_word(m));
    polar_from_units(u1, u2)
}

// The parts of `gaussian_polar`, for the line kernels of `crate::simd` (which
// repeat `polar_units_from_word` in AVX2 instructions, and are tested to agree bit for bit).

/// The hash state of [`gaussian_polar`] after the words `(seed, n)`, which all the draws of
/// one line of constant `n` share.
#[inline(always)]
pub(crate) fn polar_prefix(seed: u64, n: i64) -> u64 {
    hash_step(hash_step(HASH_INIT, seed), n as u64)
}

/// The part of [`gaussian_polar`]`(seed, n, m)`'s hash that depends on `m` alone.
#[inline(always)]
pub(crate) fn polar_word(m: i64) -> u64 {
    mix64((m as u64).wrapping_add(HASH_INIT))
}

/// The two uniforms in (0, 1] of [`gaussian_polar`]`(seed, n, m)`, from
/// `prefix = polar_prefix(seed, n)` and `word = polar_word(m)`: integer hashing only.
#[inline(always)]
pub(crate) fn polar_units_from_word(prefix: u64, word: u64) -> (f64, f64) {
    // = hash_words(&[seed, n as u64, m as u64]).
    let key = mix64(prefix ^ word);
    (unit_open0(mix64(key ^ 0x1)), unit_open0(mix64(key ^ 0x2)))
}

/// Box–Muller's (r, φ) from the uniforms `u1, u2 ∈ (0, 1]`: straight-line code.
#[inline(always)]
pub(crate) fn polar_from_units(u1: f64, u2: f64) -> (f64, f64) {
    // u1 ∈ [2^-53, 1] is positive and normal, where ln_positive_normal equals ln.
    (
        (-2.0 * fastmath::ln_positive_normal(u1)).sqrt(),
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
    fn unit_open0_is_the_scaled_integer() {
        fn reference(bits: u64) -> f64 {
            ((bits >> 11) + 1) as f64 * (1.0 / (1u64 << 53) as f64)
        }
        let mut x = 0x0123_4567_89AB_CDEFu64;
        let edges = (0..64).flat_map(|k| [1u64 << k, (1u64 << k) - 1, !(1u64 << k)]);
        let low_bits = (0..4096u64).flat_map(|b| [b << 11, !(b << 11), b << 52 | b]);
        let random = (0..1_000_000).map(|_| {
            x = mix64(x.wrapping_add(0x9e37_79b9_7f4a_7c15));
            x
        });
        for bits in edges.chain(low_bits).chain(random).chain([0, u64::MAX]) {
            let (got, want) = (unit_open0(bits), reference(bits));
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "bits {bits:#018x}: {got} vs {want}"
            );
        }
        assert_eq!(unit_open0(0), 1.0 / (1u64 << 53) as f64);
        assert_eq!(unit_open0(u64::MAX), 1.0);
    }

    #[test]
    fn gaussian_polar_is_pinned() {
        // FNV-1a over the bits of draws; the constants are those of the original
        // one-piece implementation, so the split into parts changed no bit.
        let mut h = 0xCBF2_9CE4_8422_2325u64;
        let mut fnv = |bits: u64| {
            for byte in bits.to_le_bytes() {
                h = (h ^ byte as u64).wrapping_mul(0x0000_0100_0000_01B3);
            }
        };
        for seed in [0u64, 1, 0xDEAD_BEEF] {
            for n in -40i64..40 {
                for m in -40i64..40 {
                    let (r, phi) = gaussian_polar(seed, n, m);
                    fnv(r.to_bits());
                    fnv(phi.to_bits());
                }
            }
        }
        for (seed, n, m) in [(u64::MAX, i64::MIN, i64::MAX), (7, 1 << 40, -(1 << 50))] {
            let (r, phi) = gaussian_polar(seed, n, m);
            fnv(r.to_bits());
            fnv(phi.to_bits());
        }
        assert_eq!(h, 0x43F4_1AF8_A208_7E5C);
        let (r, phi) = gaussian_polar(1, 2, 3);
        assert_eq!(
            (r.to_bits(), phi.to_bits()),
            (0x3FE3_D244_793C_2F10, 0x4005_EA77_E7B8_DDF7)
        );
    }

    #[test]
    fn the_hash_is_pinned() {
        // Outputs must never change between versions or platforms: a changed hash
        // silently changes every seeded result.
        assert_eq!(mix64(0), 0);
        assert_eq!(mix64(1), 0x5692_161d_100b_05e5);
    }
}
