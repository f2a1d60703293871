//! `seasynth generate`: one field, written to every `-o` (format by extension).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use super::common::{resolve_params, set_threads};
use crate::cli::GenerateArgs;
use crate::config::presets;
use crate::export::Format;
use crate::export::options::ExportOptions;
use crate::pipeline::write::{SidecarExtras, write_field};

/// The default output stem: the preset's name (a file's stem + `-regenerated`), with
/// `-custom` when a flag or `--set` changed its parameters, so a file is never named after
/// a preset whose field it is not.
pub fn default_stem(preset: Option<&str>, changed: bool) -> String {
    let stem = match preset {
        None => presets::DEFAULT_PRESET.to_string(),
        Some(p) if presets::builtin(p).is_some() => p.to_string(),
        Some(p) => Path::new(p)
            .file_stem()
            .and_then(|s| s.to_str())
            .map(|s| format!("{s}-regenerated"))
            .unwrap_or_else(|| "seasynth".into()),
    };
    match changed {
        true => format!("{stem}-custom"),
        false => stem,
    }
}

/// What `generate` says it wrote for the output `path`: the file, or the pattern and count
/// of its tiles.
fn written_text(path: &Path, options: &ExportOptions) -> String {
    let tiled = Format::from_path(path).is_ok_and(|f| f.is_tiled());
    match options.tiles {
        Some(t)
            if tiled
                && crate::export::format::inner_kind(path)
                    .ok()
                    .flatten()
                    .is_none() =>
        {
            let first = crate::export::tiles::tile_path(path, 0, 0);
            let last = crate::export::tiles::tile_path(path, t.columns - 1, t.rows - 1);
            format!(
                "{} tiles {} … {}",
                t.columns * t.rows,
                first.display(),
                last.file_name().unwrap_or_default().to_string_lossy()
            )
        }
        _ => path.display().to_string(),
    }
}

/// Runs `seasynth generate`.
pub fn run(args: GenerateArgs) -> Result<()> {
    set_threads(args.threads)?;
    super::common::refuse_no_effect("generate", &args.field)?;
    let params = resolve_params(&args.field)?;
    let options = ExportOptions::from_flags(args.export.flags())?;
    let paths = if args.outputs.is_empty() {
        std::fs::create_dir_all("out").context("cannot create the folder out/")?;
        let changed = !args.field.in_order().is_empty();
        let stem = default_stem(args.field.preset.as_deref(), changed);
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
            eprintln!("wrote {}", written_text(p, &options));
        }
        if params.spectrum.model == crate::config::SpectrumModel::Phillips
            && matches!(
                params.method,
                crate::config::Method::Fft | crate::config::Method::Hybrid
            )
        {
            eprintln!(
                "note: phillips is Tessendorf's discrete convention (A scales the Fourier \
                 amplitudes): heights follow A and the grid, not meters of a real sea; \
                 pierson-moskowitz, jonswap and tma give meters"
            );
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
