use super::*;
use crate::config::{Extent2, Size2, SpectrumModel};

fn pm_params(wind: f64) -> Params {
    let mut p = Params {
        method: crate::config::Method::Trochoid,
        ..Params::default()
    };
    p.spectrum.model = SpectrumModel::PiersonMoskowitz;
    p.wind.speed_mps = wind;
    p.validate().unwrap();
    p
}

/// `--sample-at centers` evaluates the continuous sea at the texel centres: the grid
/// equals the sea of the corner grid evaluated half a cell in.
#[test]
fn centers_are_the_sea_evaluated_half_a_cell_in() {
    let p = pm_params(10.0);
    let mut q = p.clone();
    q.grid.sample_at = crate::config::SampleAt::Centers;
    let spec = GridSpec::new(24, 16, 240.0, 96.0);
    let corners = TrochoidSea::new(&p).unwrap();
    let frame = corners.frame(2.5, Some((spec.dx_m(), spec.dy_m())));
    let shifted = TrochoidSea::new(&q).unwrap();
    // The origin moves by half a cell of the parameters' grid.
    let (hx, hy) = (p.grid_spec().dx_m() / 2.0, p.grid_spec().dy_m() / 2.0);
    let g = shifted.grid(&spec, 2.5);
    let scale = g.data.iter().fold(0.0f32, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    for j in 0..spec.ny {
        for i in 0..spec.nx {
            let want = frame.at(spec.x_m(i) + hx, spec.y_m(j) + hy);
            let got = g.get(i, j);
            assert!(
                (got - want).abs() <= 1e-5 * scale,
                "sample ({i}, {j}): {got} vs {want}"
            );
        }
    }
}

#[test]
fn a_point_is_the_row_through_it_and_rows_do_not_depend_on_their_neighbours() {
    let mut p = pm_params(10.0);
    p.trochoid.origin_m = [-300.0, 120.0];
    let sea = TrochoidSea::new(&p).unwrap();
    let spec = GridSpec::new(96, 40, 384.0, 160.0);
    let g = sea.grid(&spec, 3.5);
    let frame = sea.frame(3.5, Some((spec.dx_m(), spec.dy_m())));
    for (i, j) in [(0, 0), (95, 39), (17, 23), (50, 1)] {
        let (x, y) = (-300.0 + spec.x_m(i), 120.0 + spec.y_m(j));
        assert_eq!(
            frame.at(x, y).to_bits(),
            g.get(i, j).to_bits(),
            "sample ({i}, {j})"
        );
    }
    // Half the grid from a window starting at row 20 is the same bits.
    let mut q = p.clone();
    q.trochoid.origin_m = [-300.0, 120.0 + spec.y_m(20)];
    let lower = TrochoidSea::new(&q)
        .unwrap()
        .grid(&GridSpec::new(96, 20, 384.0, 80.0), 3.5);
    assert!(
        lower.data == g.data[20 * 96..],
        "a window is a sub-grid of the sea"
    );
}

#[test]
fn the_fitted_turbulence_has_the_target_slope_and_level_at_k_max() {
    // Measured on a 1024² grid of the turbulence alone (2 m spacing over 2048 m, so
    // k_max ≈ 0.15 rad/m spans ~50 bins of Δk = 0.003), by a least-squares fit of
    // ln S(k) over ln k ∈ ln k_max ± 0.2. The measured slope of one realization scatters
    // by ~0.2 around the model's; the level by ~20 %.
    const SLOPE_TOL: f64 = 0.35;
    const LEVEL_TOL: f64 = 0.35;
    for (wind, model) in [
        (8.0, SpectrumModel::PiersonMoskowitz),
        (15.0, SpectrumModel::Jonswap),
    ] {
        let mut p = pm_params(wind);
        p.spectrum.model = model;
        p.trochoid.antialias = false;
        let sea = TrochoidSea::new(&p).unwrap();
        let fit = sea.info().turbulence.unwrap();
        let k_max = sea.info().k_max_rad_per_m;
        assert!(
            (fit.turbulence_slope - fit.target_slope).abs() < 1e-6,
            "model slope {} vs target {}",
            fit.turbulence_slope,
            fit.target_slope
        );
        let l = 2048.0 * wind / 10.0 * wind / 10.0;
        let spec = GridSpec::new(1024, 1024, l, l);
        let mut frame = sea.frame(0.0, None);
        frame.waves.clear();
        let mut data = vec![0.0f32; spec.len()];
        let mut s = RowScratch::default();
        for (j, row) in data.chunks_mut(spec.nx).enumerate() {
            frame.grid_row(&spec, j, row, &mut s);
        }
        let a = crate::measure::analyze(&Grid::new(spec, data), None);
        let pts: Vec<(f64, f64)> = a
            .radial_spectrum
            .iter()
            .filter(|b| (b.k_rad_per_m / k_max).ln().abs() <= 0.2)
            .map(|b| (b.k_rad_per_m.ln(), b.s_m2_per_rad_per_m.ln()))
            .collect();
        let n = pts.len() as f64;
        let (mx, my) = (
            pts.iter().map(|p| p.0).sum::<f64>() / n,
            pts.iter().map(|p| p.1).sum::<f64>() / n,
        );
        let slope = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
            / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
        let level = (my + slope * (k_max.ln() - mx)).exp();
        let target = fit.target_level_m2_per_rad_per_m;
        eprintln!(
            "wind {wind}: m {:.3}, A_t {:.3} m; slope measured {slope:.3} target {:.3}; level measured {level:.4} target {target:.4} ({} bins)",
            fit.multiplier,
            fit.amplitude_m,
            fit.target_slope,
            pts.len()
        );
        assert!(
            (slope - fit.target_slope).abs() <= SLOPE_TOL,
            "wind {wind}: measured slope {slope} vs target {} (± {SLOPE_TOL})",
            fit.target_slope
        );
        assert!(
            (level / target).ln().abs() <= LEVEL_TOL,
            "wind {wind}: measured level {level} vs target {target}"
        );
    }
}

/// RMS of the difference between the coarse grid and the 4×4 box average of the fine.
fn coarse_vs_box(antialias: bool) -> f64 {
    let mut p = pm_params(10.0);
    p.trochoid.antialias = antialias;
    // Fine: 1024² at 2 m. Coarse: 256² at 8 m, each sample at the centre of its 4×4
    // block of fine samples (1.5 fine samples in).
    p.trochoid.origin_m = [1000.0, -500.0];
    let fine = TrochoidSea::new(&p)
        .unwrap()
        .grid(&GridSpec::new(1024, 1024, 2048.0, 2048.0), 0.0);
    p.trochoid.origin_m = [1003.0, -497.0];
    let coarse = TrochoidSea::new(&p)
        .unwrap()
        .grid(&GridSpec::new(256, 256, 2048.0, 2048.0), 0.0);
    let mut sq = 0.0;
    for j in 0..256 {
        for i in 0..256 {
            let mut b = 0.0f64;
            for dj in 0..4 {
                for di in 0..4 {
                    b += fine.get(4 * i + di, 4 * j + dj) as f64;
                }
            }
            let d = coarse.get(i, j) as f64 - b / 16.0;
            sq += d * d;
        }
    }
    (sq / (256.0 * 256.0)).sqrt()
}

#[test]
fn antialiased_coarse_output_is_the_low_pass_of_the_fine_one() {
    // Measured 0.043 m against 0.086 m (ratio 2.0): without antialiasing the coarse grid
    // point-samples turbulence octaves far above its Nyquist wavenumber, which the box
    // filter removes; what remains with it is the octaves' broad spectra, weighted at
    // their peaks only.
    const MIN_RATIO: f64 = 1.8;
    let with = coarse_vs_box(true);
    let without = coarse_vs_box(false);
    eprintln!(
        "RMS coarse − box(fine): {with:.4} m antialiased, {without:.4} m without, ratio {:.2}",
        without / with
    );
    assert!(
        without >= MIN_RATIO * with,
        "antialiasing should cut the error by ≥ {MIN_RATIO}×: {with} vs {without}"
    );
}

#[test]
fn trochoids_travel_at_their_phase_speed() {
    let mut p = pm_params(10.0);
    p.trochoid.components = 1;
    p.trochoid.turbulence = false;
    p.trochoid.sharpness = 0.0;
    let sea = TrochoidSea::new(&p).unwrap();
    let c = sea.components()[0];
    let k = c.wavenumber();
    let speed = c.omega / k;
    let (ux, uy) = (c.k.0 / k, c.k.1 / k);
    let t = 2.5;
    let (f0, f1) = (sea.frame(0.0, None), sea.frame(t, None));
    for i in 0..20 {
        let (x, y) = (i as f64 * 7.3, i as f64 * -3.1);
        let moved = f1.at(x + ux * speed * t, y + uy * speed * t);
        let here = f0.at(x, y);
        assert!(
            (moved - here).abs() <= 1e-4 * c.amplitude_m as f32,
            "point {i}: {moved} vs {here}"
        );
    }
    // ... and the amplitude is A = 2√P of the strongest cell, as a cosine at kr = 0.
    let want = c.amplitude_m * (c.phase).cos();
    assert!((f0.at(0.0, 0.0) as f64 - want).abs() < 1e-5 * c.amplitude_m);
}

#[test]
fn the_trochoid_loop_gives_the_same_bits_on_every_instruction_set() {
    let sea = TrochoidSea::new(&pm_params(12.0)).unwrap();
    let frame = sea.frame(7.0, None);
    let xs: Vec<f64> = (0..1001).map(|i| -5e4 + i as f64 * 37.3).collect();
    let isas = Isa::available();
    let outs: Vec<Vec<f32>> = isas
        .iter()
        .map(|&isa| {
            let mut out = vec![0.0f32; xs.len()];
            for w in &frame.waves {
                wave_run(
                    isa,
                    frame.table,
                    &xs,
                    w.ax,
                    w.ay * 3.0 + w.c0,
                    w.amp,
                    &mut out,
                );
            }
            out
        })
        .collect();
    for (isa, out) in isas.iter().zip(&outs) {
        for (i, (a, b)) in out.iter().zip(&outs[0]).enumerate() {
            assert_eq!(a.to_bits(), b.to_bits(), "{isa:?}, sample {i}");
        }
    }
    // And the same as the point API (no turbulence difference: turbulence is added
    // after the trochoids in both).
    let mut p = pm_params(12.0);
    p.trochoid.turbulence = false;
    let calm = TrochoidSea::new(&p).unwrap();
    let mut out = vec![0.0f32; 3];
    calm.frame(7.0, None)
        .row(xs[5], 37.3, 3.0, &mut out, &mut RowScratch::default());
    assert_eq!(out[0].to_bits(), calm.height_at(xs[5], 3.0, 7.0).to_bits());
}

#[test]
fn the_synthesized_field_is_the_sea_sampled_on_the_grid() {
    let mut p = pm_params(10.0);
    p.grid.size = Size2([64, 48]);
    p.grid.extent_m = Extent2([64.0, 96.0]);
    p.time_s = 1.5;
    let s = crate::field::synthesize(&p).unwrap();
    let sea = TrochoidSea::new(&p).unwrap();
    assert_eq!(s.info.trochoid.as_ref(), Some(sea.info()));
    assert!(s.grid.stats().std_m > 0.0);
    let want = sea.grid(&p.grid_spec(), p.time_s);
    assert_eq!(s.grid.spec, want.spec);
    for (i, (a, b)) in s.grid.data.iter().zip(&want.data).enumerate() {
        assert_eq!(a.to_bits(), b.to_bits(), "sample {i}");
    }
}

/// The normalized autocorrelation R(τ) = C(τ)/C(0) of `g`'s deviations from its mean,
/// C(τ) the mean product over the samples that overlap at lag τ (a linear, not
/// circular, autocorrelation: zero-padded FFTs), for lags |τx|, |τy| ≤ half the
/// window; the largest R at lags at least `r0_m` long.
fn largest_autocorrelation_beyond(g: &Grid, r0_m: f64) -> (f64, [f64; 2]) {
    use rustfft::FftPlanner;
    use rustfft::num_complex::Complex64;
    let (nx, ny) = (g.spec.nx, g.spec.ny);
    let (px, py) = (2 * nx, 2 * ny);
    let mean = g.stats().mean_m;
    let mut planner = FftPlanner::<f64>::new();
    let (fx, fy) = (planner.plan_fft_forward(px), planner.plan_fft_forward(py));
    let (ix, iy) = (planner.plan_fft_inverse(px), planner.plan_fft_inverse(py));
    // 2D transform of a px × py buffer (rows along x), forward or inverse.
    let transform = |buf: &mut Vec<Complex64>, forward: bool| {
        let (rx, ry) = if forward { (&fx, &fy) } else { (&ix, &iy) };
        for row in buf.chunks_mut(px) {
            rx.process(row);
        }
        let mut col = vec![Complex64::new(0.0, 0.0); py];
        for i in 0..px {
            for j in 0..py {
                col[j] = buf[j * px + i];
            }
            ry.process(&mut col);
            for j in 0..py {
                buf[j * px + i] = col[j];
            }
        }
    };
    let padded = |f: &dyn Fn(usize, usize) -> f64| {
        let mut b = vec![Complex64::new(0.0, 0.0); px * py];
        for j in 0..ny {
            for i in 0..nx {
                b[j * px + i] = Complex64::new(f(i, j), 0.0);
            }
        }
        b
    };
    let mut h = padded(&|i, j| g.data[j * nx + i] as f64 - mean);
    let mut ones = padded(&|_, _| 1.0);
    for (b, forward) in [(&mut h, true), (&mut ones, true)] {
        transform(b, forward);
    }
    for b in [&mut h, &mut ones] {
        for v in b.iter_mut() {
            *v = Complex64::new(v.norm_sqr(), 0.0);
        }
        transform(b, false);
    }
    let at = |b: &Vec<Complex64>, tx: i64, ty: i64| {
        b[ty.rem_euclid(py as i64) as usize * px + tx.rem_euclid(px as i64) as usize].re
    };
    let c0 = at(&h, 0, 0) / at(&ones, 0, 0);
    let (hx, hy) = (nx as i64 / 2, ny as i64 / 2);
    let mut best = (f64::NEG_INFINITY, [0.0, 0.0]);
    for ty in -hy..=hy {
        for tx in -hx..=hx {
            let lag = [tx as f64 * g.spec.dx_m(), ty as f64 * g.spec.dy_m()];
            if lag[0].hypot(lag[1]) < r0_m {
                continue;
            }
            let r = at(&h, tx, ty) / at(&ones, tx, ty) / c0;
            if r > best.0 {
                best = (r, lag);
            }
        }
    }
    best
}

/// Thon's sea in a window of 4 km (8 tiles of the selection matrix): with every
/// component on its cell's centre the sum repeats every tile side L, a lattice of
/// copies whose autocorrelation is 1 at lag L; placed at random inside their cells
/// the components have no common period, and the autocorrelation beyond the central
/// lobe stays far below it.
#[test]
fn the_trochoid_sea_has_no_secondary_autocorrelation_peak() {
    // The largest autocorrelation allowed at lags of a peak wavelength or more.
    const SECONDARY_PEAK_MAX: f64 = 0.6;
    for seed in [1, 2, 3] {
        let mut p = Params::preset("thon-2000").unwrap();
        p.seed = seed;
        p.grid.size = Size2([512, 512]);
        p.grid.extent_m = Extent2([4096.0, 4096.0]);
        p.trochoid.turbulence = false;
        let sea = TrochoidSea::new(&p).unwrap();
        let tile = sea.info().matrix_extent_m;
        assert!(tile < 4096.0 / 4.0, "the window holds several tiles");
        let lambda_p = tile / MATRIX_PEAK_WAVELENGTHS;
        let spec = p.grid_spec();
        let (now, now_lag) = largest_autocorrelation_beyond(&sea.grid(&spec, 0.0), lambda_p);
        // The old placement, on the cell centres, fails the same measure.
        let mut centred = sea.clone();
        let dk = std::f64::consts::TAU / tile;
        for c in centred.components.iter_mut() {
            c.k = (c.index.0 as f64 * dk, c.index.1 as f64 * dk);
        }
        let (old, old_lag) = largest_autocorrelation_beyond(&centred.grid(&spec, 0.0), lambda_p);
        eprintln!(
            "seed {seed}: largest autocorrelation beyond {lambda_p:.0} m: {now:.3} at {now_lag:?} m (in-cell), {old:.3} at {old_lag:?} m (cell centres, tile {tile:.0} m)"
        );
        // Within a sample of a multiple of the tile on each axis.
        let on_lattice = |v: f64| (v / tile - (v / tile).round()).abs() * tile <= spec.dx_m();
        assert!(
            old > SECONDARY_PEAK_MAX && old_lag.iter().all(|&v| on_lattice(v)),
            "seed {seed}: the centred components repeat every tile: {old} at {old_lag:?}"
        );
        assert!(
            now < SECONDARY_PEAK_MAX,
            "seed {seed}: a secondary peak {now} at {now_lag:?} m"
        );
    }
}
