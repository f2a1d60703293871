use super::*;
use crate::grid::GridSpec;

fn flat(n: usize, extent: f64) -> Grid {
    Grid::zeros(GridSpec::new(n, n, extent, extent))
}

fn level_camera(z: f64, pitch_deg: f64) -> Camera {
    Camera {
        position_m: [10.0, 20.0, z],
        yaw_rad: 0.4,
        pitch_rad: pitch_deg.to_radians(),
        fov_x_rad: 60f64.to_radians(),
    }
}

/// Options without sun, spray or haze, so the sea is the height color and the sky.
fn plain(camera: Camera, w: u32, h: u32) -> RenderOptions {
    RenderOptions {
        width: w,
        height: h,
        lighting: Lighting {
            sun_dir: shade::sun_direction(0.0, -0.5),
            haze_distance_m: f64::INFINITY,
            ..Lighting::default()
        },
        ..RenderOptions::new(camera)
    }
}

/// First row whose pixel at column `x` sees the sea.
fn horizon_row(img: &RgbImage, x: u32) -> u32 {
    (0..img.height)
        .find(|&y| img.distance_m[(y * img.width + x) as usize].is_finite())
        .expect("some row sees the sea")
}

#[test]
fn a_flat_sea_shows_the_horizon_where_geometry_says_and_reflects_the_sky() {
    const W: u32 = 160;
    const H: u32 = 90;
    // The horizon of an infinite plane seen level: the image's center row, ± 1 px.
    const HORIZON_TOL_PX: i64 = 1;
    // 8-bit sRGB steps between the pixel and the color computed at its center.
    const COLOR_TOL: i32 = 2;
    for (periodic, repeat) in [(true, None), (false, None), (true, Some(false))] {
        let field = flat(32, 32.0);
        for pitch in [0.0, -10.0] {
            let cam = level_camera(3.0, pitch);
            let mut opts = plain(cam, W, H);
            opts.repeat = repeat;
            let img = render(&field, None, periodic, &opts).unwrap();
            let proj = Projection::new(&cam, W, H);
            // Pitched down by p, the horizon rises by focal·tan(p) pixels.
            let expected = H as f64 / 2.0 - proj.focal_px() * (-pitch.to_radians()).tan();
            let got = horizon_row(&img, W / 2) as i64;
            assert!(
                (got - expected.round() as i64).abs() <= HORIZON_TOL_PX,
                "periodic {periodic}, repeat {repeat:?}, pitch {pitch}: horizon at row {got}, expected {expected}"
            );
            // Below it: the Fresnel-weighted mix of the middle height color and the sky
            // in the mirror direction.
            let l = &opts.lighting;
            for y in [got as u32 + 3, (got as u32 + H) / 2, H - 1] {
                for x in [0, W / 3, W - 1] {
                    let d = proj.direction(x as f64 + 0.5, y as f64 + 0.5);
                    let cos_v = -d[2];
                    let f0 = ((1.33f64 - 1.0) / (1.33 + 1.0)).powi(2);
                    let fresnel = f0 + (1.0 - f0) * (1.0 - cos_v).powi(5);
                    let water = [0, 1, 2].map(|k| 0.5 * (l.deep_color[k] + l.crest_color[k]));
                    let sky = l.sky([d[0], d[1], -d[2]]);
                    let want = [0, 1, 2].map(|k| {
                        shade::encode_srgb8((1.0 - fresnel) * water[k] + fresnel * sky[k])
                    });
                    let px = img.pixel(x, y);
                    for k in 0..3 {
                        assert!(
                            (px[k] as i32 - want[k] as i32).abs() <= COLOR_TOL,
                            "pixel ({x}, {y}): {px:?}, expected {want:?}"
                        );
                    }
                }
            }
            // Above it: the sky.
            let y = (got - 5).max(0) as u32;
            let d = proj.direction(W as f64 / 2.0 + 0.5, y as f64 + 0.5);
            let sky = l.sky(d).map(shade::encode_srgb8);
            let px = img.pixel(W / 2, y);
            assert!((0..3).all(|k| (px[k] as i32 - sky[k] as i32).abs() <= COLOR_TOL));
        }
    }
}

