//! One-sided frequency spectra F(f) in m²/Hz (f in Hz): Pierson–Moskowitz (Mastin eq. 1–2,
//! Thon eq. 5–6), JONSWAP and TMA.
//!
//! All three share one parametric form (a [`JonswapShape`]):
//!
//! F(f) = A · f⁻⁵ · exp(−5/4 (fp/f)⁴) · γ^r(f) · Φ(ω_h),
//! r = exp(−(f − fp)² / (2 σ² fp²)), σ = 0.07 for f ≤ fp, 0.09 above,
//!
//! with A = α g² (2π)⁻⁴ (Phillips' α), γ = 1 for Pierson–Moskowitz, and Kitaigorodskii's
//! depth factor Φ (TMA only, else 1). γ^r is computed as exp(r·ln γ), so the density stays
//! finite and positive for every valid input.
//!
//! Significant wave height Hs = 4·√m0, m0 = ∫F df: closed form for Pierson–Moskowitz,
//! otherwise a composite Gauss–Legendre integral in ln f computed once at construction
//! (relative error below 1e-9; see [`JonswapShape::m0_numeric`]).
//!
//! Elementary functions are [`crate::fastmath`]'s, so values are bit-identical on every
//! platform.

use super::G;
use crate::error::ParamError;
use crate::fastmath::{exp, ln};

const TWO_PI: f64 = 2.0 * std::f64::consts::PI;

/// Phillips' constant of the Pierson–Moskowitz spectrum (Mastin eq. 1).
pub const PM_ALPHA: f64 = 0.0081;
/// fm = 0.13 g / U10 (Mastin eq. 2).
pub const PM_PEAK_COEF: f64 = 0.13;
/// JONSWAP peak width below and above the peak.
pub const SIGMA_LOW: f64 = 0.07;
pub const SIGMA_HIGH: f64 = 0.09;
/// Allowed peak enhancement γ.
pub const GAMMA_MIN: f64 = 1.0;
pub const GAMMA_MAX: f64 = 20.0;

/// One-sided frequency spectrum F(f) in m²/Hz, f in Hz.
pub trait FrequencySpectrum: Send + Sync + std::fmt::Debug {
    /// F(f) ≥ 0, finite; 0 for f ≤ 0 (and for NaN).
    fn density(&self, f_hz: f64) -> f64;
    /// The frequency where F is largest, Hz.
    fn peak_hz(&self) -> f64;
    /// 4·√m0 of the model, m: closed form where it exists (PM), else a numerical integral
    /// computed once at construction.
    fn hs_m(&self) -> f64;
    /// The JONSWAP-family parameters, when the model is one: lets
    /// [`DirectionalSpectrum`](super::DirectionalSpectrum) evaluate F inline, without a
    /// virtual call per wavevector. `density` must equal `shape().density` bit for bit.
    fn shape(&self) -> Option<JonswapShape> {
        None
    }
}

fn param(name: &str, allowed: &str, got: impl std::fmt::Display) -> ParamError {
    ParamError {
        name: name.to_string(),
        allowed: allowed.to_string(),
        got: got.to_string(),
    }
}

fn positive(name: &str, unit: &str, v: f64) -> Result<f64, ParamError> {
    if v > 0.0 && v.is_finite() {
        Ok(v)
    } else {
        Err(param(name, &format!("> 0{unit}"), v))
    }
}

pub(crate) const WIND_SPEED: &str = "--wind-speed (wind.speed_mps)";
const HS: &str = "--hs (spectrum.hs_m)";
const TP: &str = "--tp (spectrum.tp_s)";
const GAMMA: &str = "--gamma (spectrum.gamma)";
const FETCH: &str = "--fetch-km (spectrum.fetch_km)";
pub(crate) const DEPTH: &str = "--depth (spectrum.depth_m)";

fn check_gamma(gamma: f64) -> Result<f64, ParamError> {
    if (GAMMA_MIN..=GAMMA_MAX).contains(&gamma) {
        Ok(gamma)
    } else {
        Err(param(GAMMA, "between 1 and 20", gamma))
    }
}

/// Kitaigorodskii's depth factor Φ(ω_h), ω_h = ω·√(d/g): ½ω_h² for ω_h ≤ 1,
/// 1 − ½(2 − ω_h)² for 1 < ω_h < 2, 1 above (continuous with a continuous slope).
#[inline]
pub fn kitaigorodskii(omega_h: f64) -> f64 {
    if omega_h <= 1.0 {
        0.5 * omega_h * omega_h
    } else if omega_h < 2.0 {
        let d = 2.0 - omega_h;
        1.0 - 0.5 * d * d
    } else {
        1.0
    }
}

