//! Properties over random parameters (proptest): any parameter set that validates gives a
//! finite field and finite derived fields; a `--set` value is what the sidecar records,
//! and the sidecar read back as a preset gives the same parameters.

use proptest::prelude::*;

use seasynth::config::layers::{self, Assignment};
use seasynth::config::{Params, presets};
use seasynth::export::sidecar::Sidecar;
use seasynth::field::{Synthesizer, dynamics::Extras};

/// A number spread evenly in log scale between `lo` and `hi` (both > 0).
fn log_range(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..hi.ln()).prop_map(f64::exp)
}

/// Assignments that together stay within the documented ranges (many combinations are
/// still refused, e.g. `--hs` with `phillips`: those cases are skipped).
fn assignments() -> impl Strategy<Value = Vec<(&'static str, String)>> {
    let method = prop::sample::select(vec!["hybrid", "fft", "filtered-noise", "perlin"]);
    let spectrum = prop::sample::select(vec![
        "phillips",
        "pierson-moskowitz",
        "jonswap",
        "tma",
        "fractal",
    ]);
    let spreading = prop::sample::select(vec!["cos2", "hasselmann", "mitsuyasu", "donelan-banner"]);
    let grid = (
        2usize..20,
        2usize..20,
        log_range(1e-3, 1e6),
        log_range(1e-3, 1e6),
    );
    let sea = (
        log_range(0.1, 100.0),
        -1e4..1e4f64,
        log_range(1e-3, 1e4),
        prop::option::of(log_range(1e-3, 1e5)),
        1.0..20.0f64,
        prop::option::of((log_range(1e-2, 1e3), log_range(0.1, 1e4))),
    );
    let motion = (
        -10.0..10.0f64,
        -1e6..1e6f64,
        prop::option::of(log_range(1e-3, 1e6)),
    );
    let perlin = (
        1u32..25,
        0.01..0.99f64,
        1.01..16.0f64,
        log_range(1e-12, 1e6),
    );
    (
        method,
        spectrum,
        spreading,
        grid,
        sea,
        motion,
        perlin,
        0u64..(1 << 63),
    )
        .prop_map(
            |(m, s, sp, (nx, ny, lx, ly), (u, dir, fetch, depth, gamma, hs_tp), mo, pe, seed)| {
                let (chop, t, loop_t) = mo;
                let (oct, pers, lac, a) = pe;
                let mut v: Vec<(&'static str, String)> = vec![
                    ("method", m.into()),
                    ("spectrum", s.into()),
                    ("spreading", sp.into()),
                    ("size", format!("{nx}x{ny}")),
                    ("extent", format!("{lx}x{ly}")),
                    ("wind-speed", u.to_string()),
                    ("wind-dir", dir.to_string()),
                    ("fetch-km", fetch.to_string()),
                    ("gamma", gamma.to_string()),
                    ("choppiness", chop.to_string()),
                    ("time", t.to_string()),
                    ("seed", seed.to_string()),
                    ("perlin.octaves", oct.to_string()),
                    ("perlin.persistence", pers.to_string()),
                    ("perlin.lacunarity", lac.to_string()),
                    ("spectrum.phillips_a", a.to_string()),
                ];
                if let Some(d) = depth.or((s == "tma").then_some(20.0)) {
                    v.push(("depth", d.to_string()));
                }
                if let Some((h, tp)) = hs_tp {
                    v.push(("hs", h.to_string()));
                    v.push(("tp", tp.to_string()));
                }
                if let Some(l) = loop_t {
                    v.push(("loop-period", l.to_string()));
                }
                v
            },
        )
}

/// The parameters of the assignments; a set that does not validate rejects the case.
fn resolve(v: &[(&str, String)]) -> Result<Params, TestCaseError> {
    let sets: Vec<Assignment> = v
        .iter()
        .map(|(k, val)| Assignment::parse_set(&format!("{k}={val}")).unwrap())
        .collect();
    layers::apply(Params::default(), &sets).map_err(|e| TestCaseError::reject(e.to_string()))
}

fn all_finite(name: &str, v: &[f32]) -> Result<(), TestCaseError> {
    match v.iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(i) => Err(TestCaseError::fail(format!("{name}[{i}] = {}", v[i]))),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn any_valid_parameter_set_gives_a_finite_field_and_finite_derived_fields(
        v in assignments()
    ) {
        let params = resolve(&v)?;
        let extras = Extras::ALL;
        let syn = Synthesizer::new(&params, extras, false)
            .map_err(|e| TestCaseError::fail(format!("{v:?}: {e}")))?
            .frame(params.time_s);
        all_finite("height", &syn.grid.data)?;
        let s = &syn.surface;
        for (name, f) in [("slope", &s.slopes), ("displacement", &s.displacement)] {
            if let Some([a, b]) = f {
                all_finite(name, a)?;
                all_finite(name, b)?;
            }
        }
        if let Some(j) = &s.jacobian {
            all_finite("jacobian", &j.values(syn.grid.data.len()))?;
        }
    }

    #[test]
    fn a_set_value_is_recorded_in_the_sidecar_and_regenerates_the_same_parameters(
        v in assignments()
    ) {
        let params = resolve(&v)?;
        let info = Default::default();
        let stats = seasynth::grid::Grid::zeros(params.grid_spec()).stats();
        let doc = serde_json::to_string_pretty(&Sidecar::new(&params, &info, stats)).unwrap();
        let side: serde_json::Value = serde_json::from_str(&doc).unwrap();
        // The sidecar holds each value as given (numbers read back exactly).
        let recorded = |ptr: &str| side["params"].pointer(ptr).and_then(|x| x.as_f64());
        for (key, ptr) in [
            ("wind-speed", "/wind/speed_mps"),
            ("wind-dir", "/wind/direction_deg"),
            ("choppiness", "/motion/choppiness"),
            ("time", "/time_s"),
            ("perlin.persistence", "/perlin/persistence"),
        ] {
            let given: f64 = v.iter().find(|(k, _)| *k == key).unwrap().1.parse().unwrap();
            prop_assert_eq!(recorded(ptr), Some(given), "{}", key);
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.json");
        std::fs::write(&path, &doc).unwrap();
        let back = presets::load(path.to_str().unwrap())
            .map_err(|e| TestCaseError::fail(format!("the sidecar does not load: {e}")))?;
        prop_assert_eq!(back, params);
    }
}
