//! Second-order seas against their physical references: Pierson–Moskowitz at 15 m/s
//! with Hasselmann spreading, each seed generated linear and second-order (the same free
//! waves), so the differences show the bound waves alone.

mod common;

use seasynth::config::Params;
use seasynth::config::layers::{Assignment, apply};
use seasynth::field::synthesize;
use seasynth::measure::analyze;
use seasynth::measure::waves::{GAUSSIAN_P_3SIGMA, SeaContext, moments, wave_statistics};
use seasynth::spectrum::G;

fn params(sets: &[&str]) -> Params {
    let a: Vec<Assignment> = sets
        .iter()
        .map(|s| Assignment::parse_set(s).unwrap())
        .collect();
    apply(Params::default(), &a).unwrap()
}

const BASE: [&str; 6] = [
    "method=fft",
    "spectrum=pierson-moskowitz",
    "wind-speed=15",
    "spectrum.spreading=hasselmann",
    "size=256",
    "extent=2048",
];

#[test]
fn pierson_moskowitz_storm_has_tayfun_skewness_and_raised_crests() {
    // Tayfun's narrow-band skewness λ3 = 3 k_m σ (k_m = ω_m²/g, ω_m = 2π/Tm01 of the
    // measured field). A directional, broad sea whose bound waves are formed from the
    // components of 98 % of the variance has less: SKEW_BAND of λ3. A kernel of the wrong
    // sign gives negative skewness, a factor 2 off gives ≈ 2× too much.
    const SKEW_BAND: (f64, f64) = (0.45, 1.1);
    // 4·std of the second-order sea against the linear Hs (the bound waves add ≈ (kσ)²
    // of the variance).
    const HS_TOL: f64 = 0.02;
    let mut lin = params(&BASE);
    let mut so = lin.clone();
    so = apply(
        so,
        &[
            Assignment::parse_set("nonlinear=second-order").unwrap(),
            Assignment::parse_set("spectrum.nonlinear_fraction=0.98").unwrap(),
        ],
    )
    .unwrap();
    let (mut skew_lin, mut skew_so, mut tayfun, mut p3_lin, mut p3_so) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let seeds = [11u64, 12, 13, 14];
    for &seed in &seeds {
        lin.seed = seed;
        so.seed = seed;
        let gl = synthesize(&lin).unwrap().grid;
        let syn = synthesize(&so).unwrap();
        let info = syn.info.second_order.clone().unwrap();
        eprintln!("{info:?}");
        let gs = syn.grid;
        let (sl, _, sigma) = moments(&gl.data);
        let (ss, _, sigma2) = moments(&gs.data);
        let a = analyze(&gl, None);
        let w = wave_statistics(&gl, &a, &SeaContext::default());
        let tm01 = w.crests.mean_period_tm01_s.unwrap();
        let km = (2.0 * std::f64::consts::PI / tm01).powi(2) / G;
        let lambda3 = 3.0 * km * sigma;
        let a2 = analyze(&gs, None);
        let w2 = wave_statistics(&gs, &a2, &SeaContext::default());
        eprintln!(
            "seed {seed}: skewness linear {sl:.4}, second-order {ss:.4}, Tayfun {lambda3:.4}; \
             P(η > 3σ) {:.5} → {:.5} (Gaussian {GAUSSIAN_P_3SIGMA:.5}); Hs {:.4} → {:.4} m; \
             kurtosis {:.3} → {:.3}",
            w.exceed_3sigma,
            w2.exceed_3sigma,
            4.0 * sigma,
            4.0 * sigma2,
            w.kurtosis,
            w2.kurtosis,
        );
        assert!(
            ((sigma2 / sigma) - 1.0).abs() < HS_TOL,
            "seed {seed}: Hs {} vs linear {}",
            4.0 * sigma2,
            4.0 * sigma
        );
        skew_lin += sl;
        skew_so += ss;
        tayfun += lambda3;
        p3_lin += w.exceed_3sigma;
        p3_so += w2.exceed_3sigma;
    }
    let n = seeds.len() as f64;
    let (skew_lin, skew_so, tayfun) = (skew_lin / n, skew_so / n, tayfun / n);
    let bound = skew_so - skew_lin;
    eprintln!(
        "mean: skewness added by the bound waves {bound:.4}, Tayfun {tayfun:.4} (ratio {:.3}); \
         P(η > 3σ) linear {:.5}, second-order {:.5}",
        bound / tayfun,
        p3_lin / n,
        p3_so / n
    );
    assert!(
        bound > SKEW_BAND.0 * tayfun && bound < SKEW_BAND.1 * tayfun,
        "skewness added {bound} vs Tayfun {tayfun}"
    );
    // High crests are more frequent than in the Gaussian sea.
    assert!(p3_so > 1.3 * p3_lin, "P(η > 3σ) {p3_so} vs linear {p3_lin}");
}

