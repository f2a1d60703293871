//! Raw height maps without a header: `.r16` (unsigned 16-bit) and `.r32` (f32 meters),
//! little-endian unless `--byte-order big`, row-major with row 0 at y = 0 like every
//! other format.
//!
//! Without `--engine` a raw file holds the field's samples as they are (nx × ny). With
//! `--engine` it is resampled bilinearly (with the periodic wrap for periodic fields) to
//! a size the engine accepts, spanning the field from x = 0 to its far edge: x = Lx for a
//! periodic field (the last sample is sample 0 again, as terrain systems expect of
//! neighbouring tiles) or the last sample otherwise. A lattice whose cells match the
//! field's (a periodic 4096² field as a 4097² Unity terrain) is copied exactly.
//!
//! - **Unity**: square heightmaps of 2ⁿ + 1 samples, 33 … 4097, `.r16` by the same
//!   [`HeightMapping`] as the PNG (terrain height = max − min, placed at y = min).
//! - **Unreal**: the recommended landscape sizes 127, 253, 505, 1009, 2017, 4033, 8129
//!   per axis, `.r16` in Unreal's encoding: value = 32768 + h·128·(100/Z), Z the
//!   landscape's Z scale, chosen by [`unreal_z_scale`] and recorded in the sidecar.
//!
//! The size chosen is the legal one whose cell count is nearest the field's (in ratio;
//! a tie goes to the larger), so a 512-sample periodic field becomes 513 for Unity and 505
//! for Unreal. With `--tiles C×R` every tile has that size and neighbours share their
//! edge samples (`NAME_x{i}_y{j}.r16`, as Unreal's World Partition import expects).

use std::io::{self, Write};

use super::mesh::{self, Tile};
use super::options::{ByteOrder, Engine, Tiles};
use super::sidecar::{GodotImport, RawInfo, Sidecar, UnityImport, UnrealImport};
use super::{Describe, Exporter, FieldOut, Format, HeightMapping, WriteSeek};
use crate::error::Result;

/// The raw writer: `.r16` or `.r32` samples of a lattice, one file per tile; or the
/// `.r16` samples as a 16-bit grayscale PNG (a PNG for `--engine`).
pub struct Raw {
    pub layout: RawLayout,
    /// `.r16` (else `.r32`).
    pub r16: bool,
    /// The 16-bit samples in a PNG (else headerless).
    pub png: bool,
}

impl Exporter for Raw {
    fn format(&self) -> Format {
        match (self.png, self.r16) {
            (true, _) => Format::Png16,
            (false, true) => Format::R16,
            (false, false) => Format::R32,
        }
    }

    fn tiles(&self) -> Option<&[Tile]> {
        Some(&self.layout.tiles)
    }

    fn write(
        &self,
        field: &FieldOut,
        part: usize,
        _name: &str,
        out: &mut dyn WriteSeek,
    ) -> io::Result<()> {
        let samples = if self.r16 {
            Samples::R16(super::r16_encoding(self.layout.engine, field.mapping))
        } else {
            Samples::R32
        };
        let tile = &self.layout.tiles[part];
        if let (true, Samples::R16(e)) = (self.png, samples) {
            let (nw, nh) = tile.size();
            let mut values = Vec::with_capacity(nw * nh);
            for r in tile.vy.0..tile.vy.0 + nh {
                for c in tile.vx.0..tile.vx.0 + nw {
                    values.push(e.encode(self.layout.height(field.grid, c, r)));
                }
            }
            let spec = GridSpec::new(nw, nh, 1.0, 1.0);
            return super::maps::write_gray16(out, &spec, &values);
        }
        write_tile(out, field.grid, &self.layout, tile, samples)
    }

    fn uses_mapping(&self) -> bool {
        self.r16 && self.layout.engine != Some(Engine::Unreal)
    }

    /// `.r16`, `.r32` and an engine's `.png` of one stem share the layout: one record.
    fn describe(&self, doc: &mut Sidecar, cx: &Describe) {
        let has = |f: Format| cx.formats.contains(&f);
        if (self.r16 && !(self.png && has(Format::R16))) || !(has(Format::R16) || self.png) {
            let r16 = self
                .r16
                .then(|| super::r16_encoding(self.layout.engine, cx.mapping));
            let mut info = self.layout.info(cx.spec, r16, has(Format::R32));
            if self.png && !has(Format::R16) && !has(Format::R32) {
                info.layout = "16-bit grayscale PNG; row 0 is y = 0, column 0 is x = 0";
            }
            doc.raw = Some(info);
        }
    }

