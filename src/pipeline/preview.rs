//! The default preview of a synthesized field (`generate -o NAME.preview.png`, `animate
//! --format preview`), and what any preview of a synthesized field is shaded with: its
//! material and its foam coverage.

use crate::config::{Method, Params, SpectrumModel};
use crate::field::{Synthesis, dynamics};
use crate::render::{Maps, Material};

/// The default preview of a synthesized field (`generate -o NAME.preview.png`, `animate
/// --format preview`): exact spectral slopes when the state has them for the height map
/// itself (an FFT or filtered-noise field that is not resampled by choppiness), foam as
/// whitecaps when the state has its Jacobian, terrain shading for terrains.
pub fn preview_of(
    params: &Params,
    synthesis: &Synthesis,
) -> Result<crate::render::RgbImage, crate::error::Error> {
    let grid = &synthesis.grid;
    let periodic = crate::field::method_for(params).is_periodic();
    let mut opts = crate::render::RenderOptions::preview(
        grid,
        params.wind.direction_deg.to_radians(),
        periodic,
    );
    opts.material = material_of(params);
    let slopes = synthesis
        .surface
        .slopes
        .as_ref()
        .filter(|_| exact_slopes_apply(params))
        .map(|[x, y]| (&x[..], &y[..]));
    let foam = foam_coverage(synthesis, params);
    let maps = Maps {
        slopes,
        foam: foam.as_deref(),
    };
    crate::render::render_maps(grid, &maps, periodic, &opts, &|_| {})
}

/// True when spectral slopes are the slopes of the height map: one spectrum, not resampled
/// (`field::HeightMethod::exact_slopes`).
pub fn exact_slopes_apply(params: &Params) -> bool {
    crate::field::method_for(params).exact_slopes()
}

/// Terrain for a field of the `fractal` spectrum (every method but `perlin`, which has no
/// spectrum), water otherwise.
pub fn material_of(params: &Params) -> Material {
    if params.spectrum.model == SpectrumModel::Fractal && params.method != Method::Perlin {
        Material::Terrain
    } else {
        Material::Water
    }
}

/// Whether a preview of `params` draws whitecaps: a choppy field (λ ≠ 0), whose
/// synthesis then needs its Jacobian and displacement ([`preview_extras`]).
pub fn draws_foam(params: &Params) -> bool {
    params.motion.choppiness != 0.0 && material_of(params) == Material::Water
}

/// The derived fields a preview of `params` needs for its foam: the Jacobian and the
/// displacement of a choppy field (none otherwise).
pub fn preview_extras(params: &Params) -> dynamics::Extras {
    let foam = draws_foam(params);
    dynamics::Extras {
        slopes: false,
        displacement: foam,
        jacobian: foam,
        maps_only: false,
    }
}

/// The foam coverage clamp((T − J)/T, 0, 1) of a synthesis on its height grid (J moved
/// with the choppy resampling, like the heights), T resolved as the maps resolve it
/// ([`crate::export::maps::foam_coverage_of`]); `None` when the state has no Jacobian or
/// no foam anywhere.
pub fn foam_coverage(synthesis: &Synthesis, params: &Params) -> Option<Vec<f32>> {
    if !draws_foam(params) {
        return None;
    }
    let spec = synthesis.grid.spec;
    let (cover, _) = crate::export::maps::foam_coverage_of(params, synthesis)?;
    if !cover.iter().any(|&c| c > 0.0) {
        return None;
    }
    Some(match synthesis.surface.displacement.as_ref() {
        Some(d) => dynamics::resample_choppy(&cover, d, &spec),
        None => cover,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{Extent2, Size2};
    use crate::render::{Lighting, RenderOptions, render_maps, shade};

    /// An 8-bit value every channel of a near-white pixel reaches.
    const NEAR_WHITE: u8 = 200;

    /// `params` at 256² on its extent, its foam coverage, and the near-white sea pixels of
    /// its preview at 160×90 with a dark sun color (no white glitter), no spray and a
    /// grey-blue sky (its reflection and the haze stay below white): only foam can be
    /// near-white.
    fn preview_and_foam(mut params: Params) -> (usize, Option<Vec<f32>>) {
        params.grid.size = Size2([256, 256]);
        let s = crate::field::Synthesizer::new(&params, preview_extras(&params), false)
            .unwrap()
            .frame(0.0);
        let foam = foam_coverage(&s, &params);
        let periodic = crate::field::method_for(&params).is_periodic();
        let mut opts =
            RenderOptions::preview(&s.grid, params.wind.direction_deg.to_radians(), periodic);
        opts.width = 160;
        opts.height = 90;
        let l = Lighting::default();
        opts.lighting = Lighting {
            sun_color: shade::srgb([0.3, 0.3, 0.3]),
            spray_color: l.crest_color,
            sky_horizon: shade::srgb([0.5, 0.6, 0.7]),
            sky_zenith: shade::srgb([0.3, 0.45, 0.7]),
            ..opts.lighting
        };
        let maps = Maps {
            slopes: None,
            foam: foam.as_deref(),
        };
        let img = render_maps(&s.grid, &maps, periodic, &opts, &|_| {}).unwrap();
        // Sea pixels only (the sky near the horizon is near-white too).
        let white = img
            .rgb
            .chunks(3)
            .zip(&img.distance_m)
            .filter(|(p, d)| d.is_finite() && p.iter().all(|&c| c >= NEAR_WHITE))
            .count();
        (white, foam)
    }

    #[test]
    fn a_choppy_storm_shows_whitecaps_and_a_calm_sea_none() {
        let mut storm = Params::preset("storm").unwrap();
        storm.grid.extent_m = Extent2([1024.0, 1024.0]);
        storm.motion.choppiness = 1.0;
        storm.motion.foam_threshold = crate::config::FoamThreshold::Jacobian(0.8);
        let (storm_white, foam) = preview_and_foam(storm.clone());
        let foam = foam.expect("the choppy storm has foam");
        let max = foam.iter().fold(0.0f32, |m, &c| m.max(c));
        eprintln!("storm foam: max coverage {max}");
        // The coverage is clamp((T − J)/T, 0, 1) of the Jacobian, moved like the heights.
        assert!(foam.iter().all(|c| (0.0..=1.0).contains(c)));
        let (calm_white, calm_foam) = preview_and_foam(Params::preset("calm").unwrap());
        assert!(
            calm_foam.is_none(),
            "a calm sea that is not choppy has no foam"
        );
        // The same storm with a threshold under every J: no foam, no near-white pixel.
        storm.motion.foam_threshold = crate::config::FoamThreshold::Jacobian(0.05);
        let (bare_white, bare_foam) = preview_and_foam(storm);
        assert!(bare_foam.is_none());
        eprintln!(
            "near-white pixels: storm {storm_white}, calm {calm_white}, bare storm {bare_white}"
        );
        assert_eq!(bare_white, 0, "without foam nothing is near-white");
        assert_eq!(calm_white, 0);
        assert!(
            storm_white > 20,
            "whitecaps: {storm_white} near-white pixels"
        );
    }

    #[test]
    fn fractal_fields_are_terrain_and_perlin_is_water() {
        let mut p = Params::preset("fractal-terrain").unwrap();
        assert_eq!(material_of(&p), Material::Terrain);
        p.method = Method::Perlin;
        assert_eq!(material_of(&p), Material::Water);
        assert_eq!(
            material_of(&Params::preset("storm").unwrap()),
            Material::Water
        );
    }
}
