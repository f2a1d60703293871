//! `seasynth bench`: times each stage of the default job at a few sizes and reports each
//! as a ratio to a bare 2D real inverse FFT of the same size on the same machine, which
//! makes figures comparable across busy or different machines.

use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use rayon::prelude::*;
use realfft::RealFftPlanner;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex32;

use crate::cli::BenchArgs;
use crate::config::Params;
use crate::error::{Error, ParamError};
use crate::export::{FieldOut, HeightMapping, Output};
use crate::field::{self, fft, hybrid, perlin, weight};
use crate::grid::GridSpec;
use crate::rng::{Stream, sub_seed};
use crate::spectrum::{Dispersion, LineQuery, PairOut};

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

/// The median wall time of `repeats` runs of `f`.
fn time<T>(repeats: usize, f: impl FnMut() -> T) -> Duration {
    time_cpu(repeats, f).0
}

/// Columns on a terminal a text takes: its characters but combining marks (the tilde of
/// `h̃` is a second character in the same column).
fn display_width(text: &str) -> usize {
    text.chars()
        .filter(|c| !matches!(*c as u32, 0x0300..=0x036F | 0x20D0..=0x20FF))
        .count()
}

/// `text` padded with spaces to `width` columns (by [`display_width`]).
fn pad(text: &str, width: usize) -> String {
    format!(
        "{text}{}",
        " ".repeat(width.saturating_sub(display_width(text)))
    )
}

/// The width of the stage names, the same in every table of a size so that its columns
/// line up.
const NAME_WIDTH: usize = 38;

/// One row of a size's table: the stage, its time and its ratio to the bare FFT.
fn print_row(name: &str, d: Duration, bare: Duration, width: usize) {
    println!(
        "  {} {:>10.1} {:>8.2}",
        pad(name, width),
        d.as_secs_f64() * 1e3,
        d.as_secs_f64() / bare.as_secs_f64()
    );
}

/// CPU time of the whole process (user + system, every thread) so far.
fn cpu_time() -> Duration {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes the timespec it is given and nothing else.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    assert_eq!(rc, 0, "the process CPU clock exists on Linux");
    Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
}

/// As [`time`], and the median CPU time of the same runs (every thread's), which a busy
/// machine disturbs less than the wall time.
fn time_cpu<T>(repeats: usize, mut f: impl FnMut() -> T) -> (Duration, Duration) {
    let (wall, cpu): (Vec<Duration>, Vec<Duration>) = (0..repeats)
        .map(|_| {
            let (t, c) = (Instant::now(), cpu_time());
            std::hint::black_box(f());
            (t.elapsed(), cpu_time().saturating_sub(c))
        })
        .unzip();
    (median(wall), median(cpu))
}

/// The bare transform: rustfft inverse along y of the nx/2+1 kx lines, then realfft's
/// complex-to-real inverse along x of every row, on ready buffers and without the
/// transpose between them — the least work any 2D real inverse FFT does.
fn bare_fft(nx: usize, ny: usize, repeats: usize) -> Duration {
    let nh = nx / 2 + 1;
    let col = FftPlanner::<f32>::new().plan_fft_inverse(ny);
    let row = RealFftPlanner::<f32>::new().plan_fft_inverse(nx);
    let mut lines = vec![Complex32::new(0.0, 0.0); nh * ny];
    let mut rows = vec![Complex32::new(0.0, 0.0); nh * ny];
    let mut out = vec![0.0f32; nx * ny];
    time(repeats, || {
        lines.par_chunks_mut(ny * 8).for_each_init(
            || vec![Complex32::new(0.0, 0.0); col.get_inplace_scratch_len()],
            |s, c| col.process_with_scratch(c, s),
        );
        rows.par_chunks_mut(nh)
            .zip(out.par_chunks_mut(nx))
            .for_each_init(
                || vec![Complex32::new(0.0, 0.0); row.get_scratch_len()],
                |s, (i, o)| {
                    i[0].im = 0.0;
                    i[nh - 1].im = 0.0;
                    row.process_with_scratch(i, o, s)
                        .expect("lengths from the plan");
                },
            );
    })
}

