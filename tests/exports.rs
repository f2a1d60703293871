//! Engine and tool exports, run as a program: OBJ meshes and tiles, glTF binary, raw
//! `.r16`/`.r32` with Unity and Unreal sizes, OpenEXR, GeoTIFF tags, and their flags.

mod common;

use std::collections::BTreeSet;
use std::path::Path;

use common::{json_file, names_in, num, read, run_ok, run_rejected};
use seasynth::export::options::ExportOptions;
use seasynth::export::raw::{UNITY_SIZES, UNREAL_SIZES};
use seasynth::export::{FieldOut, HeightMapping, Output, exr, tiff32};
use seasynth::grid::{Grid, GridSpec};
use serde_json::Value;

/// Largest deviation of a normal's length from 1 (f32 components of a unit f64 vector).
const UNIT_TOL: f32 = 1e-6;
/// Slack on "within half a 16-bit step" for the f64 arithmetic of decoding, meters.
const DECODE_SLACK_M: f64 = 1e-9;

fn generate(dir: &Path, args: &[&str]) {
    let mut all = vec!["generate", "--quiet"];
    all.extend_from_slice(args);
    run_ok(dir, &all);
}

/// An OBJ file as parsed: per-vertex data, the text of each `v` and `vn` line, and the
/// triangles as 0-based indices.
#[derive(Debug, Default)]
struct Obj {
    v: Vec<[f32; 3]>,
    vt: Vec<[f32; 2]>,
    vn: Vec<[f32; 3]>,
    faces: Vec<[usize; 3]>,
    v_text: Vec<String>,
    vn_text: Vec<String>,
    comments: Vec<String>,
}

fn floats<const N: usize>(rest: &str, line: &str) -> [f32; N] {
    let v: Vec<f32> = rest
        .split_whitespace()
        .map(|t| {
            t.parse()
                .unwrap_or_else(|_| panic!("bad number in `{line}`"))
        })
        .collect();
    v.try_into()
        .unwrap_or_else(|_| panic!("`{line}` needs {N} numbers"))
}

/// A small OBJ parser: `v`, `vt`, `vn`, `f a/a/a b/b/b c/c/c` (the same index for the
/// three, as seasynth writes), comments and `o`; anything else fails the test.
fn parse_obj(path: &Path) -> Obj {
    let text = String::from_utf8(read(path)).expect("UTF-8 OBJ");
    let mut o = Obj::default();
    for line in text.lines() {
        let (tag, rest) = line.split_once(' ').unwrap_or((line, ""));
        match tag {
            "#" => o.comments.push(rest.to_string()),
            "o" => {}
            "v" => {
                o.v.push(floats(rest, line));
                o.v_text.push(rest.to_string());
            }
            "vt" => o.vt.push(floats(rest, line)),
            "vn" => {
                o.vn.push(floats(rest, line));
                o.vn_text.push(rest.to_string());
            }
            "f" => {
                let idx: Vec<usize> = rest
                    .split_whitespace()
                    .map(|c| {
                        let parts: Vec<usize> = c.split('/').map(|p| p.parse().unwrap()).collect();
                        assert!(
                            parts.len() == 3 && parts[0] == parts[1] && parts[1] == parts[2],
                            "{}: corner `{c}` should be k/k/k",
                            path.display()
                        );
                        parts[0] - 1
                    })
                    .collect();
                o.faces.push(idx.try_into().expect("triangles"));
            }
            other => panic!("{}: unexpected line tag `{other}`", path.display()),
        }
    }
    assert_eq!(o.v.len(), o.vt.len(), "one vt per v");
    assert_eq!(o.v.len(), o.vn.len(), "one vn per v");
    for f in &o.faces {
        assert!(f.iter().all(|&k| k < o.v.len()), "face {f:?} out of range");
    }
    o
}