#[test]
fn images_do_not_depend_on_the_thread_count() {
    let spec = GridSpec::new(64, 64, 64.0, 64.0);
    let field = Grid::new(
        spec,
        (0..64 * 64)
            .map(|k| ((k % 64) as f32 * 0.3).sin() + ((k / 64) as f32 * 0.2).cos())
            .collect(),
    );
    let cam = Camera {
        position_m: [0.0, 10.0, 6.0],
        yaw_rad: 0.2,
        pitch_rad: -0.15,
        fov_x_rad: 1.0,
    };
    let opts = RenderOptions {
        width: 96,
        height: 54,
        ..RenderOptions::new(cam)
    };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render(&field, None, true, &opts).unwrap())
    };
    let one = run(1);
    let two = run(2);
    assert!(one == two, "1 and 2 threads give different images");
    // Not a blank image: sea and sky both present.
    assert!(one.distance_m.iter().any(|d| d.is_finite()));
    assert!(one.distance_m.iter().any(|d| d.is_infinite()));
}

#[test]
fn a_camera_under_the_surface_is_refused() {
    let spec = GridSpec::new(16, 16, 16.0, 16.0);
    let field = Grid::new(spec, vec![2.0; 256]);
    let opts = RenderOptions::new(level_camera(1.0, 0.0));
    let e = render(&field, None, true, &opts).unwrap_err();
    assert!(e.is_usage(), "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains("--camera") && msg.contains("z = 2.000 m"),
        "{msg}"
    );
    // Outside a field that does not repeat, the surface is the mean plane (2 m too).
    let far = RenderOptions::new(Camera {
        position_m: [-50.0, -50.0, 1.5],
        ..level_camera(1.0, 0.0)
    });
    assert!(render(&field, None, false, &far).is_err());
}

#[test]
fn exact_slopes_replace_the_central_differences() {
    // A flat field given tilted slopes: the normals, so the colors, follow the slopes.
    let field = flat(16, 16.0);
    let cam = level_camera(3.0, -30.0);
    let opts = plain(cam, 32, 18);
    let sx = vec![0.3f32; 256];
    let sy = vec![0.0f32; 256];
    let a = render(&field, None, true, &opts).unwrap();
    let b = render(&field, Some((&sx, &sy)), true, &opts).unwrap();
    assert_eq!(a.distance_m, b.distance_m, "the geometry is the same");
    assert_ne!(a.rgb, b.rgb, "the shading is not");
    let short = vec![0.0f32; 10];
    assert!(render(&field, Some((&short, &sy)), true, &opts).is_err());
}

#[test]
fn sample_patterns_are_stratified() {
    assert_eq!(sample_offsets(1), vec![(0.5, 0.5)]);
    assert_eq!(
        sample_offsets(4),
        vec![(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)]
    );
    for n in [2u32, 3, 5, 6, 8, 12] {
        let s = sample_offsets(n);
        assert_eq!(s.len(), n as usize);
        // n-rooks: one sample in each column and each row of an n×n grid.
        let mut rows: Vec<usize> = s.iter().map(|p| (p.1 * n as f64) as usize).collect();
        rows.sort();
        assert_eq!(rows, (0..n as usize).collect::<Vec<_>>(), "spp {n}");
    }
}

#[test]
fn bad_options_name_the_flag() {
    let cam = level_camera(3.0, 0.0);
    let cases = [
        (
            RenderOptions {
                width: 0,
                height: 0,
                ..RenderOptions::new(cam)
            },
            "--image",
        ),
        (
            RenderOptions {
                spp: 0,
                ..RenderOptions::new(cam)
            },
            "--spp",
        ),
        (
            RenderOptions {
                camera: Camera {
                    fov_x_rad: 0.0,
                    ..cam
                },
                ..RenderOptions::new(cam)
            },
            "--fov",
        ),
    ];
    for (o, flag) in cases {
        let e = o.validate().unwrap_err();
        assert_eq!(e.name, flag, "{e}");
    }
}
