//! Portable elementary functions: [`exp`], [`ln`] and [`sin_cos`], and a single-precision
//! base-2 logarithm and power of two for the directional spectra's grid values
//! (`log2_f32`, `exp2_parts_f32`, `scale_f64`).
//!
//! # Why
//!
//! Spectrum synthesis evaluates a Box–Muller pair (`ln`, `sqrt`, `sin_cos`), a Phillips
//! spectrum (`exp`) and a time phase (`sin_cos`) for every wavevector, some 17 million
//! of them at 4096². The system libm's results differ between platforms and libm versions
//! (and `f64::sin_cos` is two calls), so height maps were not bit-reproducible across
//! machines.
//!
//! The functions here use only IEEE 754 basic operations (`+ − ×`, comparisons) and bit
//! manipulation of `f64`s: no division, no fused multiply–add, no libm, no tables beyond a
//! few dozen constants. Rust does not contract `a * b + c` into an FMA, so every result is
//! bit-identical on every target with IEEE binary64 arithmetic (all 64-bit targets, and
//! x86 with SSE2; not x87 extended-precision builds), whatever the compiler version or
//! optimisation level. Hot paths have no data-dependent branches (one predictable range
//! check each), which keeps them fast on random input.
//!
//! # Algorithms and accuracy
//!
//! * [`exp`]: `k = round(32x/ln2)` (by adding 1.5·2^52), `a = x − k·hi` with `hi` = ln2/32
//!   to 36 bits (so `k·hi` and the difference are exact) and `lo` = `k·(ln2/32 − hi)`,
//!   `|lo| < 2e-9`; then `e^x = 2^(k>>5) · 2^((k&31)/32) · (1 − lo) · e^a` with `2^(j/32)`
//!   from a 32-entry table and `e^a − 1` a degree-6 polynomial (`|a| ≤ ln2/64`, Chebyshev
//!   fit, Estrin's scheme). For `|x| < 690` the power of two is added to the exponent bits;
//!   beyond, a cold path clamps `x` and applies it as two power-of-two factors, so that
//!   overflow and gradual underflow come out right. Relative error ≈ 1 ulp (sweeps: max 2.2e-16).
//! * [`ln`]: `x = 2^k·z`, `z ∈ [0.703125, 1.40625)` by integer operations on the bits;
//!   `c` = `z` rounded to 4 mantissa bits, one of 16 centres (`c = 1` for z near 1, so
//!   there is no cancellation there); `ln x = k·ln2 + ln c + ln(1 + r)` with
//!   `r = (z − c)·(1/c)` (`z − c` exact, `|r| ≤ 1/32`), `(1/c, ln c)` from a 16-entry table
//!   and `ln(1 + r) = r + r²·Q(r)`, `Q` of degree 7 (Chebyshev fit, Estrin's scheme).
//!   Subnormal inputs are scaled by 2^54 on a cold path. Relative error ≤ 2 ulp
//!   (sweeps: max 4.4e-16).
//! * [`sin_cos`]: quadrant `k = round(x·2/π)` and `r = x − k·π/2` by Cody–Waite reduction
//!   with a 3-part `π/2` (27 + 27 + 53 bits, so `k·p1` and `k·p2` are exact for
//!   `|k| < 2^26`) for `|x| < 1e8`; beyond that, an exact Payne–Hanek reduction with 2/π to
//!   1150 bits (a 19-word table) on a cold path, so results stay accurate for every finite
//!   `x`. The kernels use fdlibm's `__kernel_sin`/`__kernel_cos` minimax coefficients
//!   (degrees 13 and 14 on `[−π/4, π/4]`), evaluated by Estrin's scheme; the quadrant is
//!   applied with bit masks. Absolute error ≈ 1e-16 for every finite `x` (sweeps: max
//!   2.2e-16).
//!
//! * `log2_f32`, `log2_unit_f32`, `exp2_parts_f32`, `exp2_f32`, `scale_f64`: log2 x
//!   from the bits and `u = (m − 1)/(m + 1)` (one division, a fitted cubic in u²), 2^t
//!   as `p·2^n` (a fitted degree-6 polynomial), and `p·2^n` as an exact double; ~1e-7
//!   relative, straight-line code for passes sixteen lanes wide.
//!
//! The accuracy targets are relative error ≤ 1e-14 for `exp`/`ln` and absolute error
//! ≤ 1e-15 (`|x| ≤ 16π`) and ≤ 1e-12 (`|x| ≤ 1e8`) for `sin_cos`; the tests check tighter
//! bounds against std.

/// `1.5·2^52`: adding and subtracting it rounds a double with `|v| < 2^51` to the nearest
/// integer (ties to even), and the integer sits in the low mantissa bits of the sum.
const ROUND_MAGIC: f64 = 6_755_399_441_055_744.0;
const SIGN_MASK: u64 = 0x8000_0000_0000_0000;

mod base2_f32;
mod exp;
mod ln;
mod powi;
mod round;
mod sin_cos;

pub(crate) use base2_f32::{exp2_f32, exp2_parts_f32, log2_f32, log2_unit_f32, scale_f64};
pub use exp::exp;
pub(crate) use exp::{exp_fast, exp_is_special};
pub use ln::ln;
pub(crate) use ln::{ln_is_special, ln_positive_normal};
pub use powi::powi;
pub use round::{round_clamped_f32, round_clamped_f64};
#[cfg(test)]
pub(crate) use sin_cos::SIN_COS_CW_LIMIT;
pub use sin_cos::sin_cos;
pub(crate) use sin_cos::{sin_cos_cody_waite, sin_cos_is_large};

#[cfg(test)]
mod tests;
