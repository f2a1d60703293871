//! The files of a batch's jobs: the file name suffix of each `--format` entry, the hash
//! that fixes a job's files, which files a complete job left, and the staging files a
//! killed run left.

use std::path::Path;

use crate::error::{Error, ParamError};
use crate::export::Format;
use crate::pipeline::jobs::FileKind;

/// A hash of `bytes` as 16 hex digits (the project's fixed hash, 8 bytes a word).
pub fn hash_hex(bytes: &[u8]) -> String {
    let mut words: Vec<u64> = bytes
        .chunks(8)
        .map(|c| {
            let mut w = [0u8; 8];
            w[..c.len()].copy_from_slice(c);
            u64::from_le_bytes(w)
        })
        .collect();
    words.push(bytes.len() as u64);
    format!("{:016x}", crate::rng::hash_words(&words))
}

/// The file name suffix of each `--format` entry, and whether one is a height output
/// (which carries the sidecar).
pub fn suffixes(formats: &[String]) -> Result<Vec<String>, Error> {
    let mut out: Vec<String> = Vec::new();
    let mut height = false;
    for f in formats {
        let f = f.trim().to_ascii_lowercase();
        let suffix = match FileKind::parse(&f) {
            Ok(FileKind::Png) | Ok(FileKind::Tif) | Ok(FileKind::Exr) => {
                height = true;
                f.clone()
            }
            Ok(k) => k.suffix(),
            Err(_) => {
                Format::from_path(Path::new(&format!("x.{f}"))).map_err(|_| {
                    let names = [
                        "png", "tif", "tiff", "exr", "r16", "r32", "raw", "obj", "glb", "normal",
                        "foam", "jacobian", "disp", "preview", "disp.exr", "normal.exr",
                        "foam.exr", "jacobian.exr",
                    ];
                    Error::Param(ParamError {
                        name: "--format".into(),
                        allowed: "png, tif, tiff, exr, r16, r32, raw, obj, glb, normal, foam, jacobian, disp, preview, or a map as EXR (disp.exr, normal.exr, foam.exr, jacobian.exr)".into(),
                        got: format!("{f}{}", crate::error::did_you_mean(&f, names)),
                    })
                })?;
                height = true;
                f.clone()
            }
        };
        if !out.contains(&suffix) {
            out.push(suffix);
        }
    }
    if !height {
        return Err(Error::Param(ParamError {
            name: "--format".into(),
            allowed: "a list with at least one height output (png, tif, exr, r16, r32, raw, obj or glb), which carries the job's sidecar".into(),
            got: formats.join(","),
        }));
    }
    Ok(out)
}

/// The files of a complete job, relative to the folder, and its statistics, from its
/// sidecar `DIR/NAME.json`: the files the sidecar lists (the height outputs, or their
/// tiles), the tile index, the maps and previews (`NAME.KIND.ext`, which the sidecar does
/// not list), then the sidecar. `None` unless the sidecar holds `hash` as the job's
/// `batch.hash` and every one of those files is there.
pub fn complete_files(
    name: &str,
    suffixes: &[String],
    hash: &str,
    dir: &Path,
) -> Option<(Vec<String>, crate::grid::Stats)> {
    let side = format!("{name}.json");
    let doc: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join(&side)).ok()?).ok()?;
    if doc.pointer("/batch/hash")?.as_str()? != hash {
        return None;
    }
    let mut files = Vec::new();
    for f in doc.get("files")?.as_array()? {
        files.push(f.get("file")?.as_str()?.to_string());
    }
    if let Some(t) = doc.get("tiles_index").and_then(|t| t.as_str()) {
        files.push(t.to_string());
    }
    files.extend(
        suffixes
            .iter()
            .filter(|s| s.contains('.'))
            .map(|s| format!("{name}.{s}")),
    );
    files.push(side);
    if !files.iter().all(|f| dir.join(f).is_file()) {
        return None;
    }
    let stats = serde_json::from_value(doc.get("stats")?.clone()).ok()?;
    Some((files, stats))
}

/// Removes the temporary files a killed run left for these jobs (`.NAME.….part`, the
/// staging names of `export::Staged`). Only this run's jobs: shards sharing the folder
/// keep theirs.
pub fn remove_stale_temporaries<'a>(
    dir: &Path,
    names: impl Iterator<Item = &'a str>,
) -> Result<(), Error> {
    let stale = super::files_named(dir, |n| n.starts_with('.') && n.ends_with(".part"))
        .map_err(|e| Error::io(dir, e))?;
    if stale.is_empty() {
        return Ok(());
    }
    let names: std::collections::HashSet<&str> = names.collect();
    for p in stale {
        let file = p.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        // `.NAME.SUFFIX.RANDOM.part` or a tile's `.NAME_x0_y0.SUFFIX.RANDOM.part`.
        let inner = &file[1..file.len() - ".part".len()];
        let ours = names.iter().any(|n| {
            inner
                .strip_prefix(n)
                .is_some_and(|rest| rest.starts_with('.') || rest.starts_with("_x"))
        });
        if ours {
            std::fs::remove_file(&p).map_err(|e| Error::io(&p, e))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_give_suffixes_and_need_a_height_output() {
        let s = suffixes(&["png".into(), "normal".into(), "tif".into(), "obj".into()]).unwrap();
        assert_eq!(s, ["png", "normal.png", "tif", "obj"]);
        assert!(
            suffixes(&["normal".into()]).is_err(),
            "no sidecar without a height output"
        );
        let e = suffixes(&["gif".into()]).unwrap_err().to_string();
        assert!(e.contains("gif") && e.contains("png"), "{e}");
    }

    #[test]
    fn stale_temporaries_of_other_jobs_are_left_alone() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path();
        for f in [
            ".0_a=1.png.X1.part",
            ".0_a=1_x0_y1.obj.X2.part",
            ".1_a=2.png.X3.part",
            ".0_a=10.png.X4.part",
            "0_a=1.png",
        ] {
            std::fs::write(p.join(f), b"x").unwrap();
        }
        remove_stale_temporaries(p, ["0_a=1"].into_iter()).unwrap();
        let mut left: Vec<String> = std::fs::read_dir(p)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(
            left,
            [".0_a=10.png.X4.part", ".1_a=2.png.X3.part", "0_a=1.png"],
            "only job 0_a=1's staging files go"
        );
    }
}