fn tiff(path: &Path) -> (usize, usize, Vec<f32>) {
    tiff32::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn cross(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> [f32; 3] {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

#[test]
fn obj_of_a_periodic_field_has_n_over_k_plus_one_squared_vertices_up_normals_and_the_tiff_heights()
{
    let dir = tempfile::tempdir().unwrap();
    let (n, m, k) = (64usize, 32usize, 2usize);
    generate(
        dir.path(),
        &[
            "--method",
            "fft",
            "--size",
            "64x32",
            "--extent",
            "128x64",
            "--seed",
            "3",
            "--mesh-step",
            "2",
            "-o",
            "m.obj",
            "-o",
            "m.tif",
        ],
    );
    let obj = parse_obj(&dir.path().join("m.obj"));
    let (vx, vy) = (n / k + 1, m / k + 1);
    assert_eq!(obj.v.len(), vx * vy, "(N/K+1)(M/K+1) vertices");
    assert_eq!(
        obj.faces.len(),
        2 * (n / k) * (m / k),
        "2(N/K)(M/K) triangles"
    );
    let (w, _, h) = tiff(&dir.path().join("m.tif"));
    for (idx, p) in obj.v.iter().enumerate() {
        let (vi, vj) = (idx % vx, idx / vx);
        // Y-up: X = x, Y = h, Z = −y; vertex N/K is x = L with sample 0's height.
        let (i, j) = ((vi * k) % n, (vj * k) % m);
        assert_eq!(p[0], (vi * k) as f32 * 2.0, "x of vertex ({vi},{vj})");
        assert_eq!(
            p[2],
            -((vj * k) as f32 * 2.0),
            "z = −y of vertex ({vi},{vj})"
        );
        assert_eq!(
            p[1].to_bits(),
            h[j * w + i].to_bits(),
            "height of vertex ({vi},{vj}) vs TIFF sample ({i},{j})"
        );
    }
    for (idx, nrm) in obj.vn.iter().enumerate() {
        let len = (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]).sqrt();
        assert!(
            (len - 1.0).abs() <= UNIT_TOL,
            "normal {idx} has length {len}"
        );
        assert!(nrm[1] > 0.0, "normal {idx} points down: {nrm:?}");
    }
    for f in &obj.faces {
        let c = cross(obj.v[f[0]], obj.v[f[1]], obj.v[f[2]]);
        assert!(c[1] > 0.0, "triangle {f:?} faces down: {c:?}");
    }
    assert!(
        obj.comments.iter().any(|c| c.contains("Z = -y"))
            && obj.comments.iter().any(|c| c.contains("counter-clockwise")),
        "the header states the frame and winding: {:?}",
        obj.comments
    );
    let params: Value = obj
        .comments
        .iter()
        .find_map(|c| c.strip_prefix("params "))
        .map(|j| serde_json::from_str(j).expect("the header's params are JSON"))
        .expect("the header records the parameters");
    assert_eq!(params["method"], "fft");
    assert_eq!(params["seed"], 3);
}

#[test]
fn obj_of_a_flat_field_has_unit_normals_pointing_straight_up() {
    let dir = tempfile::tempdir().unwrap();
    let g = Grid::zeros(GridSpec::new(6, 5, 12.0, 10.0));
    for (up, want) in [("y", [0.0, 1.0, 0.0]), ("z", [0.0, 0.0, 1.0])] {
        let path = dir.path().join(format!("flat-{up}.obj"));
        let args = seasynth::cli::ExportArgs {
            up: Some(up.into()),
            ..Default::default()
        };
        let options = ExportOptions::from_flags(args.flags()).unwrap();
        let out = Output::plan(&path, &options, &g.spec, true).unwrap();
        out.write(&FieldOut {
            grid: &g,
            mapping: &HeightMapping {
                min_m: 0.0,
                max_m: 0.0,
            },
            slopes: None,
            about: "flat",
        })
        .unwrap();
        let obj = parse_obj(&path);
        assert_eq!((obj.v.len(), obj.faces.len()), (7 * 6, 2 * 6 * 5));
        for (idx, nrm) in obj.vn.iter().enumerate() {
            assert_eq!(*nrm, want, "--up {up}: normal {idx}");
        }
        assert!(
            obj.vn_text.iter().all(|t| !t.contains('-')),
            "no negative zeros"
        );
    }
}

#[test]
fn obj_of_a_non_periodic_field_ends_at_its_last_sample() {
    // The default hybrid ramps α along y, which breaks the period.
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &["--size", "32", "--extent", "64", "-o", "h.obj"],
    );
    let obj = parse_obj(&dir.path().join("h.obj"));
    assert_eq!(obj.v.len(), 32 * 32);
    assert_eq!(obj.faces.len(), 2 * 31 * 31);
    assert_eq!(
        obj.v[31][0], 62.0,
        "the last vertex is the last sample, x = 31·2 m"
    );
    let doc = json_file(&dir.path().join("h.json"));
    assert_eq!(doc["mesh"]["periodic"], false, "{doc:#}");
    assert_eq!(doc["mesh"]["up"], "y");
}

/// The tiles of `stem` in `dir`, parsed, by (column, row).
fn read_tiles(dir: &Path, stem: &str, columns: usize, rows: usize) -> Vec<Vec<Obj>> {
    (0..rows)
        .map(|j| {
            (0..columns)
                .map(|i| parse_obj(&dir.join(format!("{stem}_x{i}_y{j}.obj"))))
                .collect()
        })
        .collect()
}

/// Vertex lines of column `c` (or row `r`) of a tile of `w` vertices per row.
fn column(text: &[String], w: usize, c: usize) -> Vec<&String> {
    text.iter().skip(c).step_by(w).collect()
}

fn row(text: &[String], w: usize, r: usize) -> Vec<&String> {
    text[r * w..(r + 1) * w].iter().collect()
}

#[test]
fn adjacent_tiles_share_edge_vertices_with_identical_positions_and_normals() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method", "fft", "--size", "40x24", "--extent", "80x48", "--seed", "8", "--tiles",
            "3x2", "-o", "t.obj",
        ],
    );
    generate(
        dir.path(),
        &[
            "--method",
            "fft",
            "--size",
            "40x24",
            "--extent",
            "80x48",
            "--seed",
            "8",
            "-o",
            "whole.obj",
        ],
    );
    let tiles = read_tiles(dir.path(), "t", 3, 2);
    // 40 cells split 13/13/14, 24 split 12/12: widths in vertices.
    let widths = [14usize, 14, 15];
    let heights = [13usize, 13];
    for (j, row_tiles) in tiles.iter().enumerate() {
        for (i, t) in row_tiles.iter().enumerate() {
            assert_eq!(t.v.len(), widths[i] * heights[j], "tile x{i} y{j} vertices");
            assert_eq!(
                t.faces.len(),
                2 * (widths[i] - 1) * (heights[j] - 1),
                "tile x{i} y{j} triangles"
            );
        }
    }
    for (j, row) in tiles.iter().enumerate().take(2) {
        for i in 0..2 {
            let (a, b) = (&row[i], &row[i + 1]);
            let (wa, wb) = (widths[i], widths[i + 1]);
            assert_eq!(
                column(&a.v_text, wa, wa - 1),
                column(&b.v_text, wb, 0),
                "positions on the edge between x{i} and x{} (row {j})",
                i + 1
            );
            assert_eq!(
                column(&a.vn_text, wa, wa - 1),
                column(&b.vn_text, wb, 0),
                "normals on the edge between x{i} and x{} (row {j})",
                i + 1
            );
        }
    }
    for i in 0..3 {
        let (a, b) = (&tiles[0][i], &tiles[1][i]);
        let w = widths[i];
        assert_eq!(row(&a.v_text, w, heights[0] - 1), row(&b.v_text, w, 0));
        assert_eq!(row(&a.vn_text, w, heights[0] - 1), row(&b.vn_text, w, 0));
    }
    // Together the tiles are the whole mesh: every vertex line of one is in the other.
    let whole = parse_obj(&dir.path().join("whole.obj"));
    let all: BTreeSet<(&String, &String)> = whole.v_text.iter().zip(&whole.vn_text).collect();
    let from_tiles: BTreeSet<(&String, &String)> = tiles
        .iter()
        .flatten()
        .flat_map(|t| t.v_text.iter().zip(&t.vn_text))
        .collect();
    assert_eq!(all.len(), 41 * 25);
    assert!(
        all == from_tiles,
        "the tiles' vertices are the whole mesh's"
    );

    let index = json_file(&dir.path().join("t.tiles.json"));
    let set = &index["sets"][0];
    assert_eq!(
        (set["columns"].as_u64(), set["rows"].as_u64()),
        (Some(3), Some(2))
    );
    let listed = set["tiles"].as_array().unwrap();
    assert_eq!(listed.len(), 6);
    assert_eq!(listed[4]["file"], "t_x1_y1.obj");
    assert_eq!(num(&listed[4], "/offset_m/0"), 26.0, "13 cells of 2 m");
    assert_eq!(num(&listed[4], "/offset_m/1"), 24.0);
    let doc = json_file(&dir.path().join("t.json"));
    assert_eq!(doc["tiles_index"], "t.tiles.json");
    assert_eq!(doc["files"].as_array().unwrap().len(), 6);
}

