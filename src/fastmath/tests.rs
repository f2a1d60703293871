use super::exp::{EXP_FAST_LIMIT, EXP_LN2_N_HI, EXP_LN2_N_LO, EXP_N_INV_LN2};
use super::ln::{LN2_HI, LN2_LO};
use super::sin_cos::{
    FRAC_2_PI, PIO2_1, PIO2_2, PIO2_3, PIO2_HI, TWO_OVER_PI_BITS, reduce_payne_hanek,
    sin_cos_kernel,
};
use super::*;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// Tolerances against std. They are tighter than the module's targets (relative 1e-14
/// for exp/ln; absolute 1e-15 up to 16π and 1e-12 up to 1e8 for sin_cos) so that
/// regressions show, with room for a reference libm that is itself off by an ulp.
const EXP_REL_TOL: f64 = 1e-15;
const LN_REL_TOL: f64 = 1e-15;
/// sin/cos absolute error for |x| ≤ 16π, for |x| ≤ 1e8 and beyond (Payne–Hanek path).
const SIN_COS_ABS_TOL_SMALL: f64 = 1e-15;
const SIN_COS_ABS_TOL_LARGE: f64 = 1e-15;
const SIN_COS_ABS_TOL_HUGE: f64 = 1e-15;

/// SplitMix64, for reproducible pseudo-random test points.
struct Rng(u64);
impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        lo + (hi - lo) * u
    }
}

/// Evenly spaced points of [lo, hi], both ends included.
fn grid(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| lo + (hi - lo) * (i as f64 / (n - 1) as f64))
}

/// Distance in units in the last place between two finite doubles of the same sign.
fn ulp_diff(a: f64, b: f64) -> u64 {
    (a.to_bits() as i64).abs_diff(b.to_bits() as i64)
}

fn rel_err(got: f64, want: f64) -> f64 {
    if got == want {
        0.0
    } else {
        ((got - want) / want).abs()
    }
}

/// Tracks the largest error and its argument.
struct MaxErr {
    err: f64,
    at: f64,
}
impl MaxErr {
    fn new() -> Self {
        MaxErr { err: 0.0, at: 0.0 }
    }
    fn add(&mut self, err: f64, at: f64) {
        if err > self.err {
            self.err = err;
            self.at = at;
        }
    }
}

fn check_exp(x: f64, worst: &mut MaxErr) {
    let got = exp(x);
    let want = x.exp();
    if want.is_infinite() || want == 0.0 {
        assert_eq!(got, want, "exp({x:e}) = {got:e}, std gives {want:e}");
    } else if want < f64::MIN_POSITIVE {
        // Subnormal result: absolute precision is 1 subnormal ulp.
        assert!(
            ulp_diff(got, want) <= 1,
            "exp({x:e}) = {got:e}, std gives {want:e} (subnormal)"
        );
    } else {
        let err = rel_err(got, want);
        assert!(
            err <= EXP_REL_TOL,
            "exp({x:e}) = {got:e}, std gives {want:e}, relative error {err:e}"
        );
        worst.add(err, x);
    }
}

