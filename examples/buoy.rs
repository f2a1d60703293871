//! Heights of the trochoid sea at any point and time, without a grid: the heave, pitch and
//! roll of a small rectangular float riding Thon et al.'s sea, as a game or a ship model
//! would ask for them every step.
//!
//! Run: `cargo run --release --example buoy`.

use seasynth::{Params, TrochoidSea};

/// Half the float's length (along the wind) and beam, meters.
const HALF_LENGTH_M: f64 = 6.0;
const HALF_BEAM_M: f64 = 2.5;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let params = Params::preset("thon-2000")?;
    // The sea is continuous: built once, it answers for any (x, y, t), on or off a grid.
    let sea = TrochoidSea::new(&params)?;
    let (x0, y0) = (250.0, 400.0);
    let wind = params.wind.direction_deg.to_radians();
    let (c, s) = (wind.cos(), wind.sin());
    println!("t_s,heave_m,pitch_deg,roll_deg");
    for step in 0..=40 {
        let t = step as f64 * 0.25;
        // Four corners of the float, bow and stern along the wind.
        let at = |along: f64, across: f64| {
            let (x, y) = (x0 + along * c - across * s, y0 + along * s + across * c);
            sea.height_at(x, y, t) as f64
        };
        let (bow_port, bow_star) = (
            at(HALF_LENGTH_M, HALF_BEAM_M),
            at(HALF_LENGTH_M, -HALF_BEAM_M),
        );
        let (aft_port, aft_star) = (
            at(-HALF_LENGTH_M, HALF_BEAM_M),
            at(-HALF_LENGTH_M, -HALF_BEAM_M),
        );
        let heave = (bow_port + bow_star + aft_port + aft_star) / 4.0;
        let pitch = ((bow_port + bow_star - aft_port - aft_star) / 2.0)
            .atan2(2.0 * HALF_LENGTH_M)
            .to_degrees();
        let roll = ((bow_port + aft_port - bow_star - aft_star) / 2.0)
            .atan2(2.0 * HALF_BEAM_M)
            .to_degrees();
        println!("{t:.2},{heave:.3},{pitch:.2},{roll:.2}");
    }
    Ok(())
}
