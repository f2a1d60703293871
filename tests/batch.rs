//! `seasynth batch`: the cartesian product and names, one mapping for the batch, resume
//! after a kill, shards and their merged index, a failing job, the index against the
//! files, manifests; and the same random phases across a wind-direction sweep.

mod common;

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use common::{json_file, names_in, num, read, run_exit2, run_ok, run_rejected, seasynth};
use seasynth::export::{HeightMapping, png16, tiff32};
use serde_json::Value;

/// A small FFT sea: fast jobs whose heights differ with the wind direction and seed.
const SEA: &[&str] = &["--method", "fft", "--size", "32", "--extent", "64"];

fn batch<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut v: Vec<&str> = vec!["batch"];
    v.extend(SEA);
    v.extend(extra);
    v
}

fn rows(index: &Value) -> &Vec<Value> {
    index["rows"].as_array().expect("rows")
}

/// The files an index row lists.
fn files_of(row: &Value) -> Vec<&str> {
    row["files"]
        .as_array()
        .expect("files")
        .iter()
        .map(|f| f.as_str().expect("a file name"))
        .collect()
}

/// The files of a folder that a batch writes per job (not its index or batch.json).
fn job_files(dir: &Path) -> BTreeSet<String> {
    names_in(dir)
        .into_iter()
        .filter(|n| !n.starts_with("index") && n != "batch.json")
        .collect()
}

#[test]
fn two_sweeps_give_every_combination_named_by_its_values_and_each_job_regenerates() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run_ok(
        d,
        &batch(&[
            "--sweep",
            "wind-dir=0:180:90",
            "--sweep",
            "seed=1,2,3",
            "--format",
            "png,tif",
            "-o",
            "b",
            "-q",
        ]),
    );
    let index = json_file(&d.join("b/index.json"));
    assert_eq!(rows(&index).len(), 2 * 3, "2 directions × 3 seeds");
    let mut seen = BTreeSet::new();
    for (i, row) in rows(&index).iter().enumerate() {
        // The first sweep is the outer loop.
        let (dir_deg, seed) = ([0, 90][i / 3], [1, 2, 3][i % 3]);
        let name = format!("{i}_wind-dir={dir_deg}_seed={seed}");
        assert_eq!(row["name"], name.as_str(), "job {i}");
        assert_eq!(row["params"]["wind-dir"], dir_deg.to_string().as_str());
        let side = json_file(&d.join(format!("b/{name}.json")));
        assert_eq!(num(&side, "/params/wind/direction_deg"), dir_deg as f64);
        assert_eq!(num(&side, "/params/seed"), seed as f64);
        assert_eq!(num(&side, "/batch/job"), i as f64);
        seen.insert((dir_deg, seed));
    }
    assert_eq!(seen.len(), 6, "every combination once");
    // A job's sidecar regenerates its files bit for bit (the batch's mapping included).
    let name = "4_wind-dir=90_seed=2";
    run_ok(
        d,
        &[
            "generate",
            "--preset",
            &format!("b/{name}.json"),
            "-o",
            "again.png",
            "-o",
            "again.tif",
            "-q",
        ],
    );
    for ext in ["png", "tif"] {
        assert_eq!(
            read(&d.join(format!("again.{ext}"))),
            read(&d.join(format!("b/{name}.{ext}"))),
            "generate --preset {name}.json differs from the batch's .{ext}"
        );
    }
    // A name template with any key, and an index padded to the widest number.
    run_ok(
        d,
        &batch(&[
            "--sweep",
            "seed=1:12:1",
            "--name",
            "sea-{index}-s{seed}-{size}",
            "-o",
            "n",
            "-q",
        ]),
    );
    assert!(d.join("n/sea-00-s1-32x32.png").is_file());
    assert!(d.join("n/sea-10-s11-32x32.json").is_file());
}

