//! `seasynth spectrum`, run as a program: F(f) as JSON and CSV against the closed forms,
//! JONSWAP from Hs/Tp, TMA's depth, the plots, and bad input (exit code 2, one line, no
//! file left behind).

mod common;

use common::{names_in, num, run_exit2, run_ok};
use std::path::Path;

use serde_json::Value;

const G: f64 = 9.81;
const TAU: f64 = std::f64::consts::TAU;
/// Phillips' constant of the Pierson–Moskowitz spectrum (Mastin eq. 1).
const PM_ALPHA: f64 = 0.0081;

/// Runs `seasynth spectrum ARGS`, panics with its stderr unless it succeeds, returns stdout.
fn spectrum_ok(args: &[&str]) -> String {
    let mut all = vec!["spectrum"];
    all.extend_from_slice(args);
    run_ok(Path::new("."), &all)
}

/// Runs `seasynth spectrum ARGS`, expects exit code 2 and nothing on stdout, returns stderr.
fn spectrum_usage_error(args: &[&str]) -> String {
    let mut all = vec!["spectrum"];
    all.extend_from_slice(args);
    run_exit2(Path::new("."), &all)
}

fn json(args: &[&str]) -> Value {
    let text = spectrum_ok(args);
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("not one JSON object ({e}):\n{text}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// (f_hz, s_m2_per_hz) of the `points` array.
fn points(doc: &Value) -> Vec<(f64, f64)> {
    doc["points"]
        .as_array()
        .expect("points is an array")
        .iter()
        .map(|p| {
            let keys: Vec<&str> = p.as_object().unwrap().keys().map(String::as_str).collect();
            assert_eq!(keys, ["f_hz", "s_m2_per_hz"], "keys of a point");
            (num(p, "/f_hz"), num(p, "/s_m2_per_hz"))
        })
        .collect()
}

const PM15: &[&str] = &[
    "--spectrum",
    "pierson-moskowitz",
    "--wind-speed",
    "15",
    "--freq",
    "0.05,0.085,0.2",
];

fn with(base: &[&'static str], more: &[&'static str]) -> Vec<&'static str> {
    base.iter().chain(more).copied().collect()
}

#[test]
fn pierson_moskowitz_json_matches_the_closed_form() {
    let doc = json(&with(PM15, &["--json"]));
    for key in [
        "spectrum", "points", "hs_m", "fp_hz", "tp_s", "m0_m2", "params",
    ] {
        assert!(doc.get(key).is_some(), "key {key} missing from {doc}");
    }
    assert_eq!(doc["spectrum"], "pierson-moskowitz");
    assert_eq!(doc["params"]["spectrum"]["model"], "pierson-moskowitz");
    assert_eq!(num(&doc, "/params/wind/speed_mps"), 15.0);

    let u = 15.0;
    let fm = 0.13 * G / u;
    let fp = num(&doc, "/fp_hz");
    assert!(rel(fp, fm) < 1e-9, "fp {fp} vs 0.13 g/U = {fm}");
    assert!(rel(num(&doc, "/tp_s"), 1.0 / fp) < 1e-12);

    // F(f) = α g² (2π)⁻⁴ f⁻⁵ exp(−5/4 (fm/f)⁴) (Mastin eq. 1), in the order given.
    let pts = points(&doc);
    assert_eq!(
        pts.iter().map(|p| p.0).collect::<Vec<_>>(),
        [0.05, 0.085, 0.2]
    );
    for (f, s) in pts {
        let want = PM_ALPHA * G * G / TAU.powi(4) / f.powi(5) * (-1.25 * (fm / f).powi(4)).exp();
        assert!(rel(s, want) < 1e-12, "F({f}) = {s}, closed form {want}");
    }

    // m0 = α g² / (5 (2π)⁴ fm⁴) and Hs = 4√m0.
    let m0 = num(&doc, "/m0_m2");
    let hs = num(&doc, "/hs_m");
    let m0_want = PM_ALPHA * G * G / (5.0 * TAU.powi(4) * fm.powi(4));
    assert!(rel(m0, m0_want) < 1e-12, "m0 {m0} vs {m0_want}");
    assert!(rel(hs, 4.0 * m0.sqrt()) < 1e-12, "Hs {hs} vs 4√m0");
    // With fm = 0.13 g/U10 and α = 0.0081, Hs = 4√(α/(5(2π)⁴))/0.13² · U²/g = 0.2413 U²/g.
    // The often-quoted Hs = 0.21 U²/g is for the wind at 19.5 m (U19.5 ≈ 1.07 U10, and
    // 0.21·1.07² = 0.240): within 1 % of that.
    let ratio = hs / (u * u / G);
    assert!(
        (ratio - 0.21 * 1.07f64.powi(2)).abs() < 0.01 * 0.2404,
        "Hs = {ratio} U²/g"
    );
    assert!(rel(ratio, 0.2413) < 1e-3, "Hs = {ratio} U²/g");
}

#[test]
fn csv_has_the_header_and_the_json_values() {
    let doc = json(&with(PM15, &["--json"]));
    let text = spectrum_ok(&with(PM15, &["--csv"]));
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("f_hz,s_m2_per_hz"));
    let rows: Vec<(f64, f64)> = lines
        .map(|l| {
            let (f, s) = l.split_once(',').unwrap_or_else(|| panic!("row {l:?}"));
            (f.parse().unwrap(), s.parse().unwrap())
        })
        .collect();
    assert_eq!(rows, points(&doc), "CSV rows equal the JSON points exactly");
    assert!(
        text.ends_with('\n') && !text.contains("\n\n"),
        "nothing else:\n{text}"
    );
}