#[test]
fn a_hybrid_sea_blends_the_second_order_fft_sea() {
    // h = α·h_fft + (1 − α)·b·h_perlin (Li Tian eq. 10): at a constant α the hybrid's
    // second-order field less its linear one is α times the fft method's (the same free
    // waves, the same b = max|h̃0| of the linear draws, the same noise), to the rounding
    // of single-precision heights (TOL_M). The bound waves themselves are larger than
    // BOUND_MIN_M rms, so a hybrid that dropped them fails.
    const ALPHA: f32 = 0.6;
    const TOL_M: f32 = 2e-6;
    const BOUND_MIN_M: f64 = 0.01;
    let field = |method: &'static str, nonlinear: &'static str| {
        let mut sets = BASE.to_vec();
        sets.extend([
            method,
            nonlinear,
            "blend.alpha.kind=constant",
            "blend.alpha.value=0.6",
        ]);
        synthesize(&params(&sets)).unwrap()
    };
    let fft = |n| field("method=fft", n).grid.data;
    let (f1, f2) = (fft("nonlinear=linear"), fft("nonlinear=second-order"));
    let h1 = field("method=hybrid", "nonlinear=linear");
    let h2 = field("method=hybrid", "nonlinear=second-order");
    let info = h2.info.second_order.clone();
    assert!(
        info.as_ref().is_some_and(|i| i.method.is_some()),
        "the hybrid's sidecar records the bound waves: {info:?}"
    );
    assert!(h1.info.second_order.is_none());
    let (h1, h2) = (h1.grid.data, h2.grid.data);
    let n = f1.len() as f64;
    let bound_rms = (f2
        .iter()
        .zip(&f1)
        .map(|(a, b)| f64::from(a - b).powi(2))
        .sum::<f64>()
        / n)
        .sqrt();
    assert!(bound_rms > BOUND_MIN_M, "bound waves of {bound_rms} m rms");
    let worst = (0..f1.len())
        .map(|i| ((h2[i] - h1[i]) - ALPHA * (f2[i] - f1[i])).abs())
        .fold(0.0f32, f32::max);
    eprintln!("bound waves {bound_rms:.4} m rms; hybrid against α·fft: {worst:.2e} m at most");
    assert!(
        worst <= TOL_M,
        "the hybrid's bound waves differ from α·fft's by {worst} m"
    );
}

#[test]
fn linear_is_the_default_and_second_order_needs_an_fft_sea_and_no_choppiness() {
    let p = params(&BASE);
    assert!(p.spectrum.nonlinear.is_linear());
    for (set, name) in [
        ("method=filtered-noise", "--nonlinear"),
        ("method=perlin", "--nonlinear"),
        ("method=trochoid", "--nonlinear"),
        ("spectrum=phillips", "--nonlinear"),
        ("choppiness=0.5", "--choppiness"),
        ("spectrum.nonlinear_fraction=0", "nonlinear_fraction"),
        ("spectrum.nonlinear_cutoff=0", "nonlinear_cutoff"),
        ("spectrum.nonlinear_cutoff=-1", "nonlinear_cutoff"),
    ] {
        let mut sets = BASE.to_vec();
        sets.push("nonlinear=second-order");
        sets.push(set);
        let a: Vec<Assignment> = sets
            .iter()
            .map(|s| Assignment::parse_set(s).unwrap())
            .collect();
        let e = apply(Params::default(), &a)
            .and_then(|p| p.validate().map_err(Into::into).map(|_| p))
            .err()
            .unwrap_or_else(|| panic!("{set} with second-order must be refused"));
        assert!(e.to_string().contains(name), "{set}: {e}");
    }
}

