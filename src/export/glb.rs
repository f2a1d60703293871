//! Binary glTF 2.0 (`.glb`): the triangle grid of [`super::mesh`] as one mesh of one
//! node — POSITION (f32 × 3, meters, +Y up), NORMAL (unit f32 × 3), TEXCOORD_0 (f32 × 2,
//! v = y/Ly from the image's top-left) and u32 indices of counter-clockwise triangles.
//!
//! The JSON is serialized from the few glTF objects a mesh needs; the container (12-byte header, a JSON chunk padded
//! with spaces, a BIN chunk) is written here, streaming the vertex data in batches of
//! rows, so a mesh never sits in memory whole. The BIN chunk holds, in order, the positions, the
//! normals, the texture coordinates and the indices, each a multiple of 4 bytes.

use std::io::{self, Write};

use rayon::prelude::*;

use super::mesh::{Mesh, MeshLayout, Tile};
use super::par_rows;
use super::sidecar::Sidecar;
use super::{Describe, Exporter, FieldOut, Format, WriteSeek};

/// The binary glTF writer: a mesh layout (+Y up) and its tiles, one file each.
pub struct Glb {
    pub layout: MeshLayout,
    pub tiles: Vec<Tile>,
}

impl Exporter for Glb {
    fn format(&self) -> Format {
        Format::Glb
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
        let mesh = Mesh {
            layout: &self.layout,
            grid: field.grid,
            field_slopes: field.slopes,
        };
        write_tile(out, &mesh, &self.tiles[part], name)
    }

    fn describe(&self, doc: &mut Sidecar, cx: &Describe) {
        doc.mesh = Some(self.layout.info(cx.exact_slopes));
    }

    fn mesh_layout(&self) -> Option<&MeshLayout> {
        Some(&self.layout)
    }
}

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// The glTF objects a mesh of one node needs, serialized in the specification's
/// camelCase names and in the order the fields are declared.
mod gltf {
    use serde::Serialize;

    /// `ARRAY_BUFFER` and `ELEMENT_ARRAY_BUFFER`, the targets of vertex and index views.
    pub const ARRAY_BUFFER: u32 = 34962;
    pub const ELEMENT_ARRAY_BUFFER: u32 = 34963;
    /// `FLOAT` and `UNSIGNED_INT` component types.
    pub const F32: u32 = 5126;
    pub const U32: u32 = 5125;

    #[derive(Serialize)]
    pub struct Root {
        pub accessors: Vec<Accessor>,
        pub asset: Asset,
        pub buffers: Vec<Buffer>,
        #[serde(rename = "bufferViews")]
        pub buffer_views: Vec<View>,
        pub scene: u32,
        pub meshes: Vec<Mesh>,
        pub nodes: Vec<Node>,
        pub scenes: Vec<Scene>,
    }

    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    pub struct Accessor {
        pub buffer_view: usize,
        pub count: usize,
        pub component_type: u32,
        #[serde(rename = "type")]
        pub kind: &'static str,
        /// The f32 bounds widened to f64, so they print as the exact binary values.
        #[serde(skip_serializing_if = "Option::is_none")]
        pub min: Option<[f64; 3]>,
        #[serde(skip_serializing_if = "Option::is_none")]
        pub max: Option<[f64; 3]>,
    }

    #[derive(Serialize)]
    pub struct Asset {
        pub generator: String,
        pub version: &'static str,
    }

    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    pub struct Buffer {
        pub byte_length: usize,
    }

    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    pub struct View {
        pub buffer: u32,
        pub byte_length: usize,
        pub byte_offset: usize,
        pub target: u32,
    }

    #[derive(Serialize)]
    pub struct Mesh {
        pub name: String,
        pub primitives: [Primitive; 1],
    }

    #[derive(Serialize)]
    pub struct Primitive {
        pub attributes: Attributes,
        pub indices: usize,
    }

    #[derive(Serialize)]
    pub struct Attributes {
        #[serde(rename = "POSITION")]
        pub position: usize,
        #[serde(rename = "NORMAL")]
        pub normal: usize,
        #[serde(rename = "TEXCOORD_0")]
        pub texcoord_0: usize,
    }

    #[derive(Serialize)]
    pub struct Node {
        pub mesh: u32,
        pub name: String,
    }

    #[derive(Serialize)]
    pub struct Scene {
        pub nodes: [u32; 1],
    }
}