#[test]
fn jonswap_from_hs_and_tp() {
    let doc = json(&[
        "--spectrum",
        "jonswap",
        "--hs",
        "3",
        "--tp",
        "10",
        "--gamma",
        "3.3",
        "--freq",
        "0.1",
        "--json",
    ]);
    assert_eq!(doc["spectrum"], "jonswap");
    assert!(rel(num(&doc, "/fp_hz"), 0.1) < 1e-12);
    assert!(rel(num(&doc, "/tp_s"), 10.0) < 1e-12);
    // DNV's normalization A_γ = 1 − 0.287 ln γ makes 4√m0 only approximately Hs: within
    // 0.15 % for γ ≤ 5 (3.0036 m here); 0.5 % is allowed.
    let hs = num(&doc, "/hs_m");
    assert!(rel(hs, 3.0) < 5e-3, "Hs {hs}");
    assert!(rel(hs, 4.0 * num(&doc, "/m0_m2").sqrt()) < 1e-12);
    // The peak is the largest value: above the PM spectrum of the same Hs and Tp.
    let pm = json(&[
        "--spectrum",
        "pierson-moskowitz",
        "--hs",
        "3",
        "--tp",
        "10",
        "--freq",
        "0.1",
        "--json",
    ]);
    assert!(num(&doc, "/points/0/s_m2_per_hz") > 1.5 * num(&pm, "/points/0/s_m2_per_hz"));
}

#[test]
fn tma_needs_a_depth_and_damps_low_frequencies() {
    let err = spectrum_usage_error(&["--spectrum", "tma", "--freq", "0.1", "--json"]);
    assert!(err.contains("--depth"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");

    let sea = [
        "--wind-speed",
        "12",
        "--fetch-km",
        "50",
        "--freq",
        "0.12,0.2,0.5,1",
        "--json",
    ];
    let deep = json(&[&["--spectrum", "jonswap"][..], &sea].concat());
    let shallow = json(&[&["--spectrum", "tma", "--depth", "5"][..], &sea].concat());
    let (d, s) = (points(&deep), points(&shallow));
    for ((f, fd), (_, fs)) in d.iter().zip(&s) {
        assert!(fs <= fd, "TMA above JONSWAP at {f} Hz");
    }
    assert!(
        s[0].1 < 0.5 * d[0].1,
        "Kitaigorodskii's factor at 0.12 Hz, 5 m"
    );
    assert!(rel(s[3].1, d[3].1) < 1e-12, "no depth effect at 1 Hz");
    assert!(num(&shallow, "/hs_m") < num(&deep, "/hs_m"));
}

/// (width, height, distinct colors) of an 8-bit RGB PNG, after checking its signature.
fn png_info(path: &Path) -> (u32, u32, usize) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).expect("one frame");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let mut colors: Vec<&[u8]> = buf[..info.buffer_size()].chunks_exact(3).collect();
    colors.sort_unstable();
    colors.dedup();
    (info.width, info.height, colors.len())
}

