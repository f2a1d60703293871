//! The command line as a whole: the precedence of `--set` and flags, flags without effect,
//! the help against what the commands print, output folders, default names and messages.

mod common;

use common::{json_file, names_in, run_exit2, run_ok, run_rejected, seasynth};
use serde_json::Value;

/// `spectrum … --freq 0.1 --json` with `args`: the resolved parameters, cheaply.
fn params_of(args: &[&str]) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let mut all = vec!["spectrum", "--spectrum", "pierson-moskowitz"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--freq", "0.1", "--json"]);
    let out = run_ok(dir.path(), &all);
    let doc: Value = serde_json::from_str(&out).unwrap();
    doc["params"].clone()
}

#[test]
fn set_and_flags_apply_in_command_line_order_and_a_repeated_flag_takes_its_last_value() {
    let speed = |args: &[&str]| params_of(args)["wind"]["speed_mps"].as_f64().unwrap();
    assert_eq!(
        speed(&["--wind-speed", "10", "--set", "wind-speed=12"]),
        12.0
    );
    assert_eq!(
        speed(&["--set", "wind-speed=12", "--wind-speed", "10"]),
        10.0
    );
    assert_eq!(
        speed(&["--set", "wind.speed_mps=9", "--set", "wind-speed=11"]),
        11.0
    );
    assert_eq!(speed(&["--wind-speed", "10", "--wind-speed", "12"]), 12.0);
    assert_eq!(
        speed(&["--preset", "storm", "--wind-speed", "8"]),
        8.0,
        "flags beat the preset"
    );
    assert_eq!(
        speed(&["--wind-speed", "8", "--preset", "storm"]),
        8.0,
        "wherever it is"
    );
}

/// A value each parameter flag accepts, for the table of flags without effect.
fn sample_value(flag: &str) -> &'static str {
    match flag {
        "seed" => "2",
        "time" => "1",
        "height-range" => "-1:1",
        "loop-period" => "20",
        "nonlinear" => "second-order",
        "choppiness" => "0.5",
        "foam-threshold" => "0.5",
        "foam-fade" => "2",
        "fps" => "24",
        "phase-mode" => "translate",
        "sample-at" => "centers",
        other => panic!("no sample value for --{other}: add one"),
    }
}

#[test]
fn every_flag_without_effect_on_a_command_is_refused_in_one_line() {
    let mut checked = 0;
    for (command, flags, _) in seasynth::commands::common::NO_EFFECT {
        for flag in *flags {
            let dir = tempfile::tempdir().unwrap();
            let value = sample_value(flag);
            let opt = format!("--{flag}");
            let mut args: Vec<&str> = vec![command, &opt, value];
            args.extend_from_slice(match *command {
                "spectrum" => &["--spectrum", "jonswap", "--freq", "0.1", "--json"][..],
                "render" => &["--size", "16", "--image", "8x8", "-o", "out/r.png"][..],
                "generate" => &["--size", "16", "-o", "out/g.tif"][..],
                other => panic!("no command line for {other}: add one"),
            });
            run_rejected(
                dir.path(),
                &args,
                &[&format!(
                    "--{flag} {value}: has no effect on `seasynth {command}`"
                )],
            );
            assert!(names_in(dir.path()).is_empty(), "{args:?} wrote something");
            checked += 1;
        }
    }
    assert!(checked >= 14, "{checked} cases");
    // The same flags where they have an effect are accepted.
    let dir = tempfile::tempdir().unwrap();
    run_ok(
        dir.path(),
        &[
            "generate",
            "--size",
            "16",
            "--height-range",
            "-1:1",
            "-o",
            "h.png",
        ],
    );
}

#[test]
fn spectrum_help_names_every_key_its_json_prints() {
    let dir = tempfile::tempdir().unwrap();
    let out = run_ok(
        dir.path(),
        &[
            "spectrum",
            "--spectrum",
            "jonswap",
            "--freq",
            "0.1",
            "--json",
        ],
    );
    let doc: Value = serde_json::from_str(&out).unwrap();
    let help = run_ok(dir.path(), &["spectrum", "--help"]);
    let mut keys: Vec<&String> = doc.as_object().unwrap().keys().collect();
    keys.extend(doc["points"][0].as_object().unwrap().keys());
    assert!(keys.len() >= 10, "{keys:?}");
    for k in keys {
        assert!(
            help.contains(k.as_str()),
            "`spectrum --help` does not name `{k}`"
        );
    }
}

