//! Foam that persists and fades over the frames of an animation (`motion.foam_fade_s`),
//! as a host's ocean "foam fade" does, with frames that stay independent.
//!
//! The state is the 16-bit foam coverage. Each frame it loses a fixed `step` and takes
//! the frame's own (fresh) foam where that is more: s_k = max(fresh_k, s_{k−1} ⊖ step),
//! ⊖ saturating at 0. Unrolled, s_k = max over j ≤ k of (fresh_j ⊖ (k − j)·step), and a
//! frame m = ⌈65535/step⌉ back or more adds nothing, so s_k depends only on frames
//! k − m + 1 … k. A frame whose predecessor is not computed in the same run (the first
//! frame, a frame after a gap left by `--resume`) starts from the frames before it
//! (times before the sequence's are fine: the sea is defined at any time, and a looping
//! sea wraps), and is bit for bit the frame of one continuous run, whatever the order,
//! the number of jobs or the frames already written.

use std::collections::{HashMap, HashSet};
use std::sync::{Condvar, Mutex};

use serde::Serialize;

use crate::config::Params;
use crate::export::maps::{FoamRule, MapEncoding, MapKind, ResolvedFoam, foam_value};
use crate::field::{Synthesis, Synthesizer};

/// The largest foam coverage.
const FULL: u32 = 65535;

/// The fade per frame of a fade over `fade_s` seconds at `fps` frames per second:
/// ⌈65535/(fade_s·fps)⌉, so full foam is gone within fade_s; `None` when foam does not
/// outlive its frame (fade_s·fps ≤ 1, or 0: off).
pub fn step_per_frame(fade_s: f64, fps: f64) -> Option<u16> {
    let frames = fade_s * fps;
    if frames.is_nan() || frames <= 1.0 {
        return None;
    }
    let step = (FULL as f64 / frames).ceil().clamp(1.0, FULL as f64) as u16;
    (memory_frames(step) > 1).then_some(step)
}

/// The frames a state remembers at `step` per frame: m = ⌈65535/step⌉ (the frame itself
/// and the m − 1 before it).
pub fn memory_frames(step: u16) -> usize {
    FULL.div_ceil(step.max(1) as u32) as usize
}

/// One frame: `state` ← max(`fresh`, `state` ⊖ `step`).
pub fn advance(state: &mut [u16], fresh: &[u16], step: u16) {
    for (s, &f) in state.iter_mut().zip(fresh) {
        *s = f.max(s.saturating_sub(step));
    }
}

/// The persistent foam of the frames of one run, handed from each frame to the next.
pub struct FoamFade<'a> {
    step: u16,
    /// The frames of this run.
    todo: HashSet<usize>,
    /// The fresh foam of any frame (also before the first), for the warm-up.
    fresh_of: FreshOf<'a>,
    /// The state after frame k, for frame k + 1 (`None`: frame k failed, so k + 1 warms up).
    after: Mutex<Handover>,
    ready: Condvar,
}

impl<'a> FoamFade<'a> {
    /// The fade of `step` per frame over the frames `todo` of a run; `fresh_of(k)` is the
    /// fresh foam of frame k (k < 0 before the sequence).
    pub fn new(step: u16, todo: &[usize], fresh_of: impl Fn(i64) -> Vec<u16> + Sync + 'a) -> Self {
        Self {
            step,
            todo: todo.iter().copied().collect(),
            fresh_of: Box::new(fresh_of) as FreshOf<'a>,
            after: Mutex::new((HashMap::new(), HashSet::new())),
            ready: Condvar::new(),
        }
    }

    /// The persistent foam of frame k whose fresh foam is `fresh`. Frames of the run must
    /// be started in increasing order (as `jobs::run_pool` does): frame k waits for
    /// frame k − 1 when that is in the run. Pair each frame with [`FoamFade::guard`].
    pub fn persistent(&self, k: usize, fresh: &[u16]) -> Vec<u16> {
        let before = match k.checked_sub(1).filter(|p| self.todo.contains(p)) {
            Some(p) => {
                let mut g = self
                    .after
                    .lock()
                    .expect("no frame panicked holding the lock");
                loop {
                    if let Some(s) = g.0.remove(&p) {
                        break s;
                    }
                    g = self
                        .ready
                        .wait(g)
                        .expect("no frame panicked holding the lock");
                }
            }
            None => None,
        };
        let mut state = before.unwrap_or_else(|| self.warm_up(k, fresh.len()));
        advance(&mut state, fresh, self.step);
        self.publish(k, Some(state.clone()));
        state
    }

