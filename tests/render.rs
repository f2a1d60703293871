//! `seasynth render`: the preview renderer, run as a binary.

mod common;

use std::path::Path;

use common::{names_in, read, run_exit2, run_ok, run_rejected, seasynth};

/// A small periodic sea: quick to synthesize and to render.
const FIELD: &[&str] = &["--method", "fft", "--size", "64", "--extent", "64"];

fn args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec!["render"];
    v.extend_from_slice(FIELD);
    v.extend_from_slice(extra);
    v
}

/// Width, height, color type, bit depth and pixels of a PNG.
fn decode(path: &Path) -> (u32, u32, png::ColorType, png::BitDepth, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(read(path)));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("a size")];
    let info = reader.next_frame(&mut buf).expect("one frame");
    buf.truncate(info.buffer_size());
    (
        info.width,
        info.height,
        info.color_type,
        info.bit_depth,
        buf,
    )
}

#[test]
fn render_writes_an_rgb_png_of_the_requested_size_with_sky_above_sea() {
    let dir = tempfile::tempdir().unwrap();
    run_ok(
        dir.path(),
        &args(&["--image", "96x54", "--spp", "1", "-o", "a.png"]),
    );
    let (w, h, color, depth, px) = decode(&dir.path().join("a.png"));
    assert_eq!((w, h), (96, 54));
    assert_eq!((color, depth), (png::ColorType::Rgb, png::BitDepth::Eight));
    // The grazing view: sky (bluish, bright) at the top, sea (green exceeds red) at the bottom.
    let at = |x: u32, y: u32| {
        let k = 3 * (y * w + x) as usize;
        [px[k] as i32, px[k + 1] as i32, px[k + 2] as i32]
    };
    let sky = at(48, 0);
    let sea = at(48, 53);
    assert!(
        sky[2] > sky[0] && sky[2] > 150,
        "top pixel {sky:?} is not sky"
    );
    assert!(sea[1] > sea[0] + 20, "bottom pixel {sea:?} is not sea");
    assert_eq!(
        names_in(dir.path()),
        vec!["a.png"],
        "no sidecar, no temporary file"
    );
}

#[test]
fn renders_are_identical_bytes_with_one_and_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    for (threads, name) in [("1", "one.png"), ("2", "two.png")] {
        run_ok(
            dir.path(),
            &args(&["--image", "80x45", "--threads", threads, "-q", "-o", name]),
        );
    }
    let (one, two) = (
        read(&dir.path().join("one.png")),
        read(&dir.path().join("two.png")),
    );
    assert!(one == two, "1 and 2 threads give different files");
}

#[test]
fn a_field_read_from_a_tif_renders_like_the_same_field_synthesized() {
    let dir = tempfile::tempdir().unwrap();
    let mut generate = vec!["generate"];
    generate.extend_from_slice(FIELD);
    generate.extend_from_slice(&["--wind-dir", "30", "-q", "-o", "f.tif"]);
    run_ok(dir.path(), &generate);
    // The sidecar gives the spacing, the wind (so the view) and the periodicity.
    run_ok(
        dir.path(),
        &[
            "render", "--from", "f.tif", "--image", "64x36", "-q", "-o", "from.png",
        ],
    );
    run_ok(
        dir.path(),
        &args(&[
            "--wind-dir",
            "30",
            "--image",
            "64x36",
            "-q",
            "-o",
            "direct.png",
        ]),
    );
    assert!(
        read(&dir.path().join("from.png")) == read(&dir.path().join("direct.png")),
        "--from f.tif and the same flags give different images"
    );
}

