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

/// The image formats read through `image`, for messages.
pub const IMAGE_FORMATS: &str = "PNG, JPEG, TIFF, OpenEXR, BMP or WebP";

/// An image read through `image`, and how to read its samples.
pub struct Raster {
    pub width: usize,
    pub height: usize,
    /// One value per pixel, row by row: the gray value, or the Rec. 709 luma of a color
    /// image (0.2126 R + 0.7152 G + 0.0722 B); integer samples as a fraction of their
    /// largest value (in [0, 1]), float samples as stored.
    pub values: Vec<f32>,
    /// Bits of an integer sample (8 or 16), or None for float samples.
    pub integer_bits: Option<u32>,
    pub format: image::ImageFormat,
}

/// A format's usual name (`PNG`, `OpenEXR`).
pub fn format_name(f: image::ImageFormat) -> &'static str {
    use image::ImageFormat as F;
    match f {
        F::Png => "PNG",
        F::Jpeg => "JPEG",
        F::Tiff => "TIFF",
        F::OpenExr => "OpenEXR",
        F::Bmp => "BMP",
        F::WebP => "WebP",
        F::Gif => "GIF",
        _ => "other",
    }
}

/// Refuses a file whose name's extension says another image format than its content
/// (`format`, told by its first bytes); a name that says no image format is accepted.
pub fn check_extension(path: &std::path::Path, format: image::ImageFormat) -> Result<(), String> {
    match path
        .extension()
        .and_then(image::ImageFormat::from_extension)
    {
        Some(named) if named != format => Err(format!(
            "is a {} image but its name says {}: rename it to end in .{}",
            format_name(format),
            format_name(named),
            format.extensions_str().first().copied().unwrap_or("?")
        )),
        _ => Ok(()),
    }
}

/// Reads the image at `path` through `image`, its format told by its first bytes: a name
/// whose extension says another image format is refused, the size its header declares is
/// checked ([`check_image_size`]) before any pixel is decoded, and the decoder's
/// allocations are bounded (`image::Limits`: the memory available, at most 16 GiB). The
/// message suits `FILE: message`.
pub fn read_raster(path: &std::path::Path) -> Result<Raster, String> {
    let open = || -> Result<image::ImageReader<std::io::BufReader<std::fs::File>>, String> {
        let file = std::fs::File::open(path).map_err(|e| format!("cannot read: {e}"))?;
        Ok(image::ImageReader::new(std::io::BufReader::new(file)))
    };
    // The format by the first bytes only (`image` would fall back on the name).
    let mut head = Vec::with_capacity(16);
    std::io::Read::read_to_end(
        &mut std::io::Read::take(
            std::fs::File::open(path).map_err(|e| format!("cannot read: {e}"))?,
            16,
        ),
        &mut head,
    )
    .map_err(|e| format!("cannot read: {e}"))?;
    let Some(format) = image::guess_format(&head).ok().filter(|f| {
        use image::ImageFormat as F;
        matches!(
            f,
            F::Png | F::Jpeg | F::Tiff | F::OpenExr | F::Bmp | F::WebP
        )
    }) else {
        return Err(format!(
            "is not an image of a format read here ({IMAGE_FORMATS}, told by its first bytes)"
        ));
    };
    check_extension(path, format)?;
    let mut reader = open()?;
    reader.set_format(format);
    let (w, h) = reader
        .into_dimensions()
        .map_err(|e| format!("not a readable {} image: {e}", format_name(format)))?;
    // Four float channels per pixel at most.
    check_image_size(w as u64, h as u64, 16)?;
    let mut limits = image::Limits::default();
    let available = available_memory().ok().flatten().unwrap_or(u64::MAX);
    limits.max_alloc = Some(available.min(16 << 30));
    let mut reader = open()?;
    reader.set_format(format);
    reader.limits(limits);
    let img = reader
        .decode()
        .map_err(|e| format!("not a readable {} image: {e}", format_name(format)))?;
    let (width, height) = (img.width() as usize, img.height() as usize);
    use image::DynamicImage as D;
    let luma = |r: f32, g: f32, b: f32| 0.2126 * r + 0.7152 * g + 0.0722 * b;
    let (values, bits): (Vec<f32>, _) = match &img {
        D::ImageLuma8(i) => (i.pixels().map(|p| p[0] as f32 / 255.0).collect(), Some(8)),
        D::ImageLumaA8(i) => (i.pixels().map(|p| p[0] as f32 / 255.0).collect(), Some(8)),
        D::ImageLuma16(i) => (
            i.pixels().map(|p| p[0] as f32 / 65535.0).collect(),
            Some(16),
        ),
        D::ImageLumaA16(i) => (
            i.pixels().map(|p| p[0] as f32 / 65535.0).collect(),
            Some(16),
        ),
        D::ImageRgb8(i) => (
            i.pixels()
                .map(|p| {
                    luma(
                        p[0] as f32 / 255.0,
                        p[1] as f32 / 255.0,
                        p[2] as f32 / 255.0,
                    )
                })
                .collect(),
            Some(8),
        ),
        D::ImageRgba8(i) => (
            i.pixels()
                .map(|p| {
                    luma(
                        p[0] as f32 / 255.0,
                        p[1] as f32 / 255.0,
                        p[2] as f32 / 255.0,
                    )
                })
                .collect(),
            Some(8),
        ),
        D::ImageRgb16(i) => (
            i.pixels()
                .map(|p| {
                    luma(
                        p[0] as f32 / 65535.0,
                        p[1] as f32 / 65535.0,
                        p[2] as f32 / 65535.0,
                    )
                })
                .collect(),
            Some(16),
        ),
        D::ImageRgba16(i) => (
            i.pixels()
                .map(|p| {
                    luma(
                        p[0] as f32 / 65535.0,
                        p[1] as f32 / 65535.0,
                        p[2] as f32 / 65535.0,
                    )
                })
                .collect(),
            Some(16),
        ),
        other => (
            other
                .to_rgb32f()
                .pixels()
                .map(|p| luma(p[0], p[1], p[2]))
                .collect(),
            None,
        ),
    };
    Ok(Raster {
        width,
        height,
        values,
        integer_bits: bits,
        format,
    })
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
