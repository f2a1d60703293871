//! `seasynth generate`, run as a program: default outputs, determinism, the round trips
//! through PNG, TIFF and the sidecar, the methods against each other, the wind direction,
//! the α image, and bad input (exit code 2, one line, no file left behind).

mod common;

use common::{json_file, names_in, num, read, run_ok, run_rejected};
use std::path::{Path, PathBuf};

use seasynth::cli::FieldArgs;
use seasynth::export::{png16, tiff32};
use serde_json::Value;

/// Relative tolerance of comparisons that go through an f32 product.
const REL_TOL: f64 = 1e-6;

/// `generate` with a small grid, the given arguments, in `dir`.
fn generate(dir: &Path, args: &[&str]) {
    let mut all = vec!["generate", "--quiet"];
    all.extend_from_slice(args);
    run_ok(dir, &all);
}

fn tiff(path: &Path) -> (usize, usize, Vec<f32>) {
    tiff32::read(path).unwrap_or_else(|e| panic!("{} is not a float TIFF: {e}", path.display()))
}

fn png(path: &Path) -> (usize, usize, Vec<u16>) {
    png16::read(path).unwrap_or_else(|e| panic!("{} is not a 16-bit gray PNG: {e}", path.display()))
}

/// Every file (not folder) under `dir`, hidden ones included, sorted.
fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).expect("readable folder") {
        let path = entry.expect("folder entry").path();
        if path.is_dir() {
            found.extend(files_under(&path));
        } else {
            found.push(path);
        }
    }
    found.sort();
    found
}

/// Asserts that `a` and `b` hold the same bytes, saying where they first differ.
fn assert_same_bytes(a: &Path, b: &Path) {
    let (x, y) = (read(a), read(b));
    if x != y {
        let at = x.iter().zip(&y).position(|(p, q)| p != q);
        panic!(
            "{} ({} bytes) and {} ({} bytes) differ, first at byte {:?}",
            a.display(),
            x.len(),
            b.display(),
            y.len(),
            at
        );
    }
}

/// Runs `generate ARGS` in an empty folder and checks the rejection: exit code 2, no
/// output on stdout, exactly one line on stderr containing every fragment, and no file
/// left anywhere in the folder (no outputs, sidecars or hidden `.part` files).
fn assert_rejected(args: &[&str], fragments: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let mut all = vec!["generate"];
    all.extend_from_slice(args);
    run_rejected(dir.path(), &all, fragments);
    let shown = format!("`generate {}`", args.join(" "));
    let left = files_under(dir.path());
    assert!(left.is_empty(), "{shown} left files behind: {left:?}");
}

/// The parameters a command line resolves to, computed in this process.
fn field_args(args: &[(&str, &str)], sets: &[&str]) -> FieldArgs {
    let mut f = FieldArgs {
        set: sets.iter().map(|s| s.to_string()).collect(),
        ..FieldArgs::default()
    };
    for (flag, value) in args {
        let v = Some(value.to_string());
        match *flag {
            "method" => f.method = v,
            "size" => f.size = v,
            "extent" => f.extent = v,
            "wind-speed" => f.wind_speed = v,
            "wind-dir" => f.wind_dir = v,
            "seed" => f.seed = v,
            "time" => f.time = v,
            "height-range" => f.height_range = v,
            other => panic!("test helper does not know --{other}"),
        }
    }
    f
}

/// Mean squared difference between neighbours along x and along y (periodic).
fn slope_variances(nx: usize, ny: usize, h: &[f32]) -> (f64, f64) {
    let (mut sx, mut sy) = (0.0f64, 0.0f64);
    for j in 0..ny {
        for i in 0..nx {
            let here = h[j * nx + i] as f64;
            let dx = h[j * nx + (i + 1) % nx] as f64 - here;
            let dy = h[((j + 1) % ny) * nx + i] as f64 - here;
            sx += dx * dx;
            sy += dy * dy;
        }
    }
    let n = (nx * ny) as f64;
    (sx / n, sy / n)
}

