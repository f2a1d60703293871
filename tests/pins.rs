//! Regression pins of the outputs. Each case runs one command of the binary in a
//! temporary folder and compares a hash of every file it wrote with the pinned value, so
//! a change of the code that keeps the data passes, and one that changes a sample, a
//! vertex or a statistic, or writes a file more or less, fails naming the case and the
//! file. The cases cover every method, spectrum model and spreading, every output format
//! and map, tiles, choppy waves, the engine and mesh export flags, `animate` and `batch`.
//!
//! What is hashed is what a file means, not its container: the decoded samples of PNG,
//! TIFF and EXR (with their size, channels and sample type), the bytes of `.r16`, `.raw`
//! and `.r32`, the OBJ text without its comment lines, the binary buffer of a `.glb` and
//! its JSON document without the generator, and the data of the JSON files (the
//! sidecar's `stats`, `params`, `synthesis` and 16-bit mapping; the tile index's sets;
//! the animation's and the batch's parameters, mapping and rows), never the tool's
//! version, a hash that includes it, or a timing. The hash is FNV-1a 64 over bytes
//! (floats as their little-endian bit patterns), written here so that it does not
//! depend on the toolchain.
//!
//! When an output changes on purpose, print the new pins with
//!
//! ```sh
//! PIN_PRINT=1 cargo test --test pins -- --nocapture --test-threads 1 | sed -n 's/.*pin: /    /p'
//! ```
//!
//! (one `("case", "file", hash),` line per file, in the order of the tests), paste them
//! over the lines of `PINS`, and state in the commit which outputs changed and why.

mod common;

use std::collections::BTreeMap;
use std::path::Path;

use common::{read, run_ok};
use serde_json::Value;

/// FNV-1a, 64-bit.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    fn bytes(&mut self, data: &[u8]) {
        for &b in data {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    fn u64(&mut self, v: u64) {
        self.bytes(&v.to_le_bytes());
    }

    /// A length-prefixed string, so that consecutive strings cannot run into each other.
    fn text(&mut self, s: &str) {
        self.u64(s.len() as u64);
        self.bytes(s.as_bytes());
    }

    fn f32s(&mut self, v: &[f32]) {
        self.u64(v.len() as u64);
        for x in v {
            self.bytes(&x.to_bits().to_le_bytes());
        }
    }
}

/// JSON with the keys of every object sorted and numbers as serde_json prints them
/// (shortest round trip), so the text does not depend on the order a writer used.
fn canonical(v: &Value, out: &mut String) {
    match v {
        Value::Object(map) => {
            let mut keys: Vec<&String> = map.keys().collect();
            keys.sort();
            out.push('{');
            for (i, k) in keys.into_iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                out.push_str(&Value::String(k.clone()).to_string());
                out.push(':');
                canonical(&map[k], out);
            }
            out.push('}');
        }
        Value::Array(items) => {
            out.push('[');
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                canonical(item, out);
            }
            out.push(']');
        }
        other => out.push_str(&other.to_string()),
    }
}

/// The values at `pointers` (`absent` where there is none), canonical, one per line.
fn picked(doc: &Value, pointers: &[&str]) -> String {
    let mut out = String::new();
    for p in pointers {
        out.push_str(p);
        out.push('=');
        match doc.pointer(p) {
            Some(v) => canonical(v, &mut out),
            None => out.push_str("absent"),
        }
        out.push('\n');
    }
    out
}

/// `doc` without the keys `drop` of its top-level object.
fn without(doc: &Value, drop: &[&str]) -> Value {
    let mut doc = doc.clone();
    if let Some(map) = doc.as_object_mut() {
        for k in drop {
            map.remove(*k);
        }
    }
    doc
}

fn json_of(path: &Path, bytes: &[u8]) -> Value {
    serde_json::from_slice(bytes).unwrap_or_else(|e| panic!("{} is not JSON: {e}", path.display()))
}

/// The decoded samples of a PNG, with its size, color type and bit depth; 16-bit samples
/// as little-endian u16.
fn hash_png(h: &mut Fnv, path: &Path, bytes: &[u8]) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder
        .read_info()
        .unwrap_or_else(|e| panic!("{}: not a PNG: {e}", path.display()));
    let mut buf = vec![0; reader.output_buffer_size().expect("a buffer size")];
    let info = reader
        .next_frame(&mut buf)
        .unwrap_or_else(|e| panic!("{}: bad PNG data: {e}", path.display()));
    buf.truncate(info.buffer_size());
    h.u64(u64::from(info.width));
    h.u64(u64::from(info.height));
    h.text(&format!("{:?} {:?}", info.color_type, info.bit_depth));
    if info.bit_depth == png::BitDepth::Sixteen {
        for s in buf.chunks_exact(2) {
            h.bytes(&u16::from_be_bytes([s[0], s[1]]).to_le_bytes());
        }
    } else {
        h.bytes(&buf);
    }
}

