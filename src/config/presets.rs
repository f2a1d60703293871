//! Built-in presets (`presets/*.toml`, compiled into the binary) and preset files.
//!
//! A preset is a parameter file: TOML, or the JSON sidecar of an earlier output (its
//! `params` object), which regenerates that output exactly. The first comment line of a
//! built-in preset is its one-line description.

use std::path::Path;

use super::Params;
use crate::error::{Error, Result};

/// `(name, text)` of built-in presets, read from `presets/NAME.toml` at compile time.
macro_rules! builtin_presets {
    ($($name:literal),* $(,)?) => {
        &[$(($name, include_str!(concat!("../../presets/", $name, ".toml")))),*]
    };
}

/// Name and TOML text of every built-in preset.
pub const BUILTIN: &[(&str, &str)] = builtin_presets![
    "li-tian",
    "li-tian-fft",
    "li-tian-perlin",
    "li-tian-45",
    "li-tian-90",
    "li-tian-135",
    "tessendorf-usc",
    "mastin-1987",
    "fractal-terrain",
    "calm",
    "moderate",
    "storm",
    "storm-loop",
    "swell",
    "thon-2000",
    "thon-2000-calm",
    "thon-2000-storm",
];

/// The preset used when none is named.
pub const DEFAULT_PRESET: &str = "li-tian";

/// TOML text of a built-in preset.
pub fn builtin(name: &str) -> Option<&'static str> {
    BUILTIN.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The one-line description of a preset text: its first comment line.
pub fn description(text: &str) -> &str {
    text.lines()
        .find_map(|l| l.trim().strip_prefix('#'))
        .map(str::trim)
        .unwrap_or("")
}

/// Parses TOML preset text; errors name the source, the line and the key.
pub fn parse_toml(source: &str, text: &str) -> Result<Params> {
    let params = toml::from_str::<Params>(text).map_err(|e| {
        let line = e.span().map(|s| key_line(text, s.start, e.message()));
        let line = line.map(|l| format!(":{l}")).unwrap_or_default();
        Error::Preset(format!("{source}{line}: {}", one_line(e.message())))
    })?;
    params
        .validate()
        .map_err(|e| Error::Preset(format!("{source}: {e}")))?;
    Ok(params)
}

/// The line of an error at byte `start`. For an unknown field inside a table that serde
/// buffers (a tagged enum such as `[blend.alpha]`), the span is the table's; the line
/// of the key itself is then the first line from there that assigns it.
fn key_line(text: &str, start: usize, message: &str) -> usize {
    let start = start.min(text.len());
    let line = text[..start].matches('\n').count() + 1;
    let field = message
        .strip_prefix("unknown field `")
        .and_then(|rest| rest.split('`').next());
    if let Some(field) = field {
        for (i, l) in text.lines().enumerate().skip(line - 1) {
            let l = l.trim_start();
            if let Some(rest) = l.strip_prefix(field) {
                if rest.trim_start().starts_with('=') {
                    return i + 1;
                }
            }
        }
    }
    line
}

/// Parses a JSON parameter file: a sidecar (its `params`) or a bare parameter object.
pub fn parse_json(source: &str, text: &str) -> Result<Params> {
    let bad = |e: serde_json::Error| {
        Error::Preset(format!(
            "{source}:{}: {}",
            e.line(),
            one_line(&e.to_string())
        ))
    };
    let value: serde_json::Value = serde_json::from_str(text).map_err(bad)?;
    let params = match value.get("params") {
        Some(p) => p.clone(),
        None => value,
    };
    serde_json::from_value(params)
        .map_err(|e| Error::Preset(format!("{source}: {}", one_line(&e.to_string()))))
}

fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Loads a preset by built-in name or file path (`.toml` or `.json`).
pub fn load(name_or_path: &str) -> Result<Params> {
    if let Some(text) = builtin(name_or_path) {
        return parse_toml(name_or_path, text);
    }
    let path = Path::new(name_or_path);
    if path.is_file() {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Input {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        return match path.extension().and_then(|e| e.to_str()) {
            Some("json") => parse_json(name_or_path, &text),
            _ => parse_toml(name_or_path, &text),
        };
    }
    let names: Vec<&str> = BUILTIN.iter().map(|(n, _)| *n).collect();
    let hint = crate::error::did_you_mean(name_or_path, names.iter().copied());
    Err(Error::Preset(format!(
        "--preset {name_or_path}: no such preset or file{hint} (built-in presets: {})",
        names.join(", ")
    )))
}

impl Params {
    /// The parameters of a built-in preset (`li-tian`, `storm`, …; `seasynth presets`
    /// lists them) or of a `.toml`/`.json` preset file or sidecar.
    pub fn preset(name_or_path: &str) -> Result<Params> {
        load(name_or_path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_preset_parses_validates_and_describes_itself() {
        for (name, text) in BUILTIN {
            let p = parse_toml(name, text).unwrap_or_else(|e| panic!("{name}: {e}"));
            p.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(
                !description(text).is_empty(),
                "{name} needs a description comment"
            );
        }
    }

    #[test]
    fn the_default_preset_is_the_default_parameter_set() {
        assert_eq!(load(DEFAULT_PRESET).unwrap(), Params::default());
    }

    #[test]
    fn unknown_key_error_names_key_and_line() {
        let e = parse_toml(
            "bad.toml",
            "seed = 1\n[perlin]\noctaves = 3\nocataves = 4\n",
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("bad.toml:4: "), "{e}");
        assert!(e.contains("ocataves"), "{e}");
        assert!(!e.contains('\n'), "one line: {e}");
    }

    #[test]
    fn a_sidecar_is_a_preset() {
        let p = Params {
            seed: 99,
            ..Params::default()
        };
        let side = serde_json::json!({ "tool": "seasynth", "params": p });
        assert_eq!(parse_json("x.json", &side.to_string()).unwrap(), p);
    }
}
