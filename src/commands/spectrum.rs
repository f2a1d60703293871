//! `seasynth spectrum`: the model spectrum itself, as numbers or as plots.
//!
//! - `--freq F1,F2,… --json | --csv`: the one-sided frequency spectrum F(f) in m²/Hz of a
//!   physical model (`pierson-moskowitz`, `jonswap`, `tma`) at the given frequencies (Hz),
//!   with the model's Hs = 4·√m0, peak frequency and peak period.
//! - `--plot FILE.png`: F(f) on log–log axes over [0.2 fp, 10 fp] (widened to take in
//!   the `--freq` points), the peak marked (Mastin Fig. 4, Thon Fig. 2). 800×500 RGB.
//! - `--plot2d FILE.png`: the directional wavenumber spectrum Ψ(kx, ky) (m⁴) on a
//!   Cartesian grid centred on k = 0 over ±3 kp, log color scale, wind arrow (Mastin
//!   Fig. 7). `phillips` and `fractal` have no F(f); for them the image shows the
//!   discrete amplitude variance E|h̃0(k)|² (m²) the generator uses on the preset's grid.
//!   600×600 RGB, +kx to the right and +ky **up** (mathematical orientation, unlike the
//!   height-map images where +y points down).
//!
//! The model is built from the same parameters as `generate` (preset, `--set`, flags).
//! Plot files are staged before any computation (an unwritable path fails at once) and
//! written whole or not at all.

use std::path::Path;

use anyhow::Result;

use crate::cli::SpectrumArgs;
use crate::commands::common::PLOTS;
use crate::error::{Error, ParamError};
use crate::export::Staged;
use crate::field::sea_model;
use crate::pipeline::reports::{no_frequency_spectrum, points_text};
#[cfg(feature = "plot")]
use crate::plot::spectrum::{PLOT_SIZE, PLOT2D_SIZE, render_plot, render_plot2d, wavenumber_map};

/// Parses `--freq`: comma-separated frequencies in Hz, each finite and > 0.
pub fn parse_freqs(text: &str) -> Result<Vec<f64>, ParamError> {
    let mut good = Vec::new();
    let mut bad = Vec::new();
    for item in text.split(',') {
        let item = item.trim();
        match item.parse::<f64>() {
            Ok(f) if f.is_finite() && f > 0.0 => good.push(f),
            _ => bad.push(if item.is_empty() {
                "(empty)".to_string()
            } else {
                item.to_string()
            }),
        }
    }
    if bad.is_empty() {
        Ok(good)
    } else {
        Err(ParamError {
            name: "--freq".into(),
            allowed:
                "comma-separated frequencies in Hz, each a finite number > 0 (e.g. 0.05,0.1,0.2)"
                    .into(),
            got: bad.join(", "),
        })
    }
}

/// Runs `seasynth spectrum`.
pub fn run(args: SpectrumArgs) -> Result<()> {
    crate::commands::common::refuse_no_effect("spectrum", &args.field)?;
    crate::commands::common::need_plots("--plot", args.plot.is_some())?;
    crate::commands::common::need_plots("--plot2d", args.plot2d.is_some())?;
    // Through `Error`, so a bad value exits with code 2.
    let freqs = args
        .freq
        .as_deref()
        .map(parse_freqs)
        .transpose()
        .map_err(Error::from)?;
    if freqs.is_none() && args.plot.is_none() && args.plot2d.is_none() {
        return Err(Error::Set {
            origin: "spectrum".into(),
            message: "nothing to do: give --freq F1,F2,… with --json or --csv, --plot FILE.png \
                      or --plot2d FILE.png"
                .into(),
        }
        .into());
    }
    let params = crate::commands::common::resolve_params(&args.field)?;
    let sea = sea_model(&params)?;
    if sea.is_none() {
        for (given, flag) in [(freqs.is_some(), "--freq"), (args.plot.is_some(), "--plot")] {
            if given {
                return Err(Error::Set {
                    origin: flag.into(),
                    message: no_frequency_spectrum(params.spectrum.model),
                }
                .into());
            }
        }
    }
    if let (Some(a), Some(b)) = (&args.plot, &args.plot2d) {
        if a == b {
            return Err(Error::Output {
                path: a.clone(),
                message: "given to both --plot and --plot2d".into(),
            }
            .into());
        }
    }
    // Stage the plot files before any work: a bad path fails now.
    let stage = |p: &Path| Staged::create_checked(p, &PLOTS, &[]);
    let plot = args.plot.as_deref().map(stage).transpose()?;
    let plot2d = args.plot2d.as_deref().map(stage).transpose()?;

    // The numbers first (the directional spectrum of --plot2d takes the model over).
    let text = match (&freqs, &sea) {
        (Some(freqs), Some(sea)) => Some(points_text(&params, sea, freqs, args.csv)?),
        _ => None,
    };
    #[cfg(not(feature = "plot"))]
    let _ = (plot, plot2d);
    #[cfg(feature = "plot")]
    if let Some(staged) = plot {
        let sea = sea.as_ref().expect("checked above");
        let image = render_plot(&params, sea, freqs.as_deref().unwrap_or(&[]))
            .map_err(|e| Error::io(&staged.path, e))?;
        crate::export::rgb8::write(staged, &image, PLOT_SIZE)?;
    }
    #[cfg(feature = "plot")]
    if let Some(staged) = plot2d {
        let map = wavenumber_map(&params, sea)?;
        let image = render_plot2d(&map).map_err(|e| Error::io(&staged.path, e))?;
        crate::export::rgb8::write(staged, &image, PLOT2D_SIZE)?;
    }
    if let Some(text) = text {
        print!("{text}");
    }
    Ok(())
}

