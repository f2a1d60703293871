//! `seasynth animate`: frames equal `generate --time`, loops repeat exactly, one mapping
//! for the sequence, resume, and bad arguments.

mod common;

use common::{json_file, num, read, run_ok, run_rejected};
use seasynth::export::{HeightMapping, png16, tiff32};

const SEA: &[&str] = &[
    "--method",
    "fft",
    "--spectrum",
    "jonswap",
    "--wind-speed",
    "12",
    "--fetch-km",
    "40",
    "--size",
    "64",
    "--extent",
    "200",
    "--fps",
    "10",
];

fn args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut v: Vec<&str> = vec!["animate"];
    v.extend(SEA);
    v.extend(extra);
    v
}

#[test]
fn frame_k_equals_generate_at_k_over_fps_bit_for_bit_and_choppy_maps_are_written() {
    let dir = tempfile::tempdir().unwrap();
    run_ok(
        dir.path(),
        &args(&[
            "--frames",
            "4",
            "--choppiness",
            "0.7",
            "--format",
            "tif,png,normal,foam,jacobian,disp",
            "-o",
            "seq",
            "-q",
        ]),
    );
    for k in [0usize, 3] {
        let t = format!("{}", k as f64 / 10.0);
        let mut g = vec!["generate"];
        g.extend(SEA);
        g.extend(["--choppiness", "0.7", "--time", &t, "-o", "g.tif", "-q"]);
        run_ok(dir.path(), &g);
        assert_eq!(
            read(&dir.path().join("g.tif")),
            read(&dir.path().join(format!("seq/frame_{k:05}.tif"))),
            "frame {k} differs from generate --time {t}"
        );
    }
    for suffix in ["png", "normal.png", "foam.png", "jacobian.tif", "disp.tif"] {
        assert!(
            dir.path()
                .join(format!("seq/frame_00002.{suffix}"))
                .is_file()
        );
    }
    // The displacement map's z is the undisplaced height; the Jacobian is finite and
    // below 1 somewhere (crests compress the surface).
    let (w, h, j) = tiff32::read(&dir.path().join("seq/frame_00002.jacobian.tif")).unwrap();
    assert_eq!((w, h), (64, 64));
    assert!(j.iter().all(|v| v.is_finite()));
    assert!(j.iter().any(|&v| v < 0.99) && j.iter().any(|&v| v > 1.01));
}

/// A sequence of maps alone skips the choppy resampling (no file holds the resampled
/// heights), and its maps are the same bytes as those written beside the heights.
#[test]
fn maps_without_heights_are_the_maps_written_with_them() {
    let dir = tempfile::tempdir().unwrap();
    let choppy = ["--frames", "3", "--choppiness", "0.9"];
    for (out, format) in [
        ("with", "tif,normal,foam,jacobian,disp"),
        ("alone", "normal,foam,jacobian,disp"),
    ] {
        let mut a = args(&choppy);
        a.extend(["--format", format, "-o", out, "-q"]);
        run_ok(dir.path(), &a);
    }
    // Maps are frame_NNNNN.KIND.EXT; the heights frame_NNNNN.tif and the sidecar are not.
    let maps = |out: &str| -> Vec<(String, Vec<u8>)> {
        files_of(&dir.path().join(out))
            .into_iter()
            .filter(|(name, _)| name.matches('.').count() == 2)
            .collect()
    };
    let (with, alone) = (maps("with"), maps("alone"));
    assert_eq!(alone.len(), 3 * 4, "four maps a frame");
    assert!(
        with == alone,
        "maps written alone differ from maps beside heights"
    );
}

