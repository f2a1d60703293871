//! `seasynth analyze`, run as a program: the JSON report and its keys, statistics equal to
//! the generator's sidecar, PNG against TIFF, a known cosine's wavelength and direction,
//! Parseval, the FFT method against its target spectrum, the foam fraction of a choppy
//! field (from its Jacobian map or regenerated), and bad input (exit code 2, one
//! line naming the file).

mod common;

use common::{analyze_json, json_file, names_in, num, run_ok, run_rejected};
use std::path::Path;

use seasynth::export::tiff32;
use seasynth::grid::{Grid, GridSpec};
use serde_json::Value;

/// Statistics read back through the same f32 samples agree to rounding.
const STATS_TOL: f64 = 1e-6;
/// Σ of the radial powers against the variance (Parseval), relative.
const PARSEVAL_REL_TOL: f64 = 1e-6;
/// The peak's parabolic refinement moves a little with 16-bit quantization, relative.
const PEAK_QUANTIZATION_REL_TOL: f64 = 1e-3;
/// How far the measured direction of a cosine may be from its true axis, degrees.
const DIRECTION_TOL_DEG: f64 = 5.0;
/// Measured/target variance of one FFT field (one seed), and of the mean of three.
const ONE_SEED_RATIO_TOL: f64 = 0.2;
const MEAN_RATIO_TOL: f64 = 0.1;

/// Keys every `analyze --json` report holds at the top level.
const TOP_KEYS: &[&str] = &[
    "file",
    "format",
    "spacing_source",
    "nx",
    "ny",
    "dx_m",
    "dy_m",
    "extent_m",
    "min_m",
    "max_m",
    "mean_m",
    "std_m",
    "hs_m",
    "peak_k_rad_per_m",
    "peak_wavelength_m",
    "peak_direction_deg",
    "direction_modulo_deg",
    "peak_direction_concentration",
    "dk_rad_per_m",
    "spectrum_normalization",
    "target",
    "radial_spectrum",
];

/// Keys of every radial bin.
const BIN_KEYS: &[&str] = &[
    "k_rad_per_m",
    "wavelength_m",
    "cells",
    "complete",
    "power_m2",
    "s_m2_per_rad_per_m",
];

/// Keys of the target summary, and those a bin gains when there is a target.
const TARGET_KEYS: &[&str] = &[
    "method",
    "spectrum",
    "target_std_m",
    "target_hs_m",
    "target_peak_wavelength_m",
    "variance_ratio",
    "log10_rms_difference",
    "bins_compared",
];
const TARGET_BIN_KEYS: &[&str] = &["target_power_m2", "target_s_m2_per_rad_per_m"];

/// `generate --quiet ARGS` in `dir`.
fn generate(dir: &Path, args: &[&str]) {
    let mut all = vec!["generate", "--quiet"];
    all.extend_from_slice(args);
    run_ok(dir, &all);
}

fn bins(doc: &Value) -> &Vec<Value> {
    doc["radial_spectrum"]
        .as_array()
        .expect("radial_spectrum is an array")
}

/// Writes a `n`×`n` float TIFF of amp·cos(k·x) with 1 m samples, k of `wavelength_m`
/// toward `dir_deg`.
fn write_cosine_tiff(path: &Path, n: usize, wavelength_m: f64, dir_deg: f64, amp: f64) {
    let spec = GridSpec::new(n, n, n as f64, n as f64);
    let k = 2.0 * std::f64::consts::PI / wavelength_m;
    let (kx, ky) = (
        k * dir_deg.to_radians().cos(),
        k * dir_deg.to_radians().sin(),
    );
    let mut data = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            data.push((amp * (kx * spec.x_m(i) + ky * spec.y_m(j)).cos()) as f32);
        }
    }
    let file = std::fs::File::create(path).expect("writable temporary folder");
    tiff32::write(file, &Grid::new(spec, data)).expect("TIFF written");
}

/// Distance between two axial directions (modulo 180°), degrees.
fn axial_distance_deg(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(180.0);
    d.min(180.0 - d)
}

/// Runs `analyze ARGS` in `dir` and checks the rejection: exit code 2, nothing on stdout,
/// exactly one line on stderr containing every fragment.
fn assert_rejected(dir: &Path, args: &[&str], fragments: &[&str]) {
    let mut all = vec!["analyze"];
    all.extend_from_slice(args);
    run_rejected(dir, &all, fragments);
}

