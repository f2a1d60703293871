//! Directional spreading D(f, θ): how the energy at frequency f is shared among the
//! directions θ (radians from the wind direction), normalized so ∫_{−π}^{π} D dθ = 1.
//!
//! - `Cos2`: Phillips' |k̂·ŵ|²: D = cos²θ / π (two-sided).
//! - `Hasselmann` (Mastin eq. 4–6, Thon eq. 8): D = cos^{2p}(θ/2) / N_p,
//!   p = 9.77 (f/fm)^μ, μ = 4.06 below fm, −2.34 from fm up (fm = the spectrum's peak),
//!   N_p = 2^{1−2p} π Γ(2p+1)/Γ(p+1)² = 2√π Γ(p+½)/Γ(p+1) = ∫cos^{2p}(θ/2) dθ.
//! - `Mitsuyasu` (1975): cos^{2s}(θ/2) / N_s, s = s_max (f/fp)⁵ below fp,
//!   s_max (f/fp)^{−2.5} from fp up, s_max = 11.5 (U10/c_p)^{−2.5}, c_p = g/(2π fp)
//!   (U10 ≤ 0 gives s_max = 0).
//! - `DonelanBanner` (1985): D = β/(2 tanh βπ) · sech²(βθ), θ wrapped to (−π, π], with
//!   r = f/fp: β = 2.61 r^{1.3} for r < 0.95, 2.28 r^{−1.3} for 0.95 ≤ r < 1.6,
//!   10^{−0.4 + 0.8393 exp(−0.567 ln r²)} from 1.6 up. Below r = 0.56 (outside the fit's
//!   data) β is held at its value at 0.56.
//! - Swell (Horvath 2015): every model times |cos(θ/2)|^{2 s_ξ}, s_ξ = 16 tanh(fp/f) ξ²,
//!   renormalized: for the cos^{2p}(θ/2) family the exponents add (N of the sum); for
//!   `Cos2` the normalizer is exact by Wallis' recurrence,
//!   ∫cos²θ cos^{2s}(θ/2) dθ = N_s (1 − 2(2s+1)/((2s+2)(s+2))); for `DonelanBanner` it is a
//!   numerical integral (a composite Gauss–Legendre rule, relative error < 1e-12).
//!
//! `f ≤ 0` is taken as the limit f → 0⁺. The functions here are the reference
//! implementation; [`DirectionalSpectrum`](super::DirectionalSpectrum) evaluates the same
//! formulas through a table of the per-frequency quantities built at its construction.

use std::sync::OnceLock;

use crate::error::ParamError;
use crate::fastmath::{exp, ln, sin_cos};

use super::G;
use super::frequency::{gauss_legendre, integrate};

mod cos2;
mod donelan_banner;
mod hasselmann;
mod mitsuyasu;

pub(crate) use cos2::ln_z_cos2;
pub use donelan_banner::donelan_banner_beta;
pub(crate) use donelan_banner::{DB_R_1, DB_R_2, DB_R_MIN, db_beta_branch, donelan_banner_norm};
pub(crate) use hasselmann::log2_np_f32;
pub use hasselmann::{ln_gamma, ln_np, np_hasselmann, p_hasselmann};
pub use mitsuyasu::{mitsuyasu_s, mitsuyasu_s_max};

const PI: f64 = std::f64::consts::PI;
const TWO_PI: f64 = 2.0 * PI;
/// ln(2√π).
pub(crate) const LN_2_SQRT_PI: f64 = 1.265_512_123_484_645_4;
/// Largest allowed swell parameter ξ.
pub const SWELL_MAX: f64 = 10.0;

/// The spreading models.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpreadingModel {
    Cos2,
    Hasselmann,
    Mitsuyasu,
    DonelanBanner,
}

/// A validated spreading model with optional swell narrowing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spreading {
    pub model: SpreadingModel,
    /// ξ ≥ 0 (0 = off).
    pub swell: f64,
}

impl Spreading {
    /// `swell` = ξ in [0, 10].
    pub fn new(model: SpreadingModel, swell: f64) -> Result<Self, ParamError> {
        if !(0.0..=SWELL_MAX).contains(&swell) {
            return Err(ParamError {
                name: "spectrum.swell".into(),
                allowed: "between 0 and 10".into(),
                got: swell.to_string(),
            });
        }
        Ok(Self { model, swell })
    }

