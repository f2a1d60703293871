//! `seasynth analyze`: statistics and the measured wavenumber spectrum of a height map,
//! compared with the spectrum it was generated from when its sidecar says so (the
//! conventions are stated in [`crate::measure`]).

use serde::Serialize;
use serde_json::Value;

use crate::cli::AnalyzeArgs;
use crate::commands::common::PLOTS;
use crate::config::Params;
use crate::error::Error;
use crate::export::Staged;
use crate::grid::GridSpec;
use crate::io::{ImageKind, Loaded, ReadOptions, load_with};
use crate::measure::foam::FoamRule;
use crate::measure::jacobian::{JacobianStats, jacobian_stats};
use crate::measure::waves::{SeaContext, WaveStats, wave_statistics};
use crate::measure::{Analysis, Target, analyze};
use crate::plot::analysis::{PLOT_SIZE, render_plot};

/// What `analyze --json` prints: the file, then the [`Analysis`].
#[derive(Serialize)]
struct Report<'a> {
    file: String,
    format: ImageKind,
    spacing_source: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    quantization_step_m: Option<f64>,
    #[serde(flatten)]
    analysis: &'a Analysis,
    /// Wave-by-wave statistics.
    waves: &'a WaveStats,
    /// J below the foam threshold, for a choppy field or one with a Jacobian map.
    #[serde(skip_serializing_if = "Option::is_none")]
    jacobian: Option<&'a JacobianStats>,
}

/// Runs `seasynth analyze`.
pub fn run(args: AnalyzeArgs) -> anyhow::Result<()> {
    // The plot file is staged before any work: a bad path fails now, and an error later
    // leaves no partial file.
    let plot = args
        .plot
        .as_deref()
        .map(|p| Staged::create_checked(p, &PLOTS, &[(&args.file, "is the file being analyzed")]))
        .transpose()?;
    let loaded = read_input(&args)?;
    let (target, note) = match &loaded.sidecar {
        Some(doc) => match target_from_sidecar(doc, &loaded.grid.spec) {
            Ok(t) => (Some(t), None),
            Err(note) => (None, Some(note)),
        },
        None => (
            None,
            Some("no sidecar, so there is no target spectrum".to_string()),
        ),
    };
    let plot_waves = args
        .plot_waves
        .as_deref()
        .map(|p| Staged::create_checked(p, &PLOTS, &[(&args.file, "is the file being analyzed")]))
        .transpose()?;
    let mut analysis = analyze(&loaded.grid, target.as_ref());
    if analysis.target_note.is_none() {
        analysis.target_note = note;
    }
    let waves = wave_statistics(
        &loaded.grid,
        &analysis,
        &sea_context(loaded.sidecar.as_ref()),
    );
    let jacobian = jacobian_of(&args.file, &loaded)?;
    let report = Report {
        file: args.file.display().to_string(),
        format: loaded.kind,
        spacing_source: loaded.spacing_source,
        quantization_step_m: loaded.quantization_step_m,
        analysis: &analysis,
        waves: &waves,
        jacobian: jacobian.as_ref().ok(),
    };
    if let Some(staged) = plot_waves {
        write_wave_plot(staged, &args, &report)?;
    }
    if let Some(staged) = plot {
        let name = args
            .file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| report.file.clone());
        let image = render_plot(&analysis, &name).map_err(|e| Error::io(&staged.path, e))?;
        crate::export::rgb8::write(staged, &image, PLOT_SIZE)?;
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        serde_json::to_writer(&mut out, &report)?;
        std::io::Write::write_all(&mut out, b"\n")?;
    } else {
        std::io::Write::write_all(&mut out, human_report(&report).as_bytes())?;
        std::io::Write::write_all(&mut out, wave_report(&waves, analysis.hs_m).as_bytes())?;
        std::io::Write::write_all(&mut out, jacobian_report(&jacobian).as_bytes())?;
    }
    Ok(())
}

/// The height map of `analyze FILE`: any image read, with `--height-range` for integer
/// images without a mapping and `--extent` for the spacing.
fn read_input(args: &AnalyzeArgs) -> Result<Loaded, Error> {
    read_file(&args.file, args)
}