#[test]
fn json_report_of_an_fft_tiff_holds_every_documented_key_and_the_sidecar_stats() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method", "fft", "--size", "64", "--extent", "128", "-o", "sea.tif",
        ],
    );
    let doc = analyze_json(dir.path(), "sea.tif");
    for k in TOP_KEYS {
        assert!(doc.get(k).is_some(), "missing key `{k}` in {doc:#}");
    }
    let target = &doc["target"];
    for k in TARGET_KEYS {
        assert!(
            target.get(k).is_some(),
            "missing target key `{k}` in {target:#}"
        );
    }
    let b = bins(&doc);
    assert!(!b.is_empty());
    for bin in b {
        for k in BIN_KEYS.iter().chain(TARGET_BIN_KEYS) {
            assert!(bin.get(k).is_some(), "missing bin key `{k}` in {bin}");
        }
    }
    assert_eq!(doc["format"], "tiff-f32");
    assert_eq!(doc["spacing_source"], "sidecar");
    assert_eq!(num(&doc, "/direction_modulo_deg"), 180.0);
    assert_eq!((num(&doc, "/nx"), num(&doc, "/ny")), (64.0, 64.0));
    assert_eq!((num(&doc, "/dx_m"), num(&doc, "/dy_m")), (2.0, 2.0));
    let side = json_file(&dir.path().join("sea.json"));
    for key in ["std_m", "hs_m", "min_m", "max_m", "mean_m"] {
        let (got, want) = (
            num(&doc, &format!("/{key}")),
            num(&side, &format!("/stats/{key}")),
        );
        assert!(
            (got - want).abs() <= STATS_TOL,
            "{key}: analyze {got}, sidecar {want}"
        );
    }
    assert!((num(&doc, "/hs_m") - 4.0 * num(&doc, "/std_m")).abs() <= STATS_TOL);
    let dir_deg = num(&doc, "/peak_direction_deg");
    assert!(
        (0.0..180.0).contains(&dir_deg),
        "direction in [0, 180): {dir_deg}"
    );
}

#[test]
fn png_with_its_sidecar_gives_the_tiff_stats_within_one_16_bit_step() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method", "fft", "--size", "64", "-o", "sea.tif", "-o", "sea.png",
        ],
    );
    let tif = analyze_json(dir.path(), "sea.tif");
    let png = analyze_json(dir.path(), "sea.png");
    assert_eq!(png["format"], "png16");
    let step = num(&json_file(&dir.path().join("sea.json")), "/mapping/step_m");
    assert!((num(&png, "/quantization_step_m") - step).abs() <= STATS_TOL * step);
    for key in ["std_m", "min_m", "max_m", "mean_m"] {
        let (p, t) = (num(&png, &format!("/{key}")), num(&tif, &format!("/{key}")));
        assert!(
            (p - t).abs() <= step,
            "{key}: PNG {p}, TIFF {t}, one step {step}"
        );
    }
    assert!((num(&png, "/hs_m") - num(&tif, "/hs_m")).abs() <= 4.0 * step);
    let (pw, tw) = (
        num(&png, "/peak_wavelength_m"),
        num(&tif, "/peak_wavelength_m"),
    );
    assert!(
        (pw - tw).abs() <= PEAK_QUANTIZATION_REL_TOL * tw,
        "peak wavelength: PNG {pw}, TIFF {tw}"
    );
}

#[test]
fn a_cosine_of_32_m_toward_30_degrees_peaks_at_32_m_and_30_degrees_and_keeps_parseval() {
    let dir = tempfile::tempdir().unwrap();
    write_cosine_tiff(&dir.path().join("cos.tif"), 256, 32.0, 30.0, 0.7);
    let doc = analyze_json(dir.path(), "cos.tif");
    assert_eq!(doc["spacing_source"], "assumed 1 m");
    assert_eq!(doc["target"], Value::Null);
    assert!(doc["target_note"].is_string(), "a note says why: {doc}");
    let dk = num(&doc, "/dk_rad_per_m");
    assert!((dk - 2.0 * std::f64::consts::PI / 256.0).abs() < 1e-12);
    let k = num(&doc, "/peak_k_rad_per_m");
    let k_true = 2.0 * std::f64::consts::PI / 32.0;
    assert!(
        (k - k_true).abs() <= dk,
        "peak k {k} vs {k_true} (one bin = {dk})"
    );
    let wl = num(&doc, "/peak_wavelength_m");
    assert!((wl - 2.0 * std::f64::consts::PI / k).abs() < 1e-9);
    let d = num(&doc, "/peak_direction_deg");
    assert!(
        axial_distance_deg(d, 30.0) <= DIRECTION_TOL_DEG,
        "direction {d}, expected 30"
    );
    let var = num(&doc, "/std_m").powi(2);
    let total: f64 = bins(&doc).iter().map(|b| num(b, "/power_m2")).sum();
    assert!(
        (total - var).abs() <= PARSEVAL_REL_TOL * var,
        "Σ radial power {total} vs variance {var}"
    );
    let s_integral: f64 = bins(&doc)
        .iter()
        .map(|b| num(b, "/s_m2_per_rad_per_m") * dk)
        .sum();
    assert!((s_integral - var).abs() <= PARSEVAL_REL_TOL * var);
}

