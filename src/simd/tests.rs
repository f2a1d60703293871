use super::lines::{exp_line_on, sin_cos_line_on};
use super::polar::{polar_line_on, polar_range_on};
use super::*;
use crate::fastmath;
use crate::grid::signed_index;
use crate::rng;
use std::f64::consts::FRAC_PI_2;

/// SplitMix64, for reproducible pseudo-random test points.
struct Rng(u64);
impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        rng::mix64(self.0)
    }
    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        lo + (hi - lo) * u
    }
}

#[test]
fn polar_line_equals_gaussian_polar_bit_for_bit() {
    let isas = Isa::available();
    println!("instruction sets: {isas:?}");
    let seeds = [0, 1, 7, 0xDEAD_BEEF, u64::MAX, rng::mix64(12345)];
    let ns = [0i64, 1, -1, 2, 37, -1000, 2048, i64::MAX, i64::MIN];
    let nys = [
        0usize, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 17, 31, 33, 64, 255, 1000, 4096, 4097,
    ];
    let mut count = 0usize;
    for &isa in &isas {
        for &seed in &seeds {
            for &n in &ns {
                for sign in [1i64, -1] {
                    for &ny in &nys {
                        // Also lines shorter and longer than ny.
                        for len in [ny, ny / 3, ny + 5] {
                            check_polar_line(isa, seed, n, sign, ny, len);
                            count += len;
                        }
                    }
                }
            }
        }
    }
    assert!(count > 1_000_000);
    // On the instruction set this processor has.
    let (mut r, mut phi) = (vec![0.0; 4096], vec![0.0; 4096]);
    polar_line_on(Isa::detect(), 5, 3, -1, 4096, &mut r, &mut phi);
    for (i, (r, phi)) in r.into_iter().zip(phi).enumerate() {
        let (wr, wphi) = rng::gaussian_polar(5, -3, -signed_index(i, 4096));
        assert_eq!((r.to_bits(), phi.to_bits()), (wr.to_bits(), wphi.to_bits()));
    }
}

#[test]
fn a_range_of_a_line_draws_what_the_whole_line_draws_there() {
    // The draws of a window of a line (the second order's components within the
    // convergence limit) are the whole line's there, bit for bit, on every instruction
    // set, for ranges at the ends, inside and of one element, lengths odd and even.
    for isa in Isa::available() {
        for (ny, sign) in [(1000usize, 1i64), (1000, -1), (97, 1), (4096, -1)] {
            let (mut r, mut phi) = (vec![0.0; ny], vec![0.0; ny]);
            polar_line_on(isa, 7, 11, sign, ny, &mut r, &mut phi);
            for range in [
                0..1,
                0..ny.min(37),
                ny / 2..ny,
                ny - 13..ny,
                ny / 4..ny / 4 + 1,
            ] {
                let len = range.len();
                let (mut rr, mut pp) = (vec![f64::NAN; len], vec![f64::NAN; len]);
                polar_range_on(isa, (7, 11, sign), ny, range.clone(), &mut rr, &mut pp);
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&rr), bits(&r[range.clone()]), "{isa:?} {ny} {range:?}");
                assert_eq!(
                    bits(&pp),
                    bits(&phi[range.clone()]),
                    "{isa:?} {ny} {range:?}"
                );
            }
        }
    }
}

/// Checks polar_line on `isa` against gaussian_polar.
fn check_polar_line(isa: Isa, seed: u64, n: i64, sign: i64, ny: usize, len: usize) {
    let mut r = vec![f64::NAN; len];
    let mut phi = vec![f64::NAN; len];
    polar_line_on(isa, seed, n, sign, ny, &mut r, &mut phi);
    for (i, (r, phi)) in r.into_iter().zip(phi).enumerate() {
        let m = sign.wrapping_mul(signed_index(i, ny));
        let (wr, wphi) = rng::gaussian_polar(seed, sign.wrapping_mul(n), m);
        assert!(
            r.to_bits() == wr.to_bits() && phi.to_bits() == wphi.to_bits(),
            "{isa:?}: seed {seed}, n {n}, sign {sign}, ny {ny}, len {len}, i {i}: \
             ({r}, {phi}) instead of ({wr}, {wphi})"
        );
    }
}

#[test]
fn kept_words_serve_interleaved_and_long_lines() {
    // Three line shapes take turns for the two places of the per-thread words, in
    // varying orders; and a line too long to keep.
    let shapes = [
        (1i64, 64usize, 64usize),
        (-1, 64, 64),
        (1, 65, 64),
        (-1, 64, 63),
    ];
    for &isa in &Isa::available() {
        for round in 0..12 {
            for k in 0..shapes.len() {
                let (sign, ny, len) = shapes[(k * (round % 3 + 1) + round) % shapes.len()];
                check_polar_line(isa, 3, round as i64, sign, ny, len);
            }
        }
        // Signs other than ±1 too.
        check_polar_line(isa, 6, 7, 0, 100, 100);
        check_polar_line(isa, 6, 7, 3, 100, 100);
        check_polar_line(isa, 4, 5, -1, (1 << 16) + 3, (1 << 16) + 3);
        check_polar_line(isa, 4, 5, 1, 1 << 16, 1 << 16);
    }
}