/// A still sea's foam threshold is resolved once for the sequence: its foam maps are
/// those `generate` writes at each frame's time (resolved over that frame's J). With J ≡ 1
/// the `auto` threshold leaves no foam; a threshold of 1.5 puts coverage ⅓ everywhere, so a
/// wrongly resolved threshold shows.
#[test]
fn a_still_seas_foam_maps_equal_generate_at_their_time() {
    let dir = tempfile::tempdir().unwrap();
    for (i, threshold) in ["auto", "1.5"].into_iter().enumerate() {
        let seq = format!("seq{i}");
        let mut a = args(&["--frames", "2", "--format", "foam,foam.exr,normal"]);
        a.extend(["--wind-speed", "30", "--foam-threshold", threshold]);
        a.extend(["-o", &seq, "-q"]);
        run_ok(dir.path(), &a);
        let g_name = |suffix: &str| format!("g{i}.{suffix}");
        let (png, exr_name, normal) =
            (g_name("foam.png"), g_name("foam.exr"), g_name("normal.png"));
        let mut g = vec!["generate"];
        g.extend(SEA);
        g.extend(["--wind-speed", "30", "--foam-threshold", threshold]);
        g.extend([
            "--time", "0.1", "-q", "-o", &png, "-o", &exr_name, "-o", &normal,
        ]);
        run_ok(dir.path(), &g);
        for suffix in ["foam.png", "normal.png"] {
            assert_eq!(
                read(&dir.path().join(g_name(suffix))),
                read(&dir.path().join(format!("{seq}/frame_00002.{suffix}"))),
                "{threshold}: {suffix} of frame 2 (EXR sequences start at 1) differs from generate --time 0.1"
            );
        }
        let exr = |p: &str| {
            seasynth::export::exr::read_channels(&dir.path().join(p))
                .unwrap()
                .2
        };
        let foam = exr(&exr_name);
        assert_eq!(
            foam,
            exr(&format!("{seq}/frame_00002.foam.exr")),
            "{threshold}"
        );
        let want = if threshold == "auto" { 0.0 } else { 1.0 / 3.0 };
        let all = (foam.iter().flat_map(|(_, v)| v)).all(|&v| (v as f64 - want).abs() < 1e-3);
        assert!(all, "{threshold}: a still sea's foam is {want} everywhere");
    }
}

#[test]
fn a_loop_repeats_after_its_period_and_one_mapping_serves_every_frame() {
    let dir = tempfile::tempdir().unwrap();
    // T = 1.5 s at 10 fps: frame 15 is frame 0 again.
    run_ok(
        dir.path(),
        &args(&[
            "--frames",
            "16",
            "--loop-period",
            "1.5",
            "--format",
            "tif,png",
            "-o",
            "loop",
            "-q",
        ]),
    );
    let f = |k: usize| tiff32::read(&dir.path().join(format!("loop/frame_{k:05}.tif"))).unwrap();
    let (a, b, c) = (f(0).2, f(15).2, f(7).2);
    const LOOP_TOL_M: f32 = 1e-5;
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f32::max);
    assert!(
        worst <= LOOP_TOL_M,
        "frame 15 differs from frame 0 by {worst} m"
    );
    assert!(
        a.iter().zip(&c).any(|(x, y)| (x - y).abs() > 0.01),
        "the sea moves"
    );
    let side = json_file(&dir.path().join("loop/sequence.json"));
    let mapping = HeightMapping {
        min_m: num(&side, "/mapping_min_m"),
        max_m: num(&side, "/mapping_max_m"),
    };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..16 {
        let (_, _, t) = f(k);
        let (_, _, p) = png16::read(&dir.path().join(format!("loop/frame_{k:05}.png"))).unwrap();
        for (&m, &v) in t.iter().zip(&p) {
            lo = lo.min(m as f64);
            hi = hi.max(m as f64);
            assert!((mapping.decode(v) - m as f64).abs() <= mapping.step_m());
        }
    }
    assert_eq!(
        (lo, hi),
        (mapping.min_m, mapping.max_m),
        "the range of all frames"
    );
}

