//! A numbered frame sequence of one sea (`seasynth animate`, and the Python package's
//! `write_sequence`): frame k at t = time + k/fps, with one 16-bit height mapping for
//! every frame, a sidecar for the sequence and resuming.
//!
//! Frame files are numbered from the start frame (default 1 when an EXR is written, as
//! image-sequence readers expect, else 0): file number F holds frame k = F − start.
//!
//! Frame k is bit for bit the field of `generate --time t_k` with the same parameters:
//! the random draws are made once and kept (`field::Synthesizer`), and each frame redoes
//! only the time-dependent sines and cosines and the transforms. The frames are split into
//! `jobs` runs of consecutive frames (as many as the memory estimate allows), each
//! computed in order while the frame before it is written, its files at once
//! (`pipeline::jobs::run_overlapped`); the memory a frame frees is kept for the next
//! (`pipeline::memory::keep_freed_memory`).
//!
//! Foam (`pipeline::foam_fade`): one threshold for the sequence, resolved over frame 0,
//! and, with `--foam-fade`, foam that persists and fades from frame to frame, the same
//! bits in any run (such a sequence is computed as one run, in frame order).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::config::Params;
use crate::error::{Error, ParamError};
use crate::export::maps::{self, MapContext, MapEncoding, MapKind};
use crate::export::options::ExportOptions;
use crate::export::{Format, HeightMapping, Staged, exr, png16, tiff32};
use crate::field::{Synthesis, Synthesizer};
use crate::pipeline::foam_fade::{self, FoamRecord, SequenceFoam};
use crate::pipeline::jobs::{self, FileKind as Kind, Progress};
use crate::pipeline::memory::keep_freed_memory;

/// A computed frame: its staged files, its field and its persistent foam.
type Frame = (Vec<(Kind, Staged)>, Synthesis, Option<Vec<u16>>);

/// The sequence sidecar, `DIR/sequence.json`.
#[derive(Debug, Serialize, Deserialize)]
struct SequenceDoc {
    tool: String,
    version: String,
    frames: usize,
    fps: f64,
    /// Frame k shows t = start_time_s + k / fps.
    start_time_s: f64,
    /// Frame k's files carry the number start_frame + k.
    #[serde(default)]
    start_frame: usize,
    /// The axis convention of displacement EXRs: "y" (R, G, B = x, height, −y) or "z"
    /// (x, y, height).
    #[serde(default)]
    up: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    loop_period_s: Option<f64>,
    /// File names: the pattern with {k} the file number (start_frame + k), 5 digits.
    files: Vec<String>,
    /// The one 16-bit mapping of every frame's height PNG.
    mapping_min_m: f64,
    mapping_max_m: f64,
    mapping_source: String,
    /// The foam of every frame: the threshold resolved once, the fade.
    #[serde(default, skip_deserializing, skip_serializing_if = "Option::is_none")]
    foam: Option<FoamRecord>,
    params: Params,
}

/// The file of number `number` (the first frame's is `--start-frame`).
fn frame_path(dir: &Path, number: usize, kind: Kind) -> PathBuf {
    dir.join(format!("frame_{number:05}.{}", kind.suffix()))
}

/// A sequence to write: what `seasynth animate` takes from its command line.
pub struct Sequence<'a> {
    pub params: &'a Params,
    /// Number of frames, 1 … 1000000.
    pub frames: usize,
    /// Files per frame, as `--format` names them (`png`, `disp.exr`, `foam`, …).
    pub formats: &'a [String],
    /// How EXR frames are written, and the displacement's up axis.
    pub options: ExportOptions,
    /// Number in the first frame's file names (default: 1 with an EXR, else 0).
    pub start_frame: Option<usize>,
    /// Output folder (created if missing).
    pub dir: &'a Path,
    /// Frames computed at once (default: cores, limited by memory).
    pub jobs: Option<usize>,
    /// Skip frames whose files are all there.
    pub resume: bool,
    /// No progress bar.
    pub quiet: bool,
    /// Run even when the memory estimate exceeds the available memory.
    pub force: bool,
}

/// What [`write_sequence`] did.
#[derive(Debug, Clone, Copy)]
pub struct SequenceWritten {
    /// Frames written now, and frames kept from an earlier run (`resume`).
    pub written: usize,
    pub skipped: usize,
    /// The one 16-bit mapping of every height PNG (0..0 when none is written).
    pub mapping: HeightMapping,
}

