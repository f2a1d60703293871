//! The triangle grid that the mesh formats (OBJ, glTF) share: which samples become
//! vertices, how the vertices split into tiles, and each vertex's position, normal and
//! texture coordinates in engine coordinates.
//!
//! **Vertices.** Along an axis of `n` samples, a mesh step K keeps the samples 0, K, 2K, …
//! and the far edge: sample `n` for a periodic field — the sample n·d = L, which is sample
//! 0 again, so the mesh spans the whole period and copies of it join without a seam — or
//! sample `n − 1` for a non-periodic field, whose mesh ends at its last sample. When K
//! does not divide the span the last cell is narrower. A periodic n × m field thus has
//! (n/K + 1)·(m/K + 1) vertices and 2·(n/K)·(m/K) triangles.
//!
//! **Coordinates.** The field's frame (x, y horizontal, h up) is right-handed. With
//! `--up y` (the default; glTF's convention) X = x, Y = h·s, Z = −y; with `--up z`
//! X = x, Y = y, Z = h·s (s: `--vertical-scale`). Both engine frames are right-handed: the
//! first is the second turned by −90° about X, so nothing is mirrored. Meters throughout.
//!
//! **Triangles.** Each cell with corners v00 = (i, j), v10 = (i+1, j), v11, v01 gives the
//! triangles (v00, v10, v11) and (v00, v11, v01): counter-clockwise seen from above, so
//! the faces (and the normals) point up.
//!
//! **Normals** come from the slopes of the whole field, not of the mesh or a tile, so
//! tiles and decimated meshes get the same normal at the same sample: n ∝ (−s·∂h/∂x,
//! −s·∂h/∂y, 1) in the field's frame. [`slopes_central`] gives central differences (with
//! the periodic wrap, or one-sided at the edges of a non-periodic field); [`slopes_at`]
//! gives the same numbers at a tile's vertices only, which is what the writers use, so
//! memory holds one tile's slopes rather than the field's. Slopes of the whole field from
//! elsewhere (exact spectral slopes) can be handed to [`Mesh`] instead, and
//! [`normals_from_slopes`] turns any slopes into normals.
//!
//! **Texture coordinates** (`--tile-uv global`): u = x/Lx, and v from y/Ly: glTF's
//! v = y/Ly (origin at the image's top-left), OBJ's v = 1 − y/Ly (origin bottom-left), so
//! in both the field's PNG/EXR (row 0 at the top) lands where it was sampled. Sample i's
//! texel center is at u = (i + ½)/nx: half a texel from its vertex. `--tile-uv tile`
//! runs 0..1 across each tile instead.

use rayon::prelude::*;
use serde::Serialize;

use super::options::{ExportOptions, TileUv, Tiles, UpAxis};

use crate::error::{Error, Result};
use crate::grid::{Grid, GridSpec};

/// The samples along an axis of `n` that become vertices: 0, `step`, 2·`step`, … and the
/// far edge (`n` when periodic, else `n − 1`). Sample `n` stands for sample 0 at x = L.
pub fn axis_vertices(n: usize, step: usize, periodic: bool) -> Vec<usize> {
    let last = if periodic { n } else { n - 1 };
    let mut v: Vec<usize> = (0..last).step_by(step.max(1)).collect();
    v.push(last);
    v
}

/// Splits `cells` cells into `parts` runs as equal as possible; each run is given as its
/// first and last vertex (inclusive), so neighbouring runs share a vertex.
pub fn split(cells: usize, parts: usize) -> Vec<(usize, usize)> {
    (0..parts)
        .map(|p| (p * cells / parts, (p + 1) * cells / parts))
        .collect()
}

/// One tile: a block of the vertex lattice, its edges shared with its neighbours.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Tile {
    /// Column (along x) and row (along y) of the tile; (0, 0) holds the origin.
    pub column: usize,
    pub row: usize,
    /// First and last vertex along x and along y (inclusive).
    pub vx: (usize, usize),
    pub vy: (usize, usize),
}

impl Tile {
    /// The whole lattice of `nx` × `ny` vertices as one tile.
    pub fn whole(nx: usize, ny: usize) -> Self {
        Self {
            column: 0,
            row: 0,
            vx: (0, nx - 1),
            vy: (0, ny - 1),
        }
    }

