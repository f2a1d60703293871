//! `seasynth analyze`: statistics and the measured wavenumber spectrum of a height map,
//! compared with the spectrum it was generated from when its sidecar says so (the
//! conventions are stated in [`crate::measure`]).

use crate::cli::AnalyzeArgs;
use crate::commands::common::PLOTS;
#[cfg(feature = "plot")]
use crate::error::Error;
use crate::export::Staged;
use crate::measure::jacobian::JacobianStats;
use crate::measure::waves::WaveStats;
use crate::pipeline::analysis::{Report, analyze_file};
#[cfg(feature = "plot")]
use crate::plot::analysis::{PLOT_SIZE, render_plot};

/// Runs `seasynth analyze`.
pub fn run(args: AnalyzeArgs) -> anyhow::Result<()> {
    super::common::need_plots("--plot", args.plot.is_some())?;
    super::common::need_plots("--plot-waves", args.plot_waves.is_some())?;
    // The plot file is staged before any work: a bad path fails now, and an error later
    // leaves no partial file.
    let plot = args
        .plot
        .as_deref()
        .map(|p| Staged::create_checked(p, &PLOTS, &[(&args.file, "is the file being analyzed")]))
        .transpose()?;
    let plot_waves = args
        .plot_waves
        .as_deref()
        .map(|p| Staged::create_checked(p, &PLOTS, &[(&args.file, "is the file being analyzed")]))
        .transpose()?;
    let analyzed = analyze_file(
        &args.file,
        args.height_range.as_deref(),
        args.extent.as_deref(),
    )?;
    let report = analyzed.report();
    let (analysis, waves, jacobian) = (&analyzed.analysis, &analyzed.waves, &analyzed.jacobian);
    #[cfg(not(feature = "plot"))]
    let _ = (plot, plot_waves);
    #[cfg(feature = "plot")]
    if let Some(staged) = plot_waves {
        write_wave_plot(staged, &args, &report)?;
    }
    #[cfg(feature = "plot")]
    if let Some(staged) = plot {
        let name = args
            .file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| report.file.clone());
        let image = render_plot(analysis, &name).map_err(|e| Error::io(&staged.path, e))?;
        crate::export::rgb8::write(staged, &image, PLOT_SIZE)?;
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        serde_json::to_writer(&mut out, &report)?;
        std::io::Write::write_all(&mut out, b"\n")?;
    } else {
        std::io::Write::write_all(&mut out, human_report(&report).as_bytes())?;
        std::io::Write::write_all(&mut out, wave_report(waves, analysis.hs_m).as_bytes())?;
        std::io::Write::write_all(&mut out, jacobian_report(jacobian).as_bytes())?;
    }
    Ok(())
}

fn opt(v: Option<f64>, digits: usize, unit: &str) -> String {
    match v {
        Some(v) => format!("{v:.digits$}{unit}"),
        None => "-".into(),
    }
}

/// The short report printed without `--json`.
fn human_report(r: &Report) -> String {
    let a = r.analysis;
    let mut s = String::new();
    let kind = r.format.describe();
    s += &format!(
        "{}: {kind}, {}×{} samples, spacing {} m × {} m ({}), extent {} m × {} m\n",
        r.file, a.nx, a.ny, a.dx_m, a.dy_m, r.spacing_source, a.extent_m[0], a.extent_m[1]
    );
    s += &format!(
        "heights: mean {:.4} m, std {:.4} m, Hs (4·std) {:.4} m, min {:.4} m, max {:.4} m\n",
        // A mean of −0.00001 m would print as "-0.0000".
        if a.mean_m.abs() < 5e-5 { 0.0 } else { a.mean_m },
        a.std_m,
        a.hs_m,
        a.min_m,
        a.max_m
    );
    if let Some(q) = r.quantization_step_m {
        s += &format!("16-bit step: {q:.3e} m\n");
    }
    s += &format!(
        "spectral peak: wavelength {} (k = {}), direction {} modulo 180°, concentration {}\n",
        opt(a.peak_wavelength_m, 2, " m"),
        opt(a.peak_k_rad_per_m, 4, " rad/m"),
        opt(a.peak_direction_deg, 1, "°"),
        opt(a.peak_direction_concentration, 2, "")
    );
    match (&a.target, &a.target_note) {
        (Some(t), _) => {
            s += &format!(
                "target ({} method, {} spectrum): std {:.4} m, Hs {:.4} m, peak wavelength {}\n",
                t.method,
                t.spectrum,
                t.target_std_m,
                t.target_hs_m,
                opt(t.target_peak_wavelength_m, 2, " m")
            );
            s += &format!(
                "measured/target variance {}, RMS log10 spectrum difference {} over {} bins\n",
                opt(t.variance_ratio, 3, ""),
                opt(t.log10_rms_difference, 3, ""),
                t.bins_compared
            );
        }
        (None, Some(note)) => s += &format!("target: none ({note})\n"),
        (None, None) => s += "target: none\n",
    }
    s += &format!(
        "radial spectrum: {} bins of {:.4} rad/m (--json for the values)\n",
        a.radial_spectrum.len(),
        a.dk_rad_per_m
    );
    s
}

