//! One field computed to values rather than files: the synthesis with the maps asked
//! for, as the map files hold them, and the sidecar that describes it (the Python
//! package's `generate` and `animate`).

use anyhow::Result;
use rayon::prelude::*;

use crate::config::Params;
use crate::export::maps::{self, FoamRule, MapKind};
use crate::export::sidecar::Sidecar;
use crate::field::dynamics::Extras;
use crate::field::{Synthesis, Synthesizer};

/// Synthesizes `params` at its time with the derived fields `extras`, refusing first a
/// field whose estimated peak memory exceeds the available memory, and a field that is
/// not finite.
pub fn synthesize_checked(params: &Params, extras: Extras) -> Result<Synthesis> {
    Prepared::new(params, extras, false)?.frame(params.time_s)
}

/// One sea prepared for frames at any time (the Python package's `Sea`): its draws and,
/// for a looping second-order sea, its binned pairs made once. A frame at t is
/// [`synthesize_checked`] of the same parameters at t, bit for bit.
pub struct Prepared {
    synth: Synthesizer,
}

impl Prepared {
    /// `params` with the derived fields `extras`, after the memory check; `keep_draws`:
    /// keep the random draws between frames.
    pub fn new(params: &Params, extras: Extras, keep_draws: bool) -> Result<Self> {
        let [nx, ny] = params.grid.size.0;
        crate::limits::check_memory(
            crate::pipeline::memory::Footprint::of_field(params, extras)
                .bytes(params.grid_spec().len() as u64, 1),
            &format!("a {nx}x{ny} {} field", params.method.name()),
            false,
        )?;
        Ok(Self {
            synth: Synthesizer::new(params, extras, keep_draws)?,
        })
    }

    /// The field at `time_s`, refused when not finite.
    pub fn frame(&self, time_s: f64) -> Result<Synthesis> {
        let s = self.synth.frame(time_s);
        crate::limits::check_finite(&s.grid.stats(), "the synthesized field")?;
        Ok(s)
    }
}

/// The maps of one synthesis, each a row-major float array of the grid: the values of
/// the float map files (`NAME.KIND.exr`) of the same field.
#[derive(Debug, Default)]
pub struct Maps {
    /// (λDx, λDy, h before the choppy resampling), interleaved: a displacement EXR's
    /// (R, G, B) with `--up z`.
    pub displacement: Option<Vec<f32>>,
    /// Unit normals (x, y, z), interleaved.
    pub normal: Option<Vec<f32>>,
    pub jacobian: Option<Vec<f32>>,
    /// Foam coverage 0..1.
    pub foam: Option<Vec<f32>>,
}

impl Maps {
    /// The maps `kinds` of `synthesis` (synthesized with [`maps::extras_for`] them).
    /// `foam`: the coverage resolved already (an animation's, with the sequence's
    /// threshold), else this field's own at `motion.foam_threshold`.
    pub fn of(
        params: &Params,
        synthesis: &Synthesis,
        kinds: &[MapKind],
        foam: Option<Vec<f32>>,
    ) -> Self {
        let n = synthesis.grid.spec.len();
        let surf = &synthesis.surface;
        let mut out = Maps::default();
        let jacobian = || surf.jacobian.as_ref().map(|j| j.values(n).into_owned());
        for kind in kinds {
            match kind {
                MapKind::Displacement => {
                    let h = surf
                        .undisplaced_height
                        .as_deref()
                        .unwrap_or(&synthesis.grid.data);
                    let mut d = vec![0.0f32; 3 * n];
                    let disp = surf.displacement.as_ref();
                    d.par_chunks_mut(3).enumerate().for_each(|(i, v)| {
                        if let Some([dx, dy]) = disp {
                            v[0] = dx[i];
                            v[1] = dy[i];
                        }
                        v[2] = h[i];
                    });
                    out.displacement = Some(d);
                }
                MapKind::Normal => {
                    out.normal = surf.normals().map(|n| n.into_flattened());
                }
                MapKind::Jacobian => out.jacobian = Some(jacobian().unwrap_or(vec![1.0; n])),
                MapKind::Foam => {}
            }
        }
        if kinds.contains(&MapKind::Foam) {
            out.foam = Some(foam.unwrap_or_else(|| {
                let j = jacobian().unwrap_or(vec![1.0; n]);
                let t = FoamRule::of(params).resolve(&j).threshold;
                maps::foam_coverage_at(synthesis, t)
            }));
        }
        out
    }
}

/// The sidecar of a field of `params` synthesized as `synthesis`, as JSON: what
/// `seasynth generate` writes beside its files, without their list.
pub fn sidecar_json(params: &Params, synthesis: &Synthesis) -> Result<String> {
    let stats = synthesis.grid.stats();
    let mut doc = Sidecar::new(params, &synthesis.info, stats);
    doc.foam = synthesis
        .surface
        .jacobian
        .as_ref()
        .filter(|_| params.motion.choppiness != 0.0)
        .map(|j| FoamRule::of(params).resolve(&j.values(synthesis.grid.spec.len())));
    Ok(serde_json::to_string(&doc)?)
}