#[test]
fn resume_redoes_only_missing_frames_and_gives_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let a = args(&["--frames", "5", "--format", "png,tif", "-o", "r"]);
    run_ok(dir.path(), &a);
    let before: Vec<Vec<u8>> = (0..5)
        .map(|k| read(&dir.path().join(format!("r/frame_{k:05}.png"))))
        .collect();
    std::fs::remove_file(dir.path().join("r/frame_00002.png")).unwrap();
    let mut again = a.clone();
    again.push("--resume");
    let out = common::seasynth()
        .current_dir(dir.path())
        .args(&again)
        .output()
        .unwrap();
    assert!(out.status.success());
    let msg = String::from_utf8_lossy(&out.stderr);
    assert!(
        msg.contains("wrote 1 frame(s) of 5") && msg.contains("4 skipped"),
        "{msg}"
    );
    for (k, b) in before.iter().enumerate() {
        assert_eq!(
            &read(&dir.path().join(format!("r/frame_{k:05}.png"))),
            b,
            "frame {k}"
        );
    }
    // Another sequence in the same folder is refused.
    let mut other = args(&[
        "--frames", "5", "--format", "png,tif", "-o", "r", "--resume",
    ]);
    other.extend(["--seed", "9"]);
    run_rejected(dir.path(), &other, &["sequence.json", "--resume"]);
}

#[test]
fn bad_animation_arguments_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    run_rejected(
        dir.path(),
        &args(&["--frames", "0", "-o", "x"]),
        &["--frames", "0"],
    );
    run_rejected(
        dir.path(),
        &args(&["--format", "png,gif", "-o", "x"]),
        &["--format", "gif"],
    );
    run_rejected(
        dir.path(),
        &args(&["--loop-period", "-2", "-o", "x"]),
        &["--loop-period", "-2"],
    );
    run_rejected(
        dir.path(),
        &["animate", "--method", "fft", "--fps", "0", "-o", "x"],
        &["--fps"],
    );
    run_rejected(
        dir.path(),
        &args(&["--choppiness", "nan", "-o", "x"]),
        &["--choppiness"],
    );
}

#[test]
fn preview_frames_and_generate_previews_are_rgb_images_of_the_default_view() {
    let dir = tempfile::tempdir().unwrap();
    run_ok(
        dir.path(),
        &args(&["--frames", "2", "--format", "preview", "-o", "p", "-q"]),
    );
    let mut g = vec!["generate"];
    g.extend(SEA);
    g.extend(["--time", "0.1", "-o", "one.preview.png", "-q"]);
    run_ok(dir.path(), &g);
    for f in [
        "p/frame_00000.preview.png",
        "p/frame_00001.preview.png",
        "one.preview.png",
    ] {
        let decoder = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(dir.path().join(f)).unwrap(),
        ));
        let reader = decoder.read_info().unwrap();
        let info = reader.info();
        assert_eq!((info.width, info.height), (1280, 720), "{f}");
        assert_eq!(info.color_type, png::ColorType::Rgb, "{f}");
    }
    // Frame 1 is generate --time 0.1: the same field, so the same picture.
    assert_eq!(
        read(&dir.path().join("p/frame_00001.preview.png")),
        read(&dir.path().join("one.preview.png"))
    );
    assert_ne!(
        read(&dir.path().join("p/frame_00000.preview.png")),
        read(&dir.path().join("p/frame_00001.preview.png"))
    );
}

