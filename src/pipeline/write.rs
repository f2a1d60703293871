//! Writing one field: synthesized once, written to every output path with its sidecars,
//! every file staged before the work.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use crate::config::Params;
use crate::error::Error;
use crate::export::maps::{self, MapContext, MapEncoding, MapKind};
use crate::export::mesh;
use crate::export::options::ExportOptions;
use crate::export::sidecar::{self, FileEntry, MappingInfo, Sidecar};
use crate::export::tiles::{self, TileIndex, TileSet};
use crate::export::{
    self, Describe, ExportManager, FieldOut, Format, HeightMapping, Output, OutputKind, Staged,
};
use crate::field;

/// What a caller adds to the sidecars of [`write_field`].
#[derive(Default)]
pub struct SidecarExtras<'a> {
    /// Where the 16-bit mapping came from when the caller set `output.height_range`
    /// (default: `--height-range`).
    pub mapping_source: Option<&'static str>,
    /// The batch job this field is.
    pub batch: Option<&'a crate::export::sidecar::JobRecord>,
}

/// What [`write_field`] wrote.
pub struct Written {
    pub stats: crate::grid::Stats,
    pub mapping: HeightMapping,
    /// A 16-bit PNG is among the outputs.
    pub has_png: bool,
    /// The outputs, as given (maps and previews last).
    pub files: Vec<PathBuf>,
    /// What to type into an engine's import dialog, one line per engine output (also in
    /// the sidecar's `raw` section).
    pub import_notes: Vec<String>,
}

/// The import settings of a sidecar's engine outputs, one line each.
fn import_notes(doc: &Sidecar) -> Vec<String> {
    let mut notes = Vec::new();
    let Some(raw) = &doc.raw else {
        return notes;
    };
    if let Some(u) = &raw.unity {
        notes.push(format!(
            "Unity: Import Raw, Depth 16 bit, Resolution {}, Byte Order {}, Terrain Size {:?} m (X, height, Z), position y = {} m",
            u.resolution, u.byte_order, u.terrain_size_m, u.terrain_position_m[1]
        ));
    }
    if let Some(u) = &raw.unreal {
        notes.push(format!(
            "Unreal: Landscape import, resolution {}x{}, Scale X {} Y {} Z {}, actor at Z = 0",
            u.resolution[0], u.resolution[1], u.scale[0], u.scale[1], u.scale[2]
        ));
    }
    if let Some(g) = &raw.godot {
        notes.push(format!("Godot HTerrain: {}", g.hterrain));
        notes.push(format!("Godot Terrain3D: {}", g.terrain3d));
    }
    notes
}

/// The derived fields a synthesis of `params` needs for outputs of these kinds: `maps`
/// (`None`: a preview, which shades with the slopes) and the `formats` of the height
/// outputs (meshes take exact spectral slopes where the field is one spectrum and not
/// resampled).
fn needed_extras(
    params: &Params,
    maps: impl IntoIterator<Item = Option<(MapKind, MapEncoding)>>,
    formats: &[Format],
) -> crate::field::dynamics::Extras {
    let (mut kinds, mut previews) = (Vec::new(), false);
    for m in maps {
        match m {
            Some(kind) => kinds.push(kind),
            None => previews = true,
        }
    }
    let mut extras = maps::extras_for(&kinds);
    let meshes = formats.iter().any(|f| f.is_mesh());
    extras.slopes |= (meshes && crate::pipeline::preview::exact_slopes_apply(params)) || previews;
    if previews {
        let p = crate::pipeline::preview::preview_extras(params);
        extras.jacobian |= p.jacobian;
        extras.displacement |= p.displacement;
    }
    extras
}

/// Whether writing `paths` (as `write_field` takes them) needs derived fields from the
/// synthesis of `params`, so that a field synthesized without them cannot serve; names
/// that are not outputs count as not needing any (`write_field` refuses them).
pub(crate) fn needs_extras(params: &Params, paths: &[PathBuf]) -> bool {
    let mut maps = Vec::new();
    let mut formats = Vec::new();
    for p in paths {
        match OutputKind::of_path(p) {
            Ok(OutputKind::Preview) => maps.push(None),
            Ok(OutputKind::Map(kind, enc)) => maps.push(Some((kind, enc))),
            Ok(OutputKind::Height(f)) => formats.push(f),
            Err(_) => {}
        }
    }
    needed_extras(params, maps, &formats).any()
}

