//! What `seasynth analyze` measures of a height map (the conventions are stated in
//! [`crate::measure`]): statistics, the measured wavenumber spectrum against the one it
//! was generated from when its sidecar says so, wave-by-wave statistics and the Jacobian
//! of a choppy field; the command line and the Python package print the same report.

use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::Value;

use crate::config::Params;
use crate::error::Error;
use crate::grid::{Grid, GridSpec};
use crate::io::{ImageKind, Loaded, ReadOptions, load_with};
use crate::measure::foam::FoamRule;
use crate::measure::jacobian::{JacobianStats, jacobian_stats};
use crate::measure::waves::{SeaContext, WaveStats, wave_statistics};
use crate::measure::{Analysis, Target, analyze};

/// What `analyze --json` prints: the file, then the [`Analysis`].
#[derive(Serialize)]
pub struct Report<'a> {
    pub file: String,
    pub format: ImageKind,
    pub spacing_source: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quantization_step_m: Option<f64>,
    #[serde(flatten)]
    pub analysis: &'a Analysis,
    /// Wave-by-wave statistics.
    pub waves: &'a WaveStats,
    /// J below the foam threshold, for a choppy field or one with a Jacobian map.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub jacobian: Option<&'a JacobianStats>,
}

/// A height map analyzed: what the report holds.
pub struct Analyzed {
    pub file: PathBuf,
    pub loaded: Loaded,
    pub analysis: Analysis,
    pub waves: WaveStats,
    /// The Jacobian statistics, or why there are none.
    pub jacobian: Result<JacobianStats, String>,
}

impl Analyzed {
    /// The report `analyze --json` prints.
    pub fn report(&self) -> Report<'_> {
        Report {
            file: self.file.display().to_string(),
            format: self.loaded.kind,
            spacing_source: self.loaded.spacing_source,
            quantization_step_m: self.loaded.quantization_step_m,
            analysis: &self.analysis,
            waves: &self.waves,
            jacobian: self.jacobian.as_ref().ok(),
        }
    }
}

/// Reads and analyzes the height map `path` (see [`read_file`] for the flags).
pub fn analyze_file(
    path: &Path,
    height_range: Option<&str>,
    extent: Option<&str>,
) -> Result<Analyzed, Error> {
    let loaded = read_file(path, height_range, extent)?;
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
    let mut analysis = analyze(&loaded.grid, target.as_ref());
    if analysis.target_note.is_none() {
        analysis.target_note = note;
    }
    let waves = wave_statistics(
        &loaded.grid,
        &analysis,
        &sea_context(loaded.sidecar.as_ref()),
    );
    let jacobian = jacobian_of(path, &loaded)?;
    Ok(Analyzed {
        file: path.to_path_buf(),
        loaded,
        analysis,
        waves,
        jacobian,
    })
}

/// The report of heights in meters given as values (no file, no sidecar): the keys of
/// `analyze --json` but the file's, with `spacing_source` = `"extent"`.
pub fn analyze_heights(grid: &Grid) -> Result<Value, Error> {
    let analysis = analyze(grid, None);
    let waves = wave_statistics(grid, &analysis, &SeaContext::default());
    #[derive(Serialize)]
    struct HeightsReport<'a> {
        spacing_source: &'static str,
        #[serde(flatten)]
        analysis: &'a Analysis,
        waves: &'a WaveStats,
    }
    serde_json::to_value(HeightsReport {
        spacing_source: "extent",
        analysis: &analysis,
        waves: &waves,
    })
    .map_err(|e| Error::NotFinite {
        what: "the analysis".into(),
        detail: e.to_string(),
    })
}

/// Reads `path` with `analyze`'s input flags (`--height-range` for integer images
/// without a mapping, `--extent` for the spacing).
pub fn read_file(
    path: &Path,
    height_range: Option<&str>,
    extent: Option<&str>,
) -> Result<Loaded, Error> {
    let opts = ReadOptions::parse(height_range, extent)?;
    load_with(path, &opts)
}

/// What the wave statistics take from a sidecar's `params`: the wind speed and the depth.
pub fn sea_context(sidecar: Option<&Value>) -> SeaContext {
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
pub fn jacobian_of(file: &Path, loaded: &Loaded) -> Result<Result<JacobianStats, String>, Error> {
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
fn read_jacobian_map(path: &Path, nx: usize, ny: usize) -> Result<Vec<f32>, Error> {
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
