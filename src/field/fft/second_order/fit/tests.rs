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
