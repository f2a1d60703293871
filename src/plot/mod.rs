//! Plots: the measured spectrum of `analyze --plot` and the model spectra of
//! `spectrum --plot`, drawn into RGB buffers (written by `export::rgb8`).

pub mod analysis;
pub mod spectrum;
pub mod waves;

/// The family every plot's text names.
const FONT: &str = "sans-serif";

/// Registers the embedded DejaVu Sans (regular and bold) as `sans-serif`, once per
/// process: the plots draw their text with it, whatever fonts the system has.
fn register_fonts() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        use plotters::style::{FontStyle, register_font};
        for (style, bytes) in [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
        ] {
            if register_font(FONT, style, bytes).is_err() {
                unreachable!("the embedded DejaVu Sans is a valid font");
            }
        }
    });
}

/// The chart layout both log–log plots share: margins and label areas, in pixels.
fn log_log_chart<'a, 'b, DB: plotters::prelude::DrawingBackend>(
    body: &'a plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
) -> plotters::prelude::ChartBuilder<'a, 'b, DB> {
    let mut chart = plotters::prelude::ChartBuilder::on(body);
    chart
        .margin_left(10)
        .margin_right(25)
        .margin_top(8)
        .margin_bottom(8)
        .x_label_area_size(45)
        .y_label_area_size(75);
    chart
}

/// A number with 3 significant digits and no trailing zeros (`0.0123`, `45.6`), in
/// exponent form (`1e-5`) below 10^`lowest` and from 10⁵ on; zero is `0`.
fn short_number(v: f64, lowest: i32) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if !v.is_finite() {
        return format!("{v}");
    }
    let mag = v.abs().log10().floor();
    if !(f64::from(lowest)..5.0).contains(&mag) {
        return format!("{v:.0e}");
    }
    let decimals = (2.0 - mag).max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
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
