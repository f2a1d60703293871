//! Instruction-set dispatch and the whole-line kernels of spectrum synthesis.
//!
//! The processor's best instruction set ([`Isa`]) is detected once per run
//! ([`Isa::detect`]); a plan (a spectrum model, a noise field) takes it when it is built
//! and passes it down to its kernels as a value. A kernel is written once, as a plain
//! branch-free loop over arrays, and [`multiversion!`] compiles it for the target's
//! baseline and (on x86-64) for AVX2 and AVX-512; the `Isa` value picks the copy. Code
//! written for one instruction set by hand lives in its own module (`avx2`).
//!
//! The line kernels ([`polar_line`], [`sin_cos_line`], [`exp_line`], [`ln_line`]) are
//! built from the always-inlined cores of [`crate::rng`] and [`crate::fastmath`] (the
//! range checks and special cases stay in the scalar functions: a line is checked once,
//! and rare lanes are redone by the scalar function), so the compiler vectorizes them.
//!
//! Why the bits are the same on every instruction set: vector IEEE `+ − × / √` round
//! exactly like their scalar forms, and the kernels perform the scalar functions'
//! operations in the same order, without fused multiply–add (Rust never contracts
//! `a * b + c` into one, whatever the instruction set offers); integer operations are
//! exact. The tests compare every path with the scalar functions bit for bit.

#[cfg(target_arch = "x86_64")]
mod avx2;
mod dispatch;
mod isa;
mod lines;
mod polar;

pub(crate) use dispatch::multiversion;
pub(crate) use isa::Isa;
pub(crate) use lines::{exp_line_on, sin_cos_line_on};
pub(crate) use polar::polar_range_on;

#[cfg(test)]
mod tests;
