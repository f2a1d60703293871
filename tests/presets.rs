//! `seasynth presets`: the list, printing one as TOML, and an unknown name.

use std::path::Path;

use assert_cmd::Command;
use seasynth::config::presets::BUILTIN;

/// The presets the product promises so far.
const EXPECTED: &[&str] = &[
    "li-tian",
    "li-tian-fft",
    "li-tian-perlin",
    "li-tian-45",
    "li-tian-90",
    "li-tian-135",
    "tessendorf-usc",
];

fn seasynth() -> Command {
    Command::cargo_bin("seasynth").expect("the seasynth binary is built")
}

/// Runs `seasynth ARGS` in `dir`; panics with stderr unless it succeeds; returns stdout.
fn run_ok(dir: &Path, args: &[&str]) -> String {
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
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

#[test]
fn presets_lists_every_builtin_preset_with_a_description() {
    let dir = tempfile::tempdir().unwrap();
    let stdout = run_ok(dir.path(), &["presets"]);
    let listed: Vec<(&str, &str)> = stdout
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let l = l.trim();
            l.split_once(char::is_whitespace)
                .map(|(name, desc)| (name, desc.trim()))
                .unwrap_or((l, ""))
        })
        .collect();
    for (name, desc) in &listed {
        assert!(
            !desc.is_empty(),
            "preset `{name}` is listed without a description"
        );
    }
    let names: Vec<&str> = listed.iter().map(|(n, _)| *n).collect();
    let builtin = BUILTIN.iter().map(|(n, _)| *n);
    for want in EXPECTED.iter().copied().chain(builtin) {
        assert!(
            names.contains(&want),
            "`seasynth presets` does not list `{want}`; it lists {names:?}"
        );
    }
    assert_eq!(
        names.len(),
        BUILTIN.len(),
        "one line per built-in preset: {names:?}"
    );
    assert!(
        dir.path().read_dir().unwrap().next().is_none(),
        "listing presets writes no file"
    );
}

#[test]
fn a_preset_printed_as_toml_regenerates_the_same_bytes_as_its_name() {
    let dir = tempfile::tempdir().unwrap();
    for (name, _) in BUILTIN {
        let toml = run_ok(dir.path(), &["presets", name]);
        assert!(
            toml.contains('='),
            "`seasynth presets {name}` printed no TOML:\n{toml}"
        );
        let file = dir.path().join(format!("{name}-printed.toml"));
        std::fs::write(&file, &toml).unwrap();
        let by_name = format!("{name}-by-name");
        let by_file = format!("{name}-by-file");
        for (preset, stem) in [(name.to_string(), &by_name), (file_arg(&file), &by_file)] {
            run_ok(
                dir.path(),
                &[
                    "generate",
                    "--quiet",
                    "--preset",
                    &preset,
                    "--size",
                    "64",
                    "-o",
                    &format!("{stem}.png"),
                    "-o",
                    &format!("{stem}.tif"),
                ],
            );
        }
        for ext in ["png", "tif"] {
            let a = read(&dir.path().join(format!("{by_name}.{ext}")));
            let b = read(&dir.path().join(format!("{by_file}.{ext}")));
            assert!(
                a == b,
                "preset {name}: the .{ext} from `--preset {name}` ({} bytes) and from its \
                 printed TOML ({} bytes) differ",
                a.len(),
                b.len()
            );
        }
    }
}

fn file_arg(path: &Path) -> String {
    path.to_str().expect("UTF-8 temporary path").to_string()
}

#[test]
fn an_unknown_preset_name_exits_2_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = seasynth()
        .current_dir(dir.path())
        .args(["presets", "nope"])
        .output()
        .expect("seasynth runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(2),
        "`presets nope` must exit 2; stderr:\n{stderr}"
    );
    assert!(
        out.stdout.is_empty(),
        "`presets nope` printed on stdout: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert_eq!(
        stderr.lines().count(),
        1,
        "one line on stderr, got:\n{stderr}"
    );
    assert!(
        stderr.contains("`nope`"),
        "stderr does not name the preset: {stderr}"
    );
    assert!(
        stderr.contains("li-tian"),
        "stderr does not list the known presets: {stderr}"
    );
}
