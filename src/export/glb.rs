//! Binary glTF 2.0 (`.glb`): the triangle grid of [`super::mesh`] as one mesh of one
//! node — POSITION (f32 × 3, meters, +Y up), NORMAL (unit f32 × 3), TEXCOORD_0 (f32 × 2,
//! v = y/Ly from the image's top-left) and u32 indices of counter-clockwise triangles.
//!
//! The JSON is built with `gltf-json`; the container (12-byte header, a JSON chunk padded
//! with spaces, a BIN chunk) is written here, streaming the vertex data in batches of
//! rows, so a mesh never sits in memory whole. The BIN chunk holds, in order, the positions, the
//! normals, the texture coordinates and the indices, each a multiple of 4 bytes.

use std::collections::BTreeMap;
use std::io::{self, Write};

use gltf_json as json;
use json::validation::Checked::Valid;
use json::validation::USize64;
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

/// The JSON document of a mesh of `vertices` and `triangles` whose positions span
/// `min`..`max`, and the byte length of its BIN chunk.
fn document(
    name: &str,
    vertices: usize,
    triangles: usize,
    min: [f32; 3],
    max: [f32; 3],
) -> (json::Root, usize) {
    let sections = [vertices * 12, vertices * 12, vertices * 8, triangles * 12];
    let bin_len: usize = sections.iter().sum();
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some(format!("seasynth {}", env!("CARGO_PKG_VERSION"))),
            ..Default::default()
        },
        ..Default::default()
    };
    let buffer = root.push(json::Buffer {
        byte_length: USize64::from(bin_len),
        extensions: Default::default(),
        extras: Default::default(),
        name: None,
        uri: None,
    });
    let mut offset = 0;
    let mut views = Vec::new();
    for (k, &len) in sections.iter().enumerate() {
        let target = if k == 3 {
            json::buffer::Target::ElementArrayBuffer
        } else {
            json::buffer::Target::ArrayBuffer
        };
        views.push(root.push(json::buffer::View {
            buffer,
            byte_length: USize64::from(len),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            extensions: Default::default(),
            extras: Default::default(),
            name: None,
            target: Some(Valid(target)),
        }));
        offset += len;
    }
    let mut accessor =
        |view, count: usize, kind, component, bounds: Option<([f32; 3], [f32; 3])>| {
            root.push(json::Accessor {
                buffer_view: Some(view),
                byte_offset: None,
                count: USize64::from(count),
                component_type: Valid(json::accessor::GenericComponentType(component)),
                extensions: Default::default(),
                extras: Default::default(),
                type_: Valid(kind),
                min: bounds.map(|b| json::Value::from(Vec::from(b.0))),
                max: bounds.map(|b| json::Value::from(Vec::from(b.1))),
                name: None,
                normalized: false,
                sparse: None,
            })
        };
    use json::accessor::{ComponentType, Type};
    let positions = accessor(
        views[0],
        vertices,
        Type::Vec3,
        ComponentType::F32,
        Some((min, max)),
    );
    let normals = accessor(views[1], vertices, Type::Vec3, ComponentType::F32, None);
    let uvs = accessor(views[2], vertices, Type::Vec2, ComponentType::F32, None);
    let indices = accessor(
        views[3],
        triangles * 3,
        Type::Scalar,
        ComponentType::U32,
        None,
    );
    let mut attributes = BTreeMap::new();
    attributes.insert(Valid(json::mesh::Semantic::Positions), positions);
    attributes.insert(Valid(json::mesh::Semantic::Normals), normals);
    attributes.insert(Valid(json::mesh::Semantic::TexCoords(0)), uvs);
    let mesh = root.push(json::Mesh {
        extensions: Default::default(),
        extras: Default::default(),
        name: Some(name.to_string()),
        primitives: vec![json::mesh::Primitive {
            attributes,
            extensions: Default::default(),
            extras: Default::default(),
            indices: Some(indices),
            material: None,
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        }],
        weights: None,
    });
    let node = root.push(json::Node {
        mesh: Some(mesh),
        name: Some(name.to_string()),
        ..Default::default()
    });
    let scene = root.push(json::Scene {
        extensions: Default::default(),
        extras: Default::default(),
        name: None,
        nodes: vec![node],
    });
    root.scene = Some(scene);
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
    let mut text = root.to_vec().map_err(io::Error::other)?;
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
        let offsets: Vec<u64> = root
            .buffer_views
            .iter()
            .map(|v| v.byte_offset.unwrap().0)
            .collect();
        assert_eq!(offsets, [0, 72, 144, 192]);
        assert_eq!(root.accessors[3].count.0, 12, "three indices per triangle");
        let text = String::from_utf8(root.to_vec().unwrap()).unwrap();
        assert!(
            text.contains("\"POSITION\"") && text.contains("\"TEXCOORD_0\""),
            "{text}"
        );
    }
}