/// The decoded samples of a float TIFF, with its size and color type.
fn hash_tiff(h: &mut Fnv, path: &Path, bytes: &[u8]) {
    let fail = |e: tiff::TiffError| -> ! { panic!("{}: bad TIFF: {e}", path.display()) };
    let mut dec =
        tiff::decoder::Decoder::new(std::io::Cursor::new(bytes)).unwrap_or_else(|e| fail(e));
    let (w, ht) = dec.dimensions().unwrap_or_else(|e| fail(e));
    let color = dec.colortype().unwrap_or_else(|e| fail(e));
    h.u64(u64::from(w));
    h.u64(u64::from(ht));
    h.text(&format!("{color:?}"));
    match dec.read_image().unwrap_or_else(|e| fail(e)) {
        tiff::decoder::DecodingResult::F32(v) => h.f32s(&v),
        _ => panic!("{}: expected 32-bit float samples", path.display()),
    }
}

/// The channels of an EXR's first layer: size, and each channel's name and samples.
fn hash_exr(h: &mut Fnv, path: &Path) {
    use exr::prelude::{FlatSamples, read_first_flat_layer_from_file};
    let image = read_first_flat_layer_from_file(path)
        .unwrap_or_else(|e| panic!("{}: bad EXR: {e}", path.display()));
    let layer = image.layer_data;
    h.u64(layer.size.x() as u64);
    h.u64(layer.size.y() as u64);
    for channel in &layer.channel_data.list {
        h.text(&channel.name.to_string());
        match &channel.sample_data {
            FlatSamples::F32(v) => h.f32s(v),
            _ => panic!("{}: expected 32-bit float samples", path.display()),
        }
    }
}

/// The lines of an OBJ that are not comments.
fn hash_obj(h: &mut Fnv, path: &Path, bytes: &[u8]) {
    let text = std::str::from_utf8(bytes)
        .unwrap_or_else(|_| panic!("{}: OBJ is not UTF-8", path.display()));
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        h.text(line);
    }
}

/// A GLB's binary buffer, and its JSON document without `asset.generator` (which holds
/// the tool's version).
fn hash_glb(h: &mut Fnv, path: &Path, bytes: &[u8]) {
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    assert!(
        bytes.len() >= 12 && &bytes[..4] == b"glTF" && word(8) == bytes.len(),
        "{}: not a GLB",
        path.display()
    );
    let (mut json, mut bin) = (None, None);
    let mut at = 12;
    while at + 8 <= bytes.len() {
        let (len, kind) = (word(at), word(at + 4));
        let data = &bytes[at + 8..at + 8 + len];
        match kind {
            0x4E4F_534A => json = Some(data),
            0x004E_4942 => bin = Some(data),
            _ => panic!("{}: unknown GLB chunk {kind:#x}", path.display()),
        }
        at += 8 + len;
    }
    let mut doc = json_of(path, json.expect("a JSON chunk"));
    let asset = doc
        .get_mut("asset")
        .and_then(Value::as_object_mut)
        .expect("an asset object");
    asset.remove("generator");
    let mut text = String::new();
    canonical(&doc, &mut text);
    h.text(&text);
    let bin = bin.expect("a BIN chunk");
    h.u64(bin.len() as u64);
    h.bytes(bin);
}

/// An index CSV without its `seconds` column (rows here have no quoted fields).
fn csv_without_seconds(path: &Path, bytes: &[u8]) -> String {
    let text = std::str::from_utf8(bytes).expect("UTF-8 CSV");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let col = header
        .iter()
        .position(|c| *c == "seconds")
        .unwrap_or_else(|| panic!("{}: no seconds column", path.display()));
    let mut out = String::new();
    for line in std::iter::once(header.join(",").as_str()).chain(lines) {
        let mut cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), header.len(), "{}: `{line}`", path.display());
        cells.remove(col);
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// The data of a JSON file, by its name: a sidecar, a tile index, an animation's
/// sequence, or a batch's description and index.
fn json_data(rel: &str, path: &Path, bytes: &[u8]) -> String {
    let doc = json_of(path, bytes);
    let name = rel.rsplit('/').next().unwrap();
    if name.ends_with(".tiles.json") {
        picked(&doc, &["/sets"])
    } else if name == "sequence.json" {
        let mut s = picked(&doc, &["/frames", "/fps", "/start_time_s", "/files"]);
        s += &picked(&doc, &["/mapping_min_m", "/mapping_max_m", "/params"]);
        s
    } else if name == "batch.json" {
        let mut s = picked(&doc, &["/jobs", "/name_template", "/formats", "/keys"]);
        s += &picked(&doc, &["/mapping_min_m", "/mapping_max_m"]);
        s
    } else if name == "index.json" || name.starts_with("index.shard-") {
        let rows: Vec<Value> = doc["rows"]
            .as_array()
            .unwrap_or_else(|| panic!("{}: no rows", path.display()))
            .iter()
            .map(|r| without(r, &["seconds", "hash"]))
            .collect();
        let mut s = picked(&doc, &["/jobs", "/shard", "/keys"]);
        canonical(&Value::Array(rows), &mut s);
        s
    } else {
        // A sidecar.
        picked(
            &doc,
            &[
                "/seed",
                "/stats",
                "/params",
                "/synthesis",
                "/mapping/min_m",
                "/mapping/max_m",
                "/batch/job",
                "/batch/jobs",
                "/batch/name",
                "/batch/values",
            ],
        )
    }
}

