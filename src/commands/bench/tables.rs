//! The tables `bench` prints after the stages: trochoids, choppy heights and map PNGs,
//! noise bases, mesh exports.

use super::*;

/// The trochoid method (`thon-2000` preset, n² over n meters): the setup with the
/// turbulence fit, the whole field on every thread, and the samples per second of one
/// core for the trochoids + turbulence, the trochoids alone and the turbulence alone.
pub(super) fn trochoid_rows(n: usize, repeats: usize, bare: Duration) -> Result<()> {
    use crate::field::trochoid::{RowScratch, TrochoidSea};
    let mut params = crate::config::presets::load("thon-2000")?;
    params.grid = bench_params(n).grid;
    let spec = params.grid_spec();
    let setup = time(repeats, || {
        TrochoidSea::new(&params).expect("a valid preset")
    });
    let sea = TrochoidSea::new(&params)?;
    let field = time(repeats, || sea.grid(&spec, 0.0));
    print_row("trochoid setup and fit", setup, bare, NAME_WIDTH);
    print_row("trochoid field (thon-2000)", field, bare, NAME_WIDTH);
    // One core: 64 rows in this thread.
    let rows = 64.min(n);
    let per_core = |p: &Params| -> Result<f64> {
        let sea = TrochoidSea::new(p)?;
        let frame = sea.frame(0.0, Some((spec.dx_m(), spec.dy_m())));
        let mut out = vec![0.0f32; n];
        let mut scratch = RowScratch::default();
        let t = time(repeats, || {
            for j in 0..rows {
                frame.grid_row(&spec, j, &mut out, &mut scratch);
            }
        });
        Ok((rows * n) as f64 / t.as_secs_f64() / 1e6)
    };
    let all = per_core(&params)?;
    let mut waves = params.clone();
    waves.trochoid.turbulence = false;
    let waves = per_core(&waves)?;
    let mut noise = params.clone();
    noise.trochoid.components = 1;
    let noise = per_core(&noise)?;
    println!(
        "  trochoid samples per second on one core: {all:.1} M (trochoids + turbulence), {waves:.1} M (the {} trochoids alone), {noise:.1} M (turbulence and one trochoid)",
        params.trochoid.components
    );
    Ok(())
}

/// The choppy height frame and its resampling, and the PNG writers of the height, normal
/// and foam maps (each file's size beside it), as ratios to the bare FFT: a choppy sea
/// (`choppy`, λ = 0.8) at the size being timed.
pub(super) fn resampling_and_png_rows(
    choppy: &Params,
    dir: &std::path::Path,
    repeats: usize,
    bare: Duration,
) -> Result<()> {
    use crate::export::maps::{normal_rgb, write_gray16};
    use crate::export::{Staged, rgb8};
    let all = field::dynamics::Extras::ALL;
    let heights = field::Synthesizer::new(choppy, Default::default(), true)?;
    let full = field::Synthesizer::new(choppy, all, true)?;
    let frame = full.frame(1.0);
    let spec = frame.grid.spec;
    let n = spec.nx;
    let d = frame
        .surface
        .displacement
        .as_ref()
        .context("a choppy frame has its displacement")?;
    let still = frame
        .surface
        .undisplaced_height
        .as_ref()
        .context("a choppy frame with its displacement keeps the undisplaced heights")?;
    println!(
        "  choppy heights and map PNGs (λ = {}):",
        choppy.motion.choppiness
    );
    print_row(
        "choppy height frame",
        time(repeats, || heights.frame(1.0)),
        bare,
        NAME_WIDTH,
    );
    print_row(
        "  of which: resampling",
        time(repeats, || {
            field::dynamics::resample_choppy(still, d, &spec)
        }),
        bare,
        NAME_WIDTH,
    );
    let st = frame.grid.stats();
    let mapping = HeightMapping {
        min_m: st.min_m,
        max_m: st.max_m,
    };
    let normals = frame.surface.normals().context("slopes were asked for")?;
    let rgb = normal_rgb(&normals);
    let j = frame
        .surface
        .jacobian
        .as_ref()
        .context("the Jacobian was asked for")?
        .values(spec.len());
    let t = crate::export::maps::FoamRule::of(choppy)
        .resolve(&j)
        .threshold;
    let foam: Vec<u16> = j
        .iter()
        .map(|&j| crate::export::maps::foam_value(j, t))
        .collect();
    let mut sizes = Vec::new();
    let mut file = |name: &str, write: &mut dyn FnMut(Staged) -> crate::error::Result<()>| {
        let path = dir.join(format!("bench-{n}.{name}.png"));
        let d = time(repeats, || {
            let staged = Staged::create(&path).expect("bench output is writable");
            write(staged).expect("bench output is writable")
        });
        sizes.push((name.to_string(), std::fs::metadata(&path)?.len()));
        anyhow::Ok(d)
    };
    let height = file("height", &mut |s| {
        s.write_with(|w| crate::export::png16::write(w, &frame.grid, &mapping))
    })?;
    let normal = file("normal", &mut |s| {
        rgb8::write_map(s, &rgb, (n as u32, spec.ny as u32))
    })?;
    let foam = file("foam", &mut |s| {
        s.write_with(|w| write_gray16(w, &spec, &foam))
    })?;
    print_row("PNG 16-bit height (choppy)", height, bare, NAME_WIDTH);
    print_row("PNG 8-bit RGB normal map", normal, bare, NAME_WIDTH);
    print_row("PNG 16-bit foam map", foam, bare, NAME_WIDTH);
    print_row(
        "  the three map PNGs",
        height + normal + foam,
        bare,
        NAME_WIDTH,
    );
    let sizes: Vec<String> = sizes
        .iter()
        .map(|(k, b)| format!("{k} {:.2} MB", *b as f64 / 1e6))
        .collect();
    println!("  map PNG files: {}", sizes.join(", "));
    Ok(())
}

