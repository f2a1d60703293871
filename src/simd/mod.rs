//! Whole-line kernels of spectrum synthesis: the Gaussian draws and the sines and cosines
//! of one kx line at a time, bit-identical to the scalar functions they stand for.
//!
//! The kernels are branch-free loops over arrays, built from the always-inlined cores of
//! [`crate::rng`] and [`crate::fastmath`] (the range checks and special cases stay in the
//! scalar functions: a line is checked once, and rare lanes are redone by the scalar
//! function), so the compiler vectorizes them. They are compiled for the target's
//! baseline and (on x86-64) for AVX2 and AVX-512, chosen at run time; the AVX2 hash is
//! written with intrinsics, because AVX2 has no 64-bit multiply and the compiler's
//! emulation is slower (AVX-512 has one, and the compiler vectorizes the plain loop).
//!
//! Why the bits are the same: vector IEEE `+ − × / √` round exactly like their scalar
//! forms, and the kernels perform the scalar functions' operations in the same order,
//! without fused multiply–add (Rust never contracts `a * b + c` into one, whatever the
//! instruction set offers); integer operations are exact. The tests compare every path with
//! the scalar functions bit for bit.

use crate::fastmath;
use crate::grid::signed_index;
use crate::rng;

/// For `i` in `0..r.len()`: `(r[i], phi[i]) = rng::gaussian_polar(seed, sign·n, sign·m_i)`
/// with `m_i = fft::signed_index(i, ny)`, bit-identical to calling
/// [`rng::gaussian_polar`] one by one (the products `sign·n`, `sign·m_i` wrap).
///
/// # Panics
/// If `r` and `phi` differ in length.
pub fn polar_line(seed: u64, n: i64, sign: i64, ny: usize, r: &mut [f64], phi: &mut [f64]) {
    polar_line_on(Isa::detect(), seed, n, sign, ny, r, phi);
}

/// `(s[i], c[i]) = fastmath::sin_cos(x[i])` for every `i`, bit for bit, for every `x`
/// (lanes with `|x| ≥ 1e8` or non-finite `x` are redone by the scalar function).
///
/// # Panics
/// If the slices differ in length.
pub fn sin_cos_line(x: &[f64], s: &mut [f64], c: &mut [f64]) {
    sin_cos_line_on(Isa::detect(), x, s, c);
}