    fn raw_layout(&self) -> Option<&RawLayout> {
        Some(&self.layout)
    }
}
use crate::grid::{Grid, GridSpec};

/// Unity's legal heightmap resolutions.
pub const UNITY_SIZES: [usize; 8] = [33, 65, 129, 257, 513, 1025, 2049, 4097];
/// Unreal's recommended landscape sizes (vertices per side).
pub const UNREAL_SIZES: [usize; 7] = [127, 253, 505, 1009, 2017, 4033, 8129];

/// The size in `sizes` (ascending) whose cell count (size − 1) is nearest `cells` in
/// ratio; a tie goes to the larger.
pub fn nearest_size(sizes: &[usize], cells: usize) -> usize {
    let cells = cells.max(1) as f64;
    let mut best = sizes[0];
    for &s in sizes {
        let d = ((s - 1) as f64 / cells).ln().abs();
        let b = ((best - 1) as f64 / cells).ln().abs();
        if d <= b {
            best = s;
        }
    }
    best
}

/// Unreal heightmaps: value 32768 is 0 m and one unit is Z/12800 m (128 units per meter at
/// Z scale 100, whose heights span ±256 m).
pub const UNREAL_ZERO: f64 = 32768.0;
pub const UNREAL_UNITS_PER_M_AT_100: f64 = 12800.0;
/// Fraction of the half range (32767 units) the largest |h| may use.
pub const UNREAL_HEADROOM: f64 = 0.9;

/// The Z scale for heights up to `max_abs_m`: the smallest value, rounded up to three
/// significant digits, that puts |h| ≤ `max_abs_m` within 90 % of the 16-bit half range;
/// 100 (Unreal's default) for a flat field.
pub fn unreal_z_scale(max_abs_m: f64) -> f64 {
    if max_abs_m.is_nan() || max_abs_m <= 0.0 {
        return 100.0;
    }
    let z = max_abs_m * UNREAL_UNITS_PER_M_AT_100 / (UNREAL_HEADROOM * 32767.0);
    let unit = 10f64.powi(z.log10().floor() as i32 - 2);
    let rounded = (z / unit).ceil() * unit;
    // Rounded to a decimal of three digits, which is what a person types on import.
    format!("{rounded:.2e}").parse().unwrap_or(rounded)
}

/// How 16-bit samples encode meters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum R16Encoding {
    /// value = round((h − min)/(max − min)·65535), as the PNG.
    Mapping(HeightMapping),
    /// value = round(32768 + h·12800/z_scale), clamped to 0..65535.
    Unreal { z_scale: f64 },
}

impl R16Encoding {
    #[inline]
    pub fn encode(&self, h: f32) -> u16 {
        match *self {
            R16Encoding::Mapping(m) => m.encode(h),
            R16Encoding::Unreal { z_scale } => {
                let v = (UNREAL_ZERO + h as f64 * UNREAL_UNITS_PER_M_AT_100 / z_scale).round();
                v.clamp(0.0, 65535.0) as u16
            }
        }
    }

    pub fn decode(&self, v: u16) -> f64 {
        match *self {
            R16Encoding::Mapping(m) => m.decode(v),
            R16Encoding::Unreal { z_scale } => {
                (v as f64 - UNREAL_ZERO) * z_scale / UNREAL_UNITS_PER_M_AT_100
            }
        }
    }
}

/// The lattice a raw output samples: its size, the part of the field it spans, its tiles.
#[derive(Debug, Clone, PartialEq)]
pub struct RawLayout {
    /// Samples of the whole lattice (all tiles) along x and y.
    pub size: [usize; 2],
    /// Field samples spanned along x and y: lattice sample c sits at field sample
    /// c·span/(size − 1) (sample n being sample 0 again for a periodic field).
    pub span: [usize; 2],
    pub periodic: bool,
    pub engine: Option<Engine>,
    pub byte_order: ByteOrder,
    /// The tiles, row by row; one tile when untiled.
    pub tiles: Vec<Tile>,
}