#[test]
fn single_precision_log2_and_exp2_are_within_their_bounds() {
    // log2: |Δ| ≤ LOG2_TOL·(1 + |log2 x|); 2^t: |Δ|/2^t ≤ EXP2_TOL (t exact in f32).
    const LOG2_TOL: f64 = 2e-7;
    const EXP2_TOL: f64 = 2e-7;
    let (mut worst_log, mut worst_exp) = (0.0f64, 0.0f64);
    let mut rng = Rng(7);
    for i in 0..200_000 {
        // x over the whole normal range, evenly in log2 x, and neighbours of 1.
        let x = if i % 10 == 0 {
            f32::from_bits(1.0f32.to_bits() - 50 + (i / 10 % 100) as u32)
        } else {
            rng.uniform(-126.0, 128.0).exp2() as f32
        };
        if !(x.is_normal()) {
            continue;
        }
        let want = f64::from(x).log2();
        let err = (f64::from(log2_f32(x)) - want).abs() / (1.0 + want.abs());
        worst_log = worst_log.max(err);
        assert!(
            err < LOG2_TOL,
            "log2_f32({x:e}) = {}, want {want}",
            log2_f32(x)
        );
        let t = rng.uniform(-1000.0, 1000.0) as f32;
        let (p, n) = exp2_parts_f32(t);
        assert_eq!(n as f32, t.round_ties_even(), "n of 2^{t}");
        let want = (f64::from(t) - f64::from(n)).exp2();
        let err = (f64::from(p) - want).abs() / want;
        worst_exp = worst_exp.max(err);
        assert!(err < EXP2_TOL, "2^{t}: p = {p}, want {want}");
    }
    eprintln!("log2_f32: largest |Δ|/(1 + |log2 x|) {worst_log:.2e}; 2^t: {worst_exp:.2e}");
    assert_eq!(log2_f32(1.0), 0.0);
    assert_eq!(log2_f32(0.5), -1.0);
    assert_eq!(log2_f32(1024.0), 10.0);
    assert_eq!(exp2_parts_f32(-3.0), (1.0, -3));
    // exp2_f32: normal results, 0 below 2^−126.
    assert_eq!(exp2_f32(3.0), 8.0);
    assert_eq!(exp2_f32(-126.5), 0.0);
    assert!(rel_err(f64::from(exp2_f32(-125.25)), (-125.25f64).exp2()) < EXP2_TOL);
}

#[test]
fn scale_f64_is_exact_in_range_and_saturates_outside() {
    for (p, e) in [
        (1.25f32, 0),
        (0.75, -1022),
        (1.4, 1023),
        (0.9, -300),
        (1.0, 77),
    ] {
        assert_eq!(scale_f64(p, e), f64::from(p) * 2f64.powi(e), "{p}·2^{e}");
    }
    assert_eq!(scale_f64(1.0, -1023), 0.0);
    assert_eq!(scale_f64(1.0, -5000), 0.0);
    assert_eq!(scale_f64(1.0, 1024), f64::INFINITY);
}

#[test]
fn exp_matches_std_over_dense_sweeps() {
    let mut worst = MaxErr::new();
    // The whole domain, with the grid offset so that it does not hit only round numbers.
    for x in grid(-746.0, 710.0, 400_001) {
        check_exp(x + 1.234e-4, &mut worst);
    }
    // Around zero, where Box–Muller and Phillips arguments live.
    for x in grid(-40.0, 5.0, 300_001) {
        check_exp(x, &mut worst);
    }
    // Tiny arguments and both signs.
    let mut rng = Rng(1);
    for _ in 0..100_000 {
        let x = f64::from_bits(rng.next_u64() & 0x3FEF_FFFF_FFFF_FFFF) * 0.5;
        check_exp(x, &mut worst);
        check_exp(-x, &mut worst);
    }
    // Around the overflow and underflow limits, including subnormal results.
    for x in grid(705.0, 709.9, 50_001).chain(grid(-745.3, -700.0, 100_001)) {
        check_exp(x, &mut worst);
    }
    // Near the reduction boundaries (k + 1/2)·ln2/32, where the table index switches.
    for k in -34_440..=32_780 {
        let b = (k as f64 + 0.5) * (std::f64::consts::LN_2 / 32.0);
        for d in [-1e-12, 0.0, 1e-12] {
            check_exp(b + d, &mut worst);
        }
    }
    // Around the switch between the fast and the cold path.
    for x in grid(-EXP_FAST_LIMIT - 1e-9, -EXP_FAST_LIMIT + 1e-9, 1001).chain(grid(
        EXP_FAST_LIMIT - 1e-9,
        EXP_FAST_LIMIT + 1e-9,
        1001,
    )) {
        check_exp(x, &mut worst);
    }
    println!(
        "exp: max relative error {:e} at x = {:e}",
        worst.err, worst.at
    );
}

