//! What the commands that compute many fields share (`animate`'s frames, `batch`'s
//! jobs): the per-field file kinds of `--format`, how many fields are computed at once
//! under the available memory, a worker pool that runs them, one 16-bit mapping over all
//! of them, and the progress display.

use std::io::IsTerminal;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use crate::config::Params;
use crate::error::ParamError;
use crate::export::maps::{MapEncoding, MapKind};
use crate::export::{Format, HeightMapping, OutputKind};

/// One file kind of a frame or job, as `--format` names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// 16-bit height PNG.
    Png,
    /// Float height TIFF.
    Tif,
    /// Float height EXR.
    Exr,
    /// A map of the wave state (normal, foam, Jacobian, displacement), as its usual image
    /// or as EXR.
    Map(MapKind, MapEncoding),
    /// A rendered perspective view (`seasynth render`'s default camera).
    Preview,
}

/// The names `FileKind::parse` accepts, for error messages.
pub const FILE_KINDS: &str = "png, tif, exr, normal, foam, jacobian, disp, preview, or a map as \
                              EXR: disp.exr, normal.exr, foam.exr, jacobian.exr";

impl FileKind {
    pub fn parse(s: &str) -> Result<Self, ParamError> {
        let s = s.trim().to_ascii_lowercase();
        let image = |k| FileKind::Map(k, MapEncoding::Image);
        Ok(match s.as_str() {
            "png" => FileKind::Png,
            "tif" | "tiff" => FileKind::Tif,
            "exr" => FileKind::Exr,
            "normal" => image(MapKind::Normal),
            "foam" => image(MapKind::Foam),
            "jacobian" => image(MapKind::Jacobian),
            "disp" => image(MapKind::Displacement),
            "preview" => FileKind::Preview,
            other => match OutputKind::of_path(std::path::Path::new(&format!("x.{other}"))) {
                Ok(OutputKind::Map(kind, enc)) => FileKind::Map(kind, enc),
                _ => {
                    let names = FILE_KINDS.split([',', ':', ' ']).filter(|n| {
                        n.contains(['a', 'e', 'i', 'o', 'u'])
                            && !["or", "map", "as", "EXR"].contains(n)
                    });
                    return Err(ParamError {
                        name: "--format".into(),
                        allowed: FILE_KINDS.into(),
                        got: format!("{other}{}", crate::error::did_you_mean(other, names)),
                    });
                }
            },
        })
    }

    /// What follows `NAME.` in the file name (from the table of [`OutputKind`]).
    pub fn suffix(&self) -> String {
        match self {
            FileKind::Png => OutputKind::Height(Format::Png16),
            FileKind::Tif => OutputKind::Height(Format::Tiff32),
            FileKind::Exr => OutputKind::Height(Format::Exr),
            FileKind::Map(kind, enc) => OutputKind::Map(*kind, *enc),
            FileKind::Preview => OutputKind::Preview,
        }
        .suffix()
    }

    /// True for float EXR files.
    pub fn is_exr(&self) -> bool {
        matches!(self, FileKind::Exr | FileKind::Map(_, MapEncoding::Exr))
    }
}

/// A peak-memory estimate of computing and writing one field of `params` with `maps`
/// derived maps, bytes ([`crate::pipeline::memory::Footprint`], with every derived field when there
/// is a map).
pub fn field_bytes(params: &Params, maps: usize) -> u64 {
    let all = crate::field::dynamics::Extras::ALL;
    let extras = if maps > 0 { all } else { Default::default() };
    crate::pipeline::memory::Footprint::of_field(params, extras)
        .with_outputs(maps as u64)
        .bytes(params.grid_spec().len() as u64, 1)
}

/// How many fields to compute at once: `requested` (default: the worker threads), at most
/// as many as fit twice into the available memory by the estimate `per_job_bytes`, and at
/// least one.
pub fn parallel_jobs(requested: Option<usize>, per_job_bytes: u64) -> usize {
    let by_memory = crate::limits::available_memory()
        .ok()
        .flatten()
        .map(|m| (m / 2 / per_job_bytes.max(1)).max(1) as usize)
        .unwrap_or(1);
    requested
        .unwrap_or_else(rayon::current_num_threads)
        .min(by_memory)
        .max(1)
}

