use super::bases::FINITE_NEUMANN_ORDER;
use super::sample::GUIDES;
use super::*;
use crate::field::fft::second_order::{kernel_minus, kernel_plus, self_kernels};

#[test]
fn the_split_reproduces_the_pair_kernels() {
    // K = ¼[sep + ns] is the kernel of the pair sum, deep and finite depth, sum and
    // difference, over waves of many lengths and directions (and the sum self-pair).
    const TOL: f64 = 1e-10;
    for depth in [None, Some(30.0), Some(6.0)] {
        for (k1, t1) in [(0.05, 0.0), (0.013, 0.4), (0.21, 2.0)] {
            for (k2, t2) in [(0.04, 0.1), (0.09, -1.3), (0.3, 3.0), (0.013, 0.4)] {
                let a = Component::new(k1 * f64::cos(t1), k1 * f64::sin(t1), 1.0, 0.0, depth);
                let b = Component::new(k2 * f64::cos(t2), k2 * f64::sin(t2), 1.0, 0.0, depth);
                let same = k1 == k2 && t1 == t2;
                let kp = if same {
                    self_kernels(&a, depth).0
                } else {
                    kernel_plus(&a, &b, depth)
                };
                let sp = split(&a, &b, 1.0, depth);
                let got = 0.25 * (sp.sep + sp.ns);
                assert!(
                    (got - kp).abs() <= TOL * kp.abs().max(k1),
                    "{depth:?} K⁺({k1}, {k2}): {got} vs {kp}"
                );
                if !same {
                    let km = kernel_minus(&a, &b, depth);
                    let sm = split(&a, &b, -1.0, depth);
                    let got = 0.25 * (sm.sep + sm.ns);
                    assert!(
                        (got - km).abs() <= TOL * km.abs().max(k1),
                        "{depth:?} K⁻({k1}, {k2}): {got} vs {km}"
                    );
                }
            }
        }
    }
}

#[test]
fn the_neumann_basis_with_its_series_coefficients_is_the_truncated_series() {
    // With c_ma = C(m, a)(−1)^a / (2^{m+1} s_p²) the finite-depth sum basis is the series
    // Σ_{m ≤ M} (T − P)^m / (2 s_i s_j)^{m+1} of G = 1/(2 s_i s_j + P − T), whose partial
    // sum is G·(1 − (−ρ)^{M+1}), ρ = (P − T)/(2 s_i s_j): checked on pairs of several
    // lengths and angles at 19 m (ρ < 0, near-resonant) and 60 m, with s_p from a third
    // wave. The deep basis is the six products ½[x_i^u x_j^v + x_i^v x_j^u].
    const TOL: f64 = 1e-12;
    const ORDER: i32 = 3;
    let order = FINITE_NEUMANN_ORDER as i32;
    assert_eq!(order, ORDER);
    for depth in [19.0, 60.0] {
        let bases = Bases::for_depth(Some(depth));
        assert_eq!(bases.len(0), 10);
        assert_eq!(bases.exponents(), (-4, 8));
        let s_ref = Component::new(0.035, 0.0, 1.0, 0.0, Some(depth)).s;
        for (k1, t1) in [(0.03, 0.0), (0.05, 0.3), (0.02, -0.2)] {
            for (k2, t2) in [(0.04, 0.1), (0.03, 0.0), (0.08, 0.6)] {
                let a = Component::new(k1 * f64::cos(t1), k1 * f64::sin(t1), 1.0, 0.0, Some(depth));
                let b = Component::new(k2 * f64::cos(t2), k2 * f64::sin(t2), 1.0, 0.0, Some(depth));
                let t = resonance_t((a.kx + b.kx).hypot(a.ky + b.ky), Some(depth));
                let phi = bases.eval(&a, &b, s_ref, 0, t);
                let mut got = 0.0;
                let mut l = 0;
                for m in 0..=order {
                    for k in 0..=m {
                        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                        let c = binomial(m as usize, k as usize) * sign
                            / (2f64.powi(m + 1) * s_ref * s_ref);
                        got += c * phi[l];
                        l += 1;
                    }
                }
                let two_ss = 2.0 * a.s * b.s;
                let rho = (a.r + b.r - t) / two_ss;
                let g = 1.0 / (two_ss + a.r + b.r - t);
                let want = g * (1.0 - (-rho).powi(ORDER + 1));
                assert!(
                    (got - want).abs() <= TOL * g.abs(),
                    "depth {depth} ({k1}, {k2}): {got} vs {want} (ρ = {rho})"
                );
            }
        }
    }
    let deep = Bases::for_depth(None);
    let a = Component::new(0.03, 0.01, 1.0, 0.0, None);
    let b = Component::new(0.05, -0.02, 1.0, 0.0, None);
    let phi = deep.eval(&a, &b, 0.2, 0, 1.0);
    let (xa, xb) = (a.s / 0.2, b.s / 0.2);
    let mut l = 0;
    for (i, u) in [-1, 0, 1].into_iter().enumerate() {
        for v in [-1, 0, 1].into_iter().skip(i) {
            let want = 0.5 * (xa.powi(u) * xb.powi(v) + xa.powi(v) * xb.powi(u));
            assert!((phi[l] - want).abs() <= TOL * want.abs(), "({u}, {v})");
            l += 1;
        }
    }
    assert_eq!(
        (deep.len(0), deep.len(1), deep.exponents()),
        (6, 4, (-1, 6))
    );
}

#[test]
fn the_sampler_picks_the_index_of_a_binary_search() {
    // The guide table finds the first index whose cumulative weight exceeds u·total, the
    // last if none does: what a binary search of the cumulative weights finds, for weights
    // of many scales with zeros among them, at u on and beside the steps' bounds and the
    // cumulative weights.
    let w: Vec<f64> = (0..700)
        .map(|i| match i % 7 {
            0 => 0.0,
            1 => 1e-9 * i as f64,
            _ => (i as f64 * 0.37).sin().abs() * 10f64.powi(i % 5),
        })
        .collect();
    let sampler = Sampler::new(&w);
    let total = *sampler.cum.last().unwrap();
    let search = |u: f64| {
        let x = u * total;
        sampler
            .cum
            .partition_point(|&c| c <= x)
            .min(sampler.cum.len() - 1)
    };
    let mut us: Vec<f64> = (0..20_000).map(|t| uniform(t, 9).0).collect();
    for b in 0..GUIDES {
        let u = b as f64 / GUIDES as f64;
        us.extend([u, f64::from_bits(u.to_bits() + 1), (u - 1e-17).max(0.0)]);
    }
    for &c in sampler.cum.iter().step_by(3) {
        let u = c / total;
        us.extend(
            [u, f64::from_bits(u.to_bits() + 1)]
                .into_iter()
                .filter(|&u| u < 1.0),
        );
    }
    for u in us {
        assert_eq!(sampler.pick(u), search(u), "u = {u}");
    }
}