#[test]
fn periodic_tiles_are_equal_local_and_wrap_around_seamlessly() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method",
            "fft",
            "--size",
            "32",
            "--extent",
            "64",
            "--tiles",
            "2x2",
            "--periodic-tiles",
            "--tile-uv",
            "tile",
            "-o",
            "p.obj",
        ],
    );
    let tiles = read_tiles(dir.path(), "p", 2, 2);
    let w = 17;
    for t in tiles.iter().flatten() {
        assert_eq!(t.v.len(), w * w, "equal tiles");
        assert_eq!(t.v[0][0], 0.0, "positions relative to the tile's corner");
        assert_eq!(t.v[0][2], 0.0);
        assert_eq!(t.v[w * w - 1][0], 32.0);
        assert_eq!(t.vt[0], [0.0, 1.0], "per-tile uv: (0, 1) at the corner");
        assert_eq!(t.vt[w * w - 1], [1.0, 0.0]);
    }
    // Heights (the Y field of the text) and normals across the wrap: x1's +x edge is x0's −x edge.
    let height = |s: &&String| s.split(' ').nth(1).unwrap().to_string();
    for (j, row) in tiles.iter().enumerate().take(2) {
        let (last, first) = (&row[1], &row[0]);
        let a: Vec<String> = column(&last.v_text, w, w - 1).iter().map(height).collect();
        let b: Vec<String> = column(&first.v_text, w, 0).iter().map(height).collect();
        assert_eq!(a, b, "heights across the x wrap, row {j}");
        assert_eq!(
            column(&last.vn_text, w, w - 1),
            column(&first.vn_text, w, 0)
        );
    }
    let index = json_file(&dir.path().join("p.tiles.json"));
    let set = &index["sets"][0];
    assert_eq!(set["placement"], "tile");
    assert_eq!(
        (num(set, "/period_m/0"), num(set, "/period_m/1")),
        (64.0, 64.0)
    );
    assert_eq!(
        set["tiles"][1]["neighbours"]["plus_x"], "p_x0_y0.obj",
        "wraps around"
    );
    assert_eq!(
        num(&set["tiles"][3], "/engine_offset/2"),
        -32.0,
        "Y-up: Z = −y"
    );
}

