//! The model spectrum's plots (`seasynth spectrum --plot`, `--plot2d`): F(f) on log–log
//! axes with the peak marked, and the directional wavenumber spectrum Ψ(kx, ky) as a
//! color map with +ky up.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::draw_err;
use crate::config::validate::model_name;
use crate::config::{Params, SpectrumModel};
use crate::error::Error;
use crate::field::SeaModel;
use crate::spectrum::Fractal;

/// Size of the `--plot` image, pixels.
pub const PLOT_SIZE: (u32, u32) = (800, 500);
/// Size of the `--plot2d` image, pixels.
pub const PLOT2D_SIZE: (u32, u32) = (600, 600);
/// Frequency range of `--plot`, in units of the peak frequency.
pub const PLOT_RANGE_FP: (f64, f64) = (0.2, 10.0);
/// Half-width of the `--plot2d` window, in units of the peak wavenumber.
pub const PLOT2D_RANGE_KP: f64 = 3.0;
/// Decades of the `--plot2d` color scale below the largest value.
pub const PLOT2D_DECADES: f64 = 6.0;
/// Decades of the `--plot` vertical axis below the peak.
const PLOT_DECADES: f64 = 6.0;

/// A tick value: [`super::short_number`] in exponent form below 10⁻⁴.
fn tick_text(v: f64) -> String {
    super::short_number(v, -4)
}

/// Ticks of a log axis over [lo, hi]: labelled ones (1, 2, 3, 5 × 10ⁿ, fewer over many
/// decades) or the light grid (1 … 9 × 10ⁿ).
fn log_ticks(lo: f64, hi: f64, labelled: bool) -> Vec<f64> {
    let decades = (hi / lo).log10();
    let mantissas: &[f64] = match (labelled, decades) {
        (false, _) => &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
        (true, d) if d <= 2.5 => &[1.0, 2.0, 3.0, 5.0],
        (true, d) if d <= 5.0 => &[1.0, 2.0, 5.0],
        _ => &[1.0],
    };
    let mut out = Vec::new();
    let mut e = lo.log10().floor() as i32;
    while 10f64.powi(e) <= hi {
        for m in mantissas {
            // Formatted and parsed back so 3 × 10⁻² is 0.03, not 0.030000000000000002.
            let v: f64 = format!("{m}e{e}").parse().expect("a number");
            if v >= lo && v <= hi {
                out.push(v);
            }
        }
        e += 1;
    }
    out
}

/// A power of ten as a tick label: `1e-3`, `1`, `10`, `1e4`.
fn decade_text(v: f64) -> String {
    let e = v.log10().round() as i32;
    match e {
        0 => "1".into(),
        1 => "10".into(),
        _ => format!("1e{e}"),
    }
}

/// The parameters a model is made from, for titles: wind, fetch or Hs/Tp, γ, depth.
fn parameter_text(params: &Params) -> String {
    let s = &params.spectrum;
    let mut parts = Vec::new();
    match (s.hs_m, s.tp_s) {
        (Some(hs), Some(tp)) => {
            parts.push(format!("Hs {} m, Tp {} s", tick_text(hs), tick_text(tp)))
        }
        _ => {
            parts.push(format!("U10 {} m/s", tick_text(params.wind.speed_mps)));
            if matches!(s.model, SpectrumModel::Jonswap | SpectrumModel::Tma) {
                parts.push(format!("fetch {} km", tick_text(s.fetch_km)));
            }
        }
    }
    if matches!(s.model, SpectrumModel::Jonswap | SpectrumModel::Tma) {
        parts.push(format!("γ {}", tick_text(s.gamma)));
    }
    parts.push(match s.depth_m {
        Some(d) => format!("depth {} m", tick_text(d)),
        None => "deep water".into(),
    });
    parts.join(", ")
}

