//! Images read through `image`: height maps in every format for `analyze` and `render
//! --from` (float samples in meters, integer ones through --height-range or the 16-bit
//! PNG's text chunk, spacing from --extent), α maps in every format with their aspect
//! ratio checked, and previews as JPEG or WebP.

mod common;

use std::path::Path;

use common::{analyze_json, json_file, num, run_ok, run_rejected};
use image::{ImageBuffer, Luma, Rgb};
use serde_json::Value;

const W: u32 = 40;
const H: u32 = 20;

/// An 8-bit ramp along x with a step along y: values 0 … 255.
fn gray8(i: u32, j: u32) -> u8 {
    ((i * 255) / (W - 1)).saturating_sub(if j < H / 2 { 0 } else { 3 }) as u8
}

fn analyze_with(dir: &Path, file: &str, extra: &[&str]) -> Value {
    let mut args = vec!["analyze", file, "--json"];
    args.extend(extra);
    serde_json::from_str(&run_ok(dir, &args)).expect("JSON")
}

/// min, max and mean of `values` mapped linearly from [0, 1] to [lo, hi].
fn expected(values: &[f64], lo: f64, hi: f64) -> (f64, f64, f64) {
    let h: Vec<f64> = values.iter().map(|v| lo + v * (hi - lo)).collect();
    let min = h.iter().cloned().fold(f64::MAX, f64::min);
    let max = h.iter().cloned().fold(f64::MIN, f64::max);
    (min, max, h.iter().sum::<f64>() / h.len() as f64)
}

#[test]
fn integer_images_of_every_format_read_through_the_height_range_and_the_extent() {
    let dir = tempfile::tempdir().unwrap();
    let l8 = ImageBuffer::from_fn(W, H, |i, j| Luma([gray8(i, j)]));
    let l16 = ImageBuffer::from_fn(W, H, |i, j| Luma([gray8(i, j) as u16 * 257]));
    let rgb = ImageBuffer::from_fn(W, H, |i, j| {
        let v = gray8(i, j);
        Rgb([v, v, v])
    });
    l8.save(dir.path().join("g8.png")).unwrap();
    l16.save(dir.path().join("g16.png")).unwrap();
    l8.save(dir.path().join("g8.tif")).unwrap();
    l16.save(dir.path().join("g16.tif")).unwrap();
    rgb.save(dir.path().join("rgb.bmp")).unwrap();
    rgb.save(dir.path().join("rgb.webp")).unwrap();
    l8.save(dir.path().join("g8.jpg")).unwrap();
    let fractions: Vec<f64> = (0..H)
        .flat_map(|j| (0..W).map(move |i| gray8(i, j) as f64 / 255.0))
        .collect();
    let (lo, hi) = (-2.0, 3.0);
    let (min, max, mean) = expected(&fractions, lo, hi);
    for (file, format, tol) in [
        ("g8.png", "png", 1e-5),
        ("g16.png", "png", 1e-5),
        ("g8.tif", "tiff", 1e-5),
        ("g16.tif", "tiff", 1e-5),
        ("rgb.bmp", "bmp", 1e-5),
        ("rgb.webp", "webp", 1e-5),
        // JPEG is lossy: a smooth ramp comes back within a few levels of 255.
        ("g8.jpg", "jpeg", 0.1),
    ] {
        let doc = analyze_with(
            dir.path(),
            file,
            &["--height-range", "-2:3", "--extent", "80x10"],
        );
        assert_eq!(doc["format"], format, "{file}");
        assert_eq!(doc["spacing_source"], "--extent", "{file}");
        assert!(
            (num(&doc, "/dx_m") - 2.0).abs() < 1e-12,
            "{file}: 80 m / 40"
        );
        assert!(
            (num(&doc, "/dy_m") - 0.5).abs() < 1e-12,
            "{file}: 10 m / 20"
        );
        for (key, want) in [("/min_m", min), ("/max_m", max), ("/mean_m", mean)] {
            let got = num(&doc, key);
            assert!((got - want).abs() < tol, "{file} {key}: {got} vs {want}");
        }
        let bits = if file.contains("16") { 65535.0 } else { 255.0 };
        let step = num(&doc, "/quantization_step_m");
        assert!((step - 5.0 / bits).abs() < 1e-12, "{file}: step {step}");
        // Without the range, an integer image has no heights.
        run_rejected(
            dir.path(),
            &["analyze", file],
            &[
                file,
                "integer samples with no height mapping",
                "--height-range MIN:MAX",
            ],
        );
    }
}