#[test]
fn the_camera_and_view_flags_change_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let base = ["--image", "48x27", "--spp", "1", "-q"];
    let cases: [&[&str]; 6] = [
        &[],
        &["--view", "aerial"],
        &["--view", "top"],
        &["--camera", "10,20,8", "--look-at", "40,20,0"],
        &[
            "--sun",
            "180,40",
            "--haze",
            "0",
            "--reflection",
            "pseudo:0.3",
        ],
        &[
            "--no-repeat",
            "--fov",
            "90",
            "--yaw",
            "45",
            "--pitch",
            "-20",
        ],
    ];
    let mut images = Vec::new();
    for (k, extra) in cases.iter().enumerate() {
        let name = format!("v{k}.png");
        let mut a = args(&base);
        a.extend_from_slice(extra);
        a.extend_from_slice(&["-o", &name]);
        run_ok(dir.path(), &a);
        images.push(decode(&dir.path().join(&name)).4);
    }
    for i in 0..images.len() {
        for j in i + 1..images.len() {
            assert!(
                images[i] != images[j],
                "cases {i} and {j} give the same image"
            );
        }
    }
}

#[test]
fn progress_and_summary_go_to_stderr_unless_quiet() {
    let dir = tempfile::tempdir().unwrap();
    let out = seasynth()
        .current_dir(dir.path())
        .args(args(&["--image", "32x18", "-o", "a.png"]))
        .output()
        .unwrap();
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("rays per pixel") && stderr.contains("wrote a.png"),
        "{stderr}"
    );
    assert!(out.stdout.is_empty());
    let quiet = seasynth()
        .current_dir(dir.path())
        .args(args(&["--image", "32x18", "-q", "-o", "b.png"]))
        .output()
        .unwrap();
    assert!(quiet.status.success() && quiet.stderr.is_empty() && quiet.stdout.is_empty());
}

#[test]
fn bad_camera_and_image_parameters_are_one_line_errors_with_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[(&[&str], &[&str])] = &[
        (&["--fov", "0"], &["--fov", "> 0° and < 180°", "got 0"]),
        (&["--fov", "180"], &["--fov", "got 180"]),
        (&["--fov", "-10"], &["--fov", "got -10"]),
        (&["--fov", "NaN"], &["--fov", "got NaN"]),
        (&["--image", "0x0"], &["--image", "WxH", "got 0x0"]),
        (&["--image", "wide"], &["--image", "got wide"]),
        (&["--spp", "0"], &["--spp", "got 0"]),
        (&["--pitch", "100"], &["--pitch", "-90° to 90°", "got 100"]),
        (&["--yaw", "inf"], &["--yaw", "got inf"]),
        (&["--camera", "1,2"], &["--camera", "X,Y,Z", "got 1,2"]),
        (&["--camera", "1,nan,3"], &["--camera", "got 1,nan,3"]),
        (
            &["--camera-height", "-40"],
            &["--camera", "above the sea surface", "got z = "],
        ),
        (
            &["--view", "sideways"],
            &["--view", "grazing, aerial, top", "got sideways"],
        ),
        (
            &["--look-at", "1,2,3", "--yaw", "10"],
            &["--look-at", "without --yaw", "got 1,2,3"],
        ),
        (
            &["--camera", "5,5,9", "--look-at", "5,5,9"],
            &["--look-at", "other than"],
        ),
        (&["--sun", "10,95"], &["--sun", "got 10,95"]),
        (&["--haze", "-1"], &["--haze", "got -1"]),
        (&["--reflection", "mirror"], &["--reflection", "got mirror"]),
        (&["--from", "x.tif"], &["--from", "without field flags"]),
        (&["--wind-speed", "-3"], &["--wind-speed", "got -3"]),
    ];
    for (extra, fragments) in cases {
        let mut a = args(&["-o", "bad.png"]);
        if !extra.contains(&"--image") {
            a.extend_from_slice(&["--image", "16x9"]);
        }
        a.extend_from_slice(extra);
        run_rejected(dir.path(), &a, fragments);
    }
    // A name that is not a .png, .jpg or .webp, and a missing height map.
    run_rejected(dir.path(), &args(&["-o", "bad.gif"]), &["bad.gif", ".png"]);
    run_rejected(
        dir.path(),
        &["render", "--from", "missing.tif", "-o", "bad.png"],
        &["missing.tif"],
    );
    assert!(
        names_in(dir.path()).is_empty(),
        "left {:?}",
        names_in(dir.path())
    );
    // -o is required.
    run_exit2(dir.path(), &args(&[]));
}
