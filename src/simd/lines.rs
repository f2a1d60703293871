//! Whole-line forms of `fastmath`'s sin_cos, exp and ln: a branch-free pass that
//! vectorizes, then the scalar function for the rare lanes outside its fast range.

use crate::fastmath;
use crate::simd::{Isa, multiversion};

/// `(s[i], c[i]) = fastmath::sin_cos(x[i])` for every `i`, bit for bit, for every `x`
/// (lanes with `|x| ≥ 1e8` or non-finite `x` are redone by the scalar function), on the
/// instruction set `isa`.
///
/// # Panics
/// If the slices differ in length.
pub(crate) fn sin_cos_line_on(isa: Isa, x: &[f64], s: &mut [f64], c: &mut [f64]) {
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

/// `e[i] = fastmath::exp(x[i])` bit for bit on the instruction set `isa`: a branch-free
/// pass that vectorizes, then the scalar function for lanes outside its fast range.
pub(crate) fn exp_line_on(isa: Isa, x: &[f64], e: &mut [f64]) {
    assert_eq!(x.len(), e.len(), "exp_line: x and e differ in length");
    let special = exp_run(isa, x, e);
    if special {
        for (&x, e) in x.iter().zip(e.iter_mut()) {
            if fastmath::exp_is_special(x) {
                *e = fastmath::exp(x);
            }
        }
    }
}

multiversion! {
    @on
    /// The branch-free pass of [`exp_line_on`]; true if a lane needs the scalar function.
    fn exp_run(isa: Isa, x: &[f64], e: &mut [f64]) -> bool {
        let mut special = false;
        for (&x, e) in x.iter().zip(e.iter_mut()) {
            special |= fastmath::exp_is_special(x);
            *e = fastmath::exp_fast(x);
        }
        special
    }
}