#[test]
fn float_images_are_heights_in_meters() {
    let dir = tempfile::tempdir().unwrap();
    let h = |i: u32, j: u32| (i as f32 * 0.3).sin() * 1.5 + j as f32 * 0.01 - 0.2;
    let exr = ImageBuffer::from_fn(W, H, |i, j| Rgb([h(i, j); 3]));
    image::DynamicImage::ImageRgb32F(exr)
        .save(dir.path().join("h.exr"))
        .unwrap();
    let doc = analyze_json(dir.path(), "h.exr");
    let values: Vec<f64> = (0..H)
        .flat_map(|j| (0..W).map(move |i| h(i, j) as f64))
        .collect();
    let (min, max, mean) = expected(&values, 0.0, 1.0);
    assert_eq!(doc["format"], "exr");
    assert_eq!(doc["spacing_source"], "assumed 1 m");
    assert!(doc.get("quantization_step_m").is_none());
    for (key, want) in [("/min_m", min), ("/max_m", max), ("/mean_m", mean)] {
        // Luma of three equal channels: the value, to the rounding of the weights.
        let got = num(&doc, key);
        assert!((got - want).abs() < 1e-5, "{key}: {got} vs {want}");
    }
}

#[test]
fn a_seasynth_png_without_its_sidecar_reads_through_its_text_chunk() {
    let dir = tempfile::tempdir().unwrap();
    run_ok(
        dir.path(),
        &[
            "generate", "--size", "32", "--method", "fft", "-o", "s.png", "-o", "s.tif", "-q",
        ],
    );
    let with = analyze_json(dir.path(), "s.png");
    std::fs::remove_file(dir.path().join("s.json")).unwrap();
    let without = analyze_json(dir.path(), "s.png");
    assert_eq!(without["format"], "png");
    let step = num(&with, "/quantization_step_m");
    assert!((num(&without, "/quantization_step_m") - step).abs() < 1e-12 * step.max(1.0));
    for key in ["/min_m", "/max_m", "/mean_m", "/std_m"] {
        let (a, b) = (num(&with, key), num(&without, key));
        assert!((a - b).abs() < 1e-6, "{key}: sidecar {a}, text chunk {b}");
    }
    // --height-range wins over the chunk.
    let ranged = analyze_with(dir.path(), "s.png", &["--height-range", "0:65535"]);
    assert!((num(&ranged, "/quantization_step_m") - 1.0).abs() < 1e-12);
}