/// Grid side of the noise-basis table.
const NOISE_N: usize = 256;

/// The noise bases side by side: CPU nanoseconds per sample per octave (every thread's
/// time, so one core's cost) of the builtin kernel and of each noise-rs source under fBm,
/// plane (2D) and tileable (4D torus), 6 octaves on a 256² grid, and each as a ratio to
/// the builtin kernel (tileable, as by default).
pub(super) fn noise_bases(repeats: usize) {
    use crate::config::{NoiseBasis, NoiseFractal};
    let params = bench_params(NOISE_N);
    let spec = params.grid_spec();
    let base = field::perlin_params(&params);
    let per = |d: Duration| d.as_secs_f64() * 1e9 / (spec.len() as f64 * base.octaves as f64);
    println!(
        "\nnoise bases, fBm of {} octaves at {NOISE_N}²: CPU ns per sample per octave (ratio to builtin)",
        base.octaves
    );
    println!(
        "  {:<16} {:>12} {:>16}",
        "basis", "plane (2D)", "tileable (4D)"
    );
    let mut builtin = 0.0;
    for basis in NoiseBasis::ALL {
        let mut cell = |tileable: bool| {
            if tileable && basis == NoiseBasis::SuperSimplex {
                return "-".to_string();
            }
            let pp = perlin::PerlinParams { tileable, ..base };
            let ns = per(time_cpu(repeats, || {
                perlin::noise_field(&spec, &pp, 0.0, basis, NoiseFractal::Fbm)
            })
            .1);
            if basis == NoiseBasis::Builtin && tileable {
                builtin = ns;
            }
            let ratio = if builtin > 0.0 { ns / builtin } else { 1.0 };
            format!("{ns:.1} ({ratio:.1}×)")
        };
        let tiled = cell(true);
        let plane = cell(false);
        println!("  {:<16} {:>12} {:>16}", basis.name(), plane, tiled);
    }
}