    /// D(f, θ) in 1/rad, given the spectrum's peak frequency `fp_hz` > 0 and the wind
    /// speed (used by `Mitsuyasu` only). θ is any real (2π-periodic).
    pub fn density(&self, f_hz: f64, fp_hz: f64, u10_mps: f64, theta: f64) -> f64 {
        let r = if f_hz > 0.0 { f_hz / fp_hz } else { 0.0 };
        let theta = wrap_abs(theta);
        let c = sin_cos(theta).1;
        let sx = swell_exponent(r, self.swell);
        match self.model {
            SpreadingModel::Cos2 => {
                if sx == 0.0 {
                    c * c / PI
                } else {
                    c * c * exp(sx * ln_half_one_plus(c) - ln_z_cos2(sx))
                }
            }
            SpreadingModel::Hasselmann | SpreadingModel::Mitsuyasu => {
                let s = self.model_exponent(r, fp_hz, u10_mps) + sx;
                exp(s * ln_half_one_plus(c) - ln_np(s))
            }
            SpreadingModel::DonelanBanner => {
                let beta = donelan_banner_beta(r);
                let sech2 = sech2(beta * theta);
                if sx == 0.0 {
                    beta / (2.0 * tanh(beta * PI)) * sech2
                } else {
                    sech2 * exp(sx * ln_half_one_plus(c)) / donelan_banner_norm(beta, sx)
                }
            }
        }
    }

    /// The exponent s of cos^{2s}(θ/2) of `Hasselmann` (p) and `Mitsuyasu` (s) at
    /// r = f/fp, without swell; 0 for the other models.
    pub fn model_exponent(&self, r: f64, fp_hz: f64, u10_mps: f64) -> f64 {
        match self.model {
            SpreadingModel::Hasselmann => p_hasselmann(r, 1.0),
            SpreadingModel::Mitsuyasu => mitsuyasu_s(r, 1.0, mitsuyasu_s_max(u10_mps, fp_hz)),
            _ => 0.0,
        }
    }
}

/// |θ| wrapped to [0, π].
#[inline]
pub(crate) fn wrap_abs(theta: f64) -> f64 {
    let t = theta.abs();
    if t <= PI {
        t
    } else {
        let w = t - TWO_PI * (t / TWO_PI).round();
        w.abs()
    }
}

/// ln((1 + c)/2) = ln cos²(θ/2) for c = cos θ, finite (clamped at the smallest normal).
#[inline]
pub(crate) fn ln_half_one_plus(c: f64) -> f64 {
    ln(half_one_plus(c))
}

/// (1 + c)/2 = cos²(θ/2) for c = cos θ, kept at or above the smallest normal `f64` (so
/// that its logarithm and powers stay finite).
#[inline(always)]
pub(crate) fn half_one_plus(c: f64) -> f64 {
    (0.5 + 0.5 * c).max(f64::MIN_POSITIVE)
}

/// tanh x for x ≥ 0 with fastmath's exp (portable); relative error ≈ 1e-15.
#[inline]
pub(crate) fn tanh(x: f64) -> f64 {
    if x < 0.1 {
        tanh_series(x)
    } else if x > 20.0 {
        1.0
    } else {
        let e = exp(-2.0 * x);
        (1.0 - e) / (1.0 + e)
    }
}

/// The Taylor series of tanh to x¹⁵ (the next term is below 1e-20 relative for x < 0.1).
#[inline(always)]
pub(crate) fn tanh_series(x: f64) -> f64 {
    let x2 = x * x;
    let p = -929_569.0 / 638_512_875.0;
    let p = 21_844.0 / 6_081_075.0 + x2 * p;
    let p = -1_382.0 / 155_925.0 + x2 * p;
    let p = 62.0 / 2_835.0 + x2 * p;
    let p = -17.0 / 315.0 + x2 * p;
    let p = 2.0 / 15.0 + x2 * p;
    let p = -1.0 / 3.0 + x2 * p;
    x + x * x2 * p
}

/// sech² x = 4e/(1 + e)², e = exp(−2|x|).
#[inline]
pub(crate) fn sech2(x: f64) -> f64 {
    let e = exp(-2.0 * x.abs());
    4.0 * e / ((1.0 + e) * (1.0 + e))
}