/// Synthesizes the field of `params` once and writes it to every path (format by
/// extension; maps and previews by their `NAME.KIND.ext` names), with the sidecars. Every
/// file is staged before the work, so a bad path fails first and nothing partial is left.
/// `computed`: the field of `params` already synthesized without derived fields
/// (`Synthesizer::frame` with no extras), used when the outputs need none. `force`: run
/// even when the memory estimate exceeds the available memory.
pub fn write_field(
    params: &Params,
    paths: &[PathBuf],
    options: &ExportOptions,
    notes: &SidecarExtras,
    computed: Option<field::Synthesis>,
    force: bool,
) -> Result<Written> {
    let spec = params.grid_spec();
    let periodic = field::method_for(params).is_periodic();
    refuse_repeated(paths)?;
    // Maps of the wave state (NAME.normal.png, …) and previews (NAME.preview.png) come
    // from the same computed state as the height outputs; they are staged now too.
    let mut staged_maps: Vec<(Staged, Option<(MapKind, MapEncoding)>)> = Vec::new();
    let mut height_paths = Vec::new();
    let mut formats = Vec::new();
    for p in paths {
        match OutputKind::of_path(p)? {
            OutputKind::Preview => staged_maps.push((Staged::create(p)?, None)),
            OutputKind::Map(kind, enc) => staged_maps.push((Staged::create(p)?, Some((kind, enc)))),
            OutputKind::Height(format) => {
                height_paths.push(p.clone());
                formats.push(format);
            }
        }
    }
    let paths = height_paths;
    let map_kinds: Vec<(MapKind, MapEncoding)> =
        staged_maps.iter().filter_map(|(_, k)| *k).collect();
    options.check_outputs(&formats, &map_kinds, periodic)?;
    // Stage every file before computing: a bad path fails now, not after the work.
    // (No path is given twice: checked above, before the maps were staged.)
    let mut options = options.clone();
    options.sample_at = params.grid.sample_at;
    let options = &options;
    let manager = ExportManager::plan(&paths, options, &spec, periodic)?;
    let outputs = &manager.outputs;
    let mut stems: BTreeMap<PathBuf, Vec<&Output>> = BTreeMap::new();
    for o in outputs {
        stems.entry(sidecar::path_for(&o.path)).or_default().push(o);
    }
    // Every file that will be written, to refuse one written twice (an output named like
    // the sidecar or the tile index of another).
    let mut written: Vec<(PathBuf, String)> = Vec::new();
    for o in outputs {
        for f in &o.files {
            written.push((
                f.path.clone(),
                format!("an output of -o {}", o.path.display()),
            ));
        }
    }
    for (side, outs) in &stems {
        let of = outs[0].path.display();
        written.push((side.clone(), format!("the sidecar of {of}")));
        if outs.iter().any(|o| o.is_tiled()) {
            written.push((tiles::index_path(side), format!("the tile index of {of}")));
        }
    }
    for (i, (p, what)) in written.iter().enumerate() {
        if let Some((_, first)) = written[..i].iter().find(|(q, _)| q == p) {
            return Err(Error::Output {
                path: p.clone(),
                message: format!("would be written twice, as {first} and as {what}"),
            }
            .into());
        }
    }
    let mut staged_stems = Vec::new();
    for (side, outs) in &stems {
        let index = match outs.iter().any(|o| o.is_tiled()) {
            true => Some(Staged::create(&tiles::index_path(side))?),
            false => None,
        };
        staged_stems.push((Staged::create(side)?, index, outs));
    }

    let extras = needed_extras(params, staged_maps.iter().map(|(_, k)| *k), &formats);
    let exact_slopes = crate::pipeline::preview::exact_slopes_apply(params);
    let meshes = formats.iter().any(|f| f.is_mesh());
    let [nx, ny] = params.grid.size.0;
    crate::limits::check_memory(
        crate::pipeline::memory::Footprint::of_field(params, extras)
            .with_outputs(staged_maps.len() as u64 + meshes as u64)
            .bytes(spec.len() as u64, 1),
        &format!("a {nx}x{ny} {} field", params.method.name()),
        force,
    )?;
    let synthesis = match computed.filter(|_| !extras.any()) {
        Some(s) => s,
        None => field::Synthesizer::new(params, extras, false)?.frame(params.time_s),
    };
    let mesh_slopes = synthesis
        .surface
        .slopes
        .as_ref()
        .filter(|_| meshes && exact_slopes)
        .map(|[x, y]| mesh::Slopes {
            dhdx: x.clone(),
            dhdy: y.clone(),
        });
    let stats = synthesis.grid.stats();
    crate::limits::check_finite(&stats, "the synthesized field")?;
    let (mapping, source) = HeightMapping::choose(
        params.output.height_range,
        notes.mapping_source.unwrap_or("--height-range"),
        || stats,
    );
    let grid = &synthesis.grid;
    // The foam threshold of the maps, resolved once over this field's J.
    let foam = synthesis
        .surface
        .jacobian
        .as_ref()
        .filter(|_| params.motion.choppiness != 0.0)
        .map(|j| maps::FoamRule::of(params).resolve(&j.values(spec.len())));

    // The sidecars and tile indexes describe the outputs' layouts: built before the
    // outputs are written (and consumed), saved after them.
    let mut docs = Vec::new();
    let mut notes_out = Vec::new();
    for (staged, index, outs) in staged_stems {
        let mut doc = Sidecar::new(params, &synthesis.info, stats);
        doc.batch = notes.batch;
        doc.foam = foam;
        let mut uses_mapping = false;
        let mut sets = Vec::new();
        let stem_formats: Vec<Format> = outs.iter().map(|o| o.format()).collect();
        let cx = Describe {
            spec: &spec,
            mapping: &mapping,
            formats: &stem_formats,
            exact_slopes: mesh_slopes.is_some(),
        };
        for o in outs.iter() {
            for f in &o.files {
                doc.files.push(FileEntry {
                    file: file_name(&f.path),
                    format: o.format(),
                });
            }
            o.exporter.describe(&mut doc, &cx);
            uses_mapping |= o.exporter.uses_mapping();
            sets.extend(TileSet::of(o, &spec).filter(|_| o.is_tiled()));
        }
        if uses_mapping {
            doc.mapping = Some(MappingInfo::new(mapping, source));
        }
        notes_out.extend(import_notes(&doc));
        let index = index.map(|index_file| {
            doc.tiles_index = Some(file_name(&index_file.path));
            (index_file, TileIndex::new(&staged.path, sets))
        });
        docs.push((staged, doc, index));
    }

    let about = format!(
        "{} field {nx}x{ny} over {} x {} m, wind {} m/s toward {} deg, seed {}, time {} s\n\
         params {}",
        params.method.name(),
        params.grid.extent_m.0[0],
        params.grid.extent_m.0[1],
        params.wind.speed_mps,
        params.wind.direction_deg,
        params.seed,
        params.time_s,
        serde_json::to_string(params).context("cannot describe the parameters")?
    );
    let field_out = FieldOut {
        grid,
        mapping: &mapping,
        slopes: mesh_slopes.as_ref(),
        about: &about,
    };
    // A PNG through the 16-bit mapping (not one in Unreal's encoding).
    let has_png = manager
        .outputs
        .iter()
        .any(|o| o.format() == Format::Png16 && o.exporter.uses_mapping());
    manager.write_all(&field_out)?;
    let map_paths: Vec<PathBuf> = staged_maps.iter().map(|(s, _)| s.path.clone()).collect();
    for (staged, kind) in staged_maps {
        match kind {
            Some((kind, enc)) => {
                let cx = MapContext {
                    params,
                    synthesis: &synthesis,
                    up: options.up,
                    exr: options.exr,
                    foam_threshold: foam.map(|f| f.threshold),
                    persistent_foam: None,
                };
                maps::write_map(kind, enc, staged, &cx)?;
            }
            None => {
                let img = crate::pipeline::preview::preview_of(params, &synthesis)?;
                export::rgb8::write_by_name(staged, &img.rgb, (img.width, img.height))?;
            }
        }
    }
    for (staged, doc, index) in docs {
        if let Some((staged, index)) = index {
            staged.write_json(&index)?;
        }
        staged.write_json(&doc)?;
    }
    Ok(Written {
        stats,
        mapping,
        has_png,
        files: paths.iter().chain(&map_paths).cloned().collect(),
        import_notes: notes_out,
    })
}

/// Refuses an output path given twice.
pub(crate) fn refuse_repeated(paths: &[PathBuf]) -> Result<(), Error> {
    for (i, p) in paths.iter().enumerate() {
        if paths[..i].contains(p) {
            return Err(Error::Output {
                path: p.clone(),
                message: "given twice".into(),
            });
        }
    }
    Ok(())
}

/// The file name of `p`, or empty.
pub(crate) fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}