#[test]
fn exp_special_values() {
    assert_eq!(exp(0.0), 1.0);
    assert_eq!(exp(-0.0), 1.0);
    assert_eq!(exp(1e-300), 1.0);
    assert_eq!(exp(-1e-300), 1.0);
    assert_eq!(exp(f64::INFINITY), f64::INFINITY);
    assert_eq!(exp(f64::NEG_INFINITY), 0.0);
    assert!(exp(f64::NAN).is_nan());
    assert!(exp(-f64::NAN).is_nan());
    assert_eq!(exp(709.79), f64::INFINITY);
    assert_eq!(exp(710.0), f64::INFINITY);
    assert_eq!(exp(f64::MAX), f64::INFINITY);
    assert!(exp(709.78).is_finite());
    // Just below the overflow threshold (fdlibm's o_threshold).
    let big = exp(709.782_712_893_383_9);
    assert!(
        big.is_finite() && big > 1.797e308,
        "exp(709.7827128933839) = {big}"
    );
    assert_eq!(exp(-745.2), 0.0);
    assert_eq!(exp(-746.0), 0.0);
    assert_eq!(exp(-f64::MAX), 0.0);
    assert_eq!(exp(-745.13), 5e-324);
    assert_eq!(exp(-744.5), 5e-324);
    let e = exp(1.0);
    assert!(rel_err(e, std::f64::consts::E) <= 2.3e-16, "exp(1) = {e}");
    for k in -1022..=1023 {
        // Exact powers of two are reproduced to within an ulp.
        let x = k as f64 * std::f64::consts::LN_2;
        let want = x.exp();
        assert!(rel_err(exp(x), want) <= EXP_REL_TOL, "exp({x})");
    }
}

fn check_ln(x: f64, worst: &mut MaxErr) {
    let got = ln(x);
    let want = x.ln();
    let err = rel_err(got, want);
    assert!(
        err <= LN_REL_TOL,
        "ln({x:e}) = {got:e}, std gives {want:e}, relative error {err:e}"
    );
    worst.add(err, x);
}

#[test]
fn ln_matches_std_over_dense_sweeps() {
    let mut worst = MaxErr::new();
    let mut rng = Rng(2);
    // Every positive finite double, subnormals included, log-uniformly.
    for _ in 0..300_000 {
        let x = f64::from_bits(rng.next_u64() % 0x7FF0_0000_0000_0000);
        if x > 0.0 {
            check_ln(x, &mut worst);
        }
    }
    // Box–Muller's (0, 1].
    for _ in 0..300_000 {
        check_ln(1.0 - rng.uniform(0.0, 1.0), &mut worst);
    }
    // Around 1, where ln x ≈ x − 1 is small (relative accuracy matters most here).
    for x in grid(0.5, 2.0, 200_001) {
        check_ln(x, &mut worst);
    }
    for _ in 0..100_000 {
        let d = f64::from_bits(rng.next_u64() & 0x3F8F_FFFF_FFFF_FFFF); // < 2^-6
        check_ln(1.0 + d, &mut worst);
        check_ln(1.0 - d, &mut worst);
    }
    // Around the normalisation boundary √2/2·2^k.
    for k in -1022..1023 {
        let b = std::f64::consts::FRAC_1_SQRT_2 * 2f64.powi(k);
        let mut x = b;
        for _ in 0..4 {
            x = f64::from_bits(x.to_bits() - 1);
        }
        for _ in 0..8 {
            check_ln(x, &mut worst);
            x = f64::from_bits(x.to_bits() + 1);
        }
    }
    // Exact powers of two, normal and subnormal.
    for k in -1074..=1023 {
        check_ln(2f64.powi(k), &mut worst);
        check_ln(f64::from_bits(2f64.powi(k).to_bits() + 1), &mut worst);
    }
    // Subnormals of every magnitude, and the extremes.
    for bits in [1u64, 2, 3, 0xF_FFFF_FFFF_FFFF, 0x10_0000_0000_0000] {
        check_ln(f64::from_bits(bits), &mut worst);
    }
    check_ln(f64::MAX, &mut worst);
    println!(
        "ln: max relative error {:e} at x = {:e}",
        worst.err, worst.at
    );
}