/// Reads `path` with the input flags of `args` (`--height-range`, `--extent`).
fn read_file(path: &std::path::Path, args: &AnalyzeArgs) -> Result<Loaded, Error> {
    let opts = ReadOptions::parse(args.height_range.as_deref(), args.extent.as_deref())?;
    load_with(path, &opts)
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

/// What the wave statistics take from a sidecar's `params`: the wind speed and the depth.
fn sea_context(sidecar: Option<&Value>) -> SeaContext {
    let params = sidecar
        .and_then(|d| d.get("params"))
        .and_then(|p| serde_json::from_value::<Params>(p.clone()).ok());
    match params {
        Some(p) => SeaContext {
            wind_speed_mps: Some(p.wind.speed_mps),
            depth_m: p.spectrum.depth_m,
        },
        None => SeaContext::default(),
    }
}

/// The Jacobian statistics of the field in `file`: read from the Jacobian map beside it
/// (`NAME.jacobian.tif`, else `NAME.jacobian.exr`) when there is one, else from the field
/// its sidecar describes synthesized again when that is choppy. The threshold is the
/// sidecar's `motion.foam_threshold` resolved over these J, else 0.3. `Ok(Err(note))`:
/// none, and why.
fn jacobian_of(
    file: &std::path::Path,
    loaded: &Loaded,
) -> Result<Result<JacobianStats, String>, Error> {
    let params: Option<Params> = loaded
        .sidecar
        .as_ref()
        .and_then(|d| d.get("params"))
        .and_then(|p| serde_json::from_value(p.clone()).ok());
    // The threshold of the maps: the sidecar's `motion.foam_threshold` resolved over
    // these J (a quantile for "auto"), or 0.3 without parameters.
    let rule = params.as_ref().map_or(
        FoamRule::Threshold(crate::measure::foam::FALLBACK_THRESHOLD),
        FoamRule::of,
    );
    let spec = &loaded.grid.spec;
    for ext in ["jacobian.tif", "jacobian.exr"] {
        let path = file.with_extension(ext);
        if path.is_file() {
            let j = read_jacobian_map(&path, spec.nx, spec.ny)?;
            return Ok(Ok(jacobian_stats(&j, rule, "map")));
        }
    }
    let Some(params) = params.filter(|p| p.motion.choppiness != 0.0) else {
        return Ok(Err("not a choppy field".into()));
    };
    Ok(regenerate_jacobian(&params, spec).map(|j| jacobian_stats(&j, rule, "regenerated")))
}

/// J of a Jacobian map written by seasynth: a one-channel float TIFF or an EXR's `Y`
/// channel, `nx`×`ny` like the height map.
fn read_jacobian_map(path: &std::path::Path, nx: usize, ny: usize) -> Result<Vec<f32>, Error> {
    let bad = |e: String| crate::io::input_error(path, format!("not a readable Jacobian map: {e}"));
    let (w, h, j) = if path.extension().is_some_and(|e| e == "exr") {
        let (w, h, channels) =
            crate::export::exr::read_channels(path).map_err(|e| bad(e.to_string()))?;
        let j = channels
            .into_iter()
            .find(|(name, _)| name == "Y")
            .map(|(_, v)| v)
            .ok_or_else(|| bad("no channel Y".into()))?;
        (w, h, j)
    } else {
        crate::export::tiff32::read(path).map_err(|e| bad(e.to_string()))?
    };
    if (w, h) != (nx, ny) || j.len() != nx * ny {
        return Err(crate::io::input_error(
            path,
            format!(
                "the Jacobian map holds {} values on {w}×{h} pixels but the height map is {nx}×{ny}",
                j.len()
            ),
        ));
    }
    Ok(j)
}

/// J of the choppy field that `params` (a sidecar's) describe on `spec`, synthesized
/// again (bit for bit the field that was written); `Err` says why it cannot be.
fn regenerate_jacobian(params: &Params, spec: &GridSpec) -> Result<Vec<f32>, String> {
    let not = |why: String| format!("not measured: {why}");
    params
        .validate()
        .map_err(|e| not(format!("the sidecar's `params` are not valid ({e})")))?;
    let [nx, ny] = params.grid.size.0;
    if (nx, ny) != (spec.nx, spec.ny) {
        return Err(not(format!(
            "the sidecar's `params` describe a {nx}×{ny} grid but the image is {}×{}",
            spec.nx, spec.ny
        )));
    }
    let extras = crate::field::dynamics::Extras {
        jacobian: true,
        ..Default::default()
    };
    crate::limits::check_memory(
        crate::pipeline::memory::Footprint::of_field(params, extras).bytes(spec.len() as u64, 1),
        &format!(
            "the {nx}x{ny} {} field of the sidecar",
            params.method.name()
        ),
        false,
    )
    .map_err(|e| not(e.to_string()))?;
    let synthesis = crate::field::Synthesizer::new(params, extras, false)
        .map_err(|e| not(format!("the sidecar's field cannot be synthesized ({e})")))?
        .frame(params.time_s);
    let j = synthesis
        .surface
        .jacobian
        .ok_or_else(|| not("the method gives no Jacobian".into()))?;
    Ok(j.values(spec.len()).into_owned())
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
fn write_wave_plot(staged: Staged, args: &AnalyzeArgs, r: &Report) -> anyhow::Result<()> {
    let name = args
        .file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| r.file.clone());
    let other = match &args.compare {
        Some(path) => {
            // The other file is read with the same options: its mapping and spacing.
            let loaded = read_file(path, args)?;
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

/// The methods whose fields follow their spectrum model as a whole, so that a measured
/// spectrum has a target (`field::HeightMethod::follows_spectrum`).
fn comparable_methods() -> Vec<&'static str> {
    let mut params = Params::default();
    crate::config::Method::ALL
        .iter()
        .filter(|&&m| {
            params.method = m;
            crate::field::method_for(&params).follows_spectrum()
        })
        .map(|m| m.name())
        .collect()
}

/// The target described by a sidecar's `params`, for a field on `spec`; `Err` says in one
/// sentence why there is none.
pub fn target_from_sidecar(sidecar: &Value, spec: &GridSpec) -> Result<Target, String> {
    let raw = sidecar
        .get("params")
        .ok_or("the sidecar has no `params`, so there is no target spectrum")?;
    let params: Params = serde_json::from_value(raw.clone())
        .map_err(|e| format!("the sidecar's `params` do not parse ({e}); no target"))?;
    let method = params.method.name().to_string();
    if !crate::field::method_for(&params).follows_spectrum() {
        return Err(match method.as_str() {
            "hybrid" => "method hybrid: only the alpha = 1 region follows the spectrum, \
                         so the whole field has no target spectrum"
                .to_string(),
            m => format!(
                "method {m} does not follow a spectrum model; targets exist for {}",
                comparable_methods().join(", ")
            ),
        });
    }
    params
        .validate()
        .map_err(|e| format!("the sidecar's `params` are not valid ({e}); no target"))?;
    let pspec = params.grid_spec();
    if (pspec.nx, pspec.ny) != (spec.nx, spec.ny) {
        return Err(format!(
            "the sidecar's `params` describe a {}×{} grid but the image is {}×{}; no target",
            pspec.nx, pspec.ny, spec.nx, spec.ny
        ));
    }
    if !crate::measure::same_length(pspec.extent_x_m, spec.extent_x_m)
        || !crate::measure::same_length(pspec.extent_y_m, spec.extent_y_m)
    {
        return Err(format!(
            "the sidecar's `params` describe a {} m × {} m extent but the spacing gives {} m × {} m; no target",
            pspec.extent_x_m, pspec.extent_y_m, spec.extent_x_m, spec.extent_y_m
        ));
    }
    let model = serde_json::to_value(params.spectrum.model)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_else(|| "?".into());
    let (spectrum, _dispersion) = crate::field::spectrum_model(&params)
        .map_err(|e| format!("the sidecar's spectrum cannot be built ({e}); no target"))?;
    Ok(Target {
        spectrum,
        spec: pspec,
        method,
        model,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::spectrum::tests::cosine;

    #[test]
    fn a_target_on_another_grid_is_ignored_with_a_note() {
        let params = Params::default();
        let (spectrum, _) = crate::field::spectrum_model(&params).unwrap();
        let t = Target {
            spectrum,
            spec: params.grid_spec(),
            method: "fft".into(),
            model: "phillips".into(),
        };
        let a = analyze(&cosine(16, 16.0, 4.0, 0.0, 1.0), Some(&t));
        assert!(a.target.is_none());
        assert!(a.target_note.unwrap().contains("another grid"));
    }

    #[test]
    fn the_expected_spectrum_of_a_synthesized_field_matches_its_measured_one_on_average() {
        // Average of three seeds of the FFT method at 128² over 128 m at 3 m/s: the
        // measured variance is the sum of |h̃(k)|², whose expectation is the target.
        const RATIO_TOL: f64 = 0.1;
        let mut ratio = 0.0;
        for seed in 1..=3 {
            let mut p = Params {
                method: crate::config::Method::Fft,
                seed,
                ..Params::default()
            };
            p.grid.size = crate::config::Size2([128, 128]);
            p.grid.extent_m = crate::config::Extent2([128.0, 128.0]);
            p.wind.speed_mps = 3.0;
            let g = crate::field::synthesize(&p).unwrap().grid;
            let side = serde_json::json!({ "params": serde_json::to_value(&p).unwrap() });
            let t = target_from_sidecar(&side, &g.spec).unwrap();
            let a = analyze(&g, Some(&t));
            ratio += a.target.unwrap().variance_ratio.unwrap() / 3.0;
        }
        assert!(
            (ratio - 1.0).abs() < RATIO_TOL,
            "mean variance ratio {ratio}"
        );
    }
}