/// Swell exponent s_ξ = 16 tanh(1/r) ξ² at r = f/fp (r = 0: 16ξ²).
#[inline]
pub fn swell_exponent(r: f64, xi: f64) -> f64 {
    if xi == 0.0 {
        0.0
    } else if r <= 0.0 {
        16.0 * xi * xi
    } else {
        16.0 * tanh(1.0 / r) * xi * xi
    }
}

/// ∫_{−π}^{π} g dθ for an even g that may behave like cos^{2s}(θ/2) (with a fractional
/// power) near ±π: 2∫_0^π, on [0, min(π/2, θc)] by `panels` panels of 10-point
/// Gauss–Legendre, and on [π/2, π] (when θc > π/2) with φ = π − θ = (π/2)·w⁶, which
/// turns the endpoint behaviour φ^{2s} into the smoother w^{12s+5}. θc = √(160/s) when s > 0: beyond it
/// cos^{2s}(θ/2) ≤ e^{−sθ²/4} < e^{−40}.
pub(crate) fn integrate_circle_even(g: impl Fn(f64) -> f64, s: f64, panels: usize) -> f64 {
    let rule = gl10();
    let half = 0.5 * PI;
    let cut = if s > 0.0 { (160.0 / s).sqrt() } else { PI };
    let mut total = integrate(&g, 0.0, cut.min(half), panels, rule);
    if cut > half {
        total += integrate(
            |w| {
                let w5 = w * w * w * w * w;
                g(PI - half * w5 * w) * 6.0 * half * w5
            },
            0.0,
            1.0,
            panels,
            rule,
        );
    }
    2.0 * total
}

fn gl10() -> &'static [(f64, f64)] {
    static RULE: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    RULE.get_or_init(|| gauss_legendre(10))
}

#[cfg(test)]
mod tests {
    use super::hasselmann::ln_np_large;
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// ∫_{−π}^{π} g dθ of an even g concentrated like cos^{2s}(θ/2).
    fn integrate_theta(g: impl Fn(f64) -> f64, s: f64) -> f64 {
        integrate_circle_even(g, s, 100)
    }

    #[test]
    fn ln_gamma_matches_known_values() {
        const TOL: f64 = 1e-13;
        let cases = [
            (0.5, 0.572_364_942_924_700_1), // ln √π
            (1.0, 0.0),
            (2.0, 0.0),
            (3.0, std::f64::consts::LN_2),
            (10.0, 12.801_827_480_081_469), // ln 9!
            (0.1, 2.252_712_651_734_206),   // ln Γ(0.1)
            (2.5, 0.284_682_870_472_919_2), // ln(1.329340388…)
            (100.0, 359.134_205_369_575_4), // ln 99!
        ];
        for (x, want) in cases {
            let got = ln_gamma(x);
            assert!(
                (got - want).abs() <= TOL * want.abs().max(1.0),
                "lnΓ({x}) = {got}, want {want}"
            );
        }
    }

    #[test]
    fn np_matches_mastins_formula_and_a_direct_integral() {
        const REL_INT: f64 = 1e-11;
        for p in [0.0, 0.3, 1.0, 2.5, 9.77, 30.0, 63.9, 64.0, 200.0, 3000.0] {
            let direct = integrate_theta(|t| exp(p * ln_half_one_plus(sin_cos(t).1)), p);
            let np = np_hasselmann(p);
            assert!(rel(np, direct) < REL_INT, "N_{p} = {np}, ∫ = {direct}");
            if p < 60.0 {
                // Mastin eq. 6 literally, in logs.
                let lit =
                    (1.0 - 2.0 * p) * std::f64::consts::LN_2 + ln(PI) + ln_gamma(2.0 * p + 1.0)
                        - 2.0 * ln_gamma(p + 1.0);
                assert!(
                    (lit - ln_np(p)).abs() < 1e-12,
                    "eq. 6 at p = {p}: {lit} vs {}",
                    ln_np(p)
                );
            }
        }
        assert!(rel(np_hasselmann(0.0), TWO_PI) < 1e-15);
        assert!(rel(np_hasselmann(1.0), PI) < 1e-14, "N_1 = π");
        // The two ln N forms meet continuously at 64.
        assert!(
            (ln_np_large(64.0) - (LN_2_SQRT_PI + ln_gamma(64.5) - ln_gamma(65.0))).abs() < 1e-13
        );
        assert!(
            (ln_np_large(150.0) - (LN_2_SQRT_PI + ln_gamma(150.5) - ln_gamma(151.0))).abs() < 1e-12
        );
    }

