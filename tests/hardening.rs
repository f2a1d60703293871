//! Hardening: every bad input of `tests/bad` fails cleanly, extreme but valid values give
//! finite outputs or a clear error, the memory guard refuses what would not fit, and
//! interruptions, failing writes and concurrent writers leave no partial file.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{analyze_json, names_in, read, run_ok, seasynth};

fn bad_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad")
}

fn bin() -> PathBuf {
    assert_cmd::cargo::cargo_bin("seasynth")
}

fn run_in(dir: &Path, args: &[&str]) -> Output {
    seasynth()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("seasynth runs")
}

/// The cases of `tests/bad`: each preset `*.toml` with its first line `# expect: TEXT`
/// (run as `generate --preset FILE`), and each line `ARGS<TAB>TEXT` of `cases.tsv`
/// (`{bad}` standing for the folder). Manifests join as `.toml` files or table lines.
fn bad_cases() -> Vec<(Vec<String>, String)> {
    let dir = bad_dir();
    let mut cases = Vec::new();
    let mut presets: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/bad")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    presets.sort();
    for path in presets {
        let bytes = read(&path);
        let text = String::from_utf8_lossy(&bytes);
        let fragment = text
            .lines()
            .next()
            .and_then(|l| l.strip_prefix("# expect:"))
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .unwrap_or_else(|| panic!("{}: first line must be `# expect: TEXT`", path.display()));
        let preset = path.to_str().expect("UTF-8 path").to_string();
        cases.push((
            vec!["generate".into(), "--preset".into(), preset],
            fragment.to_string(),
        ));
    }
    let table = String::from_utf8(read(&dir.join("cases.tsv"))).expect("UTF-8 table");
    let root = dir.to_str().expect("UTF-8 path");
    for (n, line) in table.lines().enumerate() {
        if line.starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let (args, fragment) = line
            .split_once('\t')
            .unwrap_or_else(|| panic!("cases.tsv:{}: expected ARGS<TAB>TEXT", n + 1));
        let args = args
            .split_whitespace()
            .map(|a| a.replace("{bad}", root))
            .collect();
        cases.push((args, fragment.trim().to_string()));
    }
    cases
}

