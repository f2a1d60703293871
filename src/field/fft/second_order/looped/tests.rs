use super::*;
use crate::field::fft::second_order::tests::{params_of, small_sea};

fn max_abs(z: &[C64]) -> f64 {
    z.iter().fold(0.0, |m, v| m.max(v.norm()))
}

#[test]
fn the_bins_give_the_pair_sum_at_any_time() {
    // The binned sum Σ_ν Z_q,ν e^{−iνθ} against the pair sum at each time (phases
    // b_i(t) b_j(t)): the same pairs, equal to the bins' f32 rounding (the precision of
    // the spectrum they join), deep and at 8 m, inside and beyond the first period; the
    // same pairs kept and dropped.
    const TOL: f64 = 1e-6;
    for depth in [None, Some(8.0)] {
        let params = small_sea("size=48x40", depth);
        let (model, dispersion) = crate::field::spectrum_model(&params).unwrap();
        let period = 20.0;
        let setup_at = |t: f64| SpectrumSetup {
            spec: params.grid_spec(),
            spectrum: model.as_ref(),
            dispersion,
            seed: 3,
            time_s: t,
            loop_period_s: Some(period),
        };
        let so = SecondOrder::new(&setup_at(0.0), 0.999);
        let looped = LoopedBound::new(&so, &setup_at(0.0)).expect("bins fit");
        assert!(looped.info.loop_multiples.unwrap() > 3);
        for t in [0.0, 3.7, 11.25, 47.9] {
            let setup = setup_at(t);
            let (want, sums, diffs) = so.bound_plane(&setup);
            let got = looped.bound_plane(&setup);
            let scale = max_abs(&want);
            assert!(scale > 0.0);
            for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                assert!(
                    (g - w).norm() <= TOL * scale,
                    "depth {depth:?} t {t} cell {i}: {g} vs {w}"
                );
            }
            assert_eq!(looped.info.sum_pairs_dropped, so.info.pairs - sums);
            assert_eq!(looped.info.difference_pairs_dropped, so.info.pairs - diffs);
        }
        // A period later, the same bits.
        let (a, b) = (
            looped.bound_plane(&setup_at(3.0)),
            looped.bound_plane(&setup_at(3.0 + period)),
        );
        assert!(a.iter().zip(&b).all(|(x, y)| x == y));
    }
}

#[test]
fn a_loop_too_long_for_the_bins_keeps_the_pair_sum_per_frame() {
    // With T = 10⁵ s the multiples of one line span hundreds of bins: more than
    // MAX_BINS_PER_CELL per cell, so no bins; nor without a loop. T = 20 s fits.
    let params = params_of(&[
        "method=fft",
        "spectrum=pierson-moskowitz",
        "wind-speed=12",
        "size=32",
        "extent=320",
    ]);
    let (model, dispersion) = crate::field::spectrum_model(&params).unwrap();
    let setup = |period: Option<f64>| SpectrumSetup {
        spec: params.grid_spec(),
        spectrum: model.as_ref(),
        dispersion,
        seed: 1,
        time_s: 0.0,
        loop_period_s: period,
    };
    let so = SecondOrder::new(&setup(Some(20.0)), 0.99);
    let short = LoopedBound::new(&so, &setup(Some(20.0))).expect("bins fit");
    assert!(short.bins() > 0);
    assert!(LoopedBound::new(&so, &setup(Some(1e5))).is_none());
    assert!(LoopedBound::new(&so, &setup(None)).is_none());
}