#[test]
fn generate_without_arguments_writes_the_li_tian_png_tiff_and_sidecar_under_out() {
    let dir = tempfile::tempdir().unwrap();
    run_ok(dir.path(), &["generate"]);
    let out = dir.path().join("out");
    assert_eq!(
        names_in(&out),
        ["li-tian.json", "li-tian.png", "li-tian.tif"],
        "files under out/"
    );

    let (w, h, _) = png(&out.join("li-tian.png"));
    assert_eq!((w, h), (512, 512), "PNG size");
    let (w, h, heights) = tiff(&out.join("li-tian.tif"));
    assert_eq!((w, h), (512, 512), "TIFF size");

    let doc = json_file(&out.join("li-tian.json"));
    for key in ["min_m", "max_m", "mean_m", "std_m", "hs_m"] {
        num(&doc, &format!("/stats/{key}"));
    }
    let std = num(&doc, "/stats/std_m");
    let hs = num(&doc, "/stats/hs_m");
    assert!(std > 0.0, "a flat default field: std {std}");
    assert!(
        (hs - 4.0 * std).abs() <= 1e-9,
        "hs_m {hs} must be 4·std_m = {}",
        4.0 * std
    );
    assert_eq!(doc["seed"], 1, "the li-tian seed");
    assert_eq!(
        doc["version"],
        env!("CARGO_PKG_VERSION"),
        "the tool version"
    );
    assert!(doc["params"].is_object(), "params object: {doc:#}");
    assert_eq!(doc["params"]["method"], "hybrid", "li-tian is hybrid");
    assert_eq!(
        num(&doc, "/mapping/min_m"),
        num(&doc, "/stats/min_m"),
        "mapping starts at the field's min"
    );
    assert_eq!(
        num(&doc, "/mapping/max_m"),
        num(&doc, "/stats/max_m"),
        "mapping ends at the field's max"
    );
    // Heights are f32; compared as f32 because serde_json (without its
    // `float_roundtrip` feature) may read a long decimal one f64 ulp off.
    let lo = heights.iter().copied().fold(f32::INFINITY, f32::min);
    let hi = heights.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    assert_eq!(
        (lo, hi),
        (
            num(&doc, "/stats/min_m") as f32,
            num(&doc, "/stats/max_m") as f32
        ),
        "TIFF heights' min/max against the sidecar's stats"
    );
}

#[test]
fn same_seed_gives_identical_png_and_tiff_bytes_with_one_thread_and_two() {
    let common = [
        "--method",
        "hybrid",
        "--size",
        "96x64",
        "--extent",
        "192x128",
        "--seed",
        "42",
        "--time",
        "3.25",
        "--wind-dir",
        "20",
        "-o",
        "f.png",
        "-o",
        "f.tif",
    ];
    let one = tempfile::tempdir().unwrap();
    let two = tempfile::tempdir().unwrap();
    let mut args = common.to_vec();
    args.extend(["--threads", "1"]);
    generate(one.path(), &args);
    let mut args = common.to_vec();
    args.extend(["--threads", "2"]);
    generate(two.path(), &args);
    for name in ["f.png", "f.tif", "f.json"] {
        assert_same_bytes(&one.path().join(name), &two.path().join(name));
    }
}

