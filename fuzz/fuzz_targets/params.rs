//! Preset parsing, `--set` layering and validation: whatever the text, an error is one
//! line, and parameters that validate give a finite field (small grids are synthesized).
//!
//! Input: a TOML preset, optionally followed by a line `---` and one `KEY=VALUE` per line.
#![no_main]

use libfuzzer_sys::fuzz_target;
use seasynth::config::layers::{self, Assignment};
use seasynth::config::presets;

fn one_line(e: &impl std::fmt::Display) {
    let text = e.to_string();
    assert!(!text.contains('\n'), "error of more than one line: {text}");
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Err(e) = presets::parse_json("fuzz.json", text) {
        one_line(&e);
    }
    let (preset, sets) = text.split_once("\n---\n").unwrap_or((text, ""));
    let base = match presets::parse_toml("fuzz.toml", preset) {
        Ok(p) => p,
        Err(e) => return one_line(&e),
    };
    let mut assignments = Vec::new();
    for line in sets.lines() {
        match Assignment::parse_set(line) {
            Ok(a) => assignments.push(a),
            Err(e) => one_line(&e),
        }
    }
    let params = match layers::apply(base, &assignments) {
        Ok(p) => p,
        Err(e) => return one_line(&e),
    };
    params.validate().expect("resolved parameters validate");
    // The sidecar's form reads back to the same parameters.
    let json = serde_json::to_string(&params).expect("parameters serialize");
    let back = presets::parse_json("round-trip.json", &json).expect("serialized parameters parse");
    assert_eq!(back, params, "JSON round trip");
    let [nx, ny] = params.grid.size.0;
    if nx * ny <= 64 * 64 {
        match seasynth::field::synthesize(&params) {
            Ok(s) => {
                let st = s.grid.stats();
                assert!(st.std_m.is_finite() && st.mean_m.is_finite(), "{st:?}");
            }
            Err(seasynth::error::Error::NotFinite { what, detail }) => {
                panic!("valid parameters gave a non-finite field: {what}: {detail}\n{json}")
            }
            Err(e) => one_line(&e),
        }
    }
});