#[test]
fn one_mapping_spans_every_job_of_the_batch() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Wind speeds 4 … 12 m/s: ranges that differ by a factor of ~9.
    run_ok(
        d,
        &batch(&[
            "--sweep",
            "wind-speed=4,8,12",
            "--format",
            "png,tif",
            "-o",
            "b",
            "-q",
        ]),
    );
    let doc = json_file(&d.join("b/batch.json"));
    let mapping = HeightMapping {
        min_m: num(&doc, "/mapping_min_m"),
        max_m: num(&doc, "/mapping_max_m"),
    };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for row in rows(&json_file(&d.join("b/index.json"))) {
        let name = row["name"].as_str().unwrap();
        let side = json_file(&d.join(format!("b/{name}.json")));
        assert_eq!(num(&side, "/mapping/min_m"), mapping.min_m, "{name}");
        assert_eq!(num(&side, "/mapping/max_m"), mapping.max_m, "{name}");
        let (_, _, t) = tiff32::read(&d.join(format!("b/{name}.tif"))).unwrap();
        let (_, _, p) = png16::read(&d.join(format!("b/{name}.png"))).unwrap();
        for (i, (&m, &v)) in t.iter().zip(&p).enumerate() {
            lo = lo.min(m as f64);
            hi = hi.max(m as f64);
            assert!(
                (mapping.decode(v) - m as f64).abs() <= mapping.step_m(),
                "{name} sample {i}: {m} m is {v} under the batch's mapping"
            );
        }
    }
    assert_eq!(
        (lo, hi),
        (mapping.min_m, mapping.max_m),
        "the mapping is the range over every job"
    );
    // --height-range replaces the first pass.
    run_ok(
        d,
        &batch(&[
            "--sweep",
            "wind-speed=4,8",
            "--height-range",
            "-2:2",
            "-o",
            "r",
            "-q",
        ]),
    );
    let side = json_file(&d.join("r/0_wind-speed=4.json"));
    assert_eq!(num(&side, "/mapping/min_m"), -2.0);
    assert_eq!(side["mapping"]["source"], "--height-range");
}

#[cfg(unix)]
#[test]
fn a_batch_killed_in_the_middle_resumes_to_the_same_bytes_as_an_uninterrupted_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Jobs of a few tens of milliseconds, one at a time, so the kill lands mid-batch.
    let args = [
        "batch",
        "--size",
        "256",
        "--sweep",
        "wind-dir=0:360:15",
        "--format",
        "png,tif",
        "--jobs",
        "1",
        "-q",
    ];
    let with_dir = |out: &'static str, resume: bool| {
        let mut v = args.to_vec();
        v.extend(["-o", out]);
        if resume {
            v.push("--resume");
        }
        v
    };
    run_ok(d, &with_dir("whole", false));
    let jobs = 24;
    let sidecars = |p: &Path| {
        names_in(p)
            .iter()
            .filter(|n| n.ends_with(".json") && n.contains("wind-dir"))
            .count()
    };
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_seasynth"))
        .current_dir(d)
        .args(with_dir("cut", false))
        .spawn()
        .expect("seasynth starts");
    let cut = d.join("cut");
    let t0 = std::time::Instant::now();
    while !(cut.is_dir() && sidecars(&cut) >= 3) {
        assert!(
            t0.elapsed().as_secs() < 120,
            "the batch wrote no jobs in 2 minutes"
        );
        assert!(
            child.try_wait().unwrap().is_none(),
            "the batch ended before the kill"
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    child.kill().expect("SIGKILL"); // Child::kill sends SIGKILL on Unix.
    child.wait().unwrap();
    let done_at_kill = sidecars(&cut);
    eprintln!("killed with {done_at_kill} of {jobs} jobs complete");
    assert!(
        done_at_kill < jobs,
        "the kill came after the last job ({done_at_kill} of {jobs} done): the test needs slower jobs"
    );
    // A job killed between its outputs and its sidecar: not complete, so redone.
    let first = names_in(&cut)
        .into_iter()
        .find(|n| n.ends_with(".json") && n.contains("wind-dir"))
        .unwrap();
    std::fs::remove_file(cut.join(&first)).unwrap();
    // A staging file left by a killed job, as SIGKILL leaves them.
    let stale = cut.join(".20_wind-dir=300.png.abc123.part");
    std::fs::write(&stale, b"partial").unwrap();
    run_ok(d, &with_dir("cut", true));
    let whole = d.join("whole");
    assert_eq!(
        job_files(&cut),
        job_files(&whole),
        "the same files, no staging files left"
    );
    for f in job_files(&whole) {
        assert_eq!(
            read(&cut.join(&f)),
            read(&whole.join(&f)),
            "{f} differs after --resume"
        );
    }
    let index = json_file(&cut.join("index.json"));
    let kept = rows(&index)
        .iter()
        .filter(|r| r["status"] == "kept")
        .count();
    assert!(
        kept >= 2 && kept < done_at_kill,
        "{kept} jobs kept, {done_at_kill} were complete at the kill"
    );
    assert!(rows(&index).iter().all(|r| r["status"] != "failed"));
}

#[test]
fn resume_redoes_a_job_whose_sidecar_holds_other_parameters() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run_ok(
        d,
        &batch(&[
            "--sweep",
            "seed=1,2",
            "-o",
            "b",
            "-q",
            "--height-range",
            "-1:1",
        ]),
    );
    // The same names under another height range: every job's hash differs.
    let other_range = batch(&[
        "--sweep",
        "seed=1,2",
        "-o",
        "b",
        "-q",
        "--height-range",
        "-2:2",
        "--resume",
    ]);
    run_ok(d, &other_range);
    let index = json_file(&d.join("b/index.json"));
    assert!(
        rows(&index).iter().all(|r| r["status"] == "ok"),
        "{index:#}"
    );
    assert_eq!(
        num(&json_file(&d.join("b/0_seed=1.json")), "/mapping/min_m"),
        -2.0
    );
    // The same command again: now every job is complete with its hash.
    run_ok(d, &other_range);
    let index = json_file(&d.join("b/index.json"));
    assert!(
        rows(&index).iter().all(|r| r["status"] == "kept"),
        "{index:#}"
    );
}

