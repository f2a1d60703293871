//! The grid passes and the near-peak cells against the double-precision spectrum, on
//! every instruction set.

use super::*;

fn all_seas() -> Vec<(String, DirectionalSpectrum)> {
    let mut all = Vec::new();
    for (name, make, disp) in seas() {
        for model in MODELS {
            for swell in [0.0, 1.5] {
                let s = sea(&make, model, swell, 0.7, disp);
                all.push((format!("{name} {model:?} swell {swell}"), s));
            }
        }
    }
    all
}

#[test]
fn grid_values_match_the_double_precision_spectrum() {
    // |P/P_ref − 1| ≤ TOL·(1 + |log2(P_ref/P_peak)|) for every cell above 2^−250 of the
    // peak: the single-precision exponent's rounding grows with its magnitude.
    const TOL: f64 = 1e-6;
    const CUT_LOG2: f64 = -250.0;
    let mut fast = 0;
    for (name, s) in all_seas() {
        fast += s.kern.fast.is_some() as usize;
        // The peak on ~12 cells, and the far tail (k up to 50 kp).
        for span in [12.0, 1.0] {
            let n = 96;
            let dk = s.peak_wavenumber() / span;
            let (mut worst, mut peak) = (0.0f64, 0.0f64);
            // The worst relative error within one octave of the peak, for the report.
            let mut near_peak = 0.0f64;
            let mut cells = Vec::new();
            for i in 0..n {
                for j in 0..n {
                    let (kx, ky) = (
                        signed_index(i, n) as f64 * dk,
                        signed_index(j, n) as f64 * 1.3 * dk,
                    );
                    let want = 0.5 * s.psi(kx, ky) * dk * (1.3 * dk);
                    let got = s.kern.grid_variance(kx, ky, dk, 1.3 * dk, s.freq());
                    peak = peak.max(want);
                    cells.push((got, want, kx, ky));
                }
            }
            for (got, want, kx, ky) in cells {
                let level = (want / peak).log2();
                if level < CUT_LOG2 {
                    assert!(
                        got <= peak * (CUT_LOG2 + 10.0).exp2(),
                        "{name} at ({kx}, {ky}): {got:e} where Ψ gives {want:e}"
                    );
                    continue;
                }
                let err = (got / want - 1.0).abs() / (1.0 + level.abs());
                worst = worst.max(err);
                if level > -1.0 {
                    near_peak = near_peak.max((got / want - 1.0).abs());
                }
                assert!(
                    err < TOL,
                    "{name} at ({kx}, {ky}): {got:e} vs {want:e} (2^{level:.1} of the peak)"
                );
            }
            eprintln!(
                "{name}, peak on {span} cells: worst {worst:.2e}, within an octave of the peak {near_peak:.2e}"
            );
        }
    }
    assert!(fast >= 8, "only {fast} seas took the fast radial lane");
}

