//! Streamed outputs of procedural fields (`--method trochoid`): the field is computed in
//! batches of rows, each batch in parallel, and written as it comes, so an output may be
//! far larger than memory (32768² and beyond). Memory stays at one batch of ~8 MiB of
//! heights (at least 16 rows) and the writers' buffers, whatever the size.
//!
//! `generate` streams when the method is `trochoid` and every output is a height format
//! whose writer takes rows ([`RowSink`]: `.png` and `.tif`). Each output is one pass
//! over the field (rows are independent, so a pass is the same bits as the in-memory
//! field). A writer of 16-bit values (PNG) needs its mapping before its first row:
//! `--height-range` gives it; otherwise a first pass without files finds the field's
//! min..max (as the in-memory path does), unless a float writer (TIFF) written first has
//! already seen them. So a PNG alone costs two passes, or one with `--height-range`.

use std::path::PathBuf;

use anyhow::Result;
use rayon::prelude::*;

use crate::config::Params;
use crate::error::Error;
use crate::export::sidecar::{self, FileEntry, MappingInfo, Sidecar};
use crate::export::{Describe, Format, HeightMapping, Output, OutputKind, RowSink, Staged};
use crate::field::SynthesisInfo;
use crate::field::trochoid::{Frame, RowScratch, TrochoidSea};
use crate::grid::{GridSpec, Stats};

/// Heights per batch (at least one TIFF strip of rows).
const BATCH_BYTES: usize = 8 << 20;

/// True when `generate` streams these outputs: a method that streams rows (trochoid), only
/// height files whose writers take rows.
pub fn applies(params: &Params, paths: &[PathBuf]) -> bool {
    crate::field::method_for(params).streams_rows()
        && paths
            .iter()
            .all(|p| matches!(OutputKind::of_path(p), Ok(OutputKind::Height(f)) if f.streams()))
}

/// The row writer of an output (see [`applies`]).
fn sink(output: &Output) -> &dyn RowSink {
    output
        .exporter
        .row_sink()
        .expect("streamed outputs take rows")
}

/// Rows per batch for rows of `nx` samples: about `BATCH_BYTES` (8 MiB), a multiple of 16.
pub fn batch_rows(nx: usize) -> usize {
    (BATCH_BYTES / (4 * nx)).max(1).div_ceil(16) * 16
}

/// Running statistics over rows, combined in row order (Chan et al.'s pairwise update),
/// so they do not depend on the number of threads.
#[derive(Debug, Clone, Copy)]
pub struct Running {
    n: f64,
    mean: f64,
    m2: f64,
    min: f32,
    max: f32,
}

impl Default for Running {
    fn default() -> Self {
        Self {
            n: 0.0,
            mean: 0.0,
            m2: 0.0,
            min: f32::INFINITY,
            max: f32::NEG_INFINITY,
        }
    }
}

impl Running {
    /// The statistics of one row.
    pub fn of_row(row: &[f32]) -> Self {
        let n = row.len() as f64;
        let mean = row.iter().map(|&v| v as f64).sum::<f64>() / n;
        let m2 = row
            .iter()
            .map(|&v| (v as f64 - mean) * (v as f64 - mean))
            .sum();
        let (min, max) = row
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        Self {
            n,
            mean,
            m2,
            min,
            max,
        }
    }

    pub fn merge(&mut self, o: &Running) {
        let n = self.n + o.n;
        if n == 0.0 {
            return;
        }
        let d = o.mean - self.mean;
        self.mean += d * o.n / n;
        self.m2 += o.m2 + d * d * self.n * o.n / n;
        self.n = n;
        self.min = self.min.min(o.min);
        self.max = self.max.max(o.max);
    }

    pub fn stats(&self) -> Stats {
        let std = (self.m2 / self.n).sqrt();
        Stats {
            min_m: self.min as f64,
            max_m: self.max as f64,
            mean_m: self.mean,
            std_m: std,
            hs_m: 4.0 * std,
        }
    }
}

/// Fills `batch` with the rows `first..` of the field `spec` and adds their statistics.
pub fn fill_rows(
    frame: &Frame,
    spec: &GridSpec,
    first: usize,
    batch: &mut [f32],
    acc: &mut Running,
) {
    let rows: Vec<Running> = batch
        .par_chunks_mut(spec.nx)
        .enumerate()
        .map_init(RowScratch::default, |s, (r, row)| {
            frame.grid_row(spec, first + r, row, s);
            Running::of_row(row)
        })
        .collect();
    for r in &rows {
        acc.merge(r);
    }
}