#[test]
fn tiff_reads_back_bit_for_bit_equal_to_the_in_process_synthesis() {
    let flags = [
        ("method", "hybrid"),
        ("size", "96x64"),
        ("extent", "192x128"),
        ("seed", "11"),
        ("time", "2.5"),
        ("wind-dir", "-30"),
    ];
    let sets = ["blend.alpha.kind=radial"];
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec![];
    for (k, v) in &flags {
        args.push(format!("--{k}={v}"));
    }
    for s in &sets {
        args.push("--set".into());
        args.push(s.to_string());
    }
    args.extend(["-o".into(), "r.tif".into()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    generate(dir.path(), &args);

    let params = seasynth::commands::common::resolve_params(&field_args(&flags, &sets))
        .expect("the parameters resolve in-process");
    let want = seasynth::field::synthesize(&params).expect("synthesis");
    let (w, h, got) = tiff(&dir.path().join("r.tif"));
    assert_eq!((w, h), (96, 64), "TIFF size is nx×ny");
    assert_eq!(got.len(), want.grid.data.len(), "sample count");
    for (idx, (g, e)) in got.iter().zip(&want.grid.data).enumerate() {
        assert!(
            g.to_bits() == e.to_bits(),
            "sample {idx} (i={}, j={}): TIFF {g} vs synthesize {e}",
            idx % w,
            idx / w
        );
    }
}

#[test]
fn png_decoded_with_the_sidecar_mapping_is_within_one_step_of_the_tiff_heights() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--size", "96x64", "--extent", "192x128", "--seed", "5", "-o", "m.png", "-o", "m.tif",
        ],
    );
    let doc = json_file(&dir.path().join("m.json"));
    let (min, max) = (num(&doc, "/mapping/min_m"), num(&doc, "/mapping/max_m"));
    let step = (max - min) / 65535.0;
    assert!(step > 0.0, "a mapping of positive span: {min}..{max}");
    let recorded = num(&doc, "/mapping/step_m");
    assert!(
        (recorded - step).abs() <= 1e-12 * step,
        "step_m {recorded} is not (max_m − min_m)/65535 = {step}"
    );
    let (pw, ph, values) = png(&dir.path().join("m.png"));
    let (tw, th, heights) = tiff(&dir.path().join("m.tif"));
    assert_eq!((pw, ph), (tw, th), "PNG and TIFF sizes");
    assert!(
        values.contains(&0) && values.contains(&65535),
        "the field's min..max spans 0..65535"
    );
    for (idx, (&v, &h)) in values.iter().zip(&heights).enumerate() {
        let decoded = min + v as f64 * step;
        let err = (decoded - h as f64).abs();
        assert!(
            err <= step,
            "sample {idx} (i={}, j={}): PNG {v} decodes to {decoded} m, TIFF {h} m, \
             off by {err} m > one step {step} m",
            idx % pw,
            idx / pw
        );
    }
}

#[test]
fn height_range_sets_the_sidecar_mapping_and_clamps_heights_outside_it() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method",
            "perlin",
            "--set",
            "perlin.amplitude_m=5",
            "--size",
            "64",
            "--extent",
            "128",
            "--height-range",
            "-2:2",
            "-o",
            "c.png",
            "-o",
            "c.tif",
        ],
    );
    let doc = json_file(&dir.path().join("c.json"));
    assert_eq!(num(&doc, "/mapping/min_m"), -2.0, "mapping min: {doc:#}");
    assert_eq!(num(&doc, "/mapping/max_m"), 2.0, "mapping max: {doc:#}");
    let step = 4.0 / 65535.0;
    let (_, _, values) = png(&dir.path().join("c.png"));
    let (w, _, heights) = tiff(&dir.path().join("c.tif"));
    let above = heights.iter().filter(|&&h| h > 2.0).count();
    let below = heights.iter().filter(|&&h| h < -2.0).count();
    assert!(
        above > 0 && below > 0,
        "the test needs heights beyond both ends of -2:2 ({above} above, {below} below)"
    );
    for (idx, (&v, &h)) in values.iter().zip(&heights).enumerate() {
        let (i, j) = (idx % w, idx / w);
        if h as f64 >= 2.0 {
            assert_eq!(v, 65535, "({i},{j}): {h} m ≥ 2 m must clamp to 65535");
        } else if h as f64 <= -2.0 {
            assert_eq!(v, 0, "({i},{j}): {h} m ≤ −2 m must clamp to 0");
        } else {
            let err = (-2.0 + v as f64 * step - h as f64).abs();
            assert!(
                err <= step,
                "({i},{j}): PNG {v} is {err} m from {h} m, over one step"
            );
        }
    }
}

