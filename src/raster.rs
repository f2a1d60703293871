//! Images read through `image`: any common raster (PNG, JPEG, TIFF, OpenEXR, BMP, WebP)
//! as one value per pixel, with the size its header declares checked against the
//! memory available before any pixel is decoded, and the decoder bounded by
//! `image::Limits`. Used by α maps (`field::weight`) and by the height-map readers (`io`).

use crate::limits::{available_memory, check_image_size};

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
    let (values, bits): (Vec<f32>, _) = match &img {
        D::ImageLuma8(i) => (gray_values(i, 255.0), Some(8)),
        D::ImageLumaA8(i) => (gray_values(i, 255.0), Some(8)),
        D::ImageLuma16(i) => (gray_values(i, 65535.0), Some(16)),
        D::ImageLumaA16(i) => (gray_values(i, 65535.0), Some(16)),
        D::ImageRgb8(i) => (gray_values(i, 255.0), Some(8)),
        D::ImageRgba8(i) => (gray_values(i, 255.0), Some(8)),
        D::ImageRgb16(i) => (gray_values(i, 65535.0), Some(16)),
        D::ImageRgba16(i) => (gray_values(i, 65535.0), Some(16)),
        other => (
            other
                .to_rgb32f()
                .pixels()
                .map(|p| luma([p[0], p[1], p[2]]))
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

/// Rec. 709 luma of linear R, G, B.
fn luma([r, g, b]: [f32; 3]) -> f32 {
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

/// One value per pixel of an integer image, as a fraction of `max`: the gray channel, or
/// the luma of R, G, B (alpha ignored).
fn gray_values<P>(img: &image::ImageBuffer<P, Vec<P::Subpixel>>, max: f32) -> Vec<f32>
where
    P: image::Pixel,
    P::Subpixel: Into<f32>,
{
    img.pixels()
        .map(|p| {
            let c = p.channels();
            let v = |k: usize| c[k].into() / max;
            if c.len() >= 3 {
                luma([v(0), v(1), v(2)])
            } else {
                v(0)
            }
        })
        .collect()
}