/// The hash of one output file, by its kind.
fn hash_file(rel: &str, path: &Path) -> u64 {
    let bytes = read(path);
    let mut h = Fnv::new();
    let ext = rel.rsplit('.').next().unwrap_or("");
    match ext {
        "png" => hash_png(&mut h, path, &bytes),
        "tif" | "tiff" => hash_tiff(&mut h, path, &bytes),
        "exr" => hash_exr(&mut h, path),
        "r16" | "raw" | "r32" => h.bytes(&bytes),
        "obj" => hash_obj(&mut h, path, &bytes),
        "glb" => hash_glb(&mut h, path, &bytes),
        "json" => h.text(&json_data(rel, path, &bytes)),
        "csv" => h.text(&csv_without_seconds(path, &bytes)),
        _ => panic!("no hash for the output {rel}"),
    }
    h.0
}

/// Every file under `dir`, by its path relative to `dir` with `/` separators, sorted.
fn files_under(dir: &Path, prefix: &str, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).expect("readable folder") {
        let entry = entry.expect("folder entry");
        let name = entry.file_name().to_string_lossy().into_owned();
        let rel = format!("{prefix}{name}");
        if entry.file_type().expect("file type").is_dir() {
            files_under(&entry.path(), &format!("{rel}/"), out);
        } else {
            out.push(rel);
        }
    }
    out.sort();
}

/// Runs `seasynth COMMAND --quiet` (COMMAND split at spaces) in a temporary folder,
/// hashes every file it wrote and compares with the pins of `case`; with `PIN_PRINT` set,
/// prints the lines of `PINS`.
fn pin(case: &str, command: &str) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mut all: Vec<&str> = command.split_whitespace().collect();
    all.push("--quiet");
    run_ok(dir.path(), &all);
    let mut files = Vec::new();
    files_under(dir.path(), "", &mut files);
    let got: BTreeMap<String, u64> = files
        .iter()
        .map(|rel| (rel.clone(), hash_file(rel, &dir.path().join(rel))))
        .collect();
    if std::env::var_os("PIN_PRINT").is_some() {
        for (file, hash) in &got {
            println!("pin: ({case:?}, {file:?}, {hash:#018x}),");
        }
    }
    let want: BTreeMap<&str, u64> = PINS
        .iter()
        .filter(|(c, _, _)| *c == case)
        .map(|&(_, f, h)| (f, h))
        .collect();
    let mut problems = Vec::new();
    for (file, hash) in &got {
        match want.get(file.as_str()) {
            None => problems.push(format!(
                "case {case}: file {file} was written but has no pin (hash {hash:#018x})"
            )),
            Some(w) if w != hash => problems.push(format!(
                "case {case}: file {file} changed: hash {hash:#018x}, pinned {w:#018x}"
            )),
            Some(_) => {}
        }
    }
    for file in want.keys().filter(|f| !got.contains_key(**f)) {
        problems.push(format!(
            "case {case}: file {file} is pinned but was not written"
        ));
    }
    assert!(
        problems.is_empty(),
        "`seasynth {}` no longer gives the pinned outputs:\n{}",
        all.join(" "),
        problems.join("\n")
    );
}

#[test]
fn hybrid_default() {
    pin(
        "hybrid-default",
        "generate --size 128 --extent 128 -o h.png -o h.tif",
    );
}

#[test]
fn hybrid_radial_matched() {
    pin(
        "hybrid-radial-matched",
        "generate --size 128 --extent 256 --wind-dir 30 --seed 7 --set blend.alpha.kind=radial \
         --set blend.beta=matched -o h.exr",
    );
}

#[test]
fn fft_phillips_every_format() {
    pin(
        "fft-phillips-every-format",
        "generate --method fft --size 64 --extent 64 --time 2 -o a.png -o a.tif -o a.exr -o a.r16 \
         -o a.r32 -o a.obj -o a.glb -o a.normal.png -o a.foam.png -o a.jacobian.tif -o a.disp.tif \
         -o a.preview.png",
    );
}

#[test]
fn fft_pierson_moskowitz_cos2() {
    pin(
        "fft-pierson-moskowitz-cos2",
        "generate --method fft --spectrum pierson-moskowitz --spreading cos2 --wind-speed 12 \
         --wind-dir 60 --size 128 --extent 512 -o p.png -o p.tif",
    );
}

#[test]
fn fft_jonswap_mitsuyasu() {
    pin(
        "fft-jonswap-mitsuyasu",
        "generate --method fft --spectrum jonswap --spreading mitsuyasu --wind-speed 10 \
         --fetch-km 50 --gamma 5 --size 128 --extent 512 -o j.tif",
    );
}