    /// A guard that tells the next frame, when frame k ends without its foam (an error),
    /// to start from the frames before it instead of waiting.
    pub fn guard(&self, k: usize) -> FrameGuard<'_, 'a> {
        FrameGuard { fade: self, k }
    }

    /// The state after frame k − 1 from the frames k − m + 1 … k − 1 alone.
    fn warm_up(&self, k: usize, len: usize) -> Vec<u16> {
        let m = memory_frames(self.step) as i64;
        let mut state = vec![0u16; len];
        for j in (k as i64 - m + 1)..k as i64 {
            advance(&mut state, &(self.fresh_of)(j), self.step);
        }
        state
    }

    /// Hands the state after frame k to frame k + 1 (once: the first word counts).
    fn publish(&self, k: usize, state: Option<Vec<u16>>) {
        let mut g = self
            .after
            .lock()
            .expect("no frame panicked holding the lock");
        if !g.1.insert(k) {
            return;
        }
        if self.todo.contains(&(k + 1)) {
            g.0.insert(k, state);
        }
        drop(g);
        self.ready.notify_all();
    }
}

/// See [`FoamFade::guard`].
pub struct FrameGuard<'f, 'a> {
    fade: &'f FoamFade<'a>,
    k: usize,
}

impl Drop for FrameGuard<'_, '_> {
    fn drop(&mut self) {
        self.fade.publish(self.k, None);
    }
}

/// The foam of an animation: one threshold for the whole sequence, resolved over the
/// frame at the sequence's time origin (frame 0), so frames stay independent of each
/// other and of the run, the covered fraction fluctuates from frame to frame as the sea
/// does around W, and foam does not flicker with a threshold that moves; and the fade.
pub struct SequenceFoam<'a> {
    pub record: FoamRecord,
    fresh_of: Option<FreshOf<'a>>,
    fade: Option<FoamFade<'a>>,
}

/// The states waiting for their next frame (`None`: that frame warms up), and the frames
/// that have handed theirs over.
type Handover = (HashMap<usize, Option<Vec<u16>>>, HashSet<usize>);

/// The fresh foam of frame k.
type FreshOf<'a> = Box<dyn Fn(i64) -> Vec<u16> + Sync + 'a>;

/// What the sequence's sidecar says of its foam.
#[derive(Debug, Clone, Serialize)]
pub struct FoamRecord {
    #[serde(flatten)]
    pub resolved: ResolvedFoam,
    /// The frame whose J the threshold was resolved over.
    pub resolved_at_frame: usize,
    /// Coverage lost per frame by persistent foam (of 65535), when it fades.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fade_step: Option<u16>,
    /// Frames a sample of full foam persists, when it fades.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fade_frames: Option<usize>,
}

/// Whether an animation of `params` writing the maps `kinds` has foam: a choppy sea with
/// a foam map or a displacement EXR (whose A channel is foam).
pub fn applies(params: &Params, kinds: &[(MapKind, MapEncoding)]) -> bool {
    params.motion.choppiness != 0.0
        && kinds.iter().any(|k| {
            matches!(
                k,
                (MapKind::Foam, _) | (MapKind::Displacement, MapEncoding::Exr)
            )
        })
}

impl<'a> SequenceFoam<'a> {
    /// The foam of the sequence of `params` (frame k at `time_of(k)`, k < 0 before it),
    /// computed by `synth` (which computes the Jacobian); [`SequenceFoam::start`] it.
    pub fn new(
        params: &Params,
        synth: &'a Synthesizer,
        time_of: impl Fn(i64) -> f64 + Sync + 'a,
    ) -> Self {
        let jacobian = |syn: &Synthesis| {
            syn.surface
                .jacobian
                .as_ref()
                .expect("the synthesizer computes the Jacobian")
                .values(syn.grid.spec.len())
                .into_owned()
        };
        let rule = FoamRule::of(params);
        let resolved = match rule {
            FoamRule::Threshold(_) => rule.resolve(&[]),
            FoamRule::Coverage(_) => rule.resolve(&jacobian(&synth.frame(time_of(0)))),
        };
        let step = step_per_frame(params.motion.foam_fade_s, params.motion.fps);
        let t = resolved.threshold;
        Self {
            record: FoamRecord {
                resolved,
                resolved_at_frame: 0,
                fade_step: step,
                fade_frames: step.map(memory_frames),
            },
            fresh_of: Some(Box::new(move |k| {
                let j = jacobian(&synth.frame(time_of(k)));
                j.iter().map(|&j| foam_value(j, t)).collect()
            })),
            fade: None,
        }
    }