/// F(f) = A f⁻⁵ exp(−5/4 (fp/f)⁴) · γ^r · Φ(ω_h): the form shared by every model here.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JonswapShape {
    a: f64,
    fp_hz: f64,
    gamma: f64,
    depth_m: f64,
    // Derived.
    a_over_fp5: f64,
    ln_gamma: f64,
    /// 2π·√(d/g): ω_h = f·this (∞ in deep water).
    omega_h_per_hz: f64,
}

/// 1/(2σ²) below and above the peak.
pub(crate) const C_LOW: f64 = 1.0 / (2.0 * SIGMA_LOW * SIGMA_LOW);
pub(crate) const C_HIGH: f64 = 1.0 / (2.0 * SIGMA_HIGH * SIGMA_HIGH);

impl JonswapShape {
    /// `a` > 0 (m²·Hz⁴), `fp_hz` > 0, γ ≥ 1, `depth_m` > 0 or +∞ (no depth factor).
    /// Callers validate.
    pub(crate) fn new(a: f64, fp_hz: f64, gamma: f64, depth_m: f64) -> Self {
        let fp5 = fp_hz * fp_hz * fp_hz * fp_hz * fp_hz;
        Self {
            a,
            fp_hz,
            gamma,
            depth_m,
            a_over_fp5: a / fp5,
            ln_gamma: if gamma == 1.0 { 0.0 } else { ln(gamma) },
            omega_h_per_hz: if depth_m.is_finite() {
                TWO_PI * (depth_m / G).sqrt()
            } else {
                f64::INFINITY
            },
        }
    }

    /// The coefficient A of f⁻⁵, m²·Hz⁴ (A = α g² (2π)⁻⁴).
    pub fn a(&self) -> f64 {
        self.a
    }
    /// Phillips' α equivalent to A.
    pub fn alpha(&self) -> f64 {
        self.a * TWO_PI.powi(4) / (G * G)
    }
    /// The peak frequency of the PM/JONSWAP part, Hz.
    pub fn fp_hz(&self) -> f64 {
        self.fp_hz
    }
    pub fn gamma(&self) -> f64 {
        self.gamma
    }
    pub(crate) fn ln_gamma(&self) -> f64 {
        self.ln_gamma
    }
    /// Depth of the TMA factor, m (+∞: none).
    pub fn depth_m(&self) -> f64 {
        self.depth_m
    }

    /// F(f) in m²/Hz.
    #[inline]
    pub fn density(&self, f_hz: f64) -> f64 {
        if f_hz.is_nan() || f_hz <= 0.0 || f_hz == f64::INFINITY {
            return 0.0;
        }
        let iq = self.fp_hz / f_hz;
        let iq2 = iq * iq;
        let u = iq2 * iq2;
        // exp(−1.25·u) underflows to 0 (and f⁻⁵ would overflow far below here).
        if u > 640.0 {
            return 0.0;
        }
        let mut e = -1.25 * u;
        if self.ln_gamma != 0.0 {
            let d = f_hz / self.fp_hz - 1.0;
            let a = d * d * if d <= 0.0 { C_LOW } else { C_HIGH };
            // Far from the peak γ^r = 1 (and exp would take its slow path).
            if a < 700.0 {
                e += self.ln_gamma * exp(-a);
            }
        }
        let phi = if self.omega_h_per_hz.is_finite() {
            kitaigorodskii(f_hz * self.omega_h_per_hz)
        } else {
            1.0
        };
        self.a_over_fp5 * (iq2 * iq2 * iq) * exp(e) * phi
    }

    /// m0 = A/(5 fp⁴) of the Pierson–Moskowitz part alone (γ = 1, no depth factor).
    pub fn m0_pm(&self) -> f64 {
        let fp2 = self.fp_hz * self.fp_hz;
        self.a / (5.0 * fp2 * fp2)
    }

    /// ∫₀^∞ F df by composite 10-point Gauss–Legendre in u = ln f on panels of width
    /// ≤ 0.02, with panel breaks at the peak (σ switches) and at the kinks of Φ, from
    /// 0.05 fp (where F < e⁻²⁰⁰⁰⁰⁰ of its peak) to max(200 fp, 4 f(ω_h = 2)), plus the
    /// exact tail beyond (F = A f⁻⁵ exp(−5/4 (fp/f)⁴) there: γ^r = 1 and Φ = 1 to
    /// double precision). Relative error below 1e-9.
    pub fn m0_numeric(&self) -> f64 {
        let fp = self.fp_hz;
        let lo = 0.05 * fp;
        let mut hi = 200.0 * fp;
        let mut breaks = vec![lo, fp];
        if self.omega_h_per_hz.is_finite() {
            for wh in [1.0, 2.0] {
                let f = wh / self.omega_h_per_hz;
                if f > lo {
                    breaks.push(f);
                }
                hi = hi.max(4.0 * f);
            }
        }
        breaks.push(hi);
        breaks.sort_by(f64::total_cmp);
        let rule = gauss_legendre(10);
        let mut m0 = 0.0;
        for w in breaks.windows(2) {
            let (ua, ub) = (ln(w[0]), ln(w[1]));
            m0 += integrate(
                |u| {
                    let f = exp(u);
                    self.density(f) * f
                },
                ua,
                ub,
                ((ub - ua) / 0.02).ceil().max(1.0) as usize,
                &rule,
            );
        }
        // Tail: ∫_hi^∞ A f⁻⁵ exp(−b f⁻⁴) df = A/(4b)·(1 − exp(−b hi⁻⁴)), b = 5/4 fp⁴.
        let y = 1.25 * (fp / hi).powi(4);
        let one_minus = if y < 1e-4 {
            y * (1.0 - 0.5 * y)
        } else {
            1.0 - exp(-y)
        };
        m0 + self.m0_pm() * one_minus
    }