#[test]
fn plots_are_png_images_of_the_documented_sizes() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("f.png");
    let plot2d = dir.path().join("psi.png");
    let (p1, p2) = (plot.to_str().unwrap(), plot2d.to_str().unwrap());
    // With --freq and --json at once: stdout is still one JSON object.
    let text = spectrum_ok(&[
        "--spectrum",
        "jonswap",
        "--wind-speed",
        "15",
        "--wind-dir",
        "45",
        "--freq",
        "0.05,0.1",
        "--json",
        "--plot",
        p1,
        "--plot2d",
        p2,
    ]);
    let doc: Value = serde_json::from_str(&text).expect("JSON");
    assert_eq!(points(&doc).len(), 2);
    let (w, h, colors) = png_info(&plot);
    assert_eq!((w, h), (800, 500));
    assert!(colors > 20, "{colors} colors: not a blank image");
    let (w, h, colors) = png_info(&plot2d);
    assert_eq!((w, h), (600, 600));
    assert!(colors > 100, "{colors} colors: a color map");
    assert_eq!(
        names_in(dir.path()),
        ["f.png", "psi.png"],
        "no temporary file left"
    );

    // Without --freq, and for the models without a frequency spectrum (--plot2d only).
    let only = dir.path().join("pm.png");
    assert!(
        spectrum_ok(&[
            "--spectrum",
            "pierson-moskowitz",
            "--plot",
            only.to_str().unwrap()
        ])
        .is_empty()
    );
    assert_eq!(png_info(&only).0, 800);
    for model in ["phillips", "fractal"] {
        let p = dir.path().join(format!("{model}.png"));
        spectrum_ok(&["--spectrum", model, "--plot2d", p.to_str().unwrap()]);
        let (w, h, colors) = png_info(&p);
        assert_eq!((w, h), (600, 600), "{model}");
        assert!(colors > 100, "{model}: {colors} colors");
    }
}

#[test]
fn an_unwritable_plot_fails_before_any_work_and_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("psi.png");
    let err = spectrum_usage_error(&[
        "--spectrum",
        "pierson-moskowitz",
        "--plot2d",
        good.to_str().unwrap(),
        "--plot",
        "/dev/null/sub/x.png",
    ]);
    assert!(err.contains("/dev/null/sub"), "{err}");
    assert!(!Path::new("/dev/null/sub/x.png").exists());
    assert!(
        names_in(dir.path()).is_empty(),
        "nothing written: {:?}",
        names_in(dir.path())
    );

    let err = spectrum_usage_error(&["--spectrum", "jonswap", "--plot", "/dev/null/sub/x.png"]);
    assert!(
        err.starts_with("Error: output /dev/null/sub/x.png"),
        "{err}"
    );
    let jpg = dir.path().join("x.jpg");
    let err = spectrum_usage_error(&["--spectrum", "jonswap", "--plot", jpg.to_str().unwrap()]);
    assert!(err.contains(".png"), "{err}");
    assert!(names_in(dir.path()).is_empty());
}

#[test]
fn bad_frequencies_are_named() {
    let err = spectrum_usage_error(&["--spectrum", "jonswap", "--freq", "0,-1", "--json"]);
    assert!(
        err.contains("--freq") && err.contains("(got 0, -1)"),
        "{err}"
    );
    assert!(err.contains("> 0"), "says what is allowed: {err}");
    let err = spectrum_usage_error(&["--spectrum", "jonswap", "--freq", "abc", "--csv"]);
    assert!(err.contains("--freq") && err.contains("abc"), "{err}");
    let err = spectrum_usage_error(&["--spectrum", "jonswap", "--freq", "0.1,inf", "--csv"]);
    assert!(err.contains("inf"), "{err}");
    let err = spectrum_usage_error(&["--spectrum", "jonswap", "--freq", "-0.1", "--csv"]);
    assert!(err.contains("-0.1"), "{err}");
}

#[test]
fn phillips_and_fractal_have_no_frequency_spectrum() {
    let err = spectrum_usage_error(&["--spectrum", "phillips", "--freq", "0.1", "--json"]);
    assert!(
        err.contains("phillips is a discrete wavenumber spectrum (Tessendorf's convention"),
        "{err}"
    );
    assert!(err.contains("use a physical model"), "{err}");
    let err = spectrum_usage_error(&["--spectrum", "fractal", "--freq", "0.1", "--csv"]);
    assert!(
        err.contains("fractal") && err.contains("no frequency spectrum"),
        "{err}"
    );
    // The default preset (li-tian) uses phillips.
    let err = spectrum_usage_error(&["--freq", "0.1", "--json"]);
    assert!(err.contains("phillips"), "{err}");
}

#[test]
fn the_output_options_are_checked() {
    // --freq needs exactly one of --json and --csv, and they need --freq.
    spectrum_usage_error(&["--spectrum", "jonswap", "--freq", "0.1"]);
    spectrum_usage_error(&["--spectrum", "jonswap", "--freq", "0.1", "--json", "--csv"]);
    spectrum_usage_error(&["--spectrum", "jonswap", "--json"]);
    let err = spectrum_usage_error(&["--spectrum", "jonswap"]);
    assert!(err.contains("--freq") && err.contains("--plot"), "{err}");
    // Field parameters are validated as for generate.
    let err = spectrum_usage_error(&[
        "--spectrum",
        "jonswap",
        "--wind-speed",
        "-3",
        "--freq",
        "0.1",
        "--json",
    ]);
    assert!(err.contains("--wind-speed"), "{err}");
}