#[test]
fn ln_special_values() {
    assert_eq!(ln(1.0).to_bits(), 0.0f64.to_bits());
    assert_eq!(ln(0.0), f64::NEG_INFINITY);
    assert_eq!(ln(-0.0), f64::NEG_INFINITY);
    assert_eq!(ln(f64::INFINITY), f64::INFINITY);
    assert!(ln(f64::NEG_INFINITY).is_nan());
    assert!(ln(-1.0).is_nan());
    assert!(ln(-5e-324).is_nan());
    assert!(ln(f64::NAN).is_nan());
    assert!(rel_err(ln(2.0), std::f64::consts::LN_2) <= 1.2e-16);
    assert!(rel_err(ln(10.0), std::f64::consts::LN_10) <= 2.3e-16);
    assert!(rel_err(ln(std::f64::consts::E), 1.0) <= 2.3e-16);
    // ln of the smallest subnormal, −1074·ln 2.
    assert!(rel_err(ln(5e-324), -744.440_071_921_381_3) <= 2.3e-16);
}

#[test]
fn exp_and_ln_are_inverse() {
    let mut rng = Rng(3);
    for _ in 0..200_000 {
        // x over the normal range: exp(ln x) has relative error ≈ |ln x|·ulp.
        let x = f64::from_bits(rng.next_u64() % 0x7FE0_0000_0000_0000 + (1 << 52));
        let l = ln(x);
        let back = exp(l);
        let tol = (l.abs() + 2.0) * 2.3e-16;
        assert!(rel_err(back, x) <= tol, "exp(ln({x:e})) = {back:e}");
        // y = ln(exp(y)) for y where exp is normal.
        let y = rng.uniform(-708.0, 709.0);
        let back = ln(exp(y));
        assert!(
            (back - y).abs() <= 4.5e-16 * y.abs().max(1.0),
            "ln(exp({y}))"
        );
    }
}

fn check_sin_cos(x: f64, tol: f64, worst: &mut MaxErr) {
    let (s, c) = sin_cos(x);
    let (ws, wc) = x.sin_cos();
    let err = (s - ws).abs().max((c - wc).abs());
    assert!(
        err <= tol,
        "sin_cos({x:e}) = ({s:e}, {c:e}), std gives ({ws:e}, {wc:e}), abs error {err:e}"
    );
    worst.add(err, x);
}

#[test]
fn sin_cos_matches_std_for_moderate_arguments() {
    let mut worst = MaxErr::new();
    let lim = 16.0 * PI;
    for x in grid(-lim, lim, 600_001) {
        check_sin_cos(x, SIN_COS_ABS_TOL_SMALL, &mut worst);
    }
    let mut rng = Rng(4);
    for _ in 0..100_000 {
        check_sin_cos(
            rng.uniform(0.0, 2.0 * PI),
            SIN_COS_ABS_TOL_SMALL,
            &mut worst,
        );
    }
    // Multiples of π/4 (zeros, extrema and the quadrant boundaries) and their
    // neighbouring doubles; tiny arguments.
    for k in -64..=64 {
        let x = k as f64 * FRAC_PI_4;
        for d in [-2i64, -1, 0, 1, 2] {
            // Neighbouring doubles (of the same sign; 0 gives the smallest subnormals).
            let y = if x == 0.0 {
                d as f64 * 5e-324
            } else {
                f64::from_bits((x.to_bits() as i64 + d) as u64)
            };
            check_sin_cos(y, SIN_COS_ABS_TOL_SMALL, &mut worst);
        }
    }
    for e in -1074..0 {
        let x = 2f64.powi(e);
        check_sin_cos(x, SIN_COS_ABS_TOL_SMALL, &mut worst);
        check_sin_cos(-x, SIN_COS_ABS_TOL_SMALL, &mut worst);
    }
    println!(
        "sin_cos, |x| <= 16π: max abs error {:e} at x = {:e}",
        worst.err, worst.at
    );
}

