//! Rounding to the nearest integer, halves away from zero, of values known to be
//! non-negative and below 2^31: the same result as `round()` without its library call
//! (x86-64's baseline has no rounding instruction, so `f64::round` and `f32::round` are
//! calls to libm's `round`/`roundf`, one per sample in the map quantizers).
//!
//! The integer part t = ⌊x⌋ comes from the truncating conversion, and x − t is exact for
//! x ≥ 0 (it keeps x's own low bits), so comparing it with ½ decides the rounding
//! exactly, where ⌊x + ½⌋ would not (x = ½ − 2^−54 gives x + ½ = 1 after rounding).
//! NaN gives 0, as `NaN.round() as u32` does.

/// round(x) for 0 ≤ x < 2^31 (NaN → 0).
#[inline(always)]
pub fn round_nonneg_f64(x: f64) -> u32 {
    let t = x as u32;
    t + u32::from(x - t as f64 >= 0.5)
}

/// round(x) for 0 ≤ x < 2^31 (NaN → 0).
#[inline(always)]
pub fn round_nonneg_f32(x: f32) -> u32 {
    let t = x as u32;
    t + u32::from(x - t as f32 >= 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_round_at_halves_neighbours_and_sweeps() {
        let mut xs: Vec<f64> = vec![0.0, 0.5, 1.5, 2.5, 65534.5, 65535.0, 254.5, 255.0];
        for k in 0..=65536u32 {
            let h = k as f64 + 0.5;
            xs.extend([h, h.next_down(), h.next_up(), k as f64]);
        }
        xs.extend([0.5f64.next_down(), f64::MIN_POSITIVE, 1e-300, 5e-324]);
        for i in 0..200_000 {
            xs.push(i as f64 * 0.327_68 + 1e-9 * i as f64);
        }
        for &x in &xs {
            assert_eq!(round_nonneg_f64(x), x.round() as u32, "f64 {x:e}");
            let y = x as f32;
            if y < 2.0e9 {
                assert_eq!(round_nonneg_f32(y), y.round() as u32, "f32 {y:e}");
            }
        }
        for y in [
            0.5f32.next_down(),
            0.5,
            1.5f32.next_down(),
            f32::MIN_POSITIVE,
            1e-45,
        ] {
            assert_eq!(round_nonneg_f32(y), y.round() as u32, "f32 {y:e}");
        }
        assert_eq!(round_nonneg_f64(f64::NAN), 0);
        assert_eq!(round_nonneg_f32(f32::NAN), 0);
    }
}