    /// Starts the fade (when foam fades) over the frames `todo` of this run.
    pub fn start(&mut self, todo: &[usize]) {
        if let (Some(step), Some(fresh_of)) = (self.record.fade_step, self.fresh_of.take()) {
            self.fade = Some(FoamFade::new(step, todo, fresh_of));
        }
    }

    /// Whether foam persists from frame to frame (each frame then needs the one before).
    pub fn fades(&self) -> bool {
        self.fade.is_some()
    }

    /// The threshold of every frame.
    pub fn threshold(&self) -> f64 {
        self.record.resolved.threshold
    }

    /// A guard to hold while frame k is made (see [`FoamFade::guard`]).
    pub fn guard(&self, k: usize) -> Option<FrameGuard<'_, 'a>> {
        self.fade.as_ref().map(|f| f.guard(k))
    }

    /// The persistent foam of frame k, computed as `syn`, when foam fades.
    pub fn persistent(&self, k: usize, syn: &Synthesis) -> Option<Vec<u16>> {
        let fade = self.fade.as_ref()?;
        let j = syn.surface.jacobian.as_ref()?.values(syn.grid.spec.len());
        let t = self.threshold();
        let fresh: Vec<u16> = j.iter().map(|&j| foam_value(j, t)).collect();
        Some(fade.persistent(k, &fresh))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::jobs::run_pool;

    /// Fresh foam of frame k: a few pseudo-random samples with foam, some full.
    fn fresh(k: i64) -> Vec<u16> {
        (0..64u64)
            .map(|i| {
                let h = (i ^ (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15))
                    .wrapping_mul(0xBF58_476D_1CE4_E5B9);
                match h >> 61 {
                    0 => 65535,
                    1 => (h >> 20) as u16,
                    _ => 0,
                }
            })
            .collect()
    }

    /// The persistent foam of frames `todo` with `workers`, each frame's result.
    fn run(step: u16, todo: &[usize], workers: usize) -> Vec<Vec<u16>> {
        let fade = FoamFade::new(step, todo, fresh);
        run_pool(todo.len(), workers, |i| {
            let _g = fade.guard(todo[i]);
            fade.persistent(todo[i], &fresh(todo[i] as i64))
        })
    }

    #[test]
    fn the_step_fades_full_foam_within_the_fade_time() {
        let step = step_per_frame(2.0, 30.0).unwrap();
        assert_eq!(step, 1093);
        assert_eq!(memory_frames(step), 60);
        assert_eq!(step_per_frame(0.0, 30.0), None);
        assert_eq!(step_per_frame(0.02, 30.0), None);
        // Full foam once, then nothing: zero exactly after m frames, not before.
        let mut s = vec![65535u16];
        for k in 1..=memory_frames(step) {
            advance(&mut s, &[0], step);
            assert_eq!(s[0] == 0, k == memory_frames(step), "frame {k}: {}", s[0]);
        }
    }

    #[test]
    fn persistent_foam_covers_the_fresh_and_equals_the_unrolled_maximum() {
        let step = 5000;
        let m = memory_frames(step) as i64;
        let got = run(step, &(0..30).collect::<Vec<_>>(), 3);
        for (k, s) in got.iter().enumerate() {
            let k = k as i64;
            let f = fresh(k);
            for (i, &v) in s.iter().enumerate() {
                assert!(v >= f[i]);
                let want = (k - m + 1..=k)
                    .map(|j| {
                        fresh(j)[i].saturating_sub(((k - j) as u32 * step as u32).min(65535) as u16)
                    })
                    .max()
                    .unwrap();
                assert_eq!(v, want, "frame {k} sample {i}");
            }
        }
    }

    #[test]
    fn a_resumed_run_or_other_jobs_give_the_same_frames() {
        let step = 3000;
        let all: Vec<usize> = (0..40).collect();
        let one = run(step, &all, 1);
        assert_eq!(run(step, &all, 4), one);
        // Resumed: only some frames, with gaps; each equals the continuous run's.
        let some = [3usize, 4, 5, 17, 30, 31, 39];
        for (got, &k) in run(step, &some, 2).iter().zip(&some) {
            assert_eq!(got, &one[k], "frame {k}");
        }
    }

    #[test]
    fn a_failed_frame_does_not_hold_up_the_next() {
        let step = 3000;
        let todo: Vec<usize> = (0..6).collect();
        let fade = FoamFade::new(step, &todo, fresh);
        let got = run_pool(todo.len(), 2, |k| {
            let _g = fade.guard(k);
            (k != 2).then(|| fade.persistent(k, &fresh(k as i64)))
        });
        assert_eq!(got[3].as_ref(), run(step, &[3], 1).first());
    }
}