#[test]
fn fft_jonswap_hs_tp_hasselmann_swell() {
    pin(
        "fft-jonswap-hs-tp-hasselmann-swell",
        "generate --method fft --spectrum jonswap --hs 2 --tp 9 --spreading hasselmann \
         --set spectrum.swell=2 --size 128x64 --extent 512x256 -o s.tif",
    );
}

#[test]
fn fft_tma_donelan_banner() {
    pin(
        "fft-tma-donelan-banner",
        "generate --method fft --spectrum tma --depth 15 --spreading donelan-banner \
         --wind-speed 15 --size 128 --extent 512 --time 4 -o d.tif",
    );
}

#[test]
fn fft_fractal() {
    pin(
        "fft-fractal",
        "generate --method fft --spectrum fractal --set fractal.rolloff_m=300 --size 128 \
         --extent 1024 -o f.png -o f.tif",
    );
}

#[test]
fn filtered_noise_pierson_moskowitz_hasselmann() {
    pin(
        "filtered-noise-pierson-moskowitz-hasselmann",
        "generate --method filtered-noise --spectrum pierson-moskowitz --spreading hasselmann \
         --wind-speed 15 --wind-dir 45 --size 128 --extent 512 --time 1.5 -o n.tif",
    );
}

#[test]
fn filtered_noise_hot_air() {
    pin(
        "filtered-noise-hot-air",
        "generate --method filtered-noise --spectrum jonswap --wind-speed 12 --phase-mode hot-air \
         --time 0.5 --size 64 --extent 256 -o n.tif",
    );
}

#[test]
fn filtered_noise_translate() {
    pin(
        "filtered-noise-translate",
        "generate --method filtered-noise --spectrum pierson-moskowitz --wind-speed 10 \
         --wind-dir 120 --phase-mode translate --time 2 --size 64 --extent 256 -o n.tif",
    );
}

#[test]
fn perlin_tileable() {
    pin(
        "perlin-tileable",
        "generate --method perlin --seed 3 --size 128 --extent 256 -o p.png -o p.tif",
    );
}

#[test]
fn perlin_not_tileable() {
    pin(
        "perlin-not-tileable",
        "generate --method perlin --set perlin.tileable=false --set perlin.octaves=4 \
         --set perlin.wavelength_m=50 --size 96x64 --extent 300x200 -o p.tif",
    );
}

#[test]
fn trochoid_streamed() {
    pin(
        "trochoid-streamed",
        "generate --method trochoid --spectrum pierson-moskowitz --wind-speed 10 --size 128 \
         --extent 256 --time 3 -o t.png -o t.tif",
    );
}

#[test]
fn trochoid_in_memory() {
    pin(
        "trochoid-in-memory",
        "generate --method trochoid --spectrum jonswap --wind-speed 8 --wind-dir 200 \
         --set trochoid.origin_m=[500,-200] --set trochoid.sharpness=0.7 --loop-period 30 \
         --time 5 --size 96x64 --extent 192x128 -o t.r32 -o t.exr -o t.normal.png",
    );
}

#[test]
fn choppy_loop_with_every_map() {
    pin(
        "choppy-loop-with-every-map",
        "generate --method fft --spectrum pierson-moskowitz --wind-speed 20 --choppiness 0.8 \
         --loop-period 20 --foam-threshold 0.5 --time 3 --size 128 --extent 256 -o c.png -o c.tif \
         -o c.normal.png -o c.foam.png -o c.jacobian.tif -o c.disp.tif",
    );
}

#[test]
fn tiles_of_every_tiled_format() {
    pin(
        "tiles-of-every-tiled-format",
        "generate --method fft --size 64 --extent 64 --tiles 2x2 -o t.obj -o t.glb -o t.r16 \
         -o t.r32",
    );
}

#[test]
fn tiles_periodic_with_tile_uvs() {
    pin(
        "tiles-periodic-with-tile-uvs",
        "generate --method fft --size 64 --extent 128 --tiles 2x2 --periodic-tiles --tile-uv tile \
         --mesh-step 2 -o p.obj -o p.glb",
    );
}

#[test]
fn tiles_uneven_of_the_hybrid() {
    pin(
        "tiles-uneven-of-the-hybrid",
        "generate --size 64 --extent 64 --tiles 3x2 -o h.obj",
    );
}

#[test]
fn mesh_up_z_step_and_scale() {
    pin(
        "mesh-up-z-step-and-scale",
        "generate --size 64 --extent 64 --up z --mesh-step 3 --vertical-scale 2 -o m.obj",
    );
}

#[test]
fn engine_unity_big_endian() {
    pin(
        "engine-unity-big-endian",
        "generate --method fft --size 64 --extent 64 --engine unity --byte-order big -o u.raw \
         -o u.r32",
    );
}