#[test]
fn every_command_creates_a_missing_output_folder() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run_ok(
        d,
        &[
            "generate",
            "--size",
            "16",
            "-o",
            "a/b/x.png",
            "-o",
            "c/x.normal.png",
        ],
    );
    assert!(d.join("a/b/x.png").is_file() && d.join("a/b/x.json").is_file());
    assert!(d.join("c/x.normal.png").is_file());
    run_ok(
        d,
        &[
            "spectrum",
            "--spectrum",
            "jonswap",
            "--plot",
            "p/f.png",
            "--plot2d",
            "q/k.png",
        ],
    );
    assert!(d.join("p/f.png").is_file() && d.join("q/k.png").is_file());
    run_ok(
        d,
        &[
            "analyze",
            "a/b/x.png",
            "--plot",
            "s/s.png",
            "--plot-waves",
            "w/w.png",
        ],
    );
    assert!(d.join("s/s.png").is_file() && d.join("w/w.png").is_file());
    run_ok(
        d,
        &["render", "--size", "16", "--image", "8x8", "-o", "r/r.png"],
    );
    assert!(d.join("r/r.png").is_file());
    run_ok(
        d,
        &[
            "render",
            "--from",
            "a/b/x.png",
            "--image",
            "8x8",
            "-o",
            "r2/r.png",
        ],
    );
    assert!(d.join("r2/r.png").is_file());
}

#[test]
fn a_file_in_the_way_of_an_output_folder_is_named_with_the_users_path() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("f"), b"").unwrap();
    for args in [
        &["generate", "--size", "16", "-o", "f/x.png"][..],
        &["spectrum", "--spectrum", "jonswap", "--plot", "f/p.png"][..],
        &[
            "render",
            "--size",
            "16",
            "--image",
            "8x8",
            "-o",
            "f/g/r.png",
        ][..],
    ] {
        let e = run_rejected(d, args, &["is a file, not a folder", "output f/"]);
        assert!(!e.contains(".part"), "{e}");
    }
    assert_eq!(names_in(d), ["f"]);
}

#[test]
fn the_default_name_is_the_presets_only_when_its_parameters_are_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run_ok(d, &["generate", "--preset", "calm"]);
    assert!(d.join("out/calm.png").is_file() && d.join("out/calm.tif").is_file());
    run_ok(
        d,
        &[
            "generate",
            "--size",
            "16",
            "--wind-dir",
            "90",
            "--method",
            "fft",
        ],
    );
    assert!(d.join("out/li-tian-custom.png").is_file());
    assert!(!d.join("out/li-tian.png").exists());
    let sidecar = json_file(&d.join("out/li-tian-custom.json"));
    assert_eq!(sidecar["params"]["method"], "fft");
}

#[test]
fn tiles_are_reported_by_their_pattern_and_count() {
    let dir = tempfile::tempdir().unwrap();
    let out = seasynth()
        .current_dir(dir.path())
        .args(["generate", "--size", "16", "--tiles", "2x3", "-o", "x.obj"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("wrote 6 tiles x_x0_y0.obj … x_x1_y2.obj"),
        "{stderr}"
    );
    assert!(!stderr.contains("wrote x.obj"), "{stderr}");
    assert!(dir.path().join("x_x1_y2.obj").is_file());
}

#[test]
fn the_phillips_spectrum_says_its_heights_are_not_meters() {
    let dir = tempfile::tempdir().unwrap();
    let note = |args: &[&str]| {
        let out = seasynth()
            .current_dir(dir.path())
            .args(args)
            .output()
            .unwrap();
        assert!(out.status.success());
        String::from_utf8_lossy(&out.stderr).contains("not meters of a real sea")
    };
    assert!(note(&[
        "generate",
        "--preset",
        "tessendorf-usc",
        "-o",
        "t.tif"
    ]));
    assert!(!note(&[
        "generate",
        "--method",
        "fft",
        "--spectrum",
        "jonswap",
        "--size",
        "16",
        "-o",
        "j.tif"
    ]));
}

#[test]
fn a_batch_with_a_bad_sweep_or_job_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let e = run_exit2(
        d,
        &[
            "batch",
            "--size",
            "16",
            "--sweep",
            "wind-dir=0:360",
            "-o",
            "b",
        ],
    );
    assert!(e.contains("a range is START:STOP:STEP"), "{e}");
    let e = run_exit2(
        d,
        &[
            "batch",
            "--size",
            "16",
            "--sweep",
            "wind-speed=7,-3",
            "-o",
            "b",
        ],
    );
    assert!(e.contains("job 1") && e.contains("(got -3)"), "{e}");
    assert!(names_in(d).is_empty(), "{:?}", names_in(d));
}