    /// The frequency of the maximum of F: fp without a depth factor; otherwise found
    /// numerically (a log grid from 0.3 fp to 6 fp, refined by golden-section search on
    /// ln F to 1e-12 relative).
    pub fn peak_numeric(&self) -> f64 {
        if !self.omega_h_per_hz.is_finite() {
            return self.fp_hz;
        }
        let n = 4000;
        let (a, b) = (ln(0.3 * self.fp_hz), ln(6.0 * self.fp_hz));
        let at = |i: usize| exp(a + (b - a) * i as f64 / n as f64);
        let mut best = 0;
        let mut best_v = -1.0;
        for i in 0..=n {
            let v = self.density(at(i));
            if v > best_v {
                best_v = v;
                best = i;
            }
        }
        let (mut lo, mut hi) = (at(best.saturating_sub(1)), at((best + 1).min(n)));
        let ratio = (5f64.sqrt() - 1.0) / 2.0;
        let mut x1 = hi - ratio * (hi - lo);
        let mut x2 = lo + ratio * (hi - lo);
        let (mut f1, mut f2) = (self.density(x1), self.density(x2));
        for _ in 0..200 {
            if hi - lo <= 1e-13 * hi {
                break;
            }
            if f1 < f2 {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + ratio * (hi - lo);
                f2 = self.density(x2);
            } else {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - ratio * (hi - lo);
                f1 = self.density(x1);
            }
        }
        0.5 * (lo + hi)
    }
}

/// Gauss–Legendre nodes and weights of order `n` ≥ 1 on (−1, 1), nodes ascending, by
/// Newton's method on the Legendre recurrence (to machine precision; basic operations
/// only, so the same on every platform).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    assert!(n >= 1, "Gauss–Legendre order");
    let mut out = Vec::with_capacity(n);
    let nf = n as f64;
    for i in 0..n {
        // Tricomi's initial guess for the i-th root (descending), then Newton.
        let theta = std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5);
        let mut x = crate::fastmath::sin_cos(theta).1;
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, d) = legendre(n, x);
            dp = d;
            let step = p / d;
            x -= step;
            if step.abs() <= 1e-16 {
                let (_, d) = legendre(n, x);
                dp = d;
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out.push((x, w));
    }
    out.reverse();
    // Exact symmetry.
    for i in 0..n / 2 {
        let (x, w) = out[n - 1 - i];
        out[i] = (-x, w);
    }
    if n % 2 == 1 {
        out[n / 2].0 = 0.0;
    }
    out
}

/// P_n(x) and P_n'(x).
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    if n == 0 {
        return (1.0, 0.0);
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

/// ∫_a^b g by `panels` equal panels of the Gauss–Legendre rule `rule`.
pub(crate) fn integrate(
    g: impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    panels: usize,
    rule: &[(f64, f64)],
) -> f64 {
    let h = (b - a) / panels as f64;
    let mut total = 0.0;
    for p in 0..panels {
        let mid = a + (p as f64 + 0.5) * h;
        let mut s = 0.0;
        for &(x, w) in rule {
            s += w * g(mid + 0.5 * h * x);
        }
        total += 0.5 * h * s;
    }
    total
}

/// Fully developed sea (Mastin eq. 1–2): F(f) = α g² (2π)⁻⁴ f⁻⁵ exp(−5/4 (fm/f)⁴).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PiersonMoskowitz {
    shape: JonswapShape,
}

impl PiersonMoskowitz {
    /// General form: α > 0, fm > 0 Hz.
    pub fn new(alpha: f64, fm_hz: f64) -> Result<Self, ParamError> {
        positive("spectrum α", "", alpha)?;
        positive("spectrum peak frequency", " Hz", fm_hz)?;
        Ok(Self {
            shape: JonswapShape::new(alpha * G * G / TWO_PI.powi(4), fm_hz, 1.0, f64::INFINITY),
        })
    }

