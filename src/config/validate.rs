//! Validation of [`Params`]: every value checked once, where parameters are resolved; a
//! valid `Params` can always be synthesized.

use super::{AlphaConfig, Beta, Method, NoiseBasis, NoiseFractal, Params, Range2, SpectrumModel};
use crate::error::ParamError;

/// Largest samples per side, and in all (the memory of one field stays under 4 GiB).
pub const MAX_SIDE: usize = 1 << 16;
pub use crate::limits::MAX_SAMPLES;

fn err(name: &str, allowed: &str, got: impl std::fmt::Display) -> ParamError {
    ParamError {
        name: name.to_string(),
        allowed: allowed.to_string(),
        got: got.to_string(),
    }
}

/// A number as the user would write it, short: exponent form when very large or small.
fn num(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && a.is_finite() && !(1e-6..1e15).contains(&a) {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

fn positive(name: &str, unit: &str, v: f64) -> Result<(), ParamError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(err(name, &format!("a finite number > 0{unit}"), num(v)))
    }
}

fn non_negative(name: &str, unit: &str, v: f64) -> Result<(), ParamError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(err(name, &format!("a finite number ≥ 0{unit}"), num(v)))
    }
}

fn finite(name: &str, v: f64) -> Result<(), ParamError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(err(name, "a finite number", num(v)))
    }
}

/// Largest height scale of any parameter, meters (and the Phillips amplitude's bound):
/// fields are stored as 32-bit floats, and sums of many components of this size stay far
/// below their range (about 3.4e38).
pub const MAX_SCALE: f64 = 1e6;

/// The lower end of a [`Bounded`] value.
#[derive(Clone, Copy)]
enum Lower {
    Positive,
    NonNegative,
}

/// A number with a lower end and a largest value: one line per parameter in
/// [`Params::bounded`], checked by one loop.
struct Bounded {
    name: &'static str,
    unit: &'static str,
    value: f64,
    lower: Lower,
    max: f64,
}

fn check_bounded(b: &Bounded) -> Result<(), ParamError> {
    let low_ok = match b.lower {
        Lower::Positive => b.value > 0.0,
        Lower::NonNegative => b.value >= 0.0,
    };
    if b.value.is_finite() && low_ok && b.value <= b.max {
        return Ok(());
    }
    let low = match b.lower {
        Lower::Positive => "> 0",
        Lower::NonNegative => "≥ 0",
    };
    Err(err(
        b.name,
        &format!("a finite number {low} and ≤ {:e}{}", b.max, b.unit),
        num(b.value),
    ))
}

impl Params {
    /// Values with a largest allowed size (height scales, amplitudes): fields stay finite.
    /// A new scale parameter is one more line here.
    fn bounded(&self) -> Vec<Bounded> {
        use Lower::{NonNegative, Positive};
        let b = |name, unit, value, lower, max| Bounded {
            name,
            unit,
            value,
            lower,
            max,
        };
        let s = &self.spectrum;
        let mut v = vec![
            b("spectrum.phillips_a", "", s.phillips_a, Positive, MAX_SCALE),
            b(
                "perlin.amplitude_m",
                " m",
                self.perlin.amplitude_m,
                NonNegative,
                MAX_SCALE,
            ),
            b(
                "fractal.relief_m",
                " m",
                self.fractal.relief_m,
                Positive,
                MAX_SCALE,
            ),
            b(
                "blend.beta_scale",
                "",
                self.blend.beta_scale,
                NonNegative,
                MAX_SCALE,
            ),
        ];
        if let Beta::Meters(m) = self.blend.beta {
            v.push(b("blend.beta", " m", m, NonNegative, MAX_SCALE));
        }
        if let Some(h) = s.hs_m {
            v.push(b("--hs (spectrum.hs_m)", " m", h, Positive, 1e3));
        }
        if let Some(t) = s.tp_s {
            v.push(b("--tp (spectrum.tp_s)", " s", t, Positive, 1e4));
        }
        if let Some(a) = self.trochoid.amplitude_m {
            v.push(b("trochoid.amplitude_m", " m", a, NonNegative, MAX_SCALE));
        }
        v
    }

