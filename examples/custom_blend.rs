//! Building blocks composed by hand: a spectrum of one's own (two swells crossing), its
//! random sea by the inverse FFT, a Perlin noise field, and Li Tian's blend of the two
//! under a weight map α = 1 − (y/Ly)²: the spectral sea at y = 0, noise toward y = Ly.
//!
//! Run: `cargo run --release --example custom_blend` (writes `out/example-blend.tif`).

use std::f64::consts::TAU;

use seasynth::config::{AlphaConfig, Axis};
use seasynth::field::fft::{SpectrumSetup, fft_field};
use seasynth::field::hybrid::blend_in_place;
use seasynth::field::perlin::{PerlinParams, perlin_field};
use seasynth::field::weight::AlphaMap;
use seasynth::spectrum::Dispersion;
use seasynth::{GridSpec, Spectrum};

/// Two swells: Gaussian bumps in the wavevector plane around the peaks `k`, each holding a
/// variance of `variance_m2` (Hs = 4·√variance) spread over a width `width` (rad/m).
struct CrossingSwells {
    peaks: [(f64, f64, f64); 2],
    width: f64,
}

impl CrossingSwells {
    fn new(wavelengths_m: [f64; 2], directions_deg: [f64; 2], hs_m: [f64; 2]) -> Self {
        let peak = |i: usize| {
            let k = TAU / wavelengths_m[i];
            let d = directions_deg[i].to_radians();
            (k * d.cos(), k * d.sin(), (hs_m[i] / 4.0).powi(2))
        };
        Self {
            peaks: [peak(0), peak(1)],
            width: 0.004,
        }
    }
}

impl Spectrum for CrossingSwells {
    /// E|h̃0(k)|²: the spectral density at k times the area dkx·dky of one grid cell, so
    /// the variances of all cells add up to the swells' variances.
    fn amplitude_variance(&self, kx: f64, ky: f64, dkx: f64, dky: f64) -> f64 {
        let s2 = self.width * self.width;
        self.peaks
            .iter()
            .map(|&(px, py, var)| {
                let r2 = (kx - px).powi(2) + (ky - py).powi(2);
                // One-sided: the waves travel toward the peak direction only.
                var * (-r2 / (2.0 * s2)).exp() / (TAU * s2)
            })
            .sum::<f64>()
            * dkx
            * dky
            / 2.0
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let spec = GridSpec::new(512, 512, 1024.0, 1024.0);
    let swells = CrossingSwells::new([120.0, 70.0], [20.0, 75.0], [1.8, 1.0]);
    let setup = SpectrumSetup {
        spec,
        spectrum: &swells,
        dispersion: Dispersion::for_depth(None),
        seed: 42,
        time_s: 0.0,
        loop_period_s: None,
    };
    let (mut sea, _h0max) = fft_field(&setup);
    println!("the swells alone: Hs {:.2} m", sea.stats().hs_m);

    let noise = perlin_field(
        &spec,
        &PerlinParams {
            wavelength_m: 64.0,
            seed: 7,
            ..PerlinParams::default()
        },
    );
    // α = 1 − (y/Ly)²: the swells at y = 0, fading into noise of amplitude 0.5 m.
    let alpha = AlphaMap::new(
        &AlphaConfig::Ramp {
            axis: Axis::Y,
            power: 2.0,
        },
        &spec,
    )?;
    blend_in_place(&mut sea, &noise, &alpha, 0.5);
    let stats = sea.stats();
    println!(
        "blended: std {:.3} m, min {:.2} m, max {:.2} m",
        stats.std_m, stats.min_m, stats.max_m
    );

    std::fs::create_dir_all("out")?;
    let file = std::io::BufWriter::new(std::fs::File::create("out/example-blend.tif")?);
    seasynth::export::tiff32::write(file, &sea)?;
    println!("wrote out/example-blend.tif");
    Ok(())
}
