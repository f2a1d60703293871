//! `seasynth animate`: a numbered frame sequence of one sea, frame k at
//! t = time + k/fps, with one 16-bit height mapping for every frame, a sidecar for the
//! sequence and `--resume`.
//!
//! Frame files are numbered from `--start-frame` (default 1 when an EXR is written, as
//! image-sequence readers expect, else 0): file number F holds frame k = F − start.
//!
//! Frame k is bit for bit the field of `generate --time t_k` with the same parameters:
//! the random draws are made once and kept (`field::Synthesizer`), and each frame redoes
//! only the time-dependent sines and cosines and the transforms. The frames are split into
//! `--jobs` runs of consecutive frames (as many as the memory estimate allows), each
//! computed in order while the frame before it is written, its files at once
//! (`pipeline::jobs::run_overlapped`); the memory a frame frees is kept for the next
//! (`pipeline::memory::keep_freed_memory`).
//!
//! Foam (`pipeline::foam_fade`): one threshold for the sequence, resolved over frame 0,
//! and, with `--foam-fade`, foam that persists and fades from frame to frame, the same
//! bits in any run (such a sequence is computed as one run, in frame order).

use std::time::Instant;

use anyhow::Result;

use crate::cli::AnimateArgs;
use crate::export::options::ExportOptions;
use crate::pipeline::sequence::{Sequence, write_sequence};

/// Runs `seasynth animate`.
pub fn run(args: AnimateArgs) -> Result<()> {
    crate::commands::common::set_threads(args.threads)?;
    let params = crate::commands::common::resolve_params(&args.field)?;
    let mut flags = args.exr.flags();
    if let Some(up) = args.up.as_deref() {
        flags.push(("--up", up));
    }
    let s = &params.spectrum;
    let per_frame_pairs = s.nonlinear == crate::config::Nonlinear::SecondOrder
        && s.nonlinear_method.is_pairs()
        && params.motion.loop_period_s.is_none();
    if per_frame_pairs && args.frames > 1 && !args.quiet {
        eprintln!(
            "note: without --loop-period every frame sums the second-order pairs again; with \
             one they are summed once for the whole sequence (docs/methods.md, looping seas)"
        );
    }
    let started = Instant::now();
    let done = write_sequence(&Sequence {
        params: &params,
        frames: args.frames,
        formats: &args.format,
        options: ExportOptions::from_flags(flags)?,
        start_frame: args.start_frame,
        dir: &args.dir,
        jobs: args.jobs,
        resume: args.resume,
        quiet: args.quiet,
        force: args.field.force,
    })?;
    if !args.quiet {
        let secs = started.elapsed().as_secs_f64();
        eprintln!(
            "wrote {} frame(s) of {} to {} in {secs:.2} s ({:.2} frames/s), {} skipped; 16-bit mapping {:.4}..{:.4} m",
            done.written,
            args.frames,
            args.dir.display(),
            done.written as f64 / secs.max(1e-9),
            done.skipped,
            done.mapping.min_m,
            done.mapping.max_m
        );
    }
    Ok(())
}