impl RawLayout {
    /// The layout for a field of `spec`, with the engine, tiles and byte order given.
    pub fn new(
        spec: &GridSpec,
        periodic: bool,
        engine: Option<Engine>,
        tiles: Option<Tiles>,
        byte_order: ByteOrder,
    ) -> Result<Self> {
        let n = [spec.nx, spec.ny];
        let parts = tiles.map_or([1, 1], |t| [t.columns, t.rows]);
        // Untiled without an engine: the samples as they are.
        let edge = |k: usize| if periodic { n[k] } else { n[k] - 1 };
        let (size, span) = match (engine, tiles) {
            (None, None) => (n, [n[0] - 1, n[1] - 1]),
            (None, Some(_)) => ([edge(0) + 1, edge(1) + 1], [edge(0), edge(1)]),
            (Some(e), _) => {
                let per_tile = |k: usize| edge(k) / parts[k];
                let s = match e {
                    Engine::Unity | Engine::Godot => {
                        let s = nearest_size(&UNITY_SIZES, per_tile(0).max(per_tile(1)));
                        [s, s]
                    }
                    Engine::Unreal => [
                        nearest_size(&UNREAL_SIZES, per_tile(0)),
                        nearest_size(&UNREAL_SIZES, per_tile(1)),
                    ],
                };
                (
                    [parts[0] * (s[0] - 1) + 1, parts[1] * (s[1] - 1) + 1],
                    [edge(0), edge(1)],
                )
            }
        };
        let tiles = match tiles {
            None => vec![Tile::whole(size[0], size[1])],
            Some(t) => mesh::tiles(size[0], size[1], t)?,
        };
        Ok(Self {
            size,
            span,
            periodic,
            engine,
            byte_order,
            tiles,
        })
    }

    /// Field position (in samples) of lattice sample `c` along axis `k`.
    #[inline]
    fn position(&self, k: usize, c: usize) -> f64 {
        (c * self.span[k]) as f64 / (self.size[k] - 1) as f64
    }

    /// Spacing of the lattice in meters along x and y.
    pub fn spacing_m(&self, spec: &GridSpec) -> [f64; 2] {
        [
            self.span[0] as f64 * spec.dx_m() / (self.size[0] - 1) as f64,
            self.span[1] as f64 * spec.dy_m() / (self.size[1] - 1) as f64,
        ]
    }

    /// Height at lattice sample (`c`, `r`): the field bilinearly interpolated, exact where
    /// the lattice falls on a sample.
    #[inline]
    pub fn height(&self, grid: &Grid, c: usize, r: usize) -> f32 {
        let (nx, ny) = (grid.spec.nx, grid.spec.ny);
        let (px, py) = (self.position(0, c), self.position(1, r));
        let (i0, j0) = (px.floor() as usize, py.floor() as usize);
        let (tx, ty) = (px - i0 as f64, py - j0 as f64);
        let next = |k: usize, n: usize| {
            if self.periodic {
                (k + 1) % n
            } else {
                (k + 1).min(n - 1)
            }
        };
        let (i0w, j0w) = (i0 % nx, j0 % ny);
        let (i1, j1) = (next(i0w, nx), next(j0w, ny));
        let h = |i: usize, j: usize| grid.data[j * nx + i] as f64;
        let top = h(i0w, j0w) + tx * (h(i1, j0w) - h(i0w, j0w));
        if ty == 0.0 {
            return top as f32;
        }
        let bottom = h(i0w, j1) + tx * (h(i1, j1) - h(i0w, j1));
        (top + ty * (bottom - top)) as f32
    }
}

/// What a raw file stores per sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Samples {
    R16(R16Encoding),
    R32,
}

/// Writes `tile` of the lattice `layout` over `grid`.
pub fn write_tile<W: Write + ?Sized>(
    w: &mut W,
    grid: &Grid,
    layout: &RawLayout,
    tile: &Tile,
    samples: Samples,
) -> io::Result<()> {
    let (nw, nh) = tile.size();
    let width = match samples {
        Samples::R16(_) => 2,
        Samples::R32 => 4,
    };
    let big = layout.byte_order == ByteOrder::Big;
    super::par_rows(w, nh, nw * width, |r, out| {
        for c in tile.vx.0..tile.vx.0 + nw {
            let h = layout.height(grid, c, tile.vy.0 + r);
            match samples {
                Samples::R16(e) => {
                    let v = e.encode(h);
                    out.extend_from_slice(&if big {
                        v.to_be_bytes()
                    } else {
                        v.to_le_bytes()
                    });
                }
                Samples::R32 => {
                    out.extend_from_slice(&if big {
                        h.to_be_bytes()
                    } else {
                        h.to_le_bytes()
                    });
                }
            }
        }
    })
}