    /// α = 0.0081, fm = 0.13 g / U10; U10 > 0 m/s.
    pub fn from_wind(u10_mps: f64) -> Result<Self, ParamError> {
        positive(WIND_SPEED, " m/s", u10_mps)?;
        Self::new(PM_ALPHA, PM_PEAK_COEF * G / u10_mps)
    }

    /// The PM shape with fm = 1/Tp and α such that 4√m0 = Hs exactly (DNV-RP-C205:
    /// S(ω) = 5/16 Hs² ωp⁴ ω⁻⁵ exp(−5/4 (ω/ωp)⁻⁴), F(f) = 2π S(2πf), i.e.
    /// A = 5/16 Hs² fp⁴).
    pub fn from_hs_tp(hs_m: f64, tp_s: f64) -> Result<Self, ParamError> {
        positive(HS, " m", hs_m)?;
        positive(TP, " s", tp_s)?;
        let fp = 1.0 / tp_s;
        let fp2 = fp * fp;
        Ok(Self {
            shape: JonswapShape::new(5.0 / 16.0 * hs_m * hs_m * fp2 * fp2, fp, 1.0, f64::INFINITY),
        })
    }

    pub fn alpha(&self) -> f64 {
        self.shape.alpha()
    }
    pub fn fm_hz(&self) -> f64 {
        self.shape.fp_hz
    }
    /// m0 = α g² / (5 (2π)⁴ fm⁴), m².
    pub fn m0(&self) -> f64 {
        self.shape.m0_pm()
    }
}

impl FrequencySpectrum for PiersonMoskowitz {
    fn density(&self, f_hz: f64) -> f64 {
        self.shape.density(f_hz)
    }
    fn peak_hz(&self) -> f64 {
        self.shape.fp_hz
    }
    fn hs_m(&self) -> f64 {
        4.0 * self.m0().sqrt()
    }
    fn shape(&self) -> Option<JonswapShape> {
        Some(self.shape)
    }
}

/// Fetch-limited sea: the PM shape times the peak enhancement γ^r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jonswap {
    shape: JonswapShape,
    hs_m: f64,
    fetch_m: Option<f64>,
}

impl Jonswap {
    /// General form: α > 0, fp > 0 Hz, 1 ≤ γ ≤ 20.
    pub fn new(alpha: f64, fp_hz: f64, gamma: f64) -> Result<Self, ParamError> {
        positive("spectrum α", "", alpha)?;
        positive("spectrum peak frequency", " Hz", fp_hz)?;
        check_gamma(gamma)?;
        Ok(Self::from_shape(
            JonswapShape::new(alpha * G * G / TWO_PI.powi(4), fp_hz, gamma, f64::INFINITY),
            None,
        ))
    }

    fn from_shape(shape: JonswapShape, fetch_m: Option<f64>) -> Self {
        Self {
            shape,
            hs_m: 4.0 * shape.m0_numeric().sqrt(),
            fetch_m,
        }
    }

    /// The fetch beyond which the sea is fully developed: where the fetch law's peak
    /// 22 (g²/(U F))^{1/3} reaches the Pierson–Moskowitz peak 2π·0.13 g/U, i.e.
    /// F = g² / (U (2π·0.13 g/(22 U))³) ≈ 19 900 U²/g (199 km at 10 m/s).
    pub fn fully_developed_fetch_m(u10_mps: f64) -> f64 {
        let w = TWO_PI * PM_PEAK_COEF * G / (22.0 * u10_mps);
        G * G / (u10_mps * w * w * w)
    }

    /// Standard JONSWAP fetch laws (F in m): ω_p = 22 (g²/(U F))^{1/3},
    /// α = 0.076 (U²/(F g))^{0.22}. U > 0 m/s, F > 0, 1 ≤ γ ≤ 20.
    ///
    /// Cap: a fetch longer than [`fully_developed_fetch_m`](Self::fully_developed_fetch_m)
    /// is clamped to it, so the peak never falls below the fully developed PM peak
    /// 0.13 g/U (and α, continuous in the fetch, stays at its value there, ≈ 0.0086).
    pub fn from_wind_fetch(u10_mps: f64, fetch_m: f64, gamma: f64) -> Result<Self, ParamError> {
        positive(WIND_SPEED, " m/s", u10_mps)?;
        if !(fetch_m > 0.0 && fetch_m.is_finite()) {
            return Err(param(FETCH, "> 0 km", fetch_m / 1000.0));
        }
        check_gamma(gamma)?;
        let fetch = fetch_m.min(Self::fully_developed_fetch_m(u10_mps));
        let omega_p = 22.0 * exp(ln(G * G / (u10_mps * fetch)) / 3.0);
        let alpha = 0.076 * exp(0.22 * ln(u10_mps * u10_mps / (fetch * G)));
        let a = alpha * G * G / TWO_PI.powi(4);
        Ok(Self::from_shape(
            JonswapShape::new(a, omega_p / TWO_PI, gamma, f64::INFINITY),
            Some(fetch),
        ))
    }