    #[test]
    fn single_precision_log2_np_matches_ln_np() {
        // |Δ log2 N_s| ≤ TOL·(1 + |log2 N_s|), over s from 0 to 1e6 (Hasselmann's p ≤ 9.77,
        // Mitsuyasu's s_max of strong young seas a few hundred).
        const TOL: f64 = 5e-7;
        let mut worst: f64 = 0.0;
        for i in 0..=20_000 {
            let s = if i < 10_000 {
                20.0 * i as f64 / 10_000.0
            } else {
                (i as f64 / 20_000.0 * 6.0 * std::f64::consts::LN_10).exp()
            };
            let s32 = s as f32;
            let want = ln_np(f64::from(s32)) * std::f64::consts::LOG2_E;
            let err = (f64::from(log2_np_f32(s32)) - want).abs() / (1.0 + want.abs());
            worst = worst.max(err);
            assert!(err < TOL, "s = {s32}: {} vs {want}", log2_np_f32(s32));
        }
        eprintln!("log2_np_f32: largest |Δ|/(1 + |log2 N_s|) {worst:.2e}");
    }

    #[test]
    fn p_hasselmann_at_hand_picked_frequencies() {
        const TOL: f64 = 1e-13;
        let fm = 0.1;
        assert!(rel(p_hasselmann(fm, fm), 9.77) < TOL);
        assert!(rel(p_hasselmann(0.5 * fm, fm), 9.77 * 0.5f64.powf(4.06)) < TOL);
        assert!(rel(p_hasselmann(2.0 * fm, fm), 9.77 * 2.0f64.powf(-2.34)) < TOL);
        assert!(
            rel(p_hasselmann(0.05, 0.1), 0.585_751) < 1e-5,
            "{}",
            p_hasselmann(0.05, 0.1)
        );
        assert_eq!(p_hasselmann(0.0, fm), 0.0);
    }

    #[test]
    fn portable_tanh() {
        for i in 0..20_000 {
            let x = i as f64 * 1.3e-3 * 1.0005f64.powi(i);
            let want = x.tanh();
            assert!(
                (tanh(x) - want).abs() <= 2e-15 * want.max(1e-300),
                "tanh({x}) = {} vs {want}",
                tanh(x)
            );
        }
    }

    #[test]
    fn wallis_cos2_normalizer() {
        // Wallis' Cos2 normalizer against a direct integral.
        for s in [0.0, 0.5, 3.0, 40.0, 500.0] {
            let direct = integrate_theta(
                |t| {
                    let c = sin_cos(t).1;
                    c * c * exp(s * ln_half_one_plus(c))
                },
                s,
            );
            assert!(rel(exp(ln_z_cos2(s)), direct) < 1e-11, "Z_cos2({s})");
        }
    }

