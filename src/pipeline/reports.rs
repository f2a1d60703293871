//! The reports `seasynth spectrum --json/--csv` and `seasynth analyze --json` print, as
//! text or JSON values the command line and the Python package share.

use std::path::Path;

use serde::Serialize;

use crate::config::validate::model_name;
use crate::config::{Params, SpectrumModel};
use crate::error::Error;
use crate::field::{SeaModel, sea_model};
use crate::grid::{Grid, GridSpec};

/// One point of the frequency spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Point {
    pub f_hz: f64,
    pub s_m2_per_hz: f64,
}

/// What `--json` prints.
#[derive(Debug, Serialize)]
pub struct Report<'a> {
    /// The model name as in presets (`pierson-moskowitz`, `jonswap`, `tma`).
    pub spectrum: String,
    /// F(f) at the requested frequencies, in the order given.
    pub points: Vec<Point>,
    /// Significant wave height of the model, 4·√m0, m.
    pub hs_m: f64,
    /// Frequency where F is largest, Hz.
    pub fp_hz: f64,
    /// Peak period 1/fp, s.
    pub tp_s: f64,
    /// m0 = ∫F df = (hs_m/4)², m².
    pub m0_m2: f64,
    /// Wavenumber of the peak frequency through the dispersion relation, rad/m.
    pub kp_rad_per_m: f64,
    /// 2π/kp, m (compare `analyze --json`'s `peak_wavelength_m`).
    pub peak_wavelength_m: f64,
    /// The fully resolved parameters.
    pub params: &'a Params,
}

/// Why a model has no frequency spectrum in m²/Hz, for `--freq` and `--plot`.
pub fn no_frequency_spectrum(model: SpectrumModel) -> String {
    let what = match model {
        SpectrumModel::Phillips => {
            "phillips is a discrete wavenumber spectrum (Tessendorf's convention: A multiplies the \
             discrete Fourier amplitudes)"
        }
        _ => "fractal is a wavenumber power law for terrain, without dispersion",
    };
    format!(
        "{what}, so it has no frequency spectrum in m²/Hz; use a physical model \
         (--spectrum pierson-moskowitz, jonswap or tma)"
    )
}

/// A number as JSON writes it (shortest text that reads back to the same f64).
pub fn number_text(v: f64) -> String {
    serde_json::to_string(&v).unwrap_or_else(|_| v.to_string())
}

/// The CSV text: header `f_hz,s_m2_per_hz`, then one row per point.
pub fn csv_text(points: &[Point]) -> String {
    let mut s = String::from("f_hz,s_m2_per_hz\n");
    for p in points {
        s.push_str(&number_text(p.f_hz));
        s.push(',');
        s.push_str(&number_text(p.s_m2_per_hz));
        s.push('\n');
    }
    s
}

/// The `--json` (or with `csv`, the `--csv`) text of F(f) at `freqs`.
pub fn points_text(
    params: &Params,
    sea: &SeaModel,
    freqs: &[f64],
    csv: bool,
) -> Result<String, serde_json::Error> {
    let points: Vec<Point> = freqs
        .iter()
        .map(|&f| Point {
            f_hz: f,
            s_m2_per_hz: sea.freq.density(f),
        })
        .collect();
    if csv {
        return Ok(csv_text(&points));
    }
    let hs = sea.freq.hs_m();
    let fp = sea.freq.peak_hz();
    let kp = sea.dispersion.wavenumber(std::f64::consts::TAU * fp);
    let report = Report {
        spectrum: model_name(params.spectrum.model),
        points,
        hs_m: hs,
        fp_hz: fp,
        tp_s: 1.0 / fp,
        m0_m2: (hs / 4.0) * (hs / 4.0),
        kp_rad_per_m: kp,
        peak_wavelength_m: std::f64::consts::TAU / kp,
        params,
    };
    Ok(serde_json::to_string_pretty(&report)? + "\n")
}

/// The `--json` report of the model spectrum of `params` at `freqs` (Hz); a model
/// without a frequency spectrum (`phillips`, `fractal`) is refused.
pub fn spectrum_json(params: &Params, freqs: &[f64]) -> anyhow::Result<String> {
    let sea = sea_model(params)?.ok_or_else(|| Error::Set {
        origin: "spectrum".into(),
        message: no_frequency_spectrum(params.spectrum.model),
    })?;
    Ok(points_text(params, &sea, freqs, false)?)
}

/// The `--json` report of `seasynth analyze FILE`; `options`: its input flags as
/// (flag, value) pairs (`--height-range`, `--extent`).
pub fn analyze_file_json(path: &Path, options: &[(String, String)]) -> anyhow::Result<String> {
    let flag = |name: &str| {
        options
            .iter()
            .find(|(f, _)| f == name)
            .map(|(_, v)| v.as_str())
    };
    for (f, v) in options {
        if f != "--height-range" && f != "--extent" {
            return Err(Error::Set {
                origin: format!("{f} {v}"),
                message: "analyze takes --height-range and --extent".into(),
            }
            .into());
        }
    }
    let analyzed =
        crate::pipeline::analysis::analyze_file(path, flag("--height-range"), flag("--extent"))?;
    Ok(serde_json::to_string(&analyzed.report())?)
}

/// The `--json` report of heights in meters, row-major `nx`×`ny`, over `extent_x_m` ×
/// `extent_y_m` (the file's keys left out); values must be finite.
pub fn analyze_array_json(
    data: Vec<f32>,
    nx: usize,
    ny: usize,
    extent_x_m: f64,
    extent_y_m: f64,
) -> anyhow::Result<String> {
    for (name, v) in [("extent x", extent_x_m), ("extent y", extent_y_m)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::Param(crate::error::ParamError {
                name: format!("the {name}"),
                allowed: "a finite length > 0 m".into(),
                got: v.to_string(),
            })
            .into());
        }
    }
    if nx < 2 || ny < 2 {
        return Err(Error::Param(crate::error::ParamError {
            name: "the array's shape".into(),
            allowed: "at least 2×2 samples".into(),
            got: format!("{ny}×{nx}"),
        })
        .into());
    }
    if let Some(i) = data.iter().position(|v| !v.is_finite()) {
        return Err(Error::Param(crate::error::ParamError {
            name: "the heights".into(),
            allowed: "finite values".into(),
            got: format!("{} at row {}, column {}", data[i], i / nx, i % nx),
        })
        .into());
    }
    let grid = Grid {
        spec: GridSpec::new(nx, ny, extent_x_m, extent_y_m),
        data,
    };
    let value = crate::pipeline::analysis::analyze_heights(&grid)?;
    Ok(serde_json::to_string(&value)?)
}
