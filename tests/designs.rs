//! `seasynth batch --sample N --vary KEY=DIST`: random and Latin-hypercube designs as
//! ordinary jobs — their values in the index and the sidecars, crossed with sweeps, the
//! same jobs in every shard, refused before any file when bad.

mod common;

use std::path::Path;

use common::{json_file, names_in, run_ok, run_rejected};
use serde_json::Value;

/// A small FFT sea: fast jobs.
const SEA: &[&str] = &["--method", "fft", "--size", "16", "--extent", "32", "-q"];

fn batch(dir: &Path, extra: &[&str]) {
    let mut args = vec!["batch"];
    args.extend(SEA);
    args.extend(extra);
    run_ok(dir, &args);
}

fn rows(index: &Value) -> Vec<Value> {
    index["rows"].as_array().expect("rows").clone()
}

fn value(row: &Value, key: &str) -> f64 {
    row["params"][key]
        .as_str()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no number for {key} in {row}"))
}

#[test]
fn a_latin_hypercube_hits_every_stratum_of_every_key_once_and_records_its_values() {
    let dir = tempfile::tempdir().unwrap();
    const N: usize = 8;
    batch(
        dir.path(),
        &[
            "--sample",
            "8",
            "--design",
            "lhs",
            "--design-seed",
            "5",
            "--vary",
            "wind-speed=uniform:4:12",
            "--vary",
            "wind-dir=int:0:7",
            "-o",
            "d",
        ],
    );
    let index = json_file(&dir.path().join("d/index.json"));
    let rows = rows(&index);
    assert_eq!(rows.len(), N);
    assert_eq!(index["keys"], serde_json::json!(["wind-speed", "wind-dir"]));
    let mut speed_strata: Vec<usize> = rows
        .iter()
        .map(|r| ((value(r, "wind-speed") - 4.0) / 8.0 * N as f64).floor() as usize)
        .collect();
    speed_strata.sort_unstable();
    assert_eq!(
        speed_strata,
        (0..N).collect::<Vec<_>>(),
        "one speed per stratum"
    );
    let mut dirs: Vec<usize> = rows.iter().map(|r| value(r, "wind-dir") as usize).collect();
    dirs.sort_unstable();
    assert_eq!(
        dirs,
        (0..N).collect::<Vec<_>>(),
        "8 strata of int:0:7: each value once"
    );
    for r in &rows {
        let name = r["name"].as_str().unwrap();
        let side = json_file(&dir.path().join(format!("d/{name}.json")));
        assert_eq!(
            side["batch"]["values"], r["params"],
            "{name}: the sidecar's values"
        );
        let p = &side["params"];
        assert_eq!(
            p["wind"]["speed_mps"].as_f64().unwrap(),
            value(r, "wind-speed"),
            "{name}: the job ran with the drawn value"
        );
    }
    let csv = std::fs::read_to_string(dir.path().join("d/index.csv")).unwrap();
    assert!(
        csv.lines()
            .next()
            .unwrap()
            .starts_with("job,name,status,wind-speed,wind-dir,"),
        "{csv}"
    );
}

#[test]
fn designed_jobs_are_the_same_in_every_shard_and_cross_the_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let design = [
        "--sample",
        "3",
        "--vary",
        "wind-speed=log-uniform:2:20",
        "--vary",
        "spectrum=choice:phillips|pierson-moskowitz",
        "--sweep",
        "seed=1,2",
    ];
    let mut whole = design.to_vec();
    whole.extend(["-o", "all"]);
    batch(dir.path(), &whole);
    for k in 1..=3 {
        let shard = format!("{k}/3");
        let mut args = design.to_vec();
        args.extend(["--shard", shard.as_str(), "-o", "sharded"]);
        batch(dir.path(), &args);
    }
    run_ok(dir.path(), &["batch", "--merge-index", "sharded", "-q"]);
    let all = rows(&json_file(&dir.path().join("all/index.json")));
    let merged = rows(&json_file(&dir.path().join("sharded/index.json")));
    assert_eq!(all.len(), 6, "3 points × 2 seeds");
    let identity = |r: &Value| {
        (
            r["job"].clone(),
            r["name"].clone(),
            r["params"].clone(),
            r["hash"].clone(),
        )
    };
    assert_eq!(
        all.iter().map(identity).collect::<Vec<_>>(),
        merged.iter().map(identity).collect::<Vec<_>>(),
        "names, values and hashes do not depend on the shards"
    );
    for p in 0..3 {
        let (a, b) = (&all[2 * p], &all[2 * p + 1]);
        assert_eq!(
            a["params"]["wind-speed"], b["params"]["wind-speed"],
            "point {p}"
        );
        assert_eq!(a["params"]["seed"], "1");
        assert_eq!(b["params"]["seed"], "2", "the sweep is inside each point");
        let s = value(a, "wind-speed");
        assert!((2.0..=20.0).contains(&s), "{s}");
    }
    // Another design seed, another design; the default follows the batch's seed.
    let mut other = design.to_vec();
    other.extend(["--design-seed", "99", "-o", "other"]);
    batch(dir.path(), &other);
    let o = rows(&json_file(&dir.path().join("other/index.json")));
    assert_ne!(o[0]["params"]["wind-speed"], all[0]["params"]["wind-speed"]);
}

#[test]
fn bad_designs_are_refused_before_any_file_is_written() {
    let dir = tempfile::tempdir().unwrap();
    for (args, fragments) in [
        (
            vec!["--sample", "0", "--vary", "hs=uniform:1:2"],
            vec!["--sample must be a number of jobs from 1"],
        ),
        (
            vec!["--sample", "4", "--vary", "wind-speed=uniform:9:3"],
            vec!["--vary wind-speed=uniform:9:3", "A must be < B"],
        ),
        (
            vec!["--sample", "4", "--vary", "bogus=uniform:1:3"],
            vec!["unknown key `bogus`"],
        ),
        (
            vec!["--sample", "4", "--vary", "spectrum=choice:jonswap|foam"],
            vec!["--vary spectrum=choice:jonswap|foam", "the value foam"],
        ),
        (
            vec!["--sample", "4", "--vary", "wind-speed=uniform:0:3"],
            vec![
                "the value 0 does not give valid parameters",
                "wind.speed_mps",
            ],
        ),
        (
            vec!["--vary", "hs=uniform:1:2"],
            vec!["--vary needs --sample N"],
        ),
        (
            vec![
                "--sample",
                "4",
                "--vary",
                "hs=uniform:1:2",
                "--design",
                "sobol",
            ],
            vec!["--design must be random or lhs (got sobol)"],
        ),
    ] {
        let mut all = vec!["batch"];
        all.extend(SEA);
        all.extend(args.iter().copied());
        all.extend(["-o", "out"]);
        run_rejected(dir.path(), &all, &fragments);
        assert!(names_in(dir.path()).is_empty(), "{args:?} left files");
    }
}
