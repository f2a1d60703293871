//! Li Tian's hybrid sea (the `li-tian` preset) at a stronger wind, written as a 32-bit
//! float TIFF in meters with its sidecar, the same files `seasynth generate` writes.
//!
//! Run: `cargo run --release --example hybrid_tiff` (writes `out/example-hybrid.tif`).

use std::path::PathBuf;

use seasynth::{Params, synthesize};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut params = Params::preset("li-tian")?;
    params.wind.speed_mps = 9.0;
    params.seed = 7;
    params.validate()?;

    // The field alone, in memory: heights in meters on params.grid.
    let field = synthesize(&params)?;
    let stats = field.grid.stats();
    println!(
        "{}×{} samples: std {:.3} m, Hs {:.3} m, min {:.3} m, max {:.3} m",
        field.grid.spec.nx, field.grid.spec.ny, stats.std_m, stats.hs_m, stats.min_m, stats.max_m
    );

    // Or written to files (format by extension) with a sidecar that regenerates them.
    std::fs::create_dir_all("out")?;
    let paths = [PathBuf::from("out/example-hybrid.tif")];
    let written = seasynth::write_field(&params, &paths, field)?;
    for f in &written.files {
        println!("wrote {}", f.display());
    }
    Ok(())
}