/// E|h̃0(±k)|² of every wavevector of the half plane (the spectrum alone, without the
/// random draws). Each line is passed through `black_box`, so nothing is optimized away
/// and nothing is added to the spectrum's own cost.
fn amplitude_variances(setup: &fft::SpectrumSetup) -> f64 {
    let (nx, ny) = (setup.spec.nx, setup.spec.ny);
    let (dkx, dky) = setup.dk();
    let ky: Vec<f64> = (0..ny)
        .map(|m| setup.wavevector(0, fft::signed_index(m, ny)).1)
        .collect();
    (0..nx / 2 + 1)
        .into_par_iter()
        .map_init(
            || (vec![0.0; ny], vec![0.0; ny]),
            |(pa, pb), n| {
                let kx = setup.wavevector(n as i64, 0).0;
                let q = LineQuery {
                    kx,
                    ky: &ky,
                    dkx,
                    dky,
                };
                let out = PairOut { a: pa, b: pb };
                setup.spectrum.amplitude_variance_pair_line(&q, out);
                std::hint::black_box((&*pa, &*pb));
                pa[ny / 3] + pb[ny / 3]
            },
        )
        .sum()
}

/// The default job at n×n samples, 1 m apart.
fn bench_params(n: usize) -> Params {
    Params {
        grid: crate::config::GridParams {
            size: crate::config::Size2([n, n]),
            extent_m: crate::config::Extent2([n as f64, n as f64]),
            ..Default::default()
        },
        ..Params::default()
    }
}