/// Defines `fn NAME(args) -> R` whose body is compiled for the target's baseline and (on
/// x86-64) for AVX2 and for AVX-512, the copy chosen at run time: for whole-line loops
/// that the compiler vectorizes. The body must give the same bits on every copy (IEEE
/// basic operations and `fastmath`'s cores only, no fused multiply–add; Rust never
/// contracts a·b + c into one).
macro_rules! multiversion {
    // `fn name(isa: Isa, …)`: the caller chooses the instruction set (tests run both).
    (@on $(#[$meta:meta])* $vis:vis fn $name:ident($isa:ident : Isa, $($arg:ident : $ty:ty),* $(,)?) $(-> $ret:ty)? $body:block) => {
        $(#[$meta])*
        #[allow(clippy::too_many_arguments)]
        $vis fn $name($isa: $crate::simd::Isa, $($arg: $ty),*) $(-> $ret)? {
            #[inline(always)]
            #[allow(clippy::too_many_arguments)]
            fn mv_body($($arg: $ty),*) $(-> $ret)? $body
            #[inline(never)]
            #[allow(clippy::too_many_arguments)]
            fn mv_plain($($arg: $ty),*) $(-> $ret)? {
                mv_body($($arg),*)
            }
            /// # Safety
            /// The processor must have AVX2.
            #[cfg(target_arch = "x86_64")]
            #[target_feature(enable = "avx2")]
            #[inline(never)]
            #[allow(clippy::too_many_arguments)]
            unsafe fn mv_avx2($($arg: $ty),*) $(-> $ret)? {
                mv_body($($arg),*)
            }
            /// # Safety
            /// The processor must have AVX-512 F, DQ and VL.
            #[cfg(target_arch = "x86_64")]
            #[target_feature(enable = "avx2,avx512f,avx512dq,avx512vl")]
            #[inline(never)]
            #[allow(clippy::too_many_arguments)]
            unsafe fn mv_avx512($($arg: $ty),*) $(-> $ret)? {
                mv_body($($arg),*)
            }
            match $isa {
                $crate::simd::Isa::Plain => mv_plain($($arg),*),
                // SAFETY: Isa::Avx2 is only chosen when the processor has AVX2.
                #[cfg(target_arch = "x86_64")]
                $crate::simd::Isa::Avx2 => unsafe { mv_avx2($($arg),*) },
                // SAFETY: Isa::Avx512 is only chosen when the processor has it.
                #[cfg(target_arch = "x86_64")]
                $crate::simd::Isa::Avx512 => unsafe { mv_avx512($($arg),*) },
            }
        }
    };
    ($(#[$meta:meta])* $vis:vis fn $name:ident($($arg:ident : $ty:ty),* $(,)?) $(-> $ret:ty)? $body:block) => {
        $(#[$meta])*
        #[allow(clippy::too_many_arguments)]
        $vis fn $name($($arg: $ty),*) $(-> $ret)? {
            $crate::simd::multiversion! {
                @on fn on(isa: Isa, $($arg: $ty),*) $(-> $ret)? $body
            }
            on($crate::simd::Isa::detect(), $($arg),*)
        }
    };
}
pub(crate) use multiversion;

/// The instruction sets the kernels are compiled for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Isa {
    /// The compilation target's baseline (SSE2 on x86-64).
    Plain,
    /// x86-64 with AVX2.
    #[cfg(target_arch = "x86_64")]
    Avx2,
    /// x86-64 with AVX-512 F, DQ and VL (and AVX2).
    #[cfg(target_arch = "x86_64")]
    Avx512,
}

impl Isa {
    /// The best instruction set of this processor (detected once).
    #[inline]
    pub(crate) fn detect() -> Isa {
        #[cfg(target_arch = "x86_64")]
        {
            use std::sync::atomic::{AtomicU8, Ordering};
            // 0: not detected yet, 1: Plain, 2: Avx2, 3: Avx512.
            static DETECTED: AtomicU8 = AtomicU8::new(0);
            match DETECTED.load(Ordering::Relaxed) {
                1 => Isa::Plain,
                2 => Isa::Avx2,
                3 => Isa::Avx512,
                _ => {
                    let avx2 = std::is_x86_feature_detected!("avx2");
                    let (code, isa) = if Self::has_avx512() {
                        (3, Isa::Avx512)
                    } else if avx2 {
                        (2, Isa::Avx2)
                    } else {
                        (1, Isa::Plain)
                    };
                    DETECTED.store(code, Ordering::Relaxed);
                    isa
                }
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            Isa::Plain
        }
    }

    /// Every instruction set this processor can run (for tests and benchmarks).
    #[cfg(test)]
    pub(crate) fn available() -> Vec<Isa> {
        let mut all = vec![Isa::Plain];
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                all.push(Isa::Avx2);
            }
            if Self::has_avx512() {
                all.push(Isa::Avx512);
            }
        }
        all
    }

    /// AVX-512 F, DQ and VL (with AVX2), unless `SEASYNTH_NO_AVX512` is set.
    #[cfg(target_arch = "x86_64")]
    fn has_avx512() -> bool {
        std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512dq")
            && std::is_x86_feature_detected!("avx512vl")
            && std::env::var_os("SEASYNTH_NO_AVX512").is_none()
    }
}

/// [`polar_line`] on the given instruction set.
fn polar_line_on(
    isa: Isa,
    seed: u64,
    n: i64,
    sign: i64,
    ny: usize,
    r: &mut [f64],
    phi: &mut [f64],
) {
    assert_eq!(r.len(), phi.len(), "polar_line: r and phi differ in length");
    let prefix = rng::polar_prefix(seed, sign.wrapping_mul(n));
    with_words(sign, ny, r.len(), |words| match isa {
        Isa::Plain => polar_run_fused(isa, prefix, words, r, phi),
        // SAFETY: Isa::Avx2 is only chosen when the processor has AVX2.
        #[cfg(target_arch = "x86_64")]
        Isa::Avx2 => unsafe { polar_run_avx2(prefix, words, r, phi) },
        #[cfg(target_arch = "x86_64")]
        Isa::Avx512 => polar_run_fused(isa, prefix, words, r, phi),
    });
}

/// The words `rng::polar_word(sign·m_i)`, `m_i = signed_index(i, ny)`, of the `len`
/// elements of a line, kept per thread for the last two `(sign, ny, len)` asked for (a
/// field's lines come in pairs of signs). A quarter of the hashing is in these words,
/// which are the same for every kx line and seed.
fn with_words<R>(sign: i64, ny: usize, len: usize, f: impl FnOnce(&[u64]) -> R) -> R {
    use std::cell::RefCell;
    /// How many word lines each thread keeps, and the longest it keeps (8 bytes each).
    const KEPT: usize = 2;
    const MAX_KEPT_LEN: usize = 1 << 16;
    struct Words {
        sign: i64,
        ny: usize,
        words: Vec<u64>,
    }
    thread_local! {
        /// Most recently used last.
        static KEPT_WORDS: RefCell<Vec<Words>> = const { RefCell::new(Vec::new()) };
    }
    let compute = || -> Vec<u64> {
        (0..len)
            .map(|i| rng::polar_word(sign.wrapping_mul(signed_index(i, ny))))
            .collect()
    };
    if len > MAX_KEPT_LEN {
        return f(&compute());
    }
    KEPT_WORDS.with(|kept| {
        // Not reentrant: `f` is a kernel, which never calls polar_line.
        let mut kept = kept.borrow_mut();
        let found = kept
            .iter()
            .position(|w| w.sign == sign && w.ny == ny && w.words.len() == len);
        let entry = match found {
            Some(i) => kept.remove(i),
            None => {
                if kept.len() == KEPT {
                    kept.remove(0);
                }
                Words {
                    sign,
                    ny,
                    words: compute(),
                }
            }
        };
        kept.push(entry);
        f(&kept[kept.len() - 1].words)
    })
}

multiversion! {
    @on
    /// `(r[j], phi[j]) = gaussian_polar` from the line's hash prefix and words, in one
    /// fused loop: on SSE2 splitting the hash off as [`polar_run_avx2`] does is slower,
    /// and with AVX-512's 64-bit multiplications the compiler vectorizes the hash itself.
    fn polar_run_fused(isa: Isa, prefix: u64, words: &[u64], r: &mut [f64], phi: &mut [f64]) {
        for ((&word, r), phi) in words.iter().zip(r.iter_mut()).zip(phi.iter_mut()) {
            let (u1, u2) = rng::polar_units_from_word(prefix, word);
            (*r, *phi) = rng::polar_from_units(u1, u2);
        }
    }
}

/// [`polar_run_plain`] with AVX2: per chunk (which stays in the L1 cache), the hash into
/// uniforms (intrinsics), then Box–Muller (vectorized by the compiler).
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline(never)]
unsafe fn polar_run_avx2(prefix: u64, words: &[u64], r: &mut [f64], phi: &mut [f64]) {
    const CHUNK: usize = 256;
    let chunks = words
        .chunks(CHUNK)
        .zip(r.chunks_mut(CHUNK).zip(phi.chunks_mut(CHUNK)));
    for (words, (r, phi)) in chunks {
        // SAFETY: the caller guarantees AVX2.
        unsafe { avx2::polar_units_run(prefix, words, r, phi) };
        for (r, phi) in r.iter_mut().zip(phi.iter_mut()) {
            (*r, *phi) = rng::polar_from_units(*r, *phi);
        }
    }
}

/// [`sin_cos_line`] on the given instruction set.
fn sin_cos_line_on(isa: Isa, x: &[f64], s: &mut [f64], c: &mut [f64]) {
    assert!(
        x.len() == s.len() && x.len() == c.len(),
        "sin_cos_line: x, s and c differ in length"
    );
    if sin_cos_run(isa, x, s, c) {
        sin_cos_fix_up(x, s, c);
    }
}

multiversion! {
    @on
    /// The Cody–Waite sin_cos of every lane; true if some lane needs the scalar function.
    fn sin_cos_run(isa: Isa, x: &[f64], s: &mut [f64], c: &mut [f64]) -> bool {
        let mut out_of_range = false;
        for ((&x, s), c) in x.iter().zip(s.iter_mut()).zip(c.iter_mut()) {
            out_of_range |= fastmath::sin_cos_is_large(x);
            (*s, *c) = fastmath::sin_cos_cody_waite(x);
        }
        out_of_range
    }
}

/// Redoes the lanes outside the Cody–Waite range with the scalar function.
#[cold]
#[inline(never)]
fn sin_cos_fix_up(x: &[f64], s: &mut [f64], c: &mut [f64]) {
    for ((&x, s), c) in x.iter().zip(s.iter_mut()).zip(c.iter_mut()) {
        if fastmath::sin_cos_is_large(x) {
            (*s, *c) = fastmath::sin_cos(x);
        }
    }
}

/// The hash of [`rng::polar_units_from_word`] in AVX2 intrinsics, four lanes at a time.
#[cfg(target_arch = "x86_64")]
mod avx2 {
    use crate::rng::{self, MIX_K1, MIX_K2};
    use std::arch::x86_64::*;

    /// `(u1[j], u2[j]) = rng::polar_units_from_word(prefix, words[j])`.
    ///
    /// Each iteration hashes four elements in vector registers and one more with scalar
    /// instructions (from the end of the run), which use the otherwise idle integer units
    /// (about 15% faster than vectors alone on Zen 4).
    ///
    /// # Safety
    /// The processor must have AVX2.
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn polar_units_run(
        prefix: u64,
        words: &[u64],
        u1: &mut [f64],
        u2: &mut [f64],
    ) {
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
                (scalar_u1[it], scalar_u2[it]) =
                    rng::polar_units_from_word(prefix, scalar_words[it]);
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    /// SplitMix64, for reproducible pseudo-random test points.
    struct Rng(u64);
    impl Rng {
        fn next_u64(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            rng::mix64(self.0)
        }
        /// Uniform in [lo, hi).
        fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
            let u = (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
            lo + (hi - lo) * u
        }
    }

    #[test]
    fn polar_line_equals_gaussian_polar_bit_for_bit() {
        let isas = Isa::available();
        println!("instruction sets: {isas:?}");
        let seeds = [0, 1, 7, 0xDEAD_BEEF, u64::MAX, rng::mix64(12345)];
        let ns = [0i64, 1, -1, 2, 37, -1000, 2048, i64::MAX, i64::MIN];
        let nys = [
            0usize, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 17, 31, 33, 64, 255, 1000, 4096, 4097,
        ];
        let mut count = 0usize;
        for &isa in &isas {
            for &seed in &seeds {
                for &n in &ns {
                    for sign in [1i64, -1] {
                        for &ny in &nys {
                            // Also lines shorter and longer than ny.
                            for len in [ny, ny / 3, ny + 5] {
                                check_polar_line(isa, seed, n, sign, ny, len);
                                count += len;
                            }
                        }
                    }
                }
            }
        }
        assert!(count > 1_000_000);
        // The public entry point, on whatever this processor has.
        let (mut r, mut phi) = (vec![0.0; 4096], vec![0.0; 4096]);
        polar_line(5, 3, -1, 4096, &mut r, &mut phi);
        for (i, (r, phi)) in r.into_iter().zip(phi).enumerate() {
            let (wr, wphi) = rng::gaussian_polar(5, -3, -signed_index(i, 4096));
            assert_eq!((r.to_bits(), phi.to_bits()), (wr.to_bits(), wphi.to_bits()));
        }
    }

    /// Checks polar_line on `isa` against gaussian_polar.
    fn check_polar_line(isa: Isa, seed: u64, n: i64, sign: i64, ny: usize, len: usize) {
        let mut r = vec![f64::NAN; len];
        let mut phi = vec![f64::NAN; len];
        polar_line_on(isa, seed, n, sign, ny, &mut r, &mut phi);
        for (i, (r, phi)) in r.into_iter().zip(phi).enumerate() {
            let m = sign.wrapping_mul(signed_index(i, ny));
            let (wr, wphi) = rng::gaussian_polar(seed, sign.wrapping_mul(n), m);
            assert!(
                r.to_bits() == wr.to_bits() && phi.to_bits() == wphi.to_bits(),
                "{isa:?}: seed {seed}, n {n}, sign {sign}, ny {ny}, len {len}, i {i}: \
                 ({r}, {phi}) instead of ({wr}, {wphi})"
            );
        }
    }

    #[test]
    fn kept_words_serve_interleaved_and_long_lines() {
        // Three line shapes take turns for the two places of the per-thread words, in
        // varying orders; and a line too long to keep.
        let shapes = [
            (1i64, 64usize, 64usize),
            (-1, 64, 64),
            (1, 65, 64),
            (-1, 64, 63),
        ];
        for &isa in &Isa::available() {
            for round in 0..12 {
                for k in 0..shapes.len() {
                    let (sign, ny, len) = shapes[(k * (round % 3 + 1) + round) % shapes.len()];
                    check_polar_line(isa, 3, round as i64, sign, ny, len);
                }
            }
            // Signs other than ±1 too.
            check_polar_line(isa, 6, 7, 0, 100, 100);
            check_polar_line(isa, 6, 7, 3, 100, 100);
            check_polar_line(isa, 4, 5, -1, (1 << 16) + 3, (1 << 16) + 3);
            check_polar_line(isa, 4, 5, 1, 1 << 16, 1 << 16);
        }
    }

    /// Checks sin_cos_line against fastmath::sin_cos on every instruction set, for the
    /// inputs `x` and for every offset and length of subslices of their first 40 (so that
    /// each input is seen in every vector lane and in the scalar remainder loops).
    fn check_sin_cos_line(x: &[f64]) {
        for &isa in &Isa::available() {
            let check = |x: &[f64]| {
                let mut s = vec![0.5; x.len()];
                let mut c = vec![0.5; x.len()];
                sin_cos_line_on(isa, x, &mut s, &mut c);
                for i in 0..x.len() {
                    let (ws, wc) = fastmath::sin_cos(x[i]);
                    assert!(
                        s[i].to_bits() == ws.to_bits() && c[i].to_bits() == wc.to_bits(),
                        "{isa:?}: sin_cos({:e}) gave ({:e}, {:e}) instead of ({ws:e}, {wc:e})",
                        x[i],
                        s[i],
                        c[i]
                    );
                }
            };
            check(x);
            let head = &x[..x.len().min(40)];
            for start in 0..head.len() {
                for end in start..=head.len() {
                    check(&head[start..end]);
                }
            }
        }
    }

    #[test]
    fn sin_cos_line_equals_sin_cos_bit_for_bit() {
        let mut rng = Rng(1);
        // Uniform arguments, as the phases φ − ωt are.
        let x: Vec<f64> = (0..200_000).map(|_| rng.uniform(-1e4, 1e4)).collect();
        check_sin_cos_line(&x);
        // Small and tiny arguments of both signs, ±0 and subnormals.
        let mut x: Vec<f64> = (0..20_000)
            .map(|_| {
                let v = f64::from_bits(rng.next_u64() & 0x3FFF_FFFF_FFFF_FFFF) * 0.25;
                if rng.next_u64() & 1 == 0 { v } else { -v }
            })
            .collect();
        x.extend([
            0.0,
            -0.0,
            5e-324,
            -5e-324,
            1e-300,
            -1e-300,
            2.2e-308,
            f64::MIN_POSITIVE,
        ]);
        check_sin_cos_line(&x);
        // Exact multiples of π/2 (as doubles) and their neighbours, up to the Cody–Waite
        // limit, where the quadrant rounding and r ≈ 0 are delicate.
        let mut x = Vec::new();
        for k in (-70_000i64..70_000).chain((-63_661_977i64..63_661_977).step_by(9_973)) {
            let v = k as f64 * FRAC_PI_2;
            for d in [-1i64, 0, 1] {
                x.push(f64::from_bits((v.to_bits() as i64 + d) as u64));
            }
            x.push((k as f64 + 0.5) * FRAC_PI_2);
        }
        check_sin_cos_line(&x);
        // Around the Cody–Waite limit, beyond it (the scalar fallback), and specials,
        // mixed with ordinary lanes.
        let limit = fastmath::SIN_COS_CW_LIMIT;
        let specials = [
            limit,
            -limit,
            f64::from_bits(limit.to_bits() - 1),
            -f64::from_bits(limit.to_bits() - 1),
            f64::from_bits(limit.to_bits() + 1),
            1e9,
            -1e9,
            1e22,
            1e300,
            -1e300,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            f64::from_bits(0x7FF0_0000_0000_0001), // signalling NaN
        ];
        let mut x = Vec::new();
        for (i, &v) in specials.iter().enumerate() {
            x.push(v);
            x.extend((0..i % 5).map(|j| j as f64 * 0.7 - 1.0));
        }
        check_sin_cos_line(&x);
        let huge: Vec<f64> = (0..1000)
            .map(|_| 10f64.powf(rng.uniform(8.0, 308.0)))
            .collect();
        check_sin_cos_line(&huge);
        // A line that is all specials.
        check_sin_cos_line(&specials);
        check_sin_cos_line(&[]);
        // The public entry point.
        let x: Vec<f64> = (0..4096).map(|_| rng.uniform(0.0, 3000.0)).collect();
        let (mut s, mut c) = (vec![0.0; 4096], vec![0.0; 4096]);
        sin_cos_line(&x, &mut s, &mut c);
        for i in 0..4096 {
            let (ws, wc) = fastmath::sin_cos(x[i]);
            assert_eq!(
                (s[i].to_bits(), c[i].to_bits()),
                (ws.to_bits(), wc.to_bits())
            );
        }
    }

    #[test]
    #[should_panic(expected = "differ in length")]
    fn polar_line_rejects_mismatched_slices() {
        polar_line(1, 2, 1, 8, &mut [0.0; 8], &mut [0.0; 7]);
    }

    #[test]
    #[should_panic(expected = "differ in length")]
    fn sin_cos_line_rejects_mismatched_slices() {
        sin_cos_line(&[0.0; 8], &mut [0.0; 8], &mut [0.0; 7]);
    }

    /// Prints ns per element at ny = 4096: the scalar loops (gaussian_polar and sin_cos one
    /// by one) vs the line functions, and each compiled path; medians of interleaved runs.
    ///
    /// `cargo test --release --lib lines -- --ignored --nocapture`
    #[test]
    #[ignore]
    fn speed() {
        use std::hint::black_box;
        use std::time::Instant;
        const NY: usize = 4096;
        const LINES: usize = 32;
        const ROUNDS: usize = 41;
        /// A case fills the two output lines for kx line `n`.
        type Case<'a> = (String, Box<dyn Fn(i64, &mut [f64], &mut [f64]) + 'a>);

        let mut rng = Rng(8);
        let x: Vec<f64> = (0..NY).map(|_| rng.uniform(0.0, 3000.0)).collect();
        let x = &x;
        let isas = Isa::available();

        let mut polar: Vec<Case> = vec![
            (
                "scalar gaussian_polar".into(),
                Box::new(|n, r, phi| {
                    let seed = black_box(9u64);
                    for i in 0..NY {
                        (r[i], phi[i]) = rng::gaussian_polar(seed, -n, -signed_index(i, NY));
                    }
                }),
            ),
            (
                "polar_line".into(),
                Box::new(|n, r, phi| polar_line(black_box(9), n, -1, NY, r, phi)),
            ),
        ];
        let mut sincos: Vec<Case> = vec![
            (
                "scalar sin_cos".into(),
                Box::new(|_, s, c| {
                    let x = black_box(x);
                    for i in 0..NY {
                        (s[i], c[i]) = fastmath::sin_cos(x[i]);
                    }
                }),
            ),
            (
                "sin_cos_line".into(),
                Box::new(|_, s, c| sin_cos_line(black_box(x), s, c)),
            ),
        ];
        for &isa in &isas {
            polar.push((
                format!("  on {isa:?}"),
                Box::new(move |n, r, phi| polar_line_on(isa, black_box(9), n, -1, NY, r, phi)),
            ));
            sincos.push((
                format!("  on {isa:?}"),
                Box::new(move |_, s, c| sin_cos_line_on(isa, black_box(x), s, c)),
            ));
        }

        let (mut a, mut b) = (vec![0.0; NY], vec![0.0; NY]);
        for (title, cases) in [("Gaussian draws", polar), ("sin_cos", sincos)] {
            let mut times = vec![Vec::with_capacity(ROUNDS); cases.len()];
            for _ in 0..ROUNDS {
                for (case, t) in cases.iter().zip(&mut times) {
                    let start = Instant::now();
                    for n in 0..LINES as i64 {
                        case.1(n, &mut a, &mut b);
                        black_box((&mut a, &mut b));
                    }
                    t.push(start.elapsed().as_secs_f64() * 1e9 / (LINES * NY) as f64);
                }
            }
            println!(
                "{title}, ns per element at ny = {NY} (medians of {ROUNDS} interleaved runs):"
            );
            let mut base = 0.0;
            for (case, mut t) in cases.iter().zip(times) {
                t.sort_by(f64::total_cmp);
                let median = t[t.len() / 2];
                if base == 0.0 {
                    base = median;
                }
                println!(
                    "  {:<24} {median:6.2} ns  (min {:6.2})  {:5.2}x",
                    case.0,
                    t[0],
                    base / median
                );
            }
        }
    }
}

/// e[i] = fastmath::exp(x[i]) bit for bit: a branch-free pass that vectorizes, then the
/// scalar function for lanes outside its fast range.
pub fn exp_line(x: &[f64], e: &mut [f64]) {
    assert_eq!(x.len(), e.len(), "exp_line: x and e differ in length");
    let special = exp_run(x, e);
    if special {
        for (&x, e) in x.iter().zip(e.iter_mut()) {
            if fastmath::exp_is_special(x) {
                *e = fastmath::exp(x);
            }
        }
    }
}

multiversion! {
    /// The branch-free pass of [`exp_line`]; true if a lane needs the scalar function.
    fn exp_run(x: &[f64], e: &mut [f64]) -> bool {
        let mut special = false;
        for (&x, e) in x.iter().zip(e.iter_mut()) {
            special |= fastmath::exp_is_special(x);
            *e = fastmath::exp_fast(x);
        }
        special
    }
}

/// o[i] = fastmath::ln(x[i]) bit for bit: a branch-free pass that vectorizes, then the
/// scalar function for lanes that are not positive, normal and finite.
pub fn ln_line(x: &[f64], o: &mut [f64]) {
    assert_eq!(x.len(), o.len(), "ln_line: x and o differ in length");
    let special = ln_run(x, o);
    if special {
        for (&x, o) in x.iter().zip(o.iter_mut()) {
            if fastmath::ln_is_special(x) {
                *o = fastmath::ln(x);
            }
        }
    }
}

multiversion! {
    /// The branch-free pass of [`ln_line`]; true if a lane needs the scalar function.
    fn ln_run(x: &[f64], o: &mut [f64]) -> bool {
        let mut special = false;
        for (&x, o) in x.iter().zip(o.iter_mut()) {
            special |= fastmath::ln_is_special(x);
            *o = fastmath::ln_positive_normal(x);
        }
        special
    }
}

#[cfg(test)]
mod exp_line_tests {
    use super::*;

    #[test]
    fn exp_line_equals_the_scalar_exp_bit_for_bit() {
        let mut x: Vec<f64> = (0..5000).map(|i| -800.0 + i as f64 * 0.3317).collect();
        x.extend([
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            709.0,
            -745.0,
            -1e300,
            1e-300,
        ]);
        let mut e = vec![0.0; x.len()];
        exp_line(&x, &mut e);
        for (i, (&x, &e)) in x.iter().zip(&e).enumerate() {
            let want = fastmath::exp(x);
            assert!(
                e.to_bits() == want.to_bits() || (e.is_nan() && want.is_nan()),
                "lane {i}: exp({x}) = {e} vs {want}"
            );
        }
    }

    #[test]
    fn ln_line_equals_the_scalar_ln_bit_for_bit() {
        let mut x: Vec<f64> = (0..5000).map(|i| 1.37f64.powi(i - 2500)).collect();
        x.extend((0..2000).map(|i| 0.5 + i as f64 * 1e-3));
        x.extend([
            0.0,
            -0.0,
            -1.0,
            f64::MIN_POSITIVE,
            f64::MIN_POSITIVE / 3.0,
            f64::MAX,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1.0,
        ]);
        let mut o = vec![0.0; x.len()];
        ln_line(&x, &mut o);
        for (i, (&x, &o)) in x.iter().zip(&o).enumerate() {
            let want = fastmath::ln(x);
            assert!(
                o.to_bits() == want.to_bits() || (o.is_nan() && want.is_nan()),
                "lane {i}: ln({x}) = {o} vs {want}"
            );
        }
    }
}