#[test]
fn shards_cover_every_job_exactly_once_and_their_indexes_merge() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let sweep = ["--sweep", "wind-dir=0:360:45", "--sweep", "seed=1,2"];
    let mut whole = batch(&sweep);
    whole.extend(["-o", "whole", "-q"]);
    run_ok(d, &whole);
    let n = 3;
    let mut owner: BTreeMap<u64, usize> = BTreeMap::new();
    for k in 1..=n {
        let shard = format!("{k}/{n}");
        // Shards 1 and 2 share a folder; shard 3 has its own.
        let out = if k < 3 { "shared" } else { "third" };
        let mut a = batch(&sweep);
        a.extend(["--shard", &shard, "-o", out, "-q"]);
        run_ok(d, &a);
        let index = json_file(&d.join(format!("{out}/index.shard-{k}-of-{n}.json")));
        for r in rows(&index) {
            let job = r["job"].as_u64().unwrap();
            assert!(owner.insert(job, k).is_none(), "job {job} in two shards");
        }
    }
    assert_eq!(
        owner.len(),
        16,
        "the shards together hold every job: {owner:?}"
    );
    // Shards of one batch share its mapping: their files equal the unsharded run's.
    for f in job_files(&d.join("whole")) {
        let here = if d.join("shared").join(&f).is_file() {
            "shared"
        } else {
            "third"
        };
        assert_eq!(
            read(&d.join(here).join(&f)),
            read(&d.join("whole").join(&f)),
            "{f}"
        );
    }
    run_ok(d, &["batch", "--merge-index", "shared", "third", "-q"]);
    let merged = json_file(&d.join("shared/index.json"));
    let jobs: Vec<u64> = rows(&merged)
        .iter()
        .map(|r| r["job"].as_u64().unwrap())
        .collect();
    assert_eq!(
        jobs,
        (0..16).collect::<Vec<_>>(),
        "every job once, in order"
    );
    for r in rows(&merged) {
        for f in files_of(r) {
            assert!(
                d.join("shared").join(f).is_file(),
                "{f} of the merged index"
            );
        }
    }
    let whole_index = json_file(&d.join("whole/index.json"));
    assert_eq!(merged["batch"], whole_index["batch"], "the same batch");
    // An incomplete set of shards is refused, naming what is missing.
    let e = run_exit2(d, &["batch", "--merge-index", "third", "-o", "partial"]);
    assert!(e.contains("miss") && e.contains("0, 1"), "{e}");
}