#[cfg(all(test, feature = "plot"))]
mod tests {
    use super::*;
    use crate::config::SpectrumModel;
    use crate::pipeline::reports::{Point, csv_text};
    use crate::plot::spectrum::tests::params;
    use crate::spectrum::FrequencySpectrum;

    #[test]
    fn frequencies_parse_and_bad_ones_are_named() {
        assert_eq!(parse_freqs("0.05, 0.1,2e-1").unwrap(), vec![0.05, 0.1, 0.2]);
        let e = parse_freqs("0,-1").unwrap_err().to_string();
        assert!(e.starts_with("--freq must be"), "{e}");
        assert!(e.contains("(got 0, -1)"), "{e}");
        let e = parse_freqs("0.1,abc,,inf,NaN").unwrap_err().to_string();
        assert!(e.contains("(got abc, (empty), inf, NaN)"), "{e}");
    }

    #[test]
    fn csv_numbers_read_back_exactly() {
        let pts = [
            Point {
                f_hz: 0.05,
                s_m2_per_hz: 1.234_567_890_123_456_7e-20,
            },
            Point {
                f_hz: 0.1,
                s_m2_per_hz: 12.5,
            },
        ];
        let text = csv_text(&pts);
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("f_hz,s_m2_per_hz"));
        for (line, p) in lines.zip(&pts) {
            let (f, s) = line.split_once(',').unwrap();
            assert_eq!(f.parse::<f64>().unwrap(), p.f_hz);
            assert_eq!(s.parse::<f64>().unwrap(), p.s_m2_per_hz);
        }
        assert_eq!(text.lines().count(), 3);
    }

    /// ∫F df by Simpson's rule in ln f over [fp/20, 1000 fp] plus the f⁻⁵ tail.
    fn m0_by_quadrature(f: &dyn FrequencySpectrum) -> f64 {
        let fp = f.peak_hz();
        let (a, b) = ((fp / 20.0).ln(), (1000.0 * fp).ln());
        let n = 20_000;
        let h = (b - a) / n as f64;
        let g = |u: f64| {
            let x = u.exp();
            f.density(x) * x
        };
        let mut s = g(a) + g(b);
        for i in 1..n {
            s += g(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        let fmax = b.exp();
        s * h / 3.0 + f.density(fmax) * fmax / 4.0
    }

    #[test]
    fn the_reported_m0_is_the_integral_of_the_printed_density() {
        let mut p = params(SpectrumModel::PiersonMoskowitz);
        p.wind.speed_mps = 15.0;
        let mut cases = vec![p.clone()];
        p.spectrum.model = SpectrumModel::Jonswap;
        cases.push(p.clone());
        p.spectrum.model = SpectrumModel::Tma;
        p.spectrum.depth_m = Some(20.0);
        cases.push(p.clone());
        for p in cases {
            p.validate().unwrap();
            let sea = sea_model(&p).unwrap().unwrap();
            let hs = sea.freq.hs_m();
            let m0 = m0_by_quadrature(sea.freq.as_ref());
            let rel = (4.0 * m0.sqrt() - hs).abs() / hs;
            assert!(
                rel < 1e-7,
                "{:?}: Hs {hs} vs 4√m0 {}",
                p.spectrum.model,
                4.0 * m0.sqrt()
            );
        }
    }

    #[test]
    fn phillips_and_fractal_have_no_sea_model_and_say_why() {
        assert!(
            sea_model(&params(SpectrumModel::Phillips))
                .unwrap()
                .is_none()
        );
        assert!(
            sea_model(&params(SpectrumModel::Fractal))
                .unwrap()
                .is_none()
        );
        let m = no_frequency_spectrum(SpectrumModel::Phillips);
        assert!(m.contains("phillips is a discrete wavenumber spectrum (Tessendorf's convention"));
        assert!(m.contains("use a physical model"));
        assert!(no_frequency_spectrum(SpectrumModel::Fractal).starts_with("fractal"));
    }
}
