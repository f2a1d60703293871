//! noise-rs generators as the noise field: a source (`perlin`, `open-simplex`,
//! `super-simplex`, `value`, `worley`) under one of noise-rs's fractal combinators (`fbm`,
//! `billow`, `ridged-multi`, `hybrid-multi`), with the octaves, persistence, lacunarity
//! and wavelength of the builtin kernel.
//!
//! **Coordinates.** Sample `(i, j)` is the fractal at the point `(x_m, y_m)` in meters,
//! with the fractal's frequency `1/λ0` (so λ0 is the lattice spacing of the first octave,
//! as for the builtin kernel): the field does not depend on the grid's resolution.
//!
//! **Tileable.** With `tileable`, the 2D point is mapped onto a 4D torus,
//! `(Rx cos θx, Rx sin θx, Ry cos θy, Ry sin θy)` with `θx = 2π x/Lx`, `Rx = Lx/2π` (and
//! the same for y), and the 4D form of the fractal is sampled there: every octave is then
//! periodic over the extent, whatever λ0. Arc length along each circle is x itself, so
//! features keep their size along the axes; the cost is the 4D source (16 lattice corners
//! for Perlin instead of 4: `seasynth bench` gives the figures). SuperSimplex has no 4D
//! form and is not tileable.
//!
//! **Normalization.** noise-rs's fractals divide their octave sum by the sum of their
//! amplitudes, which puts them near [−1, 1] but does not bound them (a source may exceed
//! its nominal range slightly, and ridged and hybrid multifractals weight octaves by one
//! another). The field is that value clamped into [−1, 1], as Li Tian's eq. 9 assumes:
//! `field = clamp(fractal(point), −1, 1)` in f32, nothing else.
//!
//! **Seed.** noise-rs takes a 32-bit seed and gives octave `i` the seed `s + i`; `s` is the
//! low 31 bits of the Perlin stream's sub-seed (so `s + i` cannot overflow).
//!
//! **Determinism.** Each band of rows builds its own generator (noise-rs's Worley holds an
//! `Rc`, so generators are not shared between threads); a sample is the same function of
//! its point whatever the band, so the field is the same at any thread count.

use noise::{
    Billow, Fbm, HybridMulti, MultiFractal, NoiseFn, OpenSimplex, Perlin, RidgedMulti, Seedable,
    SuperSimplex, Value, Worley,
};
use rayon::prelude::*;

use super::PerlinParams;
use crate::config::{NoiseBasis, NoiseFractal};
use crate::grid::GridSpec;

/// The noise-rs seed of `p` (see the module docs).
pub fn seed32(p: &PerlinParams) -> u32 {
    (p.seed & 0x7FFF_FFFF) as u32
}

/// A fractal of source `T` with `p`'s octaves, frequency 1/λ0, lacunarity and persistence.
fn configured<F: MultiFractal + Seedable>(f: F, p: &PerlinParams) -> F {
    f.set_octaves(p.octaves as usize)
        .set_frequency(1.0 / p.wavelength_m)
        .set_lacunarity(p.lacunarity)
        .set_persistence(p.persistence)
}

/// `fractal` over source `T`, as a boxed `D`-dimensional noise function.
macro_rules! fractal_of {
    ($T:ty, $fractal:expr, $p:expr, $D:literal) => {{
        let seed = seed32($p);
        let b: Box<dyn NoiseFn<f64, $D>> = match $fractal {
            NoiseFractal::Fbm => Box::new(configured(Fbm::<$T>::new(seed), $p)),
            NoiseFractal::Billow => Box::new(configured(Billow::<$T>::new(seed), $p)),
            NoiseFractal::RidgedMulti => Box::new(configured(RidgedMulti::<$T>::new(seed), $p)),
            NoiseFractal::HybridMulti => Box::new(configured(HybridMulti::<$T>::new(seed), $p)),
        };
        b
    }};
}

/// The 2D fractal of `basis` (None for `builtin`).
pub fn fractal2(
    basis: NoiseBasis,
    fractal: NoiseFractal,
    p: &PerlinParams,
) -> Option<Box<dyn NoiseFn<f64, 2>>> {
    Some(match basis {
        NoiseBasis::Builtin => return None,
        NoiseBasis::Perlin => fractal_of!(Perlin, fractal, p, 2),
        NoiseBasis::OpenSimplex => fractal_of!(OpenSimplex, fractal, p, 2),
        NoiseBasis::SuperSimplex => fractal_of!(SuperSimplex, fractal, p, 2),
        NoiseBasis::Value => fractal_of!(Value, fractal, p, 2),
        NoiseBasis::Worley => fractal_of!(Worley, fractal, p, 2),
    })
}