/// Checks sin_cos_line against fastmath::sin_cos on every instruction set, for the
/// inputs `x` and for every offset and length of subslices of their first 40 (so that
/// each input is seen in every vector lane and in the scalar remainder loops).
fn check_sin_cos_line(x: &[f64]) {
    for &isa in &Isa::available() {
        let check = |x: &[f64]| {
            let mut s = vec![0.5; x.len()];
            let mut c = vec![0.5; x.len()];
            sin_cos_line_on(isa, x, &mut s, &mut c);
            for i in 0..x.len() {
                let (ws, wc) = fastmath::sin_cos(x[i]);
                assert!(
                    s[i].to_bits() == ws.to_bits() && c[i].to_bits() == wc.to_bits(),
                    "{isa:?}: sin_cos({:e}) gave ({:e}, {:e}) instead of ({ws:e}, {wc:e})",
                    x[i],
                    s[i],
                    c[i]
                );
            }
        };
        check(x);
        let head = &x[..x.len().min(40)];
        for start in 0..head.len() {
            for end in start..=head.len() {
                check(&head[start..end]);
            }
        }
    }
}

#[test]
fn sin_cos_line_equals_sin_cos_bit_for_bit() {
    let mut rng = Rng(1);
    // Uniform arguments, as the phases φ − ωt are.
    let x: Vec<f64> = (0..200_000).map(|_| rng.uniform(-1e4, 1e4)).collect();
    check_sin_cos_line(&x);
    // Small and tiny arguments of both signs, ±0 and subnormals.
    let mut x: Vec<f64> = (0..20_000)
        .map(|_| {
            let v = f64::from_bits(rng.next_u64() & 0x3FFF_FFFF_FFFF_FFFF) * 0.25;
            if rng.next_u64() & 1 == 0 { v } else { -v }
        })
        .collect();
    x.extend([
        0.0,
        -0.0,
        5e-324,
        -5e-324,
        1e-300,
        -1e-300,
        2.2e-308,
        f64::MIN_POSITIVE,
    ]);
    check_sin_cos_line(&x);
    // Exact multiples of π/2 (as doubles) and their neighbours, up to the Cody–Waite
    // limit, where the quadrant rounding and r ≈ 0 are delicate.
    let mut x = Vec::new();
    for k in (-70_000i64..70_000).chain((-63_661_977i64..63_661_977).step_by(9_973)) {
        let v = k as f64 * FRAC_PI_2;
        for d in [-1i64, 0, 1] {
            x.push(f64::from_bits((v.to_bits() as i64 + d) as u64));
        }
        x.push((k as f64 + 0.5) * FRAC_PI_2);
    }
    check_sin_cos_line(&x);
    // Around the Cody–Waite limit, beyond it (the scalar fallback), and specials,
    // mixed with ordinary lanes.
    let limit = fastmath::SIN_COS_CW_LIMIT;
    let specials = [
        limit,
        -limit,
        f64::from_bits(limit.to_bits() - 1),
        -f64::from_bits(limit.to_bits() - 1),
        f64::from_bits(limit.to_bits() + 1),
        1e9,
        -1e9,
        1e22,
        1e300,
        -1e300,
        f64::MAX,
        f64::MIN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        -f64::NAN,
        f64::from_bits(0x7FF0_0000_0000_0001), // signalling NaN
    ];
    let mut x = Vec::new();
    for (i, &v) in specials.iter().enumerate() {
        x.push(v);
        x.extend((0..i % 5).map(|j| j as f64 * 0.7 - 1.0));
    }
    check_sin_cos_line(&x);
    let huge: Vec<f64> = (0..1000)
        .map(|_| 10f64.powf(rng.uniform(8.0, 308.0)))
        .collect();
    check_sin_cos_line(&huge);
    // A line that is all specials.
    check_sin_cos_line(&specials);
    check_sin_cos_line(&[]);
    // On the instruction set this processor has.
    let x: Vec<f64> = (0..4096).map(|_| rng.uniform(0.0, 3000.0)).collect();
    let (mut s, mut c) = (vec![0.0; 4096], vec![0.0; 4096]);
    sin_cos_line_on(Isa::detect(), &x, &mut s, &mut c);
    for i in 0..4096 {
        let (ws, wc) = fastmath::sin_cos(x[i]);
        assert_eq!(
            (s[i].to_bits(), c[i].to_bits()),
            (ws.to_bits(), wc.to_bits())
        );
    }
}

