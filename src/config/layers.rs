//! Layering: defaults < preset < `--set KEY=VALUE` and flags, in the order given.
//!
//! Each assignment names a preset key (`wind.speed_mps`, `perlin.octaves`) or a flag's
//! name without dashes (`wind-speed`, `size`); the value is read as TOML (`3`, `1e-7`,
//! `true`, `[512, 256]`, `{ kind = "constant", value = 0.5 }`) or, failing that, as a
//! string (`fft`, `512x256`, `-1:1`). Setting a `kind` key replaces the table it selects
//! (`blend.alpha.kind=radial` starts a radial α with its defaults).

use toml::{Table, Value};

use super::{Params, presets};
use crate::error::{Error, Result};

/// Flag names accepted by `--set` and `--sweep`, and the preset key each stands for.
pub const FLAG_KEYS: &[(&str, &str)] = &[
    ("method", "method"),
    ("seed", "seed"),
    ("time", "time_s"),
    ("size", "grid.size"),
    ("extent", "grid.extent_m"),
    ("wind-speed", "wind.speed_mps"),
    ("wind-dir", "wind.direction_deg"),
    ("spectrum", "spectrum.model"),
    ("spreading", "spectrum.spreading"),
    ("fetch-km", "spectrum.fetch_km"),
    ("depth", "spectrum.depth_m"),
    ("hs", "spectrum.hs_m"),
    ("tp", "spectrum.tp_s"),
    ("gamma", "spectrum.gamma"),
    ("nonlinear", "spectrum.nonlinear"),
    ("height-range", "output.height_range"),
    ("loop-period", "motion.loop_period_s"),
    ("choppiness", "motion.choppiness"),
    ("foam-threshold", "motion.foam_threshold"),
    ("foam-fade", "motion.foam_fade_s"),
    ("fps", "motion.fps"),
    ("phase-mode", "motion.phase_mode"),
    ("sample-at", "grid.sample_at"),
];

/// The preset key a user's key stands for.
pub fn canonical_key(key: &str) -> &str {
    FLAG_KEYS
        .iter()
        .find(|(flag, _)| *flag == key)
        .map(|(_, k)| *k)
        .unwrap_or(key)
}

/// One `KEY=VALUE` assignment, and where it came from (for error messages).
#[derive(Debug, Clone, PartialEq)]
pub struct Assignment {
    pub origin: String,
    pub key: String,
    pub value: String,
}

impl Assignment {
    /// Parses `KEY=VALUE` as typed after `--set`.
    pub fn parse_set(text: &str) -> Result<Self> {
        let (k, v) = text.split_once('=').ok_or_else(|| Error::Set {
            origin: format!("--set {text}"),
            message: "expected KEY=VALUE".into(),
        })?;
        Ok(Self {
            origin: format!("--set {text}"),
            key: k.trim().to_string(),
            value: v.trim().to_string(),
        })
    }

    /// An assignment made by a flag (`--wind-speed 7` is `wind-speed=7`).
    pub fn flag(flag: &str, value: impl ToString) -> Self {
        let value = value.to_string();
        Self {
            origin: format!("--{flag} {value}"),
            key: flag.to_string(),
            value,
        }
    }
}

/// A value as TOML if it parses as one, else as a string. TOML's hexadecimal, octal and
/// binary integers are not read as numbers: `--size 0x64` is the size `0x64` (0 by 64,
/// refused), not 100.
pub fn parse_value(raw: &str) -> Value {
    let digits = raw.trim().trim_start_matches(['+', '-']);
    if ["0x", "0o", "0b"].iter().any(|p| digits.starts_with(p)) {
        return Value::String(raw.to_string());
    }
    toml::from_str::<Table>(&format!("v = {raw}"))
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| Value::String(raw.to_string()))
}

fn set_path(table: &mut Table, key: &str, value: Value) -> std::result::Result<(), String> {
    let parts: Vec<&str> = key.split('.').collect();
    if parts.iter().any(|p| p.is_empty()) {
        return Err(format!("`{key}` is not a key"));
    }
    let (last, parents) = parts.split_last().expect("split gives one part at least");
    let mut cur = table;
    for p in parents {
        let entry = cur
            .entry(p.to_string())
            .or_insert_with(|| Value::Table(Table::new()));
        cur = entry
            .as_table_mut()
            .ok_or_else(|| format!("`{p}` in `{key}` is a value, not a table"))?;
    }
    if *last == "kind" {
        cur.clear();
    }
    cur.insert(last.to_string(), value);
    Ok(())
}

/// `; did you mean …?` for serde's `unknown field `X`, expected one of `a`, `b`` or
/// `unknown variant …` in `message`, about the assignment to `key`: the closest name
/// allowed (for a key, among the flag names too, given with the preset key it stands for).
pub fn suggestion(message: &str, key: &str) -> String {
    let ticked = |s: &str| -> Vec<String> {
        s.split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_string)
            .collect()
    };
    let (field, rest) = if let Some(r) = message.split_once("unknown field ") {
        (true, r.1)
    } else if let Some(r) = message.split_once("unknown variant ") {
        (false, r.1)
    } else {
        return String::new();
    };
    let words = ticked(rest);
    let Some((bad, allowed)) = words.split_first() else {
        return String::new();
    };
    if !field {
        return crate::error::did_you_mean(bad, allowed.iter().map(String::as_str));
    }
    let canonical = canonical_key(key);
    let parts: Vec<&str> = canonical.split('.').collect();
    let depth = parts.iter().position(|p| p == bad).unwrap_or(0);
    let prefix = parts[..depth].join(".");
    let flags: Vec<&str> = match depth {
        0 if !key.contains('.') => FLAG_KEYS.iter().map(|(f, _)| *f).collect(),
        _ => Vec::new(),
    };
    let typed = if depth == 0 { key } else { bad.as_str() };
    match crate::error::closest(typed, allowed.iter().map(String::as_str).chain(flags)) {
        Some(c) if FLAG_KEYS.iter().any(|(f, _)| *f == c) => {
            format!("; did you mean `{c}` ({})?", canonical_key(c))
        }
        Some(c) if prefix.is_empty() => format!("; did you mean `{c}`?"),
        Some(c) => format!("; did you mean `{prefix}.{c}`?"),
        None => String::new(),
    }
}