#[test]
fn second_order_loops_and_refuses_choppiness_from_the_command_line() {
    // With a loop period T, ω_i ± ω_j are multiples of 2π/T: the field at t + T is the
    // field at t, bit for bit; the second-order field differs from the linear one.
    let mut sets = BASE.to_vec();
    sets.extend([
        "size=64",
        "extent=1024",
        "nonlinear=second-order",
        "loop-period=20",
    ]);
    let p = params(&sets);
    let at = |t: f64| {
        let q = Params {
            time_s: t,
            ..p.clone()
        };
        synthesize(&q).unwrap().grid.data
    };
    let (a, b, c) = (at(3.0), at(23.0), at(4.0));
    assert_eq!(a, b, "t and t + T");
    assert_ne!(a, c);
    // The looping pairs are binned by multiple; a loop too long for the bins keeps the
    // per-frame pair sum, and loops as well.
    let multiples = |q: &Params| {
        synthesize(q)
            .unwrap()
            .info
            .second_order
            .unwrap()
            .loop_multiples
    };
    assert!(multiples(&p).is_some_and(|n| n >= 3));
    let long = Params {
        motion: seasynth::config::MotionParams {
            loop_period_s: Some(1e5),
            ..p.motion.clone()
        },
        ..p.clone()
    };
    assert_eq!(multiples(&long), None);
    let long_at = |t: f64| {
        let q = Params {
            time_s: t,
            ..long.clone()
        };
        synthesize(&q).unwrap().grid.data
    };
    assert_eq!(long_at(3.0), long_at(3.0 + 1e5), "t and t + T, per frame");
    let lin = Params {
        time_s: 3.0,
        spectrum: seasynth::config::SpectrumParams {
            nonlinear: seasynth::config::Nonlinear::Linear,
            ..p.spectrum.clone()
        },
        ..p.clone()
    };
    assert_ne!(synthesize(&lin).unwrap().grid.data, a);
    let dir = tempfile::tempdir().unwrap();
    let err = common::run_exit2(
        dir.path(),
        &[
            "generate",
            "--method",
            "fft",
            "--spectrum",
            "pierson-moskowitz",
            "--nonlinear",
            "second-order",
            "--choppiness",
            "1",
            "--size",
            "32",
            "-o",
            "x.tif",
        ],
    );
    assert!(err.contains("--choppiness"), "{err}");
    assert!(common::names_in(dir.path()).is_empty(), "no file left");
}