#[test]
fn exr_sequences_start_at_frame_one_and_each_file_is_generate_at_its_time() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run_ok(
        d,
        &args(&[
            "--frames",
            "3",
            "--format",
            "exr,disp.exr",
            "--choppiness",
            "0.5",
            "--up",
            "z",
            "--exr-compression",
            "zip",
            "--foam-fade",
            "0",
            "-o",
            "seq",
        ]),
    );
    let doc = json_file(&d.join("seq/sequence.json"));
    // The foam (the displacement EXR's A) has the sequence's threshold, resolved once.
    let t = num(&doc, "/foam/threshold_resolved").to_string();
    assert_eq!(
        (doc["start_frame"].as_u64(), doc["up"].as_str()),
        (Some(1), Some("z"))
    );
    assert!(!d.join("seq/frame_00000.exr").exists());
    // File number 3 is frame 2, t = 2/fps; its heights are generate's at that time.
    let mut g: Vec<&str> = vec!["generate"];
    g.extend(SEA);
    g.extend([
        "--choppiness",
        "0.5",
        "--time",
        "0.2",
        "--foam-threshold",
        &t,
        "-o",
        "g.exr",
        "-o",
        "g.disp.exr",
    ]);
    g.extend(["--up", "z", "-q"]);
    run_ok(d, &g);
    let channels = |p: &str| seasynth::export::exr::read_channels(&d.join(p)).unwrap().2;
    assert_eq!(channels("seq/frame_00003.exr"), channels("g.exr"));
    assert_eq!(channels("seq/frame_00003.disp.exr"), channels("g.disp.exr"));
    // --start-frame numbers the files from N; PNG sequences keep starting at 0.
    run_ok(
        d,
        &args(&[
            "--frames",
            "2",
            "--format",
            "exr",
            "--start-frame",
            "101",
            "-o",
            "s",
        ]),
    );
    assert!(d.join("s/frame_00101.exr").is_file() && d.join("s/frame_00102.exr").is_file());
    run_ok(d, &args(&["--frames", "1", "-o", "p"]));
    assert!(d.join("p/frame_00000.png").is_file());
    run_rejected(
        d,
        &args(&["--frames", "1", "--format", "disp.png", "-o", "bad"]),
        &["--format", "disp.png"],
    );
}

/// Every file of a sequence, by name, as bytes.
fn files_of(dir: &std::path::Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                read(&p),
            )
        })
        .collect();
    v.sort();
    v
}

#[test]
fn frames_overlapped_with_their_writing_are_the_same_bytes_at_any_jobs_and_threads() {
    let dir = tempfile::tempdir().unwrap();
    let runs: [&[&str]; 3] = [
        &["--jobs", "1", "--threads", "1"],
        &["--jobs", "3", "--threads", "2"],
        &["--jobs", "2", "--threads", "3"],
    ];
    let mut seen = Vec::new();
    for (i, extra) in runs.iter().enumerate() {
        let out = format!("j{i}");
        let mut a = args(&[
            "--frames",
            "7",
            "--choppiness",
            "0.8",
            "--format",
            "png,tif,normal,foam,disp,disp.exr",
            "--exr-compression",
            "zip",
            "-o",
            &out,
            "-q",
        ]);
        a.extend(*extra);
        run_ok(dir.path(), &a);
        let files = files_of(&dir.path().join(&out));
        assert_eq!(
            files.len(),
            7 * 6 + 1,
            "every frame's files and the sidecar"
        );
        seen.push(files);
    }
    assert!(
        seen[1] == seen[0],
        "--jobs 3 --threads 2 differs from one job and thread"
    );
    assert!(
        seen[2] == seen[0],
        "--jobs 2 --threads 3 differs from one job and thread"
    );
    // The ZIP displacement EXR holds the samples of the uncompressed one.
    let mut a = args(&[
        "--frames",
        "7",
        "--choppiness",
        "0.8",
        "--format",
        "disp.exr",
    ]);
    a.extend(["-o", "plain", "-q"]);
    run_ok(dir.path(), &a);
    for f in [1, 7] {
        let name = format!("frame_{f:05}.disp.exr");
        let zip = seasynth::export::exr::read_channels(&dir.path().join("j0").join(&name));
        let plain = seasynth::export::exr::read_channels(&dir.path().join("plain").join(&name));
        let (zip, plain) = (zip.unwrap(), plain.unwrap());
        assert_eq!(zip.2.len(), 4, "R, G, B and foam in A");
        for ((nz, z), (np, p)) in zip.2.iter().zip(&plain.2) {
            assert_eq!(nz, np);
            let same = z.iter().zip(p).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(
                same,
                "{name}, channel {nz}: ZIP and uncompressed samples differ"
            );
        }
    }
}