    /// DNV-RP-C205: S(ω) = A_γ · S_PM(ω; Hs, ωp = 2π/Tp) · γ^r, A_γ = 1 − 0.287 ln γ.
    /// A_γ makes 4√m0 only approximately Hs: within 0.15 % for γ ≤ 5, 1 % at γ = 7,
    /// 3.6 % at γ = 10 and 22 % low at γ = 20 ([`hs_m`](FrequencySpectrum::hs_m) reports
    /// the model's own value); [`from_hs_tp_exact`](Self::from_hs_tp_exact) rescales instead.
    pub fn from_hs_tp(hs_m: f64, tp_s: f64, gamma: f64) -> Result<Self, ParamError> {
        positive(HS, " m", hs_m)?;
        positive(TP, " s", tp_s)?;
        check_gamma(gamma)?;
        let fp = 1.0 / tp_s;
        let fp2 = fp * fp;
        let a_gamma = 1.0 - 0.287 * ln(gamma);
        let a = a_gamma * 5.0 / 16.0 * hs_m * hs_m * fp2 * fp2;
        Ok(Self::from_shape(
            JonswapShape::new(a, fp, gamma, f64::INFINITY),
            None,
        ))
    }

    /// The JONSWAP shape of peak period Tp and enhancement γ, scaled so that 4√m0 = Hs
    /// (to the accuracy of the numerical m0, 1e-9).
    pub fn from_hs_tp_exact(hs_m: f64, tp_s: f64, gamma: f64) -> Result<Self, ParamError> {
        positive(HS, " m", hs_m)?;
        positive(TP, " s", tp_s)?;
        check_gamma(gamma)?;
        let fp = 1.0 / tp_s;
        let unit = JonswapShape::new(1.0, fp, gamma, f64::INFINITY);
        let a = hs_m * hs_m / 16.0 / unit.m0_numeric();
        Ok(Self::from_shape(
            JonswapShape::new(a, fp, gamma, f64::INFINITY),
            None,
        ))
    }

    pub fn alpha(&self) -> f64 {
        self.shape.alpha()
    }
    pub fn fp_hz(&self) -> f64 {
        self.shape.fp_hz
    }
    pub fn gamma(&self) -> f64 {
        self.shape.gamma
    }
    /// The fetch used by [`from_wind_fetch`](Self::from_wind_fetch) after the cap, m.
    pub fn effective_fetch_m(&self) -> Option<f64> {
        self.fetch_m
    }
}

impl FrequencySpectrum for Jonswap {
    fn density(&self, f_hz: f64) -> f64 {
        self.shape.density(f_hz)
    }
    fn peak_hz(&self) -> f64 {
        self.shape.fp_hz
    }
    fn hs_m(&self) -> f64 {
        self.hs_m
    }
    fn shape(&self) -> Option<JonswapShape> {
        Some(self.shape)
    }
}

/// JONSWAP in water of depth d: F_TMA(f) = F_JONSWAP(f) · Φ(2πf √(d/g)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tma {
    jonswap: Jonswap,
    shape: JonswapShape,
    peak_hz: f64,
    hs_m: f64,
}

impl Tma {
    /// `depth_m` > 0 (+∞ allowed: exactly the JONSWAP).
    pub fn new(jonswap: Jonswap, depth_m: f64) -> Result<Self, ParamError> {
        if depth_m.is_nan() || depth_m <= 0.0 {
            return Err(param(DEPTH, "> 0 m", depth_m));
        }
        let j = jonswap.shape;
        let shape = JonswapShape::new(j.a, j.fp_hz, j.gamma, depth_m);
        Ok(Self {
            jonswap,
            shape,
            peak_hz: shape.peak_numeric(),
            hs_m: 4.0 * shape.m0_numeric().sqrt(),
        })
    }

    /// [`Jonswap::from_wind_fetch`] in water of depth `depth_m`.
    pub fn from_wind_fetch(
        u10_mps: f64,
        fetch_m: f64,
        gamma: f64,
        depth_m: f64,
    ) -> Result<Self, ParamError> {
        Self::new(Jonswap::from_wind_fetch(u10_mps, fetch_m, gamma)?, depth_m)
    }

    /// [`Jonswap::from_hs_tp`] (the deep-water Hs and Tp) in water of depth `depth_m`.
    pub fn from_hs_tp(hs_m: f64, tp_s: f64, gamma: f64, depth_m: f64) -> Result<Self, ParamError> {
        Self::new(Jonswap::from_hs_tp(hs_m, tp_s, gamma)?, depth_m)
    }