pub fn run(args: BenchArgs) -> Result<()> {
    crate::commands::common::set_threads(args.threads)?;
    // Every size is checked (and its memory estimated) before any timing starts.
    for &n in &args.sizes {
        let params = bench_params(n);
        params.validate().map_err(|e| {
            Error::Param(ParamError {
                name: "--sizes".into(),
                got: n.to_string(),
                ..e
            })
        })?;
        let all = crate::field::dynamics::Extras::ALL;
        let choppy = Params {
            motion: crate::config::MotionParams {
                choppiness: 1.0,
                ..Default::default()
            },
            ..params
        };
        crate::limits::check_memory(
            crate::pipeline::memory::Footprint::of_field(&choppy, all)
                .with_outputs(2)
                .bytes((n * n) as u64, 1),
            &format!("benchmarking {n}x{n}"),
            args.force,
        )?;
    }
    std::fs::create_dir_all(&args.dir)
        .with_context(|| format!("cannot create {}", args.dir.display()))?;
    let repeats = args.repeats.max(1);
    // As in `animate`, whose frames these runs repeat.
    crate::pipeline::memory::keep_freed_memory();
    println!(
        "seasynth bench: medians of {repeats} runs, {} threads, freed memory kept for reuse (as animate); ratio = stage time / bare 2D real inverse FFT",
        rayon::current_num_threads()
    );
    for &n in &args.sizes {
        let params = bench_params(n);
        let spec: GridSpec = params.grid_spec();
        let model = field::phillips(&params);
        let setup = fft::SpectrumSetup {
            spec,
            spectrum: &model,
            dispersion: Dispersion::Deep,
            seed: sub_seed(params.seed, Stream::SpectrumAmplitude),
            time_s: 0.0,
            loop_period_s: None,
        };
        let bare = bare_fft(n, n, repeats);
        let mut rows: Vec<(&str, Duration)> = Vec::new();
        rows.push((
            "spectrum h̃(k,0)",
            time(repeats, || fft::synthesize_spectrum(&setup)),
        ));
        let timed_setup = fft::SpectrumSetup {
            time_s: 10.0,
            ..setup
        };
        rows.push((
            "spectrum h̃(k,t), t ≠ 0",
            time(repeats, || fft::synthesize_spectrum(&timed_setup)),
        ));
        let sea_params = Params {
            spectrum: crate::config::SpectrumParams {
                model: crate::config::SpectrumModel::PiersonMoskowitz,
                ..params.spectrum.clone()
            },
            wind: crate::config::WindParams {
                speed_mps: 15.0,
                direction_deg: 30.0,
            },
            ..params.clone()
        };
        let (sea, sea_dispersion) = field::spectrum_model(&sea_params)?;
        let sea_setup = fft::SpectrumSetup {
            spectrum: sea.as_ref(),
            dispersion: sea_dispersion,
            ..setup
        };
        rows.push((
            "spectrum PM×Hasselmann, 15 m/s",
            time(repeats, || fft::synthesize_spectrum(&sea_setup)),
        ));
        rows.push((
            "  of which: P(k) Phillips",
            time(repeats, || amplitude_variances(&setup)),
        ));
        rows.push((
            "  of which: P(k) PM×Hasselmann",
            time(repeats, || amplitude_variances(&sea_setup)),
        ));
        rows.push((
            "  of which: PM×Hasselmann model",
            time(repeats, || field::spectrum_model(&sea_params)),
        ));
        let mut fft_params = sea_params.clone();
        fft_params.method = crate::config::Method::Fft;
        let heights = field::Synthesizer::new(&fft_params, Default::default(), true)?;
        let still = time_cpu(repeats, || heights.frame(1.0));
        rows.push(("animation frame: height", still.0));
        let all = field::dynamics::Extras::ALL;
        let still_full = field::Synthesizer::new(&fft_params, all, true)?;
        let still_maps = time_cpu(repeats, || {
            let f = still_full.frame(1.0);
            (f.surface.normals(), f)
        });
        rows.push(("  + normals, foam, displacement", still_maps.0));
        let mut choppy = fft_params.clone();
        choppy.motion.choppiness = 0.8;
        let choppy_heights = field::Synthesizer::new(&choppy, Default::default(), true)?;
        let choppy_only = time_cpu(repeats, || choppy_heights.frame(1.0));
        rows.push(("animation frame: choppy height λ=0.8", choppy_only.0));
        let full = field::Synthesizer::new(&choppy, all, true)?;
        let choppy_maps = time_cpu(repeats, || {
            let f = full.frame(1.0);
            (f.surface.normals(), f)
        });
        rows.push(("  + normals, foam, displacement", choppy_maps.0));
        let ratio = |a: Duration, b: Duration| a.as_secs_f64() / b.as_secs_f64();
        let maps_cost = format!(
            "  maps ÷ height frame: still {:.2}× wall, {:.2}× CPU ({:.1} / {:.1} ms CPU); choppy {:.2}× wall, {:.2}× CPU ({:.1} / {:.1} ms CPU)",
            ratio(still_maps.0, still.0),
            ratio(still_maps.1, still.1),
            still_maps.1.as_secs_f64() * 1e3,
            still.1.as_secs_f64() * 1e3,
            ratio(choppy_maps.0, choppy_only.0),
            ratio(choppy_maps.1, choppy_only.1),
            choppy_maps.1.as_secs_f64() * 1e3,
            choppy_only.1.as_secs_f64() * 1e3,
        );
        let plan = fft::InverseFft2::new(n, n);
        let template = fft::synthesize_spectrum(&setup);
        let fft_time = median(
            (0..repeats)
                .map(|_| {
                    let half = fft::HalfSpectrum {
                        data: template.data.clone(),
                        ..template
                    };
                    let t = Instant::now();
                    std::hint::black_box(plan.process(half));
                    t.elapsed()
                })
                .collect(),
        );
        rows.push(("inverse FFT (whole, row blocks)", fft_time));
        let pp = field::perlin_params(&params);
        rows.push((
            "Perlin, 6 octaves",
            time(repeats, || perlin::perlin_field(&spec, &pp)),
        ));
        let alpha = weight::AlphaMap::new(&params.blend.alpha, &spec)?;
        let synthesis = field::synthesize(&params)?;
        let noise = perlin::perlin_field(&spec, &pp);
        let mut grid = synthesis.grid.clone();
        rows.push((
            "blend",
            time(repeats, || {
                hybrid::blend_in_place(&mut grid, &noise, &alpha, 0.1)
            }),
        ));
        rows.push(("statistics", time(repeats, || synthesis.grid.stats())));
        let st = synthesis.grid.stats();
        let mapping = HeightMapping {
            min_m: st.min_m,
            max_m: st.max_m,
        };
        let mut sizes = Vec::new();
        for ext in ["png", "tif"] {
            let path = args.dir.join(format!("bench-{n}.{ext}"));
            let t = time(repeats, || {
                Output::prepare(&path)
                    .and_then(|o| {
                        o.write(&FieldOut {
                            grid: &synthesis.grid,
                            mapping: &mapping,
                            slopes: None,
                            about: "",
                        })
                    })
                    .expect("bench output is writable")
            });
            sizes.push((ext, std::fs::metadata(&path)?.len()));
            rows.push((
                if ext == "png" {
                    "PNG 16-bit writer"
                } else {
                    "TIFF f32 writer"
                },
                t,
            ));
        }
        rows.push((
            "whole synthesis (hybrid)",
            time(repeats, || field::synthesize(&params)),
        ));
        // The default preview (grazing view, 1280×720, 4 rays per pixel), pyramids included.
        let periodic = field::method_for(&params).is_periodic();
        let wind = params.wind.direction_deg.to_radians();
        let preview = crate::render::RenderOptions::preview(&synthesis.grid, wind, periodic);
        rows.push((
            "render preview 1280×720, 4 spp",
            time(repeats.min(3), || {
                crate::render::render(&synthesis.grid, None, periodic, &preview)
                    .expect("the default view renders")
            }),
        ));
        println!(
            "\n{n}×{n}: bare 2D real inverse FFT {:.1} ms",
            bare.as_secs_f64() * 1e3
        );
        let width = rows
            .iter()
            .map(|(name, _)| display_width(name))
            .max()
            .unwrap_or(0)
            .max(NAME_WIDTH);
        println!("  {} {:>10} {:>8}", pad("stage", width), "ms", "ratio");
        for (name, d) in rows {
            print_row(name, d, bare, width);
        }
        for (ext, bytes) in sizes {
            println!("  {ext} file: {:.1} MB", bytes as f64 / 1e6);
        }
        println!("{maps_cost}");
        trochoid_rows(n, repeats, bare)?;
        resampling_and_png_rows(&choppy, &args.dir, repeats, bare)?;
    }
    noise_bases(repeats);
    if args.exports {
        exports(&args.dir, repeats.min(3))?;
    }
    if args.sequence {
        sequences(&args.dir, args.threads)?;
    }
    Ok(())
}

