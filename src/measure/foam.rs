//! Foam from the Jacobian J of a choppy surface: where it starts (`motion.foam_threshold`)
//! and how much of each sample it covers.
//!
//! A number T puts foam where J < T. `"auto"` puts it on the most compressed part of the
//! surface whose area is the whitecap coverage of the wind, Monahan & O'Muircheartaigh
//! (1980): W = 3.84·10⁻⁶·U10^3.41 (0.3 % at 7 m/s, 4 % at 15 m/s, 20 % at 25 m/s; capped
//! at 1). T is then the quantile of J that leaves exactly round(W·n) of the n samples
//! below it (fewer only where samples tie at T), found by selection, so it depends on the
//! samples alone, not on threads. "Wind-driven" means a spectrum set by the wind speed:
//! Phillips (its V), Pierson–Moskowitz, JONSWAP and TMA without `--hs`/`--tp`. Any other
//! sea (Hs and Tp given, a swell or a terrain) has no wind to relate foam to, and `"auto"`
//! is the fixed J < 0.3 of a surface close to folding.
//!
//! The coverage of a sample is clamp((T − J)/T, 0, 1): 0 at J ≥ T, full where the
//! surface folds (J ≤ 0). T is kept ≥ [`MIN_THRESHOLD`], so when more than W of the
//! surface folds over, foam covers every folded sample (more than W).

use serde::Serialize;

use crate::config::{FoamThreshold, Params};

/// The threshold of `"auto"` without a wind-driven spectrum.
pub const FALLBACK_THRESHOLD: f64 = 0.3;
/// The smallest threshold `"auto"` resolves to.
pub const MIN_THRESHOLD: f64 = 0.01;

/// The whitecap coverage of a wind of `u10_mps` m/s at 10 m (Monahan & O'Muircheartaigh
/// 1980, eq. 5): W = 3.84·10⁻⁶·U10^3.41, as a fraction, capped at 1.
pub fn whitecap_coverage(u10_mps: f64) -> f64 {
    (3.84e-6 * u10_mps.max(0.0).powf(3.41)).min(1.0)
}

/// What decides the foam of a field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FoamRule {
    /// Foam on this fraction of the samples (the whitecap coverage W).
    Coverage(f64),
    /// Foam where J < this.
    Threshold(f64),
}

impl FoamRule {
    /// The rule of `params`' `motion.foam_threshold`.
    pub fn of(params: &Params) -> Self {
        match params.motion.foam_threshold {
            FoamThreshold::Jacobian(t) => FoamRule::Threshold(t),
            FoamThreshold::Auto if wind_driven(params) => {
                FoamRule::Coverage(whitecap_coverage(params.wind.speed_mps))
            }
            FoamThreshold::Auto => FoamRule::Threshold(FALLBACK_THRESHOLD),
        }
    }

    /// The threshold over the J samples `j` (not empty).
    pub fn resolve(self, j: &[f32]) -> ResolvedFoam {
        match self {
            FoamRule::Threshold(t) => ResolvedFoam {
                threshold: t,
                whitecap_coverage: None,
                rule: "fixed",
            },
            FoamRule::Coverage(w) => ResolvedFoam {
                threshold: threshold_for_fraction(j, w).max(MIN_THRESHOLD),
                whitecap_coverage: Some(w),
                rule: "whitecap coverage W = 3.84e-6 * U10^3.41 (Monahan & O'Muircheartaigh 1980)",
            },
        }
    }
}

/// Whether `params` describe a sea set by the wind (see the module's notes).
pub fn wind_driven(params: &Params) -> bool {
    use crate::config::SpectrumModel as M;
    let s = &params.spectrum;
    match s.model {
        M::Phillips => true,
        M::PiersonMoskowitz | M::Jonswap | M::Tma => s.hs_m.is_none() && s.tp_s.is_none(),
        M::Fractal => false,
    }
}

/// The foam threshold in use and where it came from (the sidecar's `foam`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ResolvedFoam {
    /// Foam where J < this.
    #[serde(rename = "threshold_resolved")]
    pub threshold: f64,
    /// The whitecap coverage W that `"auto"` aimed at (a wind-driven sea).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub whitecap_coverage: Option<f64>,
    /// How the threshold was found.
    pub rule: &'static str,
}

/// The threshold T that leaves exactly k = round(`fraction`·n) of the samples `j` below
/// it: the k-th smallest (from 0; above the largest when k = n). NaN sorts above all.
pub fn threshold_for_fraction(j: &[f32], fraction: f64) -> f64 {
    let n = j.len();
    if n == 0 {
        return FALLBACK_THRESHOLD;
    }
    let k = (fraction.clamp(0.0, 1.0) * n as f64).round() as usize;
    if k >= n {
        let max = j
            .iter()
            .copied()
            .filter(|v| !v.is_nan())
            .fold(f32::MIN, f32::max) as f64;
        return max + max.abs().max(1.0) * 1e-6;
    }
    let mut v = j.to_vec();
    let (_, kth, _) = v.select_nth_unstable_by(k, |a, b| a.total_cmp(b));
    *kth as f64
}

/// Foam coverage 0..1 of a sample of Jacobian `j` under the threshold T:
/// clamp((T − J)/T, 0, 1).
#[inline]
pub fn coverage(j: f32, threshold: f64) -> f32 {
    ((threshold - j as f64) / threshold).clamp(0.0, 1.0) as f32
}