    #[test]
    fn donelan_banner_normalizer_is_accurate() {
        // The 8-panel rule against 400 panels, over the β and s_ξ the model produces.
        const REL_TOL: f64 = 1e-9;
        for beta in [0.398, 0.6, 1.0, 1.7, 2.44] {
            for s in [0.0, 0.01, 0.18, 0.7, 3.0, 16.0, 120.0, 1600.0] {
                let g = |t: f64| sech2(beta * t) * exp(s * ln_half_one_plus(sin_cos(t).1));
                let reference = integrate_circle_even(g, s, 400);
                let got = donelan_banner_norm(beta, s);
                assert!(
                    rel(got, reference) < REL_TOL,
                    "Z(β {beta}, s {s}) = {got}, reference {reference}"
                );
                if s == 0.0 {
                    let exact = 2.0 * tanh(beta * PI) / beta;
                    assert!(
                        rel(got, exact) < REL_TOL,
                        "Z(β {beta}, 0) = {got} vs 2 tanh(βπ)/β = {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn donelan_banner_beta_branches() {
        const TOL: f64 = 1e-13;
        assert!(rel(donelan_banner_beta(0.8), 2.61 * 0.8f64.powf(1.3)) < TOL);
        assert!(rel(donelan_banner_beta(1.2), 2.28 * 1.2f64.powf(-1.3)) < TOL);
        let r: f64 = 3.0;
        let want = 10f64.powf(-0.4 + 0.8393 * (-0.567 * (r * r).ln()).exp());
        assert!(rel(donelan_banner_beta(r), want) < TOL);
        // Clamp below 0.56.
        assert_eq!(donelan_banner_beta(0.1), donelan_banner_beta(0.56));
        assert_eq!(donelan_banner_beta(0.0), donelan_banner_beta(0.56));
    }

    #[test]
    fn mitsuyasu_s_by_hand() {
        // U = 15, fp = 0.1 Hz: c_p = 9.81/(0.2π) = 15.613 m/s, s_max = 11.5·(15/15.613)^−2.5.
        let smax = mitsuyasu_s_max(15.0, 0.1);
        let cp = G / (TWO_PI * 0.1);
        assert!(rel(smax, 11.5 * (15.0 / cp).powf(-2.5)) < 1e-13);
        assert!(rel(smax, 12.711) < 1e-3, "s_max {smax}");
        assert!(rel(mitsuyasu_s(0.05, 0.1, smax), smax / 32.0) < 1e-13);
        assert!(rel(mitsuyasu_s(0.4, 0.1, smax), smax / 32.0) < 1e-13);
        assert_eq!(mitsuyasu_s_max(-1.0, 0.1), 0.0);
    }

    #[test]
    fn mitsuyasu_s_max_at_two_wave_ages() {
        // Mitsuyasu et al. (1975): s_max = 11.5 (ω_p U10/g)^−2.5 = 11.5 (U10/c_p)^−2.5.
        // A fully developed sea (U10/c_p = 0.82) spreads narrowly, s_max ≈ 18.9; a young
        // sea (U10/c_p = 2) broadly, s_max ≈ 2.03. Older seas spread narrower.
        const TOL: f64 = 1e-12;
        let u = 12.0;
        let mut last = f64::INFINITY;
        for (age, want) in [(0.82, 18.887_0), (2.0, 2.032_93)] {
            let cp = u / age;
            let fp = G / (TWO_PI * cp);
            let got = mitsuyasu_s_max(u, fp);
            let formula = 11.5 * (TWO_PI * fp * u / G).powf(-2.5);
            assert!(rel(got, formula) < TOL, "U/c_p {age}: {got} vs {formula}");
            assert!(rel(got, want) < 1e-4, "U/c_p {age}: {got} vs {want}");
            assert!(got < last, "s_max must fall as U/c_p grows");
            last = got;
        }
    }

    #[test]
    fn new_validates_swell() {
        assert!(Spreading::new(SpreadingModel::Cos2, 0.0).is_ok());
        assert!(Spreading::new(SpreadingModel::Cos2, 10.0).is_ok());
        let e = Spreading::new(SpreadingModel::Hasselmann, -0.1).unwrap_err();
        assert_eq!(
            (e.name.as_str(), e.allowed.as_str(), e.got.as_str()),
            ("spectrum.swell", "between 0 and 10", "-0.1")
        );
        assert!(Spreading::new(SpreadingModel::Hasselmann, f64::NAN).is_err());
        assert!(Spreading::new(SpreadingModel::Hasselmann, 10.5).is_err());
    }

    #[test]
    fn periodic_in_theta_and_cos2_is_phillips() {
        let sp = Spreading::new(SpreadingModel::Cos2, 0.0).unwrap();
        for t in [0.0f64, 0.4, 1.0, 2.0, 3.0] {
            let want = t.cos().powi(2) / PI;
            assert!(
                (sp.density(0.1, 0.1, 10.0, t) - want).abs() < 1e-15,
                "cos²θ/π at {t}"
            );
        }
        for model in [
            SpreadingModel::Cos2,
            SpreadingModel::Hasselmann,
            SpreadingModel::Mitsuyasu,
            SpreadingModel::DonelanBanner,
        ] {
            let sp = Spreading::new(model, 0.7).unwrap();
            for t in [0.0, 0.3, 1.7, 3.0] {
                let a = sp.density(0.13, 0.1, 12.0, t);
                for shift in [TWO_PI, -TWO_PI, 3.0 * TWO_PI] {
                    let b = sp.density(0.13, 0.1, 12.0, t + shift);
                    assert!(
                        (a - b).abs() <= 1e-12 * a.max(1e-300),
                        "{model:?} at {t} + {shift}"
                    );
                }
            }
        }
    }
}
