//! How meshes, raw height maps and tiles are written: the `generate` flags as typed
//! ([`crate::cli::ExportArgs`]) and, checked once, as [`ExportOptions`]. These are not parameters of
//! the field: they change the files, not the heights, and the sidecar records them.

use serde::Serialize;

use super::Format;
use super::format::{MapEncoding, MapKind};
use crate::error::{Error, ParamError, Result};

/// Which engine axis points up in a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum UpAxis {
    /// X = x, Y = h, Z = −y (glTF, Unity, Godot, three.js, Houdini).
    #[default]
    Y,
    /// X = x, Y = y, Z = h (Blender, Unreal, GIS).
    Z,
}

/// Texture coordinates of mesh tiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TileUv {
    /// u = x/Lx, v from y/Ly over the whole field: one texture for all tiles.
    #[default]
    Global,
    /// 0..1 across each tile: one texture per tile.
    Tile,
}

/// A terrain system whose heightmap sizes and encoding raw outputs follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Engine {
    /// Square heightmaps of 2ⁿ+1 samples, 33 … 4097; 16-bit values by the height mapping.
    Unity,
    /// Unreal's recommended landscape sizes (127 … 8129); 32768 = 0 m, Z scale recorded.
    Unreal,
    /// Godot's terrain plugins: HTerrain's 2ⁿ+1 sizes (33 … 4097, square), 16-bit values by
    /// the height mapping (the height range Terrain3D and HTerrain ask for on import).
    Godot,
}

/// Byte order of raw samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ByteOrder {
    #[default]
    Little,
    Big,
}

/// Columns × rows of tiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Tiles {
    pub columns: usize,
    pub rows: usize,
}

/// Most tiles along one side.
pub const MAX_TILES_PER_SIDE: usize = 256;

/// The export options, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportOptions {
    pub up: UpAxis,
    pub mesh_step: usize,
    pub vertical_scale: f64,
    pub tiles: Option<Tiles>,
    pub tile_uv: TileUv,
    pub periodic_tiles: bool,
    pub engine: Option<Engine>,
    pub byte_order: ByteOrder,
    /// How `.exr` files (heights and maps) are written.
    pub exr: ExrOptions,
    /// Where the field's samples sit: a parameter of the field (`--sample-at`), copied
    /// here by the writer of the field so that files can record it (GeoTIFF's raster type).
    pub sample_at: crate::config::SampleAt,
    /// The flags given, to reject those that no output uses.
    given: Vec<&'static str>,
}

impl Default for ExportOptions {
    fn default() -> Self {
        Self {
            up: UpAxis::Y,
            mesh_step: 1,
            vertical_scale: 1.0,
            tiles: None,
            tile_uv: TileUv::Global,
            periodic_tiles: false,
            engine: None,
            byte_order: ByteOrder::Little,
            exr: ExrOptions::default(),
            sample_at: crate::config::SampleAt::Corners,
            given: Vec::new(),
        }
    }
}

fn bad(name: &str, allowed: &str, got: &str) -> Error {
    Error::Param(ParamError {
        name: name.into(),
        allowed: allowed.into(),
        got: got.into(),
    })
}

fn choice<T: Copy>(name: &str, text: &str, options: &[(&str, T)]) -> Result<T> {
    options
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(text.trim()))
        .map(|(_, v)| *v)
        .ok_or_else(|| {
            let names: Vec<&str> = options.iter().map(|(n, _)| *n).collect();
            bad(name, &names.join(" or "), text)
        })
}

/// A positive integer of at most `max`.
fn count(name: &str, text: &str, max: usize) -> Result<usize> {
    match text.trim().parse::<usize>() {
        Ok(v) if (1..=max).contains(&v) => Ok(v),
        _ => Err(bad(name, &format!("an integer 1 … {max}"), text)),
    }
}

/// The export flags [`ExportOptions::from_flags`] takes.
pub const FLAGS: &[&str] = &[
    "--up",
    "--mesh-step",
    "--vertical-scale",
    "--tiles",
    "--tile-uv",
    "--periodic-tiles",
    "--engine",
    "--byte-order",
    "--exr-compression",
    "--exr-half",
];