#[test]
fn glb_rereads_with_the_same_vertices_normals_uvs_and_triangles_as_the_obj() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method", "fft", "--size", "24x16", "--extent", "48x32", "--seed", "5", "--tiles",
            "2x1", "-o", "g.glb", "-o", "g.obj",
        ],
    );
    for i in 0..2 {
        let bytes = read(&dir.path().join(format!("g_x{i}_y0.glb")));
        let gltf = gltf::Gltf::from_slice(&bytes).expect("a valid glb");
        let blob = gltf.blob.clone().expect("a BIN chunk");
        let obj = parse_obj(&dir.path().join(format!("g_x{i}_y0.obj")));
        let mesh = gltf.meshes().next().expect("one mesh");
        let prim = mesh.primitives().next().expect("one primitive");
        assert_eq!(prim.mode(), gltf::mesh::Mode::Triangles);
        let reader = prim.reader(|_| Some(&blob));
        let pos: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        let nrm: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
        let uv: Vec<[f32; 2]> = reader.read_tex_coords(0).unwrap().into_f32().collect();
        let idx: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        assert!(pos == obj.v, "tile {i}: positions differ from the OBJ's");
        assert!(nrm == obj.vn, "tile {i}: normals differ from the OBJ's");
        let faces: Vec<usize> = obj.faces.iter().flatten().copied().collect();
        assert!(
            idx.iter().map(|&k| k as usize).eq(faces),
            "tile {i}: triangles differ from the OBJ's"
        );
        // glTF's v runs down from the image top, OBJ's up: v_obj = 1 − v_gltf.
        /// One f32 rounding of each side.
        const UV_TOL: f32 = 1.2e-7;
        for (k, (g, o)) in uv.iter().zip(&obj.vt).enumerate() {
            assert_eq!(g[0], o[0], "u of vertex {k}");
            assert!(
                (g[1] - (1.0 - o[1])).abs() <= UV_TOL,
                "v of vertex {k}: {g:?} vs {o:?}"
            );
        }
        // POSITION bounds are required and must hold the data.
        let acc = prim.get(&gltf::Semantic::Positions).unwrap();
        let (min, max) = (acc.min().unwrap(), acc.max().unwrap());
        for c in 0..3 {
            let lo = pos.iter().map(|p| p[c]).fold(f32::INFINITY, f32::min);
            let hi = pos.iter().map(|p| p[c]).fold(f32::NEG_INFINITY, f32::max);
            assert_eq!(
                (
                    min[c].as_f64().unwrap() as f32,
                    max[c].as_f64().unwrap() as f32
                ),
                (lo, hi)
            );
        }
    }
}

#[test]
fn r16_has_two_bytes_per_sample_and_the_sidecar_mapping_decodes_it() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--size", "48x40", "--extent", "96x80", "--seed", "2", "-o", "h.r16", "-o", "h.tif",
        ],
    );
    generate(
        dir.path(),
        &[
            "--size",
            "48x40",
            "--extent",
            "96x80",
            "--seed",
            "2",
            "-o",
            "b.r16",
            "--byte-order",
            "big",
        ],
    );
    let bytes = read(&dir.path().join("h.r16"));
    assert_eq!(bytes.len(), 2 * 48 * 40, "2·W·H bytes");
    let big = read(&dir.path().join("b.r16"));
    let doc = json_file(&dir.path().join("h.json"));
    let (min, step) = (num(&doc, "/mapping/min_m"), num(&doc, "/mapping/step_m"));
    assert!(step > 0.0);
    assert_eq!(doc["raw"]["byte_order"], "little");
    let (_, _, heights) = tiff(&dir.path().join("h.tif"));
    for (k, (pair, &h)) in bytes.chunks_exact(2).zip(&heights).enumerate() {
        let v = u16::from_le_bytes([pair[0], pair[1]]);
        assert_eq!(
            big[2 * k..2 * k + 2],
            v.to_be_bytes(),
            "big-endian sample {k}"
        );
        let err = (min + v as f64 * step - h as f64).abs();
        assert!(
            err <= step / 2.0 + DECODE_SLACK_M,
            "sample {k}: {v} decodes {err} m off"
        );
    }
    let values: Vec<u16> = bytes
        .chunks_exact(2)
        .map(|p| u16::from_le_bytes([p[0], p[1]]))
        .collect();
    assert!(
        values.contains(&0) && values.contains(&65535),
        "full range used"
    );
    let r32 = |name: &str| {
        run_ok(
            dir.path(),
            &[
                "generate", "--quiet", "--size", "48x40", "--extent", "96x80", "--seed", "2", "-o",
                name,
            ],
        );
        read(&dir.path().join(name))
    };
    let floats = r32("h.r32");
    assert_eq!(floats.len(), 4 * 48 * 40);
    assert!(
        floats
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .zip(&heights)
            .all(|(a, b)| a.to_bits() == b.to_bits()),
        ".r32 holds the heights in meters exactly"
    );
}