    /// Vertices along x and along y.
    pub fn size(&self) -> (usize, usize) {
        (self.vx.1 - self.vx.0 + 1, self.vy.1 - self.vy.0 + 1)
    }

    pub fn vertex_count(&self) -> usize {
        let (w, h) = self.size();
        w * h
    }

    pub fn triangle_count(&self) -> usize {
        let (w, h) = self.size();
        2 * (w - 1) * (h - 1)
    }
}

/// The C × R tiles of a lattice of `nx` × `ny` vertices, row by row (row 0 first), or an
/// error naming the flag when there are fewer cells than tiles along an axis.
pub fn tiles(nx: usize, ny: usize, t: Tiles) -> Result<Vec<Tile>> {
    for (axis, cells, parts) in [("x", nx - 1, t.columns), ("y", ny - 1, t.rows)] {
        if parts > cells {
            return Err(Error::Set {
                origin: format!("--tiles {}x{}", t.columns, t.rows),
                message: format!(
                    "needs at least one cell per tile, and the lattice has {cells} cells along {axis}"
                ),
            });
        }
    }
    let xs = split(nx - 1, t.columns);
    let ys = split(ny - 1, t.rows);
    Ok(ys
        .iter()
        .enumerate()
        .flat_map(|(row, &vy)| {
            xs.iter().enumerate().map(move |(column, &vx)| Tile {
                column,
                row,
                vx,
                vy,
            })
        })
        .collect())
}

pub use crate::measure::slopes::{Slopes, slopes_at, slopes_central};

/// The unit normal of a surface of slopes (`dhdx`, `dhdy`) with heights scaled by
/// `vertical_scale`, in the engine frame of `up`.
#[inline]
pub fn normal_from_slope(dhdx: f32, dhdy: f32, vertical_scale: f64, up: UpAxis) -> [f32; 3] {
    // `0.0 - v` rather than `-v`: a flat field gives +0, never "-0" in text formats.
    let a = 0.0 - vertical_scale * dhdx as f64;
    let b = 0.0 - vertical_scale * dhdy as f64;
    let len = (a * a + b * b + 1.0).sqrt();
    let (a, b, c) = ((a / len) as f32, (b / len) as f32, (1.0 / len) as f32);
    match up {
        UpAxis::Y => [a, c, 0.0 - b],
        UpAxis::Z => [a, b, c],
    }
}

/// Unit normals, sample by sample, of slopes `dhdx` and `dhdy` (equal lengths).
pub fn normals_from_slopes(
    dhdx: &[f32],
    dhdy: &[f32],
    vertical_scale: f64,
    up: UpAxis,
) -> Vec<[f32; 3]> {
    assert_eq!(
        dhdx.len(),
        dhdy.len(),
        "one slope per sample along each axis"
    );
    dhdx.par_iter()
        .zip(dhdy)
        .map(|(&sx, &sy)| normal_from_slope(sx, sy, vertical_scale, up))
        .collect()
}

/// Where tile vertices are placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Placement {
    /// In the field's coordinates: tiles imported together form the field.
    Global,
    /// Relative to the tile's own corner (`--periodic-tiles`): every tile spans the same
    /// coordinates, placed by the offsets in the tile index.
    Tile,
}

/// How the mesh of a field is laid out: vertices, frame, scale, texture coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshLayout {
    /// Samples that become vertices along x and y (see [`axis_vertices`]).
    pub xs: Vec<usize>,
    pub ys: Vec<usize>,
    /// The mesh step K (`--mesh-step`).
    pub step: usize,
    pub up: UpAxis,
    pub vertical_scale: f64,
    pub uv: TileUv,
    pub placement: Placement,
    pub periodic: bool,
    /// Offset of the samples from the grid corners, in samples: 0, or ½ for `--sample-at
    /// centers` (vertices and UVs sit where the samples are).
    pub offset: f64,
}

