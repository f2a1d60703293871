//! The plot of a measured radial spectrum S(k) (`analyze --plot`).

use super::draw_err;
use crate::measure::Analysis;

/// Size of the `--plot` image, pixels.
pub const PLOT_SIZE: (u32, u32) = (800, 500);
/// Decades of S(k) shown below the highest value.
const PLOT_DECADES: f64 = 8.0;
/// Font of every text in the plot.
use super::FONT;

/// A label of S(k)'s plot: [`super::short_number`] in exponent form below 10⁻³.
fn short_number(v: f64) -> String {
    super::short_number(v, -3)
}

/// Draws the measured (and target) S(k) of `a` on log–log axes into an RGB buffer of
/// [`PLOT_SIZE`]; `name` heads the title.
pub fn render_plot(a: &Analysis, name: &str) -> std::io::Result<Vec<u8>> {
    use plotters::prelude::*;

    let (w, h) = PLOT_SIZE;
    let mut buf = vec![0u8; (w * h * 3) as usize];
    let bins = &a.radial_spectrum;
    let highest = bins
        .iter()
        .flat_map(|b| {
            [
                b.s_m2_per_rad_per_m,
                b.target_s_m2_per_rad_per_m.unwrap_or(0.0),
            ]
        })
        .fold(0.0f64, f64::max);
    let lowest = bins
        .iter()
        .flat_map(|b| {
            [
                b.s_m2_per_rad_per_m,
                b.target_s_m2_per_rad_per_m.unwrap_or(0.0),
            ]
        })
        .filter(|&v| v > 0.0)
        .fold(f64::INFINITY, f64::min);
    let (y_lo, y_hi) = if highest > 0.0 {
        let hi = 10f64.powf((highest * 2.0).log10().ceil());
        let lo = 10f64
            .powf(lowest.log10().floor())
            .max(hi * 10f64.powf(-PLOT_DECADES));
        (lo, hi)
    } else {
        (1e-6, 1.0)
    };
    let k_lo = bins.first().map_or(a.dk_rad_per_m, |b| b.k_rad_per_m) / 1.1;
    let k_hi = bins.last().map_or(10.0 * a.dk_rad_per_m, |b| b.k_rad_per_m) * 1.1;
    let k_hi = k_hi.max(k_lo * 10.0);
    let clamp = |v: f64| v.clamp(y_lo, y_hi);
    {
        super::register_fonts();
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (head, body) = root.split_vertically(62);
        head.draw(&Text::new(
            format!("{name}: radial wavenumber spectrum S(k)"),
            (12, 8),
            (FONT, 22).into_font().style(FontStyle::Bold),
        ))
        .map_err(draw_err)?;
        let mut sub = format!(
            "{}×{} over {}×{} m  ·  Hs {} m",
            a.nx,
            a.ny,
            short_number(a.extent_m[0]),
            short_number(a.extent_m[1]),
            short_number(a.hs_m)
        );
        if let Some(t) = &a.target {
            sub += &format!(
                "  ·  target Hs {} m, variance ratio {}",
                short_number(t.target_hs_m),
                t.variance_ratio.map_or("-".into(), |r| format!("{r:.3}"))
            );
        }
        head.draw(&Text::new(sub, (12, 36), (FONT, 16)))
            .map_err(draw_err)?;
        let mut chart = super::log_log_chart(&body)
            .build_cartesian_2d((k_lo..k_hi).log_scale(), (y_lo..y_hi).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("wavenumber k (rad/m)")
            .y_desc("S(k) (m²/(rad/m))")
            .x_label_formatter(&|v| short_number(*v))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .axis_desc_style((FONT, 17))
            .label_style((FONT, 14))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(205, 205, 205))
            .draw()
            .map_err(draw_err)?;
        let blue = RGBColor(30, 90, 200);
        let pale = RGBColor(150, 180, 230);
        let red = RGBColor(200, 30, 30);
        let gray = RGBColor(90, 90, 90);
        let complete: Vec<(f64, f64)> = bins
            .iter()
            .filter(|b| b.complete)
            .map(|b| (b.k_rad_per_m, clamp(b.s_m2_per_rad_per_m)))
            .collect();
        // Bins beyond the Nyquist circle start from the last complete one.
        let partial: Vec<(f64, f64)> = bins
            .iter()
            .enumerate()
            .filter(|(i, b)| !b.complete || bins.get(i + 1).is_some_and(|n| !n.complete))
            .map(|(_, b)| (b.k_rad_per_m, clamp(b.s_m2_per_rad_per_m)))
            .collect();
        // The target first, so the measured curve stays visible over it.
        if let Some(t) = &a.target {
            let curve: Vec<(f64, f64)> = bins
                .iter()
                .map(|b| {
                    (
                        b.k_rad_per_m,
                        clamp(b.target_s_m2_per_rad_per_m.unwrap_or(0.0)),
                    )
                })
                .collect();
            chart
                .draw_series(LineSeries::new(curve, red.stroke_width(2)))
                .map_err(draw_err)?
                .label(format!(
                    "target: expected S(k), {} ({})",
                    t.spectrum, t.method
                ))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], red.stroke_width(2))
                });
        }
        chart
            .draw_series(LineSeries::new(complete, blue.stroke_width(2)))
            .map_err(draw_err)?
            .label("measured")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], blue.stroke_width(2))
            });
        if partial.len() > 1 {
            chart
                .draw_series(LineSeries::new(partial, pale.stroke_width(2)))
                .map_err(draw_err)?
                .label("measured, beyond Nyquist (partial annuli)")
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], pale.stroke_width(2))
                });
        }
        if let (Some(kp), Some(wl)) = (a.peak_k_rad_per_m, a.peak_wavelength_m) {
            let dir = a
                .peak_direction_deg
                .map_or(String::new(), |d| format!(", {d:.1}° (mod 180°)"));
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(kp, y_lo), (kp, y_hi)],
                    6,
                    4,
                    gray.stroke_width(1),
                ))
                .map_err(draw_err)?
                .label(format!("peak: λ = {} m{dir}", short_number(wl)))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], gray.stroke_width(1))
                });
        }
        crate::plot::draw_legend(&mut chart, SeriesLabelPosition::LowerLeft)?;
        root.present().map_err(draw_err)?;
    }
    Ok(buf)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Grid, GridSpec};
    use crate::measure::analyze;
    use crate::measure::spectrum::tests::cosine;

    #[test]
    fn plot_labels_are_short_numbers() {
        assert_eq!(short_number(0.0123456), "0.0123");
        assert_eq!(short_number(45.0), "45");
        assert_eq!(short_number(1234.6), "1235");
        assert_eq!(short_number(2e-5), "2e-5");
    }

    #[test]
    fn the_plot_renders_for_a_cosine_and_for_a_flat_field() {
        for g in [
            cosine(64, 64.0, 8.0, 30.0, 1.0),
            Grid::new(GridSpec::new(8, 8, 8.0, 8.0), vec![0.5; 64]),
        ] {
            let rgb = render_plot(&analyze(&g, None), "test").unwrap();
            assert_eq!(rgb.len(), (PLOT_SIZE.0 * PLOT_SIZE.1 * 3) as usize);
            assert!(rgb.iter().any(|&v| v != 255), "something is drawn");
        }
    }
}