fn spreading_name(params: &Params) -> String {
    serde_json::to_value(params.spectrum.spreading)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

/// Font of every text in the plots.
use super::FONT;

/// Draws F(f) on log–log axes into an RGB buffer of [`PLOT_SIZE`].
pub fn render_plot(params: &Params, sea: &SeaModel, marks: &[f64]) -> std::io::Result<Vec<u8>> {
    let (w, h) = PLOT_SIZE;
    let mut buf = vec![0u8; (w * h * 3) as usize];
    let fp = sea.freq.peak_hz();
    let hs = sea.freq.hs_m();
    let mut f_lo = PLOT_RANGE_FP.0 * fp;
    let mut f_hi = PLOT_RANGE_FP.1 * fp;
    for &f in marks {
        f_lo = f_lo.min(f / 1.25);
        f_hi = f_hi.max(f * 1.25);
    }
    const N: usize = 1200;
    let curve: Vec<(f64, f64)> = (0..=N)
        .map(|i| {
            let f = f_lo * (f_hi / f_lo).powf(i as f64 / N as f64);
            (f, sea.freq.density(f))
        })
        .collect();
    let peak = sea
        .freq
        .density(fp)
        .max(curve.iter().map(|p| p.1).fold(0.0, f64::max));
    let y_hi = 10f64.powf((peak * 3.0).log10().ceil());
    let y_lo = 10f64.powf((peak * 10f64.powf(-PLOT_DECADES)).log10().floor());
    {
        super::register_fonts();
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (head, body) = root.split_vertically(62);
        let name = model_name(params.spectrum.model);
        head.draw(&Text::new(
            format!("{name}: frequency spectrum F(f)"),
            (12, 8),
            (FONT, 22).into_font().style(FontStyle::Bold),
        ))
        .map_err(draw_err)?;
        head.draw(&Text::new(
            format!(
                "{}  →  Hs {} m, fp {} Hz (Tp {} s)",
                parameter_text(params),
                tick_text(hs),
                tick_text(fp),
                tick_text(1.0 / fp)
            ),
            (12, 36),
            (FONT, 16),
        ))
        .map_err(draw_err)?;
        let mut chart = super::log_log_chart(&body)
            .build_cartesian_2d(
                (f_lo..f_hi)
                    .log_scale()
                    .with_key_points(log_ticks(f_lo, f_hi, true))
                    .with_light_points(log_ticks(f_lo, f_hi, false)),
                (y_lo..y_hi).log_scale(),
            )
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("frequency f (Hz)")
            .y_desc("F(f) (m²/Hz)")
            .x_label_formatter(&|v| tick_text(*v))
            .y_label_formatter(&|v| decade_text(*v))
            .axis_desc_style((FONT, 17))
            .label_style((FONT, 14))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(205, 205, 205))
            .draw()
            .map_err(draw_err)?;
        // The curve, without the part below the axis (F underflows to 0 far below fp).
        let visible = curve.iter().copied().filter(|p| p.1 >= y_lo);
        chart
            .draw_series(LineSeries::new(visible, BLUE.stroke_width(2)))
            .map_err(draw_err)?
            .label("F(f)")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
        let red = RGBColor(200, 30, 30);
        chart
            .draw_series(DashedLineSeries::new(
                vec![(fp, y_lo), (fp, y_hi)],
                6,
                4,
                red.stroke_width(2),
            ))
            .map_err(draw_err)?;
        let label = format!("fp = {} Hz", tick_text(fp));
        // Below the curve's right flank, which stays high for decades beyond fp.
        let bottom = chart.backend_coord(&(fp, y_lo));
        root.draw(&Text::new(
            label,
            (bottom.0 + 7, bottom.1 - 26),
            (FONT, 16).into_font().color(&red),
        ))
        .map_err(draw_err)?;
        if !marks.is_empty() {
            chart
                .draw_series(
                    marks
                        .iter()
                        .map(|&f| (f, sea.freq.density(f)))
                        .filter(|p| p.1 >= y_lo && p.1 <= y_hi)
                        .map(|p| Circle::new(p, 5, BLACK.stroke_width(2))),
                )
                .map_err(draw_err)?
                .label("--freq points")
                .legend(|(x, y)| Circle::new((x + 10, y), 5, BLACK.stroke_width(2)));
        }
        crate::plot::draw_legend(&mut chart, SeriesLabelPosition::UpperRight)?;
        root.present().map_err(draw_err)?;
    }
    Ok(buf)
}

