//! 8-bit RGB PNG of a rendered image (plots), written through a staged file.

use super::Staged;
use crate::error::Error;

/// Encodes an RGB buffer (`w`·`h`·3 bytes, rows top to bottom) into the staged file.
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
