use super::*;

/// Tolerance for values that should agree up to rounding of the lattice coordinate.
const PERIOD_TOL: f32 = 1e-6;
/// A non-periodic field must differ from its shift by at least this somewhere.
const NOT_PERIODIC_MIN: f32 = 1e-3;
/// Minimum standard deviation of a 6-octave, a = 0.5 field.
const MIN_STD: f64 = 0.05;

fn params(octaves: u32, wavelength_m: f64, tileable: bool, seed: u64) -> PerlinParams {
    PerlinParams {
        octaves,
        persistence: 0.5,
        lacunarity: 2.0,
        wavelength_m,
        tileable,
        seed,
    }
}

/// Deterministic pseudo-random points for probing (not grid points).
fn probe_points(n: usize, lx: f64, ly: f64) -> Vec<(f64, f64)> {
    (0..n as u64)
        .map(|k| {
            let h = fmix(k ^ 0x1234_5678);
            let u = (h >> 11) as f64 / (1u64 << 53) as f64;
            let v = (fmix(h) >> 11) as f64 / (1u64 << 53) as f64;
            // Some points also outside [0, L), including negative ones.
            (u * 3.0 * lx - lx, v * 3.0 * ly - ly)
        })
        .collect()
}

#[test]
fn gradients_are_unit_length() {
    for (k, g) in GRADIENTS.iter().enumerate() {
        let len = ((g[0] as f64).powi(2) + (g[1] as f64).powi(2)).sqrt();
        assert!((len - 1.0).abs() < 1e-6, "gradient {k} has length {len}");
    }
    let a = GRADIENTS[N_GRAD / 8 * 3]; // angle −π + 3π/4 = −π/4
    let h = std::f32::consts::FRAC_1_SQRT_2;
    assert!((a[0] - h).abs() < 1e-7 && (a[1] + h).abs() < 1e-7, "{a:?}");
}

#[test]
fn values_lie_in_unit_interval_and_are_not_trivial() {
    let cases = [
        (
            GridSpec::new(256, 256, 512.0, 512.0),
            params(6, 100.0, true, 1),
        ),
        (
            GridSpec::new(200, 120, 300.0, 90.0),
            params(6, 37.0, false, 2),
        ),
        (GridSpec::new(128, 128, 64.0, 64.0), params(1, 8.0, true, 3)),
        (
            GridSpec::new(64, 96, 1000.0, 1500.0),
            params(8, 250.0, true, 4),
        ),
    ];
    for (c, (spec, p)) in cases.iter().enumerate() {
        let f = perlin_field(spec, p);
        assert_eq!(f.len(), spec.len());
        for (k, &v) in f.iter().enumerate() {
            assert!(
                (-1.0..=1.0).contains(&v),
                "case {c}: value {v} at index {k} (i={}, j={}) outside [-1, 1]",
                k % spec.nx,
                k / spec.nx
            );
        }
        let n = f.len() as f64;
        let mean = f.iter().map(|&v| v as f64).sum::<f64>() / n;
        let std = (f.iter().map(|&v| (v as f64 - mean).powi(2)).sum::<f64>() / n).sqrt();
        if p.octaves == 6 {
            assert!(std > MIN_STD, "case {c}: std {std} <= {MIN_STD}");
        }
        assert!(std > 0.0, "case {c}: constant field");
    }
}

