//! 8-bit RGB images (plots, maps, previews), written through a staged file: PNG, or for
//! previews JPEG (quality 90) or lossless WebP by the file name, through `image`.

use super::Staged;
use crate::error::Error;

/// Encodes an RGB buffer (`w`·`h`·3 bytes, rows top to bottom) into the staged file as
/// PNG with the png crate's default deflate and adaptive filter: the plots and previews,
/// whose flat areas it compresses ~10× better than [`write_map`] would.
pub fn write(staged: Staged, rgb: &[u8], (w, h): (u32, u32)) -> Result<(), Error> {
    staged.write_with(|out| {
        let mut enc = png::Encoder::new(out, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(std::io::Error::other)?;
        writer
            .write_image_data(rgb)
            .map_err(std::io::Error::other)?;
        writer.finish().map_err(std::io::Error::other)
    })
}

/// As [`write()`], through [`super::png_par`] (Up filter, pieces deflated in parallel):
/// the normal maps, a frame's worth of smooth samples written at the speed of the
/// synthesis, in files the size the default deflate gives them (+1.5 % at 1024²).
pub fn write_map(staged: Staged, rgb: &[u8], (w, h): (u32, u32)) -> Result<(), Error> {
    use super::png_par::{Layout, PngWriter};
    staged.write_with(|out| {
        let mut png = PngWriter::new(out, (w as usize, h as usize), Layout::Rgb8, &[])?;
        png.write_rows(rgb)?;
        png.finish().map(drop)
    })
}

/// JPEG quality of previews.
pub const JPEG_QUALITY: u8 = 90;

/// Encodes an RGB buffer as the staged file's name asks: `.jpg`/`.jpeg` (JPEG, quality
/// [`JPEG_QUALITY`]), `.webp` (lossless WebP), else PNG ([`write()`]).
pub fn write_by_name(staged: Staged, rgb: &[u8], (w, h): (u32, u32)) -> Result<(), Error> {
    let ext = staged
        .path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default()
        .to_ascii_lowercase();
    match ext.as_str() {
        "jpg" | "jpeg" => staged.write_with(|out| {
            image::codecs::jpeg::JpegEncoder::new_with_quality(out, JPEG_QUALITY)
                .encode(rgb, w, h, image::ExtendedColorType::Rgb8)
                .map_err(std::io::Error::other)
        }),
        "webp" => staged.write_with(|out| {
            image::codecs::webp::WebPEncoder::new_lossless(out)
                .encode(rgb, w, h, image::ExtendedColorType::Rgb8)
                .map_err(std::io::Error::other)
        }),
        _ => write(staged, rgb, (w, h)),
    }
}