    pub fn jonswap(&self) -> &Jonswap {
        &self.jonswap
    }
    pub fn depth_m(&self) -> f64 {
        self.shape.depth_m
    }
    /// Φ at frequency `f_hz`.
    pub fn depth_factor(&self, f_hz: f64) -> f64 {
        if self.shape.omega_h_per_hz.is_finite() {
            kitaigorodskii(f_hz * self.shape.omega_h_per_hz)
        } else {
            1.0
        }
    }
}

impl FrequencySpectrum for Tma {
    fn density(&self, f_hz: f64) -> f64 {
        self.shape.density(f_hz)
    }
    fn peak_hz(&self) -> f64 {
        self.peak_hz
    }
    fn hs_m(&self) -> f64 {
        self.hs_m
    }
    fn shape(&self) -> Option<JonswapShape> {
        Some(self.shape)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const REL_FORMULA: f64 = 1e-13;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        const TOL: f64 = 1e-14;
        for n in 1..=20 {
            let rule = gauss_legendre(n);
            let wsum: f64 = rule.iter().map(|r| r.1).sum();
            assert!((wsum - 2.0).abs() < TOL, "n = {n}: Σw = {wsum}");
            for deg in 0..2 * n {
                let q: f64 = rule.iter().map(|&(x, w)| w * x.powi(deg as i32)).sum();
                let want = if deg % 2 == 1 {
                    0.0
                } else {
                    2.0 / (deg as f64 + 1.0)
                };
                assert!((q - want).abs() < TOL, "n = {n}, x^{deg}: {q} vs {want}");
            }
        }
    }

    #[test]
    fn pierson_moskowitz_matches_the_formula_by_hand() {
        // Mastin eq. 1 evaluated with std's powf/exp, independently of the shape code.
        for u in [5.0, 10.0, 15.0, 25.0] {
            let pm = PiersonMoskowitz::from_wind(u).unwrap();
            let fm = 0.13 * G / u;
            assert!(rel(pm.fm_hz(), fm) < REL_FORMULA, "fm at U = {u}");
            for ratio in [0.5, 0.8, 1.0, 1.3, 2.0, 5.0] {
                let f = ratio * fm;
                let want = 0.0081
                    * G
                    * G
                    * (2.0 * std::f64::consts::PI).powf(-4.0)
                    * f.powf(-5.0)
                    * (-1.25 * (fm / f).powf(4.0)).exp();
                let got = pm.density(f);
                assert!(
                    rel(got, want) < REL_FORMULA,
                    "U {u}, f/fm {ratio}: {got} vs {want}"
                );
            }
        }
        // Literal values (computed separately): U = 15 m/s → fm = 0.08502 Hz,
        // F(fm) = 0.0081·9.81²/(2π)⁴·fm⁻⁵·e^{−5/4} = 32.2574 m²/Hz.
        let pm = PiersonMoskowitz::from_wind(15.0).unwrap();
        assert!(rel(pm.peak_hz(), 0.08502) < 1e-12, "fm {}", pm.peak_hz());
        let fm: f64 = 0.08502;
        let want = 0.0081 * 96.2361 / 1_558.545_456_544_039 / fm.powi(5) * (-1.25f64).exp();
        assert!(
            rel(pm.density(fm), want) < 1e-9,
            "F(fm) {} vs {want}",
            pm.density(fm)
        );
        assert!(
            rel(pm.density(fm), 32.2574) < 1e-5,
            "F(fm) {}",
            pm.density(fm)
        );
    }

    #[test]
    fn pierson_moskowitz_hs_closed_form() {
        const REL_NUM: f64 = 1e-10;
        for u in [3.0, 10.0, 20.0, 40.0] {
            let pm = PiersonMoskowitz::from_wind(u).unwrap();
            let fm = 0.13 * G / u;
            let m0 = 0.0081 * G * G / (5.0 * (2.0 * std::f64::consts::PI).powi(4) * fm.powi(4));
            assert!(rel(pm.m0(), m0) < REL_FORMULA, "m0 at U = {u}");
            // Hs = 0.2413 U²/g: 0.0246 U².
            let hs = pm.hs_m();
            assert!(rel(hs, 0.24130 * u * u / G) < 1e-4, "Hs {hs} at U = {u}");
            // The classic Hs = 0.21 U19.5²/g, with U19.5 = 1.074 U10 (the ratio that makes
            // PM's ωp = 0.877 g/U19.5 equal fm = 0.13 g/U10).
            let u195 = 1.074 * u;
            assert!(
                rel(hs, 0.21 * u195 * u195 / G) < 0.01,
                "Hs {hs} vs 0.21 U19.5²/g"
            );
            // The numerical integral agrees with the closed form.
            let num = pm.shape.m0_numeric();
            assert!(rel(num, m0) < REL_NUM, "numeric m0 {num} vs {m0}");
        }
    }

