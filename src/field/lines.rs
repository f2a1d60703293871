//! Baseline (temporary).
use super::fft::signed_index;
use crate::fastmath;
use crate::rng;

pub fn polar_line(seed: u64, n: i64, sign: i64, ny: usize, r: &mut [f64], phi: &mut [f64]) {
    for i in 0..r.len() {
        (r[i], phi[i]) = rng::gaussian_polar(seed, sign * n, sign * signed_index(i, ny));
    }
}

pub fn sin_cos_line(x: &[f64], s: &mut [f64], c: &mut [f64]) {
    for i in 0..x.len() {
        (s[i], c[i]) = fastmath::sin_cos(x[i]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[ignore]
    fn speed() {
        use std::hint::black_box;
        use std::time::Instant;
        const NY: usize = 4096;
        const LINES: usize = 64;
        const ROUNDS: usize = 21;
        fn median(mut v: Vec<f64>) -> f64 {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        }
        let mut r = vec![0.0; NY];
        let mut phi = vec![0.0; NY];
        let mut t = [(); 4].map(|_| Vec::new());
        let x: Vec<f64> = (0..NY).map(|i| (i as f64 * 0.7331).sin().abs() * 3000.0).collect();
        for _ in 0..ROUNDS {
            let st = Instant::now();
            for n in 0..LINES as i64 {
                let seed = black_box(9);
                for i in 0..NY {
                    (r[i], phi[i]) = rng::gaussian_polar(seed, -n, -signed_index(i, NY));
                }
                black_box((&mut r, &mut phi));
            }
            t[0].push(st.elapsed().as_secs_f64() * 1e9 / (LINES * NY) as f64);
            let st = Instant::now();
            for n in 0..LINES as i64 {
                polar_line(black_box(9), n, -1, NY, &mut r, &mut phi);
                black_box((&mut r, &mut phi));
            }
            t[1].push(st.elapsed().as_secs_f64() * 1e9 / (LINES * NY) as f64);
            let st = Instant::now();
            for _ in 0..LINES {
                for i in 0..NY {
                    (r[i], phi[i]) = fastmath::sin_cos(black_box(x[i]));
                }
                black_box((&mut r, &mut phi));
            }
            t[2].push(st.elapsed().as_secs_f64() * 1e9 / (LINES * NY) as f64);
            let st = Instant::now();
            for _ in 0..LINES {
                sin_cos_line(black_box(&x), &mut r, &mut phi);
                black_box((&mut r, &mut phi));
            }
            t[3].push(st.elapsed().as_secs_f64() * 1e9 / (LINES * NY) as f64);
        }
        let [a, b, c, d] = t.map(median);
        println!("polar: scalar {a:.2} ns, line {b:.2} ns; sin_cos: scalar {c:.2} ns, line {d:.2} ns");
    }
}