impl MeshLayout {
    /// The mesh of a field of `spec` with `options`, `up` the engine's up axis, and its
    /// tiles (`tiled`; one tile when `None`).
    pub fn plan(
        options: &ExportOptions,
        spec: &GridSpec,
        periodic: bool,
        up: UpAxis,
        tiled: Option<Tiles>,
    ) -> Result<(Self, Vec<Tile>)> {
        let layout = MeshLayout {
            xs: axis_vertices(spec.nx, options.mesh_step, periodic),
            ys: axis_vertices(spec.ny, options.mesh_step, periodic),
            step: options.mesh_step,
            up,
            vertical_scale: options.vertical_scale,
            uv: options.tile_uv,
            placement: if options.periodic_tiles {
                Placement::Tile
            } else {
                Placement::Global
            },
            periodic,
            offset: options.sample_at.offset(),
        };
        let (vx, vy) = (layout.xs.len(), layout.ys.len());
        let tiles = match tiled {
            None => vec![Tile::whole(vx, vy)],
            Some(t) => tiles(vx, vy, t)?,
        };
        if options.periodic_tiles {
            equal_tiles(&layout, &tiles, spec, options.mesh_step)?;
        }
        Ok((layout, tiles))
    }
}

/// Periodic tiles must all be alike: the same number of equal cells.
fn equal_tiles(layout: &MeshLayout, tiles: &[Tile], spec: &GridSpec, step: usize) -> Result<()> {
    let uniform = spec.nx % step == 0 && spec.ny % step == 0;
    let first = tiles[0].size();
    if uniform && tiles.iter().all(|t| t.size() == first) {
        return Ok(());
    }
    let columns = tiles.iter().map(|t| t.column).max().unwrap_or(0) + 1;
    let rows = tiles.len() / columns;
    Err(Error::Set {
        origin: "--periodic-tiles".into(),
        message: format!(
            "needs equal tiles: --mesh-step {step} must divide the grid size {}x{} and the              tiles {columns}x{rows} the mesh's {}x{} cells",
            spec.nx,
            spec.ny,
            layout.xs.len() - 1,
            layout.ys.len() - 1
        ),
    })
}

/// The mesh of one field: a layout over a grid.
pub struct Mesh<'a> {
    pub layout: &'a MeshLayout,
    pub grid: &'a Grid,
    /// Slopes of the whole field, per sample, to use instead of central differences.
    pub field_slopes: Option<&'a Slopes>,
}

/// The slopes at the vertices of one tile, row-major over the tile.
pub struct TileSlopes {
    slopes: Slopes,
    first: (usize, usize),
    width: usize,
}