#[test]
fn a_job_with_bad_parameters_fails_the_batch_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let stderr = run_exit2(d, &batch(&["--sweep", "wind-speed=7,-3,10,-4", "-o", "b"]));
    assert!(
        stderr.contains("job 1 1_wind-speed=-3: --wind-speed")
            && stderr.contains("(got -3)")
            && stderr.contains("and 1 more; --plan lists them"),
        "the first bad job and its value are named:\n{stderr}"
    );
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        names_in(d).is_empty(),
        "not even the folder: {:?}",
        names_in(d)
    );
    // --plan still lists every job, the bad ones with their error.
    let plan = run_ok(d, &batch(&["--sweep", "wind-speed=7,-3", "--plan"]));
    assert!(plan.contains("must be > 0"), "{plan}");
    // A good batch prints a plain line per job when stderr is not a terminal.
    let out = seasynth()
        .current_dir(d)
        .args(batch(&["--sweep", "wind-speed=7,10", "-o", "b"]))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("[2/2] job ") && stderr.contains("ETA"),
        "a plain line per job when stderr is not a terminal:\n{stderr}"
    );
}

#[test]
fn the_index_lists_the_files_on_disk_with_their_statistics() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run_ok(
        d,
        &batch(&[
            "--sweep",
            "time=0:2:0.5",
            "--format",
            "tif,png,normal",
            "-o",
            "b",
            "-q",
        ]),
    );
    let b = d.join("b");
    let index = json_file(&b.join("index.json"));
    let csv = std::fs::read_to_string(b.join("index.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 4, "a header and one line per job");
    let mut listed = BTreeSet::new();
    for (r, line) in rows(&index).iter().zip(csv.lines().skip(1)) {
        let files = files_of(r);
        assert_eq!(files.len(), 4, "tif, png, normal map and sidecar");
        for f in &files {
            assert!(b.join(f).is_file(), "{f} is listed but not on disk");
            listed.insert(f.to_string());
        }
        assert!(
            line.contains(&files.join(" ")),
            "the CSV row lists the files: {line}"
        );
        // The statistics are those of the written heights.
        let (_, _, t) = tiff32::read(&b.join(files[0])).unwrap();
        let min = t.iter().fold(f32::INFINITY, |a, &b| a.min(b)) as f64;
        let max = t.iter().fold(f32::NEG_INFINITY, |a, &b| a.max(b)) as f64;
        let mean = t.iter().map(|&v| v as f64).sum::<f64>() / t.len() as f64;
        let var = t.iter().map(|&v| (v as f64 - mean).powi(2)).sum::<f64>() / t.len() as f64;
        assert_eq!(num(r, "/stats/min_m"), min);
        assert_eq!(num(r, "/stats/max_m"), max);
        const HS_REL_TOL: f64 = 1e-9;
        let hs = num(r, "/stats/hs_m");
        assert!(
            (hs - 4.0 * var.sqrt()).abs() <= HS_REL_TOL * hs,
            "Hs {hs} is not 4·std = {}",
            4.0 * var.sqrt()
        );
        assert!(num(r, "/seconds") > 0.0);
        let hs_cell = line.split(',').nth(5).unwrap();
        assert_eq!(hs_cell.parse::<f64>().unwrap(), hs, "CSV and JSON agree");
    }
    assert_eq!(
        listed,
        job_files(&b),
        "every job file on disk is in the index"
    );
}

#[test]
fn a_manifest_gives_jobs_and_sweeps_and_names_the_line_of_an_unknown_key() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("m.toml"),
        r#"# two sea states, each at two directions
preset = "li-tian"
name = "{index}-{wind-speed}-{wind-dir}"
format = ["tif"]

[set]
method = "fft"
size = "32"
grid.extent_m = [64, 64]

[sweep]
wind-dir = [0, 90]

[[job]]
wind-speed = 6

[[job]]
wind = { speed_mps = 11 }
seed = 5
"#,
    )
    .unwrap();
    run_ok(d, &["batch", "--manifest", "m.toml", "-o", "m", "-q"]);
    let names: Vec<String> = rows(&json_file(&d.join("m/index.json")))
        .iter()
        .map(|r| r["name"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(names, ["0-6-0", "1-6-90", "2-11-0", "3-11-90"]);
    let side = json_file(&d.join("m/3-11-90.json"));
    assert_eq!(num(&side, "/params/seed"), 5.0);
    assert_eq!(num(&side, "/params/grid/extent_m/0"), 64.0);
    assert!(d.join("m/0-6-0.tif").is_file() && !d.join("m/0-6-0.png").exists());
    std::fs::write(
        d.join("bad.toml"),
        "[set]\nsize = \"32\"\n\n[[job]]\nwind.sped_mps = 3\n",
    )
    .unwrap();
    run_rejected(
        d,
        &["batch", "--manifest", "bad.toml", "-o", "bad"],
        &["bad.toml:5", "sped_mps"],
    );
    std::fs::write(d.join("bad2.toml"), "preset = \"calm\"\nsweeps = 3\n").unwrap();
    run_rejected(
        d,
        &["batch", "--manifest", "bad2.toml", "-o", "bad"],
        &["bad2.toml:2", "sweeps"],
    );
    assert!(
        !d.join("bad").exists(),
        "nothing written for a bad manifest"
    );
}

#[test]
fn bad_batch_arguments_are_one_line_errors_before_any_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: &[(&[&str], &[&str])] = &[
        (
            &["--sweep", "wind.sped=1,2", "-o", "x"],
            &["wind.sped", "unknown"],
        ),
        (
            &["--sweep", "wind-dir=0:90:-5", "-o", "x"],
            &["0:90:-5", "STEP"],
        ),
        (
            &["--sweep", "seed=1,2", "--name", "same", "-o", "x"],
            &["same", "{index}"],
        ),
        (
            &["--sweep", "seed=1,2", "--shard", "3/2", "-o", "x"],
            &["--shard", "3/2"],
        ),
        (
            &["--sweep", "seed=1,2", "--format", "gif", "-o", "x"],
            &["--format", "gif"],
        ),
        (
            &["--sweep", "seed=1,2", "--format", "normal", "-o", "x"],
            &["--format", "height"],
        ),
        (&["--sweep", "seed=1,2"], &["-o"]),
    ];
    for (extra, fragments) in cases {
        run_rejected(d, &batch(extra), fragments);
    }
    assert!(!d.join("x").exists(), "no output folder for bad arguments");
}

