//! `seasynth presets`: the list, printing one as TOML, and an unknown name.

mod common;

use common::{read, run_ok, run_rejected};
use std::path::Path;

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
    // The message names the preset and lists the known ones.
    let dir = tempfile::tempdir().unwrap();
    run_rejected(dir.path(), &["presets", "nope"], &["`nope`", "li-tian"]);
}