/// A deep 64² second-order sea over 640 m, 0.4 frames a second (`extra` before `-q`).
fn small_sea(extra: &[&'static str]) -> Vec<&'static str> {
    let mut sea = vec![
        "--method",
        "fft",
        "--spectrum",
        "pierson-moskowitz",
        "--wind-speed",
        "12",
        "--spreading",
        "hasselmann",
        "--nonlinear",
        "second-order",
        "--size",
        "64",
        "--extent",
        "640",
        "--fps",
        "0.4",
    ];
    sea.extend(extra);
    sea.push("-q");
    sea
}

/// Runs `animate` of `frames` frames of `sea` in `dir` with 1 and 2 threads (into `1/` and
/// `2/`), asserts the same bytes, moving frames, and frames 1 and 3 equal to `generate
/// --time k/fps` (into g.tif); returns the frames' bytes.
fn frames_are_generate(dir: &std::path::Path, sea: &[&str], frames: usize) -> Vec<Vec<u8>> {
    let count = frames.to_string();
    for threads in ["1", "2"] {
        let mut a = vec!["animate", "--frames", &count, "--format", "tif"];
        a.extend(sea);
        a.extend(["--threads", threads, "-o", threads]);
        common::run_ok(dir, &a);
    }
    let frame = |t: &str, k: usize| common::read(&dir.join(format!("{t}/frame_{k:05}.tif")));
    for k in 0..frames {
        assert_eq!(frame("1", k), frame("2", k), "frame {k}: 1 and 2 threads");
    }
    assert_ne!(frame("1", 0), frame("1", 1));
    for k in [1usize, 3] {
        let t = format!("{}", k as f64 / 0.4);
        let mut g = vec!["generate", "--time", &t, "-o", "g.tif", "--force"];
        g.extend(sea);
        common::run_ok(dir, &g);
        assert_eq!(
            common::read(&dir.join("g.tif")),
            frame("1", k),
            "frame {k} and generate --time {t}"
        );
    }
    (0..frames).map(|k| frame("1", k)).collect()
}

#[test]
fn an_unlooped_second_order_animation_is_generate_at_each_time_at_any_thread_count() {
    // Without a loop the default (`auto`) takes the fitted method on this deep sea, its
    // components and fit prepared once for the sequence: every frame of `animate` is
    // `generate --time k/fps` bit for bit, with 1 or 2 threads, and the frames move.
    let dir = tempfile::tempdir().unwrap();
    frames_are_generate(dir.path(), &small_sea(&[]), 4);
    let side = common::json_file(&dir.path().join("g.json"));
    assert_eq!(side["synthesis"]["second_order"]["method"], "fitted");
    // The same at finite depth (double precision, the S·A terms), the fitted method asked
    // for: a sequence's output coefficients are tabulated once, a single frame's computed
    // at each output.
    let dir = tempfile::tempdir().unwrap();
    let depth_20 = ["--depth", "20", "--set", "spectrum.nonlinear_method=fitted"];
    frames_are_generate(dir.path(), &small_sea(&depth_20), 4);
    let side = common::json_file(&dir.path().join("g.json"));
    assert_eq!(side["synthesis"]["second_order"]["method"], "fitted");
    // The hybrid method's FFT sea: the same, under the blend with the noise.
    let dir = tempfile::tempdir().unwrap();
    let mut hybrid = small_sea(&[]);
    assert_eq!(hybrid[..2], ["--method", "fft"]);
    hybrid[1] = "hybrid";
    frames_are_generate(dir.path(), &hybrid, 4);
    let side = common::json_file(&dir.path().join("g.json"));
    assert_eq!(side["params"]["method"], "hybrid");
    assert_eq!(side["synthesis"]["second_order"]["method"], "fitted");
}

#[test]
fn a_looping_second_order_animation_is_generate_at_each_time_at_any_thread_count() {
    // A looping sea's pair sum is binned once by the pairs' multiples of 2π/T: every
    // frame of `animate` is `generate --time k/fps` bit for bit, with 1 or 2 threads, a
    // frame one period on repeats the first, and the sidecar records the bins.
    let dir = tempfile::tempdir().unwrap();
    let sea = small_sea(&["--loop-period", "10"]);
    let frames = frames_are_generate(dir.path(), &sea, 6);
    // Frame 4 is at t = 10 s = T.
    assert_eq!(frames[0], frames[4], "one period on");
    // Without a loop the exact pair sum sums its pairs at every frame: animate says so, and
    // how to avoid it (the default `auto` takes the fitted method on this deep sea).
    let mut unlooped: Vec<&str> = sea
        .iter()
        .copied()
        .filter(|a| !matches!(*a, "--loop-period" | "10" | "-q"))
        .collect();
    let stderr_of = |out: &str, args: &[&str]| {
        let mut a = vec!["animate", "--frames", "2", "--format", "tif", "-o", out];
        a.extend(args);
        let run = common::seasynth().current_dir(dir.path()).args(&a).output();
        String::from_utf8(run.unwrap().stderr).unwrap()
    };
    let err = stderr_of("a", &unlooped);
    assert!(!err.contains("note: without --loop-period"), "{err}");
    unlooped.extend(["--set", "spectrum.nonlinear_method=pairs"]);
    let err = stderr_of("u", &unlooped);
    assert!(err.contains("note: without --loop-period"), "{err}");
    let looped: Vec<&str> = sea.iter().copied().filter(|a| *a != "-q").collect();
    let err = stderr_of("l", &looped);
    assert!(!err.contains("note: without --loop-period"), "{err}");
    let side = common::json_file(&dir.path().join("g.json"));
    let multiples = side["synthesis"]["second_order"]["loop_multiples"]
        .as_u64()
        .expect("loop_multiples in the sidecar");
    assert!(multiples >= 3, "{multiples}");
}

#[test]
fn the_fitted_method_has_tayfun_skewness_at_any_thread_count_and_every_component_at_q_1() {
    // `spectrum.nonlinear_method = fitted` (what `auto` takes in deep water): every wave
    // within the convergence limit, the fitted kernels by transforms. The same physical
    // checks as the pair sum's, the sidecar records the method, its error estimate and
    // the limit, the bytes do not depend on the number of threads, and without the limit
    // (`inf`) every wave of the grid is paired.
    const SKEW_BAND: (f64, f64) = (0.45, 1.1);
    const HS_TOL: f64 = 0.02;
    // The estimate of the fitted kernels' rms error on this sea (measured 0.043).
    const ESTIMATE_MAX: f64 = 0.1;
    let mut sets = BASE.to_vec();
    sets.extend(["nonlinear=second-order", "spectrum.nonlinear_method=fitted"]);
    let so = params(&sets);
    let lin = params(&BASE);
    let (mut skew, mut tayfun, mut p3_lin, mut p3_so) = (0.0, 0.0, 0.0, 0.0);
    let seeds = [21u64, 22];
    for &seed in &seeds {
        let gl = synthesize(&Params {
            seed,
            ..lin.clone()
        })
        .unwrap()
        .grid;
        let syn = synthesize(&Params { seed, ..so.clone() }).unwrap();
        let info = syn.info.second_order.clone().unwrap();
        assert_eq!(info.method.as_deref(), Some("fitted"));
        let e = info.estimated_rel_rms_error.unwrap();
        assert!(e > 0.0 && e < ESTIMATE_MAX, "estimate {e}");
        // Every wave within the convergence limit (the fitted method's default q = 1).
        assert_eq!(info.components, info.components_available);
        assert_eq!(info.variance_fraction_kept, 1.0);
        assert!(info.cutoff_rad_s.is_some_and(|w| w > 0.0 && w.is_finite()));
        let (sl, _, sigma) = moments(&gl.data);
        let (ss, _, sigma2) = moments(&syn.grid.data);
        let a = analyze(&gl, None);
        let w = wave_statistics(&gl, &a, &SeaContext::default());
        let km = (2.0 * std::f64::consts::PI / w.crests.mean_period_tm01_s.unwrap()).powi(2) / G;
        let a2 = analyze(&syn.grid, None);
        let w2 = wave_statistics(&syn.grid, &a2, &SeaContext::default());
        assert!(
            (sigma2 / sigma - 1.0).abs() < HS_TOL,
            "Hs {sigma} → {sigma2}"
        );
        skew += ss - sl;
        tayfun += 3.0 * km * sigma;
        p3_lin += w.exceed_3sigma;
        p3_so += w2.exceed_3sigma;
    }
    eprintln!("fitted: skewness added {skew:.4} vs Tayfun {tayfun:.4} (sums of two seeds)");
    assert!(
        skew > SKEW_BAND.0 * tayfun && skew < SKEW_BAND.1 * tayfun,
        "skewness added {skew} vs Tayfun {tayfun}"
    );
    assert!(p3_so > p3_lin, "P(η > 3σ) {p3_so} vs linear {p3_lin}");

    let args = [
        "generate",
        "--method",
        "fft",
        "--spectrum",
        "jonswap",
        "--depth",
        "15",
        "--size",
        "48x40",
        "--extent",
        "480x400",
        "--nonlinear",
        "second-order",
        "--set",
        "spectrum.nonlinear_method=fitted",
        "--time",
        "2.5",
        "-o",
        "f.tif",
    ];
    let dirs = [tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap()];
    for (dir, threads) in dirs.iter().zip(["1", "2"]) {
        let mut a = args.to_vec();
        a.extend(["--threads", threads]);
        common::run_ok(dir.path(), &a);
    }
    for name in ["f.tif", "f.json"] {
        assert_eq!(
            common::read(&dirs[0].path().join(name)),
            common::read(&dirs[1].path().join(name)),
            "{name} at 1 and 2 threads"
        );
    }
    let side = common::json_file(&dirs[0].path().join("f.json"));
    assert_eq!(side["synthesis"]["second_order"]["method"], "fitted");
    let within = side["synthesis"]["second_order"]["components_available"]
        .as_u64()
        .unwrap();
    assert!(side["synthesis"]["second_order"]["cutoff_rad_s"].is_f64());
    // No convergence limit: every wave of the grid (on this small grid the limit lies
    // beyond its Nyquist wavenumber, so no more than within it).
    let mut a: Vec<&str> = args
        .iter()
        .map(|x| if *x == "f.tif" { "all.tif" } else { x })
        .collect();
    a.extend(["--set", "spectrum.nonlinear_cutoff=inf"]);
    common::run_ok(dirs[0].path(), &a);
    let side = common::json_file(&dirs[0].path().join("all.json"));
    let so = &side["synthesis"]["second_order"];
    assert_eq!(so["components"], so["components_available"]);
    assert!(so["components_available"].as_u64().unwrap() >= within);
    assert!(so.get("cutoff_rad_s").is_none());
}

/// `bench --second-order` times the linear sea, the pair sum and the fitted method at each
/// size and states the two ratios to the linear field: both are numbers, and a second-order
/// sea, which computes the linear one and its bound waves, is not faster than it; a
/// looping 48-frame sequence of each, with its ratio; and the fitted method where the
/// paired waves fill the grid (4 m cells), deep and at 19 m, with their ratios.
#[test]
fn bench_second_order_times_the_pair_sum_and_the_fitted_method_against_the_linear_sea() {
    let dir = tempfile::tempdir().unwrap();
    let out = common::run_ok(
        dir.path(),
        &[
            "bench",
            "--sizes",
            "64",
            "--repeats",
            "1",
            "--second-order",
            "--dir",
            "bench",
        ],
    );
    for row in [
        "linear sea (PM 15 m/s, 2048 m)",
        "second order, pair sum (0.99 in limit)",
        "second order, fitted (all in limit)",
        "48 frames, linear",
        "48 frames, second order (auto)",
        "48 frames, linear, loop 20 s",
        "48 frames, pair sum, loop 20 s",
        "linear sea, 4 m cells",
        "second order, fitted, 4 m cells",
        "second order, fitted, 19 m, 4 m cells",
    ] {
        assert!(out.contains(row), "no row {row:?}:\n{out}");
    }
    let numbers = |line: &str| -> Vec<f64> {
        line.split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .filter_map(|s| s.parse().ok())
            .collect()
    };
    let line = out
        .lines()
        .find(|l| l.contains("second order ÷ linear field"))
        .unwrap_or_else(|| panic!("no ratio line:\n{out}"));
    let ratios = numbers(line);
    assert_eq!(ratios.len(), 2, "{line}");
    for r in ratios {
        assert!(r.is_finite() && r >= 1.0, "{line}");
    }
    // The sequences' ratios (numbers: at 64² they take a few milliseconds, so their size
    // is noise here).
    let line = out
        .lines()
        .find(|l| l.contains("48-frame sequence, second order ÷ linear"))
        .unwrap_or_else(|| panic!("no sequence ratio line:\n{out}"));
    let (_, after) = line.split_once(": ").unwrap_or_else(|| panic!("{line}"));
    let ratios = numbers(after);
    assert_eq!(ratios.len(), 2, "{line}");
    for r in ratios {
        assert!(r.is_finite() && r > 0.0, "{line}");
    }
    // Where the paired waves fill the grid (64² over 256 m): two ratios, each at least 1.
    let filling = out
        .lines()
        .find(|l| l.contains("paired waves filling the grid (4 m cells, 256 m)"))
        .unwrap_or_else(|| panic!("no filling ratio line:\n{out}"));
    let (_, after) = filling
        .split_once("linear field: ")
        .unwrap_or_else(|| panic!("{filling}"));
    let ratios = numbers(after);
    assert_eq!(ratios.len(), 3, "deep, 19 and its ratio: {filling}");
    for r in [ratios[0], ratios[2]] {
        assert!(r.is_finite() && r >= 1.0, "{filling}");
    }
    // It names the method `auto` took for the same sea (the pair sum where the fit's
    // estimate is above its bound).
    let sets: Vec<&str> = BASE
        .iter()
        .map(|s| if s.starts_with("size=") { "size=64" } else { s })
        .chain(["nonlinear=second-order"])
        .collect();
    let took = synthesize(&params(&sets))
        .unwrap()
        .info
        .second_order
        .and_then(|s| s.method)
        .expect("a second-order method");
    assert!(
        line.contains(&format!("(auto took {took})")),
        "{took}: {line}"
    );
}

#[test]
fn auto_says_why_it_keeps_the_exact_pairs_and_names_shallow_water_only_at_depth() {
    // Where the fit's estimate exceeds the margin, auto keeps the pairs and says why: at
    // 10 m for shallow water's near-resonant pairs; in deep water (every wave of a 256²
    // grid over 2048 m) without naming shallow water.
    for (extra, shallow) in [("spectrum.nonlinear_cutoff=inf", false), ("depth=10", true)] {
        let sets: Vec<&str> = BASE
            .iter()
            .copied()
            .chain(["nonlinear=second-order", extra])
            .collect();
        let info = synthesize(&params(&sets))
            .unwrap()
            .info
            .second_order
            .unwrap();
        assert_eq!(info.method.as_deref(), Some("pairs"), "{extra}");
        let why = info.method_reason.expect("auto gives its reason");
        assert!(why.contains("exceeds"), "{extra}: {why}");
        assert_eq!(why.contains("shallow water"), shallow, "{extra}: {why}");
    }
}