/// The FFT and filtered-noise methods draw each wavevector's Gaussian pair from (seed,
/// n, m) alone; the wind direction only scales the amplitudes. So across a direction
/// sweep h̃0(k) keeps its phase wherever both amplitudes are above zero.
#[test]
fn the_same_seed_gives_the_same_random_phases_at_every_wind_direction() {
    use seasynth::config::layers::{Assignment, resolve};
    use seasynth::field::fft::{SpectrumSetup, signed_index};
    use seasynth::field::{filtered_noise, spectrum_model};
    use seasynth::rng::{Stream, sub_seed};

    const PHASE_TOL_RAD: f64 = 1e-9;
    const PHASE_TOL_F32_RAD: f64 = 1e-5;
    for spectrum in ["phillips", "pierson-moskowitz"] {
        let params = |dir: &str| {
            resolve(
                None,
                &[
                    Assignment::flag("method", "fft"),
                    Assignment::flag("spectrum", spectrum),
                    Assignment::flag("wind-speed", "10"),
                    Assignment::flag("size", "32"),
                    Assignment::flag("extent", "400"),
                    Assignment::flag("seed", "9"),
                    Assignment::flag("wind-dir", dir),
                ],
            )
            .unwrap()
        };
        let (pa, pb) = (params("0"), params("130"));
        let (ma, da) = spectrum_model(&pa).unwrap();
        let (mb, db) = spectrum_model(&pb).unwrap();
        fn setup<'a>(
            m: &'a dyn seasynth::spectrum::Spectrum,
            dispersion: seasynth::spectrum::Dispersion,
            p: &seasynth::config::Params,
        ) -> SpectrumSetup<'a> {
            SpectrumSetup {
                spec: p.grid_spec(),
                spectrum: m,
                dispersion,
                seed: sub_seed(p.seed, Stream::SpectrumAmplitude),
                time_s: 0.0,
                loop_period_s: None,
            }
        }
        let (sa, sb) = (setup(ma.as_ref(), da, &pa), setup(mb.as_ref(), db, &pb));
        let mut compared = 0;
        for n in -15..16i64 {
            for m in -15..16i64 {
                let (a, b) = (sa.h0(n, m), sb.h0(n, m));
                if a.norm() > 0.0 && b.norm() > 0.0 {
                    let d = (a * b.conj()).arg().abs();
                    assert!(
                        d <= PHASE_TOL_RAD,
                        "{spectrum} ({n}, {m}): phases differ by {d} rad"
                    );
                    compared += 1;
                }
            }
        }
        assert!(
            compared > 200,
            "{spectrum}: only {compared} wavevectors compared"
        );
        assert!(
            (sa.h0(3, 0).norm() - sb.h0(3, 0).norm()).abs() > 0.0,
            "{spectrum}: the amplitudes do change with the direction"
        );
        // Filtered noise, Mastin's method: the same draws under the symmetrized filter.
        let (fa, fb) = (
            filtered_noise::filtered_spectrum(&sa, None),
            filtered_noise::filtered_spectrum(&sb, None),
        );
        let mut compared = 0;
        for (i, (a, b)) in fa.data.iter().zip(&fb.data).enumerate() {
            if a.norm() > 1e-20 && b.norm() > 1e-20 {
                let d = ((*a * b.conj()).arg() as f64).abs();
                let (line, bin) = (i / fa.ny, signed_index(i % fa.ny, fa.ny));
                assert!(
                    d <= PHASE_TOL_F32_RAD,
                    "filtered {spectrum} line {line} bin {bin}: {d} rad"
                );
                compared += 1;
            }
        }
        assert!(
            compared > 100,
            "filtered {spectrum}: only {compared} compared"
        );
    }
}