#[test]
fn tileable_field_is_periodic() {
    let spec = GridSpec::new(96, 80, 512.0, 300.0);
    let p = params(5, 100.0, true, 7);
    let (lx, ly) = (spec.extent_x_m, spec.extent_y_m);
    for (k, &(x, y)) in probe_points(500, lx, ly).iter().enumerate() {
        let v = perlin_at(&spec, &p, x, y);
        let vx = perlin_at(&spec, &p, x + lx, y);
        let vy = perlin_at(&spec, &p, x, y + ly);
        assert!(
            (v - vx).abs() <= PERIOD_TOL,
            "point {k} ({x}, {y}): x-shift {vx} vs {v}"
        );
        assert!(
            (v - vy).abs() <= PERIOD_TOL,
            "point {k} ({x}, {y}): y-shift {vy} vs {v}"
        );
    }
    // Column 0 of the grid (x = 0) continues seamlessly at x = Lx, row 0 at y = Ly.
    let f = perlin_field(&spec, &p);
    for j in 0..spec.ny {
        let at = perlin_at(&spec, &p, lx, spec.y_m(j));
        let g = f[j * spec.nx];
        assert!(
            (g - at).abs() <= PERIOD_TOL,
            "row {j}: column 0 {g} vs x=Lx {at}"
        );
    }
    for (i, &g) in f[..spec.nx].iter().enumerate() {
        let at = perlin_at(&spec, &p, spec.x_m(i), ly);
        assert!(
            (g - at).abs() <= PERIOD_TOL,
            "column {i}: row 0 {g} vs y=Ly {at}"
        );
    }
}

#[test]
fn non_tileable_field_is_not_periodic() {
    let spec = GridSpec::new(64, 64, 512.0, 512.0);
    let p = params(4, 100.0, false, 7);
    let max_diff = probe_points(200, 512.0, 512.0)
        .iter()
        .map(|&(x, y)| (perlin_at(&spec, &p, x + 512.0, y) - perlin_at(&spec, &p, x, y)).abs())
        .fold(0.0f32, f32::max);
    assert!(
        max_diff > NOT_PERIODIC_MIN,
        "non-tileable field looks periodic: max diff {max_diff}"
    );
}

#[test]
fn field_agrees_with_point_evaluation() {
    for (spec, p) in [
        (
            GridSpec::new(48, 40, 512.0, 300.0),
            params(6, 100.0, true, 11),
        ),
        (
            GridSpec::new(40, 48, 333.0, 517.0),
            params(6, 41.0, false, 12),
        ),
        // Lattice finer than the samples: cells are skipped between samples.
        (
            GridSpec::new(16, 16, 512.0, 512.0),
            params(7, 40.0, true, 13),
        ),
        // Odd lacunarity and spacing: cell boundaries fall between samples irregularly.
        (
            GridSpec::new(300, 7, 1234.567, 89.0),
            PerlinParams {
                lacunarity: 1.87,
                ..params(9, 77.7, false, 14)
            },
        ),
        // Sample spacing equal to the lattice spacing, then finer lattices.
        (GridSpec::new(64, 8, 64.0, 8.0), params(3, 1.0, true, 15)),
    ] {
        assert_field_equals_point_values(&spec, &p);
    }
}

/// `perlin_field` equals `perlin_at` at every grid point, bit for bit.
fn assert_field_equals_point_values(spec: &GridSpec, p: &PerlinParams) {
    let f = perlin_field(spec, p);
    for j in 0..spec.ny {
        for i in 0..spec.nx {
            let at = perlin_at(spec, p, spec.x_m(i), spec.y_m(j));
            let g = f[j * spec.nx + i];
            assert_eq!(
                g.to_bits(),
                at.to_bits(),
                "({i}, {j}): field {g} vs perlin_at {at} for {p:?}"
            );
        }
    }
}

#[test]
fn field_agrees_with_point_evaluation_in_extreme_cases() {
    for (spec, p) in [
        // Lattice coordinates beyond 2^52 (integral f64) and far beyond i64.
        (GridSpec::new(12, 5, 1e12, 1e12), params(3, 1e-6, false, 21)),
        (GridSpec::new(9, 4, 1e30, 1e30), params(2, 1e-3, false, 22)),
        // One cell across the extent: iy and iy + 1 wrap to the same lattice row.
        (GridSpec::new(33, 17, 10.0, 10.0), params(2, 1e6, true, 23)),
        // Cells wider than the row and several cells per sample in one grid.
        (
            GridSpec::new(5, 70, 2.0, 700.0),
            params(12, 300.0, true, 24),
        ),
    ] {
        assert_field_equals_point_values(&spec, &p);
    }
}