fn decode_r16(bytes: &[u8]) -> Vec<u16> {
    bytes
        .chunks_exact(2)
        .map(|p| u16::from_le_bytes([p[0], p[1]]))
        .collect()
}

fn decode_r32(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect()
}

#[test]
fn unity_sizes_are_two_to_the_n_plus_one_and_copy_a_matching_periodic_field() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method", "fft", "--size", "64", "--extent", "128", "--engine", "unity", "-o",
            "u.r16", "-o", "u.r32", "-o", "u.tif",
        ],
    );
    let doc = json_file(&dir.path().join("u.json"));
    let s = num(&doc, "/raw/unity/resolution") as usize;
    assert_eq!(s, 65, "a 64-cell periodic field is a 65² Unity terrain");
    assert!(UNITY_SIZES.contains(&s));
    assert_eq!(read(&dir.path().join("u.r16")).len(), 2 * s * s);
    assert_eq!(num(&doc, "/raw/unity/terrain_size_m/0"), 128.0);
    let r32 = decode_r32(&read(&dir.path().join("u.r32")));
    let (w, _, h) = tiff(&dir.path().join("u.tif"));
    for r in 0..s {
        for c in 0..s {
            let want = h[(r % w) * w + c % w];
            assert_eq!(
                r32[r * s + c],
                want,
                "({c},{r}) is sample ({},{})",
                c % w,
                r % w
            );
        }
    }
    // A 200-sample field resamples to the nearest legal size.
    generate(
        dir.path(),
        &["--size", "200", "--engine", "unity", "-o", "v.r16"],
    );
    let doc = json_file(&dir.path().join("v.json"));
    let s = num(&doc, "/raw/unity/resolution") as usize;
    assert_eq!(s, 257);
    assert_eq!(read(&dir.path().join("v.r16")).len(), 2 * s * s);
}

#[test]
fn unreal_sizes_are_recommended_ones_and_the_recorded_z_scale_decodes_the_heights() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method", "fft", "--size", "512", "--engine", "unreal", "-o", "e.r16", "-o", "e.r32",
        ],
    );
    let doc = json_file(&dir.path().join("e.json"));
    let (sx, sy) = (
        num(&doc, "/raw/unreal/resolution/0") as usize,
        num(&doc, "/raw/unreal/resolution/1") as usize,
    );
    assert_eq!(
        (sx, sy),
        (505, 505),
        "512 cells → 505, the nearest recommended size"
    );
    assert!(UNREAL_SIZES.contains(&sx));
    let z = num(&doc, "/raw/unreal/z_scale");
    assert_eq!(num(&doc, "/raw/unreal/scale/2"), z);
    let xy_cm = num(&doc, "/raw/unreal/scale/0");
    assert!(
        (xy_cm - 51200.0 / 504.0).abs() < DECODE_SLACK_M,
        "X scale {xy_cm} cm"
    );
    let values = decode_r16(&read(&dir.path().join("e.r16")));
    let meters = decode_r32(&read(&dir.path().join("e.r32")));
    assert_eq!(values.len(), sx * sy);
    let unit = z / 12800.0;
    let mut extreme = 0u16;
    for (k, (&v, &h)) in values.iter().zip(&meters).enumerate() {
        let decoded = (v as f64 - 32768.0) * unit;
        assert!(
            (decoded - h as f64).abs() <= unit / 2.0 + DECODE_SLACK_M,
            "sample {k}: {v} decodes to {decoded} m, the .r32 has {h} m"
        );
        extreme = extreme.max(v.abs_diff(32768));
    }
    assert!(
        (0.8 * 32767.0..=0.9 * 32767.0 + 1.0).contains(&(extreme as f64)),
        "the Z scale uses 80–90 % of the half range: {extreme}"
    );
}

#[test]
fn unreal_world_partition_tiles_are_named_x_y_equal_and_share_edges() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method", "fft", "--size", "256", "--engine", "unreal", "--tiles", "2x2", "-o",
            "w.r16",
        ],
    );
    assert_eq!(
        names_in(dir.path()),
        [
            "w.json",
            "w.tiles.json",
            "w_x0_y0.r16",
            "w_x0_y1.r16",
            "w_x1_y0.r16",
            "w_x1_y1.r16"
        ]
    );
    let s = 127; // 128 cells per tile → 126
    let tile = |i: usize, j: usize| decode_r16(&read(&dir.path().join(format!("w_x{i}_y{j}.r16"))));
    let t: Vec<Vec<u16>> = vec![tile(0, 0), tile(1, 0), tile(0, 1), tile(1, 1)];
    assert!(t.iter().all(|v| v.len() == s * s), "every tile {s}²");
    for r in 0..s {
        assert_eq!(t[0][r * s + s - 1], t[1][r * s], "x edge, row {r}");
    }
    assert_eq!(t[0][(s - 1) * s..], t[2][..s], "y edge");
    let doc = json_file(&dir.path().join("w.json"));
    assert_eq!(num(&doc, "/raw/tile_size/0") as usize, s);
    assert_eq!(num(&doc, "/raw/size/0") as usize, 2 * (s - 1) + 1);
}

