//! The evaluation kernel of a directional sea: the model folded into the radial part a(|k|)
//! and the directional part m(θ)·cos^{2s}(θ/2) of Ψ, and the cell rule's orders (see the
//! parent module's docs).

use super::spread_table::SpreadTable;
use super::{
    C_HIGH, C_LOW, FrequencySpectrum, G, MAX_CELL_ORDER, MIDPOINT_RATIO, PI, POWER_EXPONENT_MIN,
    TAIL_SCALE, TWO_PI, U_MAX, atan2_pos, half_one_plus, kitaigorodskii, ln_half_one_plus, sech2,
    tanh,
};
use crate::fastmath::{exp, ln};

/// The JONSWAP-family frequency part, folded for the kernel.
#[derive(Debug, Clone, Copy)]
pub(super) struct ShapeK {
    /// A (2π)⁴.
    pub(super) coef: f64,
    /// 1/ωp⁴ of the shape.
    pub(super) inv_wp4: f64,
    pub(super) ln_gamma: f64,
    /// ωp √(d/g): ω_h = (ω/ωp)·this; ∞ without a depth factor.
    pub(super) tma_h: f64,
    /// ln(ω_peak/ωp): the spreading's x = ln(ω/ωp) − this.
    pub(super) x_shift: f64,
}

/// How the spreading factor is evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum SpreadKind {
    /// cos²θ/π (no per-frequency quantities).
    Cos2Plain,
    /// cos²θ · cos^{2s}(θ/2) / Z_cos2(s) (Cos2 with swell).
    Cos2Swell,
    /// cos^{2s}(θ/2) / N_s (Hasselmann, Mitsuyasu, with or without swell).
    Family,
    /// sech²(βθ) · cos^{2s}(θ/2) / Z(β, s).
    DonelanBanner,
}

#[derive(Debug, Clone)]
pub(super) struct Kernel {
    pub(super) wx: f64,
    pub(super) wy: f64,
    /// Dispersion depth, m (∞: deep).
    pub(super) depth: f64,
    pub(super) shape: Option<ShapeK>,
    /// ln ω_peak (for models without a shape).
    pub(super) ln_w_peak: f64,
    pub(super) kind: SpreadKind,
    pub(super) table: SpreadTable,
    // Cell rule.
    pub(super) zone_k: f64,
    pub(super) zone2: f64,
    pub(super) ell_peak: f64,
    pub(super) sigma_theta: f64,
    pub(super) far_c2: f64,
    /// Gauss–Legendre rules of orders 1..=MAX_CELL_ORDER: (node in (−½, ½), weight), Σw = 1.
    pub(super) rules: Vec<Vec<(f64, f64)>>,
    /// log2 of the radial part at the peak wavenumber (0 if it is 0 there): the reference
    /// of the grid's single-precision exponents (see `grid`).
    pub(super) grid_l0: f64,
    /// The grid's single-precision radial lane, for the seas it covers.
    pub(super) fast: Option<super::fast_radial::FastRadial>,
}

impl Kernel {
    #[inline]
    pub(super) fn order(&self, k: f64, h: f64) -> usize {
        let ell_r = if k < self.zone_k {
            self.ell_peak
        } else {
            TAIL_SCALE * k
        };
        let m = h / ell_r.min(k * self.sigma_theta);
        if m.is_nan() || m <= MIDPOINT_RATIO {
            // (NaN: a zero-size cell at k = 0.)
            1
        } else {
            ((2.0 + 1.2 * m).ceil() as usize).min(MAX_CELL_ORDER)
        }
    }

