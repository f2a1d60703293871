//! The memory a run will need: bytes per grid sample of each method and output, checked
//! against what is available (`limits::check_memory`) before any work starts.

use crate::config::Params;
use crate::field::dynamics::Extras;

/// Peak memory of one field's synthesis and export, as bytes per grid sample plus a
/// fixed part: the method's own bytes per sample (`field::HeightMethod::bytes_per_sample`)
/// and those of choppy waves, derived fields and outputs. The figures are measured peaks
/// (maximum resident set, `/usr/bin/time -v`) of `generate` between 2048² and 4096², plus
/// about a quarter: 8 bytes a sample for the height field and its transform, 12 for
/// `hybrid`, 8 more for choppy waves; see the README's Guarantees section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    pub per_sample: u64,
    pub fixed: u64,
}

/// Bytes that do not grow with the grid (code, thread stacks, writer buffers).
const FIXED_BYTES: u64 = 64 << 20;

/// Bytes a sample of one derived 32-bit field (a slope, a displacement, the Jacobian), or
/// of one map or mesh written from them.
pub const DERIVED_BYTES: u64 = 8;

impl Footprint {
    /// One field of `params` with its height outputs and the derived fields `extras`.
    pub fn of_field(params: &Params, extras: Extras) -> Self {
        let base = crate::field::method_for(params).bytes_per_sample();
        let choppy = if params.motion.choppiness != 0.0 {
            10
        } else {
            0
        };
        let derived =
            2 * extras.slopes as u64 + 2 * extras.displacement as u64 + extras.jacobian as u64;
        Self {
            per_sample: base + choppy + DERIVED_BYTES * derived,
            fixed: FIXED_BYTES,
        }
    }

    /// This footprint with `outputs` more per-sample outputs (maps, meshes) alive at once.
    pub fn with_outputs(self, outputs: u64) -> Self {
        Self {
            per_sample: self.per_sample + DERIVED_BYTES * outputs,
            ..self
        }
    }

    /// Bytes for `samples` grid samples, `copies` fields at once (parallel frames).
    pub fn bytes(&self, samples: u64, copies: u64) -> u64 {
        self.per_sample
            .saturating_mul(samples)
            .saturating_mul(copies.max(1))
            .saturating_add(self.fixed)
    }
}

/// Makes the allocator keep freed memory for reuse instead of returning it to the system
/// (glibc: no `mmap` for large blocks, no trimming of the heap). Every frame allocates the
/// same buffers as the one before it; kept, they are reused as they are, where fresh
/// pages cost a page fault per 4 KiB (a quarter of a 1024² frame with maps) and their
/// release a `munmap`. The peak memory is that of the frames running at once; it is kept
/// until the process ends. A no-op on other platforms.
pub fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        // SAFETY: mallopt only sets the allocator's tuning parameters (under its lock).
        let (no_mmap, no_trim) = unsafe {
            (
                libc::mallopt(libc::M_MMAP_MAX, 0),
                libc::mallopt(libc::M_TRIM_THRESHOLD, libc::c_int::MAX),
            )
        };
        // 0 means the setting was refused: the frames are then only slower.
        debug_assert!(no_mmap == 1 && no_trim == 1, "mallopt refused a setting");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn footprints_grow_with_samples_and_copies_and_saturate() {
        let f = Footprint {
            per_sample: 10,
            fixed: 5,
        };
        assert_eq!(f.bytes(100, 1), 1005);
        assert_eq!(f.bytes(100, 3), 3005);
        assert_eq!(f.bytes(u64::MAX, 2), u64::MAX);
    }
}
