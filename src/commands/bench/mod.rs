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

mod sequence;
mod tables;

use sequence::sequences;
use tables::{exports, noise_bases, resampling_and_png_rows, second_order_rows, trochoid_rows};

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
        if args.second_order {
            second_order_rows(n, repeats, bare)?;
        }
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