#[test]
fn grid_lines_equal_single_values_on_every_instruction_set() {
    for (name, s) in all_seas() {
        let dk = s.peak_wavenumber() / 7.0;
        for n in [64usize, 63, 10] {
            // FFT order (mirrored) and a plain ascending line.
            let fft: Vec<f64> = (0..n).map(|j| signed_index(j, n) as f64 * dk).collect();
            let plain: Vec<f64> = (0..n).map(|j| (j as f64 - 20.0) * 0.9 * dk).collect();
            for ky in [&fft, &plain] {
                for kx in [0.0, 3.0 * dk, -11.0 * dk, 40.0 * dk] {
                    for isa in crate::simd::Isa::available() {
                        let (mut pa, mut pb) = (vec![0.0; n], vec![0.0; n]);
                        let mut scratch = grid::GridScratch::default();
                        let q = LineQuery {
                            kx,
                            ky,
                            dkx: dk,
                            dky: 1.3 * dk,
                        };
                        let out = PairOut {
                            a: &mut pa,
                            b: &mut pb,
                        };
                        s.kern
                            .grid_pair_line_on(isa, s.freq(), &q, out, &mut scratch);
                        for j in 0..n {
                            for (got, x, y) in [(pa[j], kx, ky[j]), (pb[j], -kx, -ky[j])] {
                                let want = s.kern.grid_variance(x, y, dk, 1.3 * dk, s.freq());
                                assert_eq!(
                                    got.to_bits(),
                                    want.to_bits(),
                                    "{name} {isa:?} at ({x}, {y}): line {got:e}, single {want:e}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn batched_near_peak_cells_equal_the_cell_rule_bit_for_bit_on_every_instruction_set() {
    use crate::simd::Isa;
    // Lines of a grid whose peak spans 4.5 cells (kx from 0 to beyond the near zone, ky
    // in FFT order and in a line without mirrored entries, odd and even lengths), and
    // of a grid so fine (kp = 600 Δk) that cells at the peak take the midpoint.
    const MIN_NEAR: usize = 300;
    const COARSE: f64 = 4.5;
    const FINE: f64 = 600.0;
    let fft_line = |n: usize, dk: f64| -> Vec<f64> {
        (0..n).map(|j| signed_index(j, n) as f64 * dk).collect()
    };
    let mut scratch = cells::CellScratch::default();
    for (name, make, disp) in seas() {
        for model in MODELS {
            for swell in [0.0, 1.0] {
                let s = sea(make.as_ref(), model, swell, 0.6, disp);
                let kp = s.peak_wavenumber();
                let mut cases: Vec<(f64, Vec<f64>, f64, f64)> = Vec::new();
                let dk = kp / COARSE;
                let shifted: Vec<f64> = (0..41).map(|j| (j as f64 - 20.3) * 1.3 * dk).collect();
                for m in [0, 1, 2, 3, 5, 8, 11, 15, 20, 27, 35, 45, 60] {
                    let kx = m as f64 * dk;
                    cases.push((kx, fft_line(64, 1.3 * dk), dk, 1.3 * dk));
                    cases.push((-kx, fft_line(63, 1.3 * dk), dk, 1.3 * dk));
                    cases.push((kx, shifted.clone(), dk, 1.3 * dk));
                }
                let dk = kp / FINE;
                for m in [600, 750] {
                    cases.push((m as f64 * dk, fft_line(64, 1.3 * dk), dk, 1.3 * dk));
                }
                let (mut near, mut far, mut midpoint) = (0, 0, 0);
                for (kx, ky, dkx, dky) in &cases {
                    let (kx, n) = (*kx, ky.len());
                    let h = dkx.max(*dky);
                    // The reference: 0.5·cell_integral of the near cells that take a
                    // Gauss–Legendre rule; NaN (left as it was) at the midpoint cells,
                    // far or 1 × 1.
                    let want: Vec<(f64, f64)> = ky
                        .iter()
                        .map(|&y| {
                            if s.kern.is_far(kx * kx + y * y, h) {
                                return (f64::NAN, f64::NAN);
                            }
                            if s.cell_orders(kx, y, *dkx, *dky) == (1, 1) {
                                midpoint += 1;
                                return (f64::NAN, f64::NAN);
                            }
                            (
                                0.5 * s.cell_integral(kx, y, *dkx, *dky),
                                0.5 * s.cell_integral(-kx, -y, *dkx, *dky),
                            )
                        })
                        .collect();
                    let near_here = want.iter().filter(|w| !w.0.is_nan()).count();
                    near += 2 * near_here;
                    far += 2 * (n - near_here);
                    for isa in Isa::available() {
                        let (mut pa, mut pb) = (vec![f64::NAN; n], vec![f64::NAN; n]);
                        let q = LineQuery {
                            kx,
                            ky,
                            dkx: *dkx,
                            dky: *dky,
                        };
                        let out = PairOut {
                            a: &mut pa,
                            b: &mut pb,
                        };
                        s.kern
                            .near_cells_pair_line_on(isa, s.freq(), &q, out, &mut scratch);
                        for j in 0..n {
                            for (got, w, sign) in
                                [(pa[j], want[j].0, 1.0), (pb[j], want[j].1, -1.0)]
                            {
                                assert_eq!(
                                    got.to_bits(),
                                    w.to_bits(),
                                    "{name} {model:?} ξ {swell} {isa:?}: cell ({}, {}) of Δk ({dkx}, {dky}): batched {got}, cell rule {w}",
                                    sign * kx,
                                    sign * ky[j]
                                );
                            }
                        }
                    }
                }
                assert!(
                    near >= MIN_NEAR && far > 0 && midpoint > 0,
                    "{name} {model:?} ξ {swell}: {near} near cells ({midpoint} by the midpoint), {far} far"
                );
            }
        }
    }
}

#[test]
fn batched_near_peak_cells_keep_the_cell_rule_when_the_nodes_are_not_symmetric() {
    // The batch reuses a node's radial part for its reflections only where their k²
    // are equal bit for bit: with rules whose nodes are not exactly symmetric (every
    // first node moved by 1e-9 of itself) the values still equal the cell rule's.
    const SHIFT: f64 = 1e-9;
    let make = || -> Box<dyn FrequencySpectrum> {
        Box::new(Jonswap::from_wind_fetch(11.0, 60e3, 3.3).unwrap())
    };
    for model in [SpreadingModel::Hasselmann, SpreadingModel::DonelanBanner] {
        let mut s = sea(&make, model, 0.5, 0.3, Dispersion::Deep);
        for rule in s.kern.rules.iter_mut().skip(1) {
            rule[0].0 *= 1.0 + SHIFT;
        }
        let dk = s.peak_wavenumber() / 4.5;
        let n = 48;
        let ky: Vec<f64> = (0..n).map(|j| signed_index(j, n) as f64 * dk).collect();
        let mut checked = 0;
        for m in [0, 1, 2, 3, 5, 7, 9] {
            let kx = m as f64 * dk;
            let (mut pa, mut pb) = (vec![f64::NAN; n], vec![f64::NAN; n]);
            let q = LineQuery {
                kx,
                ky: &ky,
                dkx: dk,
                dky: dk,
            };
            let out = PairOut {
                a: &mut pa,
                b: &mut pb,
            };
            s.amplitude_variance_pair_line(&q, out);
            for j in 0..n {
                if s.kern.is_far(kx * kx + ky[j] * ky[j], dk) {
                    continue;
                }
                for (got, (x, y)) in [(pa[j], (kx, ky[j])), (pb[j], (-kx, -ky[j]))] {
                    let want = 0.5 * s.cell_integral(x, y, dk, dk);
                    assert_eq!(
                        got.to_bits(),
                        want.to_bits(),
                        "{model:?} at ({x}, {y}): batched {got}, cell rule {want}"
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 500, "{model:?}: only {checked} cells checked");
    }
}