#[test]
#[should_panic(expected = "differ in length")]
fn polar_line_rejects_mismatched_slices() {
    polar_line_on(Isa::detect(), 1, 2, 1, 8, &mut [0.0; 8], &mut [0.0; 7]);
}

#[test]
#[should_panic(expected = "differ in length")]
fn sin_cos_line_rejects_mismatched_slices() {
    sin_cos_line_on(Isa::detect(), &[0.0; 8], &mut [0.0; 8], &mut [0.0; 7]);
}

/// Prints ns per element at ny = 4096: the scalar loops (gaussian_polar and sin_cos one
/// by one) vs the line functions, and each compiled path; medians of interleaved runs.
///
/// `cargo test --release --lib simd::tests::speed -- --ignored --nocapture`
#[test]
#[ignore]
fn speed() {
    use std::hint::black_box;
    use std::time::Instant;
    const NY: usize = 4096;
    const LINES: usize = 32;
    const ROUNDS: usize = 41;
    /// A case fills the two output lines for kx line `n`.
    type Case<'a> = (String, Box<dyn Fn(i64, &mut [f64], &mut [f64]) + 'a>);

    let mut rng = Rng(8);
    let x: Vec<f64> = (0..NY).map(|_| rng.uniform(0.0, 3000.0)).collect();
    let x = &x;
    let isas = Isa::available();

    let mut polar: Vec<Case> = vec![
        (
            "scalar gaussian_polar".into(),
            Box::new(|n, r, phi| {
                let seed = black_box(9u64);
                for i in 0..NY {
                    (r[i], phi[i]) = rng::gaussian_polar(seed, -n, -signed_index(i, NY));
                }
            }),
        ),
        (
            "polar_line".into(),
            Box::new(|n, r, phi| polar_line_on(Isa::detect(), black_box(9), n, -1, NY, r, phi)),
        ),
    ];
    let mut sincos: Vec<Case> = vec![
        (
            "scalar sin_cos".into(),
            Box::new(|_, s, c| {
                let x = black_box(x);
                for i in 0..NY {
                    (s[i], c[i]) = fastmath::sin_cos(x[i]);
                }
            }),
        ),
        (
            "sin_cos_line".into(),
            Box::new(|_, s, c| sin_cos_line_on(Isa::detect(), black_box(x), s, c)),
        ),
    ];
    for &isa in &isas {
        polar.push((
            format!("  on {isa:?}"),
            Box::new(move |n, r, phi| polar_line_on(isa, black_box(9), n, -1, NY, r, phi)),
        ));
        sincos.push((
            format!("  on {isa:?}"),
            Box::new(move |_, s, c| sin_cos_line_on(isa, black_box(x), s, c)),
        ));
    }

    let (mut a, mut b) = (vec![0.0; NY], vec![0.0; NY]);
    for (title, cases) in [("Gaussian draws", polar), ("sin_cos", sincos)] {
        let mut times = vec![Vec::with_capacity(ROUNDS); cases.len()];
        for _ in 0..ROUNDS {
            for (case, t) in cases.iter().zip(&mut times) {
                let start = Instant::now();
                for n in 0..LINES as i64 {
                    case.1(n, &mut a, &mut b);
                    black_box((&mut a, &mut b));
                }
                t.push(start.elapsed().as_secs_f64() * 1e9 / (LINES * NY) as f64);
            }
        }
        println!("{title}, ns per element at ny = {NY} (medians of {ROUNDS} interleaved runs):");
        let mut base = 0.0;
        for (case, mut t) in cases.iter().zip(times) {
            t.sort_by(f64::total_cmp);
            let median = t[t.len() / 2];
            if base == 0.0 {
                base = median;
            }
            println!(
                "  {:<24} {median:6.2} ns  (min {:6.2})  {:5.2}x",
                case.0,
                t[0],
                base / median
            );
        }
    }
}

#[test]
fn exp_line_equals_the_scalar_exp_bit_for_bit() {
    let mut x: Vec<f64> = (0..5000).map(|i| -800.0 + i as f64 * 0.3317).collect();
    x.extend([
        0.0,
        -0.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        709.0,
        -745.0,
        -1e300,
        1e-300,
    ]);
    let mut e = vec![0.0; x.len()];
    exp_line_on(Isa::detect(), &x, &mut e);
    for (i, (&x, &e)) in x.iter().zip(&e).enumerate() {
        let want = fastmath::exp(x);
        assert!(
            e.to_bits() == want.to_bits() || (e.is_nan() && want.is_nan()),
            "lane {i}: exp({x}) = {e} vs {want}"
        );
    }
    for isa in Isa::available() {
        exp_line_on(isa, &x, &mut e);
        for (i, (&x, &e)) in x.iter().zip(&e).enumerate() {
            let want = fastmath::exp(x);
            assert!(
                e.to_bits() == want.to_bits() || (e.is_nan() && want.is_nan()),
                "{isa:?}, lane {i}: exp({x}) = {e} vs {want}"
            );
        }
    }
}