/// Resolves the preset (default: `li-tian`) and the assignments into validated parameters.
pub fn resolve(preset: Option<&str>, assignments: &[Assignment]) -> Result<Params> {
    let base = presets::load(preset.unwrap_or(presets::DEFAULT_PRESET))?;
    apply(base, assignments)
}

/// Applies assignments over `base`, then validates.
pub fn apply(base: Params, assignments: &[Assignment]) -> Result<Params> {
    let mut table = Table::try_from(&base).expect("parameters serialize to TOML");
    // An assignment may need the next one to complete it (`kind`, then its fields), so
    // the table is checked after each, and a failure is blamed on the assignment that
    // began the run of failing states that reaches the end.
    let mut first_failing: Option<&Assignment> = None;
    let mut last_error = None;
    for a in assignments {
        set_path(&mut table, canonical_key(&a.key), parse_value(&a.value)).map_err(|message| {
            Error::Set {
                origin: a.origin.clone(),
                message,
            }
        })?;
        match table.clone().try_into::<Params>() {
            Ok(_) => first_failing = None,
            Err(e) => {
                first_failing.get_or_insert(a);
                last_error = Some(e);
            }
        }
    }
    if let (Some(a), Some(e)) = (first_failing, last_error) {
        let message = e.message().split_whitespace().collect::<Vec<_>>().join(" ");
        let hint = suggestion(&message, &a.key);
        return Err(Error::Set {
            origin: a.origin.clone(),
            message: format!("{message}{hint}"),
        });
    }
    let params: Params = table.try_into().expect("the last state deserialized");
    params.validate()?;
    Ok(params)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{AlphaConfig, Method, Size2};

    fn set(s: &str) -> Assignment {
        Assignment::parse_set(s).unwrap()
    }

    #[test]
    fn command_line_beats_preset_beats_defaults() {
        let p = resolve(Some("li-tian-90"), &[]).unwrap();
        assert_eq!(p.wind.direction_deg, 90.0);
        assert_eq!(
            p.grid.size,
            Size2([512, 512]),
            "untouched keys keep the defaults"
        );
        let p = resolve(
            Some("li-tian-90"),
            &[
                set("wind.direction_deg=30"),
                Assignment::flag("wind-dir", 45),
            ],
        )
        .unwrap();
        assert_eq!(p.wind.direction_deg, 45.0, "later assignments win");
    }

    #[test]
    fn flag_names_and_keys_and_loose_values() {
        let p = resolve(
            None,
            &[
                set("size=64x32"),
                set("method=fft"),
                set("perlin.octaves=3"),
                set("height-range=-1:2"),
            ],
        )
        .unwrap();
        assert_eq!(p.grid.size, Size2([64, 32]));
        assert_eq!(p.method, Method::Fft);
        assert_eq!(p.perlin.octaves, 3);
        assert_eq!(p.output.height_range.unwrap().0, [-1.0, 2.0]);
    }

    #[test]
    fn setting_a_kind_starts_a_fresh_table() {
        let p = resolve(
            None,
            &[
                set("blend.alpha.kind=constant"),
                set("blend.alpha.value=0.25"),
            ],
        )
        .unwrap();
        assert_eq!(p.blend.alpha, AlphaConfig::Constant { value: 0.25 });
    }

    #[test]
    fn errors_name_the_assignment() {
        let e = resolve(None, &[set("wind.sped_mps=3")])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--set wind.sped_mps=3: "), "{e}");
        assert!(e.contains("sped_mps"), "{e}");
        let e = resolve(None, &[Assignment::flag("wind-speed", -3)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("--wind-speed") && e.contains("-3"), "{e}");
        let e = resolve(None, &[set("method=spline")])
            .unwrap_err()
            .to_string();
        assert!(e.contains("spline") && e.contains("hybrid"), "{e}");
        assert!(Assignment::parse_set("novalue").is_err());
    }

    #[test]
    fn unknown_names_get_the_closest_one_suggested() {
        let e = resolve(None, &[set("wind-dri=90")])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("did you mean `wind-dir` (wind.direction_deg)?"),
            "{e}"
        );
        let e = resolve(None, &[set("wind.directon_deg=90")])
            .unwrap_err()
            .to_string();
        assert!(e.contains("did you mean `wind.direction_deg`?"), "{e}");
        let e = resolve(None, &[Assignment::flag("method", "fftt")])
            .unwrap_err()
            .to_string();
        assert!(e.contains("did you mean `fft`?"), "{e}");
        let e = resolve(None, &[Assignment::flag("spectrum", "jonswop")])
            .unwrap_err()
            .to_string();
        assert!(e.contains("did you mean `jonswap`?"), "{e}");
        let e = resolve(None, &[Assignment::flag("spreading", "hasselman")])
            .unwrap_err()
            .to_string();
        assert!(e.contains("did you mean `hasselmann`?"), "{e}");
        let e = resolve(None, &[set("zzzzzzzz=1")]).unwrap_err().to_string();
        assert!(!e.contains("did you mean"), "nothing close: {e}");
    }
}
