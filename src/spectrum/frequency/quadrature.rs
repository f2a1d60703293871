//! Gauss–Legendre quadrature: nodes and weights, and composite integrals.

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