    #[test]
    fn jonswap_with_gamma_one_is_pierson_moskowitz() {
        let pm = PiersonMoskowitz::new(0.01, 0.12).unwrap();
        let j = Jonswap::new(0.01, 0.12, 1.0).unwrap();
        for i in 0..200 {
            let f = 0.01 * 1.04f64.powi(i);
            assert_eq!(j.density(f), pm.density(f), "f = {f}");
        }
        assert!(
            rel(j.hs_m(), pm.hs_m()) < 1e-10,
            "{} vs {}",
            j.hs_m(),
            pm.hs_m()
        );
    }

    #[test]
    fn jonswap_fetch_laws_by_hand() {
        // U = 10 m/s, F = 100 km: g²/(U F) = 9.6236e-5, ω_p = 22·(9.6236e-5)^{1/3}
        // = 1.00817 rad/s (fp = 0.160456 Hz); α = 0.076·(100/(1e5·9.81))^0.22 = 0.0100611.
        const REL_HAND: f64 = 1e-5;
        let j = Jonswap::from_wind_fetch(10.0, 100e3, 3.3).unwrap();
        assert!(
            rel(j.fp_hz() * TWO_PI, 1.008_17) < REL_HAND,
            "ω_p {}",
            j.fp_hz() * TWO_PI
        );
        assert!(rel(j.fp_hz(), 0.160_456) < REL_HAND, "fp {}", j.fp_hz());
        assert!(rel(j.alpha(), 0.010_061_1) < REL_HAND, "α {}", j.alpha());
        assert_eq!(j.peak_hz(), j.fp_hz());
        assert_eq!(j.effective_fetch_m(), Some(100e3));
        // Peak enhancement: F(fp) = γ·F_PM(fp).
        let pm = PiersonMoskowitz::new(j.alpha(), j.fp_hz()).unwrap();
        assert!(rel(j.density(j.fp_hz()), 3.3 * pm.density(j.fp_hz())) < 1e-13);
    }

    #[test]
    fn jonswap_fetch_is_capped_at_the_fully_developed_peak() {
        for u in [5.0, 10.0, 20.0] {
            let full = Jonswap::fully_developed_fetch_m(u);
            let pm_peak = 0.13 * G / u;
            // Beyond the cap the spectrum no longer changes, and its peak is PM's.
            let a = Jonswap::from_wind_fetch(u, full, 3.3).unwrap();
            let b = Jonswap::from_wind_fetch(u, 1e9, 3.3).unwrap();
            assert_eq!(a, b, "U {u}");
            assert!(
                rel(b.fp_hz(), pm_peak) < 1e-12,
                "U {u}: fp {} vs {pm_peak}",
                b.fp_hz()
            );
            // Continuity below the cap.
            let c = Jonswap::from_wind_fetch(u, full * (1.0 - 1e-9), 3.3).unwrap();
            assert!(rel(c.fp_hz(), pm_peak) < 1e-8);
            // Shorter fetch: a higher peak, always finite and positive.
            let d = Jonswap::from_wind_fetch(u, 0.1 * full, 3.3).unwrap();
            assert!(d.fp_hz() > pm_peak);
        }
        assert!(rel(Jonswap::fully_developed_fetch_m(10.0), 199_172.5) < 1e-6);
    }

    #[test]
    fn hs_tp_forms_give_the_requested_hs() {
        // PM: exact. JONSWAP (DNV's A_γ): documented tolerance per γ.
        let pm = PiersonMoskowitz::from_hs_tp(3.0, 9.0).unwrap();
        assert!(rel(pm.hs_m(), 3.0) < 1e-13, "PM Hs {}", pm.hs_m());
        assert!(rel(pm.shape.m0_numeric().sqrt() * 4.0, 3.0) < 1e-10);
        assert!(rel(pm.peak_hz(), 1.0 / 9.0) < 1e-15);
        for (gamma, tol) in [
            (1.0, 1e-9),
            (2.0, 0.0015),
            (3.3, 0.0015),
            (5.0, 0.0015),
            (7.0, 0.01),
            (10.0, 0.037),
            (20.0, 0.23),
        ] {
            let j = Jonswap::from_hs_tp(2.0, 8.0, gamma).unwrap();
            assert!(
                rel(j.hs_m(), 2.0) < tol,
                "γ {gamma}: Hs {} (tolerance {tol})",
                j.hs_m()
            );
            let e = Jonswap::from_hs_tp_exact(2.0, 8.0, gamma).unwrap();
            assert!(
                rel(e.hs_m(), 2.0) < 1e-9,
                "exact γ {gamma}: Hs {}",
                e.hs_m()
            );
            assert!(rel(e.density(0.2) / j.density(0.2), e.alpha() / j.alpha()) < 1e-12);
        }
    }