/// What `--plot2d` shows: a square window of wavevectors and a function over it.
pub struct WavenumberMap {
    /// The window is [−half, half]² rad/m.
    pub half_rad_per_m: f64,
    /// The peak wavenumber the window is scaled by (a circle is drawn there), rad/m.
    pub kp_rad_per_m: Option<f64>,
    /// Wind direction (toward), radians from +x.
    pub wind_dir_rad: f64,
    /// Title lines.
    pub title: String,
    pub subtitle: String,
    /// Quantity and unit for the color bar.
    pub quantity: String,
    /// Draw the wind arrow (not for the isotropic fractal spectrum).
    pub show_wind: bool,
    /// The function of (kx, ky) shown.
    value: Box<dyn Fn(f64, f64) -> f64 + Send + Sync>,
}

impl WavenumberMap {
    pub fn value(&self, kx: f64, ky: f64) -> f64 {
        (self.value)(kx, ky)
    }
}

/// The wavenumber map of `params`: Ψ(kx, ky) for a physical sea, the discrete amplitude
/// variance on the preset's grid for `phillips` and `fractal`.
pub fn wavenumber_map(params: &Params, sea: Option<SeaModel>) -> Result<WavenumberMap, Error> {
    let name = model_name(params.spectrum.model);
    let wind_dir_rad = params.wind.direction_deg.to_radians();
    let wind = format!(
        "wind {} m/s toward {}°",
        tick_text(params.wind.speed_mps),
        tick_text(params.wind.direction_deg)
    );
    let [nx, ny] = params.grid.size.0;
    let [lx, ly] = params.grid.extent_m.0;
    let tau = std::f64::consts::TAU;
    let (dkx, dky) = (tau / lx, tau / ly);
    let grid_text = format!(
        "on the {nx}×{ny} grid over {} × {} m",
        tick_text(lx),
        tick_text(ly)
    );
    if let Some(sea) = sea {
        let spectrum = sea.into_directional()?;
        let kp = spectrum.peak_wavenumber();
        return Ok(WavenumberMap {
            half_rad_per_m: PLOT2D_RANGE_KP * kp,
            kp_rad_per_m: Some(kp),
            wind_dir_rad,
            title: format!("{name} + {}: Ψ(kx, ky)", spreading_name(params)),
            subtitle: format!(
                "{}, toward {}°; kp {} rad/m",
                parameter_text(params),
                tick_text(params.wind.direction_deg),
                tick_text(kp)
            ),
            quantity: "Ψ (m⁴)".into(),
            value: Box::new(move |kx, ky| spectrum.psi(kx, ky)),
            show_wind: true,
        });
    }
    match params.spectrum.model {
        SpectrumModel::Phillips => {
            // The generator's own model.
            let (p, _) = crate::field::spectrum_model(params)?;
            // Along the wind P ∝ exp(−1/(kL)²)/k⁴ peaks at k = 1/(√2 L).
            let big_l = crate::field::phillips(params).largest_wave_m();
            let kp = 1.0 / (std::f64::consts::SQRT_2 * big_l);
            Ok(WavenumberMap {
                half_rad_per_m: PLOT2D_RANGE_KP * kp,
                kp_rad_per_m: Some(kp),
                wind_dir_rad,
                title: "phillips: P(k) = E|h0(k)|², discrete convention".into(),
                subtitle: format!(
                    "A {:e}, {wind}; kp = 1/(√2 L) = {} rad/m",
                    params.spectrum.phillips_a,
                    tick_text(kp)
                ),
                quantity: "P (m²)".into(),
                value: Box::new(move |kx, ky| p.amplitude_variance(kx, ky, dkx, dky)),
                show_wind: true,
            })
        }
        _ => {
            let f = &params.fractal;
            let beta = Fractal::new(f.dimension, f.relief_m, f.rolloff_m)?.beta();
            // The generator's own model, scaled to the grid.
            let (on_grid, _) = crate::field::spectrum_model(params)?;
            let kp = f.rolloff_m.map(|r| tau / r);
            let dk_min = dkx.min(dky);
            // Without a roll-off the power law has no scale: show the grid's band.
            let nyquist =
                (std::f64::consts::PI * nx as f64 / lx).min(std::f64::consts::PI * ny as f64 / ly);
            let half = match kp {
                Some(k) => PLOT2D_RANGE_KP * k,
                None => nyquist.min(32.0 * dkx.max(dky)),
            };
            Ok(WavenumberMap {
                half_rad_per_m: half,
                kp_rad_per_m: kp,
                wind_dir_rad,
                title: "fractal: E|h0(k)|², isotropic power law".into(),
                subtitle: format!(
                    "D {}, β {}, relief {} m{}, {grid_text}",
                    tick_text(f.dimension),
                    tick_text(beta),
                    tick_text(f.relief_m),
                    f.rolloff_m
                        .map(|r| format!(", roll-off {} m", tick_text(r)))
                        .unwrap_or_default()
                ),
                quantity: "E|h0|² (m²)".into(),
                // The grid has no wavevector shorter than its spacing but k = 0 (left out).
                value: Box::new(move |kx, ky| {
                    if kx * kx + ky * ky < dk_min * dk_min {
                        0.0
                    } else {
                        on_grid.amplitude_variance(kx, ky, dkx, dky)
                    }
                }),
                show_wind: false,
            })
        }
    }
}