impl ExportOptions {
    /// Parses the export flags given, as (flag, text) in command-line order; each bad
    /// value is one error naming the flag and what is allowed. A switch (`--periodic-tiles`)
    /// is given with any text.
    pub fn from_flags<'a>(
        flags: impl IntoIterator<Item = (&'static str, &'a str)>,
    ) -> Result<Self> {
        let mut o = Self::default();
        for (flag, text) in flags {
            o.set(flag, text)?;
        }
        Ok(o)
    }

    /// [`from_flags`](Self::from_flags) with the flags' names as owned text (`--up`,
    /// `--exr-half` with any value, …).
    pub fn from_named_flags(flags: &[(String, String)]) -> Result<Self> {
        let mut o = Self::default();
        for (name, text) in flags {
            let flag = FLAGS
                .iter()
                .find(|f| **f == name.as_str())
                .ok_or_else(|| bad("export flag", &FLAGS.join(", "), name))?;
            o.set(flag, text)?;
        }
        Ok(o)
    }

    /// Parses one export flag (one of [`FLAGS`]).
    fn set(&mut self, flag: &'static str, t: &str) -> Result<()> {
        let o = self;
        match flag {
            "--up" => o.up = choice("--up", t, &[("y", UpAxis::Y), ("z", UpAxis::Z)])?,
            "--mesh-step" => o.mesh_step = count("--mesh-step", t, crate::config::MAX_SIDE)?,
            "--vertical-scale" => {
                o.vertical_scale = match t.trim().parse::<f64>() {
                    Ok(v) if v.is_finite() && v > 0.0 && v <= 1e6 => v,
                    _ => return Err(bad("--vertical-scale", "a number > 0 and ≤ 1e6", t)),
                }
            }
            "--tiles" => {
                let parsed = t.split_once(['x', 'X']).and_then(|(c, r)| {
                    let c = c.trim().parse::<usize>().ok()?;
                    let r = r.trim().parse::<usize>().ok()?;
                    let ok = |v: usize| (1..=MAX_TILES_PER_SIDE).contains(&v);
                    (ok(c) && ok(r)).then_some(Tiles {
                        columns: c,
                        rows: r,
                    })
                });
                o.tiles = Some(parsed.ok_or_else(|| {
                    bad(
                        "--tiles",
                        &format!("CxR with 1 ≤ C, R ≤ {MAX_TILES_PER_SIDE}, e.g. 4x4"),
                        t,
                    )
                })?);
            }
            "--tile-uv" => {
                o.tile_uv = choice(
                    "--tile-uv",
                    t,
                    &[("global", TileUv::Global), ("tile", TileUv::Tile)],
                )?
            }
            "--periodic-tiles" => o.periodic_tiles = true,
            "--engine" => {
                o.engine = Some(choice(
                    "--engine",
                    t,
                    &[
                        ("unity", Engine::Unity),
                        ("unreal", Engine::Unreal),
                        ("godot", Engine::Godot),
                    ],
                )?)
            }
            "--exr-compression" => {
                o.exr.compression = choice(
                    "--exr-compression",
                    t,
                    &[
                        ("none", ExrCompression::None),
                        ("zip", ExrCompression::Zip),
                        ("piz", ExrCompression::Piz),
                    ],
                )?
            }
            "--exr-half" => o.exr.half = true,
            "--byte-order" => {
                o.byte_order = choice(
                    "--byte-order",
                    t,
                    &[("little", ByteOrder::Little), ("big", ByteOrder::Big)],
                )?
            }
            _ => {
                return Err(bad("export flag", &FLAGS.join(", "), flag));
            }
        }
        o.given.push(flag);
        Ok(())
    }

    /// Rejects flags that none of `formats` uses, and combinations that cannot be
    /// honoured, so that no flag is silently ignored.
    pub fn check(&self, formats: &[Format], periodic: bool) -> Result<()> {
        self.check_outputs(formats, &[], periodic)
    }

    /// [`check`](Self::check) with the maps written besides the height `formats` (an
    /// `.exr` map uses the EXR flags, a `.disp.exr` the up axis).
    pub fn check_outputs(
        &self,
        formats: &[Format],
        maps: &[(MapKind, MapEncoding)],
        periodic: bool,
    ) -> Result<()> {
        let has = |f: &[Format]| formats.iter().any(|x| f.contains(x));
        let exr_map = maps.iter().any(|(_, e)| *e == MapEncoding::Exr);
        let disp_exr = maps.contains(&(MapKind::Displacement, MapEncoding::Exr));
        let mesh = has(&[Format::Obj, Format::Glb]);
        let raw = has(&[Format::R16, Format::R32]);
        let engine = raw || has(&[Format::Png16]);
        let exr = exr_map || has(&[Format::Exr]);
        let unused = |flag: &str, what: &str| Error::Set {
            origin: flag.to_string(),
            message: format!("applies only to {what} outputs, and none is given"),
        };
        for &flag in &self.given {
            match flag {
                "--up" if !mesh && !disp_exr => {
                    return Err(unused(flag, ".obj, .glb and .disp.exr"));
                }
                "--mesh-step" | "--vertical-scale" | "--tile-uv" | "--periodic-tiles" if !mesh => {
                    return Err(unused(flag, ".obj and .glb"));
                }
                "--engine" if !engine => {
                    return Err(unused(flag, ".r16, .r32 and .png"));
                }
                "--byte-order" if !raw => {
                    return Err(unused(flag, ".r16 and .r32"));
                }
                "--exr-compression" | "--exr-half" if !exr => {
                    return Err(unused(flag, ".exr"));
                }
                "--tiles" if !(mesh || raw || (self.engine.is_some() && engine)) => {
                    return Err(unused(
                        flag,
                        ".obj, .glb, .r16 and .r32 (and .png with --engine)",
                    ));
                }
                "--tile-uv" | "--periodic-tiles" if self.tiles.is_none() => {
                    return Err(Error::Set {
                        origin: flag.to_string(),
                        message: "needs --tiles".into(),
                    });
                }
                _ => {}
            }
        }
        if self.up == UpAxis::Z && has(&[Format::Glb]) {
            return Err(Error::Set {
                origin: "--up z".into(),
                message: "a .glb is +Y up by the glTF specification; write the .glb in a \
                          separate run or leave --up at y"
                    .into(),
            });
        }
        if self.periodic_tiles && !periodic {
            return Err(Error::Set {
                origin: "--periodic-tiles".into(),
                message: "needs a periodic field (fft, filtered-noise, tileable perlin, or \
                          hybrid with tileable noise and a constant blend.alpha)"
                    .into(),
            });
        }
        Ok(())
    }
}