/// The file kinds of `formats` (`--format`), each once, in order.
pub fn file_kinds(formats: &[String]) -> Result<Vec<Kind>, Error> {
    let mut kinds = Vec::new();
    for f in formats {
        let k = Kind::parse(f).map_err(Error::Param)?;
        if !kinds.contains(&k) {
            kinds.push(k);
        }
    }
    Ok(kinds)
}

/// Writes the frames of `seq` and `DIR/sequence.json`; every file is staged and appears
/// only when complete.
pub fn write_sequence(seq: &Sequence) -> Result<SequenceWritten> {
    keep_freed_memory();
    let params = seq.params;
    if seq.frames == 0 || seq.frames > 1_000_000 {
        return Err(Error::Param(ParamError {
            name: "--frames".into(),
            allowed: "1 … 1000000".into(),
            got: seq.frames.to_string(),
        })
        .into());
    }
    let kinds = file_kinds(seq.formats)?;
    let map_kinds: Vec<(MapKind, MapEncoding)> = kinds
        .iter()
        .filter_map(|k| match k {
            Kind::Map(m, e) => Some((*m, *e)),
            _ => None,
        })
        .collect();
    let options = &seq.options;
    let heights: Vec<Format> = kinds
        .iter()
        .filter_map(|k| match k {
            Kind::Png => Some(Format::Png16),
            Kind::Tif => Some(Format::Tiff32),
            Kind::Exr => Some(Format::Exr),
            _ => None,
        })
        .collect();
    options.check_outputs(&heights, &map_kinds, true)?;
    let start = seq
        .start_frame
        .unwrap_or(usize::from(kinds.iter().any(|k| k.is_exr())));
    if start > 1_000_000_000 {
        return Err(Error::Param(ParamError {
            name: "--start-frame".into(),
            allowed: "0 … 1000000000".into(),
            got: start.to_string(),
        })
        .into());
    }
    let mut extras = maps::extras_for(&map_kinds);
    extras.slopes |= kinds.contains(&Kind::Preview);
    // Heights are written (or previewed) only by these; a sequence of maps alone skips
    // the choppy resampling.
    extras.maps_only = !kinds
        .iter()
        .any(|k| matches!(k, Kind::Png | Kind::Tif | Kind::Exr | Kind::Preview));
    // Frames run `jobs` at a time, as many as the memory estimate allows, each with the
    // frame before it being written (two frames a job); the draws are kept for the whole
    // sequence (16 bytes a sample, measured).
    let n = params.grid_spec().len() as u64;
    let per_frame = crate::pipeline::memory::Footprint::of_field(params, extras)
        .with_outputs(kinds.len() as u64);
    let jobs = jobs::parallel_jobs(seq.jobs, per_frame.bytes(n, 2));
    let [nx, ny] = params.grid.size.0;
    crate::limits::check_memory(
        per_frame.bytes(n, 2 * jobs as u64).saturating_add(16 * n),
        &format!("{jobs} {nx}x{ny} {} frame(s) at once", params.method.name()),
        seq.force,
    )?;
    std::fs::create_dir_all(seq.dir)
        .map_err(|e| Error::io(seq.dir, e))
        .with_context(|| format!("cannot create {}", seq.dir.display()))?;
    let fps = params.motion.fps;
    let time_of = |k: usize| params.time_s + k as f64 / fps;
    let side_path = seq.dir.join("sequence.json");
    let earlier: Option<SequenceDoc> = if seq.resume {
        std::fs::read(&side_path)
            .ok()
            .and_then(|b| serde_json::from_slice(&b).ok())
    } else {
        None
    };
    if earlier
        .as_ref()
        .is_some_and(|e| e.params != *params || e.frames != seq.frames || e.start_frame != start)
    {
        return Err(Error::Output {
            path: side_path.clone(),
            message: "holds another sequence (other parameters, frame count or start frame): remove the folder or drop --resume".into(),
        }
        .into());
    }
    let synth = Synthesizer::new(params, extras, true)?;
    // Foam: one threshold for the sequence, and foam that persists and fades.
    let mut foam = foam_fade::applies(params, &map_kinds)
        .then(|| SequenceFoam::new(params, &synth, |k| params.time_s + k as f64 / fps));
    let quiet = seq.quiet;
    // One mapping for the whole sequence: given, kept from the earlier run, or the range
    // of every frame's heights (a first pass without files).
    let (mapping, source) = match (params.output.height_range, &earlier) {
        (Some(r), _) => (
            HeightMapping {
                min_m: r.0[0],
                max_m: r.0[1],
            },
            "--height-range".to_string(),
        ),
        (None, Some(e)) => (
            HeightMapping {
                min_m: e.mapping_min_m,
                max_m: e.mapping_max_m,
            },
            e.mapping_source.clone(),
        ),
        (None, None) if kinds.contains(&Kind::Png) => {
            let ranges = jobs::run_pool(seq.frames, jobs, |k| {
                let s = synth.heights(time_of(k)).stats();
                (s.min_m, s.max_m)
            });
            (
                jobs::union_range(ranges).expect("at least one frame"),
                "min..max over all frames".to_string(),
            )
        }
        (None, None) => (
            HeightMapping {
                min_m: 0.0,
                max_m: 0.0,
            },
            "no 16-bit heights written".to_string(),
        ),
    };
    if !(mapping.min_m.is_finite() && mapping.max_m.is_finite()) {
        return Err(Error::NotFinite {
            what: "the sequence's heights".into(),
            detail: format!("range {} … {} m", mapping.min_m, mapping.max_m),
        }
        .into());
    }
    let doc = SequenceDoc {
        tool: "seasynth".into(),
        version: env!("CARGO_PKG_VERSION").into(),
        frames: seq.frames,
        fps,
        start_time_s: params.time_s,
        start_frame: start,
        up: match options.up {
            crate::export::options::UpAxis::Y => "y".into(),
            crate::export::options::UpAxis::Z => "z".into(),
        },
        loop_period_s: params.motion.loop_period_s,
        files: kinds
            .iter()
            .map(|k| format!("frame_{{k}}.{}", k.suffix()))
            .collect(),
        mapping_min_m: mapping.min_m,
        mapping_max_m: mapping.max_m,
        mapping_source: source,
        foam: foam.as_ref().map(|f| f.record.clone()),
        params: params.clone(),
    };
    Staged::create(&side_path)?.write_json(&doc)?;
    let todo: Vec<usize> = (0..seq.frames)
        .filter(|&k| {
            !seq.resume
                || !kinds
                    .iter()
                    .all(|&kind| frame_path(seq.dir, start + k, kind).is_file())
        })
        .collect();
    if let Some(f) = foam.as_mut() {
        f.start(&todo);
    }
    let foam = foam.as_ref();
    // A still sea's foam map: J = 1 at every sample of every frame, so its threshold is
    // resolved once here instead of over each frame's identical J.
    let still_foam_threshold =
        (foam.is_none() && map_kinds.iter().any(|(m, _)| *m == MapKind::Foam)).then(|| {
            maps::FoamRule::of(params)
                .resolve(&vec![1.0f32; params.grid_spec().len()])
                .threshold
        });
    let bar = Progress::new(todo.len(), "frames", quiet, false);
    let cx_params = &params;
    // Frame k's files, staged first (a bad path fails before the work), its field and
    // its persistent foam (computed in frame order: see `pipeline::foam_fade`).
    let compute = |i: usize| -> Result<Frame, Error> {
        let k = todo[i];
        let _foam_guard = foam.and_then(|f| f.guard(k));
        let mut staged = Vec::new();
        for &kind in &kinds {
            staged.push((kind, Staged::create(&frame_path(seq.dir, start + k, kind))?));
        }
        let syn: Synthesis = synth.frame(time_of(k));
        crate::limits::check_finite(&syn.grid.stats(), &format!("frame {k}"))?;
        let persistent_foam = foam.and_then(|f| f.persistent(k, &syn));
        Ok((staged, syn, persistent_foam))
    };
    let write_file = |kind: Kind,
                      st: Staged,
                      syn: &Synthesis,
                      persistent_foam: Option<&[u16]>|
     -> Result<(), Error> {
        match kind {
            Kind::Png => st.write_with(|w| png16::write(w, &syn.grid, &mapping)),
            Kind::Tif => st.write_with(|w| tiff32::write(w, &syn.grid)),
            Kind::Exr => st.write_with(|w| exr::write_with(w, &syn.grid, options.exr)),
            Kind::Preview => {
                let img = crate::pipeline::preview::preview_of(cx_params, syn)?;
                crate::export::rgb8::write(st, &img.rgb, (img.width, img.height))
            }
            Kind::Map(m, e) => {
                let cx = MapContext {
                    params: cx_params,
                    synthesis: syn,
                    up: options.up,
                    exr: options.exr,
                    foam_threshold: foam.map(|f| f.threshold()).or(still_foam_threshold),
                    persistent_foam,
                };
                maps::write_map(m, e, st, &cx)
            }
        }
    };
    // The files of a frame are written at once, while the next frame is computed.
    let write = |i: usize, (staged, syn, persistent_foam): Frame| {
        staged
            .into_par_iter()
            .map(|(kind, st)| write_file(kind, st, &syn, persistent_foam.as_deref()))
            .collect::<Result<(), Error>>()?;
        bar.finished(&format!("frame {}", start + todo[i]));
        Ok(())
    };
    // Persistent foam makes each frame wait for the one before it: one run, in order.
    let runs = if foam.is_some_and(|f| f.fades()) {
        1
    } else {
        jobs
    };
    let result = jobs::run_overlapped(todo.len(), runs, compute, write);
    bar.finish();
    result?;
    Ok(SequenceWritten {
        written: todo.len(),
        skipped: seq.frames - todo.len(),
        mapping,
    })
}