#[test]
fn every_bad_input_in_tests_bad_fails_with_its_expected_message_and_writes_nothing() {
    let cases = bad_cases();
    assert!(cases.len() >= 100, "tests/bad holds {} cases", cases.len());
    let mut failures = Vec::new();
    for (args, fragment) in &cases {
        let dir = tempfile::tempdir().unwrap();
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_in(dir.path(), &refs);
        let stderr = String::from_utf8_lossy(&out.stderr);
        let shown = format!("`seasynth {}`", args.join(" "));
        if out.status.code() != Some(2) {
            failures.push(format!(
                "{shown}: exit {:?}, not 2: {stderr}",
                out.status.code()
            ));
        } else if stderr.trim_end().lines().count() != 1 {
            failures.push(format!("{shown}: not one line on stderr: {stderr}"));
        } else if !stderr.contains(fragment.as_str()) {
            failures.push(format!("{shown}: stderr lacks `{fragment}`: {stderr}"));
        } else if !out.stdout.is_empty() {
            failures.push(format!("{shown}: printed on stdout"));
        } else if !names_in(dir.path()).is_empty() {
            failures.push(format!("{shown}: left {:?}", names_in(dir.path())));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} bad inputs misbehaved:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// Extreme but valid values: each is run with every method and with every spectrum model.
const EXTREMES: &[(&str, &[&str])] = &[
    ("--wind-speed", &["1", "60", "100", "1e-9"]),
    ("--extent", &["1", "100000", "1e-6", "1e9", "1x100000"]),
    ("--depth", &["0.01", "1e6"]),
    ("--fetch-km", &["1e-6", "1e6"]),
    ("--gamma", &["1", "20"]),
    ("--choppiness", &["10", "-10"]),
    ("--loop-period", &["1e-6", "1e9"]),
    ("--time", &["1e15", "-1e15"]),
    ("--wind-dir", &["1e15", "-720"]),
    ("--size", &["2", "2x64", "3x5"]),
    ("--seed", &["0", "9223372036854775807"]),
    (
        "--set",
        &[
            "perlin.octaves=24",
            "perlin.persistence=0.999999",
            "perlin.lacunarity=16",
            "perlin.wavelength_m=1e-9",
            "perlin.amplitude_m=1e6",
            "spectrum.phillips_a=1e6",
            "spectrum.small_wave_m=1e9",
            "spectrum.swell=10",
            "fractal.dimension=2.000001",
            "fractal.relief_m=1e6",
            "fractal.rolloff_m=1e-9",
            "blend.beta=1e6",
            "blend.beta_scale=1e6",
            "trochoid.components=4096",
            "trochoid.sharpness=0.98",
            "trochoid.octaves=16",
            "trochoid.multiplier=8",
            "trochoid.amplitude_m=1e6",
        ],
    ),
];

/// What each extreme value runs with: the methods, and the spectrum models under `fft`.
const SETTINGS: &[&[&str]] = &[
    &["--method", "hybrid"],
    &["--method", "trochoid"],
    &["--method", "fft"],
    &["--method", "filtered-noise"],
    &["--method", "perlin"],
    &["--method", "fft", "--spectrum", "pierson-moskowitz"],
    &["--method", "fft", "--spectrum", "jonswap"],
    // A `--set` depth, so that the extreme `--depth` values override it.
    &[
        "--method",
        "fft",
        "--spectrum",
        "tma",
        "--set",
        "spectrum.depth_m=3",
    ],
    &["--method", "fft", "--spectrum", "fractal"],
    &[
        "--method",
        "filtered-noise",
        "--spectrum",
        "jonswap",
        "--hs",
        "1000",
        "--tp",
        "1e4",
    ],
];

/// Every float of a TIFF written by seasynth is finite, and the sidecar's statistics too.
fn assert_finite_outputs(dir: &Path, shown: &str) {
    let (w, h, v) = seasynth::export::tiff32::read(&dir.join("x.tif"))
        .unwrap_or_else(|e| panic!("{shown}: x.tif unreadable: {e}"));
    assert_eq!(v.len(), w * h, "{shown}: one sample per pixel");
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        panic!("{shown}: sample {i} of x.tif is {}", v[i]);
    }
    let side: serde_json::Value = serde_json::from_slice(&read(&dir.join("x.json"))).unwrap();
    for k in ["min_m", "max_m", "mean_m", "std_m", "hs_m"] {
        let s = &side["stats"][k];
        assert!(
            s.as_f64().is_some_and(f64::is_finite),
            "{shown}: stats.{k} is {s}"
        );
    }
    let obj = String::from_utf8(read(&dir.join("x.obj"))).unwrap();
    let bad = obj
        .lines()
        .filter(|l| !l.starts_with('#'))
        .flat_map(str::split_whitespace)
        .find(|t| {
            let t = t.to_ascii_lowercase();
            t.contains("nan") || t.contains("inf")
        });
    assert!(bad.is_none(), "{shown}: x.obj holds {bad:?}");
}

#[test]
fn extreme_values_exit_with_0_or_2_and_give_finite_outputs() {
    let mut runs = Vec::new();
    for (flag, values) in EXTREMES {
        for v in *values {
            for setting in SETTINGS {
                let mut args = vec!["generate", "--quiet"];
                if *flag != "--size" {
                    args.extend(["--size", "12x10"]);
                }
                args.extend_from_slice(setting);
                args.extend([*flag, *v, "-o", "x.tif", "-o", "x.obj"]);
                runs.push(args);
            }
        }
    }
    // Two at a time (the machine's cores), each in its own folder.
    let refused = std::sync::atomic::AtomicUsize::new(0);
    std::thread::scope(|s| {
        for half in runs.chunks(runs.len().div_ceil(2)) {
            let refused = &refused;
            s.spawn(move || {
                for args in half {
                    let dir = tempfile::tempdir().unwrap();
                    let out = run_in(dir.path(), args);
                    let shown = format!("`seasynth {}`", args.join(" "));
                    let stderr = String::from_utf8_lossy(&out.stderr);
                    match out.status.code() {
                        Some(0) => assert_finite_outputs(dir.path(), &shown),
                        Some(2) => {
                            assert_eq!(stderr.trim_end().lines().count(), 1, "{shown}: {stderr}");
                            assert!(names_in(dir.path()).is_empty(), "{shown} left files");
                            refused.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        }
                        other => panic!("{shown}: exit {other:?} (a panic is 101):\n{stderr}"),
                    }
                }
            });
        }
    });
    let refused = refused.into_inner();
    assert!(
        refused * 10 < runs.len(),
        "{refused} of {} extreme but valid runs were refused",
        runs.len()
    );
}

#[test]
fn extreme_values_of_the_other_commands_exit_with_0_or_2() {
    let cases: &[&[&str]] = &[
        &[
            "spectrum",
            "--spectrum",
            "jonswap",
            "--wind-speed",
            "1e-300",
            "--freq",
            "0.1",
            "--json",
        ],
        &[
            "spectrum",
            "--spectrum",
            "jonswap",
            "--wind-speed",
            "100",
            "--freq",
            "1e-300,1e300",
            "--json",
        ],
        &[
            "spectrum",
            "--spectrum",
            "tma",
            "--depth",
            "1e-3",
            "--freq",
            "0.01,10",
            "--json",
        ],
        &[
            "spectrum",
            "--spectrum",
            "pierson-moskowitz",
            "--hs",
            "1000",
            "--tp",
            "1e4",
            "--freq",
            "1e-4",
            "--json",
        ],
        &[
            "animate",
            "--size",
            "8",
            "--frames",
            "2",
            "--fps",
            "1000",
            "--format",
            "png,tif,normal,foam,jacobian,disp",
            "-o",
            "a",
        ],
        &[
            "animate",
            "--size",
            "8",
            "--frames",
            "2",
            "--loop-period",
            "1e-6",
            "--choppiness",
            "10",
            "--format",
            "tif,jacobian",
            "-o",
            "b",
        ],
        &[
            "animate",
            "--size",
            "8",
            "--frames",
            "2",
            "--method",
            "filtered-noise",
            "--phase-mode",
            "hot-air",
            "-o",
            "c",
        ],
        &[
            "render", "--size", "8", "--image", "16x9", "--camera", "0,0,1e9", "-o", "r.png",
        ],
        &[
            "render", "--size", "8", "--image", "1x1", "--extent", "1e-6", "--fov", "179", "-o",
            "s.png",
        ],
        &[
            "render",
            "--size",
            "2",
            "--image",
            "16x9",
            "--view",
            "top",
            "--wind-speed",
            "60",
            "-o",
            "t.png",
        ],
        &[
            "bench",
            "--sizes",
            "2,3",
            "--repeats",
            "1",
            "--dir",
            "bench",
        ],
        // Very unequal spacings: analyze once asked for 1e15 radial bins (an abort).
        &[
            "generate",
            "--quiet",
            "--size",
            "8",
            "--extent",
            "1e-6x1e9",
            "-o",
            "aniso.tif",
        ],
        &["analyze", "aniso.tif", "--json", "--plot", "aniso.png"],
        &[
            "render",
            "--from",
            "aniso.tif",
            "--image",
            "16x9",
            "-o",
            "aniso-view.png",
        ],
    ];
    let dir = tempfile::tempdir().unwrap();
    for args in cases {
        let out = run_in(dir.path(), args);
        let shown = format!("`seasynth {}`", args.join(" "));
        let stdout = String::from_utf8_lossy(&out.stdout);
        match out.status.code() {
            Some(0) => {
                if let Ok(doc) = serde_json::from_str::<serde_json::Value>(&stdout) {
                    let mut nulls = Vec::new();
                    null_numbers(&doc, "", &mut nulls);
                    assert!(nulls.is_empty(), "{shown}: non-finite numbers at {nulls:?}");
                }
            }
            Some(2) => {}
            other => panic!(
                "{shown}: exit {other:?}:\n{}",
                String::from_utf8_lossy(&out.stderr)
            ),
        }
    }
    // Every float TIFF the animations wrote is finite.
    for sub in ["a", "b"] {
        for name in names_in(&dir.path().join(sub)) {
            if name.ends_with("png.tif") || !name.ends_with(".tif") {
                continue;
            }
            let (_, _, v) = seasynth::export::tiff32::read(&dir.path().join(sub).join(&name))
                .unwrap_or_else(|e| panic!("{sub}/{name}: {e}"));
            assert!(v.iter().all(|x| x.is_finite()), "{sub}/{name} not finite");
        }
    }
}

/// Keys with a unit (`hs_m`, `fp_hz`, …) whose value is null: a NaN or an infinity that
/// serde_json wrote as null.
fn null_numbers(v: &serde_json::Value, at: &str, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                let unit = ["_m", "_hz", "_s", "_m2", "_per_m", "_deg"]
                    .iter()
                    .any(|u| k.ends_with(u));
                if x.is_null() && unit {
                    out.push(format!("{at}/{k}"));
                }
                null_numbers(x, &format!("{at}/{k}"), out);
            }
        }
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                null_numbers(x, &format!("{at}/{i}"), out);
            }
        }
        _ => {}
    }
}