#[test]
fn spacing_from_a_hand_written_sidecar_scales_the_wavelengths() {
    let dir = tempfile::tempdir().unwrap();
    // 16 samples per period at 1 m; with 2 m samples it is 32 m.
    write_cosine_tiff(&dir.path().join("cos.tif"), 128, 16.0, 0.0, 1.0);
    let side = serde_json::json!({ "grid": { "nx": 128, "ny": 128, "dx_m": 2.0, "dy_m": 2.0 } });
    std::fs::write(dir.path().join("cos.json"), side.to_string()).unwrap();
    let doc = analyze_json(dir.path(), "cos.tif");
    assert_eq!(doc["spacing_source"], "sidecar");
    assert_eq!(num(&doc, "/extent_m/0"), 256.0);
    assert!(
        (num(&doc, "/peak_wavelength_m") - 32.0).abs() < 1e-9,
        "{doc}"
    );
    assert!(axial_distance_deg(num(&doc, "/peak_direction_deg"), 0.0) < 1e-6);
}

#[test]
fn fft_method_variance_matches_the_target_within_20_percent_and_on_average_within_10() {
    let dir = tempfile::tempdir().unwrap();
    let mut mean = 0.0;
    const SEEDS: [&str; 3] = ["1", "2", "3"];
    for seed in SEEDS {
        let name = format!("s{seed}.tif");
        generate(
            dir.path(),
            &[
                "--method",
                "fft",
                "--size",
                "128",
                "--extent",
                "128",
                "--wind-speed",
                "3",
                "--seed",
                seed,
                "-o",
                &name,
            ],
        );
        let doc = analyze_json(dir.path(), &name);
        let ratio = num(&doc, "/target/variance_ratio");
        assert!(
            (ratio - 1.0).abs() <= ONE_SEED_RATIO_TOL,
            "seed {seed}: measured/target variance {ratio}"
        );
        let side = json_file(&dir.path().join(format!("s{seed}.json")));
        let expected_std = num(&doc, "/target/target_std_m");
        assert!(
            (num(&side, "/stats/std_m") / expected_std - ratio.sqrt()).abs() < STATS_TOL,
            "the ratio is the sidecar's variance over the target's"
        );
        mean += ratio / SEEDS.len() as f64;
    }
    assert!(
        (mean - 1.0).abs() <= MEAN_RATIO_TOL,
        "mean measured/target variance {mean}"
    );
}

#[test]
fn hybrid_output_has_a_null_target_and_a_note_saying_why() {
    let dir = tempfile::tempdir().unwrap();
    generate(dir.path(), &["--size", "64", "-o", "h.tif"]);
    let doc = analyze_json(dir.path(), "h.tif");
    assert_eq!(doc["target"], Value::Null);
    let note = doc["target_note"].as_str().expect("target_note is text");
    assert!(note.contains("hybrid"), "{note}");
    assert!(bins(&doc)[0].get("target_power_m2").is_none());
}

#[test]
fn the_human_report_names_the_file_the_hs_the_peak_and_the_180_degree_ambiguity() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &["--method", "fft", "--size", "64", "-o", "sea.tif"],
    );
    let out = run_ok(dir.path(), &["analyze", "sea.tif"]);
    for f in [
        "sea.tif",
        "Hs",
        "wavelength",
        "modulo 180",
        "target",
        "skewness",
        "Cox–Munk",
        "H1/3",
        "Forristall",
    ] {
        assert!(out.contains(f), "report should contain `{f}`:\n{out}");
    }
    assert!(out.lines().count() <= 15, "a short report:\n{out}");
}

#[test]
fn a_missing_file_is_rejected_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    assert_rejected(dir.path(), &["nothing-here.tif"], &["nothing-here.tif"]);
}

#[test]
fn a_text_file_named_tif_is_rejected_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("x.tif"), "just some text\n").unwrap();
    assert_rejected(
        dir.path(),
        &["x.tif"],
        &["x.tif", "is not an image of a format read here"],
    );
}