    /// The part of Ψ that depends on |k| only.
    #[inline(always)]
    pub(super) fn radial(&self, k2: f64, freq: &dyn FrequencySpectrum) -> Radial {
        if !(k2 > 0.0 && k2 < f64::INFINITY) {
            return Radial::ZERO;
        }
        let k = k2.sqrt();
        // ω² and c_g/(k ω⁵).
        let (w2, geo) = if self.depth == f64::INFINITY {
            let w2 = G * k;
            (w2, 0.5 / (G * G * k2 * k2))
        } else {
            let kd = k * self.depth;
            let t = tanh(kd);
            let w2 = G * k * t;
            (w2, G * (t + kd * (1.0 - t * t)) / (2.0 * k * w2 * w2 * w2))
        };
        let (amp, mut e, x) = if let Some(sh) = &self.shape {
            // F = A (2π)⁵ ω⁻⁵ exp(−5/4 (ωp/ω)⁴ + r ln γ) Φ.
            let v = w2 * w2 * sh.inv_wp4;
            let u = 1.0 / v;
            if u > U_MAX {
                return Radial::ZERO;
            }
            let mut e = -1.25 * u;
            let mut phi = 1.0;
            if sh.ln_gamma != 0.0 || sh.tma_h != f64::INFINITY {
                let q = v.sqrt().sqrt();
                if sh.ln_gamma != 0.0 {
                    let d = q - 1.0;
                    let a = d * d * if d <= 0.0 { C_LOW } else { C_HIGH };
                    // Far from the peak γ^r = 1 (and exp would take its slow path).
                    if a < 700.0 {
                        e += sh.ln_gamma * exp(-a);
                    }
                }
                if sh.tma_h != f64::INFINITY {
                    phi = kitaigorodskii(q * sh.tma_h);
                }
            }
            let x = if self.kind == SpreadKind::Cos2Plain {
                0.0
            } else {
                0.25 * ln(v) - sh.x_shift
            };
            (sh.coef * geo * phi, e, x)
        } else {
            // c_g/(2πk) = geo·ω⁵/(2π).
            let w = w2.sqrt();
            let big_f = freq.density(w / TWO_PI);
            if big_f == 0.0 {
                return Radial::ZERO;
            }
            let x = if self.kind == SpreadKind::Cos2Plain {
                0.0
            } else {
                0.5 * ln(w2) - self.ln_w_peak
            };
            (big_f * geo * (w2 * w2 * w) / TWO_PI, 0.0, x)
        };
        let [s, ln_z, beta] = if self.kind == SpreadKind::Cos2Plain {
            [0.0, 0.0, 0.0]
        } else {
            self.table.eval(x)
        };
        e -= ln_z;
        let mut a = amp * exp(e);
        if self.kind == SpreadKind::Cos2Plain {
            a *= 1.0 / PI;
        }
        Radial {
            inv_k: 1.0 / k,
            a,
            s,
            beta,
        }
    }

    /// Ψ without its power cos^{2s}(θ/2): `Err(Ψ)` where there is no power to take (no
    /// energy, plain cos², s = 0), else `Ok((a·m(θ), cos θ))`.
    #[inline(always)]
    pub(super) fn before_power(&self, r: &Radial, kx: f64, ky: f64) -> Result<(f64, f64), f64> {
        if r.a == 0.0 {
            return Err(0.0);
        }
        let cu = kx * self.wx + ky * self.wy;
        let c = cu * r.inv_k;
        let m = match self.kind {
            SpreadKind::Cos2Plain => return Err(r.a * (c * c)),
            SpreadKind::Family => r.a,
            SpreadKind::Cos2Swell => r.a * (c * c),
            SpreadKind::DonelanBanner => {
                let su = (ky * self.wx - kx * self.wy).abs();
                r.a * sech2(r.beta * atan2_pos(su, cu))
            }
        };
        if r.s == 0.0 { Err(m) } else { Ok((m, c)) }
    }

    /// Ψ from its radial part and the direction: a·m(θ)·cos^{2s}(θ/2).
    #[inline(always)]
    pub(super) fn angular(&self, r: &Radial, kx: f64, ky: f64) -> f64 {
        let (m, c) = match self.before_power(r, kx, ky) {
            Ok(parts) => parts,
            Err(psi) => return psi,
        };
        let e = r.s * ln_half_one_plus(c);
        // Below the floor the power is negligible (and the products would be subnormal).
        if e < POWER_EXPONENT_MIN {
            0.0
        } else {
            m * exp(e)
        }
    }

    #[inline(always)]
    pub(super) fn psi(&self, kx: f64, ky: f64, freq: &dyn FrequencySpectrum) -> f64 {
        let r = self.radial(kx * kx + ky * ky, freq);
        self.angular(&r, kx, ky)
    }

    /// True when the cell at k² takes the midpoint without further tests (see
    /// `cell_integral`).
    #[inline(always)]
    pub(super) fn is_far(&self, k2: f64, h: f64) -> bool {
        k2 >= self.zone2 && k2 * self.far_c2 >= h * h
    }
}

/// The |k|-dependent part of Ψ: Ψ = a · m(θ) · cos^{2s}(θ/2).
#[derive(Debug, Clone, Copy)]
pub(super) struct Radial {
    pub(super) inv_k: f64,
    pub(super) a: f64,
    pub(super) s: f64,
    pub(super) beta: f64,
}

impl Radial {
    /// No energy at this |k|.
    const ZERO: Radial = Radial {
        inv_k: 0.0,
        a: 0.0,
        s: 0.0,
        beta: 0.0,
    };
}

/// (1 + c)/2 of the directional power as its single-precision argument, kept at or above
/// the smallest normal `f32` (the power's domain).
#[inline(always)]
pub(super) fn half_one_plus_f32(c: f64) -> f32 {
    (half_one_plus(c) as f32).max(f32::MIN_POSITIVE)
}

/// The spreading exponent s as the power's single-precision exponent (finite).
#[inline(always)]
pub(super) fn power_f32(s: f64) -> f32 {
    s.min(1e30) as f32
}
