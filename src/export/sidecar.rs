//! The JSON sidecar written beside every output (`NAME.json` for `NAME.png`, `NAME.tif`):
//! the fully resolved parameters (give the file back as `--preset NAME.json` to regenerate
//! the outputs bit for bit), the seed, the version, the 16-bit mapping and statistics,
//! and what each export needs to be imported correctly: the mesh frame (`mesh`), the raw
//! layout and encoding with Unity's and Unreal's import settings (`raw`), the EXR
//! channel (`exr`), the GeoTIFF frame (`geotiff`) and the tile index (`tiles_index`).

use std::path::{Path, PathBuf};

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::mesh::MeshInfo;
use super::options::{ByteOrder, Engine};
use super::{Format, HeightMapping};
use crate::config::Params;
use crate::field::SynthesisInfo;
use crate::grid::{GridSpec, Stats};

/// The grid as written: how samples map to meters.
#[derive(Debug, Serialize)]
pub struct GridInfo {
    pub nx: usize,
    pub ny: usize,
    pub dx_m: f64,
    pub dy_m: f64,
    pub extent_m: [f64; 2],
    /// Where sample (i, j) sits and how rows are stored.
    pub layout: &'static str,
    /// `corners` or `centers` (`--sample-at`).
    pub sample_at: &'static str,
}

impl GridInfo {
    /// The grid of `params`, with where its samples sit.
    pub fn of(params: &Params) -> Self {
        let mut g = GridInfo::from(&params.grid_spec());
        g.sample_at = params.grid.sample_at.name();
        if !params.grid.sample_at.is_corners() {
            g.layout = "sample (i, j) at x = (i + 0.5)*dx_m, y = (j + 0.5)*dy_m (texel centres); image row j is y_j, row 0 first";
        }
        g
    }
}

impl From<&GridSpec> for GridInfo {
    fn from(s: &GridSpec) -> Self {
        Self {
            nx: s.nx,
            ny: s.ny,
            dx_m: s.dx_m(),
            dy_m: s.dy_m(),
            extent_m: [s.extent_x_m, s.extent_y_m],
            layout: "sample (i, j) at x = i*dx_m, y = j*dy_m; image row j is y_j, row 0 first",
            sample_at: "corners",
        }
    }
}

#[derive(Debug, Serialize)]
pub struct FileEntry {
    pub file: String,
    pub format: Format,
}

/// The 16-bit mapping as recorded.
#[derive(Debug, Serialize)]
pub struct MappingInfo {
    #[serde(flatten)]
    pub range: HeightMapping,
    pub step_m: f64,
    pub formula: &'static str,
    /// Where the range came from: the field's min..max, or `--height-range`.
    pub source: &'static str,
}

#[derive(Debug, Serialize)]
pub struct Sidecar<'a> {
    pub tool: &'static str,
    pub version: &'static str,
    pub seed: u64,
    pub files: Vec<FileEntry>,
    pub grid: GridInfo,
    pub stats: Stats,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mapping: Option<MappingInfo>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<MeshInfo>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub raw: Option<RawInfo>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exr: Option<ExrInfo>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub geotiff: Option<GeoTiffInfo>,
    /// The tile index listing the tile files, when outputs are tiled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tiles_index: Option<String>,
    /// The job of a `seasynth batch` this output belongs to.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub batch: Option<&'a crate::export::sidecar::JobRecord>,
    /// The foam threshold of the maps, resolved (`motion.foam_threshold` may be "auto"),
    /// when the Jacobian was computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub foam: Option<crate::measure::foam::ResolvedFoam>,
    pub synthesis: &'a SynthesisInfo,
    pub params: &'a Params,
}

/// The EXR channel and its meaning.
#[derive(Debug, Serialize)]
pub struct ExrInfo {
    pub channel: &'static str,
    pub sample: String,
}

/// The GeoTIFF frame of the float TIFF.
#[derive(Debug, Serialize)]
pub struct GeoTiffInfo {
    pub pixel_scale_m: [f64; 3],
    pub tiepoint: [f64; 6],
    pub crs: &'static str,
    pub raster_type: &'static str,
    pub model_y: &'static str,
}

impl GeoTiffInfo {
    /// The frame of a TIFF of `spec`, samples at texel centres (PixelIsArea) when `area`.
    pub fn new(spec: &GridSpec, area: bool) -> Self {
        Self {
            pixel_scale_m: [spec.dx_m(), spec.dy_m(), 0.0],
            tiepoint: [0.0; 6],
            crs: CRS_CITATION,
            raster_type: if area {
                "PixelIsArea: pixel (i, j) covers model [i*dx_m, (i+1)*dx_m] x [-(j+1)*dy_m, -j*dy_m]; the sample is its centre"
            } else {
                "PixelIsPoint: sample (i, j) at model (i*dx_m, -j*dy_m)"
            },
            model_y: "GIS model Y = -y (row 0 at the top)",
        }
    }
}

