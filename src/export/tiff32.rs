//! 32-bit float TIFF, one channel (SampleFormat = IEEE float), heights in meters,
//! uncompressed (deflate makes float heights barely smaller and ten times slower to write).

use std::io::{Seek, Write};

use crate::grid::Grid;

/// Rows per strip: ~256 KiB strips for 4096-wide grids.
const ROWS_PER_STRIP: u32 = 16;

/// Encodes `grid` as a single-channel float TIFF.
pub fn write<W: Write + Seek>(w: W, grid: &Grid) -> std::io::Result<()> {
    let err = |e: tiff::TiffError| std::io::Error::other(e.to_string());
    let mut enc = tiff::encoder::TiffEncoder::new(w).map_err(err)?;
    let mut image = enc
        .new_image::<tiff::encoder::colortype::Gray32Float>(
            grid.spec.nx as u32,
            grid.spec.ny as u32,
        )
        .map_err(err)?;
    image.rows_per_strip(ROWS_PER_STRIP).map_err(err)?;
    image.write_data(&grid.data).map_err(err)
}

/// Reads a single-channel float TIFF: (width, height, samples row by row).
pub fn read(path: &std::path::Path) -> std::io::Result<(usize, usize, Vec<f32>)> {
    let err = |e: tiff::TiffError| std::io::Error::other(e.to_string());
    let file = std::io::BufReader::new(std::fs::File::open(path)?);
    let mut dec = tiff::decoder::Decoder::new(file).map_err(err)?;
    let (w, h) = dec.dimensions().map_err(err)?;
    match dec.read_image().map_err(err)? {
        tiff::decoder::DecodingResult::F32(v) => Ok((w as usize, h as usize, v)),
        _ => Err(std::io::Error::other("expected 32-bit float samples")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::GridSpec;

    #[test]
    fn reads_back_bit_exactly() {
        let spec = GridSpec::new(40, 23, 1.0, 1.0);
        let g = Grid::new(
            spec,
            (0..40 * 23)
                .map(|v| (v as f32 * 0.77).cos() * 1e-3 + v as f32)
                .collect(),
        );
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.tif");
        write(std::fs::File::create(&path).unwrap(), &g).unwrap();
        let (w, h, v) = read(&path).unwrap();
        assert_eq!((w, h), (40, 23));
        assert!(v == g.data, "float samples must read back unchanged");
    }
}