/// Samples `map` at the centres of an n×n pixel grid, row 0 at the top (+ky largest).
pub fn sample_map(map: &WavenumberMap, n: usize) -> Vec<f64> {
    use rayon::prelude::*;
    let half = map.half_rad_per_m;
    let step = 2.0 * half / n as f64;
    let rows: Vec<Vec<f64>> = (0..n)
        .into_par_iter()
        .map(|row| {
            let ky = half - (row as f64 + 0.5) * step;
            (0..n)
                .map(|col| map.value(-half + (col as f64 + 0.5) * step, ky))
                .collect()
        })
        .collect();
    rows.concat()
}

/// Draws the wavenumber map into an RGB buffer of [`PLOT2D_SIZE`].
pub fn render_plot2d(map: &WavenumberMap) -> std::io::Result<Vec<u8>> {
    let (w, h) = PLOT2D_SIZE;
    let mut buf = vec![0u8; (w * h * 3) as usize];
    // Layout: title 60 px, a square plot of SIDE px with axes left and below, the color
    // bar on the right.
    const SIDE: i32 = 450;
    const LEFT: i32 = 80;
    const TOP: i32 = 70;
    {
        super::register_fonts();
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        root.draw(&Text::new(
            map.title.clone(),
            (12, 8),
            (FONT, 20).into_font().style(FontStyle::Bold),
        ))
        .map_err(draw_err)?;
        root.draw(&Text::new(map.subtitle.clone(), (12, 36), (FONT, 14)))
            .map_err(draw_err)?;
        let half = map.half_rad_per_m;
        // Ticks at 0 come out as ±1e-17 from the evenly spaced key points.
        let snap = |v: f64| if v.abs() < 1e-9 * half { 0.0 } else { v };
        let area = root.clone().shrink(
            (LEFT - 70, TOP - 10),
            ((SIDE + 70 + 10) as u32, (SIDE + 10 + 50) as u32),
        );
        let mut chart = ChartBuilder::on(&area)
            .margin_top(10)
            .margin_right(10)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(-half..half, -half..half)
            .map_err(draw_err)?;
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let (pw, ph) = ((xr.end - xr.start) as usize, (yr.end - yr.start) as usize);
        let n = pw.min(ph);
        let values = sample_map(map, n);
        let vmax = values.iter().copied().fold(0.0, f64::max);
        let lmax = if vmax > 0.0 { vmax.log10().ceil() } else { 0.0 };
        let lmin = lmax - PLOT2D_DECADES;
        let color = |v: f64| -> RGBColor {
            let l = if v > 0.0 { v.log10() } else { lmin };
            ViridisRGB.get_color_normalized(l.clamp(lmin, lmax), lmin, lmax)
        };
        for row in 0..n {
            for col in 0..n {
                let c = color(values[row * n + col]);
                root.draw_pixel((xr.start + col as i32, yr.start + row as i32), &c)
                    .map_err(draw_err)?;
            }
        }
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("kx (rad/m)")
            .y_desc("ky (rad/m)")
            .x_label_formatter(&|v| tick_text(snap(*v)))
            .y_label_formatter(&|v| tick_text(snap(*v)))
            .axis_desc_style((FONT, 16))
            .label_style((FONT, 13))
            .x_labels(7)
            .y_labels(7)
            .draw()
            .map_err(draw_err)?;
        let white = WHITE.mix(0.9);
        if let Some(kp) = map.kp_rad_per_m {
            let ring: Vec<(f64, f64)> = (0..=180)
                .map(|i| {
                    let a = i as f64 * std::f64::consts::TAU / 180.0;
                    (kp * a.cos(), kp * a.sin())
                })
                .collect();
            chart
                .draw_series(DashedLineSeries::new(ring, 5, 5, white.stroke_width(1)))
                .map_err(draw_err)?;
            // Away from the wind arrow.
            let a = map.wind_dir_rad + 2.4;
            let at = chart.backend_coord(&(kp * a.cos(), kp * a.sin()));
            root.draw(&Text::new(
                "kp",
                (at.0 + 4, at.1 - 18),
                (FONT, 15).into_font().color(&WHITE),
            ))
            .map_err(draw_err)?;
        }
        if map.show_wind {
            // From the origin toward the wind direction, 0.8 of the way to the edge.
            let (s, c) = map.wind_dir_rad.sin_cos();
            let len = 0.8 * half;
            let from = chart.backend_coord(&(0.0, 0.0));
            let to = chart.backend_coord(&(len * c, len * s));
            draw_wind_arrow(&root, from, to, map.wind_dir_rad)?;
        }
        // The color bar.
        let bx = xr.end + 14;
        let (by0, by1) = (yr.start, yr.start + n as i32);
        for y in by0..by1 {
            let l = lmax - (y - by0) as f64 / (by1 - by0) as f64 * (lmax - lmin);
            let c = ViridisRGB.get_color_normalized(l, lmin, lmax);
            root.draw(&Rectangle::new([(bx, y), (bx + 18, y + 1)], c.filled()))
                .map_err(draw_err)?;
        }
        root.draw(&Rectangle::new(
            [(bx, by0), (bx + 18, by1)],
            BLACK.stroke_width(1),
        ))
        .map_err(draw_err)?;
        for d in 0..=(PLOT2D_DECADES as i32) {
            let y = by0 + ((by1 - by0) as f64 * d as f64 / PLOT2D_DECADES).round() as i32;
            root.draw(&PathElement::new(
                vec![(bx + 18, y), (bx + 22, y)],
                BLACK.stroke_width(1),
            ))
            .map_err(draw_err)?;
            root.draw(&Text::new(
                decade_text(10f64.powf(lmax - d as f64)),
                (bx + 24, y - 7),
                (FONT, 13),
            ))
            .map_err(draw_err)?;
        }
        root.draw(&Text::new(
            map.quantity.clone(),
            (bx - 6, by0 - 22),
            (FONT, 14),
        ))
        .map_err(draw_err)?;
        root.present().map_err(draw_err)?;
    }
    Ok(buf)
}

