//! Rounding to the nearest integer, halves away from zero, of a value clamped to 0..=hi:
//! round(clamp(x, 0, hi)) without the library call (x86-64's baseline has no rounding
//! instruction, so `f64::round` and `f32::round` are calls to libm's `round`/`roundf`, one
//! per sample in the map quantizers) and without the checks of a saturating conversion,
//! so a loop of them compiles to vector instructions.
//!
//! The clamp is `max(0)` then `min(hi)`, which takes NaN to 0 (as `NaN.round() as u32`
//! gives). The integer part t = ⌊v⌋ comes from the truncating conversion, and v − t is
//! exact for v ≥ 0 (it keeps v's own low bits), so comparing it with ½ decides the
//! rounding exactly, where ⌊v + ½⌋ would not (v = ½ − 2^−54 gives v + ½ = 1 after
//! rounding).

/// The largest `hi` taken: below 2^31, so every clamped value converts to an i32.
const HI_MAX_F64: f64 = 2_147_483_520.0;
const HI_MAX_F32: f32 = 2_147_483_520.0;

/// round(clamp(x, 0, hi)) for hi ≤ 2^31 − 128 (a larger or NaN `hi` is taken as that);
/// NaN → 0.
#[inline(always)]
pub fn round_clamped_f64(x: f64, hi: f64) -> u32 {
    // Not `clamp`: it keeps NaN, which must become 0 before the conversion.
    #[allow(clippy::manual_clamp)]
    let v = x.max(0.0).min(hi.min(HI_MAX_F64));
    // SAFETY: v is in 0..=HI_MAX_F64 (`max` of NaN and 0 is 0), so it truncates to an i32.
    let t: i32 = unsafe { v.to_int_unchecked() };
    (t + i32::from(v - t as f64 >= 0.5)) as u32
}

/// round(clamp(x, 0, hi)) for hi ≤ 2^31 − 128 (a larger or NaN `hi` is taken as that);
/// NaN → 0.
#[inline(always)]
pub fn round_clamped_f32(x: f32, hi: f32) -> u32 {
    #[allow(clippy::manual_clamp)]
    let v = x.max(0.0).min(hi.min(HI_MAX_F32));
    // SAFETY: as in `round_clamped_f64`.
    let t: i32 = unsafe { v.to_int_unchecked() };
    (t + i32::from(v - t as f32 >= 0.5)) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_the_library_round_of_the_clamped_value() {
        let mut xs: Vec<f64> = vec![0.0, -0.0, 0.5, 1.5, 2.5, 65534.5, 65535.0, 254.5, 255.0];
        for k in 0..=65536u32 {
            let h = k as f64 + 0.5;
            xs.extend([h, h.next_down(), h.next_up(), k as f64]);
        }
        xs.extend([0.5f64.next_down(), f64::MIN_POSITIVE, 1e-300, 5e-324]);
        xs.extend([-0.4, -0.5, -1.0, -1e300, 1e300, 3e9, f64::INFINITY]);
        xs.extend([f64::NEG_INFINITY, f64::NAN]);
        for i in 0..200_000 {
            xs.push(i as f64 * 0.327_68 + 1e-9 * i as f64);
        }
        let lib64 = |x: f64, hi: f64| {
            if x.is_nan() {
                0
            } else {
                x.clamp(0.0, hi).round() as u32
            }
        };
        let lib32 = |x: f32, hi: f32| {
            if x.is_nan() {
                0
            } else {
                x.clamp(0.0, hi).round() as u32
            }
        };
        for hi in [255.0, 65535.0, 1e9] {
            for &x in &xs {
                assert_eq!(round_clamped_f64(x, hi), lib64(x, hi), "f64 {x:e} ≤ {hi}");
                let y = x as f32;
                let hi = hi as f32;
                assert_eq!(round_clamped_f32(y, hi), lib32(y, hi), "f32 {y:e} ≤ {hi}");
            }
            for y in [
                0.5f32.next_down(),
                1.5f32.next_down(),
                f32::MIN_POSITIVE,
                1e-45,
            ] {
                assert_eq!(
                    round_clamped_f32(y, hi as f32),
                    lib32(y, hi as f32),
                    "f32 {y:e}"
                );
            }
        }
        // A NaN or too large bound is the largest one.
        assert_eq!(round_clamped_f64(1e12, f64::NAN), HI_MAX_F64 as u32);
        assert_eq!(round_clamped_f32(1e12, f32::INFINITY), HI_MAX_F32 as u32);
    }
}