/// Frames of the sequence rows.
const SEQUENCE_FRAMES: usize = 48;

/// Blender's ocean bake of [`sequences`] (`contrib/blender/ocean_bake.py`).
const BLENDER_BAKE: &str = include_str!("../../contrib/blender/ocean_bake.py");

/// CPU time of the finished child processes (user + system), so far.
fn children_cpu_time() -> Duration {
    // SAFETY: getrusage writes the struct it is given and nothing else.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    let rc = unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut u) };
    assert_eq!(rc, 0, "RUSAGE_CHILDREN exists on Linux");
    let t = |v: libc::timeval| Duration::new(v.tv_sec as u64, v.tv_usec as u32 * 1000);
    t(u.ru_utime) + t(u.ru_stime)
}

/// Runs `cmd` to the end: its wall time and the CPU time of its processes.
fn run_timed(cmd: &mut std::process::Command) -> Result<(Duration, Duration)> {
    let (t, c) = (Instant::now(), children_cpu_time());
    let out = cmd.output().context("cannot start the timed command")?;
    let wall = t.elapsed();
    if !out.status.success() {
        anyhow::bail!(
            "timed command failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    Ok((wall, children_cpu_time().saturating_sub(c)))
}

/// Times 48-frame `animate` sequences at 1024² (PM 15 m/s over 1024 m, `--method fft`),
/// each a whole run of this executable (start-up, draws and sidecar included), as
/// milliseconds per frame of wall and of CPU time: choppy λ = 1 displacement + foam, the
/// displacement as half-float ZIP EXR with foam in A (Blender's bake format), and a still
/// sea's height PNG + normal + foam. When `blender` runs, its ocean bake of the same sea
/// (resolution 32, 1024², PM 15 m/s, choppiness 1, foam, frames 1–48) is timed from its
/// first file to its last, and the ratio Blender ÷ seasynth per frame is printed.
fn sequences(dir: &std::path::Path, threads: Option<usize>) -> Result<()> {
    let frames = SEQUENCE_FRAMES;
    let exe = std::env::current_exe().context("cannot find this executable")?;
    let base = dir.join("sequence");
    let field = [
        "--method",
        "fft",
        "--spectrum",
        "pierson-moskowitz",
        "--wind-speed",
        "15",
        "--size",
        "1024",
        "--extent",
        "1024",
    ];
    let rows: [(&str, &[&str]); 3] = [
        (
            "choppy λ=1, disp + foam",
            &["--choppiness", "1", "--format", "disp,foam"],
        ),
        (
            "choppy λ=1, disp.exr half ZIP",
            &[
                "--choppiness",
                "1",
                "--format",
                "disp.exr",
                "--exr-half",
                "--exr-compression",
                "zip",
            ],
        ),
        (
            "still, png + normal + foam",
            &["--format", "png,normal,foam"],
        ),
    ];
    println!(
        "\nsequences, {frames} frames of 1024² (PM 15 m/s over 1024 m), whole runs: ms per frame"
    );
    println!("  {:<32} {:>8} {:>8}", "animate", "wall", "CPU");
    let per_frame = |d: Duration| d.as_secs_f64() * 1e3 / frames as f64;
    let mut walls = Vec::new();
    for (i, (name, extra)) in rows.iter().enumerate() {
        let out = base.join(format!("s{i}"));
        let mut cmd = std::process::Command::new(&exe);
        cmd.arg("animate")
            .args(field)
            .args(*extra)
            .args(["--frames", &frames.to_string(), "-q", "-o"])
            .arg(&out);
        if let Some(t) = threads {
            cmd.args(["--threads", &t.to_string()]);
        }
        let (wall, cpu) = run_timed(&mut cmd)?;
        println!(
            "  {:<32} {:>8.1} {:>8.1}",
            name,
            per_frame(wall),
            per_frame(cpu)
        );
        walls.push(per_frame(wall));
        std::fs::remove_dir_all(&out).ok();
    }
    let blender = std::process::Command::new("blender")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !blender {
        println!(
            "  note: blender is not on the PATH: its ocean bake is not timed beside these rows"
        );
        return Ok(());
    }
    let script = base.join("ocean_bake.py");
    let out = base.join("blender");
    std::fs::create_dir_all(&out)?;
    std::fs::write(&script, BLENDER_BAKE)?;
    let mut cmd = std::process::Command::new("blender");
    cmd.args(["-b", "--factory-startup", "--python"])
        .arg(&script)
        .arg("--")
        .arg(format!("{}/", out.display()))
        .arg(frames.to_string());
    run_timed(&mut cmd)?;
    // From the first file to the last: Blender's start-up and scene set-up left out.
    let mut times = Vec::new();
    for e in std::fs::read_dir(&out)? {
        times.push(e?.metadata()?.modified()?);
    }
    let (first, last) = (times.iter().min(), times.iter().max());
    let span = match (first, last) {
        (Some(a), Some(b)) if times.len() >= 2 * frames => b.duration_since(*a)?,
        _ => anyhow::bail!(
            "Blender's bake wrote {} files, not {}",
            times.len(),
            2 * frames
        ),
    };
    let blender_frame = span.as_secs_f64() * 1e3 / (frames - 1) as f64;
    println!(
        "  {:<32} {:>8.1}          Blender ÷ seasynth per frame (wall): disp + foam {:.1}, disp.exr half ZIP {:.1}",
        "Blender 3.x ocean bake, 1st→last",
        blender_frame,
        blender_frame / walls[0],
        blender_frame / walls[1]
    );
    std::fs::remove_dir_all(&out).ok();
    std::fs::remove_file(&script).ok();
    Ok(())
}

/// The trochoid method (`thon-2000` preset, n² over n meters): the setup with the
/// turbulence fit, the whole field on every thread, and the samples per second of one
/// core for the trochoids + turbulence, the trochoids alone and the turbulence alone.
fn trochoid_rows(n: usize, repeats: usize, bare: Duration) -> Result<()> {
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
fn resampling_and_png_rows(
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
fn noise_bases(repeats: usize) {
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
fn exports(dir: &std::path::Path, repeats: usize) -> Result<()> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_are_padded_by_display_width() {
        assert_eq!(
            display_width("spectrum h̃(k,0)"),
            15,
            "the combining tilde takes no column"
        );
        assert_eq!(display_width("λ=0.8"), 5);
        assert_eq!(pad("h̃", 3), "h̃  ");
        assert_eq!(display_width(&pad("choppy λ", 12)), 12);
        assert_eq!(pad("longer than the width", 4), "longer than the width");
    }
}