/// Foam coverage in 0..=65535: round(65535·clamp((T − J)/T, 0, 1)).
#[inline]
pub fn coverage_u16(j: f32, threshold: f64) -> u16 {
    // Clamping 65535·f to 0..=65535 is clamping f to 0..=1 first (exact at both ends).
    let f = (threshold - j as f64) / threshold;
    crate::fastmath::round_clamped_f64(f * 65535.0, 65535.0) as u16
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coverage_u16_rounds_like_round() {
        for t in [0.3, 0.7, 0.9123, 1.0] {
            for k in 0..=200_000 {
                let j = (k as f32 / 100_000.0 - 0.5) * t as f32;
                let f = ((t - j as f64) / t).clamp(0.0, 1.0);
                assert_eq!(
                    coverage_u16(j, t),
                    (f * 65535.0).round() as u16,
                    "J {j}, T {t}"
                );
            }
        }
    }

    #[test]
    fn monahan_coverage_matches_its_quoted_values() {
        // Monahan & O'Muircheartaigh (1980): about 0.3 % at 7 m/s, 4 % at 15 m/s, 20 % at
        // 25 m/s.
        assert!((whitecap_coverage(7.0) - 0.0029).abs() < 0.0002);
        assert!((whitecap_coverage(15.0) - 0.0393).abs() < 0.0002);
        assert!((whitecap_coverage(25.0) - 0.2245).abs() < 0.0002);
        assert_eq!(whitecap_coverage(0.0), 0.0);
        assert_eq!(whitecap_coverage(60.0), 1.0, "capped");
    }

    #[test]
    fn the_threshold_leaves_the_asked_fraction_below_it() {
        // A permutation of 0.0, 0.01, …, 0.99: k samples lie below the k-th.
        let j: Vec<f32> = (0..100).map(|i| ((i * 37) % 100) as f32 / 100.0).collect();
        for (w, k) in [(0.0, 0), (0.04, 4), (0.2, 20), (0.555, 56), (0.99, 99)] {
            let t = threshold_for_fraction(&j, w);
            assert_eq!(t, (k as f32 / 100.0) as f64, "w {w}");
            assert_eq!(j.iter().filter(|&&v| (v as f64) < t).count(), k, "w {w}");
        }
        let t = threshold_for_fraction(&j, 1.0);
        assert!(j.iter().all(|&v| (v as f64) < t));
        // Ties: never more than asked.
        let flat = vec![1.0f32; 50];
        assert_eq!(threshold_for_fraction(&flat, 0.2), 1.0);
    }

    #[test]
    fn auto_follows_the_wind_only_for_a_wind_driven_sea() {
        let mut p = Params::default();
        p.wind.speed_mps = 15.0;
        assert_eq!(
            FoamRule::of(&p),
            FoamRule::Coverage(whitecap_coverage(15.0))
        );
        p.spectrum.model = crate::config::SpectrumModel::Jonswap;
        assert_eq!(
            FoamRule::of(&p),
            FoamRule::Coverage(whitecap_coverage(15.0))
        );
        p.spectrum.hs_m = Some(2.0);
        p.spectrum.tp_s = Some(9.0);
        assert_eq!(FoamRule::of(&p), FoamRule::Threshold(FALLBACK_THRESHOLD));
        p.spectrum.model = crate::config::SpectrumModel::Fractal;
        assert_eq!(FoamRule::of(&p), FoamRule::Threshold(FALLBACK_THRESHOLD));
        p.motion.foam_threshold = FoamThreshold::Jacobian(0.5);
        assert_eq!(FoamRule::of(&p), FoamRule::Threshold(0.5));
        // A surface folded over more than W: every folded sample gets foam.
        let folded = vec![-0.5f32; 10];
        let r = FoamRule::Coverage(0.1).resolve(&folded);
        assert_eq!(r.threshold, MIN_THRESHOLD);
        assert_eq!(coverage(-0.5, r.threshold), 1.0);
    }

    #[test]
    fn coverage_encodes_its_documented_ramp() {
        assert_eq!(coverage_u16(1.0, 0.3), 0);
        assert_eq!(coverage_u16(0.3, 0.3), 0);
        assert_eq!(coverage_u16(0.25, 0.5), 32768);
        assert_eq!(coverage_u16(-0.5, 0.3), 65535);
        assert_eq!(coverage(0.25, 0.5), 0.5);
    }

    #[test]
    fn the_threshold_reads_auto_or_a_number() {
        let t: FoamThreshold = serde_json::from_str("\"auto\"").unwrap();
        assert_eq!(t, FoamThreshold::Auto);
        let t: FoamThreshold = serde_json::from_str("0.3").unwrap();
        assert_eq!(t, FoamThreshold::Jacobian(0.3));
        assert_eq!(
            serde_json::to_string(&FoamThreshold::Auto).unwrap(),
            "\"auto\""
        );
        assert_eq!(
            serde_json::to_string(&FoamThreshold::Jacobian(0.5)).unwrap(),
            "0.5"
        );
        let e = serde_json::from_str::<FoamThreshold>("\"aut\"").unwrap_err();
        assert!(e.to_string().contains("`aut`"), "{e}");
        // Through --set and flags, and integers as numbers.
        use crate::config::layers::{Assignment, resolve};
        let p = resolve(None, &[Assignment::flag("foam-threshold", 1)]).unwrap();
        assert_eq!(p.motion.foam_threshold, FoamThreshold::Jacobian(1.0));
        let p = resolve(None, &[Assignment::flag("foam-threshold", "auto")]).unwrap();
        assert_eq!(p.motion.foam_threshold, FoamThreshold::Auto);
        let e = resolve(None, &[Assignment::flag("foam-threshold", "often")])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("--foam-threshold often") && e.contains("auto"),
            "{e}"
        );
        let e = resolve(None, &[Assignment::flag("foam-threshold", 3)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("auto, or a number > 0 and ≤ 2"), "{e}");
    }
}