#[test]
fn avx2_and_portable_builds_agree_bit_for_bit() {
    for (spec, p) in [
        (
            GridSpec::new(1000, 70, 1000.0, 70.0),
            params(6, 64.0, true, 31),
        ),
        (
            GridSpec::new(301, 40, 1234.567, 89.0),
            PerlinParams {
                lacunarity: 1.87,
                ..params(9, 77.7, false, 32)
            },
        ),
        (
            GridSpec::new(64, 64, 512.0, 512.0),
            params(7, 40.0, true, 33),
        ),
    ] {
        // The portable build against every build this processor runs (AVX2, AVX-512).
        let portable = perlin_field_on(Isa::Plain, &spec, &p, 0.0);
        for isa in Isa::available() {
            let fast = perlin_field_on(isa, &spec, &p, 0.0);
            for (k, (a, b)) in portable.iter().zip(&fast).enumerate() {
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "{isa:?}, index {k}: {a} vs {b} for {p:?}"
                );
            }
        }
    }
}

#[test]
fn single_octave_is_zero_at_lattice_points() {
    // dx = 1 m, λ0 = 8 m: every 8th sample is a lattice point.
    for tileable in [true, false] {
        let spec = GridSpec::new(64, 64, 64.0, 64.0);
        let p = params(1, 8.0, tileable, 5);
        let f = perlin_field(&spec, &p);
        for j in (0..64).step_by(8) {
            for i in (0..64).step_by(8) {
                let v = f[j * 64 + i];
                assert_eq!(v, 0.0, "lattice point ({i}, {j}): {v}, tileable {tileable}");
            }
        }
        assert!(f.iter().any(|&v| v.abs() > 0.1), "field is trivially zero");
    }
}

#[test]
fn deterministic_across_thread_counts_and_seed_dependent() {
    let spec = GridSpec::new(257, 131, 700.0, 350.0);
    let p = params(6, 90.0, true, 42);
    let run = |threads: usize, p: PerlinParams| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| perlin_field(&spec, &p))
    };
    let one = run(1, p);
    let two = run(2, p);
    let four = run(4, p);
    for (k, ((a, b), c)) in one.iter().zip(&two).zip(&four).enumerate() {
        assert_eq!(a.to_bits(), b.to_bits(), "index {k}: 1 thread {a} vs 2 {b}");
        assert_eq!(a.to_bits(), c.to_bits(), "index {k}: 1 thread {a} vs 4 {c}");
    }
    let other = run(2, PerlinParams { seed: 43, ..p });
    let differing = one.iter().zip(&other).filter(|(a, b)| a != b).count();
    assert!(
        differing > one.len() * 9 / 10,
        "seeds 42 and 43 differ at only {differing} of {} samples",
        one.len()
    );
}

#[test]
fn octave_cells_are_the_documented_counts() {
    let spec = GridSpec::new(64, 64, 512.0, 256.0);
    let p = params(4, 100.0, true, 0);
    // x: 512/100·2^i = 5.12, 10.24, 20.48, 40.96; y: 2.56, 5.12, 10.24, 20.48.
    assert_eq!(
        octave_cells(&spec, &p),
        vec![(5, 3), (10, 5), (20, 10), (41, 20)]
    );
    let w = octave_wavelengths(&spec, &p);
    assert_eq!(w[0], (512.0 / 5.0, 256.0 / 3.0));
    // A wavelength longer than twice the extent still gets one cell.
    let big = PerlinParams {
        wavelength_m: 5000.0,
        octaves: 2,
        ..p
    };
    assert_eq!(octave_cells(&spec, &big), vec![(1, 1), (1, 1)]);
    let free = PerlinParams {
        tileable: false,
        ..p
    };
    assert_eq!(octave_wavelengths(&spec, &free)[2], (25.0, 25.0));
}