/// Runs `f(0) … f(count − 1)` on `workers` threads, each taking the next index when it is
/// free, and returns the results in index order. Each call may itself use the rayon pool.
pub fn run_pool<T: Send>(count: usize, workers: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<T>>> = Mutex::new((0..count).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..workers.clamp(1, count.max(1)) {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= count {
                        break;
                    }
                    let r = f(i);
                    results.lock().expect("no worker panicked holding the lock")[i] = Some(r);
                }
            });
        }
    });
    results
        .into_inner()
        .expect("no worker panicked holding the lock")
        .into_iter()
        .map(|r| r.expect("every index was run"))
        .collect()
}

/// `count` items split into `workers` runs of consecutive items, in order (the first runs
/// one longer when they do not divide evenly), none empty.
pub fn consecutive_runs(count: usize, workers: usize) -> Vec<std::ops::Range<usize>> {
    let runs = workers.clamp(1, count.max(1));
    let (each, longer) = (count / runs, count % runs);
    let mut start = 0;
    (0..runs)
        .map(|r| {
            let len = each + usize::from(r < longer);
            start += len;
            start - len..start
        })
        .filter(|r| !r.is_empty())
        .collect()
}

/// Runs `compute(i)` then `write(i, result)` for every i < `count`, overlapping the two:
/// the items are split into `workers` runs of consecutive items ([`consecutive_runs`]),
/// each run computes its items in order on its own thread and hands each result to a
/// writer thread of its own, so that item i + 1 is computed while item i is written. A
/// run has at most two items alive at once (one written, one computed; the hand-over
/// waits for the writer). Both closures may use the rayon pool. A run stops at its first
/// error; the first error in run order is returned (within a run, a write's error comes
/// before the computation's, which is of a later item).
pub fn run_overlapped<T: Send, E: Send>(
    count: usize,
    workers: usize,
    compute: impl Fn(usize) -> Result<T, E> + Sync,
    write: impl Fn(usize, T) -> Result<(), E> + Sync,
) -> Result<(), E> {
    let runs = consecutive_runs(count, workers);
    let (compute, write) = (&compute, &write);
    let results: Vec<Result<(), E>> = std::thread::scope(|s| {
        let handles: Vec<_> = runs
            .into_iter()
            .map(|run| s.spawn(move || overlapped_run(run, compute, write)))
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .collect()
    });
    results.into_iter().collect()
}

/// One run of [`run_overlapped`].
fn overlapped_run<T: Send, E: Send>(
    run: std::ops::Range<usize>,
    compute: &(impl Fn(usize) -> Result<T, E> + Sync),
    write: &(impl Fn(usize, T) -> Result<(), E> + Sync),
) -> Result<(), E> {
    // A rendezvous channel: the next item is handed over only when the writer takes it.
    let (hand, take) = std::sync::mpsc::sync_channel::<(usize, T)>(0);
    std::thread::scope(|s| {
        let writer = s.spawn(move || {
            for (i, item) in take {
                write(i, item)?;
            }
            Ok(())
        });
        let mut computed = Ok(());
        for i in run {
            match compute(i) {
                // A closed channel: the writer has stopped at an error.
                Ok(item) => {
                    if hand.send((i, item)).is_err() {
                        break;
                    }
                }
                Err(e) => {
                    computed = Err(e);
                    break;
                }
            }
        }
        drop(hand);
        let written = writer
            .join()
            .unwrap_or_else(|p| std::panic::resume_unwind(p));
        written.and(computed)
    })
}

/// One 16-bit mapping over many fields: the smallest min and largest max of `ranges`
/// (`None` when there is none).
pub fn union_range(ranges: impl IntoIterator<Item = (f64, f64)>) -> Option<HeightMapping> {
    let (lo, hi) = ranges
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (a, b)| {
            (lo.min(a), hi.max(b))
        });
    (lo <= hi).then_some(HeightMapping {
        min_m: lo,
        max_m: hi,
    })
}

/// Progress of many fields: an indicatif bar on a terminal, and, when `plain` is asked
/// and stderr is not a terminal, one plain line per finished field with the ETA.
pub struct Progress {
    bar: indicatif::ProgressBar,
    plain: bool,
    total: usize,
    done: AtomicUsize,
    started: Instant,
}

