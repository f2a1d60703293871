//! `seasynth generate`: one field, written to every `-o` (format by extension).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use super::common::{resolve_params, set_threads};
use crate::cli::GenerateArgs;
use crate::config::presets;
use crate::export::Format;
use crate::export::options::ExportOptions;
use crate::pipeline::write::{SidecarExtras, write_field};

/// The default output stem: the preset's name (or file stem), else `seasynth`.
fn default_stem(preset: Option<&str>) -> String {
    match preset {
        None => presets::DEFAULT_PRESET.to_string(),
        Some(p) if presets::builtin(p).is_some() => p.to_string(),
        Some(p) => Path::new(p)
            .file_stem()
            .and_then(|s| s.to_str())
            .map(|s| format!("{s}-regenerated"))
            .unwrap_or_else(|| "seasynth".into()),
    }
}

/// Runs `seasynth generate`.
pub fn run(args: GenerateArgs) -> Result<()> {
    set_threads(args.threads)?;
    let params = resolve_params(&args.field)?;
    let options = ExportOptions::from_flags(args.export.flags())?;
    let paths = if args.outputs.is_empty() {
        std::fs::create_dir_all("out").context("cannot create the folder out/")?;
        let stem = default_stem(args.field.preset.as_deref());
        vec![
            PathBuf::from(format!("out/{stem}.png")),
            PathBuf::from(format!("out/{stem}.tif")),
        ]
    } else {
        args.outputs.clone()
    };
    // A trochoid field written only to PNG and TIFF (no maps) is streamed: it may exceed
    // memory.
    let written = if crate::pipeline::stream::applies(&params, &paths) && options.engine.is_none() {
        let formats = paths
            .iter()
            .map(|p| Format::from_path(p))
            .collect::<Result<Vec<_>, _>>()?;
        options.check(&formats, crate::field::method_for(&params).is_periodic())?;
        crate::pipeline::stream::generate(&params, &paths, args.quiet)?
    } else {
        write_field(
            &params,
            &paths,
            &options,
            &SidecarExtras::default(),
            None,
            args.field.force,
        )?
    };
    if !args.quiet {
        let [nx, ny] = params.grid.size.0;
        let stats = written.stats;
        let mapping = written.mapping;
        eprintln!(
            "{} {nx}×{ny} over {}×{} m: std {:.3} m, Hs {:.3} m, min {:.3} m, max {:.3} m",
            params.method.name(),
            params.grid.extent_m.0[0],
            params.grid.extent_m.0[1],
            stats.std_m,
            stats.hs_m,
            stats.min_m,
            stats.max_m
        );
        for p in &written.files {
            eprintln!("wrote {}", p.display());
        }
        for note in &written.import_notes {
            eprintln!("import: {note}");
        }
        if written.has_png {
            eprintln!(
                "16-bit mapping: {:.4} m → 0, {:.4} m → 65535",
                mapping.min_m, mapping.max_m
            );
        }
    }
    Ok(())
}