impl RawLayout {
    /// The sidecar's record of this layout, for `.r16` (with its encoding) and/or `.r32`.
    pub fn info(&self, spec: &GridSpec, r16: Option<R16Encoding>, r32: bool) -> RawInfo {
        let spacing = self.spacing_m(spec);
        let span = [
            self.span[0] as f64 * spec.dx_m(),
            self.span[1] as f64 * spec.dy_m(),
        ];
        let tile_size = (self.tiles.len() > 1).then(|| {
            let (w, h) = self.tiles[0].size();
            [w, h]
        });
        let per_tile = tile_size.unwrap_or(self.size);
        let unity = match (self.engine, r16) {
            (Some(Engine::Unity), Some(R16Encoding::Mapping(m))) => Some(UnityImport {
                depth_bits: 16,
                resolution: per_tile[0],
                byte_order: match self.byte_order {
                    ByteOrder::Little => "Windows",
                    ByteOrder::Big => "Mac",
                },
                flip_vertically: false,
                terrain_size_m: [
                    spacing[0] * (per_tile[0] - 1) as f64,
                    m.max_m - m.min_m,
                    spacing[1] * (per_tile[1] - 1) as f64,
                ],
                terrain_position_m: [0.0, m.min_m, 0.0],
            }),
            _ => None,
        };
        let godot = match (self.engine, r16) {
            (Some(Engine::Godot), Some(R16Encoding::Mapping(m))) => Some(GodotImport {
                resolution: per_tile,
                height_range_m: [m.min_m, m.max_m],
                spacing_m: spacing,
                hterrain: format!(
                    "Import: heightmap = the .r16 or .png, Min Height {} m, Max Height {} m \
                     (map size {} = 2^n + 1); scale the terrain node by {} m per cell",
                    m.min_m, m.max_m, per_tile[0], spacing[0]
                ),
                terrain3d: format!(
                    "Importer: height file = the .r16/.png with Height Offset {} m and Import \
                     Scale {} m (the range), or the field's .exr at scale 1; vertex spacing {} m",
                    m.min_m,
                    m.max_m - m.min_m,
                    spacing[0]
                ),
            }),
            _ => None,
        };
        let unreal = match r16 {
            Some(R16Encoding::Unreal { z_scale }) => Some(UnrealImport {
                resolution: per_tile,
                scale: [spacing[0] * 100.0, spacing[1] * 100.0, z_scale],
                z_scale,
                formula: "value = round(32768 + h_m * 128 * 100 / z_scale), clamped to 0..65535",
                decode: "h_m = (value - 32768) * z_scale / 12800",
            }),
            _ => None,
        };
        RawInfo {
            size: self.size,
            tile_size,
            byte_order: self.byte_order,
            layout: "row-major, no header; row 0 is y = 0, column 0 is x = 0",
            spacing_m: spacing,
            span_m: span,
            resampled: self.engine.is_some(),
            engine: self.engine,
            r16: r16.map(|e| match e {
                R16Encoding::Mapping(m) => format!(
                    "unsigned 16-bit; h_m = {} + value * {} (the 16-bit mapping)",
                    m.min_m,
                    m.step_m()
                ),
                R16Encoding::Unreal { z_scale } => format!(
                    "unsigned 16-bit, Unreal landscape encoding; h_m = (value - 32768) * {z_scale} / 12800"
                ),
            }),
            r32: r32.then_some("32-bit IEEE float, meters"),
            unity,
            unreal,
            godot,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_sizes_follow_the_ratio_of_cells() {
        assert_eq!(nearest_size(&UNITY_SIZES, 512), 513);
        assert_eq!(nearest_size(&UNITY_SIZES, 4096), 4097);
        assert_eq!(nearest_size(&UNITY_SIZES, 600), 513);
        assert_eq!(nearest_size(&UNITY_SIZES, 800), 1025);
        assert_eq!(nearest_size(&UNITY_SIZES, 10), 33);
        assert_eq!(nearest_size(&UNITY_SIZES, 100_000), 4097);
        assert_eq!(nearest_size(&UNREAL_SIZES, 512), 505);
        assert_eq!(nearest_size(&UNREAL_SIZES, 4096), 4033);
        assert_eq!(nearest_size(&UNREAL_SIZES, 1024), 1009);
        assert_eq!(nearest_size(&UNREAL_SIZES, 20_000), 8129);
    }

    #[test]
    fn the_unreal_z_scale_fits_the_heights_with_headroom() {
        for h in [0.05, 0.37, 1.0, 2.5, 15.0, 240.0, 1000.0] {
            let z = unreal_z_scale(h);
            let e = R16Encoding::Unreal { z_scale: z };
            let top = e.encode(h as f32) as f64 - UNREAL_ZERO;
            let bottom = UNREAL_ZERO - e.encode(-h as f32) as f64;
            assert!(top <= 0.9 * 32767.0 + 1.0, "h {h}: z {z} puts it at +{top}");
            assert!(
                bottom <= 0.9 * 32767.0 + 1.0,
                "h {h}: z {z} puts −h at −{bottom}"
            );
            assert!(top >= 0.8 * 32767.0, "h {h}: z {z} wastes range ({top})");
            // Round trip within half a unit (plus the f32 rounding of 0.3·h).
            let unit = z / 12800.0;
            let slack = 1e-7 * h;
            assert!((e.decode(e.encode(0.3 * h as f32)) - 0.3 * h).abs() <= unit / 2.0 + slack);
        }
        assert_eq!(unreal_z_scale(0.0), 100.0);
        assert_eq!(R16Encoding::Unreal { z_scale: 100.0 }.encode(0.0), 32768);
        assert_eq!(
            R16Encoding::Unreal { z_scale: 100.0 }.encode(1.0),
            32768 + 128
        );
    }

    fn ramp_grid(n: usize) -> Grid {
        Grid::new(
            GridSpec::new(n, n, n as f64, n as f64),
            (0..n * n)
                .map(|k| (k % n) as f32 + 10.0 * (k / n) as f32)
                .collect(),
        )
    }

    #[test]
    fn untiled_without_an_engine_is_the_field_itself() {
        let g = ramp_grid(8);
        let l = RawLayout::new(&g.spec, true, None, None, ByteOrder::Little).unwrap();
        assert_eq!(l.size, [8, 8]);
        for r in 0..8 {
            for c in 0..8 {
                assert_eq!(l.height(&g, c, r), g.get(c, r));
            }
        }
    }

    #[test]
    fn a_matching_unity_lattice_copies_samples_and_wraps_the_far_edge() {
        let g = ramp_grid(32);
        let l =
            RawLayout::new(&g.spec, true, Some(Engine::Unity), None, ByteOrder::Little).unwrap();
        assert_eq!(l.size, [33, 33]);
        assert_eq!(l.height(&g, 5, 7), g.get(5, 7));
        assert_eq!(l.height(&g, 32, 7), g.get(0, 7), "x = L is sample 0");
        // Unreal resamples 32 cells onto 126: between samples, bilinear.
        let l = RawLayout::new(&g.spec, false, Some(Engine::Unreal), None, ByteOrder::Big).unwrap();
        assert_eq!(l.size, [127, 127]);
        // The ramp h = x is linear, so bilinear interpolation is exact up to f32 rounding.
        const RAMP_TOL: f32 = 1e-5;
        let want = (31.0 / 126.0 * 50.0) as f32;
        assert!((l.height(&g, 50, 0) - want).abs() < RAMP_TOL);
        assert_eq!(
            l.height(&g, 126, 126),
            g.get(31, 31),
            "non-periodic: ends on the last sample"
        );
    }

    #[test]
    fn engine_tiles_are_equal_and_share_edges() {
        let spec = GridSpec::new(4096, 2048, 4096.0, 2048.0);
        let t = Tiles {
            columns: 4,
            rows: 2,
        };
        let l = RawLayout::new(
            &spec,
            true,
            Some(Engine::Unreal),
            Some(t),
            ByteOrder::Little,
        )
        .unwrap();
        assert_eq!(l.size, [4 * 1008 + 1, 2 * 1008 + 1]);
        assert_eq!(l.tiles.len(), 8);
        assert!(l.tiles.iter().all(|t| t.size() == (1009, 1009)));
        assert_eq!(l.tiles[0].vx.1, l.tiles[1].vx.0);
    }
}
