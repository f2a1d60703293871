//! Tile file names and the tile index `NAME.tiles.json`, which lists, for every tiled
//! output of one stem, each tile's file, its place in the grid of tiles, the vertices or
//! samples it covers and its offset in meters.

use std::path::{Path, PathBuf};

use serde::Serialize;

use super::mesh::{Placement, Tile};
use super::options::{Engine, TileUv, UpAxis};
use super::{Format, Output};
use crate::grid::GridSpec;

/// The file of tile (`column`, `row`) of the output `path`: `NAME_x{column}_y{row}.EXT`.
pub fn tile_path(path: &Path, column: usize, row: usize) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = match path.extension() {
        Some(e) => format!("{stem}_x{column}_y{row}.{}", e.to_string_lossy()),
        None => format!("{stem}_x{column}_y{row}"),
    };
    path.with_file_name(name)
}

/// The tile index of an output stem: `NAME.tiles.json` beside `NAME.json`.
pub fn index_path(output: &Path) -> PathBuf {
    output.with_extension("tiles.json")
}

#[derive(Debug, Serialize)]
pub struct TileEntry {
    pub file: String,
    /// Column (along x) and row (along y) in the grid of tiles.
    pub x: usize,
    pub y: usize,
    /// Vertices (meshes) or samples (raw) of the tile along x and y.
    pub size: [usize; 2],
    /// Field coordinates of the tile's first vertex or sample, meters.
    pub offset_m: [f64; 2],
    /// Distance from the tile's first to its last vertex or sample, meters.
    pub size_m: [f64; 2],
    /// Where the tile's corner goes in the engine frame of a mesh (with `placement` =
    /// "tile", place the tile there; with "global" its vertices already include it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub engine_offset: Option<[f64; 3]>,
    /// Neighbouring tiles east (+x), west, south (+y) and north, by their files; at the
    /// edges of a periodic set they wrap around.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub neighbours: Option<Neighbours>,
}

#[derive(Debug, Serialize)]
pub struct Neighbours {
    pub plus_x: String,
    pub minus_x: String,
    pub plus_y: String,
    pub minus_y: String,
}

#[derive(Debug, Serialize)]
pub struct TileSet {
    pub format: Format,
    pub columns: usize,
    pub rows: usize,
    /// Meshes: the engine's up axis, where vertices are placed, and the texture coordinates.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub up: Option<UpAxis>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub placement: Option<Placement>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub uv: Option<TileUv>,
    /// Raw height maps: the engine whose sizes the tiles follow.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub engine: Option<Engine>,
    /// The period of the field in meters, when tiles repeat (`--periodic-tiles`): tile
    /// (x + k·columns, y + l·rows) is tile (x, y) moved by (k·Lx, l·Ly).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub period_m: Option<[f64; 2]>,
    pub tiles: Vec<TileEntry>,
}

#[derive(Debug, Serialize)]
pub struct TileIndex {
    pub tool: &'static str,
    pub version: &'static str,
    /// The sidecar holding the field's parameters and each format's import settings.
    pub sidecar: String,
    pub conventions: &'static str,
    pub sets: Vec<TileSet>,
}

fn name_of(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

impl TileSet {
    /// The tile set of a tiled output over a field of `spec`; `None` when untiled.
    pub fn of(output: &Output, spec: &GridSpec) -> Option<TileSet> {
        let tiles = output.tiles()?;
        let columns = tiles.iter().map(|t| t.column).max().unwrap_or(0) + 1;
        let rows = tiles.len() / columns;
        let file = |t: &Tile| name_of(&tile_path(&output.path, t.column, t.row));
        let mut set = TileSet {
            format: output.format(),
            columns,
            rows,
            up: None,
            placement: None,
            uv: None,
            engine: None,
            period_m: None,
            tiles: Vec::new(),
        };
        // Meters of vertex/sample index k along x and y.
        type ToMeters = Box<dyn Fn(usize) -> f64>;
        let exporter = &output.exporter;
        let (to_mx, to_my): (ToMeters, ToMeters) = if let Some(layout) = exporter.mesh_layout() {
            set.up = Some(layout.up);
            set.placement = Some(layout.placement);
            set.uv = Some(layout.uv);
            if layout.placement == Placement::Tile {
                set.period_m = Some([spec.extent_x_m, spec.extent_y_m]);
            }
            let (xs, ys) = (layout.xs.clone(), layout.ys.clone());
            let (dx, dy) = (spec.dx_m(), spec.dy_m());
            (
                Box::new(move |k| xs[k] as f64 * dx),
                Box::new(move |k| ys[k] as f64 * dy),
            )
        } else if let Some(layout) = exporter.raw_layout() {
            set.engine = layout.engine;
            let [sx, sy] = layout.spacing_m(spec);
            (
                Box::new(move |k| k as f64 * sx),
                Box::new(move |k| k as f64 * sy),
            )
        } else {
            return None;
        };
        let find = |c: usize, r: usize| &tiles[r * columns + c];
        for t in tiles {
            let (w, h) = t.size();
            let offset = [to_mx(t.vx.0), to_my(t.vy.0)];
            let engine_offset = set.up.map(|up| match up {
                UpAxis::Y => [offset[0], 0.0, 0.0 - offset[1]],
                UpAxis::Z => [offset[0], offset[1], 0.0],
            });
            let neighbours = (set.period_m.is_some()).then(|| Neighbours {
                plus_x: file(find((t.column + 1) % columns, t.row)),
                minus_x: file(find((t.column + columns - 1) % columns, t.row)),
                plus_y: file(find(t.column, (t.row + 1) % rows)),
                minus_y: file(find(t.column, (t.row + rows - 1) % rows)),
            });
            set.tiles.push(TileEntry {
                file: file(t),
                x: t.column,
                y: t.row,
                size: [w, h],
                offset_m: offset,
                size_m: [to_mx(t.vx.1) - offset[0], to_my(t.vy.1) - offset[1]],
                engine_offset,
                neighbours,
            });
        }
        Some(set)
    }
}

impl TileIndex {
    pub fn new(sidecar: &Path, sets: Vec<TileSet>) -> Self {
        Self {
            tool: "seasynth",
            version: env!("CARGO_PKG_VERSION"),
            sidecar: name_of(sidecar),
            conventions: "tile (x, y): column x along +x, row y along +y, (0, 0) at the origin; \
                          neighbouring tiles share their edge vertices or samples",
            sets,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tile_files_and_the_index_derive_from_the_output_name() {
        assert_eq!(
            tile_path(Path::new("out/sea.obj"), 2, 3),
            PathBuf::from("out/sea_x2_y3.obj")
        );
        assert_eq!(
            index_path(Path::new("out/sea.obj")),
            PathBuf::from("out/sea.tiles.json")
        );
    }
}
