//! Phillips spectrum in Tessendorf's discrete convention (Li Tian eq. 7–8):
//!
//! P(k) = A · exp(−1/(kL)²) / k⁴ · |k̂·ŵ|² · exp(−k²l²),   L = V²/g,
//!
//! where `A` multiplies the discrete Fourier amplitudes directly (so the papers' values of
//! `A` reproduce their figures, and the field's variance grows with the extent), ŵ is the
//! unit wind direction, V the wind speed and l the small-wave cutoff length.

use super::{G, LineQuery, PairOut, Spectrum};
use crate::fastmath;
use crate::simd::{Isa, exp_line_on};
use crate::spectrum::mirror::{fft_mirrored, mirror_f64_on};

/// A validated Phillips spectrum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Phillips {
    a: f64,
    big_l_m: f64,
    small_l_m: f64,
    wind_dir: (f64, f64),
    /// The instruction set of the line passes, chosen when the model is built.
    isa: Isa,
}

impl Phillips {
    /// `a` > 0 (m²·rad⁴/m⁴, discrete convention), wind speed > 0 m/s, direction in radians
    /// (0 toward +x), small-wave cutoff `small_wave_m` ≥ 0 (0 disables eq. 8).
    /// Parameters are validated where they are resolved (see `config`).
    pub fn new(a: f64, wind_speed_mps: f64, wind_dir_rad: f64, small_wave_m: f64) -> Self {
        Self {
            a,
            big_l_m: wind_speed_mps * wind_speed_mps / G,
            small_l_m: small_wave_m,
            wind_dir: (wind_dir_rad.cos(), wind_dir_rad.sin()),
            isa: Isa::detect(),
        }
    }

    /// The largest wave arising from a continuous wind, L = V²/g, in meters.
    pub fn largest_wave_m(&self) -> f64 {
        self.big_l_m
    }

    /// P(k) at wavevector `(kx, ky)`; 0 at k = 0.
    #[inline]
    pub fn value(&self, kx: f64, ky: f64) -> f64 {
        let k2 = kx * kx + ky * ky;
        if k2 == 0.0 {
            return 0.0;
        }
        let kl2 = k2 * self.big_l_m * self.big_l_m;
        let cos = (kx * self.wind_dir.0 + ky * self.wind_dir.1) / k2.sqrt();
        let damping = if self.small_l_m > 0.0 {
            fastmath::exp(-k2 * self.small_l_m * self.small_l_m)
        } else {
            1.0
        };
        self.a * fastmath::exp(-1.0 / kl2) / (k2 * k2) * (cos * cos) * damping
    }
}

/// The exponentials of a line (see [`Phillips::line`]).
#[derive(Debug, Default)]
struct LineScratch {
    arg: Vec<f64>,
    e1: Vec<f64>,
    e2: Vec<f64>,
}

thread_local! {
    /// Buffers of the line evaluation, one set per thread.
    static SCRATCH: std::cell::RefCell<LineScratch> =
        std::cell::RefCell::new(LineScratch::default());
}

impl Phillips {
    /// P over a line: the same operations as [`Phillips::value`], in passes that
    /// vectorize: the exponents and exponentials once per distinct k² (a line in FFT order
    /// repeats them mirrored), then the products in `value`'s order.
    fn line(&self, kx: f64, ky: &[f64], out: &mut [f64], s: &mut LineScratch) {
        let n = ky.len().min(out.len());
        let (ky, out) = (&ky[..n], &mut out[..n]);
        let isa = self.isa;
        let unique = if fft_mirrored(ky) { n / 2 + 1 } else { n };
        let LineScratch { arg, e1, e2 } = s;
        for v in [&mut *arg, &mut *e1, &mut *e2] {
            v.resize(n, 0.0);
        }
        for (a, &y) in arg[..unique].iter_mut().zip(ky) {
            let k2 = kx * kx + y * y;
            *a = -1.0 / (k2 * self.big_l_m * self.big_l_m);
        }
        exp_line_on(isa, &arg[..unique], &mut e1[..unique]);
        if self.small_l_m > 0.0 {
            for (a, &y) in arg[..unique].iter_mut().zip(ky) {
                let k2 = kx * kx + y * y;
                *a = -k2 * self.small_l_m * self.small_l_m;
            }
            exp_line_on(isa, &arg[..unique], &mut e2[..unique]);
        } else {
            e2[..unique].fill(1.0);
        }
        if unique < n {
            mirror_f64_on(isa, e1, unique);
            mirror_f64_on(isa, e2, unique);
        }
        for (i, (o, &y)) in out.iter_mut().zip(ky).enumerate() {
            let k2 = kx * kx + y * y;
            let cos = (kx * self.wind_dir.0 + y * self.wind_dir.1) / k2.sqrt();
            let v = self.a * e1[i] / (k2 * k2) * (cos * cos) * e2[i];
            *o = if k2 == 0.0 { 0.0 } else { v };
        }
    }
}

impl Spectrum for Phillips {
    fn amplitude_variance(&self, kx: f64, ky: f64, _dkx: f64, _dky: f64) -> f64 {
        self.value(kx, ky)
    }