    #[test]
    fn tma_deep_is_jonswap_and_shallow_has_less_low_frequency_energy() {
        let j = Jonswap::from_wind_fetch(12.0, 50e3, 3.3).unwrap();
        let inf = Tma::new(j, f64::INFINITY).unwrap();
        let deep = Tma::new(j, 1e4).unwrap();
        for i in 0..300 {
            let f = 0.02 * 1.02f64.powi(i);
            assert_eq!(inf.density(f), j.density(f), "∞ depth at f = {f}");
            assert_eq!(deep.density(f), j.density(f), "10 km depth at f = {f}");
        }
        assert_eq!(inf.peak_hz(), j.peak_hz());
        assert!(rel(deep.hs_m(), j.hs_m()) < 1e-9);
        let shallow = Tma::new(j, 5.0).unwrap();
        let fp = j.fp_hz();
        for ratio in [0.6, 0.8, 0.95, 1.0] {
            let f = ratio * fp;
            assert!(
                shallow.density(f) < j.density(f),
                "f/fp {ratio}: {} !< {}",
                shallow.density(f),
                j.density(f)
            );
        }
        assert!(shallow.hs_m() < j.hs_m());
        // Φ at hand-picked ω_h.
        assert_eq!(kitaigorodskii(0.5), 0.125);
        assert_eq!(kitaigorodskii(1.0), 0.5);
        assert_eq!(kitaigorodskii(1.5), 0.875);
        assert_eq!(kitaigorodskii(2.0), 1.0);
        let wh = TWO_PI * 0.1 * (5.0 / G).sqrt();
        assert!(rel(shallow.depth_factor(0.1), kitaigorodskii(wh)) < 1e-15);
    }

    #[test]
    fn stays_finite_and_positive_for_extreme_valid_inputs() {
        let mut models: Vec<Box<dyn FrequencySpectrum>> = Vec::new();
        for u in [0.05, 1.0, 70.0, 300.0] {
            models.push(Box::new(PiersonMoskowitz::from_wind(u).unwrap()));
            for fetch in [1.0, 1e3, 1e9] {
                for gamma in [1.0, 20.0] {
                    models.push(Box::new(Jonswap::from_wind_fetch(u, fetch, gamma).unwrap()));
                    models.push(Box::new(
                        Tma::from_wind_fetch(u, fetch, gamma, 0.5).unwrap(),
                    ));
                }
            }
        }
        for m in &models {
            assert!(
                m.hs_m().is_finite() && m.hs_m() > 0.0,
                "{m:?}: Hs {}",
                m.hs_m()
            );
            assert!(m.peak_hz().is_finite() && m.peak_hz() > 0.0, "{m:?}");
            assert!(m.density(m.peak_hz()) > 0.0, "{m:?}: F(peak) = 0");
            for e in -60..=60 {
                let f = 10f64.powf(e as f64 / 10.0);
                let v = m.density(f);
                assert!(v.is_finite() && v >= 0.0, "{m:?}: F({f}) = {v}");
            }
            for f in [
                0.0,
                -1.0,
                f64::NAN,
                f64::INFINITY,
                f64::MIN_POSITIVE,
                5e-324,
            ] {
                assert_eq!(m.density(f), 0.0, "{m:?}: F({f})");
            }
        }
    }

    #[test]
    fn invalid_parameters_name_the_parameter() {
        let e = PiersonMoskowitz::from_wind(-3.0).unwrap_err();
        assert_eq!(e.name, "--wind-speed (wind.speed_mps)");
        assert_eq!(e.allowed, "> 0 m/s");
        assert_eq!(e.got, "-3");
        assert_eq!(
            Jonswap::from_wind_fetch(10.0, 1e4, 0.5).unwrap_err().name,
            "--gamma (spectrum.gamma)"
        );
        assert_eq!(
            Jonswap::from_wind_fetch(10.0, 1e4, 21.0)
                .unwrap_err()
                .allowed,
            "between 1 and 20"
        );
        let f = Jonswap::from_wind_fetch(10.0, -2000.0, 3.3).unwrap_err();
        assert_eq!(
            (f.name.as_str(), f.got.as_str()),
            ("--fetch-km (spectrum.fetch_km)", "-2")
        );
        assert_eq!(
            Jonswap::from_hs_tp(0.0, 8.0, 3.3).unwrap_err().name,
            "--hs (spectrum.hs_m)"
        );
        assert_eq!(
            PiersonMoskowitz::from_hs_tp(1.0, f64::NAN)
                .unwrap_err()
                .name,
            "--tp (spectrum.tp_s)"
        );
        let j = Jonswap::from_wind_fetch(10.0, 1e4, 3.3).unwrap();
        assert_eq!(
            Tma::new(j, 0.0).unwrap_err().name,
            "--depth (spectrum.depth_m)"
        );
        assert!(Tma::new(j, f64::NAN).is_err());
    }
}
