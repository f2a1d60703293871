//! Reading a one-channel 32-bit float TIFF in meters.

use std::path::{Path, PathBuf};

use serde_json::Value;

use super::{HeightReader, Heights, ImageKind, input_error};
use crate::error::Error;

/// The float TIFF reader (classic and BigTIFF, either byte order).
pub struct Tiff32Reader;

impl HeightReader for Tiff32Reader {
    fn kind(&self) -> ImageKind {
        ImageKind::TiffF32
    }

    fn sniff(&self, head: &[u8]) -> bool {
        head.starts_with(b"II*\0")
            || head.starts_with(b"MM\0*")
            || head.starts_with(b"II+\0")
            || head.starts_with(b"MM\0+")
    }

    fn read(&self, path: &Path, _sidecar: Option<&(PathBuf, Value)>) -> Result<Heights, Error> {
        let (w, h, v) = crate::export::tiff32::read(path).map_err(|e| {
            input_error(
                path,
                format!("not a readable one-channel 32-bit float TIFF: {e}"),
            )
        })?;
        if v.len() != w * h {
            return Err(input_error(
                path,
                format!(
                    "expected one channel of 32-bit float samples, found {} values for {w}×{h} pixels",
                    v.len()
                ),
            ));
        }
        Ok(Heights {
            nx: w,
            ny: h,
            data: v,
            quantization_step_m: None,
        })
    }
}
