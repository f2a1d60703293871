//! The distributions chart of `analyze --plot-waves`: P(C > c) of the crests and
//! P(H > h) of the zero-crossing wave heights, over Hs, on a logarithmic probability
//! axis, against Rayleigh (exp(−8c²/Hs²), exp(−2h²/Hs²)) and Forristall's (2000)
//! short-crested crest distribution.

use super::draw_err;
use crate::measure::waves::WaveStats;

/// Size of the `--plot-waves` image, pixels.
pub const WAVE_PLOT_SIZE: (u32, u32) = (800, 500);
use super::FONT;
/// The smallest probability drawn.
const P_MIN: f64 = 1e-5;
/// Largest level over Hs drawn.
const X_MAX: f64 = 1.6;

/// The empirical exceedance of ascending `sorted` values: (x, P(X > x)) at up to 400
/// points, the last ones (the rare events) all kept.
fn exceedance_curve(sorted: &[f64]) -> Vec<(f64, f64)> {
    let n = sorted.len();
    if n == 0 {
        return Vec::new();
    }
    let step = (n / 400).max(1);
    let tail = n.saturating_sub(200);
    (0..n)
        .filter(|&i| i % step == 0 || i >= tail)
        .map(|i| (sorted[i], ((n - i - 1) as f64 / n as f64).max(P_MIN)))
        .filter(|&(x, p)| x <= X_MAX && p > P_MIN)
        .collect()
}

/// Draws the exceedance chart of `w` (and the crests of `other`, when given) into an RGB
/// buffer of [`WAVE_PLOT_SIZE`]; `name` heads the title.
pub fn render_wave_plot(
    w: &WaveStats,
    name: &str,
    other: Option<(&str, &WaveStats)>,
) -> std::io::Result<Vec<u8>> {
    use plotters::prelude::*;

    let (width, height) = WAVE_PLOT_SIZE;
    let mut buf = vec![0u8; (width * height * 3) as usize];
    {
        super::register_fonts();
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (head, body) = root.split_vertically(62);
        head.draw(&Text::new(
            format!("{name}: crest and wave-height exceedance"),
            (12, 8),
            (FONT, 22).into_font().style(FontStyle::Bold),
        ))
        .map_err(draw_err)?;
        let sub = format!(
            "skewness {:.3}, kurtosis {:.3}  ·  {} crests, {} waves  ·  S1 {}, Ur {}",
            w.skewness,
            w.kurtosis,
            w.crests.count,
            w.waves.count,
            w.crests
                .steepness_s1
                .map_or("-".into(), |v| format!("{v:.4}")),
            w.crests.ursell.map_or("-".into(), |v| format!("{v:.3}")),
        );
        head.draw(&Text::new(sub, (12, 36), (FONT, 16)))
            .map_err(draw_err)?;
        let mut chart = super::log_log_chart(&body)
            .build_cartesian_2d(0.0..X_MAX, (P_MIN..1.0).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("crest c / Hs, height h / Hs")
            .y_desc("probability of exceedance")
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .axis_desc_style((FONT, 17))
            .label_style((FONT, 14))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(205, 205, 205))
            .draw()
            .map_err(draw_err)?;
        let xs: Vec<f64> = (0..=160).map(|i| i as f64 * X_MAX / 160.0).collect();
        let curve = |f: &dyn Fn(f64) -> f64| -> Vec<(f64, f64)> {
            xs.iter()
                .map(|&x| (x, f(x)))
                .filter(|&(_, p)| p >= P_MIN)
                .collect()
        };
        let gray = RGBColor(120, 120, 120);
        let black = RGBColor(20, 20, 20);
        let blue = RGBColor(30, 90, 200);
        let red = RGBColor(200, 30, 30);
        let green = RGBColor(20, 140, 60);
        let orange = RGBColor(230, 120, 0);
        chart
            .draw_series(DashedLineSeries::new(
                curve(&|x| (-8.0 * x * x).exp()),
                6,
                4,
                gray.stroke_width(2),
            ))
            .map_err(draw_err)?
            .label("crests, Rayleigh exp(−8c²/Hs²)")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], gray.stroke_width(2))
            });
        if let (Some(a), Some(b)) = (w.crests.forristall_alpha, w.crests.forristall_beta) {
            chart
                .draw_series(LineSeries::new(
                    curve(&|x| (-(x / a).powf(b)).exp()),
                    black.stroke_width(2),
                ))
                .map_err(draw_err)?
                .label(format!("crests, Forristall 2000 (α {a:.3}, β {b:.3})"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], black.stroke_width(2))
                });
        }
        chart
            .draw_series(DashedLineSeries::new(
                curve(&|x| (-2.0 * x * x).exp()),
                2,
                4,
                green.stroke_width(2),
            ))
            .map_err(draw_err)?
            .label("heights, Rayleigh exp(−2h²/Hs²)")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], green.stroke_width(2))
            });
        chart
            .draw_series(LineSeries::new(
                exceedance_curve(&w.heights_over_hs),
                orange.stroke_width(2),
            ))
            .map_err(draw_err)?
            .label(format!("heights, {name}"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], orange.stroke_width(2))
            });
        chart
            .draw_series(LineSeries::new(
                exceedance_curve(&w.crests_over_hs),
                blue.stroke_width(2),
            ))
            .map_err(draw_err)?
            .label(format!("crests, {name}"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], blue.stroke_width(2))
            });
        if let Some((other_name, o)) = other {
            chart
                .draw_series(LineSeries::new(
                    exceedance_curve(&o.crests_over_hs),
                    red.stroke_width(2),
                ))
                .map_err(draw_err)?
                .label(format!("crests, {other_name}"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], red.stroke_width(2))
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
    use crate::measure::analyze;
    use crate::measure::spectrum::tests::cosine;
    use crate::measure::waves::{SeaContext, wave_statistics};

    #[test]
    fn the_exceedance_curve_counts_values_above() {
        let v: Vec<f64> = (0..10).map(|i| i as f64 * 0.1).collect();
        let c = exceedance_curve(&v);
        assert_eq!(c.len(), 9, "the last value has P = 0 and is left out");
        assert!((c[0].1 - 0.9).abs() < 1e-12 && (c[4].1 - 0.5).abs() < 1e-12);
    }

    #[test]
    fn the_wave_plot_renders() {
        let g = cosine(64, 64.0, 8.0, 30.0, 1.0);
        let a = analyze(&g, None);
        let w = wave_statistics(&g, &a, &SeaContext::default());
        let rgb = render_wave_plot(&w, "test", Some(("other", &w))).unwrap();
        assert_eq!(
            rgb.len(),
            (WAVE_PLOT_SIZE.0 * WAVE_PLOT_SIZE.1 * 3) as usize
        );
        assert!(rgb.iter().any(|&v| v != 255));
    }
}
