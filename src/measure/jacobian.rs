//! The part of a choppy surface that folds toward foam: the fraction of samples whose
//! Jacobian J of the displacement is below a threshold, and the smallest J.

use serde::Serialize;

/// What `analyze` reports of a Jacobian field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JacobianStats {
    /// The threshold T (the sidecar's `motion.foam_threshold`, else its default).
    pub threshold: f64,
    /// The fraction of the samples with J < T (foam where the `foam` map is not 0).
    pub fraction_below: f64,
    /// The smallest J (< 0: the surface folds over).
    pub min: f64,
    /// `"map"` (read from `NAME.jacobian.tif` or `.exr`) or `"regenerated"` (the field
    /// of the sidecar's parameters synthesized again).
    pub source: &'static str,
}

/// The statistics of the J samples `j` (not empty; NaN counts as not below) against
/// `threshold`.
pub fn jacobian_stats(j: &[f32], threshold: f64, source: &'static str) -> JacobianStats {
    let below = j.iter().filter(|&&v| (v as f64) < threshold).count();
    let min = j.iter().copied().fold(f32::INFINITY, f32::min);
    JacobianStats {
        threshold,
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
        let s = jacobian_stats(&j, 0.5, "map");
        assert_eq!(s.fraction_below, 3.0 / 8.0);
        assert_eq!(s.min, -0.75);
        assert_eq!(s.threshold, 0.5);
        assert_eq!(s.source, "map");
    }
}
