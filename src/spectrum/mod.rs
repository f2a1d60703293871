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

/// One line of grid cells, the unit of work of the line kernels: the cells centred on
/// (kx, ky[j]) in rad/m, each `dkx` × `dky`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LineQuery<'a> {
    pub kx: f64,
    pub ky: &'a [f64],
    pub dkx: f64,
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

/// The values of a line's two half-planes: at (kx, ky[j]) into `a[j]` and at (−kx, −ky[j])
/// into `b[j]` (every h̃(k, t) needs both).
#[derive(Debug)]
pub(crate) struct PairOut<'a, T> {
    pub a: &'a mut [T],
    pub b: &'a mut [T],
}

/// A directional wave spectrum sampled on a discrete wavevector grid.
pub trait Spectrum: Send + Sync {
    /// E|h̃0(k)|² in m² for wavevector `(kx, ky)` in rad/m, on a grid with wavevector
    /// spacing `(dkx, dky)` = 2π·(1/Lx, 1/Ly). Never negative, finite for k ≠ 0.
    fn amplitude_variance(&self, kx: f64, ky: f64, dkx: f64, dky: f64) -> f64;

    /// [`amplitude_variance`](Self::amplitude_variance) along a line of wavevectors
    /// (kx, ky[i]), into `out`. Models override it with a loop the compiler can inline;
    /// results must equal the one-at-a-time values bit for bit.
    fn amplitude_variance_line(&self, kx: f64, ky: &[f64], dkx: f64, dky: f64, out: &mut [f64]) {
        for (o, &y) in out.iter_mut().zip(ky) {
            *o = self.amplitude_variance(kx, y, dkx, dky);
        }
    }

    /// The line (kx, ky[i]) into `pa` and its mirror (−kx, −ky[i]) into `pb`: the two
    /// amplitude variances every h̃(k, t) needs. Equal bit for bit to
    /// [`amplitude_variance_line`](Self::amplitude_variance_line) of each; models
    /// override it to share the work that depends on |k| only.
    fn amplitude_variance_pair_line(
        &self,
        kx: f64,
        ky: &[f64],
        dkx: f64,
        dky: f64,
        pa: &mut [f64],
        pb: &mut [f64],
    ) {
        let neg: Vec<f64> = ky.iter().map(|v| -v).collect();
        self.amplitude_variance_line(kx, ky, dkx, dky, pa);
        self.amplitude_variance_line(-kx, &neg, dkx, dky, pb);
    }
}
