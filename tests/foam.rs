//! Foam: `--foam-threshold auto` covers the whitecap fraction of Monahan &
//! O'Muircheartaigh (1980), the choppy storm preset has foam, and the foam that persists
//! over an animation's frames is the same whatever the jobs, a resume or the start frame.

mod common;

use std::path::Path;

use common::{analyze_json, json_file, num, read, run_ok, run_rejected};
use seasynth::export::{png16, tiff32};

/// Monahan & O'Muircheartaigh (1980): W = 3.84·10⁻⁶·U10^3.41.
fn monahan(u10: f64) -> f64 {
    3.84e-6 * u10.powf(3.41)
}

/// The fraction of a foam map's samples with any foam.
fn foam_fraction(path: &Path) -> f64 {
    let (_, _, v) = png16::read(path).unwrap();
    v.iter().filter(|&&v| v > 0).count() as f64 / v.len() as f64
}

#[test]
fn auto_foam_covers_monahans_whitecap_fraction_at_8_15_and_25_mps() {
    const N: usize = 256;
    // The threshold is a quantile of J: the fraction below it is round(W·n)/n, exact but
    // for the rounding to a sample and ties (none in a continuous field).
    let quantile_tol = 1.0 / (N * N) as f64;
    // Samples just below T whose coverage rounds to 0 of 65535.
    const ROUNDED_TO_ZERO: f64 = 2e-3;
    let dir = tempfile::tempdir().unwrap();
    for (u, extent) in [(8.0, 512), (15.0, 1024), (25.0, 4096)] {
        let name = format!("w{u}");
        run_ok(
            dir.path(),
            &[
                "generate",
                "--method",
                "fft",
                "--spectrum",
                "pierson-moskowitz",
                "--wind-speed",
                &u.to_string(),
                "--choppiness",
                "1",
                "--size",
                &N.to_string(),
                "--extent",
                &extent.to_string(),
                "-o",
                &format!("{name}.tif"),
                "-o",
                &format!("{name}.jacobian.tif"),
                "-o",
                &format!("{name}.foam.png"),
                "-q",
            ],
        );
        let w = monahan(u);
        let doc = analyze_json(dir.path(), &format!("{name}.tif"));
        let j = &doc["jacobian"];
        let fraction = num(j, "/fraction_below");
        assert!(
            (fraction - w).abs() <= quantile_tol,
            "{u} m/s: J below T on {fraction} of the sea, W = {w}"
        );
        assert!((num(j, "/whitecap_coverage") - w).abs() < 1e-12, "{j}");
        // The sidecar records the threshold the map used, and it is the analyzed one.
        let side = json_file(&dir.path().join(format!("{name}.json")));
        let t = num(&side, "/foam/threshold_resolved");
        assert_eq!(t, num(j, "/threshold"));
        assert!((num(&side, "/foam/whitecap_coverage") - w).abs() < 1e-12);
        assert_eq!(side["params"]["motion"]["foam_threshold"], "auto");
        // The foam map covers that part of the sea, and only it.
        let (_, _, jv) = tiff32::read(&dir.path().join(format!("{name}.jacobian.tif"))).unwrap();
        let (_, _, fv) = png16::read(&dir.path().join(format!("{name}.foam.png"))).unwrap();
        for (&jv, &fv) in jv.iter().zip(&fv) {
            assert!(fv == 0 || (jv as f64) < t, "foam at J {jv} ≥ T {t}");
        }
        let covered = foam_fraction(&dir.path().join(format!("{name}.foam.png")));
        assert!(
            covered <= fraction && covered >= fraction - ROUNDED_TO_ZERO,
            "{u} m/s: foam on {covered}, J below T on {fraction}"
        );
    }
}

#[test]
fn a_number_keeps_its_meaning_and_a_bad_threshold_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let sea = [
        "generate",
        "--method",
        "fft",
        "--spectrum",
        "pierson-moskowitz",
        "--wind-speed",
        "15",
        "--choppiness",
        "1",
        "--size",
        "64",
        "--extent",
        "256",
    ];
    let mut a = sea.to_vec();
    a.extend([
        "--foam-threshold",
        "0.9",
        "-o",
        "n.tif",
        "-o",
        "n.jacobian.tif",
        "-q",
    ]);
    run_ok(dir.path(), &a);
    let (_, _, j) = tiff32::read(&dir.path().join("n.jacobian.tif")).unwrap();
    let below = j.iter().filter(|&&v| (v as f64) < 0.9).count() as f64 / j.len() as f64;
    let doc = analyze_json(dir.path(), "n.tif");
    assert_eq!(num(&doc, "/jacobian/threshold"), 0.9);
    assert_eq!(num(&doc, "/jacobian/fraction_below"), below);
    assert!(doc["jacobian"].get("whitecap_coverage").is_none());
    let side = json_file(&dir.path().join("n.json"));
    assert_eq!(num(&side, "/foam/threshold_resolved"), 0.9);
    let mut a = sea.to_vec();
    a.extend(["--foam-threshold", "often", "-o", "x.tif"]);
    run_rejected(dir.path(), &a, &["--foam-threshold often", "auto"]);
    let mut a = sea.to_vec();
    a.extend(["--foam-fade", "-1", "-o", "x.tif"]);
    run_rejected(dir.path(), &a, &["--foam-fade", "-1"]);
    assert!(!dir.path().join("x.tif").exists());
}