#[test]
fn exr_and_tiff_read_back_bit_for_bit_equal_to_the_in_process_field() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--size", "40x24", "--extent", "80x48", "--seed", "12", "--time", "1.5", "-o", "f.exr",
            "-o", "f.tif",
        ],
    );
    let args = seasynth::cli::FieldArgs {
        size: Some("40x24".into()),
        extent: Some("80x48".into()),
        seed: Some("12".into()),
        time: Some("1.5".into()),
        ..Default::default()
    };
    let params = seasynth::commands::common::resolve_params(&args).unwrap();
    let want = seasynth::field::synthesize(&params).unwrap().grid.data;
    let (w, h, name, got) = exr::read(&dir.path().join("f.exr")).unwrap();
    assert_eq!((w, h, name.as_str()), (40, 24, "Y"));
    let (tw, th, tif) = tiff(&dir.path().join("f.tif"));
    assert_eq!((tw, th), (40, 24));
    for k in 0..want.len() {
        assert_eq!(got[k].to_bits(), want[k].to_bits(), "EXR sample {k}");
        assert_eq!(tif[k].to_bits(), want[k].to_bits(), "TIFF sample {k}");
    }
    let doc = json_file(&dir.path().join("f.json"));
    assert_eq!(doc["exr"]["channel"], "Y");
    assert_eq!(num(&doc, "/geotiff/pixel_scale_m/0"), 2.0);
}

#[test]
fn gdalinfo_reports_the_tiff_pixel_size_in_meters() {
    let Ok(probe) = std::process::Command::new("gdalinfo")
        .arg("--version")
        .output()
    else {
        // Straight to the process's stderr, past the test harness's capture, so it shows.
        use std::io::Write;
        let note = b"note: gdalinfo not found; the GDAL check is skipped (install gdal-bin)\n";
        std::io::stderr().write_all(note).expect("stderr");
        return;
    };
    assert!(probe.status.success(), "gdalinfo --version fails");
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &["--size", "40x20", "--extent", "100x30", "-o", "g.tif"],
    );
    let out = std::process::Command::new("gdalinfo")
        .arg("-json")
        .arg(dir.path().join("g.tif"))
        .output()
        .expect("gdalinfo runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let info: Value = serde_json::from_slice(&out.stdout).expect("gdalinfo -json prints JSON");
    let gt: Vec<f64> = info["geoTransform"]
        .as_array()
        .unwrap_or_else(|| panic!("no geoTransform: {info:#}"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    // Pixel size (dx, −dy) = (2.5, −1.5) m; points as samples put the origin half a pixel out.
    assert_eq!((gt[1], gt[5]), (2.5, -1.5), "pixel size: {gt:?}");
    assert_eq!((gt[0], gt[3]), (-1.25, 0.75), "origin: {gt:?}");
    let wkt = info["coordinateSystem"]["wkt"].as_str().unwrap_or_default();
    assert!(wkt.contains("metre"), "a frame in meters: {wkt}");
}

#[test]
fn gdalinfo_places_texel_centre_samples_with_their_area_at_the_origin() {
    let Ok(probe) = std::process::Command::new("gdalinfo")
        .arg("--version")
        .output()
    else {
        use std::io::Write;
        let note = b"note: gdalinfo not found; the GDAL check is skipped (install gdal-bin)\n";
        std::io::stderr().write_all(note).expect("stderr");
        return;
    };
    assert!(probe.status.success(), "gdalinfo --version fails");
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--size",
            "40x20",
            "--extent",
            "100x30",
            "--sample-at",
            "centers",
            "-o",
            "c.tif",
        ],
    );
    let out = std::process::Command::new("gdalinfo")
        .arg("-json")
        .arg(dir.path().join("c.tif"))
        .output()
        .expect("gdalinfo runs");
    let info: Value = serde_json::from_slice(&out.stdout).expect("gdalinfo -json prints JSON");
    let gt: Vec<f64> = info["geoTransform"]
        .as_array()
        .unwrap_or_else(|| panic!("no geoTransform: {info:#}"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    // PixelIsArea: pixel (0, 0) starts at the origin, its centre (the sample) at (dx/2, dy/2).
    assert_eq!(
        (gt[0], gt[1], gt[3], gt[5]),
        (0.0, 2.5, 0.0, -1.5),
        "{gt:?}"
    );
    let area = info["metadata"][""]["AREA_OR_POINT"].as_str();
    assert_eq!(area, Some("Area"), "{info:#}");
    let side = json_file(&dir.path().join("c.json"));
    assert_eq!(side["grid"]["sample_at"], "centers");
    assert!(
        side["geotiff"]["raster_type"]
            .as_str()
            .unwrap()
            .starts_with("PixelIsArea")
    );
}

#[test]
fn engine_pngs_hold_the_r16_samples_of_the_engine_lattice() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for engine in ["unreal", "godot", "unity"] {
        let (png, r16) = (format!("{engine}.png"), format!("{engine}.r16"));
        generate(
            d,
            &[
                "--method", "fft", "--size", "64", "--extent", "64", "--engine", engine, "-o",
                &png, "-o", &r16,
            ],
        );
        let raw: Vec<u16> = std::fs::read(d.join(&r16))
            .unwrap()
            .chunks(2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]))
            .collect();
        let decoder = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(d.join(&png)).unwrap(),
        ));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let frame = reader.next_frame(&mut buf).unwrap();
        let side = if engine == "unreal" { 127 } else { 65 };
        assert_eq!((frame.width, frame.height), (side, side), "{engine}");
        let px: Vec<u16> = buf[..frame.buffer_size()]
            .chunks(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
            .collect();
        assert_eq!(px, raw, "{engine}: the PNG holds the .r16's samples");
        let doc = json_file(&d.join(format!("{engine}.json")));
        if engine == "godot" {
            let g = &doc["raw"]["godot"];
            let range = [
                doc["mapping"]["min_m"].as_f64(),
                doc["mapping"]["max_m"].as_f64(),
            ];
            assert_eq!(
                [
                    g["height_range_m"][0].as_f64(),
                    g["height_range_m"][1].as_f64()
                ],
                range,
                "{doc:#}"
            );
            assert_eq!(g["resolution"][0], 65);
        }
        if engine == "unreal" {
            assert!(doc["raw"]["unreal"]["z_scale"].as_f64().unwrap() > 0.0);
            // 32768 is 0 m: the mean of a sea sits near it.
            let mean = px.iter().map(|&v| v as f64).sum::<f64>() / px.len() as f64;
            assert!((mean - 32768.0).abs() < 2000.0, "mean {mean}");
        }
    }
}

