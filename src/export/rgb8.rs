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

/// A drawing error as an I/O error (a failure while working: exit code 1).
pub fn draw_err<E: std::fmt::Display>(e: E) -> std::io::Error {
    std::io::Error::other(format!("cannot draw the plot: {e}"))
}

/// The legend box both plot commands draw: at `position`, 15-pt text on a
/// translucent white box with a gray border.
pub fn draw_legend<'a, DB, CT>(
    chart: &mut plotters::chart::ChartContext<'a, DB, CT>,
    position: plotters::chart::SeriesLabelPosition,
) -> std::io::Result<()>
where
    DB: plotters::prelude::DrawingBackend + 'a,
    CT: plotters::coord::CoordTranslate,
{
    use plotters::style::{Color, RGBColor, WHITE};
    chart
        .configure_series_labels()
        .position(position)
        .label_font(("sans-serif", 15))
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(160, 160, 160))
        .draw()
        .map_err(draw_err)
}