#[test]
fn the_choppy_storm_loop_has_foam_on_its_whitecap_fraction() {
    let dir = tempfile::tempdir().unwrap();
    let storm = |fade: &str, out: &str| {
        run_ok(
            dir.path(),
            &[
                "animate",
                "--preset",
                "storm-loop",
                "--size",
                "128",
                "--frames",
                "2",
                "--foam-fade",
                fade,
                "--format",
                "foam,jacobian",
                "-o",
                out,
                "-q",
            ],
        )
    };
    storm("0", "fresh");
    let w = monahan(20.0);
    let n = 128.0 * 128.0;
    // Frame 0, at the sequence's time origin, resolves the threshold: J below it on W of
    // the sea exactly (to a sample), foam on all of that but samples rounded to 0.
    let seq = json_file(&dir.path().join("fresh/sequence.json"));
    let t = num(&seq, "/foam/threshold_resolved");
    assert!(
        (num(&seq, "/foam/whitecap_coverage") - w).abs() < 1e-12,
        "{seq}"
    );
    let (_, _, j0) = tiff32::read(&dir.path().join("fresh/frame_00000.jacobian.tif")).unwrap();
    let below = j0.iter().filter(|&&v| (v as f64) < t).count() as f64 / n;
    assert!((below - w).abs() <= 1.0 / n, "J < T on {below}, W = {w}");
    let covered = foam_fraction(&dir.path().join("fresh/frame_00000.foam.png"));
    assert!(
        covered > 0.0 && (covered - w).abs() < 2e-3,
        "foam on {covered}, W = {w}"
    );
    // Frame 1 keeps the threshold; its foam moves with the sea.
    let covered1 = foam_fraction(&dir.path().join("fresh/frame_00001.foam.png"));
    assert!(
        (covered1 - w).abs() < 0.5 * w,
        "frame 1: foam on {covered1}"
    );
    // Foam that persists (3 s: at 8 m samples the 2 s default rarely outlasts a crest
    // from one frame to the next) covers the fresh foam and more.
    storm("3", "faded");
    for k in 0..2 {
        let name = format!("frame_{k:05}.foam.png");
        let (_, _, fresh) = png16::read(&dir.path().join("fresh").join(&name)).unwrap();
        let (_, _, faded) = png16::read(&dir.path().join("faded").join(&name)).unwrap();
        assert!(fresh.iter().zip(&faded).all(|(a, b)| b >= a), "frame {k}");
        assert!(fresh.iter().zip(&faded).any(|(a, b)| b > a), "frame {k}");
    }
}

#[test]
fn persistent_foam_is_the_same_for_any_jobs_resume_or_start_frame() {
    let dir = tempfile::tempdir().unwrap();
    // 0.5 s at 10 fps: full foam lasts 5 frames.
    let anim = |out: &str, extra: &[&str]| {
        let mut a = vec![
            "animate",
            "--method",
            "fft",
            "--spectrum",
            "pierson-moskowitz",
            "--wind-speed",
            "20",
            "--choppiness",
            "1",
            "--size",
            "64",
            "--extent",
            "256",
            "--fps",
            "10",
            "--foam-fade",
            "0.5",
            "--frames",
            "8",
            "--format",
            "foam,disp.exr",
            "-o",
            out,
            "-q",
        ];
        a.extend_from_slice(extra);
        run_ok(dir.path(), &a);
    };
    let foam = |out: &str, number: usize| {
        read(&dir.path().join(format!("{out}/frame_{number:05}.foam.png")))
    };
    anim("one", &["--jobs", "1", "--start-frame", "0"]);
    anim("three", &["--jobs", "3", "--start-frame", "0"]);
    anim("later", &["--jobs", "2", "--start-frame", "100"]);
    // A resumed run that lost frames 0, 3 and 4.
    anim("resumed", &["--jobs", "2", "--start-frame", "0"]);
    for k in [0, 3, 4] {
        for s in ["foam.png", "disp.exr"] {
            std::fs::remove_file(dir.path().join(format!("resumed/frame_{k:05}.{s}"))).unwrap();
        }
    }
    anim(
        "resumed",
        &["--jobs", "2", "--start-frame", "0", "--resume"],
    );
    let seq = json_file(&dir.path().join("one/sequence.json"));
    assert_eq!(num(&seq, "/foam/fade_frames"), 5.0, "{seq}");
    for k in 0..8 {
        let want = foam("one", k);
        assert_eq!(foam("three", k), want, "frame {k}, 3 jobs");
        assert_eq!(foam("later", 100 + k), want, "frame {k}, numbered from 100");
        assert_eq!(foam("resumed", k), want, "frame {k}, resumed");
    }
    // The displacement EXR's foam is the persistent foam too.
    let (_, _, ch) =
        seasynth::export::exr::read_channels(&dir.path().join("one/frame_00003.disp.exr")).unwrap();
    let a = &ch.iter().find(|(n, _)| n == "A").expect("an A channel").1;
    let (_, _, f) = png16::read(&dir.path().join("one/frame_00003.foam.png")).unwrap();
    for (&a, &f) in a.iter().zip(&f) {
        assert_eq!(a, f as f32 / 65535.0);
    }
}