#[test]
fn exr_maps_carry_the_displacement_in_the_up_convention_and_foam_in_alpha() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let base = [
        "--method",
        "fft",
        "--size",
        "32",
        "--extent",
        "64",
        "--wind-speed",
        "12",
        "--choppiness",
        "1",
        "--foam-threshold",
        "1",
    ];
    let mut y = base.to_vec();
    y.extend(["-o", "y.disp.exr", "-o", "y.foam.exr", "-o", "y.foam.png"]);
    generate(d, &y);
    let mut z = base.to_vec();
    z.extend(["--up", "z", "--exr-compression", "piz", "-o", "z.disp.exr"]);
    generate(d, &z);
    let mut zh = base.to_vec();
    zh.extend([
        "--up",
        "z",
        "--exr-half",
        "--exr-compression",
        "zip",
        "-o",
        "h.disp.exr",
    ]);
    generate(d, &zh);
    type Channels = Vec<(String, Vec<f32>)>;
    let read = |f: &str| exr::read_channels(&d.join(f)).unwrap().2;
    let (ych, zch, hch) = (read("y.disp.exr"), read("z.disp.exr"), read("h.disp.exr"));
    let names = |c: &Channels| c.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(names(&ych), ["A", "B", "G", "R"]);
    let get = |c: &Channels, n: &str| c.iter().find(|(m, _)| m == n).unwrap().1.clone();
    let (zr, zg, zb) = (get(&zch, "R"), get(&zch, "G"), get(&zch, "B"));
    assert!(zr.iter().any(|&v| v != 0.0), "a choppy sea moves sideways");
    for k in 0..32 * 32 {
        // --up y: (x, height, −y); --up z: (x, y, height); half floats round each.
        assert_eq!(
            [get(&ych, "R")[k], get(&ych, "G")[k], get(&ych, "B")[k]],
            [zr[k], zb[k], -zg[k]],
            "sample {k}"
        );
        assert_eq!(
            [get(&hch, "R")[k], get(&hch, "G")[k], get(&hch, "B")[k]],
            [exr_half(zr[k]), exr_half(zg[k]), exr_half(zb[k])],
            "sample {k}"
        );
    }
    // A = the foam coverage, as in the foam maps (16-bit in the PNG).
    let a = get(&ych, "A");
    assert_eq!(a, read("y.foam.exr")[0].1);
    assert!(a.iter().any(|&f| f > 0.0), "foam where J < 1");
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(d.join("y.foam.png")).unwrap(),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let frame = reader.next_frame(&mut buf).unwrap();
    let png: Vec<u16> = buf[..frame.buffer_size()]
        .chunks(2)
        .map(|b| u16::from_be_bytes([b[0], b[1]]))
        .collect();
    for (k, (&f, &p)) in a.iter().zip(&png).enumerate() {
        assert!(
            (f as f64 * 65535.0 - p as f64).abs() <= 0.5 + 1e-3,
            "sample {k}: {f} vs {p}"
        );
    }
}

