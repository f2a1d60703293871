//! The default preview of a synthesized field (`generate -o NAME.preview.png`, `animate
//! --format preview`).

use crate::config::Params;

/// The default preview of a synthesized field (`generate -o NAME.preview.png`, `animate
/// --format preview`): exact spectral slopes when the state has them for the height map
/// itself (an FFT or filtered-noise field that is not resampled by choppiness).
pub fn preview_of(
    params: &Params,
    synthesis: &crate::field::Synthesis,
) -> Result<crate::render::RgbImage, crate::error::Error> {
    let grid = &synthesis.grid;
    let periodic = crate::field::method_for(params).is_periodic();
    let opts = crate::render::RenderOptions::preview(
        grid,
        params.wind.direction_deg.to_radians(),
        periodic,
    );
    let slopes = synthesis
        .surface
        .slopes
        .as_ref()
        .filter(|_| exact_slopes_apply(params))
        .map(|[x, y]| (&x[..], &y[..]));
    crate::render::render(grid, slopes, periodic, &opts)
}

/// True when spectral slopes are the slopes of the height map: one spectrum, not resampled
/// (`field::HeightMethod::exact_slopes`).
pub fn exact_slopes_apply(params: &Params) -> bool {
    crate::field::method_for(params).exact_slopes()
}
