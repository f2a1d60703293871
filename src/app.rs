//! What each command does, between the parsed command line and the library.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use crate::cli::{Cli, Command, FieldArgs, GenerateArgs};
use crate::config::layers::{self, Assignment};
use crate::config::{Params, presets};
use crate::error::Error;
use crate::export::sidecar::{self, FileEntry, MappingInfo, Sidecar};
use crate::export::{Format, HeightMapping, Output, Staged};
use crate::field;

/// Runs one command.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Generate(args) => generate(*args),
        Command::Presets { name } => list_presets(name.as_deref()),
        Command::Analyze(args) => crate::analyze::run(args),
        Command::Bench(args) => crate::bench::run(args),
        Command::Spectrum(args) => crate::spectrum_cmd::run(args),
    }
}

/// Sets the number of worker threads for the whole process.
pub fn set_threads(threads: Option<usize>) -> Result<()> {
    if let Some(n) = threads {
        if n == 0 {
            return Err(Error::Param(crate::error::ParamError {
                name: "--threads".into(),
                allowed: "≥ 1".into(),
                got: "0".into(),
            })
            .into());
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .context("cannot start worker threads")?;
    }
    Ok(())
}

/// Resolves the field parameters of a command line.
pub fn resolve_params(args: &FieldArgs) -> Result<Params, Error> {
    let mut assignments = Vec::new();
    for s in &args.set {
        assignments.push(Assignment::parse_set(s)?);
    }
    for (flag, value) in args.flags() {
        assignments.push(Assignment::flag(flag, value));
    }
    layers::resolve(args.preset.as_deref(), &assignments)
}

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

fn generate(args: GenerateArgs) -> Result<()> {
    set_threads(args.threads)?;
    let params = resolve_params(&args.field)?;
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
    // Stage every file before computing: a bad path fails now, not after the work.
    let mut outputs = Vec::new();
    for (i, p) in paths.iter().enumerate() {
        if paths[..i].contains(p) {
            return Err(Error::Output {
                path: p.clone(),
                message: "given twice".into(),
            }
            .into());
        }
        outputs.push(Output::prepare(p)?);
    }
    let mut sidecars: BTreeMap<PathBuf, Vec<&Output>> = BTreeMap::new();
    for o in &outputs {
        sidecars
            .entry(sidecar::path_for(&o.staged.path))
            .or_default()
            .push(o);
    }
    for side in sidecars.keys() {
        if paths.contains(side) {
            return Err(Error::Output {
                path: side.clone(),
                message: "is the sidecar of another output".into(),
            }
            .into());
        }
    }
    let mut staged_sidecars = Vec::new();
    for (side, outs) in &sidecars {
        let files = outs
            .iter()
            .map(|o| FileEntry {
                file: file_name(&o.staged.path),
                format: o.format,
            })
            .collect::<Vec<_>>();
        staged_sidecars.push((Staged::create(side)?, files));
    }

    let synthesis = field::synthesize(&params)?;
    let stats = synthesis.grid.stats();
    let (mapping, source) = match params.output.height_range {
        Some(r) => (
            HeightMapping {
                min_m: r.0[0],
                max_m: r.0[1],
            },
            "--height-range",
        ),
        None => (
            HeightMapping {
                min_m: stats.min_m,
                max_m: stats.max_m,
            },
            "field min..max",
        ),
    };
    let grid = &synthesis.grid;
    let has_png = outputs.iter().any(|o| o.format == Format::Png16);
    let results: Vec<Result<(), Error>> = {
        use rayon::prelude::*;
        outputs
            .into_par_iter()
            .map(|o| o.write(grid, &mapping))
            .collect()
    };
    for r in results {
        r?;
    }
    for (staged, files) in staged_sidecars {
        let mut doc = Sidecar::new(&params, &synthesis.info, stats);
        let png_here = files.iter().any(|f| f.format == Format::Png16);
        doc.files = files;
        if png_here {
            doc.mapping = Some(MappingInfo {
                range: mapping,
                step_m: mapping.step_m(),
                formula: sidecar::FORMULA,
                source,
            });
        }
        staged.write_with(|w| {
            serde_json::to_writer_pretty(&mut *w, &doc)?;
            std::io::Write::write_all(w, b"\n")
        })?;
    }
    if !args.quiet {
        let [nx, ny] = params.grid.size.0;
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
        for p in &paths {
            eprintln!("wrote {}", p.display());
        }
        if has_png {
            eprintln!(
                "16-bit mapping: {:.4} m → 0, {:.4} m → 65535",
                mapping.min_m, mapping.max_m
            );
        }
    }
    Ok(())
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn list_presets(name: Option<&str>) -> Result<()> {
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
