//! Li Tian's blend (eq. 10): h = α(x,y)·h_fft + β(x,y)·h_perlin, β = (1 − α)·b.

use rayon::prelude::*;

use super::weight::AlphaMap;
use crate::grid::Grid;

/// Replaces `fft` by α·h_fft + (1 − α)·b·h_perlin, row by row. With α ≡ 1 the result is
/// h_fft exactly; with α ≡ 0 it is b·h_perlin exactly.
pub fn blend_in_place(fft: &mut Grid, perlin: &[f32], alpha: &AlphaMap, b_m: f32) {
    let nx = fft.spec.nx;
    assert_eq!(perlin.len(), fft.data.len(), "fields on one grid");
    fft.data
        .par_chunks_mut(nx)
        .zip(perlin.par_chunks(nx))
        .enumerate()
        .for_each_init(
            || vec![0.0f32; nx],
            |a, (j, (h, p))| {
                alpha.row(j, a);
                for ((h, &p), &a) in h.iter_mut().zip(p).zip(a.iter()) {
                    *h = a * *h + (1.0 - a) * b_m * p;
                }
            },
        );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{AlphaConfig, Axis};
    use crate::grid::GridSpec;

    fn fields() -> (Grid, Vec<f32>) {
        let spec = GridSpec::new(8, 4, 8.0, 4.0);
        let f = Grid::new(spec, (0..32).map(|v| (v as f32 * 0.37).sin()).collect());
        let p = (0..32).map(|v| (v as f32 * 0.91).cos()).collect();
        (f, p)
    }

    #[test]
    fn alpha_one_gives_the_fft_field_and_alpha_zero_the_scaled_perlin() {
        let (f, p) = fields();
        let mut g = f.clone();
        blend_in_place(&mut g, &p, &AlphaMap::Constant(1.0), 0.7);
        assert_eq!(g.data, f.data);
        let mut g = f.clone();
        blend_in_place(&mut g, &p, &AlphaMap::Constant(0.0), 0.7);
        let want: Vec<f32> = p.iter().map(|v| 0.7 * v).collect();
        assert_eq!(g.data, want);
    }

    #[test]
    fn ramp_blend_mixes_per_row() {
        let (f, p) = fields();
        let alpha = AlphaMap::new(
            &AlphaConfig::Ramp {
                axis: Axis::Y,
                power: 1.0,
            },
            &f.spec,
        )
        .unwrap();
        let mut g = f.clone();
        blend_in_place(&mut g, &p, &alpha, 2.0);
        for j in 0..4 {
            let a = 1.0 - j as f32 / 4.0;
            for i in 0..8 {
                let k = j * 8 + i;
                let want = a * f.data[k] + (1.0 - a) * 2.0 * p[k];
                assert!((g.data[k] - want).abs() < 1e-6, "({i},{j})");
            }
        }
    }
}
