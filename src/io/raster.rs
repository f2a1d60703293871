//! Reading any image `image` decodes (PNG, JPEG, TIFF, OpenEXR, BMP, WebP) as heights:
//! gray, or color by its Rec. 709 luma; float samples in meters; integer samples (8 or
//! 16 bit) through `--height-range MIN:MAX` (the heights of the smallest and largest
//! value), else the mapping in a seasynth 16-bit PNG's text chunk, else refused.

use std::path::Path;

use super::{Heights, ImageKind, ReadOptions, input_error};
use crate::error::Error;

/// The kind of image a format is.
pub fn kind_of(format: image::ImageFormat) -> ImageKind {
    use image::ImageFormat as F;
    match format {
        F::Jpeg => ImageKind::Jpeg,
        F::Tiff => ImageKind::Tiff,
        F::OpenExr => ImageKind::Exr,
        F::Bmp => ImageKind::Bmp,
        F::WebP => ImageKind::Webp,
        _ => ImageKind::Png,
    }
}

/// The heights of `path` and the kind of image it is.
pub fn read(path: &Path, opts: &ReadOptions) -> Result<(Heights, ImageKind), Error> {
    let r = crate::raster::read_raster(path).map_err(|m| input_error(path, m))?;
    let kind = kind_of(r.format);
    let (data, step) = match r.integer_bits {
        None => (r.values, None),
        Some(bits) => {
            let (lo, hi) = match opts.height_range {
                Some(range) => range,
                None => match (bits, text_mapping(path)) {
                    (16, Some(m)) => m,
                    _ => {
                        return Err(input_error(
                            path,
                            format!(
                                "is a {} image of {bits}-bit integer samples with no height mapping of its own (a sidecar for a 16-bit gray PNG, or a seasynth text chunk): give --height-range MIN:MAX, the heights in meters of its darkest and brightest values",
                                crate::raster::format_name(r.format)
                            ),
                        ));
                    }
                },
            };
            let largest = ((1u64 << bits) - 1) as f64;
            (
                r.values
                    .iter()
                    .map(|&v| (lo + v as f64 * (hi - lo)) as f32)
                    .collect(),
                Some((hi - lo) / largest),
            )
        }
    };
    Ok((
        Heights {
            nx: r.width,
            ny: r.height,
            data,
            quantization_step_m: step,
        },
        kind,
    ))
}

/// The heights of 0 and 65535 from a seasynth 16-bit PNG's `Description` text chunk
/// (`… meters = MIN + value * STEP (0..65535) …`), if it has one.
pub fn text_mapping(path: &Path) -> Option<(f64, f64)> {
    let file = std::io::BufReader::new(std::fs::File::open(path).ok()?);
    let reader = png::Decoder::new(file).read_info().ok()?;
    reader
        .info()
        .uncompressed_latin1_text
        .iter()
        .filter(|t| t.keyword == "Description")
        .find_map(|t| parse_mapping(&t.text))
}

fn parse_mapping(text: &str) -> Option<(f64, f64)> {
    let rest = text
        .strip_prefix("seasynth height map: meters = ")?
        .split_once(" (0..65535)")?
        .0;
    let (min, step) = rest.split_once(" + value * ")?;
    let (min, step): (f64, f64) = (min.trim().parse().ok()?, step.trim().parse().ok()?);
    (min.is_finite() && step.is_finite() && step > 0.0).then_some((min, min + 65535.0 * step))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_text_chunk_gives_the_heights_of_0_and_65535() {
        let m = crate::export::HeightMapping {
            min_m: -1.5,
            max_m: 2.0,
        };
        let text = format!(
            "seasynth height map: meters = {} + value * {} (0..65535); row 0 is y = 0",
            m.min_m,
            m.step_m()
        );
        let (lo, hi) = parse_mapping(&text).unwrap();
        assert_eq!(lo, -1.5);
        assert!((hi - 2.0).abs() < 1e-12, "{hi}");
        assert!(parse_mapping("another tool's description").is_none());
    }
}