/// `v` rounded to a half float and back.
fn exr_half(v: f32) -> f32 {
    ::exr::prelude::f16::from_f32(v).to_f32()
}

/// `generate ARGS` in an empty folder: rejected with one line naming each fragment, and
/// nothing left behind.
fn assert_rejected(args: &[&str], fragments: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let mut all = vec!["generate"];
    all.extend_from_slice(args);
    run_rejected(dir.path(), &all, fragments);
    let left = names_in(dir.path());
    assert!(left.is_empty(), "`{}` left {left:?}", args.join(" "));
}

#[test]
fn bad_export_flags_are_rejected_in_one_line_before_any_file_is_written() {
    assert_rejected(
        &["--size", "32", "--mesh-step", "0", "-o", "a.obj"],
        &["--mesh-step", "1 … 65536", "(got 0)"],
    );
    assert_rejected(
        &["--size", "32", "--tiles", "4", "-o", "a.obj"],
        &["--tiles", "CxR", "(got 4)"],
    );
    assert_rejected(
        &["--size", "32", "--tiles", "40x1", "-o", "a.obj"],
        &["--tiles 40x1", "31 cells along x"],
    );
    assert_rejected(
        &["--size", "32", "--engine", "unity", "-o", "a.tif"],
        &["--engine", ".r16, .r32 and .png"],
    );
    assert_rejected(
        &["--size", "32", "--engine", "cryengine", "-o", "a.r16"],
        &["--engine", "unity or unreal or godot", "(got cryengine)"],
    );
    assert_rejected(
        &["--size", "32", "--exr-compression", "rle", "-o", "a.exr"],
        &["--exr-compression", "none or zip or piz", "(got rle)"],
    );
    assert_rejected(
        &["--size", "32", "--exr-half", "-o", "a.tif"],
        &["--exr-half", "applies only to .exr"],
    );
    assert_rejected(
        &["--size", "32", "--up", "z", "-o", "a.disp.tif"],
        &["--up", ".obj, .glb and .disp.exr"],
    );
    assert_rejected(
        &["--size", "32", "--sample-at", "middle", "-o", "a.tif"],
        &["--sample-at", "middle", "corners", "centers"],
    );
    assert_rejected(
        &[
            "--size",
            "32",
            "--tiles",
            "2x2",
            "--periodic-tiles",
            "-o",
            "a.obj",
        ],
        &["--periodic-tiles", "periodic field"],
    );
    assert_rejected(
        &["--size", "32", "--up", "z", "-o", "a.glb"],
        &["--up z", "glTF"],
    );
    assert_rejected(
        &["--size", "32", "--vertical-scale", "0", "-o", "a.obj"],
        &["--vertical-scale", "(got 0)"],
    );
    assert_rejected(
        &[
            "--size",
            "32",
            "--tiles",
            "2x1",
            "-o",
            "a.obj",
            "-o",
            "a.tiles.png",
        ],
        &[
            "a.tiles.json",
            "written twice",
            "tile index of a.obj",
            "sidecar of a.tiles.png",
        ],
    );
}

#[test]
fn the_sidecar_records_what_each_export_needs_on_import() {
    let dir = tempfile::tempdir().unwrap();
    generate(
        dir.path(),
        &[
            "--method",
            "fft",
            "--size",
            "32",
            "--extent",
            "64",
            "--up",
            "z",
            "--vertical-scale",
            "2",
            "--mesh-step",
            "4",
            "-o",
            "s.obj",
            "-o",
            "s.r16",
            "-o",
            "s.exr",
        ],
    );
    let doc = json_file(&dir.path().join("s.json"));
    assert_eq!(doc["mesh"]["up"], "z");
    assert_eq!(num(&doc, "/mesh/vertical_scale"), 2.0);
    assert_eq!(num(&doc, "/mesh/mesh_step"), 4.0);
    assert_eq!(
        (num(&doc, "/mesh/vertices/0"), num(&doc, "/mesh/triangles")),
        (9.0, 128.0)
    );
    assert!(
        doc["raw"]["r16"].as_str().unwrap().contains("mapping"),
        "{doc:#}"
    );
    assert!(doc["mapping"].is_object(), "the .r16 mapping: {doc:#}");
    assert_eq!(doc["exr"]["channel"], "Y");
    let files: Vec<&str> = doc["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["format"].as_str().unwrap())
        .collect();
    assert_eq!(files, ["obj", "r16", "exr"]);
    let obj = parse_obj(&dir.path().join("s.obj"));
    assert_eq!(obj.v.len(), 81);
    // Z-up with heights doubled: Z of vertex (1, 0) is twice sample (4, 0).
    let (_, _, _, ex) = exr::read(&dir.path().join("s.exr")).unwrap();
    assert_eq!(obj.v[1][2], (ex[4] as f64 * 2.0) as f32);
    assert_eq!(obj.v[9][1], 8.0, "Z-up: Y = y");
}
