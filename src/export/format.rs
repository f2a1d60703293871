//! The one table from file names to what is written: a height format by the extension
//! (`NAME.png`, `NAME.tif`, …), or a map of the wave state or a preview by an inner
//! extension (`NAME.normal.png`, `NAME.disp.tif`, `NAME.preview.png`, …); every map is
//! also written as float EXR (`NAME.disp.exr`, `NAME.normal.exr`, …).

use std::path::Path;

use serde::Serialize;

use crate::error::{Error, Result};

/// Output formats of the height, chosen by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Format {
    /// `.png`: 16-bit grayscale, heights mapped linearly to 0..65535.
    Png16,
    /// `.tif`, `.tiff`: 32-bit float, one channel, meters, GeoTIFF spacing.
    Tiff32,
    /// `.exr`: OpenEXR, one float channel `Y`, meters.
    Exr,
    /// `.obj`: triangle mesh with normals and texture coordinates, meters.
    Obj,
    /// `.glb`: binary glTF 2.0 mesh, +Y up, meters.
    Glb,
    /// `.r16`, `.raw`: unsigned 16-bit samples, no header.
    R16,
    /// `.r32`: 32-bit float samples in meters, no header.
    R32,
}

/// The kind of map an output name asks for (`NAME.KIND.ext`), if any.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MapKind {
    Normal,
    Foam,
    Jacobian,
    Displacement,
}

/// How a map is stored: its usual image (8-bit PNG normals, 16-bit PNG foam, float TIFF
/// Jacobian and displacement) or float EXR.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MapEncoding {
    Image,
    Exr,
}

/// Extensions of the height formats, for error messages and the README (the first of a
/// format is its usual one).
pub const EXTENSIONS: &[(&str, Format)] = &[
    ("png", Format::Png16),
    ("tif", Format::Tiff32),
    ("tiff", Format::Tiff32),
    ("exr", Format::Exr),
    ("obj", Format::Obj),
    ("glb", Format::Glb),
    ("r16", Format::R16),
    ("raw", Format::R16),
    ("r32", Format::R32),
];

/// What an output file name asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputKind {
    /// The height field in a format.
    Height(Format),
    /// A map of the wave state, in its usual image format or as EXR.
    Map(MapKind, MapEncoding),
    /// A shaded perspective view (8-bit RGB PNG, JPEG or WebP).
    Preview,
}

/// An inner extension (`NAME.KIND.ext`): its kind, the outer extensions it is written as
/// (the first named in errors; `exr` writes a map as float EXR), and whether another outer
/// extension is an error (maps) or leaves the name to the height formats (previews).
struct Inner {
    name: &'static str,
    outer: &'static [&'static str],
    kind: OutputKind,
    strict: bool,
}

const INNER: &[Inner] = &[
    Inner {
        name: "normal",
        outer: &["png", "exr"],
        kind: OutputKind::Map(MapKind::Normal, MapEncoding::Image),
        strict: true,
    },
    Inner {
        name: "foam",
        outer: &["png", "exr"],
        kind: OutputKind::Map(MapKind::Foam, MapEncoding::Image),
        strict: true,
    },
    Inner {
        name: "jacobian",
        outer: &["tif", "tiff", "exr"],
        kind: OutputKind::Map(MapKind::Jacobian, MapEncoding::Image),
        strict: true,
    },
    Inner {
        name: "disp",
        outer: &["tif", "tiff", "exr"],
        kind: OutputKind::Map(MapKind::Displacement, MapEncoding::Image),
        strict: true,
    },
    Inner {
        name: "preview",
        outer: &["png", "jpg", "jpeg", "webp"],
        kind: OutputKind::Preview,
        strict: false,
    },
];

impl OutputKind {
    /// What `path` names (case-insensitive): a map or a preview by its inner extension,
    /// else a height format by its extension.
    pub fn of_path(path: &Path) -> Result<Self> {
        match inner_kind(path) {
            Ok(Some(kind)) => Ok(kind),
            Ok(None) => Format::from_path(path).map(OutputKind::Height),
            Err(message) => Err(Error::Output {
                path: path.to_path_buf(),
                message,
            }),
        }
    }

    /// What follows `NAME.` in the file name of this kind (its usual extensions).
    pub fn suffix(&self) -> String {
        match self {
            OutputKind::Height(f) => f.extension().to_string(),
            OutputKind::Map(kind, MapEncoding::Exr) => {
                let i = INNER
                    .iter()
                    .find(|i| i.kind == OutputKind::Map(*kind, MapEncoding::Image))
                    .expect("every map is in the table");
                format!("{}.exr", i.name)
            }
            other => {
                let i = INNER
                    .iter()
                    .find(|i| i.kind == *other)
                    .expect("every map and the preview are in the table");
                format!("{}.{}", i.name, i.outer[0])
            }
        }
    }
}