#[test]
fn alpha_maps_read_any_format_and_refuse_another_aspect_ratio_unless_stretched() {
    let dir = tempfile::tempdir().unwrap();
    // White on the left half: the hybrid is the FFT sea there.
    let (nx, ny) = (64u32, 32u32);
    let white = |i: u32| i < nx / 2;
    ImageBuffer::from_fn(nx, ny, |i, _| Luma([if white(i) { 255u8 } else { 0 }]))
        .save(dir.path().join("a.png"))
        .unwrap();
    ImageBuffer::from_fn(nx, ny, |i, _| {
        let v = if white(i) { 255u8 } else { 0 };
        Rgb([v, v, v])
    })
    .save(dir.path().join("a.bmp"))
    .unwrap();
    let exr = ImageBuffer::from_fn(nx, ny, |i, _| Rgb([if white(i) { 1.0f32 } else { 0.0 }; 3]));
    image::DynamicImage::ImageRgb32F(exr)
        .save(dir.path().join("a.exr"))
        .unwrap();
    let sea = ["--size", "64x32", "--extent", "128x64", "--seed", "3", "-q"];
    let hybrid = |alpha: &str, out: &str, extra: &[&str]| {
        let set = format!("blend.alpha.path={alpha}");
        let mut args = vec!["generate"];
        args.extend(sea);
        args.extend([
            "--method",
            "hybrid",
            "--set",
            "blend.alpha.kind=image",
            "--set",
        ]);
        args.push(&set);
        args.extend(extra);
        args.extend(["-o", out]);
        run_ok(dir.path(), &args);
    };
    hybrid("a.png", "png.tif", &[]);
    hybrid("a.bmp", "bmp.tif", &[]);
    hybrid("a.exr", "exr.tif", &[]);
    let read = |f: &str| {
        seasynth::export::tiff32::read(&dir.path().join(f))
            .unwrap()
            .2
    };
    let reference = read("png.tif");
    for f in ["bmp.tif", "exr.tif"] {
        let got = read(f);
        let worst = got
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f32, f32::max);
        assert!(worst < 1e-5, "{f}: differs from the PNG α by {worst}");
    }
    // A 2:1 grid and a 1:1 image: refused naming both, or stretched when asked.
    ImageBuffer::from_fn(32, 32, |i, _| Luma([if i < 16 { 255u8 } else { 0 }]))
        .save(dir.path().join("square.png"))
        .unwrap();
    let mut args = vec!["generate"];
    args.extend(sea);
    args.extend([
        "--set",
        "blend.alpha.kind=image",
        "--set",
        "blend.alpha.path=square.png",
        "-o",
        "x.tif",
    ]);
    run_rejected(
        dir.path(),
        &args,
        &[
            "blend.alpha.path",
            "32×32",
            "128 m × 64 m",
            "fit = \"stretch\"",
        ],
    );
    hybrid(
        "square.png",
        "stretched.tif",
        &["--set", "blend.alpha.fit=stretch"],
    );
    let side = json_file(&dir.path().join("stretched.json"));
    assert_eq!(side["params"]["blend"]["alpha"]["fit"], "stretch");
    // Stretched: the half-white square is the half-white 64×32 image away from the edge
    // between them (columns 30 … 33 interpolate).
    let stretched = read("stretched.tif");
    for (k, (a, b)) in stretched.iter().zip(&reference).enumerate() {
        let i = k % nx as usize;
        if !(30..34).contains(&i) {
            assert_eq!(a, b, "column {i}, row {}", k / nx as usize);
        }
    }
}

#[test]
fn render_reads_any_image_and_writes_jpeg_and_webp_previews() {
    let dir = tempfile::tempdir().unwrap();
    ImageBuffer::from_fn(W, H, |i, j| Luma([gray8(i, j)]))
        .save(dir.path().join("g.png"))
        .unwrap();
    for out in ["r.jpg", "r.webp", "r.png"] {
        run_ok(
            dir.path(),
            &[
                "render",
                "--from",
                "g.png",
                "--height-range",
                "0:4",
                "--extent",
                "80x40",
                "--image",
                "48x32",
                "--spp",
                "1",
                "-q",
                "-o",
                out,
            ],
        );
        let img = image::open(dir.path().join(out)).unwrap();
        assert_eq!((img.width(), img.height()), (48, 32), "{out}");
    }
    // Lossless WebP holds the PNG's pixels.
    let png = image::open(dir.path().join("r.png")).unwrap().to_rgb8();
    let webp = image::open(dir.path().join("r.webp")).unwrap().to_rgb8();
    assert!(png == webp, "lossless WebP");
    run_rejected(
        dir.path(),
        &["render", "--from", "g.png", "-q", "-o", "r2.png"],
        &["--height-range MIN:MAX"],
    );
    run_ok(
        dir.path(),
        &[
            "generate",
            "--size",
            "32",
            "--method",
            "fft",
            "-q",
            "-o",
            "s.preview.jpg",
        ],
    );
    let img = image::open(dir.path().join("s.preview.jpg")).unwrap();
    assert!(img.width() > 0);
}
