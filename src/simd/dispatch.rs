//! [`multiversion!`]: one kernel body, compiled once per instruction set.

/// Defines `fn NAME(isa: Isa, args) -> R` whose body is compiled for the target's
/// baseline and (on x86-64) for AVX2 and for AVX-512; `isa` picks the copy. For
/// whole-line loops that the compiler vectorizes. The body must give the same bits on
/// every copy (IEEE basic operations and `fastmath`'s cores only, no fused multiply–add;
/// Rust never contracts a·b + c into one).
/// Callers pass the instruction set their plan chose once (`Isa::detect` when the plan is
/// built).
macro_rules! multiversion {
    // `fn name(isa: Isa, …)`: the caller passes the instruction set of its plan.
    (@on $(#[$meta:meta])* $vis:vis fn $name:ident($isa:ident : Isa, $($arg:ident : $ty:ty),* $(,)?) $(-> $ret:ty)? $body:block) => {
        $(#[$meta])*
        $vis fn $name($isa: $crate::simd::Isa, $($arg: $ty),*) $(-> $ret)? {
            $crate::simd::multiversion!(@dispatch $isa, ($($arg: $ty),*) $(-> $ret)? $body)
        }
    };
    // The copies of the body, and the choice among them.
    (@dispatch $isa:expr, ($($arg:ident : $ty:ty),*) $(-> $ret:ty)? $body:block) => {{
        #[inline(always)]
        fn mv_body($($arg: $ty),*) $(-> $ret)? $body
        #[inline(never)]
        fn mv_plain($($arg: $ty),*) $(-> $ret)? {
            mv_body($($arg),*)
        }
        /// # Safety
        /// The processor must have AVX2.
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2")]
        #[inline(never)]
        unsafe fn mv_avx2($($arg: $ty),*) $(-> $ret)? {
            mv_body($($arg),*)
        }
        /// # Safety
        /// The processor must have AVX-512 F, DQ and VL.
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2,avx512f,avx512dq,avx512vl")]
        #[inline(never)]
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
    }};
}
pub(crate) use multiversion;