/// Compression of EXR files (`--exr-compression`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ExrCompression {
    /// Uncompressed scan lines.
    #[default]
    None,
    /// Deflate, blocks of 16 lines (OpenEXR's ZIP).
    Zip,
    /// Wavelet and Huffman coding (OpenEXR's PIZ).
    Piz,
}

/// How EXR files are written: the compression and the sample type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct ExrOptions {
    pub compression: ExrCompression,
    /// 16-bit half floats instead of 32-bit floats.
    pub half: bool,
}

impl ExrOptions {
    /// What the sidecar says of the samples.
    pub fn describe(&self) -> String {
        format!(
            "{}, meters; {} scan lines, row 0 is y = 0",
            if self.half {
                "16-bit half float"
            } else {
                "32-bit float"
            },
            match self.compression {
                ExrCompression::None => "uncompressed",
                ExrCompression::Zip => "ZIP-compressed",
                ExrCompression::Piz => "PIZ-compressed",
            }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::cli::ExportArgs;

    fn parse(f: impl FnOnce(&mut ExportArgs)) -> Result<ExportOptions> {
        let mut a = ExportArgs::default();
        f(&mut a);
        ExportOptions::from_flags(a.flags())
    }

    #[test]
    fn defaults_are_y_up_step_one_scale_one_little_endian_untiled() {
        let o = parse(|_| {}).unwrap();
        assert_eq!(
            (o.up, o.mesh_step, o.vertical_scale, o.tiles, o.byte_order),
            (UpAxis::Y, 1, 1.0, None, ByteOrder::Little)
        );
        o.check(&[Format::Png16], false).unwrap();
    }

    #[test]
    fn values_parse_and_bad_ones_name_the_flag_and_what_is_allowed() {
        let o = parse(|a| {
            a.up = Some("Z".into());
            a.tiles = Some("4x2".into());
            a.engine = Some("unreal".into());
            a.mesh_step = Some("4".into());
        })
        .unwrap();
        assert_eq!(o.up, UpAxis::Z);
        assert_eq!(
            o.tiles,
            Some(Tiles {
                columns: 4,
                rows: 2
            })
        );
        assert_eq!(o.engine, Some(Engine::Unreal));
        assert_eq!(o.mesh_step, 4);
        type Case = (fn(&mut ExportArgs), &'static str);
        let cases: [Case; 5] = [
            (|a| a.up = Some("x".into()), "--up must be y or z (got x)"),
            (
                |a| a.mesh_step = Some("0".into()),
                "--mesh-step must be an integer 1 … 65536 (got 0)",
            ),
            (
                |a| a.tiles = Some("4".into()),
                "--tiles must be CxR with 1 ≤ C, R ≤ 256, e.g. 4x4 (got 4)",
            ),
            (
                |a| a.vertical_scale = Some("-1".into()),
                "--vertical-scale must be a number > 0 and ≤ 1e6 (got -1)",
            ),
            (
                |a| a.byte_order = Some("middle".into()),
                "--byte-order must be little or big (got middle)",
            ),
        ];
        for (set, want) in cases {
            assert_eq!(parse(set).unwrap_err().to_string(), want);
        }
    }

    #[test]
    fn flags_without_an_output_that_uses_them_are_rejected() {
        let o = parse(|a| a.engine = Some("unity".into())).unwrap();
        let e = o.check(&[Format::Obj], true).unwrap_err().to_string();
        assert!(
            e.starts_with("--engine: applies only to .r16, .r32 and .png"),
            "{e}"
        );
        o.check(&[Format::R16], true).unwrap();
        let o = parse(|a| a.periodic_tiles = true).unwrap();
        let e = o.check(&[Format::Obj], true).unwrap_err().to_string();
        assert_eq!(e, "--periodic-tiles: needs --tiles");
        let o = parse(|a| {
            a.periodic_tiles = true;
            a.tiles = Some("2x2".into());
        })
        .unwrap();
        o.check(&[Format::Obj], true).unwrap();
        let e = o.check(&[Format::Obj], false).unwrap_err().to_string();
        assert!(e.contains("needs a periodic field"), "{e}");
        let o = parse(|a| a.up = Some("z".into())).unwrap();
        assert!(o.check(&[Format::Glb], true).is_err());
        o.check(&[Format::Obj], true).unwrap();
    }
}