/// Times the mesh exports of periodic FFT fields: a 2048² OBJ and GLB (normals from
/// central differences, and texture coordinates), and a 4×4 OBJ tile set of a 4096²
/// field. Each file is removed after it is timed.
pub(super) fn exports(dir: &std::path::Path, repeats: usize) -> Result<()> {
    use crate::export::options::{ExportOptions, Tiles};
    println!(
        "\nexports, periodic FFT fields: medians of {repeats} runs; files removed after timing"
    );
    println!(
        "  {} {:>9} {:>9} {:>9}",
        pad("export", 34),
        "ms",
        "MB",
        "MB/s"
    );
    let cases = [
        (2048, "obj", None, "OBJ 2048², normals + UVs"),
        (2048, "glb", None, "GLB 2048², normals + UVs"),
        (
            4096,
            "obj",
            Some(Tiles {
                columns: 4,
                rows: 4,
            }),
            "OBJ 4096², 4×4 tiles",
        ),
    ];
    for (n, ext, tiles, name) in cases {
        let params = Params {
            method: crate::config::Method::Fft,
            grid: crate::config::GridParams {
                size: crate::config::Size2([n, n]),
                extent_m: crate::config::Extent2([n as f64, n as f64]),
                ..Default::default()
            },
            ..Params::default()
        };
        let grid = field::synthesize(&params)?.grid;
        let mapping = HeightMapping {
            min_m: 0.0,
            max_m: 1.0,
        };
        let field = FieldOut {
            grid: &grid,
            mapping: &mapping,
            slopes: None,
            about: "bench",
        };
        let mut options = ExportOptions::default();
        options.tiles = tiles;
        let path = dir.join(format!("bench-mesh-{n}.{ext}"));
        let mut runs = Vec::new();
        let mut bytes = 0u64;
        for _ in 0..repeats {
            let out = Output::plan(&path, &options, &grid.spec, true)?;
            let files: Vec<_> = out.files.iter().map(|f| f.path.clone()).collect();
            let t = Instant::now();
            out.write(&field)?;
            runs.push(t.elapsed());
            bytes = 0;
            for f in files {
                bytes += std::fs::metadata(&f)?.len();
                std::fs::remove_file(&f)?;
            }
        }
        let d = median(runs);
        println!(
            "  {} {:>9.1} {:>9.1} {:>9.0}",
            pad(name, 34),
            d.as_secs_f64() * 1e3,
            bytes as f64 / 1e6,
            bytes as f64 / 1e6 / d.as_secs_f64()
        );
    }
    Ok(())
}

/// Frames of the looping sequence rows of [`second_order_rows`].
const LOOP_FRAMES: usize = 48;

/// The cells (m) of the rows where the paired waves fill the grid: the storm's
/// convergence limit (0.39 rad/m deep, 0.34 at 19 m) lies near half the grid's Nyquist
/// wavenumber (0.79 rad/m), so the padded box of the paired waves is the whole grid.
const FILLING_CELL_M: usize = 4;

/// Runs of each 48-frame sequence of `second_order_rows`, the median reported.
const SEQUENCE_RUNS: usize = 3;

