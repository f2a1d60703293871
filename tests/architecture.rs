//! The layers of the library import only downward (docs/architecture.md): each top-level
//! module may `use` only modules of a lower layer, never one of its own layer or above.
//! Test modules are not checked (a test may build its inputs with anything): inline
//! `#[cfg(test)]` modules and the `tests.rs` files beside their modules.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The layer table, lowest first: a module may import the modules of lower rows only.
const LAYERS: &[&[&str]] = &[
    &["units"],
    &["error"],
    &["grid", "fastmath"],
    &["limits", "rng"],
    &["simd", "raster"],
    &["config", "spectrum"],
    &["measure"],
    &["field"],
    &["export"],
    &["io", "render"],
    &["plot"],
    &["pipeline"],
    &["cli"],
    &["commands"],
];

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|row| row.contains(&module))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level module a file belongs to (`src/field/fft.rs` → `field`).
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?;
    let first = rel.components().next()?.as_os_str().to_str()?;
    Some(first.trim_end_matches(".rs").to_string())
}

/// The production part of a file: everything before its first `#[cfg(test)]` item.
fn production(text: &str) -> &str {
    match text.find("#[cfg(test)]") {
        Some(i) => &text[..i],
        None => text,
    }
}

/// Every `crate::NAME` a text names, outside comments.
fn crate_paths(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(i) = rest.find("crate::") {
            let after = &rest[i + "crate::".len()..];
            let name: String = after
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                found.push((n + 1, name));
            }
            rest = after;
        }
    }
    found
}

#[test]
fn every_module_is_in_the_layer_table() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut missing = Vec::new();
    for f in &files {
        let m = module_of(&src, f).unwrap();
        if m != "lib" && m != "main" && layer_of(&m).is_none() {
            missing.push(m);
        }
    }
    missing.sort();
    missing.dedup();
    assert!(missing.is_empty(), "modules without a layer: {missing:?}");
}

#[test]
fn imports_point_only_to_lower_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut wrong: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for f in &files {
        let m = module_of(&src, f).unwrap();
        let Some(layer) = layer_of(&m) else { continue };
        // A module's `tests.rs` or `tests/` beside it is a test module (`#[cfg(test)] mod
        // tests;` in the module's mod.rs).
        let rel = f.strip_prefix(&src).unwrap();
        let parts: Vec<&str> = rel.iter().filter_map(|c| c.to_str()).collect();
        if let Some(at) = parts.iter().position(|&c| c == "tests" || c == "tests.rs") {
            let owner = src.join(parts[..at].join("/")).join("mod.rs");
            let declared = std::fs::read_to_string(&owner).unwrap_or_default();
            assert!(
                declared.contains("#[cfg(test)]\nmod tests;"),
                "{} is skipped as a test module, but {} does not declare it as one",
                f.display(),
                owner.display()
            );
            continue;
        }
        let text = std::fs::read_to_string(f).unwrap();
        for (line, name) in crate_paths(production(&text)) {
            if name == m {
                continue;
            }
            match layer_of(&name) {
                Some(l) if l < layer => {}
                _ => wrong
                    .entry(format!(
                        "{}:{line}",
                        f.strip_prefix(&src).unwrap().display()
                    ))
                    .or_default()
                    .push(format!("{m} → {name}")),
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports that do not point down the layer table:\n{}",
        wrong
            .iter()
            .map(|(k, v)| format!("  src/{k}: {}", v.join(", ")))
            .collect::<Vec<_>>()
            .join("\n")
    );
}

#[test]
fn the_checker_finds_paths_and_skips_comments_and_tests() {
    let text = "use crate::grid::Grid; // crate::commands\nfn f() { crate::field::x(); }\n#[cfg(test)]\nmod tests { use crate::commands; }\n";
    let names: Vec<String> = crate_paths(production(text))
        .into_iter()
        .map(|(_, n)| n)
        .collect();
    assert_eq!(names, ["grid", "field"]);
    assert!(layer_of("commands") > layer_of("pipeline"));
    assert!(layer_of("field") > layer_of("spectrum"));
}