/// `generate` for streamed outputs (see the module docs).
pub fn generate(
    params: &Params,
    paths: &[PathBuf],
    quiet: bool,
) -> Result<crate::pipeline::write::Written> {
    let spec = params.grid_spec();
    crate::pipeline::write::refuse_repeated(paths)?;
    // Stage every file (and one sidecar per stem) before any work.
    let mut outputs = Vec::new();
    for p in paths {
        let mut options = crate::export::options::ExportOptions::default();
        options.sample_at = params.grid.sample_at;
        outputs.push(Output::prepare_with(p, &options)?);
    }
    let mut stems: Vec<PathBuf> = Vec::new();
    for p in paths {
        let side = sidecar::path_for(p);
        if paths.contains(&side) {
            return Err(Error::Output {
                path: side,
                message: "would be written twice, as an output and as a sidecar".into(),
            }
            .into());
        }
        if !stems.contains(&side) {
            stems.push(side);
        }
    }
    let staged_sides = stems
        .iter()
        .map(|s| Staged::create(s))
        .collect::<Result<Vec<_>, _>>()?;

    let sea = TrochoidSea::new(params)?;
    let frame = sea.frame(params.time_s, Some((spec.dx_m(), spec.dy_m())));
    let info = SynthesisInfo::of_trochoid(params, &sea)?;
    // Writers without a mapping (TIFF) first: their pass also finds the range the others
    // need.
    outputs.sort_by_key(|o| o.exporter.uses_mapping());
    let mapped = |o: &Output| o.exporter.uses_mapping();
    let needs_range_pass = params.output.height_range.is_none()
        && outputs.iter().any(mapped)
        && outputs.iter().all(mapped);
    let passes = outputs.len() + needs_range_pass as usize;
    let bar = crate::pipeline::jobs::progress_bar(
        (passes * spec.ny) as u64,
        "{msg} {bar:40} {pos}/{len} rows, {per_sec}, ETA {eta}",
        !quiet,
    );
    let batch = batch_rows(spec.nx);
    let mut stats: Option<Stats> = None;
    if needs_range_pass {
        bar.set_message("range");
        let mut acc = Running::default();
        let mut buf = vec![0.0f32; batch * spec.nx];
        let mut first = 0;
        while first < spec.ny {
            let rows = batch.min(spec.ny - first);
            fill_rows(&frame, &spec, first, &mut buf[..rows * spec.nx], &mut acc);
            bar.inc(rows as u64);
            first += rows;
        }
        stats = Some(acc.stats());
    }
    let mut mapping: Option<(HeightMapping, &str)> = None;
    for output in &mut outputs {
        let files = std::mem::take(&mut output.files);
        let mut acc = Running::default();
        let mut fill = |first: usize, rows: &mut [f32]| {
            fill_rows(&frame, &spec, first, rows, &mut acc);
            bar.inc((rows.len() / spec.nx) as u64);
            Ok(())
        };
        bar.set_message(output.format().extension());
        let m = output.exporter.uses_mapping().then(|| {
            mapping
                .get_or_insert_with(|| {
                    HeightMapping::choose(params.output.height_range, "--height-range", || {
                        stats.expect("a pass has found the range")
                    })
                })
                .0
        });
        let sink = sink(output);
        let staged = files.into_iter().next().expect("one file");
        staged.write_with(|w| sink.write_rows(w, &spec, m.as_ref(), batch, &mut fill))?;
        stats.get_or_insert(acc.stats());
    }
    bar.finish_and_clear();
    let stats = stats.expect("at least one output");
    for (side, staged) in stems.iter().zip(staged_sides) {
        let mut doc = Sidecar::new(params, &info, stats);
        // In the order given.
        let of_stem: Vec<&Output> = paths
            .iter()
            .filter(|p| &sidecar::path_for(p) == side)
            .filter_map(|p| outputs.iter().find(|o| &o.path == p))
            .collect();
        let formats: Vec<Format> = of_stem.iter().map(|o| o.format()).collect();
        let (range, source) = mapping.unwrap_or((
            HeightMapping {
                min_m: stats.min_m,
                max_m: stats.max_m,
            },
            "field min..max",
        ));
        let cx = Describe {
            spec: &spec,
            mapping: &range,
            formats: &formats,
            exact_slopes: false,
        };
        for o in &of_stem {
            doc.files.push(FileEntry {
                file: crate::pipeline::write::file_name(&o.path),
                format: o.format(),
            });
            o.exporter.describe(&mut doc, &cx);
            if o.exporter.uses_mapping() {
                doc.mapping = Some(MappingInfo::new(range, source));
            }
        }
        staged.write_json(&doc)?;
    }
    Ok(crate::pipeline::write::Written {
        import_notes: Vec::new(),
        stats,
        mapping: mapping.map_or(
            HeightMapping {
                min_m: stats.min_m,
                max_m: stats.max_m,
            },
            |(m, _)| m,
        ),
        has_png: mapping.is_some(),
        files: paths.to_vec(),
    })
}
