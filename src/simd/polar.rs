//! Gaussian draws of a whole kx line: the polar form (r, φ) of
//! [`rng::gaussian_polar`] for every ky of the line, bit for bit.

use crate::grid::signed_index;
use crate::rng;
use crate::simd::{Isa, multiversion};

/// On the instruction set `isa`, for `i` in `0..r.len()`: `(r[i], phi[i]) = rng::gaussian_polar(seed, sign·n, sign·m_i)`
/// with `m_i = fft::signed_index(i, ny)`, bit-identical to calling
/// [`rng::gaussian_polar`] one by one (the products `sign·n`, `sign·m_i` wrap).
///
/// (The whole-line case of [`polar_range_on`], which the field's lines call; kept for
/// the tests of the kernels against [`rng::gaussian_polar`].)
///
/// # Panics
/// If `r` and `phi` differ in length.
#[cfg(test)]
pub(crate) fn polar_line_on(
    isa: Isa,
    seed: u64,
    n: i64,
    sign: i64,
    ny: usize,
    r: &mut [f64],
    phi: &mut [f64],
) {
    assert_eq!(r.len(), phi.len(), "polar_line: r and phi differ in length");
    polar_range_on(isa, (seed, n, sign), ny, 0..r.len(), r, phi);
}

/// On the instruction set `isa`, for the elements `i` of `range` of a line of `ny`
/// (`r`, `phi` of its length, index i − range.start): `(r, phi) =
/// rng::gaussian_polar(seed, sign·n, sign·m_i)` with `m_i = fft::signed_index(i, ny)`,
/// bit-identical to calling [`rng::gaussian_polar`] one by one (the products wrap): the
/// words of the whole line, kept per thread, read at `range`.
///
/// # Panics
/// If `r` or `phi` differ in length from `range`.
pub(crate) fn polar_range_on(
    isa: Isa,
    (seed, n, sign): (u64, i64, i64),
    ny: usize,
    range: std::ops::Range<usize>,
    r: &mut [f64],
    phi: &mut [f64],
) {
    assert!(
        r.len() == range.len() && phi.len() == range.len(),
        "polar_range: r and phi differ in length from the range"
    );
    let prefix = rng::polar_prefix(seed, sign.wrapping_mul(n));
    with_words(sign, ny, range.end.max(ny), |words| {
        let words = &words[range];
        match isa {
            Isa::Plain => polar_run_fused(isa, prefix, words, r, phi),
            // SAFETY: Isa::Avx2 is only chosen when the processor has AVX2.
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => unsafe { super::avx2::polar_run(prefix, words, r, phi) },
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 => polar_run_fused(isa, prefix, words, r, phi),
        }
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