/// The 4D fractal of `basis` (None for `builtin` and `super-simplex`, which has no 4D form).
pub fn fractal4(
    basis: NoiseBasis,
    fractal: NoiseFractal,
    p: &PerlinParams,
) -> Option<Box<dyn NoiseFn<f64, 4>>> {
    Some(match basis {
        NoiseBasis::Builtin | NoiseBasis::SuperSimplex => return None,
        NoiseBasis::Perlin => fractal_of!(Perlin, fractal, p, 4),
        NoiseBasis::OpenSimplex => fractal_of!(OpenSimplex, fractal, p, 4),
        NoiseBasis::Value => fractal_of!(Value, fractal, p, 4),
        NoiseBasis::Worley => fractal_of!(Worley, fractal, p, 4),
    })
}

/// The point on the 4D torus of coordinate `c` over extent `l`: `(R cos θ, R sin θ)`.
pub fn circle(c: f64, l: f64) -> [f64; 2] {
    let r = l / std::f64::consts::TAU;
    let (s, co) = crate::fastmath::sin_cos(c / l * std::f64::consts::TAU);
    [r * co, r * s]
}

/// Target number of samples per parallel band of rows.
const BAND_SAMPLES: usize = 1 << 14;

/// The noise-rs field over the grid, row-major, in [−1, 1] (see the module docs), sample
/// (i, j) at ((i + offset)·dx, (j + offset)·dy): offset ½ for texel centres.
/// Panics for `builtin`, or `super-simplex` with `tileable` (refused by validation).
pub fn noise_rs_field(
    spec: &GridSpec,
    p: &PerlinParams,
    offset: f64,
    basis: NoiseBasis,
    fractal: NoiseFractal,
) -> Vec<f32> {
    let nx = spec.nx;
    let mut out = vec![0.0f32; spec.len()];
    if out.is_empty() {
        return out;
    }
    let band_rows = (BAND_SAMPLES / nx).clamp(1, 64);
    let (dx, dy) = (spec.dx_m(), spec.dy_m());
    if p.tileable {
        let cols: Vec<[f64; 2]> = (0..nx)
            .map(|i| circle(spec.x_m(i) + offset * dx, spec.extent_x_m))
            .collect();
        out.par_chunks_mut(nx * band_rows)
            .enumerate()
            .for_each(|(b, band)| {
                let f = fractal4(basis, fractal, p).expect("a basis with a 4D form");
                for (r, row) in band.chunks_mut(nx).enumerate() {
                    let [z, w] = circle(spec.y_m(b * band_rows + r) + offset * dy, spec.extent_y_m);
                    for (o, [x, y]) in row.iter_mut().zip(&cols) {
                        *o = f.get([*x, *y, z, w]).clamp(-1.0, 1.0) as f32;
                    }
                }
            });
    } else {
        out.par_chunks_mut(nx * band_rows)
            .enumerate()
            .for_each(|(b, band)| {
                let f = fractal2(basis, fractal, p).expect("a noise-rs basis");
                for (r, row) in band.chunks_mut(nx).enumerate() {
                    let y = spec.y_m(b * band_rows + r) + offset * dy;
                    for (i, o) in row.iter_mut().enumerate() {
                        *o = f.get([spec.x_m(i) + offset * dx, y]).clamp(-1.0, 1.0) as f32;
                    }
                }
            });
    }
    out
}

