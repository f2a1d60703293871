//! Helpers shared by the tests that run the `seasynth` binary. Each test file uses a
//! subset, hence the `dead_code` allowance.
#![allow(dead_code)]

use std::path::Path;

use assert_cmd::Command;
use serde_json::Value;

pub fn seasynth() -> Command {
    Command::cargo_bin("seasynth").expect("the seasynth binary is built")
}

/// Runs `seasynth ARGS` in `dir`, panics with its stderr unless it succeeds, returns stdout.
pub fn run_ok(dir: &Path, args: &[&str]) -> String {
    let out = seasynth()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("seasynth runs");
    assert!(
        out.status.success(),
        "seasynth {} failed with {:?}:\n{}",
        args.join(" "),
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("stdout is UTF-8")
}

/// `analyze FILE --json` in `dir`, parsed; stdout must be exactly one JSON object.
pub fn analyze_json(dir: &Path, file: &str) -> Value {
    let out = run_ok(dir, &["analyze", file, "--json"]);
    assert_eq!(
        out.trim_end().lines().count(),
        1,
        "one line of JSON:\n{out}"
    );
    let doc: Value =
        serde_json::from_str(&out).unwrap_or_else(|e| panic!("not JSON ({e}):\n{out}"));
    assert!(doc.is_object(), "one JSON object: {doc}");
    doc
}

/// Runs `seasynth ARGS` in `dir`, expects exit code 2 and nothing on stdout; returns stderr.
pub fn run_exit2(dir: &Path, args: &[&str]) -> String {
    let out = seasynth()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("seasynth runs");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let shown = format!("`seasynth {}`", args.join(" "));
    assert_eq!(
        out.status.code(),
        Some(2),
        "{shown} must exit with code 2; stderr:\n{stderr}"
    );
    assert!(
        out.stdout.is_empty(),
        "{shown} printed on stdout: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    stderr
}

/// [`run_exit2`], plus exactly one line on stderr containing every fragment.
pub fn run_rejected(dir: &Path, args: &[&str], fragments: &[&str]) -> String {
    let stderr = run_exit2(dir, args);
    let shown = format!("`seasynth {}`", args.join(" "));
    assert_eq!(
        stderr.trim_end().lines().count(),
        1,
        "{shown} must print exactly one line on stderr, got:\n{stderr}"
    );
    for f in fragments {
        assert!(
            stderr.contains(f),
            "{shown}: stderr does not name `{f}`:\n{stderr}"
        );
    }
    stderr
}

pub fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

pub fn json_file(path: &Path) -> Value {
    serde_json::from_slice(&read(path))
        .unwrap_or_else(|e| panic!("{} is not JSON: {e}", path.display()))
}

pub fn num(doc: &Value, pointer: &str) -> f64 {
    doc.pointer(pointer)
        .and_then(Value::as_f64)
        .unwrap_or_else(|| panic!("no number at {pointer} in {doc:#}"))
}

/// Every entry directly in `dir`, hidden ones included, sorted.
pub fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("readable folder")
        .map(|e| {
            e.expect("folder entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    names.sort();
    names
}