    /// Checks every value once; a valid `Params` can always be synthesized.
    pub fn validate(&self) -> Result<(), ParamError> {
        let [nx, ny] = self.grid.size.0;
        // A trochoid field is evaluated strip by strip: it may be far larger than memory.
        let (max_side, max_samples) = match self.method {
            Method::Trochoid => (
                super::trochoid::MAX_STREAM_SIDE,
                super::trochoid::MAX_STREAM_SAMPLES,
            ),
            _ => (MAX_SIDE, MAX_SAMPLES as u64),
        };
        for (axis, n) in [("x", nx), ("y", ny)] {
            if !(2..=max_side).contains(&n) {
                return Err(err(
                    &format!("--size (grid.size, {axis})"),
                    &format!("between 2 and {max_side} samples"),
                    n,
                ));
            }
        }
        if nx as u64 * ny as u64 > max_samples {
            return Err(err(
                "--size (grid.size)",
                &format!("at most {max_samples} samples in all"),
                format!("{nx}x{ny}"),
            ));
        }
        for (axis, l) in [
            ("x", self.grid.extent_m.0[0]),
            ("y", self.grid.extent_m.0[1]),
        ] {
            positive(&format!("--extent (grid.extent_m, {axis})"), " m", l)?;
        }
        if self.seed > i64::MAX as u64 {
            return Err(err(
                "--seed (seed)",
                &format!("between 0 and {}", i64::MAX),
                self.seed,
            ));
        }
        finite("--time (time_s)", self.time_s)?;
        let w = &self.wind;
        if !(w.speed_mps.is_finite() && w.speed_mps > 0.0 && w.speed_mps <= 100.0) {
            return Err(err(
                "--wind-speed (wind.speed_mps)",
                "> 0 and ≤ 100 m/s",
                w.speed_mps,
            ));
        }
        finite("--wind-dir (wind.direction_deg)", w.direction_deg)?;
        let s = &self.spectrum;
        positive("spectrum.phillips_a", "", s.phillips_a)?;
        non_negative("spectrum.small_wave_m", " m", s.small_wave_m)?;
        let p = &self.perlin;
        if !(1..=24).contains(&p.octaves) {
            return Err(err("perlin.octaves", "between 1 and 24", p.octaves));
        }
        if !(p.persistence > 0.0 && p.persistence < 1.0) {
            return Err(err("perlin.persistence", "> 0 and < 1", p.persistence));
        }
        if !(p.lacunarity.is_finite() && p.lacunarity > 1.0 && p.lacunarity <= 16.0) {
            return Err(err("perlin.lacunarity", "> 1 and ≤ 16", p.lacunarity));
        }
        positive("perlin.wavelength_m", " m", p.wavelength_m)?;
        non_negative("perlin.amplitude_m", " m", p.amplitude_m)?;
        if p.basis == NoiseBasis::Builtin && p.fractal != NoiseFractal::Fbm {
            return Err(err(
                "perlin.fractal",
                "fbm with perlin.basis = builtin (billow, ridged-multi and hybrid-multi need a noise-rs basis: perlin, open-simplex, super-simplex, value or worley)",
                p.fractal.name(),
            ));
        }
        if p.basis == NoiseBasis::SuperSimplex && p.tileable {
            return Err(err(
                "perlin.tileable",
                "false with perlin.basis = super-simplex (it has no 4D form to tile on)",
                p.tileable,
            ));
        }
        match &self.blend.alpha {
            AlphaConfig::Constant { value } => {
                if !(0.0..=1.0).contains(value) {
                    return Err(err("blend.alpha.value", "between 0 and 1", value));
                }
            }
            AlphaConfig::Ramp { power, .. } => positive("blend.alpha.power", "", *power)?,
            AlphaConfig::Radial {
                power,
                center_m,
                radius_m,
            } => {
                positive("blend.alpha.power", "", *power)?;
                if let Some(c) = center_m {
                    finite("blend.alpha.center_m (x)", c[0])?;
                    finite("blend.alpha.center_m (y)", c[1])?;
                }
                if let Some(r) = radius_m {
                    positive("blend.alpha.radius_m", " m", *r)?;
                }
            }
            AlphaConfig::Image { path, .. } => {
                if !path.is_file() {
                    return Err(err(
                        "blend.alpha.path",
                        "an existing image file",
                        path.display(),
                    ));
                }
            }
        }
        if let Beta::Meters(b) = self.blend.beta {
            non_negative("blend.beta", " m", b)?;
        }
        non_negative("blend.beta_scale", "", self.blend.beta_scale)?;
        if let Some(Range2([lo, hi])) = self.output.height_range {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(err(
                    "--height-range (output.height_range)",
                    "MIN:MAX with finite MIN < MAX",
                    format!("{lo}:{hi}"),
                ));
            }
        }
        self.trochoid.validate()?;
        if self.method == Method::Trochoid && self.motion.choppiness != 0.0 {
            return Err(err(
                "--choppiness (motion.choppiness)",
                "0 with --method trochoid (its profile is already Gerstner's: trochoid.sharpness)",
                self.motion.choppiness,
            ));
        }
        self.validate_nonlinear()?;
        self.validate_sea()?;
        self.bounded().iter().try_for_each(check_bounded)
    }

    /// `spectrum.nonlinear = second-order`: the `fft` method of a physical spectrum,
    /// without choppiness; the fraction in (0, 1].
    fn validate_nonlinear(&self) -> Result<(), ParamError> {
        use super::Nonlinear;
        const KEY: &str = "--nonlinear (spectrum.nonlinear)";
        if let Some(q) = self.spectrum.nonlinear_fraction {
            if !(q > 0.0 && q <= 1.0) {
                return Err(err(
                    "spectrum.nonlinear_fraction",
                    "a fraction of the variance, 0 < q <= 1",
                    q,
                ));
            }
        }
        if let Some(c) = self.spectrum.nonlinear_cutoff {
            if c.is_nan() || c <= 0.0 {
                return Err(err(
                    "spectrum.nonlinear_cutoff",
                    "a convergence criterion C > 0 (2: convergence, 0.5: no bump in the \
                     trough; inf: every wave)",
                    c,
                ));
            }
        }
        if self.spectrum.nonlinear == Nonlinear::Linear {
            return Ok(());
        }
        if !matches!(self.method, Method::Fft | Method::Hybrid) {
            return Err(err(
                KEY,
                "linear unless --method fft or hybrid (the bound waves are those of the FFT \
                 sea's random spectrum, which the other methods do not draw)",
                "second-order",
            ));
        }
        if matches!(
            self.spectrum.model,
            SpectrumModel::Phillips | SpectrumModel::Fractal
        ) {
            return Err(err(
                KEY,
                "linear with the phillips and fractal spectra (second-order needs a physical \
                 sea: pierson-moskowitz, jonswap or tma)",
                "second-order",
            ));
        }
        if self.motion.choppiness != 0.0 {
            return Err(err(
                "--choppiness (motion.choppiness)",
                "0 with --nonlinear second-order (the bound waves already shape the crests; \
                 a displacement of them has no consistent second-order meaning)",
                self.motion.choppiness,
            ));
        }
        Ok(())
    }

    /// The grid these parameters describe.
    pub fn grid_spec(&self) -> crate::grid::GridSpec {
        let [nx, ny] = self.grid.size.0;
        let [lx, ly] = self.grid.extent_m.0;
        crate::grid::GridSpec::new(nx, ny, lx, ly)
    }
}

