//! 16-bit grayscale PNG. Samples are big-endian as PNG requires; heights map to 0..65535 by
//! the [`HeightMapping`] (recorded in the sidecar and in a `tEXt` chunk). Written by
//! [`super::png_par`]: the Up filter and fdeflate's fast coder, in pieces of rows
//! compressed in parallel.

use std::io::Write;

use rayon::prelude::*;

use super::png_par::{Layout, PngWriter};
use super::{Exporter, FieldOut, Format, HeightMapping, RowSink, WriteSeek};
use crate::grid::{Grid, GridSpec};

/// The 16-bit grayscale PNG writer, whole or row by row.
pub struct Png16;

impl Exporter for Png16 {
    fn format(&self) -> Format {
        Format::Png16
    }

    fn write(
        &self,
        field: &FieldOut,
        _part: usize,
        _name: &str,
        out: &mut dyn WriteSeek,
    ) -> std::io::Result<()> {
        write(out, field.grid, field.mapping)
    }

    fn uses_mapping(&self) -> bool {
        true
    }

    fn row_sink(&self) -> Option<&dyn RowSink> {
        Some(self)
    }
}

impl RowSink for Png16 {
    fn write_rows(
        &self,
        out: &mut dyn WriteSeek,
        spec: &GridSpec,
        mapping: Option<&HeightMapping>,
        batch_rows: usize,
        fill: &mut dyn FnMut(usize, &mut [f32]) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        let mapping =
            mapping.ok_or_else(|| std::io::Error::other("a 16-bit PNG needs its mapping"))?;
        write_rows(out, (spec.nx, spec.ny), mapping, batch_rows, fill)
    }
}

/// Encodes `grid` as a 16-bit grayscale PNG.
pub fn write<W: Write>(w: W, grid: &Grid, mapping: &HeightMapping) -> std::io::Result<()> {
    let nx = grid.spec.nx;
    // Batches of ~4 MiB of heights.
    let batch = ((4 << 20) / (4 * nx)).max(1);
    write_rows(w, (nx, grid.spec.ny), mapping, batch, |first, rows| {
        rows.copy_from_slice(&grid.data[first * nx..first * nx + rows.len()]);
        Ok(())
    })
}

/// The `Description` text chunk of a height map: its mapping.
fn description(mapping: &HeightMapping) -> String {
    format!(
        "seasynth height map: meters = {} + value * {} (0..65535); row 0 is y = 0",
        mapping.min_m,
        mapping.step_m()
    )
}

/// Writes the PNG of an `nx` × `ny` field batch by batch, holding one batch in memory:
/// `fill(first_row, batch)` fills the heights of rows `first_row..` (`batch.len()/nx` of
/// them, `batch_rows` except at the end). The file's bytes do not depend on `batch_rows`
/// (see [`super::png_par`]).
pub fn write_rows<W: Write>(
    w: W,
    (nx, ny): (usize, usize),
    mapping: &HeightMapping,
    batch_rows: usize,
    mut fill: impl FnMut(usize, &mut [f32]) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let text = description(mapping);
    let mut png = PngWriter::new(w, (nx, ny), Layout::Gray16, &[("Description", &text)])?;
    let batch_rows = batch_rows.max(1);
    let (mut heights, mut bytes) = (Vec::new(), Vec::new());
    let mut first = 0;
    while first < ny {
        let rows = batch_rows.min(ny - first);
        heights.resize(rows * nx, 0.0f32);
        fill(first, &mut heights)?;
        bytes.resize(rows * nx * 2, 0u8);
        bytes
            .par_chunks_mut(nx * 2)
            .zip(heights.par_chunks(nx))
            .for_each(|(out, row)| mapping.encode_be(row, out));
        png.write_rows(&bytes)?;
        first += rows;
    }
    png.finish()?.flush()
}

/// Reads a 16-bit grayscale PNG: (width, height, samples row by row).
pub fn read(path: &std::path::Path) -> std::io::Result<(usize, usize, Vec<u16>)> {
    let file = std::io::BufReader::new(std::fs::File::open(path)?);
    let mut reader = png::Decoder::new(file)
        .read_info()
        .map_err(std::io::Error::other)?;
    let (w, h) = reader.info().size();
    crate::limits::check_image_size(w as u64, h as u64, 2).map_err(std::io::Error::other)?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| std::io::Error::other("PNG too large"))?;
    let mut buf = vec![0u8; size];
    let info = reader.next_frame(&mut buf).map_err(std::io::Error::other)?;
    if info.bit_depth != png::BitDepth::Sixteen || info.color_type != png::ColorType::Grayscale {
        return Err(std::io::Error::other(format!(
            "expected 16-bit grayscale, found {:?} {:?}",
            info.bit_depth, info.color_type
        )));
    }
    let values = buf[..info.buffer_size()]
        .chunks_exact(2)
        .map(|b| u16::from_be_bytes([b[0], b[1]]))
        .collect();
    Ok((info.width as usize, info.height as usize, values))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::GridSpec;

    #[test]
    fn reads_back_within_one_step_of_the_mapping() {
        let spec = GridSpec::new(37, 11, 1.0, 1.0);
        let g = Grid::new(
            spec,
            (0..37 * 11)
                .map(|v| ((v as f32) * 0.1).sin() * 2.5)
                .collect(),
        );
        let st = g.stats();
        let m = HeightMapping {
            min_m: st.min_m,
            max_m: st.max_m,
        };
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        write(std::fs::File::create(&path).unwrap(), &g, &m).unwrap();
        let (w, h, v) = read(&path).unwrap();
        assert_eq!((w, h), (37, 11));
        assert!(
            v.contains(&0) && v.contains(&65535),
            "min..max spans the range"
        );
        for (idx, (&raw, &want)) in v.iter().zip(&g.data).enumerate() {
            let err = (m.decode(raw) - want as f64).abs();
            assert!(
                err <= m.step_m(),
                "sample {idx}: error {err} over one step {}",
                m.step_m()
            );
        }
    }
}