#[test]
fn sidecar_given_as_preset_regenerates_identical_png_and_tiff_bytes() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method",
            "hybrid",
            "--wind-dir",
            "30",
            "--seed",
            "7",
            "--time",
            "1.5",
            "--set",
            "blend.beta=matched",
            "--set",
            "perlin.octaves=4",
            "--set",
            "blend.alpha.kind=radial",
            "--size",
            "80x64",
            "--extent",
            "160x128",
            "-o",
            "a.png",
            "-o",
            "a.tif",
        ],
    );
    let a = json_file(&dir.path().join("a.json"));
    let p = &a["params"];
    assert_eq!(
        (
            &p["method"],
            &p["seed"],
            &p["wind"]["direction_deg"],
            &p["blend"]["beta"],
            &p["perlin"]["octaves"],
            &p["blend"]["alpha"]["kind"],
        ),
        (
            &Value::from("hybrid"),
            &Value::from(7),
            &Value::from(30.0),
            &Value::from("matched"),
            &Value::from(4),
            &Value::from("radial"),
        ),
        "the sidecar records the settings given: {p:#}"
    );
    generate(
        dir.path(),
        &["--preset", "a.json", "-o", "b.png", "-o", "b.tif"],
    );
    assert_same_bytes(&dir.path().join("a.png"), &dir.path().join("b.png"));
    assert_same_bytes(&dir.path().join("a.tif"), &dir.path().join("b.tif"));
    let b = json_file(&dir.path().join("b.json"));
    assert_eq!(a["params"], b["params"], "regenerated parameters");
}

#[test]
fn sidecar_parameters_read_back_equal_the_resolved_parameters_bit_for_bit() {
    // Decimals of 17 significant digits, as ryu writes many f64 values; serde_json's
    // default parser gets about one in six of them one ulp off.
    let flags = [
        ("size", "64"),
        ("extent", "128"),
        ("wind-speed", "39.430133835633676"),
        ("wind-dir", "0.39430132508277893"),
        ("time", "0.17546218633651733"),
    ];
    let dir = tempfile::tempdir().unwrap();
    let args: Vec<String> = flags
        .iter()
        .map(|(k, v)| format!("--{k}={v}"))
        .chain(["-o".into(), "a.tif".into()])
        .collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    generate(dir.path(), &args);
    let want =
        seasynth::commands::common::resolve_params(&field_args(&flags, &[])).expect("resolves");
    let sidecar = dir.path().join("a.json");
    let got = seasynth::config::presets::load(sidecar.to_str().unwrap())
        .expect("the sidecar loads as a preset");
    assert_eq!(
        (
            got.wind.speed_mps.to_bits(),
            got.wind.direction_deg.to_bits(),
            got.time_s.to_bits()
        ),
        (
            want.wind.speed_mps.to_bits(),
            want.wind.direction_deg.to_bits(),
            want.time_s.to_bits()
        ),
        "sidecar parameters {:?} {:?} {:?} vs resolved {:?} {:?} {:?}",
        got.wind.speed_mps,
        got.wind.direction_deg,
        got.time_s,
        want.wind.speed_mps,
        want.wind.direction_deg,
        want.time_s
    );
    assert_eq!(got, want, "every sidecar parameter");
}