#[test]
fn a_truncated_tiff_is_rejected_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &["--method", "fft", "--size", "64", "-o", "sea.tif"],
    );
    let bytes = std::fs::read(dir.path().join("sea.tif")).unwrap();
    std::fs::write(dir.path().join("cut.tif"), &bytes[..bytes.len() / 2]).unwrap();
    assert_rejected(dir.path(), &["cut.tif"], &["cut.tif"]);
}

#[test]
fn a_16_bit_png_without_sidecar_or_text_chunk_is_rejected_naming_the_height_range() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bare.png");
    let mut enc = png::Encoder::new(std::fs::File::create(&path).unwrap(), 4, 4);
    enc.set_color(png::ColorType::Grayscale);
    enc.set_depth(png::BitDepth::Sixteen);
    let mut w = enc.write_header().unwrap();
    w.write_image_data(&[7u8; 32]).unwrap();
    w.finish().unwrap();
    assert_rejected(
        dir.path(),
        &["bare.png"],
        &[
            "bare.png",
            "16-bit integer samples",
            "--height-range MIN:MAX",
        ],
    );
}

#[test]
fn an_8_bit_png_needs_the_height_range_even_with_a_sidecar() {
    let dir = tempfile::tempdir().unwrap();
    generate(dir.path(), &["--size", "32", "-o", "sea.png"]);
    let path = dir.path().join("gray8.png");
    let mut enc = png::Encoder::new(std::fs::File::create(&path).unwrap(), 4, 4);
    enc.set_color(png::ColorType::Grayscale);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().unwrap();
    w.write_image_data(&[128u8; 16]).unwrap();
    w.finish().unwrap();
    std::fs::copy(dir.path().join("sea.json"), dir.path().join("gray8.json")).unwrap();
    assert_rejected(
        dir.path(),
        &["gray8.png"],
        &["gray8.png", "8-bit integer samples", "--height-range"],
    );
}

#[test]
fn a_sidecar_for_another_grid_size_is_rejected_naming_the_sidecar() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &["--method", "fft", "--size", "64", "-o", "sea.tif"],
    );
    generate(
        dir.path(),
        &["--method", "fft", "--size", "32", "-o", "small.tif"],
    );
    std::fs::copy(dir.path().join("small.json"), dir.path().join("sea.json")).unwrap();
    assert_rejected(dir.path(), &["sea.tif"], &["sea.json", "32×32", "64×64"]);
}

/// Pixels of `rgb` within 40 of `color` in every channel.
fn pixels_near(rgb: &[u8], color: [u8; 3]) -> usize {
    rgb.chunks_exact(3)
        .filter(|p| p.iter().zip(color).all(|(&a, b)| a.abs_diff(b) <= 40))
        .count()
}

#[test]
fn plot_writes_an_800_by_500_rgb_png_with_the_measured_and_target_curves() {
    /// Pixels each curve's color must cover at least (a 2-pixel line across the plot).
    const MIN_CURVE_PIXELS: usize = 300;
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &["--method", "fft", "--size", "64", "-o", "sea.tif"],
    );
    let out = run_ok(
        dir.path(),
        &["analyze", "sea.tif", "--json", "--plot", "spec.png"],
    );
    serde_json::from_str::<Value>(&out).expect("--json still prints the report");
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(dir.path().join("spec.png")).expect("the plot is written"),
    ));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0u8; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (800, 500));
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let rgb = &buf[..info.buffer_size()];
    let (blue, red) = (
        pixels_near(rgb, [30, 90, 200]),
        pixels_near(rgb, [200, 30, 30]),
    );
    assert!(
        blue >= MIN_CURVE_PIXELS,
        "measured curve (blue): {blue} pixels"
    );
    assert!(red >= MIN_CURVE_PIXELS, "target curve (red): {red} pixels");
    assert_eq!(names_in(dir.path()), ["sea.json", "sea.tif", "spec.png"]);
}

#[test]
fn plot_with_a_name_not_ending_in_png_is_rejected_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &["--method", "fft", "--size", "32", "-o", "sea.tif"],
    );
    assert_rejected(
        dir.path(),
        &["sea.tif", "--plot", "spec.jpg"],
        &["spec.jpg", ".png"],
    );
    assert_eq!(names_in(dir.path()), ["sea.json", "sea.tif"]);
}

