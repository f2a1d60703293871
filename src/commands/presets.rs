//! `seasynth presets`: the built-in presets, or one of them as TOML.

use anyhow::Result;

use crate::config::presets;
use crate::error::Error;

/// Runs `seasynth presets [NAME]`.
pub fn run(name: Option<&str>) -> Result<()> {
    match name {
        Some(n) => {
            let text = presets::builtin(n).ok_or_else(|| {
                let names: Vec<&str> = presets::BUILTIN.iter().map(|(n, _)| *n).collect();
                Error::Preset(format!(
                    "no preset `{n}` (built-in presets: {})",
                    names.join(", ")
                ))
            })?;
            print!("{text}");
        }
        None => {
            let width = presets::BUILTIN
                .iter()
                .map(|(n, _)| n.len())
                .max()
                .unwrap_or(0);
            for (n, text) in presets::BUILTIN {
                println!("{n:width$}  {}", presets::description(text));
            }
        }
    }
    Ok(())
}