/// The same value at one point (x_m, y_m) in meters.
pub fn noise_rs_at(
    spec: &GridSpec,
    p: &PerlinParams,
    basis: NoiseBasis,
    fractal: NoiseFractal,
    x_m: f64,
    y_m: f64,
) -> f32 {
    let v = if p.tileable {
        let [x, y] = circle(x_m, spec.extent_x_m);
        let [z, w] = circle(y_m, spec.extent_y_m);
        fractal4(basis, fractal, p)
            .expect("a basis with a 4D form")
            .get([x, y, z, w])
    } else {
        fractal2(basis, fractal, p)
            .expect("a noise-rs basis")
            .get([x_m, y_m])
    };
    v.clamp(-1.0, 1.0) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(tileable: bool) -> PerlinParams {
        PerlinParams {
            octaves: 4,
            persistence: 0.5,
            lacunarity: 2.0,
            wavelength_m: 23.0,
            tileable,
            seed: 0x1234_5678_9ABC_DEF0,
        }
    }

    const BASES: [NoiseBasis; 5] = [
        NoiseBasis::Perlin,
        NoiseBasis::OpenSimplex,
        NoiseBasis::SuperSimplex,
        NoiseBasis::Value,
        NoiseBasis::Worley,
    ];

    #[test]
    fn the_field_is_noise_rs_own_fractal_at_the_sample_points() {
        let spec = GridSpec::new(24, 16, 96.0, 40.0);
        let p = params(false);
        let seed = seed32(&p);
        // The fractals built here by hand, as noise-rs's documentation shows them.
        let fbm = Fbm::<Perlin>::new(seed)
            .set_octaves(4)
            .set_frequency(1.0 / 23.0)
            .set_lacunarity(2.0)
            .set_persistence(0.5);
        let ridged = RidgedMulti::<Worley>::new(seed)
            .set_octaves(4)
            .set_frequency(1.0 / 23.0)
            .set_lacunarity(2.0)
            .set_persistence(0.5);
        for (basis, fractal, f) in [
            (
                NoiseBasis::Perlin,
                NoiseFractal::Fbm,
                &fbm as &dyn NoiseFn<f64, 2>,
            ),
            (NoiseBasis::Worley, NoiseFractal::RidgedMulti, &ridged),
        ] {
            let field = noise_rs_field(&spec, &p, 0.0, basis, fractal);
            let mut nonzero = 0;
            for j in 0..spec.ny {
                for i in 0..spec.nx {
                    let want = f.get([spec.x_m(i), spec.y_m(j)]).clamp(-1.0, 1.0) as f32;
                    let got = field[j * spec.nx + i];
                    assert_eq!(got.to_bits(), want.to_bits(), "{basis:?} ({i}, {j})");
                    nonzero += usize::from(got != 0.0);
                }
            }
            assert!(nonzero > spec.len() / 2, "{basis:?}: a field, not zeros");
        }
        // Tileable: the 4D fractal at the torus point.
        let p = params(true);
        let fbm4 = Fbm::<Value>::new(seed)
            .set_octaves(4)
            .set_frequency(1.0 / 23.0)
            .set_lacunarity(2.0)
            .set_persistence(0.5);
        let field = noise_rs_field(&spec, &p, 0.0, NoiseBasis::Value, NoiseFractal::Fbm);
        let (i, j) = (5, 11);
        let (x, y) = (spec.x_m(i), spec.y_m(j));
        let (r, t) = (
            96.0 / std::f64::consts::TAU,
            x / 96.0 * std::f64::consts::TAU,
        );
        let (rz, tz) = (
            40.0 / std::f64::consts::TAU,
            y / 40.0 * std::f64::consts::TAU,
        );
        let want = fbm4.get([r * t.cos(), r * t.sin(), rz * tz.cos(), rz * tz.sin()]);
        assert!(
            (field[j * spec.nx + i] as f64 - want).abs() < 1e-6,
            "{} vs {want}",
            field[j * spec.nx + i]
        );
    }

    #[test]
    fn every_basis_and_fractal_stays_in_the_unit_interval_and_varies() {
        let spec = GridSpec::new(32, 32, 200.0, 200.0);
        for basis in BASES {
            for fractal in NoiseFractal::ALL {
                let p = params(basis != NoiseBasis::SuperSimplex);
                let f = noise_rs_field(&spec, &p, 0.0, basis, fractal);
                let (lo, hi) = f
                    .iter()
                    .fold((f32::MAX, f32::MIN), |(a, b), &v| (a.min(v), b.max(v)));
                assert!(lo >= -1.0 && hi <= 1.0, "{basis:?} {fractal:?}: {lo}..{hi}");
                assert!(hi - lo > 0.05, "{basis:?} {fractal:?}: flat {lo}..{hi}");
            }
        }
    }

    #[test]
    fn tileable_fields_are_periodic_over_the_extent() {
        let spec = GridSpec::new(16, 12, 64.0, 48.0);
        for basis in [
            NoiseBasis::Perlin,
            NoiseBasis::OpenSimplex,
            NoiseBasis::Value,
            NoiseBasis::Worley,
        ] {
            let p = params(true);
            for (x, y) in [(0.0, 0.0), (3.7, 11.2), (63.0, 47.5)] {
                let a = noise_rs_at(&spec, &p, basis, NoiseFractal::Fbm, x, y);
                let b = noise_rs_at(&spec, &p, basis, NoiseFractal::Fbm, x + 64.0, y - 48.0);
                let c = noise_rs_at(&spec, &p, basis, NoiseFractal::Fbm, x - 128.0, y + 96.0);
                // Only the rounding of cos and sin of θ and θ ± 2π differ.
                assert!(
                    (a - b).abs() < 1e-5 && (a - c).abs() < 1e-5,
                    "{basis:?} ({x}, {y}): {a} {b} {c}"
                );
            }
            let field = noise_rs_field(&spec, &p, 0.0, basis, NoiseFractal::Fbm);
            assert_eq!(
                field[5 * 16 + 3],
                noise_rs_at(
                    &spec,
                    &p,
                    basis,
                    NoiseFractal::Fbm,
                    spec.x_m(3),
                    spec.y_m(5)
                )
            );
        }
    }

    #[test]
    fn the_field_is_the_same_at_any_thread_count() {
        let spec = GridSpec::new(300, 70, 300.0, 70.0);
        for tileable in [false, true] {
            let p = params(tileable);
            let run = |threads: usize| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap()
                    .install(|| {
                        noise_rs_field(&spec, &p, 0.0, NoiseBasis::Worley, NoiseFractal::Billow)
                    })
            };
            let one = run(1);
            assert!(one == run(4), "tileable {tileable}");
        }
    }
}