#[test]
fn fft_method_equals_hybrid_with_alpha_constant_one() {
    let dir = tempfile::tempdir().unwrap();
    let grid = ["--size", "96x64", "--extent", "192x128", "--seed", "3"];
    let mut args = grid.to_vec();
    args.extend(["--method", "fft", "-o", "fft.tif"]);
    generate(dir.path(), &args);
    let mut args = grid.to_vec();
    args.extend([
        "--method",
        "hybrid",
        "--set",
        "blend.alpha.kind=constant",
        "--set",
        "blend.alpha.value=1",
        "-o",
        "hyb.tif",
    ]);
    generate(dir.path(), &args);
    let (w, _, fft) = tiff(&dir.path().join("fft.tif"));
    let (_, _, hyb) = tiff(&dir.path().join("hyb.tif"));
    assert_eq!(fft.len(), hyb.len(), "sample count");
    assert!(fft.iter().any(|&v| v != 0.0), "the FFT field is not flat");
    for (idx, (f, h)) in fft.iter().zip(&hyb).enumerate() {
        assert!(
            f == h,
            "({},{}): --method fft {f} vs hybrid with α = 1 {h}",
            idx % w,
            idx / w
        );
    }
}

#[test]
fn hybrid_with_alpha_zero_is_beta_times_the_perlin_method_field() {
    let dir = tempfile::tempdir().unwrap();
    let grid = ["--size", "96x64", "--extent", "192x128", "--seed", "3"];
    let mut args = grid.to_vec();
    args.extend(["--method", "perlin", "-o", "perlin.tif"]);
    generate(dir.path(), &args);
    let mut args = grid.to_vec();
    args.extend([
        "--method",
        "hybrid",
        "--set",
        "blend.alpha.kind=constant",
        "--set",
        "blend.alpha.value=0",
        "--set",
        "blend.beta=0.5",
        "-o",
        "hyb.tif",
    ]);
    generate(dir.path(), &args);
    let beta = num(
        &json_file(&dir.path().join("hyb.json")),
        "/synthesis/beta_m",
    );
    assert_eq!(beta, 0.5, "the sidecar's β");
    let (w, _, perlin) = tiff(&dir.path().join("perlin.tif"));
    let (_, _, hyb) = tiff(&dir.path().join("hyb.tif"));
    assert_eq!(perlin.len(), hyb.len(), "sample count");
    assert!(perlin.iter().any(|&v| v != 0.0), "the Perlin field is flat");
    for (idx, (&p, &h)) in perlin.iter().zip(&hyb).enumerate() {
        let want = 0.5 * p as f64;
        assert!(
            (h as f64 - want).abs() <= REL_TOL * want.abs(),
            "({},{}): hybrid {h} vs 0.5 × perlin = {want}",
            idx % w,
            idx / w
        );
    }
}

#[test]
fn perlin_method_field_lies_within_plus_minus_its_amplitude() {
    let dir = tempfile::tempdir().unwrap();
    for (amp, file) in [("1", "p1.tif"), ("2.5", "p25.tif")] {
        generate(
            dir.path(),
            &[
                "--method",
                "perlin",
                "--set",
                &format!("perlin.amplitude_m={amp}"),
                "--size",
                "96x64",
                "--extent",
                "192x128",
                "--seed",
                "9",
                "-o",
                file,
            ],
        );
        let a: f32 = amp.parse().unwrap();
        let (w, _, h) = tiff(&dir.path().join(file));
        for (idx, &v) in h.iter().enumerate() {
            assert!(
                v.abs() <= a,
                "amplitude {a} m: ({},{}) is {v} m",
                idx % w,
                idx / w
            );
        }
        let peak = h.iter().fold(0.0f32, |m, v| m.max(v.abs()));
        assert!(
            peak > 0.25 * a,
            "amplitude {a} m: the field barely moves (peak {peak} m)"
        );
    }
}

