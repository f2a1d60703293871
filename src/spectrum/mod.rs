//! Wave spectra: how much energy each wavevector carries.
//!
//! Every model implements [`Spectrum`], which answers one question for the spectral
//! methods: the expected squared magnitude E|h̃0(k)|² of the discrete Fourier amplitude
//! at wavevector `k` on a grid whose wavevector spacing is `dk`.
//! With h̃(k,t) = h̃0(k)·e^{−iωt} + conj(h̃0(−k))·e^{iωt}, the expected variance of the
//! field is Σ_k (E|h̃0(k)|² + E|h̃0(−k)|²).

pub mod directional;
pub mod dispersion;
pub mod fractal;
pub mod frequency;
#[cfg(test)]
mod invariants;
pub(crate) mod mirror;
pub mod phillips;
pub mod spreading;

pub use directional::DirectionalSpectrum;
pub use dispersion::Dispersion;
pub use fractal::{Fractal, FractalOnGrid};
pub use frequency::{FrequencySpectrum, Jonswap, JonswapShape, PiersonMoskowitz, Tma};
pub use phillips::Phillips;
pub use spreading::{Spreading, SpreadingModel};

/// Gravitational acceleration, m/s².
pub const G: f64 = 9.81;

/// One line of grid cells, the query of [`Spectrum`]'s line methods: the cells centred on
/// `(kx, ky[j])` in rad/m, each `dkx` × `dky`.
#[derive(Debug, Clone, Copy)]
pub struct LineQuery<'a> {
    /// The line's kx, rad/m.
    pub kx: f64,
    /// The ky of its cells, rad/m.
    pub ky: &'a [f64],
    /// The grid's wavevector spacing along x, rad/m.
    pub dkx: f64,
    /// The grid's wavevector spacing along y, rad/m.
    pub dky: f64,
}

impl<'a> LineQuery<'a> {
    /// The cells `range` of the line.
    pub fn part(&self, range: std::ops::Range<usize>) -> LineQuery<'a> {
        LineQuery {
            ky: &self.ky[range],
            ..*self
        }
    }
}

/// The values of a line's two half-planes: at `(kx, ky[j])` into `a[j]` and at `(−kx, −ky[j])`
/// into `b[j]` (every h̃(k, t) needs both).
#[derive(Debug)]
pub struct PairOut<'a, T> {
    /// The values at `(kx, ky[j])`.
    pub a: &'a mut [T],
    /// The values at the mirror cells `(−kx, −ky[j])`.
    pub b: &'a mut [T],
}

/// A directional wave spectrum sampled on a discrete wavevector grid.
///
/// A model implements [`amplitude_variance`](Self::amplitude_variance), the value of one
/// cell; the line methods, which the spectral methods call once per kx line, have default
/// forms built on it, and models override them with whole-line loops that give the same
/// bits.
///
/// ```
/// use seasynth::spectrum::{LineQuery, Spectrum};
///
/// /// A flat spectrum: the same density ψ, m⁴, at every k ≠ 0.
/// struct Flat {
///     psi_m4: f64,
/// }
///
/// impl Spectrum for Flat {
///     fn amplitude_variance(&self, kx: f64, ky: f64, dkx: f64, dky: f64) -> f64 {
///         if kx == 0.0 && ky == 0.0 {
///             0.0
///         } else {
///             // ½·ψ·(cell area): half the cell's variance goes to h̃0(k), half to h̃0(−k).
///             0.5 * self.psi_m4 * dkx * dky
///         }
///     }
/// }
///
/// let flat = Flat { psi_m4: 2.0 };
/// let ky = [0.0, 0.5, -0.5];
/// let q = LineQuery { kx: 0.0, ky: &ky, dkx: 0.5, dky: 0.5 };
/// let mut out = [0.0; 3];
/// flat.amplitude_variance_line(&q, &mut out);
/// assert_eq!(out, [0.0, 0.25, 0.25]);
/// ```
pub trait Spectrum: Send + Sync {
    /// E|h̃0(k)|² in m² for wavevector `(kx, ky)` in rad/m, on a grid with wavevector
    /// spacing `(dkx, dky)` = 2π·(1/Lx, 1/Ly). Never negative, finite for k ≠ 0.
    fn amplitude_variance(&self, kx: f64, ky: f64, dkx: f64, dky: f64) -> f64;

    /// [`amplitude_variance`](Self::amplitude_variance) of every cell of the line `q`
    /// `(kx, ky[i])`, into `out[i]`. Models override it with a loop the compiler can
    /// vectorize; results must equal the one-at-a-time values bit for bit.
    fn amplitude_variance_line(&self, q: &LineQuery, out: &mut [f64]) {
        for (o, &y) in out.iter_mut().zip(q.ky) {
            *o = self.amplitude_variance(q.kx, y, q.dkx, q.dky);
        }
    }

    /// The line `q` `(kx, ky[i])` into `out.a` and its mirror `(−kx, −ky[i])` into `out.b`:
    /// the two amplitude variances every h̃(k, t) needs. Equal bit for bit to
    /// [`amplitude_variance_line`](Self::amplitude_variance_line) of each; models
    /// override it to share the work that depends on |k| only.
    fn amplitude_variance_pair_line(&self, q: &LineQuery, out: PairOut<f64>) {
        let neg: Vec<f64> = q.ky.iter().map(|v| -v).collect();
        let mirror = LineQuery {
            kx: -q.kx,
            ky: &neg,
            ..*q
        };
        self.amplitude_variance_line(q, out.a);
        self.amplitude_variance_line(&mirror, out.b);
    }
}