/// A computed frame of a sequence, as values: what [`each_frame`] hands over.
pub struct FrameOut {
    /// Frame k (0 is the first), at `time_s` = time + k/fps.
    pub index: usize,
    pub time_s: f64,
    pub synthesis: Synthesis,
    /// The frame's foam coverage 0..1, when asked for: the values of its `foam.exr`
    /// (the sequence's one threshold, and the persistent foam of `motion.foam_fade_s`).
    pub foam: Option<Vec<f32>>,
}

/// Computes frames 0, 1, … `frames` − 1 of the sequence of `params`, in order, handing
/// each to `emit`, which returns `false` to stop early: the frames [`write_sequence`]
/// writes, bit for bit, as values. `extras`: the derived fields each frame computes;
/// `foam`: each frame's foam coverage too.
pub fn each_frame(
    params: &Params,
    frames: usize,
    mut extras: crate::field::dynamics::Extras,
    foam: bool,
    mut emit: impl FnMut(FrameOut) -> bool,
) -> Result<(), Error> {
    if frames == 0 || frames > 1_000_000 {
        return Err(Error::Param(ParamError {
            name: "--frames".into(),
            allowed: "1 … 1000000".into(),
            got: frames.to_string(),
        }));
    }
    extras.jacobian |= foam;
    let synth = Synthesizer::new(params, extras, true)?;
    let fps = params.motion.fps;
    let time_of = |k: i64| params.time_s + k as f64 / fps;
    let kinds = match foam {
        true => vec![(MapKind::Foam, MapEncoding::Exr)],
        false => Vec::new(),
    };
    let mut sequence_foam =
        foam_fade::applies(params, &kinds).then(|| SequenceFoam::new(params, &synth, time_of));
    if let Some(f) = sequence_foam.as_mut() {
        f.start(&(0..frames).collect::<Vec<_>>());
    }
    let n = params.grid_spec().len();
    let still_threshold = (foam && sequence_foam.is_none()).then(|| {
        maps::FoamRule::of(params)
            .resolve(&vec![1.0f32; n])
            .threshold
    });
    for k in 0..frames {
        let guard = sequence_foam.as_ref().and_then(|f| f.guard(k));
        let time_s = time_of(k as i64);
        let syn = synth.frame(time_s);
        crate::limits::check_finite(&syn.grid.stats(), &format!("frame {k}"))?;
        let foam_values = match (&sequence_foam, still_threshold) {
            (Some(f), _) => Some(match f.persistent(k, &syn) {
                Some(p) => p.iter().map(|&v| v as f32 / 65535.0).collect(),
                None => maps::foam_coverage_at(&syn, f.threshold()),
            }),
            (None, Some(t)) => Some(maps::foam_coverage_at(&syn, t)),
            (None, None) => None,
        };
        drop(guard);
        let out = FrameOut {
            index: k,
            time_s,
            synthesis: syn,
            foam: foam_values,
        };
        if !emit(out) {
            break;
        }
    }
    Ok(())
}