#[test]
fn wind_toward_90_degrees_turns_the_steep_direction_from_x_to_y() {
    // Phillips' |k̂·ŵ|² spreading puts the energy on wavevectors along the wind, so with
    // wind toward +x the crests run along y and heights change faster along x. For
    // cos² spreading the expected ratio of the x to the y slope variance is 3.
    let dir = tempfile::tempdir().unwrap();
    let mut ratio = Vec::new();
    for (deg, file) in [("0", "w0.tif"), ("90", "w90.tif")] {
        generate(
            dir.path(),
            &[
                "--method",
                "fft",
                "--size",
                "64",
                "--extent",
                "128",
                "--seed",
                "4",
                "--wind-dir",
                deg,
                "-o",
                file,
            ],
        );
        let (nx, ny, h) = tiff(&dir.path().join(file));
        let (vx, vy) = slope_variances(nx, ny, &h);
        assert!(vx > 0.0 && vy > 0.0, "{deg}°: a flat field");
        ratio.push(vx / vy);
    }
    let (r0, r90) = (ratio[0], ratio[1]);
    assert!(
        r0 > 1.5,
        "wind toward +x: x/y slope variance ratio {r0} should be well above 1"
    );
    assert!(
        r90 < 1.0 / 1.5,
        "wind toward +y: x/y slope variance ratio {r90} should be well below 1"
    );
    assert!(
        (0.5..2.0).contains(&(r0 * r90)),
        "90° should be 0° transposed: ratios {r0} and {r90} are not near reciprocal"
    );
}

#[test]
fn negative_wind_speed_is_rejected_naming_the_value() {
    assert_rejected(
        &["--wind-speed", "-3"],
        &["--wind-speed", "> 0 and ≤ 100 m/s", "(got -3)"],
    );
}

#[test]
fn zero_size_is_rejected_naming_the_value() {
    assert_rejected(&["--size", "0"], &["--size", "(got 0)"]);
}

#[test]
fn unknown_output_extension_is_rejected_naming_the_extension() {
    assert_rejected(
        &["-o", "x.bmp"],
        &["x.bmp", "unknown extension `.bmp`", ".png"],
    );
}

#[test]
fn unwritable_output_folder_is_rejected_naming_the_folder() {
    // A missing folder is created (tests/cli.rs); one under a file that is not a folder
    // cannot be, even for root.
    assert_rejected(
        &["--size", "64", "-o", "/dev/null/sub/x.png"],
        &[
            "output /dev/null/sub/x.png",
            "/dev/null is a file, not a folder",
        ],
    );
}

#[test]
fn misspelled_set_key_is_rejected_naming_the_key() {
    assert_rejected(
        &["--set", "wind.sped_mps=3"],
        &["--set wind.sped_mps=3", "unknown field `sped_mps`"],
    );
}

#[test]
fn unknown_method_is_rejected_naming_it_and_the_known_ones() {
    assert_rejected(
        &["--method", "spline"],
        &["--method spline", "`spline`", "hybrid"],
    );
}

#[test]
fn reversed_height_range_is_rejected_naming_the_range() {
    assert_rejected(
        &["--height-range", "2:1"],
        &["--height-range", "MIN < MAX", "(got 2:1)"],
    );
}

#[test]
fn perlin_persistence_above_one_is_rejected_naming_the_key() {
    assert_rejected(
        &["--set", "perlin.persistence=1.5"],
        &["perlin.persistence", "< 1", "(got 1.5)"],
    );
}

#[test]
fn negative_extent_given_with_an_equals_sign_is_rejected_naming_the_value() {
    assert_rejected(&["--extent=-5"], &["--extent", "> 0 m", "(got -5)"]);
}

#[test]
fn negative_extent_is_rejected_naming_the_value() {
    assert_rejected(&["--extent", "-5"], &["--extent", "> 0 m", "(got -5)"]);
}

#[test]
fn missing_alpha_image_is_rejected_naming_the_file() {
    assert_rejected(
        &[
            "--size",
            "64",
            "--set",
            "blend.alpha.kind=image",
            "--set",
            "blend.alpha.path=missing.png",
        ],
        &["blend.alpha.path", "missing.png"],
    );
}

#[test]
fn zero_threads_is_rejected() {
    assert_rejected(&["--threads", "0"], &["--threads", "(got 0)"]);
}

#[test]
fn the_same_output_given_twice_is_rejected() {
    assert_rejected(
        &["--size", "64", "-o", "a.png", "-o", "a.png"],
        &["a.png", "given twice"],
    );
}

