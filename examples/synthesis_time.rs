//! The time of one field through the library, as the Python package's `generate` does
//! it (`pipeline::compute::synthesize_checked`): the default hybrid sea at N², median
//! of R runs, in milliseconds. `python/examples/overhead.py` runs it beside the Python
//! call.
//!
//! Run: `cargo run --release --example synthesis_time -- 1024 15 [keep]` (`keep`: freed
//! memory kept for reuse, `pipeline::memory::keep_freed_memory`).

use std::time::Instant;

use seasynth::config::Size2;
use seasynth::field::dynamics::Extras;
use seasynth::pipeline::compute::synthesize_checked;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = args.first().map_or(Ok(1024), |a| a.parse())?;
    let runs: usize = args.get(1).map_or(Ok(15), |a| a.parse())?;
    if args.get(2).is_some_and(|a| a == "keep") {
        seasynth::pipeline::memory::keep_freed_memory();
    }
    let mut params = seasynth::Params::preset("li-tian")?;
    params.grid.size = Size2([n, n]);
    params.validate()?;
    let mut times = Vec::with_capacity(runs);
    for _ in 0..runs {
        let t = Instant::now();
        let field = synthesize_checked(&params, Extras::default())?;
        times.push(t.elapsed().as_secs_f64() * 1e3);
        std::hint::black_box(&field.grid.data);
    }
    times.sort_by(f64::total_cmp);
    println!("{:.3}", times[times.len() / 2]);
    Ok(())
}