impl Mesh<'_> {
    /// Field index of vertex (`vi`, `vj`) (sample n wraps to 0).
    #[inline]
    fn sample(&self, vi: usize, vj: usize) -> usize {
        let s = &self.grid.spec;
        (self.layout.ys[vj] % s.ny) * s.nx + self.layout.xs[vi] % s.nx
    }

    /// Vertex (`vi`, `vj`) of `tile` in engine coordinates, meters. Computed from integer
    /// sample offsets, so a vertex shared by two tiles gets the same bits in both.
    #[inline]
    pub fn position(&self, vi: usize, vj: usize, tile: &Tile) -> [f32; 3] {
        let l = self.layout;
        let (ox, oy) = match l.placement {
            Placement::Global => (0, 0),
            Placement::Tile => (l.xs[tile.vx.0], l.ys[tile.vy.0]),
        };
        // `offset` is 0 for samples at corners (then these are (xs − ox)·dx exactly).
        let x = (((l.xs[vi] - ox) as f64 + l.offset) * self.grid.spec.dx_m()) as f32;
        let y = (((l.ys[vj] - oy) as f64 + l.offset) * self.grid.spec.dy_m()) as f32;
        let h = (self.grid.data[self.sample(vi, vj)] as f64 * l.vertical_scale) as f32;
        match l.up {
            UpAxis::Y => [x, h, 0.0 - y],
            UpAxis::Z => [x, y, h],
        }
    }

    /// The slopes at the vertices of `tile`: central differences of the whole field at
    /// those samples, or the field slopes given.
    pub fn tile_slopes(&self, tile: &Tile) -> TileSlopes {
        let xs = &self.layout.xs[tile.vx.0..=tile.vx.1];
        let ys = &self.layout.ys[tile.vy.0..=tile.vy.1];
        let slopes = match self.field_slopes {
            None => slopes_at(self.grid, self.layout.periodic, xs, ys),
            Some(f) => {
                let (nx, ny) = (self.grid.spec.nx, self.grid.spec.ny);
                let at = |v: &[f32]| -> Vec<f32> {
                    ys.iter()
                        .flat_map(|&y| xs.iter().map(move |&x| v[(y % ny) * nx + x % nx]))
                        .collect()
                };
                Slopes {
                    dhdx: at(&f.dhdx),
                    dhdy: at(&f.dhdy),
                }
            }
        };
        TileSlopes {
            slopes,
            first: (tile.vx.0, tile.vy.0),
            width: xs.len(),
        }
    }

    /// Unit normal at vertex (`vi`, `vj`) of the tile whose slopes are `s`.
    #[inline]
    pub fn normal(&self, s: &TileSlopes, vi: usize, vj: usize) -> [f32; 3] {
        let k = (vj - s.first.1) * s.width + (vi - s.first.0);
        normal_from_slope(
            s.slopes.dhdx[k],
            s.slopes.dhdy[k],
            self.layout.vertical_scale,
            self.layout.up,
        )
    }

    /// Texture coordinates (u, t) of vertex (`vi`, `vj`) of `tile`, t growing with y:
    /// glTF's v is t, OBJ's v is 1 − t.
    #[inline]
    pub fn uv(&self, vi: usize, vj: usize, tile: &Tile) -> (f64, f64) {
        let l = self.layout;
        match l.uv {
            TileUv::Global => {
                let s = &self.grid.spec;
                (
                    (l.xs[vi] as f64 + l.offset) / s.nx as f64,
                    (l.ys[vj] as f64 + l.offset) / s.ny as f64,
                )
            }
            TileUv::Tile => {
                let frac = |v: &[usize], k: usize, (a, b): (usize, usize)| {
                    (v[k] - v[a]) as f64 / (v[b] - v[a]) as f64
                };
                (frac(&l.xs, vi, tile.vx), frac(&l.ys, vj, tile.vy))
            }
        }
    }
}

/// The conventions of a mesh, recorded in the sidecar and in each OBJ's header.
#[derive(Debug, Serialize)]
pub struct MeshInfo {
    pub up: UpAxis,
    pub coordinates: &'static str,
    pub winding: &'static str,
    pub units: &'static str,
    pub mesh_step: usize,
    pub vertical_scale: f64,
    /// Vertices of the whole mesh along x and y (all tiles together).
    pub vertices: [usize; 2],
    pub triangles: usize,
    pub periodic: bool,
    pub placement: Placement,
    pub uv: TileUv,
    pub uv_convention: &'static str,
    pub normals: &'static str,
}