#[test]
fn resolution_independent() {
    for tileable in [true, false] {
        let p = params(6, 70.0, tileable, 9);
        let coarse = perlin_field(&GridSpec::new(64, 64, 400.0, 400.0), &p);
        let fine = perlin_field(&GridSpec::new(128, 128, 400.0, 400.0), &p);
        for j in 0..64 {
            for i in 0..64 {
                let c = coarse[j * 64 + i];
                let f = fine[2 * j * 128 + 2 * i];
                assert!(
                    (c - f).abs() <= PERIOD_TOL,
                    "({i}, {j}): 64² gives {c}, 128² gives {f} (tileable {tileable})"
                );
            }
        }
    }
}

#[test]
fn works_far_from_the_origin() {
    let spec = GridSpec::new(8, 8, 80.0, 80.0);
    let p = params(3, 10.0, false, 1);
    for &(x, y) in &[
        (-1e9, 3e9),
        (1e12 + 0.5, -7.25e11),
        (1e17, 1e17),
        (-1e30, 5.0),
    ] {
        let v = perlin_at(&spec, &p, x, y);
        assert!((-1.0..=1.0).contains(&v), "({x}, {y}) gives {v}");
    }
    // Far away the field is still noise, not constant.
    let vals: Vec<f32> = (0..50)
        .map(|k| perlin_at(&spec, &p, 1e9 + 0.73 * k as f64, -2e9))
        .collect();
    assert!(vals.iter().any(|&v| (v - vals[0]).abs() > 1e-2), "{vals:?}");
}

#[test]
#[should_panic(expected = "persistence")]
fn invalid_params_panic() {
    let spec = GridSpec::new(8, 8, 80.0, 80.0);
    let p = PerlinParams {
        persistence: 0.0,
        ..PerlinParams::default()
    };
    perlin_field(&spec, &p);
}

/// Speed check: `cargo test --release --lib perlin -- --ignored --nocapture`.
#[test]
#[ignore]
fn speed_4096_6_octaves() {
    let spec = GridSpec::new(4096, 4096, 4096.0, 4096.0);
    let p = params(6, 256.0, true, 1);
    let per = (spec.len() * p.octaves as usize) as f64;
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut best = f64::INFINITY;
        for _ in 0..3 {
            let t = std::time::Instant::now();
            let f = pool.install(|| perlin_field(&spec, &p));
            best = best.min(t.elapsed().as_secs_f64());
            if threads == 1 {
                let st = crate::grid::Grid::new(spec, f).stats();
                println!(
                    "  min {:.3} max {:.3} mean {:.4} std {:.4}",
                    st.min_m, st.max_m, st.mean_m, st.std_m
                );
            } else {
                std::hint::black_box(f);
            }
        }
        println!(
            "{threads} thread(s): 4096² × 6 octaves in {best:.3} s, {:.2} ns/sample/octave \
             ({:.2} ns per thread)",
            best * 1e9 / per,
            best * 1e9 / per * threads as f64
        );
    }
}

/// `--sample-at centers`: the field with offset ½ is `perlin_at` at the texel centres, bit
/// for bit, and offset 0 is the corner field.
#[test]
fn centers_are_the_noise_at_the_texel_centres() {
    for (spec, p) in [
        (
            GridSpec::new(40, 48, 333.0, 517.0),
            params(6, 41.0, false, 12),
        ),
        (GridSpec::new(32, 16, 64.0, 32.0), params(4, 8.0, true, 3)),
    ] {
        assert_eq!(perlin_field_offset(&spec, &p, 0.0), perlin_field(&spec, &p));
        let f = perlin_field_offset(&spec, &p, 0.5);
        for j in 0..spec.ny {
            for i in 0..spec.nx {
                let (x, y) = (
                    (i as f64 + 0.5) * spec.dx_m(),
                    (j as f64 + 0.5) * spec.dy_m(),
                );
                let at = perlin_at(&spec, &p, x, y);
                let g = f[j * spec.nx + i];
                assert_eq!(g.to_bits(), at.to_bits(), "({i}, {j}): {g} vs {at}");
            }
        }
    }
}