#[test]
fn engine_unreal_tiles() {
    pin(
        "engine-unreal-tiles",
        "generate --method fft --spectrum pierson-moskowitz --wind-speed 9 --size 128 \
         --extent 256 --engine unreal --tiles 2x2 -o l.r16 -o l.r32",
    );
}

#[test]
fn animate_choppy_with_maps() {
    pin(
        "animate-choppy-with-maps",
        "animate --method fft --spectrum pierson-moskowitz --wind-speed 15 --choppiness 0.8 \
         --loop-period 10 --fps 12 --size 64 --extent 128 --frames 3 \
         --format png,tif,normal,foam,jacobian,disp -o anim",
    );
}

#[test]
fn animate_filtered_noise_hot_air() {
    pin(
        "animate-filtered-noise-hot-air",
        "animate --method filtered-noise --spectrum pierson-moskowitz --phase-mode hot-air \
         --size 64 --extent 256 --frames 3 --format png,tif -o anim",
    );
}

#[test]
fn animate_trochoid() {
    pin(
        "animate-trochoid",
        "animate --method trochoid --spectrum pierson-moskowitz --wind-speed 12 --size 64 \
         --extent 256 --time 1 --frames 2 --format png,normal -o anim",
    );
}

#[test]
fn batch_two_sweeps() {
    pin(
        "batch-two-sweeps",
        "batch --method fft --spectrum pierson-moskowitz --size 64 --extent 128 \
         --sweep wind-dir=0:180:90 --sweep seed=1,2 --format png,tif,exr,normal -o bat",
    );
}

#[test]
fn batch_named_with_a_height_range() {
    pin(
        "batch-named-with-a-height-range",
        "batch --size 64 --extent 64 --sweep wind-speed=5,9 --name w{wind-speed}-{index} \
         --height-range=-1:1 --format png,r16,obj -o bat",
    );
}

