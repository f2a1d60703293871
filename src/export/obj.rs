//! Wavefront OBJ: the triangle grid of [`super::mesh`] as text — `v` positions (meters),
//! `vt` texture coordinates, `vn` unit normals, one of each per vertex in the same order,
//! then `f a/a/a b/b/b c/c/c` triangles (counter-clockwise seen from above). A comment
//! header records the frame, the winding and the parameters.
//!
//! Numbers are the shortest decimal that reads back as the same f32 (zmij), integers by
//! itoa, formatted into byte buffers batch by batch on all cores and written in order:
//! several times faster than `write!`. Shared tile vertices are the same text in both
//! tiles, since both compute them from the same samples.

use std::io::{self, Write};
use std::path::Path;

use super::mesh::{Mesh, MeshLayout, Placement, Tile};
use super::options::TileUv;
use super::par_rows as write_rows;
use super::sidecar::Sidecar;
use super::{Describe, Exporter, FieldOut, Format, WriteSeek};
use crate::grid::Grid;

/// The OBJ writer: a mesh layout, its tiles (one file each) and the sidecar the header
/// names.
pub struct Obj {
    layout: MeshLayout,
    tiles: Vec<Tile>,
    /// The file name of the output's sidecar.
    sidecar: String,
}

impl Obj {
    /// The writer of the output `path` laid out as `layout` in `tiles`.
    pub fn new(layout: MeshLayout, tiles: Vec<Tile>, path: &Path) -> Self {
        let sidecar = super::sidecar::path_for(path)
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        Self {
            layout,
            tiles,
            sidecar,
        }
    }
}

impl Exporter for Obj {
    fn format(&self) -> Format {
        Format::Obj
    }

    fn tiles(&self) -> Option<&[Tile]> {
        Some(&self.tiles)
    }

    fn write(
        &self,
        field: &FieldOut,
        part: usize,
        name: &str,
        out: &mut dyn WriteSeek,
    ) -> io::Result<()> {
        let (layout, tile) = (&self.layout, &self.tiles[part]);
        let mesh = Mesh {
            layout,
            grid: field.grid,
            field_slopes: field.slopes,
        };
        let exact = field.slopes.is_some();
        let mut header = mesh_header(layout, (field.grid, exact), field.about, &self.sidecar);
        header.push(tile_line(tile, self.tiles.len(), layout.placement));
        write_tile(out, &mesh, tile, name, &header)
    }

    fn describe(&self, doc: &mut Sidecar, cx: &Describe) {
        doc.mesh = Some(self.layout.info(cx.exact_slopes));
    }

    fn mesh_layout(&self) -> Option<&MeshLayout> {
        Some(&self.layout)
    }
}

/// The comment lines of a mesh file: the frame, the winding, the field.
fn mesh_header(
    layout: &MeshLayout,
    (grid, exact_slopes): (&Grid, bool),
    about: &str,
    sidecar: &str,
) -> Vec<String> {
    let info = layout.info(exact_slopes);
    let s = &grid.spec;
    let mut lines = vec![format!(
        "seasynth {} height-field mesh, meters",
        env!("CARGO_PKG_VERSION")
    )];
    lines.extend(about.lines().map(str::to_string));
    lines.extend([
        format!(
            "grid {}x{} samples over {} x {} m, periodic: {}; parameters in {}",
            s.nx,
            s.ny,
            s.extent_x_m,
            s.extent_y_m,
            if layout.periodic { "yes" } else { "no" },
            sidecar
        ),
        format!(
            "{} with vertical_scale {}",
            info.coordinates, layout.vertical_scale
        ),
        format!("triangles {}; normals: {}", info.winding, info.normals),
        match layout.uv {
            TileUv::Global => "uv: u = x / Lx, v = 1 - y / Ly (0..1 over the field)",
            TileUv::Tile => "uv: 0..1 across each tile, v = 1 at the tile's y = 0 edge",
        }
        .to_string(),
        format!(
            "mesh step {}: {}x{} vertices (samples 0, {}, {}, ... and the far edge)",
            layout.step,
            layout.xs.len(),
            layout.ys.len(),
            layout.step,
            2 * layout.step
        ),
    ]);
    lines
}

/// The header line naming a tile and its vertex counts.
fn tile_line(tile: &Tile, count: usize, placement: Placement) -> String {
    let (w, h) = tile.size();
    if count == 1 {
        return format!("{} vertices, {} triangles", w * h, tile.triangle_count());
    }
    format!(
        "tile x{} y{} of {count}: mesh vertices {}..={} x {}..={}; {} vertices, {} triangles; positions {}",
        tile.column,
        tile.row,
        tile.vx.0,
        tile.vx.1,
        tile.vy.0,
        tile.vy.1,
        w * h,
        tile.triangle_count(),
        match placement {
            Placement::Global => "in field coordinates",
            Placement::Tile => "relative to the tile's corner",
        }
    )
}