#[test]
fn alpha_image_selects_the_fft_field_where_white_and_beta_times_perlin_where_black() {
    let (nx, ny) = (96usize, 64usize);
    // White (α = 1) on the left half of the rows j ≥ ny/4 and on the right half of the
    // rows above: half the samples, and a flip of either axis would move them.
    let white = |i: usize, j: usize| (i < nx / 2) != (j < ny / 4);
    let dir = tempfile::tempdir().unwrap();
    let img = dir.path().join("alpha.png");
    {
        let file = std::fs::File::create(&img).unwrap();
        let mut enc = png::Encoder::new(std::io::BufWriter::new(file), nx as u32, ny as u32);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().unwrap();
        let pixels: Vec<u8> = (0..nx * ny)
            .map(|k| if white(k % nx, k / nx) { 255 } else { 0 })
            .collect();
        w.write_image_data(&pixels).unwrap();
        w.finish().unwrap();
    }
    let grid = ["--size", "96x64", "--extent", "192x128", "--seed", "13"];
    let mut args = grid.to_vec();
    args.extend([
        "--method",
        "hybrid",
        "--set",
        "blend.alpha.kind=image",
        "--set",
        "blend.alpha.path=alpha.png",
        "-o",
        "hyb.tif",
    ]);
    generate(dir.path(), &args);
    let mut args = grid.to_vec();
    args.extend(["--method", "fft", "-o", "fft.tif"]);
    generate(dir.path(), &args);
    let mut args = grid.to_vec();
    args.extend(["--method", "perlin", "-o", "perlin.tif"]);
    generate(dir.path(), &args);

    let beta = num(
        &json_file(&dir.path().join("hyb.json")),
        "/synthesis/beta_m",
    );
    assert!(beta > 0.0, "β from the sidecar: {beta}");
    let (w, h, hyb) = tiff(&dir.path().join("hyb.tif"));
    assert_eq!((w, h), (nx, ny), "hybrid TIFF size");
    let (_, _, fft) = tiff(&dir.path().join("fft.tif"));
    let (_, _, perlin) = tiff(&dir.path().join("perlin.tif"));
    for j in 0..ny {
        for i in 0..nx {
            let k = j * nx + i;
            if white(i, j) {
                assert!(
                    hyb[k] == fft[k],
                    "white ({i},{j}): hybrid {} vs FFT {}",
                    hyb[k],
                    fft[k]
                );
            } else {
                let want = beta * perlin[k] as f64;
                assert!(
                    (hyb[k] as f64 - want).abs() <= REL_TOL * want.abs(),
                    "black ({i},{j}): hybrid {} vs β·perlin = {beta} × {} = {want}",
                    hyb[k],
                    perlin[k]
                );
            }
        }
    }
}

#[test]
fn png_and_tiff_of_one_stem_share_one_sidecar_listing_both() {
    let dir = tempfile::tempdir().unwrap();
    generate(dir.path(), &["--size", "64", "-o", "a.png", "-o", "a.tif"]);
    assert_eq!(
        names_in(dir.path()),
        ["a.json", "a.png", "a.tif"],
        "two outputs and one sidecar"
    );
    let doc = json_file(&dir.path().join("a.json"));
    let files = doc["files"]
        .as_array()
        .unwrap_or_else(|| panic!("sidecar `files` is not a list: {doc:#}"));
    let mut listed: Vec<(String, String)> = files
        .iter()
        .map(|f| {
            (
                f["file"].as_str().unwrap_or_default().to_string(),
                f["format"].as_str().unwrap_or_default().to_string(),
            )
        })
        .collect();
    listed.sort();
    assert_eq!(
        listed,
        [
            ("a.png".to_string(), "png16".to_string()),
            ("a.tif".to_string(), "tiff32".to_string())
        ],
        "files listed in a.json"
    );
    assert!(
        doc["mapping"].is_object(),
        "a PNG output records its mapping"
    );
}
