//! Limits of a run: the memory available, checked before any work; the size an image
//! declares, checked before its pixels are read; and the finiteness of what was
//! computed, checked before anything is written.
//!
//! Memory: each command estimates its peak (see `pipeline::memory::Footprint`) and refuses
//! when that exceeds the memory available (`MemAvailable` of `/proc/meminfo`), unless
//! `--force` is given. The environment variable `SEASYNTH_MEMORY_AVAILABLE` (bytes, or
//! with a K/M/G/T suffix, powers of 1024) replaces the figure of `/proc/meminfo`, for
//! tests and for machines whose limit is not the system's (a container's memory limit).

use crate::error::Error;
use crate::grid::Stats;
use crate::units::human_bytes;

/// Samples of one field, at most (2³⁰: 4 GiB of f32 heights).
pub const MAX_SAMPLES: usize = 1 << 30;

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

/// Checks the size an image file's header declares before its pixels are allocated:
/// at least one pixel, at most [`MAX_SAMPLES`], and
/// `bytes_per_pixel` for each (plus what the analysis holds) within the available memory. The message suits
/// `FILE: message`.
pub fn check_image_size(width: u64, height: u64, bytes_per_pixel: u64) -> Result<(), String> {
    let max = MAX_SAMPLES as u64;
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