/// Slow: a 16384² field takes about 25 s and 2.1 GB to generate and 60 s and 5.2 GB to
/// analyze (release build).
#[test]
#[ignore]
fn the_largest_common_grid_generates_and_analyzes_to_finite_values() {
    let dir = tempfile::tempdir().unwrap();
    run_ok(
        dir.path(),
        &[
            "generate", "--quiet", "--method", "fft", "--size", "16384", "-o", "big.tif",
        ],
    );
    let doc = analyze_json(dir.path(), "big.tif");
    let std = doc["std_m"].as_f64().expect("std_m");
    assert!(std.is_finite() && std > 0.0, "std {std}");
}

#[test]
fn a_run_that_needs_more_memory_than_available_is_refused_with_the_options_unless_forced() {
    let runs: &[&[&str]] = &[
        &["generate", "--size", "256", "-o", "g.tif"],
        &["animate", "--size", "256", "--frames", "2", "-o", "frames"],
        &["render", "--size", "256", "--image", "16x9", "-o", "r.png"],
    ];
    for args in runs {
        let dir = tempfile::tempdir().unwrap();
        let out = seasynth()
            .current_dir(dir.path())
            .env(seasynth::limits::MEMORY_ENV, "1M")
            .args(*args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        let shown = format!("`seasynth {}`", args.join(" "));
        assert_eq!(out.status.code(), Some(2), "{shown}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{shown}: {stderr}");
        for want in [
            "256x256",
            "needs about",
            "1.0 MiB is available",
            "smaller --size",
            "--method trochoid",
            "--force",
        ] {
            assert!(stderr.contains(want), "{shown}: lacks `{want}`: {stderr}");
        }
        assert!(names_in(dir.path()).is_empty(), "{shown} wrote files");
        let mut forced = args.to_vec();
        forced.extend(["--force", "--quiet"]);
        let out = seasynth()
            .current_dir(dir.path())
            .env(seasynth::limits::MEMORY_ENV, "1M")
            .args(&forced)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{shown} --force failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// Temporary files (`.NAME.XXXXXX.part`) in `dir`.
fn parts_in(dir: &Path) -> Vec<String> {
    names_in(dir)
        .into_iter()
        .filter(|n| n.ends_with(".part"))
        .collect()
}

/// Waits until `dir` holds a temporary file (the run is writing), or the child ends.
fn wait_for_part(child: &mut std::process::Child, dir: &Path) {
    let start = Instant::now();
    while parts_in(dir).is_empty() {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the run ended ({status}) before it wrote anything");
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "no temporary file"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn signal(child: &std::process::Child, sig: i32) {
    // SAFETY: kill(2) on the pid of a child this test started and has not reaped.
    let r = unsafe { libc::kill(child.id() as i32, sig) };
    assert_eq!(r, 0, "kill failed");
}

#[test]
fn sigint_during_a_large_run_removes_its_temporary_files_and_keeps_the_earlier_output() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("big.obj"), b"earlier").unwrap();
    let mut child = Command::new(bin())
        .current_dir(dir.path())
        .args([
            "generate", "--quiet", "--size", "2048", "-o", "big.obj", "-o", "big.glb",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    wait_for_part(&mut child, dir.path());
    std::thread::sleep(Duration::from_millis(200));
    signal(&child, libc::SIGINT);
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(seasynth::error::exit::INTERRUPTED),
        "exit code after SIGINT: {stderr}"
    );
    assert!(stderr.contains("interrupted by SIGINT"), "{stderr}");
    assert_eq!(
        parts_in(dir.path()),
        Vec::<String>::new(),
        "temporary files left"
    );
    assert_eq!(
        read(&dir.path().join("big.obj")),
        b"earlier",
        "earlier output replaced"
    );
    assert!(
        !dir.path().join("big.json").exists(),
        "the sidecar is written last, after an interruption there is none"
    );
}

#[test]
fn sigterm_during_an_animation_leaves_only_complete_frames() {
    let dir = tempfile::tempdir().unwrap();
    let frames = dir.path().join("frames");
    let child = Command::new(bin())
        .current_dir(dir.path())
        .args(["animate", "--quiet", "--size", "512", "--frames", "100000"])
        .args([
            "--height-range",
            "-3:3",
            "--format",
            "png,tif",
            "-o",
            "frames",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::fs::create_dir_all(&frames).unwrap();
    // Some frames are complete before the signal.
    let start = Instant::now();
    while names_in(&frames)
        .iter()
        .filter(|n| n.ends_with(".tif"))
        .count()
        < 2
    {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "no frame written"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    signal(&child, libc::SIGTERM);
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(seasynth::error::exit::INTERRUPTED),
        "exit code after SIGTERM: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        parts_in(&frames),
        Vec::<String>::new(),
        "temporary files left"
    );
    for name in names_in(&frames) {
        let p = frames.join(&name);
        if name.ends_with(".tif") {
            let (w, h, v) = seasynth::export::tiff32::read(&p).unwrap();
            assert_eq!((w, h, v.len()), (512, 512, 512 * 512), "{name} incomplete");
        } else if name.ends_with(".png") {
            let (w, h, v) = seasynth::export::png16::read(&p).unwrap();
            assert_eq!((w, h, v.len()), (512, 512, 512 * 512), "{name} incomplete");
        }
    }
}

/// Runs `seasynth ARGS` in `dir` with a file-size limit (`ulimit -f`) of `bytes`.
fn run_with_file_limit(dir: &Path, bytes: u64, args: &[&str]) -> Output {
    use std::os::unix::process::CommandExt;
    let mut cmd = Command::new(bin());
    cmd.current_dir(dir).args(args);
    // SAFETY: setrlimit is async-signal-safe; nothing else runs between fork and exec.
    unsafe {
        cmd.pre_exec(move || {
            let lim = libc::rlimit {
                rlim_cur: bytes as libc::rlim_t,
                rlim_max: bytes as libc::rlim_t,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    cmd.output().expect("seasynth runs")
}

#[test]
fn a_write_past_the_file_size_limit_fails_naming_the_file_and_keeps_the_earlier_one() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("a.tif"), b"earlier").unwrap();
    // A 256² float TIFF is 256 KiB: four times the limit.
    let out = run_with_file_limit(
        dir.path(),
        64 << 10,
        &["generate", "--quiet", "--size", "256", "-o", "a.tif"],
    );
    assert_failed_cleanly(&out, 1, dir.path(), "a.tif", "File too large");
}

/// A run that failed writing `name` in `dir`: exit `code`, one line naming the file and
/// `os_error`, the earlier file (`earlier`) intact and nothing else left.
fn assert_failed_cleanly(out: &Output, code: i32, dir: &Path, name: &str, os_error: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(code), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains(name) && stderr.contains(os_error),
        "names the file and the OS error: {stderr}"
    );
    assert_eq!(read(&dir.join(name)), b"earlier");
    assert_eq!(names_in(dir), vec![name.to_string()], "nothing else left");
}

#[test]
fn a_read_only_destination_fails_at_once_and_keeps_the_earlier_file() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let ro = dir.path().join("ro");
    std::fs::create_dir(&ro).unwrap();
    std::fs::write(ro.join("a.png"), b"earlier").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    // As root (some CI runners), permission bits do not stop writes: then there is
    // nothing to test here (the file-size limit test covers failing writes).
    let root_writes = std::fs::write(ro.join("probe"), b"").is_ok();
    if root_writes {
        std::fs::remove_file(ro.join("probe")).unwrap();
        eprintln!("note: permission bits do not stop this user's writes; skipped");
    } else {
        let out = run_in(
            dir.path(),
            &["generate", "--quiet", "--size", "64", "-o", "ro/a.png"],
        );
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains("ro/a.png") && stderr.contains("Permission denied"),
            "{stderr}"
        );
        assert_eq!(names_in(&ro), vec!["a.png".to_string()]);
    }
    assert_eq!(read(&ro.join("a.png")), b"earlier");
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).unwrap();
}

#[test]
fn concurrent_writers_to_one_path_leave_one_complete_file() {
    let dir = tempfile::tempdir().unwrap();
    let seeds = ["1", "2", "3", "4"];
    let base = ["generate", "--quiet", "--size", "256", "--method", "fft"];
    for s in seeds {
        let mut args = base.to_vec();
        args.extend(["--seed", s, "-o"]);
        let name = format!("ref{s}.tif");
        args.push(&name);
        run_ok(dir.path(), &args);
    }
    let refs: Vec<Vec<u8>> = seeds
        .iter()
        .map(|s| read(&dir.path().join(format!("ref{s}.tif"))))
        .collect();
    for round in 0..3 {
        let children: Vec<_> = seeds
            .iter()
            .map(|s| {
                Command::new(bin())
                    .current_dir(dir.path())
                    .args(base)
                    .args(["--seed", s, "-o", "same.tif"])
                    .stderr(Stdio::piped())
                    .spawn()
                    .unwrap()
            })
            .collect();
        for c in children {
            let out = c.wait_with_output().unwrap();
            assert!(
                out.status.success(),
                "round {round}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        let got = read(&dir.path().join("same.tif"));
        assert!(
            refs.contains(&got),
            "round {round}: same.tif is none of the four complete outputs"
        );
        let side: serde_json::Value =
            serde_json::from_slice(&read(&dir.path().join("same.json"))).expect("valid sidecar");
        assert!(side["seed"].as_u64().is_some(), "round {round}: sidecar");
        assert_eq!(parts_in(dir.path()), Vec::<String>::new(), "round {round}");
    }
}

/// A small tmpfs mounted on a folder for a test's life, so that a full or read-only
/// file system is real (the permission bits of the test above do not stop root). `None`
/// where this user may not mount.
struct Tmpfs(PathBuf);

impl Tmpfs {
    fn mount(dir: &Path, options: &str) -> Option<Self> {
        let mounted = Command::new("mount")
            .args(["-t", "tmpfs", "-o", options, "tmpfs"])
            .arg(dir)
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        mounted.then(|| Tmpfs(dir.to_path_buf()))
    }

    fn remount_read_only(&self) {
        let status = Command::new("mount")
            .args(["-o", "remount,ro"])
            .arg(&self.0)
            .status()
            .expect("mount runs");
        assert!(status.success(), "remount read-only");
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        if let Err(e) = Command::new("umount").arg(&self.0).status() {
            eprintln!("umount {}: {e}", self.0.display());
        }
    }
}

#[test]
fn a_write_to_a_full_file_system_fails_naming_the_file_and_keeps_the_earlier_one() {
    let dir = tempfile::tempdir().unwrap();
    // 128 KiB of space; a 256² float TIFF needs 256 KiB.
    let Some(_fs) = Tmpfs::mount(dir.path(), "size=128k") else {
        eprintln!(
            "note: this user may not mount a tmpfs; skipped (the file-size limit test covers failing writes)"
        );
        return;
    };
    std::fs::write(dir.path().join("a.tif"), b"earlier").unwrap();
    let out = run_in(
        dir.path(),
        &["generate", "--quiet", "--size", "256", "-o", "a.tif"],
    );
    assert_failed_cleanly(&out, 1, dir.path(), "a.tif", "No space left on device");
}

#[test]
fn a_read_only_file_system_fails_at_once_and_keeps_the_earlier_file() {
    let dir = tempfile::tempdir().unwrap();
    let Some(fs) = Tmpfs::mount(dir.path(), "size=1m") else {
        eprintln!("note: this user may not mount a tmpfs; skipped");
        return;
    };
    std::fs::write(dir.path().join("a.png"), b"earlier").unwrap();
    fs.remount_read_only();
    let out = run_in(
        dir.path(),
        &["generate", "--quiet", "--size", "64", "-o", "a.png"],
    );
    assert_failed_cleanly(&out, 2, dir.path(), "a.png", "Read-only file system");
}
