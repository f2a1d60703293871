//! Lines of wavevectors in FFT order: ky[n − j] = −ky[j], so entries j and n − j share
//! k² and whatever depends on it alone, computed for the first n/2 + 1 entries and
//! mirrored.

use crate::simd::multiversion;

/// True if `ky` is in FFT order (ky[n − j] = −ky[j] for 0 < j < n/2), so that its entries
/// j ≥ n/2 + 1 repeat the k² of entries n − j.
pub(crate) fn fft_mirrored(ky: &[f64]) -> bool {
    let n = ky.len();
    n >= 2 && {
        let h = n.div_ceil(2);
        // (A fold without early exit, which vectorizes.)
        ky[1..h]
            .iter()
            .zip(ky[n + 1 - h..].iter().rev())
            .fold(true, |ok, (&a, &b)| ok & (b == -a))
    }
}

/// `dst[i] = src[len − 1 − i]`, in blocks of 16 (a load, a permutation and a store each).
#[inline(always)]
fn reverse_copy<T: Copy + Default>(src: &[T], dst: &mut [T]) {
    const B: usize = 16;
    let m = dst.len().min(src.len());
    let (src, dst) = (&src[..m], &mut dst[..m]);
    let mut blocks = dst.chunks_exact_mut(B);
    for (d, s) in (&mut blocks).zip(src.rchunks_exact(B)) {
        let mut a = [T::default(); B];
        a.copy_from_slice(s);
        a.reverse();
        d.copy_from_slice(&a);
    }
    let rest = m % B;
    let d = blocks.into_remainder();
    for k in 0..rest {
        d[k] = src[rest - 1 - k];
    }
}

multiversion! {
    @on
    /// `v[j] = v[n − j]` for j = h..n, n = v.len() (the mirrored half of a line in FFT
    /// order from its first h entries).
    pub(crate) fn mirror_f32_on(isa: Isa, v: &mut [f32], h: usize) {
        let (src, dst) = v.split_at_mut(h);
        let m = dst.len();
        reverse_copy::<f32>(&src[1..=m], dst);
    }
}

multiversion! {
    @on
    /// [`mirror_f32_on`] for doubles.
    pub(crate) fn mirror_f64_on(isa: Isa, v: &mut [f64], h: usize) {
        let (src, dst) = v.split_at_mut(h);
        let m = dst.len();
        reverse_copy::<f64>(&src[1..=m], dst);
    }
}
