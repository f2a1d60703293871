//! Integer powers of a double, inlined.

/// `x` to the integer power `n`, the same bits as [`f64::powi`] where it is a call
/// (binary powering, the reciprocal taken last for n < 0, as the runtime's `__powidf2`
/// computes it), but inlined: in a loop over many values the call and its spills cost
/// more than the few multiplications.
#[inline(always)]
pub fn powi(mut x: f64, n: i32) -> f64 {
    let mut e = n.unsigned_abs();
    let mut r = 1.0;
    loop {
        if e & 1 != 0 {
            r *= x;
        }
        e >>= 1;
        if e == 0 {
            break;
        }
        x *= x;
    }
    if n < 0 { 1.0 / r } else { r }
}