/// The Jacobian line of the text report.
fn jacobian_report(j: &Result<JacobianStats, String>) -> String {
    match j {
        Ok(j) => format!(
            "J: fraction below {:.4} (foam) {:.5}{}, min {:.4} ({})\n",
            j.threshold,
            j.fraction_below,
            j.whitecap_coverage.map_or(String::new(), |w| format!(
                " (auto: the whitecap coverage W {w:.5} of the wind, Monahan & O'Muircheartaigh 1980)"
            )),
            j.min,
            match j.source {
                "map" => "from the Jacobian map",
                _ => "the sidecar's field regenerated",
            }
        ),
        Err(note) => format!("J: {note}\n"),
    }
}

/// The wave statistics' lines of the text report.
fn wave_report(w: &WaveStats, hs: f64) -> String {
    let mut s = String::new();
    s += &format!(
        "surface: skewness {:.4}, kurtosis {:.4} (Gaussian 0, 3), fraction above 3σ {:.5} (Gaussian {:.5})\n",
        w.skewness, w.kurtosis, w.exceed_3sigma, w.exceed_3sigma_gaussian
    );
    s += &format!(
        "mean-square slope {:.5}, Cox–Munk clean surface {} (the grid resolves only part of it)\n",
        w.mean_square_slope,
        opt(w.cox_munk_mss, 5, "")
    );
    s += &format!(
        "zero-crossing waves along {} transects at {:.1}°: {} waves, H1/3 {} ({} Hs), Hmax {}\n",
        w.transects,
        w.transect_direction_deg,
        w.waves.count,
        opt(w.waves.h_third_m, 3, " m"),
        opt(w.waves.h_third_over_hs, 3, ""),
        opt(w.waves.h_max_m, 3, " m")
    );
    s += &format!(
        "crests: {}, Cmax {} ({} Hs); S1 {}, Ur {}, Tm01 {}; Forristall α {}, β {}\n",
        w.crests.count,
        opt(w.crests.c_max_m, 3, " m"),
        opt(w.crests.c_max_m.filter(|_| hs > 0.0).map(|c| c / hs), 3, ""),
        opt(w.crests.steepness_s1, 4, ""),
        opt(w.crests.ursell, 4, ""),
        opt(w.crests.mean_period_tm01_s, 2, " s"),
        opt(w.crests.forristall_alpha, 4, ""),
        opt(w.crests.forristall_beta, 4, "")
    );
    if let Some(e) = w.crests.exceedance.iter().find(|e| e.level_hs == 0.8) {
        s += &format!(
            "  P(C > 0.8 Hs): measured {:.5}, Rayleigh {:.5}, Forristall {} (--json for the table)\n",
            e.measured,
            e.rayleigh,
            opt(e.forristall, 5, "")
        );
    }
    s
}

/// Draws `--plot-waves`: the crest and height exceedance of the report (and of the
/// `--compare` file's crests).
#[cfg(feature = "plot")]
fn write_wave_plot(staged: Staged, args: &AnalyzeArgs, r: &Report) -> anyhow::Result<()> {
    let name = args
        .file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| r.file.clone());
    let other = match &args.compare {
        Some(path) => {
            // The other file is read with the same options: its mapping and spacing.
            use crate::measure::{analyze, waves::wave_statistics};
            use crate::pipeline::analysis::{read_file, sea_context};
            let loaded = read_file(path, args.height_range.as_deref(), args.extent.as_deref())?;
            let a = analyze(&loaded.grid, None);
            let w = wave_statistics(&loaded.grid, &a, &sea_context(loaded.sidecar.as_ref()));
            let n = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            Some((n, w))
        }
        None => None,
    };
    let image = crate::plot::waves::render_wave_plot(
        r.waves,
        &name,
        other.as_ref().map(|(n, w)| (n.as_str(), w)),
    )
    .map_err(|e| Error::io(&staged.path, e))?;
    crate::export::rgb8::write(staged, &image, crate::plot::waves::WAVE_PLOT_SIZE)?;
    Ok(())
}