#[test]
fn sin_cos_matches_std_for_large_arguments() {
    let mut worst = MaxErr::new();
    let mut rng = Rng(5);
    for _ in 0..150_000 {
        check_sin_cos(rng.uniform(-1e8, 1e8), SIN_COS_ABS_TOL_LARGE, &mut worst);
        // Log-uniform magnitudes 1..1e8.
        let x = 10f64.powf(rng.uniform(0.0, 8.0));
        check_sin_cos(x, SIN_COS_ABS_TOL_LARGE, &mut worst);
    }
    // Multiples of π/2 up to the Cody–Waite limit, where r is tiny.
    for k in (1..64_000_000i64).step_by(6_421) {
        check_sin_cos(k as f64 * FRAC_PI_2, SIN_COS_ABS_TOL_LARGE, &mut worst);
        check_sin_cos(-(k as f64) * FRAC_PI_2, SIN_COS_ABS_TOL_LARGE, &mut worst);
    }
    for x in [1e8, -1e8, 99_999_999.999_999_99, 1.0e8 + 1e-8] {
        check_sin_cos(x, SIN_COS_ABS_TOL_LARGE, &mut worst);
    }
    println!(
        "sin_cos, |x| <= 1e8: max abs error {:e} at x = {:e}",
        worst.err, worst.at
    );
    // Beyond: the Payne–Hanek path, up to f64::MAX.
    let mut worst = MaxErr::new();
    for _ in 0..100_000 {
        let x = 10f64.powf(rng.uniform(8.0, 308.25));
        let x = if rng.next_u64() & 1 == 0 { x } else { -x };
        check_sin_cos(x, SIN_COS_ABS_TOL_HUGE, &mut worst);
    }
    for x in [f64::MAX, -f64::MAX, 2f64.powi(1023), 1e22, 2f64.powi(60)] {
        check_sin_cos(x, SIN_COS_ABS_TOL_HUGE, &mut worst);
    }
    println!(
        "sin_cos, |x| > 1e8: max abs error {:e} at x = {:e}",
        worst.err, worst.at
    );
    // Independent of std: correctly rounded values (from 2000-bit arithmetic).
    for (x, sin_x, cos_x) in [
        (1e22, -0.852_200_849_767_188_8, 0.523_214_785_395_139),
        (
            f64::MAX,
            0.004_961_954_789_184_062,
            -0.999_987_689_426_559_9,
        ),
        (1e8, 0.931_639_027_109_726, -0.363_385_089_355_690_5),
    ] {
        let (s, c) = sin_cos(x);
        let err = (s - sin_x).abs().max((c - cos_x).abs());
        assert!(err <= 2.3e-16, "sin_cos({x:e}) = ({s}, {c}), error {err:e}");
    }
}

#[test]
fn payne_hanek_agrees_with_cody_waite() {
    // Both reductions are accurate where both apply; compare them directly.
    let mut rng = Rng(6);
    for _ in 0..100_000 {
        let x = 10f64.powf(rng.uniform(-2.0, 8.0));
        let x = if rng.next_u64() & 1 == 0 { x } else { -x };
        let (r, q) = reduce_payne_hanek(x);
        let (s1, c1) = sin_cos_kernel(r, q);
        let (s2, c2) = sin_cos(x);
        let err = (s1 - s2).abs().max((c1 - c2).abs());
        assert!(err <= 4e-16, "reductions differ at x = {x:e} by {err:e}");
    }
}