    fn amplitude_variance_line(&self, q: &LineQuery, out: &mut [f64]) {
        SCRATCH.with(|cell| match cell.try_borrow_mut() {
            Ok(mut scratch) => self.line(q.kx, q.ky, out, &mut scratch),
            Err(_) => self.line(q.kx, q.ky, out, &mut LineScratch::default()),
        });
    }

    /// P(−k) = P(k) exactly: k² is the same and cos changes sign only, so its square is
    /// the same number.
    fn amplitude_variance_pair_line(&self, q: &LineQuery, out: PairOut<f64>) {
        self.amplitude_variance_line(q, out.a);
        out.b.copy_from_slice(out.a);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const REL_TOL: f64 = 1e-12;

    #[test]
    fn matches_the_formula_at_hand_picked_wavevectors() {
        let p = Phillips::new(2.0, 7.0, 0.0, 0.5);
        let big_l = 49.0 / G;
        // Along the wind, k = 0.2: cos = 1.
        let k: f64 = 0.2;
        let want = 2.0 * (-1.0 / (k * big_l).powi(2)).exp() / k.powi(4) * (-k * k * 0.25).exp();
        assert!((p.value(k, 0.0) - want).abs() <= REL_TOL * want);
        // At 60° to the wind the directional factor is cos² 60° = 1/4.
        let (kx, ky) = (k * 0.5, k * 3f64.sqrt() / 2.0);
        assert!((p.value(kx, ky) - want / 4.0).abs() <= REL_TOL * want);
        // Across the wind there is no energy, and none at k = 0.
        assert!(p.value(0.0, k).abs() < 1e-30);
        assert_eq!(p.value(0.0, 0.0), 0.0);
    }

    #[test]
    fn the_line_evaluation_equals_the_single_values_bit_for_bit() {
        // A plain line, and lines in FFT order (even and odd lengths), whose mirrored half
        // reuses the exponentials.
        let plain: Vec<f64> = (-40..40).map(|m| (m as f64 + 0.3) * 0.0123).collect();
        let fft = |n: usize| -> Vec<f64> {
            (0..n)
                .map(|j| crate::field::fft::signed_index(j, n) as f64 * 0.0123)
                .collect()
        };
        let mirrored = crate::spectrum::mirror::fft_mirrored;
        assert!(mirrored(&fft(64)) && mirrored(&fft(63)) && !mirrored(&plain));
        for l in [0.0, 0.7] {
            let p = Phillips::new(3e-7, 13.0, 0.9, l);
            for (ky, kx) in [plain.clone(), fft(64), fft(63), fft(2)]
                .into_iter()
                .flat_map(|ky| [0.0, 0.0123, -0.5, 3.0].map(|kx| (ky.clone(), kx)))
            {
                let mut out = vec![0.0; ky.len()];
                let q = LineQuery {
                    kx,
                    ky: &ky,
                    dkx: 0.0,
                    dky: 0.0,
                };
                p.amplitude_variance_line(&q, &mut out);
                for (i, (&o, &y)) in out.iter().zip(&ky).enumerate() {
                    let want = p.value(kx, y);
                    assert!(
                        o.to_bits() == want.to_bits(),
                        "l={l} kx={kx} ky[{i}]={y}: {o} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_mirror_line_equals_the_single_values_bit_for_bit() {
        let p = Phillips::new(3e-7, 13.0, 0.9, 0.7);
        let ky: Vec<f64> = (-40..40).map(|m| m as f64 * 0.0123).collect();
        let (mut pa, mut pb) = (vec![0.0; ky.len()], vec![0.0; ky.len()]);
        for kx in [0.0, 0.0123, -0.5, 3.0] {
            let q = LineQuery {
                kx,
                ky: &ky,
                dkx: 0.0,
                dky: 0.0,
            };
            let out = PairOut {
                a: &mut pa,
                b: &mut pb,
            };
            p.amplitude_variance_pair_line(&q, out);
            for (i, &y) in ky.iter().enumerate() {
                assert_eq!(pa[i].to_bits(), p.value(kx, y).to_bits(), "kx={kx} ky={y}");
                assert_eq!(
                    pb[i].to_bits(),
                    p.value(-kx, -y).to_bits(),
                    "-kx={kx} -ky={y}"
                );
            }
        }
    }

    #[test]
    fn wind_direction_rotates_the_spectrum() {
        let p = Phillips::new(1.0, 10.0, std::f64::consts::FRAC_PI_2, 0.0);
        let q = Phillips::new(1.0, 10.0, 0.0, 0.0);
        let want = q.value(0.3, 0.0);
        assert!((p.value(0.0, 0.3) - want).abs() <= REL_TOL * want);
        assert!((p.value(0.0, -0.3) - want).abs() <= REL_TOL * want);
    }

    #[test]
    fn is_finite_and_non_negative_over_a_wide_range() {
        let p = Phillips::new(3e-7, 50.0, 0.7, 0.0);
        for i in -50..50 {
            for j in -50..50 {
                let v = p.value(i as f64 * 0.37, j as f64 * 0.011);
                assert!(v.is_finite() && v >= 0.0, "P({i}, {j}) = {v}");
            }
        }
    }
}