/// A progress bar of `len` steps drawn on stderr with the indicatif `template`, hidden
/// unless `show` and stderr is a terminal.
pub(crate) fn progress_bar(len: u64, template: &str, show: bool) -> indicatif::ProgressBar {
    if !show || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let b = indicatif::ProgressBar::new(len);
    // `{per_sec}` is indicatif's rate with four decimals (`74.8102/s`): three significant
    // digits instead.
    let template = template.replace("{per_sec}", "{rate}");
    b.set_style(
        indicatif::ProgressStyle::with_template(&template)
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
            .with_key(
                "rate",
                |s: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                    let _ = write!(w, "{}", rate_text(s.per_sec()));
                },
            ),
    );
    b
}

/// A rate per second to three significant digits (`74.8/s`, `1234/s`, `0.512/s`).
pub(crate) fn rate_text(per_sec: f64) -> String {
    let r = per_sec.max(0.0);
    match r {
        r if !r.is_finite() => "-/s".to_string(),
        r if r >= 100.0 => format!("{r:.0}/s"),
        r if r >= 10.0 => format!("{r:.1}/s"),
        r if r >= 1.0 => format!("{r:.2}/s"),
        r => format!("{r:.3}/s"),
    }
}

impl Progress {
    /// `unit`: what is counted ("frames", "jobs"). Nothing is shown when `quiet`.
    pub fn new(total: usize, unit: &str, quiet: bool, plain: bool) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let bar = progress_bar(
            total as u64,
            &format!("{{bar:40}} {{pos}}/{{len}} {unit}, {{per_sec}}, ETA {{eta}} {{msg}}"),
            !quiet,
        );
        Self {
            bar,
            plain: plain && !quiet && !terminal,
            total,
            done: AtomicUsize::new(0),
            started: Instant::now(),
        }
    }

    /// One more field finished; `status` describes it (shown beside the bar, or as a line).
    pub fn finished(&self, status: &str) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if self.plain {
            let secs = self.started.elapsed().as_secs_f64();
            let eta = secs / done as f64 * (self.total - done.min(self.total)) as f64;
            eprintln!("[{done}/{}] {status} (ETA {eta:.0} s)", self.total);
        } else {
            self.bar.set_message(status.to_string());
        }
        self.bar.inc(1);
    }

    /// Prints a line above the bar (or as it is, without one), unless quiet.
    pub fn println(&self, line: &str) {
        if self.bar.is_hidden() {
            if self.plain {
                eprintln!("{line}");
            }
        } else {
            self.bar.println(line);
        }
    }

    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pool_runs_every_index_once_and_keeps_their_order() {
        for workers in [1, 3, 8] {
            let calls = AtomicUsize::new(0);
            let out = run_pool(17, workers, |i| {
                calls.fetch_add(1, Ordering::Relaxed);
                i * i
            });
            assert_eq!(calls.load(Ordering::Relaxed), 17, "{workers} workers");
            assert_eq!(out, (0..17).map(|i| i * i).collect::<Vec<_>>());
        }
        assert!(run_pool(0, 2, |i| i).is_empty());
    }

    #[test]
    fn consecutive_runs_cover_every_item_once_in_order() {
        for (count, workers) in [(17, 1), (17, 3), (17, 4), (2, 5), (0, 2), (6, 6)] {
            let runs = consecutive_runs(count, workers);
            let all: Vec<usize> = runs.iter().flat_map(|r| r.clone()).collect();
            assert_eq!(
                all,
                (0..count).collect::<Vec<_>>(),
                "{count} over {workers}"
            );
            assert!(runs.len() <= workers.max(1));
            assert!(runs.iter().all(|r| !r.is_empty()));
            let lens: Vec<usize> = runs.iter().map(|r| r.len()).collect();
            let (lo, hi) = (lens.iter().min(), lens.iter().max());
            assert!(hi.zip(lo).is_none_or(|(h, l)| h - l <= 1), "{lens:?}");
        }
    }

    #[test]
    fn overlapped_runs_write_every_item_in_order_with_two_alive_at_most() {
        for workers in [1, 2, 5] {
            let alive = AtomicUsize::new(0);
            let most = AtomicUsize::new(0);
            let written = Mutex::new(Vec::new());
            let r: Result<(), ()> = run_overlapped(
                23,
                workers,
                |i| {
                    let now = alive.fetch_add(1, Ordering::SeqCst) + 1;
                    most.fetch_max(now, Ordering::SeqCst);
                    Ok(i * 10)
                },
                |i, v| {
                    assert_eq!(v, i * 10);
                    std::thread::sleep(std::time::Duration::from_millis(1));
                    written.lock().unwrap().push(i);
                    alive.fetch_sub(1, Ordering::SeqCst);
                    Ok(())
                },
            );
            assert_eq!(r, Ok(()));
            let mut w = written.into_inner().unwrap();
            // Each run writes its items in order.
            for run in consecutive_runs(23, workers) {
                let of_run: Vec<usize> = w.iter().copied().filter(|i| run.contains(i)).collect();
                assert_eq!(of_run, run.collect::<Vec<_>>());
            }
            w.sort();
            assert_eq!(w, (0..23).collect::<Vec<_>>());
            let bound = 2 * consecutive_runs(23, workers).len();
            assert!(most.load(Ordering::SeqCst) <= bound, "{workers} workers");
        }
    }

    #[test]
    fn overlapped_runs_stop_at_the_first_error_of_either_stage() {
        let written = Mutex::new(Vec::new());
        let r = run_overlapped(
            10,
            1,
            |i| {
                if i == 6 {
                    Err(format!("compute {i}"))
                } else {
                    Ok(i)
                }
            },
            |i, _| {
                written.lock().unwrap().push(i);
                Ok(())
            },
        );
        assert_eq!(r, Err("compute 6".to_string()));
        assert_eq!(*written.lock().unwrap(), (0..6).collect::<Vec<_>>());
        let computed = AtomicUsize::new(0);
        let r = run_overlapped(
            10,
            1,
            |i| {
                computed.fetch_add(1, Ordering::SeqCst);
                Ok(i)
            },
            |i, _| {
                if i == 3 {
                    Err(format!("write {i}"))
                } else {
                    Ok(())
                }
            },
        );
        assert_eq!(r, Err("write 3".to_string()));
        // Item 4 may have been computed before the writer stopped, not more.
        assert!(computed.load(Ordering::SeqCst) <= 5);
    }

    #[test]
    fn parallel_jobs_stay_under_the_available_memory() {
        assert_eq!(parallel_jobs(Some(3), 1), 3, "small jobs: as many as asked");
        assert_eq!(
            parallel_jobs(Some(3), u64::MAX / 4),
            1,
            "huge jobs: one at a time"
        );
        assert_eq!(parallel_jobs(Some(0), 1), 1, "at least one");
        if let Ok(Some(m)) = crate::limits::available_memory() {
            assert_eq!(
                parallel_jobs(Some(8), m / 5),
                2,
                "two fit twice into {m} bytes"
            );
        }
    }

    #[test]
    fn rates_are_shown_to_three_significant_digits() {
        assert_eq!(rate_text(74.8102), "74.8/s");
        assert_eq!(rate_text(1234.56), "1235/s");
        assert_eq!(rate_text(2.5049), "2.50/s");
        assert_eq!(rate_text(0.51234), "0.512/s");
        assert_eq!(rate_text(f64::INFINITY), "-/s");
    }

    #[test]
    fn the_union_range_spans_every_field() {
        let m = union_range([(-1.0, 0.5), (-0.25, 2.0), (0.0, 1.0)]).unwrap();
        assert_eq!((m.min_m, m.max_m), (-1.0, 2.0));
        assert!(union_range(std::iter::empty()).is_none());
    }

    #[test]
    fn file_kinds_round_trip_through_their_names() {
        for name in [
            "png", "tif", "normal", "foam", "jacobian", "disp", "preview",
        ] {
            let k = FileKind::parse(name).unwrap();
            assert!(k.suffix().starts_with(name), "{name} → {}", k.suffix());
        }
        assert!(FileKind::parse("gif").is_err());
    }
}