/// Appends `tag` and the three numbers of `v` as one line.
#[inline]
fn line3(out: &mut Vec<u8>, f: &mut zmij::Buffer, tag: &[u8], v: [f32; 3]) {
    out.extend_from_slice(tag);
    for (k, c) in v.into_iter().enumerate() {
        if k > 0 {
            out.push(b' ');
        }
        out.extend_from_slice(f.format(c).as_bytes());
    }
    out.push(b'\n');
}

/// Writes `tile` of `mesh` as an OBJ object named `name`, after the comment lines of
/// `header` (each line gets a leading `# `).
pub fn write_tile<W: Write + ?Sized>(
    w: &mut W,
    mesh: &Mesh,
    tile: &Tile,
    name: &str,
    header: &[String],
) -> io::Result<()> {
    for line in header {
        writeln!(w, "# {line}")?;
    }
    writeln!(w, "o {name}")?;
    let (nw, nh) = tile.size();
    let (x0, y0) = (tile.vx.0, tile.vy.0);
    // Generous line lengths, so row buffers never grow (a copy) while formatting.
    let digits = (nw * nh).to_string().len();
    let face_bytes = 2 * (9 * digits + 12);
    write_rows(w, nh, nw * 44, |r, out| {
        let mut f = zmij::Buffer::new();
        for vi in x0..x0 + nw {
            line3(out, &mut f, b"v ", mesh.position(vi, y0 + r, tile));
        }
    })?;
    write_rows(w, nh, nw * 28, |r, out| {
        let mut f = zmij::Buffer::new();
        for vi in x0..x0 + nw {
            let (u, t) = mesh.uv(vi, y0 + r, tile);
            out.extend_from_slice(b"vt ");
            out.extend_from_slice(f.format(u as f32).as_bytes());
            out.push(b' ');
            out.extend_from_slice(f.format((1.0 - t) as f32).as_bytes());
            out.push(b'\n');
        }
    })?;
    let slopes = mesh.tile_slopes(tile);
    write_rows(w, nh, nw * 44, |r, out| {
        let mut f = zmij::Buffer::new();
        for vi in x0..x0 + nw {
            line3(out, &mut f, b"vn ", mesh.normal(&slopes, vi, y0 + r));
        }
    })?;
    // Faces: 1-based indices, the same for v, vt and vn.
    write_rows(w, nh - 1, (nw - 1) * face_bytes, |r, out| {
        let mut num = itoa::Buffer::new();
        let mut corner = |out: &mut Vec<u8>, k: usize| {
            let s = num.format(k).as_bytes();
            out.push(b' ');
            out.extend_from_slice(s);
            out.push(b'/');
            out.extend_from_slice(s);
            out.push(b'/');
            out.extend_from_slice(s);
        };
        for c in 0..nw - 1 {
            let a = r * nw + c + 1;
            let (b, cc, d) = (a + 1, a + nw + 1, a + nw);
            for tri in [[a, b, cc], [a, cc, d]] {
                out.push(b'f');
                for k in tri {
                    corner(out, k);
                }
                out.push(b'\n');
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::mesh::{MeshLayout, Placement, axis_vertices};
    use crate::export::options::{TileUv, UpAxis};
    use crate::grid::{Grid, GridSpec};

    #[test]
    fn a_two_by_two_periodic_field_gives_nine_vertices_and_eight_triangles() {
        let g = Grid::new(GridSpec::new(2, 2, 2.0, 2.0), vec![0.0, 1.0, 2.0, 3.0]);
        let layout = MeshLayout {
            xs: axis_vertices(2, 1, true),
            ys: axis_vertices(2, 1, true),
            up: UpAxis::Y,
            vertical_scale: 1.0,
            step: 1,
            uv: TileUv::Global,
            placement: Placement::Global,
            periodic: true,
            offset: 0.0,
        };
        let mesh = Mesh {
            layout: &layout,
            grid: &g,
            field_slopes: None,
        };
        let mut out = Vec::new();
        write_tile(&mut out, &mesh, &Tile::whole(3, 3), "m", &["hello".into()]).unwrap();
        let text = String::from_utf8(out).unwrap();
        let count = |tag: &str| text.lines().filter(|l| l.starts_with(tag)).count();
        assert_eq!(
            (count("v "), count("vt "), count("vn "), count("f ")),
            (9, 9, 9, 8)
        );
        assert!(text.starts_with("# hello\no m\nv 0.0 0.0 0.0\nv 1.0 1.0 0.0\nv 2.0 0.0 0.0\n"));
        assert!(
            text.contains("\nvt 1.0 0.0\n"),
            "the far corner: u = 1, v = 0"
        );
        assert!(text.contains("\nf 1/1/1 2/2/2 5/5/5\nf 1/1/1 5/5/5 4/4/4\n"));
        assert!(text.ends_with("f 5/5/5 9/9/9 8/8/8\n"), "{text}");
    }
}