/// The map or preview `path` names (`x.normal.png` → a normal map), or None for other
/// names; an error text when the inner name is a map's with the wrong outer extension.
pub(crate) fn inner_kind(path: &Path) -> std::result::Result<Option<OutputKind>, String> {
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or_default()
        .to_ascii_lowercase();
    let mut parts = name.rsplitn(3, '.');
    let (Some(ext), Some(inner), Some(_stem)) = (parts.next(), parts.next(), parts.next()) else {
        return Ok(None);
    };
    let Some(i) = INNER.iter().find(|i| i.name == inner) else {
        return Ok(None);
    };
    if i.outer.contains(&ext) {
        Ok(Some(match i.kind {
            OutputKind::Map(kind, _) if ext == "exr" => OutputKind::Map(kind, MapEncoding::Exr),
            other => other,
        }))
    } else if i.strict {
        let (n, e) = (i.name, i.outer[0]);
        Err(format!(
            "a .{n} map is written as .{n}.{e} (got .{n}.{ext})"
        ))
    } else {
        Ok(None)
    }
}

/// Every file-name ending an output may have, from the tables above: the height formats
/// (`.png`, `.tif`, …), then each map and the preview with each of its extensions
/// (`.normal.png`, `.normal.exr`, …). The help of `-o` lists them all (tested).
pub fn all_suffixes() -> Vec<String> {
    EXTENSIONS
        .iter()
        .map(|(e, _)| format!(".{e}"))
        .chain(
            INNER
                .iter()
                .flat_map(|i| i.outer.iter().map(move |o| format!(".{}.{o}", i.name))),
        )
        .collect()
}

impl Format {
    /// Meshes: OBJ and glTF.
    pub fn is_mesh(&self) -> bool {
        matches!(self, Format::Obj | Format::Glb)
    }

    /// Headerless samples: `.r16` and `.r32`.
    pub fn is_raw(&self) -> bool {
        matches!(self, Format::R16 | Format::R32)
    }

    /// Formats that `--tiles` splits.
    pub fn is_tiled(&self) -> bool {
        self.is_mesh() || self.is_raw()
    }

    /// The usual extension of the format (without the dot).
    pub fn extension(&self) -> &'static str {
        EXTENSIONS
            .iter()
            .find(|(_, f)| f == self)
            .map(|(e, _)| *e)
            .expect("every format has an extension")
    }

    /// The format of `path` by its extension (case-insensitive).
    pub fn from_path(path: &Path) -> Result<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .unwrap_or_default();
        EXTENSIONS
            .iter()
            .find(|(e, _)| *e == ext)
            .map(|(_, f)| *f)
            .ok_or_else(|| {
                let allowed: Vec<String> =
                    EXTENSIONS.iter().map(|(e, _)| format!(".{e}")).collect();
                let hint = crate::error::closest(&ext, EXTENSIONS.iter().map(|(e, _)| *e))
                    .filter(|_| !ext.is_empty())
                    .map(|c| format!("; did you mean `.{c}`?"))
                    .unwrap_or_default();
                Error::Output {
                    path: path.to_path_buf(),
                    message: format!(
                        "unknown extension `{}`{hint} (allowed: {})",
                        if ext.is_empty() {
                            "(none)".to_string()
                        } else {
                            format!(".{ext}")
                        },
                        allowed.join(", ")
                    ),
                }
            })
    }
}

impl MapKind {
    /// The map `path` names (`x.normal.png` → Normal), or None for other names; an error
    /// text when the inner name is a map's with the wrong outer extension. The names are
    /// those of the one table in this module.
    pub fn from_path(path: &std::path::Path) -> Result<Option<MapKind>, String> {
        Ok(match inner_kind(path)? {
            Some(OutputKind::Map(kind, _)) => Some(kind),
            _ => None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_table_names_heights_maps_and_previews() {
        let kind = |p: &str| OutputKind::of_path(Path::new(p)).unwrap();
        assert_eq!(kind("a/x.PNG"), OutputKind::Height(Format::Png16));
        let image = |k| OutputKind::Map(k, MapEncoding::Image);
        let exr = |k| OutputKind::Map(k, MapEncoding::Exr);
        assert_eq!(kind("x.normal.png"), image(MapKind::Normal));
        assert_eq!(kind("x.DISP.tiff"), image(MapKind::Displacement));
        assert_eq!(kind("x.disp.exr"), exr(MapKind::Displacement));
        assert_eq!(kind("x.exr"), OutputKind::Height(Format::Exr));
        assert_eq!(kind("x.preview.png"), OutputKind::Preview);
        assert_eq!(kind("x.preview.tif"), OutputKind::Height(Format::Tiff32));
        assert_eq!(kind("normal.png"), OutputKind::Height(Format::Png16));
        assert_eq!(kind("my.sea.png"), OutputKind::Height(Format::Png16));
        let e = OutputKind::of_path(Path::new("x.foam.tif"))
            .unwrap_err()
            .to_string();
        assert!(e.contains(".foam.png"), "{e}");
        for (k, s) in [
            (image(MapKind::Normal), "normal.png"),
            (image(MapKind::Jacobian), "jacobian.tif"),
            (exr(MapKind::Foam), "foam.exr"),
            (exr(MapKind::Normal), "normal.exr"),
            (exr(MapKind::Jacobian), "jacobian.exr"),
            (exr(MapKind::Displacement), "disp.exr"),
            (OutputKind::Preview, "preview.png"),
            (OutputKind::Height(Format::Tiff32), "tif"),
            (OutputKind::Height(Format::R16), "r16"),
        ] {
            assert_eq!(k.suffix(), s);
            assert_eq!(kind(&format!("x.{s}")), k, "x.{s}");
        }
    }
}