/// The pins: (case, file, hash of its data).
#[rustfmt::skip]
const PINS: &[(&str, &str, u64)] = &[
    ("animate-choppy-with-maps", "anim/frame_00000.disp.tif", 0x5ec694b687e461a4),
    ("animate-choppy-with-maps", "anim/frame_00000.foam.png", 0xe9d4fc0700e81f71),
    ("animate-choppy-with-maps", "anim/frame_00000.jacobian.tif", 0x9294a1f78979cf73),
    ("animate-choppy-with-maps", "anim/frame_00000.normal.png", 0x736aad3d6c315e4b),
    ("animate-choppy-with-maps", "anim/frame_00000.png", 0xbcc6dd5c61e032a5),
    ("animate-choppy-with-maps", "anim/frame_00000.tif", 0x47ff923389cb2426),
    ("animate-choppy-with-maps", "anim/frame_00001.disp.tif", 0x17f357bac494f6d9),
    ("animate-choppy-with-maps", "anim/frame_00001.foam.png", 0xe4b36dca7c574aef),
    ("animate-choppy-with-maps", "anim/frame_00001.jacobian.tif", 0xcec253142cc786a6),
    ("animate-choppy-with-maps", "anim/frame_00001.normal.png", 0xf8bb006491da62d4),
    ("animate-choppy-with-maps", "anim/frame_00001.png", 0xd89188f2e1224bb1),
    ("animate-choppy-with-maps", "anim/frame_00001.tif", 0xd390944fe567afc6),
    ("animate-choppy-with-maps", "anim/frame_00002.disp.tif", 0x5997989b488c75e9),
    ("animate-choppy-with-maps", "anim/frame_00002.foam.png", 0x732e7d078746d311),
    ("animate-choppy-with-maps", "anim/frame_00002.jacobian.tif", 0x3bf6372c3ebf02c1),
    ("animate-choppy-with-maps", "anim/frame_00002.normal.png", 0x32a5172e5f484298),
    ("animate-choppy-with-maps", "anim/frame_00002.png", 0x41a464b098b55ba9),
    ("animate-choppy-with-maps", "anim/frame_00002.tif", 0x2ce274aeca93037e),
    ("animate-choppy-with-maps", "anim/sequence.json", 0x8f76763a9d0c0f8d),
    ("animate-filtered-noise-hot-air", "anim/frame_00000.png", 0x3c30a73f53924eab),
    ("animate-filtered-noise-hot-air", "anim/frame_00000.tif", 0x71dc2ba7b056bd56),
    ("animate-filtered-noise-hot-air", "anim/frame_00001.png", 0x8e0545217a7858ab),
    ("animate-filtered-noise-hot-air", "anim/frame_00001.tif", 0x12bf811d14ef827a),
    ("animate-filtered-noise-hot-air", "anim/frame_00002.png", 0x1657519e94e688fa),
    ("animate-filtered-noise-hot-air", "anim/frame_00002.tif", 0x44bd8ee49e6d2180),
    ("animate-filtered-noise-hot-air", "anim/sequence.json", 0xc08912887347beb9),
    ("animate-trochoid", "anim/frame_00000.normal.png", 0x9d63b69f737db1fb),
    ("animate-trochoid", "anim/frame_00000.png", 0x1be77e396ccfaa2a),
    ("animate-trochoid", "anim/frame_00001.normal.png", 0x87763530bffd93ae),
    ("animate-trochoid", "anim/frame_00001.png", 0x989e441c02096fd0),
    ("animate-trochoid", "anim/sequence.json", 0x9a637f6c38453bb0),
    ("batch-named-with-a-height-range", "bat/batch.json", 0x66e2336f44b64d85),
    ("batch-named-with-a-height-range", "bat/index.csv", 0xe47f466b1fbd0150),
    ("batch-named-with-a-height-range", "bat/index.json", 0xd946070491021ff1),
    ("batch-named-with-a-height-range", "bat/w5-0.json", 0x512d5ca9055885fa),
    ("batch-named-with-a-height-range", "bat/w5-0.obj", 0x6aa4e20428efb72c),
    ("batch-named-with-a-height-range", "bat/w5-0.png", 0xa3a7135ded6cf5e4),
    ("batch-named-with-a-height-range", "bat/w5-0.r16", 0x2dbbf3006646983a),
    ("batch-named-with-a-height-range", "bat/w9-1.json", 0xb287da776cecf223),
    ("batch-named-with-a-height-range", "bat/w9-1.obj", 0xc469ce1080e0ee0c),
    ("batch-named-with-a-height-range", "bat/w9-1.png", 0x0dcc9a1a20aca5be),
    ("batch-named-with-a-height-range", "bat/w9-1.r16", 0x12ae953967143f20),
    ("batch-two-sweeps", "bat/0_wind-dir=0_seed=1.exr", 0xbe0c27b888a44d92),
    ("batch-two-sweeps", "bat/0_wind-dir=0_seed=1.json", 0x77abe02c8823b4ca),
    ("batch-two-sweeps", "bat/0_wind-dir=0_seed=1.normal.png", 0x3e812af55ec77121),
    ("batch-two-sweeps", "bat/0_wind-dir=0_seed=1.png", 0xedd4ec1da753cab2),
    ("batch-two-sweeps", "bat/0_wind-dir=0_seed=1.tif", 0xeaf2a7187ca918ab),
    ("batch-two-sweeps", "bat/1_wind-dir=0_seed=2.exr", 0xdcfee9daf516efae),
    ("batch-two-sweeps", "bat/1_wind-dir=0_seed=2.json", 0x927922ce47acc91c),
    ("batch-two-sweeps", "bat/1_wind-dir=0_seed=2.normal.png", 0x9368786a58add3aa),
    ("batch-two-sweeps", "bat/1_wind-dir=0_seed=2.png", 0xab67305793fe63bd),
    ("batch-two-sweeps", "bat/1_wind-dir=0_seed=2.tif", 0x6e1dc2cf7911a017),
    ("batch-two-sweeps", "bat/2_wind-dir=90_seed=1.exr", 0x04f4b94a2c35e8f1),
    ("batch-two-sweeps", "bat/2_wind-dir=90_seed=1.json", 0x6e5d6d5b5f0bb9c8),
    ("batch-two-sweeps", "bat/2_wind-dir=90_seed=1.normal.png", 0x28aeab1621578ae4),
    ("batch-two-sweeps", "bat/2_wind-dir=90_seed=1.png", 0xaef94c1019f3d189),
    ("batch-two-sweeps", "bat/2_wind-dir=90_seed=1.tif", 0xd99fed292b88b3d0),
    ("batch-two-sweeps", "bat/3_wind-dir=90_seed=2.exr", 0x5407d472dc9c4bb1),
    ("batch-two-sweeps", "bat/3_wind-dir=90_seed=2.json", 0x66f4f3cba2da2558),
    ("batch-two-sweeps", "bat/3_wind-dir=90_seed=2.normal.png", 0x4c30e0515265c9e6),
    ("batch-two-sweeps", "bat/3_wind-dir=90_seed=2.png", 0x594a1821fdeeabb6),
    ("batch-two-sweeps", "bat/3_wind-dir=90_seed=2.tif", 0x26299407005371ac),
    ("batch-two-sweeps", "bat/batch.json", 0x204de5961dd4c156),
    ("batch-two-sweeps", "bat/index.csv", 0xaf4676c20b5a9e04),
    ("batch-two-sweeps", "bat/index.json", 0x028295c892550b68),
    ("choppy-loop-with-every-map", "c.disp.tif", 0xd7bff1d116f324e3),
    ("choppy-loop-with-every-map", "c.foam.png", 0xa31eef99354174e7),
    ("choppy-loop-with-every-map", "c.jacobian.tif", 0xcb74db3e7ce62723),
    ("choppy-loop-with-every-map", "c.json", 0xeb87ec94eb5a5825),
    ("choppy-loop-with-every-map", "c.normal.png", 0x7ef9e5fd8d46ebcb),
    ("choppy-loop-with-every-map", "c.png", 0x9c84454e12ee04a6),
    ("choppy-loop-with-every-map", "c.tif", 0xf26572e5f615cbed),
    ("engine-unity-big-endian", "u.json", 0xae891398ab899cd4),
    ("engine-unity-big-endian", "u.r32", 0x525bc2d0c6f57295),
    ("engine-unity-big-endian", "u.raw", 0xa28584c175c81777),
    ("engine-unreal-tiles", "l.json", 0xf5e653ff7c9f5465),
    ("engine-unreal-tiles", "l.tiles.json", 0x4f685cf245efa53d),
    ("engine-unreal-tiles", "l_x0_y0.r16", 0x8b6a7b62fdffada1),
    ("engine-unreal-tiles", "l_x0_y0.r32", 0xffd2ed7516cb321e),
    ("engine-unreal-tiles", "l_x0_y1.r16", 0x12925e84036411e1),
    ("engine-unreal-tiles", "l_x0_y1.r32", 0x2b86e98fb8c809ef),
    ("engine-unreal-tiles", "l_x1_y0.r16", 0x08800ab84349f92d),
    ("engine-unreal-tiles", "l_x1_y0.r32", 0x455043244a621b0b),
    ("engine-unreal-tiles", "l_x1_y1.r16", 0xa2738aac550d6274),
    ("engine-unreal-tiles", "l_x1_y1.r32", 0x083deaa4b48b3e99),
    ("fft-fractal", "f.json", 0x9d7fbdd598c848bf),
    ("fft-fractal", "f.png", 0x32e5d04c19a073bd),
    ("fft-fractal", "f.tif", 0xc929062558f07f1c),
    ("fft-jonswap-hs-tp-hasselmann-swell", "s.json", 0xe05b0c492f4417af),
    ("fft-jonswap-hs-tp-hasselmann-swell", "s.tif", 0x90125886ff40cd14),
    ("fft-jonswap-mitsuyasu", "j.json", 0xb32ea2408c6ca142),
    ("fft-jonswap-mitsuyasu", "j.tif", 0x3b68d6cd8441d74d),
    ("fft-phillips-every-format", "a.disp.tif", 0xff78130fe24f00cb),
    ("fft-phillips-every-format", "a.exr", 0xe877310b9e9b2c6d),
    ("fft-phillips-every-format", "a.foam.png", 0x3dc3caec45704367),
    ("fft-phillips-every-format", "a.glb", 0x6166a238a83d160e),
    ("fft-phillips-every-format", "a.jacobian.tif", 0x169485d3ce613222),
    ("fft-phillips-every-format", "a.json", 0xee4778ce6fe6d892),
    ("fft-phillips-every-format", "a.normal.png", 0x224a2f20fe89e5d4),
    ("fft-phillips-every-format", "a.obj", 0xb5ba8a17812f773d),
    ("fft-phillips-every-format", "a.png", 0x430a50c1c4ac5531),
    ("fft-phillips-every-format", "a.preview.png", 0x857ee46f1366a545),
    ("fft-phillips-every-format", "a.r16", 0xf0fde5c99232a2c3),
    ("fft-phillips-every-format", "a.r32", 0xe56b6dad05beab27),
    ("fft-phillips-every-format", "a.tif", 0xf8c63198bf2fb480),
    ("fft-pierson-moskowitz-cos2", "p.json", 0x2eaf38fbed25b39a),
    ("fft-pierson-moskowitz-cos2", "p.png", 0xc24ad874ffa8780d),
    ("fft-pierson-moskowitz-cos2", "p.tif", 0x2303944b84e1daab),
    ("fft-tma-donelan-banner", "d.json", 0xee41fa9c3edb4e9a),
    ("fft-tma-donelan-banner", "d.tif", 0x45dc40af7437dd85),
    ("filtered-noise-hot-air", "n.json", 0x37b44898fdfd2af1),
    ("filtered-noise-hot-air", "n.tif", 0x2793c0ebc54c4ae7),
    ("filtered-noise-pierson-moskowitz-hasselmann", "n.json", 0x2b394b349bb68f94),
    ("filtered-noise-pierson-moskowitz-hasselmann", "n.tif", 0xcf03c07cb2dd1413),
    ("filtered-noise-translate", "n.json", 0xcb258e39ddcc0dcd),
    ("filtered-noise-translate", "n.tif", 0x833e3e92c552f504),
    ("hybrid-default", "h.json", 0x3481cf67409c1914),
    ("hybrid-default", "h.png", 0x1ea9f469fb830422),
    ("hybrid-default", "h.tif", 0x23891ec673ccd51e),
    ("hybrid-radial-matched", "h.exr", 0xb29fb35472af439d),
    ("hybrid-radial-matched", "h.json", 0x263a8437a8f070d9),
    ("mesh-up-z-step-and-scale", "m.json", 0xf9f31e5ffc783063),
    ("mesh-up-z-step-and-scale", "m.obj", 0x813193376835b720),
    ("perlin-not-tileable", "p.json", 0x78440038361e8485),
    ("perlin-not-tileable", "p.tif", 0xa4b9b3060641de94),
    ("perlin-tileable", "p.json", 0xa279e870b3606540),
    ("perlin-tileable", "p.png", 0xc40c3992ba454d3c),
    ("perlin-tileable", "p.tif", 0x02225a2d3d3b12db),
    ("tiles-of-every-tiled-format", "t.json", 0xae891398ab899cd4),
    ("tiles-of-every-tiled-format", "t.tiles.json", 0x234791971341ee37),
    ("tiles-of-every-tiled-format", "t_x0_y0.glb", 0x571b6510e89a5cfe),
    ("tiles-of-every-tiled-format", "t_x0_y0.obj", 0x4e753fb91c3b4d81),
    ("tiles-of-every-tiled-format", "t_x0_y0.r16", 0x35e464ef3c5ac4d7),
    ("tiles-of-every-tiled-format", "t_x0_y0.r32", 0x4818412a7fdf9702),
    ("tiles-of-every-tiled-format", "t_x0_y1.glb", 0xf7988304a3cc6476),
    ("tiles-of-every-tiled-format", "t_x0_y1.obj", 0x6e61b7e67f4b2efa),
    ("tiles-of-every-tiled-format", "t_x0_y1.r16", 0x103a88e614c6e937),
    ("tiles-of-every-tiled-format", "t_x0_y1.r32", 0xe737e1365c34263e),
    ("tiles-of-every-tiled-format", "t_x1_y0.glb", 0x3fbc29b5e8abe757),
    ("tiles-of-every-tiled-format", "t_x1_y0.obj", 0xcd57d4d9472eb033),
    ("tiles-of-every-tiled-format", "t_x1_y0.r16", 0x847f4f187ed4d15a),
    ("tiles-of-every-tiled-format", "t_x1_y0.r32", 0x19e9463d8972f17a),
    ("tiles-of-every-tiled-format", "t_x1_y1.glb", 0x05bad6646fc0a39d),
    ("tiles-of-every-tiled-format", "t_x1_y1.obj", 0xf025ce6e080e90af),
    ("tiles-of-every-tiled-format", "t_x1_y1.r16", 0x68e0a32ce063ab12),
    ("tiles-of-every-tiled-format", "t_x1_y1.r32", 0x30dd85203966b728),
    ("tiles-periodic-with-tile-uvs", "p.json", 0xc0500307bbeeb85b),
    ("tiles-periodic-with-tile-uvs", "p.tiles.json", 0x1e1d01b8d02e56ca),
    ("tiles-periodic-with-tile-uvs", "p_x0_y0.glb", 0x8ecd661f3bd2f927),
    ("tiles-periodic-with-tile-uvs", "p_x0_y0.obj", 0x2e14ed0617a975bf),
    ("tiles-periodic-with-tile-uvs", "p_x0_y1.glb", 0x8e80ae70c87c8dfd),
    ("tiles-periodic-with-tile-uvs", "p_x0_y1.obj", 0x41a78bf15099a0ae),
    ("tiles-periodic-with-tile-uvs", "p_x1_y0.glb", 0x3a22fa89e34035b9),
    ("tiles-periodic-with-tile-uvs", "p_x1_y0.obj", 0xbde8e2a0dc5ce541),
    ("tiles-periodic-with-tile-uvs", "p_x1_y1.glb", 0xe86307280311c4c2),
    ("tiles-periodic-with-tile-uvs", "p_x1_y1.obj", 0xbfa4d00a60f68620),
    ("tiles-uneven-of-the-hybrid", "h.json", 0xf9f31e5ffc783063),
    ("tiles-uneven-of-the-hybrid", "h.tiles.json", 0xb51ec69b64db55eb),
    ("tiles-uneven-of-the-hybrid", "h_x0_y0.obj", 0x3b87ae7917396490),
    ("tiles-uneven-of-the-hybrid", "h_x0_y1.obj", 0x0eb1d0fd0462dd31),
    ("tiles-uneven-of-the-hybrid", "h_x1_y0.obj", 0xe7865549c32cf3f4),
    ("tiles-uneven-of-the-hybrid", "h_x1_y1.obj", 0x54585411a7755e81),
    ("tiles-uneven-of-the-hybrid", "h_x2_y0.obj", 0x24a051ff9432efbf),
    ("tiles-uneven-of-the-hybrid", "h_x2_y1.obj", 0x0812f60821312f90),
    ("trochoid-in-memory", "t.exr", 0xa0afd31a399c21ff),
    ("trochoid-in-memory", "t.json", 0xebe2f1772e11fd07),
    ("trochoid-in-memory", "t.normal.png", 0x29ba84300b06d86d),
    ("trochoid-in-memory", "t.r32", 0x6415e9d3231099f9),
    ("trochoid-streamed", "t.json", 0x5d742fcba4ad48ba),
    ("trochoid-streamed", "t.png", 0xd337074da66c61e1),
    ("trochoid-streamed", "t.tif", 0x6ab985715ecae45f),
];