impl MappingInfo {
    /// The record of `range`, taken from `source`.
    pub fn new(range: HeightMapping, source: &'static str) -> Self {
        Self {
            range,
            step_m: range.step_m(),
            formula: FORMULA,
            source,
        }
    }
}

pub const FORMULA: &str =
    "value = round((h - min_m) / (max_m - min_m) * 65535), clamped to 0..65535";

impl<'a> Sidecar<'a> {
    pub fn new(params: &'a Params, info: &'a SynthesisInfo, stats: Stats) -> Self {
        Self {
            tool: "seasynth",
            version: env!("CARGO_PKG_VERSION"),
            seed: params.seed,
            files: Vec::new(),
            grid: GridInfo::of(params),
            stats,
            mapping: None,
            mesh: None,
            raw: None,
            exr: None,
            geotiff: None,
            tiles_index: None,
            batch: None,
            foam: None,
            synthesis: info,
            params,
        }
    }
}

/// The sidecar path of an output: same folder and stem, `.json`.
pub fn path_for(output: &Path) -> PathBuf {
    output.with_extension("json")
}

/// The `batch` record of a job's sidecar.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JobRecord {
    /// The job's number in the whole batch, from 0.
    pub job: usize,
    /// Jobs in the batch.
    pub jobs: usize,
    pub name: String,
    /// Hash of what fixes the job's files: version, parameters (with the batch's
    /// mapping), file names and export options.
    pub hash: String,
    /// The job's value of each swept key.
    pub values: BTreeMap<String, String>,
}

/// The name of an EXR height map's single channel.
pub const EXR_CHANNEL: &str = "Y";

/// The GeoTIFF citation of the coordinate system: a local engineering frame in meters.
pub const CRS_CITATION: &str = "seasynth local engineering frame, meters";

/// What Unity's "Import Raw" dialog needs.
#[derive(Debug, Serialize)]
pub struct UnityImport {
    pub depth_bits: u32,
    /// Resolution of each terrain (square).
    pub resolution: usize,
    /// "Windows" (little-endian) or "Mac" (big-endian).
    pub byte_order: &'static str,
    pub flip_vertically: bool,
    /// Terrain size X (width), Y (height), Z (length), meters.
    pub terrain_size_m: [f64; 3],
    /// Place the terrain at this position (its y is the height of value 0).
    pub terrain_position_m: [f64; 3],
}

/// What Unreal's landscape import needs.
#[derive(Debug, Serialize)]
pub struct UnrealImport {
    /// Vertices of each heightmap (x, y).
    pub resolution: [usize; 2],
    /// Landscape scale X, Y, Z in Unreal's units (cm per vertex; Z as on import).
    pub scale: [f64; 3],
    pub z_scale: f64,
    pub formula: &'static str,
    pub decode: &'static str,
}

/// What Godot's terrain plugins (HTerrain, Terrain3D) need on import.
#[derive(Debug, Serialize)]
pub struct GodotImport {
    /// Samples of each heightmap (x, y): 2ⁿ + 1, as HTerrain requires.
    pub resolution: [usize; 2],
    /// Heights of 16-bit values 0 and 65535, meters.
    pub height_range_m: [f64; 2],
    /// Meters between samples.
    pub spacing_m: [f64; 2],
    /// The numbers HTerrain's import dialog asks for.
    pub hterrain: String,
    /// The numbers Terrain3D's importer asks for.
    pub terrain3d: String,
}

/// The raw outputs of one sidecar, as recorded there.
#[derive(Debug, Serialize)]
pub struct RawInfo {
    /// Samples of the whole lattice (all tiles together), x then y.
    pub size: [usize; 2],
    /// Samples of each tile, when tiled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tile_size: Option<[usize; 2]>,
    pub byte_order: ByteOrder,
    pub layout: &'static str,
    pub spacing_m: [f64; 2],
    /// Distance from the first to the last sample, x and y.
    pub span_m: [f64; 2],
    pub resampled: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub engine: Option<Engine>,
    /// How `.r16` values encode meters.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub r16: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub r32: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unity: Option<UnityImport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unreal: Option<UnrealImport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub godot: Option<GodotImport>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sidecar_paths_share_the_stem() {
        assert_eq!(
            path_for(Path::new("out/a.png")),
            PathBuf::from("out/a.json")
        );
        assert_eq!(path_for(Path::new("a.b.tif")), PathBuf::from("a.b.json"));
    }
}