/// The wind arrow from pixel `a` to pixel `b` (direction `dir_rad` from +kx, +ky up),
/// with its label beyond the head.
fn draw_wind_arrow(
    root: &DrawingArea<BitMapBackend<'_>, Shift>,
    a: (i32, i32),
    b: (i32, i32),
    dir_rad: f64,
) -> std::io::Result<()> {
    let arrow = RGBColor(255, 80, 60);
    root.draw(&PathElement::new(vec![a, b], arrow.stroke_width(3)))
        .map_err(draw_err)?;
    // Pixel directions: +ky is up on the screen.
    let (s, c) = dir_rad.sin_cos();
    let (ux, uy) = (c, -s);
    let head = |along: f64, across: f64| -> (i32, i32) {
        (
            (b.0 as f64 - along * ux - across * uy).round() as i32,
            (b.1 as f64 - along * uy + across * ux).round() as i32,
        )
    };
    root.draw(&Polygon::new(
        vec![b, head(16.0, 7.0), head(16.0, -7.0)],
        arrow.filled(),
    ))
    .map_err(draw_err)?;
    // The label beside the shaft at 60 % of its length, on the upper side.
    let (mut nx, mut ny) = (-uy, ux);
    if ny > 0.0 || (ny == 0.0 && nx < 0.0) {
        (nx, ny) = (-nx, -ny);
    }
    let at = (
        (a.0 as f64 + 0.6 * (b.0 - a.0) as f64 + 28.0 * nx).round() as i32,
        (a.1 as f64 + 0.6 * (b.1 - a.1) as f64 + 28.0 * ny).round() as i32,
    );
    let style = (FONT, 15)
        .into_font()
        .color(&arrow)
        .pos(Pos::new(HPos::Center, VPos::Center));
    root.draw(&Rectangle::new(
        [(at.0 - 22, at.1 - 10), (at.0 + 22, at.1 + 10)],
        BLACK.mix(0.55).filled(),
    ))
    .map_err(draw_err)?;
    root.draw(&Text::new("wind", at, style)).map_err(draw_err)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::field::sea_model;

    /// The default parameters with the spectrum `model`.
    pub(crate) fn params(model: SpectrumModel) -> Params {
        let mut p = Params::default();
        p.spectrum.model = model;
        p
    }

    #[test]
    fn log_ticks_cover_the_range() {
        assert_eq!(
            log_ticks(0.017, 0.85, true),
            vec![0.02, 0.03, 0.05, 0.1, 0.2, 0.3, 0.5]
        );
        assert_eq!(
            log_ticks(1e-3, 2e3, true),
            vec![1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e3]
        );
        assert_eq!(log_ticks(0.15, 0.45, false), vec![0.2, 0.3, 0.4]);
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_text(0.085), "0.085");
        assert_eq!(tick_text(0.1), "0.1");
        assert_eq!(tick_text(15.0), "15");
        assert_eq!(tick_text(0.0294118), "0.0294");
        assert_eq!(tick_text(123.4), "123");
        assert_eq!(decade_text(1e-3), "1e-3");
        assert_eq!(decade_text(1.0), "1");
        assert_eq!(decade_text(1e4), "1e4");
    }

    /// (row, col) of the largest sample.
    fn argmax(v: &[f64], n: usize) -> (usize, usize) {
        let i = v
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
            .unwrap()
            .0;
        (i / n, i % n)
    }

    #[test]
    fn the_map_peaks_at_kp_in_the_wind_direction_with_ky_up() {
        let mut p = params(SpectrumModel::PiersonMoskowitz);
        p.wind.speed_mps = 15.0;
        p.wind.direction_deg = 90.0;
        let sea = sea_model(&p).unwrap().unwrap();
        let fp = sea.freq.peak_hz();
        let map = wavenumber_map(&p, Some(sea)).unwrap();
        let kp = map.kp_rad_per_m.unwrap();
        let want = (std::f64::consts::TAU * fp).powi(2) / crate::spectrum::G;
        assert!((kp - want).abs() < 1e-9 * want, "kp {kp} vs {want}");
        let n = 121;
        let v = sample_map(&map, n);
        let (row, col) = argmax(&v, n);
        let step = 2.0 * map.half_rad_per_m / n as f64;
        let kx = -map.half_rad_per_m + (col as f64 + 0.5) * step;
        let ky = map.half_rad_per_m - (row as f64 + 0.5) * step;
        assert!(kx.abs() <= step, "peak at kx {kx}");
        // Ψ (per unit kx·ky) peaks a little below kp: the Jacobian 1/k·df/dk grows to k → 0.
        assert!(ky > 0.5 * kp && ky < 1.2 * kp, "peak at ky {ky}, kp {kp}");
        // Upwind there is (almost) nothing with Hasselmann spreading.
        assert!(v[(n - 1 - row) * n + col] < 1e-3 * v[row * n + col]);
    }

    fn colors(buf: &[u8]) -> usize {
        let mut set: Vec<[u8; 3]> = buf.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        set.sort_unstable();
        set.dedup();
        set.len()
    }

    #[test]
    fn plots_render_for_every_model() {
        let mut p = params(SpectrumModel::Jonswap);
        p.spectrum.hs_m = Some(3.0);
        p.spectrum.tp_s = Some(10.0);
        p.validate().unwrap();
        let sea = sea_model(&p).unwrap().unwrap();
        let buf = render_plot(&p, &sea, &[0.05, 0.1, 0.3]).unwrap();
        assert_eq!(buf.len(), (PLOT_SIZE.0 * PLOT_SIZE.1 * 3) as usize);
        assert!(colors(&buf) > 10);
        let map = wavenumber_map(&p, Some(sea)).unwrap();
        let buf = render_plot2d(&map).unwrap();
        assert!(colors(&buf) > 50);
        for model in [SpectrumModel::Phillips, SpectrumModel::Fractal] {
            let p = params(model);
            let map = wavenumber_map(&p, None).unwrap();
            assert!(map.value(0.3 * map.half_rad_per_m, 0.1 * map.half_rad_per_m) > 0.0);
            let buf = render_plot2d(&map).unwrap();
            assert!(colors(&buf) > 50, "{model:?}");
        }
    }
}