impl MeshLayout {
    /// The conventions of this layout; `exact_slopes`: the normals come from the field's
    /// exact spectral slopes (else from central differences of its heights).
    pub fn info(&self, exact_slopes: bool) -> MeshInfo {
        let (nx, ny) = (self.xs.len(), self.ys.len());
        MeshInfo {
            up: self.up,
            coordinates: match self.up {
                UpAxis::Y => "X = x, Y = h * vertical_scale, Z = -y (right-handed, +Y up)",
                UpAxis::Z => "X = x, Y = y, Z = h * vertical_scale (right-handed, +Z up)",
            },
            winding: "counter-clockwise seen from above; faces and normals point up",
            units: "meters",
            mesh_step: self.step,
            vertical_scale: self.vertical_scale,
            vertices: [nx, ny],
            triangles: 2 * (nx - 1) * (ny - 1),
            periodic: self.periodic,
            placement: self.placement,
            uv: self.uv,
            uv_convention: "u = x / Lx; glTF v = y / Ly, OBJ v = 1 - y / Ly (per tile with uv = tile)",
            normals: if exact_slopes {
                "exact spectral slopes of the whole field (i kx h, i ky h in Fourier space)"
            } else if self.periodic {
                "central differences of the whole field, periodic wrap"
            } else {
                "central differences of the whole field, one-sided at its edges"
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::GridSpec;

    fn layout(nx: usize, ny: usize, step: usize, periodic: bool, up: UpAxis) -> MeshLayout {
        MeshLayout {
            xs: axis_vertices(nx, step, periodic),
            ys: axis_vertices(ny, step, periodic),
            step,
            up,
            vertical_scale: 1.0,
            uv: TileUv::Global,
            placement: Placement::Global,
            periodic,
            offset: 0.0,
        }
    }

    #[test]
    fn periodic_axes_end_at_sample_n_and_others_at_n_minus_one() {
        assert_eq!(axis_vertices(8, 1, true), (0..=8).collect::<Vec<_>>());
        assert_eq!(axis_vertices(8, 2, true), [0, 2, 4, 6, 8]);
        assert_eq!(
            axis_vertices(8, 3, true),
            [0, 3, 6, 8],
            "narrower last cell"
        );
        assert_eq!(axis_vertices(8, 2, false), [0, 2, 4, 6, 7]);
        assert_eq!(axis_vertices(2, 1, false), [0, 1]);
        assert_eq!(axis_vertices(8, 100, true), [0, 8]);
    }

    #[test]
    fn tiles_share_their_edge_vertices_and_cover_the_lattice() {
        let t = tiles(
            11,
            5,
            Tiles {
                columns: 3,
                rows: 2,
            },
        )
        .unwrap();
        assert_eq!(t.len(), 6);
        for row in t.chunks(3) {
            assert_eq!(row[0].vx.0, 0);
            assert_eq!(row[2].vx.1, 10);
            for pair in row.windows(2) {
                assert_eq!(pair[0].vx.1, pair[1].vx.0, "shared column");
            }
        }
        assert_eq!((t[0].vy, t[3].vy), ((0, 2), (2, 4)));
        let e = tiles(
            3,
            3,
            Tiles {
                columns: 3,
                rows: 1,
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("2 cells along x"), "{e}");
    }

    #[test]
    fn a_flat_field_has_unit_normals_pointing_up_in_both_frames() {
        let g = Grid::new(GridSpec::new(6, 4, 12.0, 8.0), vec![0.7; 24]);
        for up in [UpAxis::Y, UpAxis::Z] {
            let l = layout(6, 4, 1, false, up);
            let m = Mesh {
                layout: &l,
                grid: &g,
                field_slopes: None,
            };
            let want = match up {
                UpAxis::Y => [0.0, 1.0, 0.0],
                UpAxis::Z => [0.0, 0.0, 1.0],
            };
            let s = m.tile_slopes(&Tile::whole(6, 4));
            for vj in 0..4 {
                for vi in 0..6 {
                    let n = m.normal(&s, vi, vj);
                    assert_eq!(n, want, "{up:?} ({vi},{vj})");
                    assert!(n.iter().all(|c| c.to_bits() != (-0.0f32).to_bits()));
                }
            }
        }
    }

    #[test]
    fn central_slopes_of_a_plane_and_of_a_periodic_sine_match_their_derivatives() {
        // A plane h = 0.5 x − 0.25 y (not periodic): exact everywhere, edges included.
        let spec = GridSpec::new(8, 6, 16.0, 6.0);
        let plane: Vec<f32> = (0..48)
            .map(|k| 0.5 * spec.x_m(k % 8) as f32 - 0.25 * spec.y_m(k / 8) as f32)
            .collect();
        let s = slopes_central(&Grid::new(spec, plane), false);
        /// f32 heights of up to 7 m differenced over 2–4 m.
        const PLANE_TOL: f32 = 1e-6;
        assert!(
            s.dhdx.iter().all(|&v| (v - 0.5).abs() < PLANE_TOL),
            "{:?}",
            s.dhdx
        );
        assert!(
            s.dhdy.iter().all(|&v| (v + 0.25).abs() < PLANE_TOL),
            "{:?}",
            s.dhdy
        );
        // One period of sin(2πx/L): central differences give cos·sin(kd)/d, with the wrap.
        let (n, l) = (32usize, 64.0f64);
        let k = 2.0 * std::f64::consts::PI / l;
        let spec = GridSpec::new(n, 2, l, 2.0);
        let h: Vec<f32> = (0..2 * n)
            .map(|i| (k * spec.x_m(i % n)).sin() as f32)
            .collect();
        let s = slopes_central(&Grid::new(spec, h), true);
        let d = spec.dx_m();
        /// f32 heights differenced over 2d = 4 m: a few 1e-7 relative.
        const TOL: f64 = 1e-6;
        for i in 0..n {
            let want = (k * spec.x_m(i)).cos() * (k * d).sin() / d;
            assert!(
                (s.dhdx[i] as f64 - want).abs() < TOL,
                "i={i}: {} vs {want}",
                s.dhdx[i]
            );
        }
    }

    #[test]
    fn tile_slopes_are_the_field_slopes_at_the_tile_vertices_bit_for_bit() {
        let spec = GridSpec::new(12, 9, 30.0, 18.0);
        let g = Grid::new(
            spec,
            (0..12 * 9)
                .map(|k| ((k * 7919) % 101) as f32 * 0.01 - 0.5)
                .collect(),
        );
        for periodic in [true, false] {
            let field = slopes_central(&g, periodic);
            let mut l = layout(12, 9, 2, periodic, UpAxis::Y);
            l.vertical_scale = 1.5;
            let (nx, ny) = (l.xs.len(), l.ys.len());
            let per_tile = Mesh {
                layout: &l,
                grid: &g,
                field_slopes: None,
            };
            let given = Mesh {
                field_slopes: Some(&field),
                ..per_tile
            };
            let t = Tiles {
                columns: 2,
                rows: 2,
            };
            for tile in tiles(nx, ny, t).unwrap() {
                let (a, b) = (per_tile.tile_slopes(&tile), given.tile_slopes(&tile));
                for vj in tile.vy.0..=tile.vy.1 {
                    for vi in tile.vx.0..=tile.vx.1 {
                        let (p, q) = (per_tile.normal(&a, vi, vj), given.normal(&b, vi, vj));
                        assert!(
                            p.iter().zip(&q).all(|(x, y)| x.to_bits() == y.to_bits()),
                            "periodic {periodic}, vertex ({vi},{vj}): {p:?} vs {q:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn normals_tilt_against_the_slope_and_scale_with_the_heights() {
        /// One f32 rounding of 1/√2.
        const F32_TOL: f32 = 1e-7;
        let n = normal_from_slope(1.0, 0.0, 1.0, UpAxis::Z);
        let r = std::f32::consts::FRAC_1_SQRT_2;
        assert!((n[0] + r).abs() < F32_TOL && n[1] == 0.0 && (n[2] - r).abs() < F32_TOL);
        // Y-up: the field's +y is −Z, so a slope up along y tilts the normal toward +Z.
        let n = normal_from_slope(0.0, 2.0, 0.5, UpAxis::Y);
        assert!((n[2] - r).abs() < F32_TOL && (n[1] - r).abs() < F32_TOL && n[0] == 0.0);
        let many = normals_from_slopes(&[1.0, 0.0], &[0.0, 2.0], 0.5, UpAxis::Y);
        assert_eq!(many[1], n);
    }

    #[test]
    fn y_up_triangles_are_counter_clockwise_from_above_and_positions_wrap() {
        let g = Grid::new(
            GridSpec::new(4, 4, 8.0, 8.0),
            (0..16).map(|v| v as f32).collect(),
        );
        let l = layout(4, 4, 1, true, UpAxis::Y);
        let m = Mesh {
            layout: &l,
            grid: &g,
            field_slopes: None,
        };
        let t = Tile::whole(5, 5);
        let p = |i, j| m.position(i, j, &t);
        let (a, b, c) = (p(0, 0), p(1, 0), p(1, 1));
        let (u, v) = (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        let cross_y = u[2] * v[0] - u[0] * v[2];
        assert!(cross_y > 0.0, "(v00, v10, v11) faces +Y: {cross_y}");
        assert_eq!(
            p(4, 0),
            [8.0, 0.0, 0.0],
            "vertex n is x = L with sample 0's height"
        );
        assert_eq!(p(0, 4)[2], -8.0);
        assert_eq!(p(3, 2), [6.0, 11.0, -4.0]);
        assert_eq!(m.uv(4, 2, &t), (1.0, 0.5));
    }
}