#[test]
fn sin_cos_special_values_and_identities() {
    assert_eq!(sin_cos(0.0), (0.0, 1.0));
    let (s, c) = sin_cos(-0.0);
    assert!(s == 0.0 && s.is_sign_negative() && c == 1.0, "sin_cos(-0)");
    assert_eq!(sin_cos(1e-300), (1e-300, 1.0));
    assert_eq!(sin_cos(-5e-324), (-5e-324, 1.0));
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let (s, c) = sin_cos(x);
        assert!(s.is_nan() && c.is_nan(), "sin_cos({x})");
    }
    let mut rng = Rng(7);
    for _ in 0..200_000 {
        let x = rng.uniform(-1e4, 1e4);
        let (s, c) = sin_cos(x);
        // Odd/even symmetry holds exactly.
        let (sn, cn) = sin_cos(-x);
        assert!(sn == -s && cn == c, "sin_cos(-{x}) is not (-sin, cos)");
        let norm = s * s + c * c;
        assert!((norm - 1.0).abs() <= 4.5e-16, "sin² + cos² = {norm} at {x}");
        assert!(s.abs() <= 1.0 && c.abs() <= 1.0, "|sin_cos({x})| > 1");
    }
}

/// FNV-1a over the bits of the outputs for fixed inputs.
fn output_hashes() -> [u64; 3] {
    fn fnv(h: &mut u64, bits: u64) {
        for byte in bits.to_le_bytes() {
            *h = (*h ^ byte as u64).wrapping_mul(0x0000_0100_0000_01B3);
        }
    }
    let mut h = [0xCBF2_9CE4_8422_2325u64; 3];
    let mut rng = Rng(9);
    for _ in 0..20_000 {
        fnv(&mut h[0], exp(rng.uniform(-750.0, 712.0)).to_bits());
        fnv(&mut h[1], ln(f64::from_bits(rng.next_u64() >> 1)).to_bits());
        let (s, c) = sin_cos(rng.uniform(-1e3, 1e3));
        fnv(&mut h[2], s.to_bits());
        fnv(&mut h[2], c.to_bits());
    }
    h
}

#[test]
fn outputs_are_bit_stable() {
    // The point of this module: the same bits on every platform, compiler and
    // optimisation level. A change here changes generated height maps; update the
    // constants only for a deliberate change of algorithm.
    let h = output_hashes();
    println!(
        "output hashes: {:#018X} {:#018X} {:#018X}",
        h[0], h[1], h[2]
    );
    assert_eq!(
        h,
        [
            0xE3FC_AB2E_B25C_B200,
            0x7547_C8E2_CE34_44B5,
            0x8D29_28B2_EC68_21A5
        ]
    );
}

#[test]
fn constants_are_what_they_claim() {
    assert_eq!(LN2_HI + LN2_LO, std::f64::consts::LN_2);
    assert_eq!(LN2_HI.to_bits() & 0x1F_FFFF, 0, "LN2_HI has 32 bits");
    assert_eq!(EXP_N_INV_LN2, 32.0 * std::f64::consts::LOG2_E);
    assert_eq!(EXP_LN2_N_HI + EXP_LN2_N_LO, std::f64::consts::LN_2 / 32.0);
    assert_eq!(
        EXP_LN2_N_HI.to_bits() & 0x1_FFFF,
        0,
        "EXP_LN2_N_HI has 36 bits"
    );
    assert_eq!(PIO2_HI, FRAC_PI_2);
    assert_eq!(PIO2_1 + PIO2_2, PIO2_1 + PIO2_2 + PIO2_3 - PIO2_3);
    assert_eq!(PIO2_1.to_bits() & 0x3FF_FFFF, 0, "PIO2_1 has 27 bits");
    assert_eq!(PIO2_2.to_bits() & 0x3FF_FFFF, 0, "PIO2_2 has 27 bits");
    assert_eq!(PIO2_1 + (PIO2_2 + PIO2_3), FRAC_PI_2);
    // The 2/π table starts with the bits of FRAC_2_PI (truncated rather than rounded).
    let mantissa = (TWO_OVER_PI_BITS[1] >> 11) & 0xF_FFFF_FFFF_FFFF;
    let lead = f64::from_bits(0x3FE0_0000_0000_0000 | mantissa);
    assert!(
        (lead - FRAC_2_PI).abs() <= 1.2e-16,
        "2/π table starts with {lead}"
    );
}