/// Second-order seas beside the linear one (`bench --second-order`): Pierson–Moskowitz,
/// 15 m/s, Hasselmann spreading, n² over 2048 m (so the paired components do not grow
/// with n), each the whole synthesis of one field (the fit included), as ratios to the
/// linear field of the same grid and to the bare FFT; then the same storm in cells of
/// [`FILLING_CELL_M`] (its paired waves' box the whole grid, where the fitted frame costs
/// most against the linear one), deep and at 19 m.
pub(super) fn second_order_rows(n: usize, repeats: usize, bare: Duration) -> Result<()> {
    use crate::config::layers::{Assignment, resolve};
    use crate::field::dynamics::Extras;
    use crate::pipeline::compute::synthesize_checked;
    let over = |extent: usize, extra: &[(&str, &str)]| -> Result<Params> {
        let size = n.to_string();
        let extent = extent.to_string();
        let base = [
            ("method", "fft"),
            ("spectrum", "pierson-moskowitz"),
            ("wind-speed", "15"),
            ("spectrum.spreading", "hasselmann"),
            ("extent", extent.as_str()),
            ("size", size.as_str()),
        ];
        let a: Vec<Assignment> = base
            .iter()
            .chain(extra)
            .map(|(k, v)| Assignment::flag(k, v))
            .collect();
        Ok(resolve(None, &a)?)
    };
    let sea = |extra: &[(&str, &str)]| over(2048, extra);
    let run = |p: &Params, r: usize| -> Result<Duration> {
        synthesize_checked(p, Extras::default())?;
        Ok(time(r, || {
            synthesize_checked(p, Extras::default()).expect("checked above")
        }))
    };
    let so = ("nonlinear", "second-order");
    let linear = run(&sea(&[])?, repeats)?;
    let pairs = run(
        &sea(&[so, ("spectrum.nonlinear_method", "pairs")])?,
        repeats.min(3),
    )?;
    let fitted = run(
        &sea(&[so, ("spectrum.nonlinear_method", "fitted")])?,
        repeats,
    )?;
    // Sequences of 48 frames (computed, not written): unlooped, the default method (the
    // fitted one on this deep sea) at each frame; looping, the pair sum binned once by
    // the pairs' multiples of 2π/T, each frame a sum over them.
    // (The median of three runs each: a sequence takes seconds, long enough for a busy
    // machine to slow one run.)
    let sequence = |extra: &[(&str, &str)]| -> Result<Duration> {
        let p = sea(extra)?;
        let mut failed = Ok(());
        let d = time(SEQUENCE_RUNS, || {
            let run = crate::pipeline::sequence::each_frame(
                &p,
                LOOP_FRAMES,
                Extras::default(),
                false,
                |_| true,
            );
            if let Err(e) = run {
                failed = Err(e);
            }
        });
        failed?;
        Ok(d)
    };
    let loop20 = ("loop-period", "20");
    let linear_seq = sequence(&[])?;
    let default_seq = sequence(&[so])?;
    // The method `auto` took for the unlooped sequence (fitted, or the pair sum where the
    // fit's estimate is above its bound).
    let took = synthesize_checked(&sea(&[so])?, Extras::default())?
        .info
        .second_order
        .and_then(|s| s.method)
        .unwrap_or_else(|| "none".into());
    let linear_loop = sequence(&[loop20])?;
    let pairs_loop = sequence(&[loop20, so])?;
    print_row("linear sea (PM 15 m/s, 2048 m)", linear, bare, NAME_WIDTH);
    print_row(
        "second order, pair sum (0.99 in limit)",
        pairs,
        bare,
        NAME_WIDTH,
    );
    print_row(
        "second order, fitted (all in limit)",
        fitted,
        bare,
        NAME_WIDTH,
    );
    let per = |d: Duration| d.as_secs_f64() / linear.as_secs_f64();
    println!(
        "  second order ÷ linear field: pair sum {:.1}×, fitted {:.1}×",
        per(pairs),
        per(fitted)
    );
    let rows = [
        ("48 frames, linear", linear_seq),
        ("48 frames, second order (auto)", default_seq),
        ("48 frames, linear, loop 20 s", linear_loop),
        ("48 frames, pair sum, loop 20 s", pairs_loop),
    ];
    for (name, d) in rows {
        print_row(name, d, bare, NAME_WIDTH);
    }
    let ratio = |a: Duration, b: Duration| a.as_secs_f64() / b.as_secs_f64();
    println!(
        "  {LOOP_FRAMES}-frame sequence, second order ÷ linear: {:.1}× (auto took {took}), looping {:.1}× (pair sum binned)",
        ratio(default_seq, linear_seq),
        ratio(pairs_loop, linear_loop)
    );
    // The paired waves' box the whole grid (three runs each: the second-order rows take
    // seconds at 4096²).
    let filling = FILLING_CELL_M * n;
    let fitted_at = |extra: &[(&str, &str)]| -> Result<Duration> {
        let with: Vec<_> = [so, ("spectrum.nonlinear_method", "fitted")]
            .into_iter()
            .chain(extra.iter().copied())
            .collect();
        run(&over(filling, &with)?, repeats.min(3))
    };
    let linear_fill = run(&over(filling, &[])?, repeats)?;
    let deep_fill = fitted_at(&[])?;
    let shallow_fill = fitted_at(&[("depth", "19")])?;
    let cells = format!("{FILLING_CELL_M} m cells");
    for (name, d) in [
        ("linear sea", linear_fill),
        ("second order, fitted", deep_fill),
        ("second order, fitted, 19 m", shallow_fill),
    ] {
        print_row(&format!("{name}, {cells}"), d, bare, NAME_WIDTH);
    }
    println!(
        "  paired waves filling the grid ({cells}, {filling} m), fitted ÷ linear field: deep {:.1}×, 19 m {:.1}×",
        ratio(deep_fill, linear_fill),
        ratio(shallow_fill, linear_fill)
    );
    Ok(())
}
