//! Reading a 16-bit grayscale PNG, in meters by its sidecar's mapping.

use std::path::{Path, PathBuf};

use serde_json::Value;

use super::{HeightReader, Heights, ImageKind, input_error};
use crate::error::Error;
use crate::export::HeightMapping;

/// The 16-bit PNG reader: needs the sidecar's `mapping`.
pub struct Png16Reader;

impl HeightReader for Png16Reader {
    fn kind(&self) -> ImageKind {
        ImageKind::Png16
    }

    fn sniff(&self, head: &[u8]) -> bool {
        head.starts_with(b"\x89PNG\r\n\x1a\n")
    }

    fn read(&self, path: &Path, sidecar: Option<&(PathBuf, Value)>) -> Result<Heights, Error> {
        let (w, h, v) = crate::export::png16::read(path)
            .map_err(|e| input_error(path, format!("not a readable 16-bit grayscale PNG: {e}")))?;
        let Some((side, doc)) = sidecar else {
            let want = crate::export::sidecar::path_for(path);
            return Err(input_error(
                path,
                format!(
                    "has no sidecar {}: the PNG's heights cannot be converted to meters (analyze the .tif, or keep the .json beside the PNG)",
                    want.file_name()
                        .map(|n| n.to_string_lossy())
                        .unwrap_or_default()
                ),
            ));
        };
        let mapping = doc.get("mapping").and_then(|m| {
            let lo = m.get("min_m")?.as_f64()?;
            let hi = m.get("max_m")?.as_f64()?;
            Some(HeightMapping {
                min_m: lo,
                max_m: hi,
            })
        });
        let Some(mapping) = mapping.filter(|m| m.min_m.is_finite() && m.max_m.is_finite()) else {
            return Err(input_error(
                side,
                "sidecar has no `mapping` {min_m, max_m}: the PNG's heights cannot be converted to meters",
            ));
        };
        Ok(Heights {
            nx: w,
            ny: h,
            data: v.iter().map(|&x| mapping.decode(x) as f32).collect(),
            quantization_step_m: Some(mapping.step_m()),
        })
    }
}
