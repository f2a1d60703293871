//! Guards around a run: the memory it will need, checked before any work, and the
//! finiteness of what it computed, checked before anything is written.
//!
//! Memory: each command estimates its peak as bytes per grid sample ([`Footprint`]) times
//! the samples, plus fixed buffers, and refuses when that exceeds the memory available
//! (`MemAvailable` of `/proc/meminfo`), unless `--force` is given. The environment
//! variable `SEASYNTH_MEMORY_AVAILABLE` (bytes, or with a K/M/G/T suffix, powers of 1024)
//! replaces the figure of `/proc/meminfo`, for tests and for machines whose limit is not
//! the system's (a container's memory limit).

use crate::config::{Method, Params};
use crate::error::Error;
use crate::field::dynamics::Extras;
use crate::grid::Stats;

/// The variable that replaces `MemAvailable` (see the module docs).
pub const MEMORY_ENV: &str = "SEASYNTH_MEMORY_AVAILABLE";

/// Parses a byte count: `123`, `64K`, `1.5G` (powers of 1024).
pub fn parse_bytes(s: &str) -> Option<u64> {
    let s = s.trim();
    let (num, mult) = match s.char_indices().last()? {
        (i, c) if c.is_ascii_alphabetic() => {
            let pow = match c.to_ascii_uppercase() {
                'K' => 1,
                'M' => 2,
                'G' => 3,
                'T' => 4,
                _ => return None,
            };
            (&s[..i], 1024f64.powi(pow))
        }
        _ => (s, 1.0),
    };
    let v: f64 = num.trim().parse().ok()?;
    (v.is_finite() && v >= 0.0).then_some((v * mult) as u64)
}

/// Memory available to this run, bytes: [`MEMORY_ENV`] if set, else `MemAvailable` from
/// `/proc/meminfo`; `None` when neither is known (no guard then).
pub fn available_memory() -> Result<Option<u64>, Error> {
    if let Ok(v) = std::env::var(MEMORY_ENV) {
        return parse_bytes(&v).map(Some).ok_or_else(|| {
            Error::Param(crate::error::ParamError {
                name: MEMORY_ENV.into(),
                allowed: "a number of bytes, optionally with K, M, G or T".into(),
                got: v,
            })
        });
    }
    Ok(meminfo_available())
}

fn meminfo_available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Peak memory of one field's synthesis and export, as bytes per grid sample plus a
/// fixed part. The figures are measured peaks (maximum resident set, `/usr/bin/time -v`)
/// of `generate` between 2048² and 4096², plus about a quarter: 8 bytes a sample for
/// the height field and its transform, 12 for `hybrid`, 8 more for choppy waves; see the
/// README's Guarantees section.
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
        // The per-method table: a new method is one more line.
        let base = match params.method {
            Method::Perlin | Method::Fft | Method::FilteredNoise => 10,
            // Held in memory only when not streamed (the field and its outputs).
            Method::Trochoid => 8,
            Method::Hybrid => 14,
        };
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

/// Refuses a run whose estimated peak `needed` bytes exceeds the available memory,
/// unless `force`. `what` names the run (`a 16384x16384 hybrid field`).
pub fn check_memory(needed: u64, what: &str, force: bool) -> Result<(), Error> {
    if force {
        return Ok(());
    }
    match available_memory()? {
        Some(available) if needed > available => Err(Error::Memory {
            what: what.to_string(),
            needed_bytes: needed,
            available_bytes: available,
        }),
        _ => Ok(()),
    }
}

/// Bytes in a short human form: `1.5 GiB`.
pub fn human_bytes(b: u64) -> String {
    let units = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = b as f64;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < units.len() {
        v /= 1024.0;
        u += 1;
    }
    if u == 0 {
        format!("{b} B")
    } else {
        format!("{v:.1} {}", units[u])
    }
}

/// Checks the size an image file's header declares before its pixels are allocated:
/// at least one pixel, at most [`MAX_SAMPLES`](crate::config::MAX_SAMPLES), and
/// `bytes_per_pixel` for each (plus what the analysis holds) within the available memory. The message suits
/// `FILE: message`.
pub fn check_image_size(width: u64, height: u64, bytes_per_pixel: u64) -> Result<(), String> {
    let max = crate::config::MAX_SAMPLES as u64;
    if width == 0 || height == 0 {
        return Err(format!(
            "the header declares {width}×{height} pixels: no samples"
        ));
    }
    let pixels = width.saturating_mul(height);
    if pixels > max {
        return Err(format!(
            "the header declares {width}×{height} pixels: at most {max} are read"
        ));
    }
    // The decoded samples, and what reading and analyzing them holds besides (about
    // 20 bytes a pixel: `analyze` of a 16384² TIFF peaks at 5.2 GB).
    let needed = pixels.saturating_mul(bytes_per_pixel + 20);
    match available_memory() {
        Ok(Some(available)) if needed > available => Err(format!(
            "the header declares {width}×{height} pixels, which need about {} of memory but {} is available",
            human_bytes(needed),
            human_bytes(available)
        )),
        _ => Ok(()),
    }
}

/// Refuses a field that is not finite (the statistics of any NaN or infinite sample are
/// not finite), before anything is written.
pub fn check_finite(stats: &Stats, what: &str) -> Result<(), Error> {
    let all = [stats.min_m, stats.max_m, stats.mean_m, stats.std_m];
    if all.iter().all(|v| v.is_finite()) {
        return Ok(());
    }
    Err(Error::NotFinite {
        what: what.to_string(),
        detail: format!(
            "min {} m, max {} m, mean {} m",
            stats.min_m, stats.max_m, stats.mean_m
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_counts_parse_with_and_without_suffixes() {
        assert_eq!(parse_bytes("123"), Some(123));
        assert_eq!(parse_bytes("64K"), Some(64 << 10));
        assert_eq!(parse_bytes("1.5g"), Some(3 << 29));
        assert_eq!(parse_bytes("2T"), Some(2 << 40));
        assert_eq!(parse_bytes("-1"), None);
        assert_eq!(parse_bytes("lots"), None);
        assert_eq!(parse_bytes("3Q"), None);
        assert_eq!(parse_bytes(""), None);
    }

    #[test]
    fn human_bytes_picks_the_largest_unit_below_the_value() {
        assert_eq!(human_bytes(512), "512 B");
        assert_eq!(human_bytes(3 << 29), "1.5 GiB");
        assert_eq!(human_bytes(u64::MAX), "16.0 EiB");
    }

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

    #[test]
    fn non_finite_statistics_are_refused_naming_the_field() {
        let mut s = Stats {
            min_m: -1.0,
            max_m: 1.0,
            mean_m: 0.0,
            std_m: 0.5,
            hs_m: 2.0,
        };
        assert!(check_finite(&s, "the field").is_ok());
        s.mean_m = f64::NAN;
        let e = check_finite(&s, "the field").unwrap_err().to_string();
        assert!(e.contains("the field") && e.contains("NaN"), "{e}");
    }
}
