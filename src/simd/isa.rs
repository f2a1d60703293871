//! The instruction sets the kernels are compiled for, and which one this processor runs.

use std::sync::OnceLock;

/// The instruction sets the kernels are compiled for (see [`crate::simd::multiversion`]).
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
    /// The best instruction set of this processor, detected on the first call of the run
    /// (later calls read the stored answer). Plans call this when they are built and
    /// hand the value to their kernels.
    #[inline]
    pub(crate) fn detect() -> Isa {
        static DETECTED: OnceLock<Isa> = OnceLock::new();
        *DETECTED.get_or_init(Isa::best)
    }

    /// The best instruction set of this processor (AVX-512 only if
    /// `SEASYNTH_NO_AVX512` is not set).
    fn best() -> Isa {
        #[cfg(target_arch = "x86_64")]
        {
            if Self::has_avx512() {
                return Isa::Avx512;
            }
            if std::is_x86_feature_detected!("avx2") {
                return Isa::Avx2;
            }
        }
        Isa::Plain
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
