//! The part of a choppy surface that folds toward foam: the fraction of samples whose
//! Jacobian J of the displacement is below a threshold, and the smallest J.

use serde::Serialize;

/// What `analyze` reports of a Jacobian field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JacobianStats {
    /// The threshold T (the sidecar's `motion.foam_threshold` resolved over these J as
    /// the maps were, [`super::foam`]; without a sidecar, 0.3).
    pub threshold: f64,
    /// The whitecap coverage W that `"auto"` aimed at, for a wind-driven sea.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub whitecap_coverage: Option<f64>,
    /// The fraction of the samples with J < T (foam where the `foam` map is not 0).
    pub fraction_below: f64,
    /// The smallest J (< 0: the surface folds over).
    pub min: f64,
    /// `"map"` (read from `NAME.jacobian.tif` or `.exr`) or `"regenerated"` (the field
    /// of the sidecar's parameters synthesized again).
    pub source: &'static str,
}

/// The statistics of the J samples `j` (not empty; NaN counts as not below) against the
/// threshold `rule` resolves to over them.
pub fn jacobian_stats(
    j: &[f32],
    rule: super::foam::FoamRule,
    source: &'static str,
) -> JacobianStats {
    let foam = rule.resolve(j);
    let threshold = foam.threshold;
    let below = j.iter().filter(|&&v| (v as f64) < threshold).count();
    let min = j.iter().copied().fold(f32::INFINITY, f32::min);
    JacobianStats {
        threshold,
        whitecap_coverage: foam.whitecap_coverage,
        fraction_below: below as f64 / j.len().max(1) as f64,
        min: min as f64,
        source,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_the_samples_strictly_below_the_threshold_and_finds_the_minimum() {
        // 1 (flat), the threshold itself (not below), two below, one folded.
        let j = [1.0, 0.5, 0.25, 0.0, -0.75, 2.0, f32::NAN, 0.5];
        let s = jacobian_stats(&j, super::super::foam::FoamRule::Threshold(0.5), "map");
        assert_eq!(s.fraction_below, 3.0 / 8.0);
        assert_eq!(s.min, -0.75);
        assert_eq!(s.threshold, 0.5);
        assert_eq!(s.source, "map");
        assert_eq!(s.whitecap_coverage, None);
        // "auto" with a wind: the fraction asked for, up to the rounding to samples.
        let j: Vec<f32> = (0..1000)
            .map(|i| ((i * 7919) % 1000) as f32 / 500.0)
            .collect();
        let s = jacobian_stats(&j, super::super::foam::FoamRule::Coverage(0.0393), "map");
        assert_eq!(s.fraction_below, 0.039);
        assert_eq!(s.whitecap_coverage, Some(0.0393));
    }
}