impl Params {
    fn validate_sea(&self) -> Result<(), ParamError> {
        let s = &self.spectrum;
        non_negative("spectrum.swell", "", s.swell)?;
        if s.swell > 10.0 {
            return Err(err("spectrum.swell", "between 0 and 10", s.swell));
        }
        positive("--fetch-km (spectrum.fetch_km)", " km", s.fetch_km)?;
        if let Some(d) = s.depth_m {
            positive("--depth (spectrum.depth_m)", " m", d)?;
        }
        if !(s.gamma.is_finite() && (1.0..=20.0).contains(&s.gamma)) {
            return Err(err("--gamma (spectrum.gamma)", "between 1 and 20", s.gamma));
        }
        match (s.hs_m, s.tp_s) {
            (Some(h), Some(t)) => {
                positive("--hs (spectrum.hs_m)", " m", h)?;
                positive("--tp (spectrum.tp_s)", " s", t)?;
                if !s.model.is_physical_sea() {
                    return Err(err(
                        "--hs/--tp",
                        "used with --spectrum pierson-moskowitz, jonswap or tma",
                        format!("--spectrum {}", model_name(s.model)),
                    ));
                }
            }
            (None, None) => {}
            (Some(_), None) => return Err(err("--tp (spectrum.tp_s)", "given with --hs", "none")),
            (None, Some(_)) => return Err(err("--hs (spectrum.hs_m)", "given with --tp", "none")),
        }
        if s.model == SpectrumModel::Tma && s.depth_m.is_none() {
            return Err(err(
                "--depth (spectrum.depth_m)",
                "set for --spectrum tma",
                "none",
            ));
        }
        let f = &self.fractal;
        if !(f.dimension > 2.0 && f.dimension < 3.0) {
            return Err(err("fractal.dimension", "> 2 and < 3", f.dimension));
        }
        positive("fractal.relief_m", " m", f.relief_m)?;
        if let Some(r) = f.rolloff_m {
            positive("fractal.rolloff_m", " m", r)?;
        }
        let m = &self.motion;
        if let Some(t) = m.loop_period_s {
            positive("--loop-period (motion.loop_period_s)", " s", t)?;
        }
        finite("--choppiness (motion.choppiness)", m.choppiness)?;
        if m.choppiness.abs() > 10.0 {
            return Err(err(
                "--choppiness (motion.choppiness)",
                "between -10 and 10",
                m.choppiness,
            ));
        }
        if let Some(t) = m.foam_threshold.fixed() {
            finite("--foam-threshold (motion.foam_threshold)", t)?;
            if !(t > 0.0 && t <= 2.0) {
                return Err(err(
                    "--foam-threshold (motion.foam_threshold)",
                    "auto, or a number > 0 and ≤ 2",
                    t,
                ));
            }
        }
        if !(m.foam_fade_s.is_finite() && (0.0..=60.0).contains(&m.foam_fade_s)) {
            return Err(err(
                "--foam-fade (motion.foam_fade_s)",
                "0 (off) … 60 s",
                num(m.foam_fade_s),
            ));
        }
        positive("--fps (motion.fps)", " frames/s", m.fps)?;
        if m.fps > 1000.0 {
            return Err(err("--fps (motion.fps)", "≤ 1000 frames/s", m.fps));
        }
        for (name, v) in [
            ("motion.hot_air_dominant_rad", m.hot_air_dominant_rad),
            ("motion.hot_air_other_rad", m.hot_air_other_rad),
        ] {
            finite(name, v)?;
            if v.abs() >= std::f64::consts::PI {
                return Err(err(name, "between -π and π radians per frame", v));
            }
        }
        if let Some(v) = m.translate_speed_mps {
            finite("motion.translate_speed_mps", v)?;
        }
        Ok(())
    }
}

/// The name of a spectrum model as written in presets.
pub fn model_name(m: SpectrumModel) -> String {
    serde_json::to_value(m)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}
/// Refuses a field too large to hold in memory (only streamed outputs can be larger).
pub fn check_in_memory(params: &super::Params) -> Result<(), ParamError> {
    let [nx, ny] = params.grid.size.0;
    if nx > MAX_SIDE || ny > MAX_SIDE || nx * ny > MAX_SAMPLES {
        return Err(ParamError {
            name: "--size (grid.size)".into(),
            allowed: format!(
                "at most {MAX_SIDE} per side and {MAX_SAMPLES} samples in all when the field is held in memory (only .png and .tif outputs of --method trochoid are streamed)"
            ),
            got: format!("{nx}x{ny}"),
        });
    }
    Ok(())
}