/// The JSON document of a mesh of `vertices` and `triangles` whose positions span
/// `min`..`max`, and the byte length of its BIN chunk.
fn document(
    name: &str,
    vertices: usize,
    triangles: usize,
    min: [f32; 3],
    max: [f32; 3],
) -> (gltf::Root, usize) {
    let sections = [vertices * 12, vertices * 12, vertices * 8, triangles * 12];
    let bin_len: usize = sections.iter().sum();
    let mut offset = 0;
    let buffer_views = sections
        .iter()
        .enumerate()
        .map(|(k, &len)| {
            let view = gltf::View {
                buffer: 0,
                byte_length: len,
                byte_offset: offset,
                target: match k {
                    3 => gltf::ELEMENT_ARRAY_BUFFER,
                    _ => gltf::ARRAY_BUFFER,
                },
            };
            offset += len;
            view
        })
        .collect();
    let accessor =
        |view, count, kind, component_type, bounds: Option<([f32; 3], [f32; 3])>| gltf::Accessor {
            buffer_view: view,
            count,
            component_type,
            kind,
            min: bounds.map(|b| b.0.map(f64::from)),
            max: bounds.map(|b| b.1.map(f64::from)),
        };
    let root = gltf::Root {
        accessors: vec![
            accessor(0, vertices, "VEC3", gltf::F32, Some((min, max))),
            accessor(1, vertices, "VEC3", gltf::F32, None),
            accessor(2, vertices, "VEC2", gltf::F32, None),
            accessor(3, triangles * 3, "SCALAR", gltf::U32, None),
        ],
        asset: gltf::Asset {
            generator: format!("seasynth {}", env!("CARGO_PKG_VERSION")),
            version: "2.0",
        },
        buffers: vec![gltf::Buffer {
            byte_length: bin_len,
        }],
        buffer_views,
        scene: 0,
        meshes: vec![gltf::Mesh {
            name: name.to_string(),
            primitives: [gltf::Primitive {
                attributes: gltf::Attributes {
                    position: 0,
                    normal: 1,
                    texcoord_0: 2,
                },
                indices: 3,
            }],
        }],
        nodes: vec![gltf::Node {
            mesh: 0,
            name: name.to_string(),
        }],
        scenes: vec![gltf::Scene { nodes: [0] }],
    };
    (root, bin_len)
}

/// Writes `tile` of `mesh` as a binary glTF file whose mesh and node are named `name`.
/// Fails (without writing) when the file would pass the format's 4 GiB limit.
pub fn write_tile<W: Write + ?Sized>(
    w: &mut W,
    mesh: &Mesh,
    tile: &Tile,
    name: &str,
) -> io::Result<()> {
    let (nw, nh) = tile.size();
    let (x0, y0) = (tile.vx.0, tile.vy.0);
    let cols = || x0..x0 + nw;
    // POSITION needs its bounds, before any data.
    let (min, max) = (y0..y0 + nh)
        .into_par_iter()
        .map(|vj| {
            let mut lo = [f32::INFINITY; 3];
            let mut hi = [f32::NEG_INFINITY; 3];
            for vi in cols() {
                let p = mesh.position(vi, vj, tile);
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            (lo, hi)
        })
        .reduce(
            || ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
            |(a, b), (c, d)| {
                (
                    std::array::from_fn(|k| a[k].min(c[k])),
                    std::array::from_fn(|k| b[k].max(d[k])),
                )
            },
        );
    let (root, bin_len) = document(name, nw * nh, tile.triangle_count(), min, max);
    let mut text = serde_json::to_vec(&root).map_err(io::Error::other)?;
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    let total = 12 + 8 + text.len() + 8 + bin_len;
    let total32 = u32::try_from(total).map_err(|_| {
        io::Error::other(format!(
            "a .glb holds at most 4 GiB and this mesh needs {total} bytes: \
             use --mesh-step or --tiles"
        ))
    })?;
    w.write_all(GLB_MAGIC)?;
    w.write_all(&2u32.to_le_bytes())?;
    w.write_all(&total32.to_le_bytes())?;
    w.write_all(&(text.len() as u32).to_le_bytes())?;
    w.write_all(&CHUNK_JSON.to_le_bytes())?;
    w.write_all(&text)?;
    w.write_all(&(bin_len as u32).to_le_bytes())?;
    w.write_all(&CHUNK_BIN.to_le_bytes())?;

    let put = |out: &mut Vec<u8>, v: &[f32]| {
        for c in v {
            out.extend_from_slice(&c.to_le_bytes());
        }
    };
    par_rows(w, nh, nw * 12, |r, out| {
        for vi in cols() {
            put(out, &mesh.position(vi, y0 + r, tile));
        }
    })?;
    let slopes = mesh.tile_slopes(tile);
    par_rows(w, nh, nw * 12, |r, out| {
        for vi in cols() {
            put(out, &mesh.normal(&slopes, vi, y0 + r));
        }
    })?;
    par_rows(w, nh, nw * 8, |r, out| {
        for vi in cols() {
            let (u, t) = mesh.uv(vi, y0 + r, tile);
            put(out, &[u as f32, t as f32]);
        }
    })?;
    par_rows(w, nh - 1, (nw - 1) * 24, |r, out| {
        for c in 0..nw - 1 {
            let a = (r * nw + c) as u32;
            let (b, cc, d) = (a + 1, a + nw as u32 + 1, a + nw as u32);
            for k in [a, b, cc, a, cc, d] {
                out.extend_from_slice(&k.to_le_bytes());
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_document_lays_out_four_aligned_sections_and_serializes() {
        let (root, bin) = document("t", 6, 4, [0.0; 3], [1.0; 3]);
        assert_eq!(bin, 6 * 12 + 6 * 12 + 6 * 8 + 4 * 12);
        let offsets: Vec<usize> = root.buffer_views.iter().map(|v| v.byte_offset).collect();
        assert_eq!(offsets, [0, 72, 144, 192]);
        assert_eq!(root.accessors[3].count, 12, "three indices per triangle");
        let text = serde_json::to_string(&root).unwrap();
        assert!(
            text.contains("\"POSITION\"") && text.contains("\"TEXCOORD_0\""),
            "{text}"
        );
    }
}