#[test]
fn tiled_jobs_list_their_tiles_and_are_kept_by_resume() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let args = batch(&[
        "--sweep",
        "seed=1,2",
        "--format",
        "obj,normal",
        "--tiles",
        "2x2",
        "-o",
        "t",
        "-q",
    ]);
    run_ok(d, &args);
    let index = json_file(&d.join("t/index.json"));
    let mut listed = BTreeSet::new();
    for r in rows(&index) {
        let files = files_of(r);
        assert_eq!(
            files.len(),
            4 + 1 + 1 + 1,
            "4 tiles, the tile index, the map, the sidecar"
        );
        listed.extend(files.iter().map(|f| f.to_string()));
    }
    assert_eq!(
        listed,
        job_files(&d.join("t")),
        "the index lists every file on disk"
    );
    let mut again = args.clone();
    again.push("--resume");
    run_ok(d, &again);
    let index = json_file(&d.join("t/index.json"));
    assert!(
        rows(&index).iter().all(|r| r["status"] == "kept"),
        "{index:#}"
    );
    // A missing tile makes its job incomplete.
    std::fs::remove_file(d.join("t/1_seed=2_x1_y1.obj")).unwrap();
    run_ok(d, &again);
    let statuses: Vec<Value> = rows(&json_file(&d.join("t/index.json")))
        .iter()
        .map(|r| r["status"].clone())
        .collect();
    assert_eq!(statuses, ["kept", "ok"]);
    assert!(d.join("t/1_seed=2_x1_y1.obj").is_file());
}

#[test]
fn the_li_tian_fig3_one_liner_gives_the_fig3_presets_under_one_mapping() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run_ok(
        d,
        &[
            "batch",
            "--preset",
            "li-tian",
            "--sweep",
            "wind-dir=0,45,90,135",
            "-o",
            "out/fig3",
            "-q",
        ],
    );
    let doc = json_file(&d.join("out/fig3/batch.json"));
    let range = format!(
        "{}:{}",
        num(&doc, "/mapping_min_m"),
        num(&doc, "/mapping_max_m")
    );
    for (i, deg) in [(1, 45), (2, 90), (3, 135)] {
        let preset = format!("li-tian-{deg}");
        run_ok(
            d,
            &[
                "generate",
                "--preset",
                &preset,
                &format!("--height-range={range}"),
                "-o",
                "g.png",
                "-q",
            ],
        );
        assert_eq!(
            read(&d.join("g.png")),
            read(&d.join(format!("out/fig3/{i}_wind-dir={deg}.png"))),
            "job {i} is not the {preset} preset under the batch's mapping"
        );
    }
}