#[test]
fn plot_over_the_analyzed_png_is_rejected_and_leaves_it_intact() {
    let dir = tempfile::tempdir().unwrap();
    generate(dir.path(), &["--size", "32", "-o", "sea.png"]);
    let before = std::fs::read(dir.path().join("sea.png")).unwrap();
    assert_rejected(
        dir.path(),
        &["sea.png", "--plot", "sea.png"],
        &["sea.png", "is the file being analyzed"],
    );
    assert_eq!(std::fs::read(dir.path().join("sea.png")).unwrap(), before);
}

#[test]
fn a_bad_input_with_plot_leaves_no_plot_file_behind() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("x.tif"), "not an image").unwrap();
    assert_rejected(dir.path(), &["x.tif", "--plot", "spec.png"], &["x.tif"]);
    assert_eq!(
        names_in(dir.path()),
        ["x.tif"],
        "no plot and no hidden .part file"
    );
}

/// The fraction of the samples `j` below `t` and their minimum, computed here.
fn below_and_min(j: &[f32], t: f64) -> (f64, f64) {
    let below = j.iter().filter(|&&v| (v as f64) < t).count();
    let min = j.iter().copied().fold(f32::INFINITY, f32::min);
    (below as f64 / j.len() as f64, min as f64)
}

/// Checks the `jacobian` report of `doc` against the J samples `j`, threshold `t`.
fn assert_jacobian(doc: &Value, j: &[f32], t: f64, source: &str) {
    let (fraction, min) = below_and_min(j, t);
    let r = &doc["jacobian"];
    assert_eq!(r["source"], source, "{r}");
    assert_eq!(num(r, "/threshold"), t, "{r}");
    assert_eq!(num(r, "/fraction_below"), fraction, "{r}");
    assert_eq!(num(r, "/min"), min, "{r}");
}

#[test]
fn a_choppy_field_reports_the_fraction_of_j_below_its_foam_threshold_from_the_map_or_regenerated() {
    const T: f64 = 0.8;
    let dir = tempfile::tempdir().unwrap();
    let field = [
        "--method",
        "fft",
        "--size",
        "64",
        "--choppiness",
        "2",
        "--wind-speed",
        "15",
        "--foam-threshold",
        "0.8",
    ];
    let with = |outs: &[&str]| {
        let mut a = field.to_vec();
        a.extend_from_slice(outs);
        generate(dir.path(), &a);
    };
    with(&["-o", "c.tif", "-o", "c.jacobian.tif"]);
    let (_, _, j) = tiff32::read(&dir.path().join("c.jacobian.tif")).unwrap();
    let (fraction, _) = below_and_min(&j, T);
    assert!(
        fraction > 0.0 && fraction < 1.0,
        "a sea with some foam: {fraction}"
    );
    assert_jacobian(&analyze_json(dir.path(), "c.tif"), &j, T, "map");
    // Without the map, the sidecar's field is synthesized again: the same J.
    std::fs::remove_file(dir.path().join("c.jacobian.tif")).unwrap();
    assert_jacobian(&analyze_json(dir.path(), "c.tif"), &j, T, "regenerated");
    let out = run_ok(dir.path(), &["analyze", "c.tif"]);
    assert!(out.contains("J: fraction below 0.8"), "{out}");
    // The EXR map's Y channel is read too.
    with(&["-o", "e.tif", "-o", "e.jacobian.exr"]);
    let (_, _, ch) =
        seasynth::export::exr::read_channels(&dir.path().join("e.jacobian.exr")).unwrap();
    let y = &ch.iter().find(|(n, _)| n == "Y").expect("a Y channel").1;
    assert_jacobian(&analyze_json(dir.path(), "e.tif"), y, T, "map");
}

#[test]
fn a_field_that_is_not_choppy_and_has_no_jacobian_map_reports_no_jacobian() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &["--method", "fft", "--size", "64", "-o", "still.tif"],
    );
    let doc = analyze_json(dir.path(), "still.tif");
    assert!(doc.get("jacobian").is_none(), "{doc:#}");
    let out = run_ok(dir.path(), &["analyze", "still.tif"]);
    assert!(out.contains("J: not a choppy field"), "{out}");
}

#[test]
fn a_jacobian_map_of_another_size_is_rejected_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &["--method", "fft", "--size", "64", "-o", "s.tif"],
    );
    write_cosine_tiff(&dir.path().join("s.jacobian.tif"), 32, 8.0, 0.0, 1.0);
    assert_rejected(
        dir.path(),
        &["s.tif"],
        &["s.jacobian.tif", "32×32", "64×64"],
    );
}