/// Prints ns per call, fastmath vs std, as medians of interleaved runs:
/// *throughput* (independent calls, results stored) and *latency* (each argument
/// depends on the previous result, as in `acc = f(x + acc·0)`); the harness's own
/// cost is printed as `identity`.
///
/// `cargo test --release --lib fastmath::tests::speed_vs_std -- --ignored --nocapture`
#[test]
#[ignore]
fn speed_vs_std() {
    use std::hint::black_box;
    use std::time::Instant;
    const N: usize = 1 << 14;
    const ROUNDS: usize = 21;
    const REPS: usize = 16;

    fn throughput(inputs: &[f64], out: &mut [f64], f: impl Fn(f64) -> f64) -> f64 {
        let start = Instant::now();
        for _ in 0..REPS {
            for (o, &x) in out.iter_mut().zip(inputs) {
                *o = f(black_box(x));
            }
            black_box(&mut *out);
        }
        start.elapsed().as_secs_f64() * 1e9 / (REPS * inputs.len()) as f64
    }
    fn latency(inputs: &[f64], f: impl Fn(f64) -> f64) -> f64 {
        let start = Instant::now();
        let mut acc = 0.0;
        for _ in 0..REPS {
            for &x in inputs {
                acc = f(x + acc * 0.0);
            }
        }
        black_box(acc);
        start.elapsed().as_secs_f64() * 1e9 / (REPS * inputs.len()) as f64
    }
    fn median(mut v: Vec<f64>) -> f64 {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    }
    macro_rules! compare {
        ($name:expr, $inputs:expr, $ours:expr, $theirs:expr) => {{
            let inputs: &[f64] = $inputs;
            let mut out = vec![0.0; inputs.len()];
            let mut t = [(); 4].map(|_| Vec::with_capacity(ROUNDS));
            for _ in 0..ROUNDS {
                t[0].push(throughput(inputs, &mut out, $ours));
                t[1].push(throughput(inputs, &mut out, $theirs));
                t[2].push(latency(inputs, $ours));
                t[3].push(latency(inputs, $theirs));
            }
            let [a, b, c, d] = t.map(median);
            println!(
                "{:<18} throughput {a:5.2} vs {b:5.2} ns ({:.2}x)   latency {c:5.2} vs {d:5.2} ns ({:.2}x)",
                $name,
                b / a,
                d / c
            );
        }};
    }

    let mut rng = Rng(8);
    let exp_in: Vec<f64> = (0..N).map(|_| rng.uniform(-30.0, 5.0)).collect();
    let ln_in: Vec<f64> = (0..N).map(|_| 1.0 - rng.uniform(0.0, 1.0)).collect();
    let angle_in: Vec<f64> = (0..N).map(|_| rng.uniform(0.0, 2.0 * PI)).collect();
    let phase_in: Vec<f64> = (0..N).map(|_| rng.uniform(0.0, 3000.0)).collect();
    let ours = |x| {
        let (s, c) = sin_cos(x);
        s + c
    };
    let theirs = |x: f64| {
        let (s, c) = x.sin_cos();
        s + c
    };
    println!("fastmath vs std, ns per call (medians of {ROUNDS} interleaved runs)");
    compare!("identity", &exp_in, |x| x, |x| x);
    compare!("exp [-30, 5)", &exp_in, exp, f64::exp);
    compare!("ln (0, 1]", &ln_in, ln, f64::ln);
    compare!("sin_cos [0, 2π)", &angle_in, ours, theirs);
    compare!("sin_cos [0, 3000)", &phase_in, ours, theirs);
}

#[test]
fn powi_has_the_bits_of_std_powi() {
    // Exponents as the second-order fields use them and beyond, bases over many octaves
    // (both signs); `black_box` keeps std's exponent a run-time value (its call).
    let mut rng = Rng(11);
    for _ in 0..20_000 {
        let x = rng.uniform(-8.0, 8.0) * 2f64.powf(rng.uniform(-20.0, 20.0));
        for n in -12..=12 {
            let theirs = x.powi(std::hint::black_box(n));
            assert_eq!(powi(x, n).to_bits(), theirs.to_bits(), "{x:e}^{n}");
        }
    }
}
