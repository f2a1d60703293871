//! How meshes, raw height maps and tiles are written: the export flags as typed.

use clap::Args;

/// The export flags of `generate`, as typed; `commands::common::export_options` checks them.
#[derive(Debug, Args, Clone, Default)]
pub struct ExportArgs {
    /// Up axis of .obj meshes and .disp.exr vectors: y (default; X = x, Y = height, Z = −y)
    /// or z (X = x, Y = y, Z = height)
    #[arg(long, value_name = "y|z")]
    pub up: Option<String>,
    /// Mesh vertices at every K-th sample (and the far edge); default 1
    #[arg(long, value_name = "K", allow_hyphen_values = true)]
    pub mesh_step: Option<String>,
    /// Factor on the heights of .obj/.glb meshes (normals follow); default 1
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub vertical_scale: Option<String>,
    /// Split .obj/.glb/.r16/.r32 outputs into C×R tiles NAME_x{i}_y{j}.EXT sharing their edges
    /// [default: one file]
    #[arg(long, value_name = "CxR", allow_hyphen_values = true)]
    pub tiles: Option<String>,
    /// Texture coordinates of mesh tiles: global (default: 0..1 over the field) or tile (0..1 per tile)
    #[arg(long, value_name = "global|tile")]
    pub tile_uv: Option<String>,
    /// Mesh tiles of a periodic field written relative to their own corner, equal in size,
    /// with their wrap-around neighbours in the tile index
    #[arg(long)]
    pub periodic_tiles: bool,
    /// Resample .r16/.r32/.png to a legal terrain size: unity (2ⁿ+1), unreal (Unreal's
    /// recommended sizes; 16-bit values in Unreal's encoding with a Z scale) or godot
    /// (2ⁿ+1, with the height range to enter on import); default none
    #[arg(long, value_name = "unity|unreal|godot")]
    pub engine: Option<String>,
    /// Byte order of .r16/.r32: little (default) or big
    #[arg(long, value_name = "little|big")]
    pub byte_order: Option<String>,
    /// How .exr outputs are written
    #[command(flatten)]
    pub exr: ExrArgs,
}

/// The EXR flags, shared by `generate` and `animate`.
#[derive(Debug, Args, Clone, Default)]
pub struct ExrArgs {
    /// Compression of .exr outputs: none (default), zip or piz (both lossless)
    #[arg(long, value_name = "none|zip|piz")]
    pub exr_compression: Option<String>,
    /// Write .exr outputs as 16-bit half floats (default: 32-bit floats)
    #[arg(long)]
    pub exr_half: bool,
}

impl ExrArgs {
    /// The flags given, as (flag, text) (`--exr-half` with an empty text).
    pub fn flags(&self) -> Vec<(&'static str, &str)> {
        [
            ("--exr-compression", self.exr_compression.as_deref()),
            ("--exr-half", self.exr_half.then_some("")),
        ]
        .into_iter()
        .filter_map(|(k, v)| v.map(|v| (k, v)))
        .collect()
    }
}

impl ExportArgs {
    /// The flags given, as (flag, text) in a fixed order (`--periodic-tiles` with an empty
    /// text).
    pub fn flags(&self) -> Vec<(&'static str, &str)> {
        [
            ("--up", self.up.as_deref()),
            ("--mesh-step", self.mesh_step.as_deref()),
            ("--vertical-scale", self.vertical_scale.as_deref()),
            ("--tiles", self.tiles.as_deref()),
            ("--tile-uv", self.tile_uv.as_deref()),
            ("--periodic-tiles", self.periodic_tiles.then_some("")),
            ("--engine", self.engine.as_deref()),
            ("--byte-order", self.byte_order.as_deref()),
        ]
        .into_iter()
        .filter_map(|(k, v)| v.map(|v| (k, v)))
        .chain(self.exr.flags())
        .collect()
    }
}
