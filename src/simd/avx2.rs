//! Code written for AVX2 by hand: the hash of the Gaussian draws. AVX2 has no 64-bit
//! multiply, and the compiler's emulation of one is slower than the 32-bit products here
//! (AVX-512 has one, and the compiler vectorizes the plain loop).

use crate::rng::{self, MIX_K1, MIX_K2};
use std::arch::x86_64::*;

/// The Gaussian draws of a line from its hash prefix and words, with AVX2: per chunk
/// (which stays in the L1 cache), the hash into uniforms (intrinsics), then Box–Muller
/// (vectorized by the compiler).
///
/// # Safety
/// The processor must have AVX2.
#[target_feature(enable = "avx2")]
#[inline(never)]
pub(super) unsafe fn polar_run(prefix: u64, words: &[u64], r: &mut [f64], phi: &mut [f64]) {
    const CHUNK: usize = 256;
    let chunks = words
        .chunks(CHUNK)
        .zip(r.chunks_mut(CHUNK).zip(phi.chunks_mut(CHUNK)));
    for (words, (r, phi)) in chunks {
        // SAFETY: the caller guarantees AVX2.
        unsafe { polar_units_run(prefix, words, r, phi) };
        for (r, phi) in r.iter_mut().zip(phi.iter_mut()) {
            (*r, *phi) = rng::polar_from_units(*r, *phi);
        }
    }
}

/// `(u1[j], u2[j]) = rng::polar_units_from_word(prefix, words[j])`.
///
/// Each iteration hashes four elements in vector registers and one more with scalar
/// instructions (from the end of the run), which use the otherwise idle integer units
/// (about 15% faster than vectors alone on Zen 4).
///
/// # Safety
/// The processor must have AVX2.
#[target_feature(enable = "avx2")]
unsafe fn polar_units_run(prefix: u64, words: &[u64], u1: &mut [f64], u2: &mut [f64]) {
    let len = words.len().min(u1.len()).min(u2.len());
    let (words, u1, u2) = (&words[..len], &mut u1[..len], &mut u2[..len]);
    let iterations = len / 5;
    let vector_len = 4 * iterations;
    let (vector_words, scalar_words) = words.split_at(vector_len);
    let (vector_u1, scalar_u1) = u1.split_at_mut(vector_len);
    let (vector_u2, scalar_u2) = u2.split_at_mut(vector_len);
    // SAFETY: the caller guarantees AVX2; the pointers address elements 4·it..4·it + 4
    // of slices of length 4·iterations.
    unsafe {
        let prefix_v = _mm256_set1_epi64x(prefix as i64);
        let (w, p1, p2) = (
            vector_words.as_ptr(),
            vector_u1.as_mut_ptr(),
            vector_u2.as_mut_ptr(),
        );
        for it in 0..iterations {
            let j = 4 * it;
            let word = _mm256_loadu_si256(w.add(j).cast::<__m256i>());
            let key = mix64(_mm256_xor_si256(prefix_v, word));
            let a = mix64(_mm256_xor_si256(key, _mm256_set1_epi64x(1)));
            let b = mix64(_mm256_xor_si256(key, _mm256_set1_epi64x(2)));
            _mm256_storeu_pd(p1.add(j), unit_open0(a));
            _mm256_storeu_pd(p2.add(j), unit_open0(b));
            (scalar_u1[it], scalar_u2[it]) = rng::polar_units_from_word(prefix, scalar_words[it]);
        }
    }
    let rest = scalar_words[iterations..].iter().zip(
        scalar_u1[iterations..]
            .iter_mut()
            .zip(&mut scalar_u2[iterations..]),
    );
    for (&word, (u1, u2)) in rest {
        (*u1, *u2) = rng::polar_units_from_word(prefix, word);
    }
}

/// `x·k mod 2^64` in each lane: `lo·k_lo + ((lo·k_hi + hi·k_lo) mod 2^32)·2^32`, the
/// cross terms by one 32-bit multiply of `x` with `k`'s halves swapped.
#[inline(always)]
unsafe fn mul_const(x: __m256i, k: u64) -> __m256i {
    // SAFETY: only called from AVX2 code.
    unsafe {
        // 32-bit lanes: (lo·k_hi, hi·k_lo) mod 2^32.
        let cross = _mm256_mullo_epi32(x, _mm256_set1_epi64x(k.rotate_left(32) as i64));
        // Their sum in the high half of each 64-bit lane.
        let cross = _mm256_and_si256(
            _mm256_add_epi64(cross, _mm256_slli_epi64(cross, 32)),
            _mm256_set1_epi64x(0xFFFF_FFFF_0000_0000u64 as i64),
        );
        _mm256_add_epi64(_mm256_mul_epu32(x, _mm256_set1_epi64x(k as i64)), cross)
    }
}

/// [`rng::mix64`] in each lane.
#[inline(always)]
unsafe fn mix64(z: __m256i) -> __m256i {
    // SAFETY: only called from AVX2 code.
    unsafe {
        let z = mul_const(_mm256_xor_si256(z, _mm256_srli_epi64(z, 30)), MIX_K1);
        let z = mul_const(_mm256_xor_si256(z, _mm256_srli_epi64(z, 27)), MIX_K2);
        _mm256_xor_si256(z, _mm256_srli_epi64(z, 31))
    }
}

/// `rng::unit_open0` in each lane: `(x − (x & 1))·2^-53 + ((x & 1) + 1)·2^-53`, with
/// `x = bits >> 11`, both terms and the sum exact.
#[inline(always)]
unsafe fn unit_open0(bits: __m256i) -> __m256d {
    // SAFETY: only called from AVX2 code.
    unsafe {
        let one_plus = _mm256_or_si256(
            _mm256_srli_epi64(bits, 12),
            _mm256_set1_epi64x(0x3FF0_0000_0000_0000),
        );
        let even = _mm256_sub_pd(_mm256_castsi256_pd(one_plus), _mm256_set1_pd(1.0));
        let x_even = _mm256_cmpeq_epi64(
            _mm256_and_si256(bits, _mm256_set1_epi64x(1 << 11)),
            _mm256_setzero_si256(),
        );
        let low = _mm256_blendv_pd(
            _mm256_set1_pd(f64::from_bits(0x3CB0_0000_0000_0000)), // 2^-52
            _mm256_set1_pd(f64::from_bits(0x3CA0_0000_0000_0000)), // 2^-53
            _mm256_castsi256_pd(x_even),
        );
        _mm256_add_pd(even, low)
    }
}
