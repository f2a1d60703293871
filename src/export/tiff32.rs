//! 32-bit float TIFF, one channel (SampleFormat = IEEE float), heights in meters,
//! uncompressed (deflate makes float heights barely smaller and ten times slower to write).
//!
//! GeoTIFF tags give GIS tools (GDAL, QGIS) the grid spacing in meters: ModelPixelScale
//! (dx, dy, 0), ModelTiepoint (0, 0, 0, 0, 0, 0) — sample (0, 0) at the origin — and a
//! GeoKey directory declaring a user-defined local engineering frame in meters
//! (GTModelType 32767, ProjLinearUnits 9001 = metre) with points as samples
//! (RasterPixelIsPoint). GIS convention puts model Y = −j·dy, so GDAL reports the pixel
//! size as (dx, −dy) and, for point samples, an origin half a pixel to the upper left.

use std::io::{Seek, Write};

use tiff::encoder::colortype::Gray32Float;
use tiff::encoder::{TiffEncoder, TiffKind};
use tiff::tags::Tag;

use super::sidecar::{CRS_CITATION, GeoTiffInfo, Sidecar};
use super::{Describe, Exporter, FieldOut, Format, HeightMapping, RowSink, WriteSeek};
use crate::grid::{Grid, GridSpec};

/// The float TIFF writer, whole or row by row.
pub struct Tiff32 {
    /// Samples at texel centres (`--sample-at centers`): GTRasterType PixelIsArea, so
    /// pixel (i, j)'s area starts at the tiepoint and its centre is the sample; else
    /// PixelIsPoint, the sample at the tiepoint.
    pub area: bool,
}

impl Exporter for Tiff32 {
    fn format(&self) -> Format {
        Format::Tiff32
    }

    fn write(
        &self,
        field: &FieldOut,
        _part: usize,
        _name: &str,
        out: &mut dyn WriteSeek,
    ) -> std::io::Result<()> {
        write_as(out, field.grid, self.area)
    }

    fn describe(&self, doc: &mut Sidecar, cx: &Describe) {
        doc.geotiff = Some(GeoTiffInfo::new(cx.spec, self.area));
    }

    fn row_sink(&self) -> Option<&dyn RowSink> {
        Some(self)
    }
}

impl RowSink for Tiff32 {
    fn write_rows(
        &self,
        out: &mut dyn WriteSeek,
        spec: &GridSpec,
        _mapping: Option<&HeightMapping>,
        batch_rows: usize,
        fill: &mut dyn FnMut(usize, &mut [f32]) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        write_strips(out, spec, self.area, batch_rows, fill)
    }
}

/// Rows per strip: ~256 KiB strips for 4096-wide grids.
const ROWS_PER_STRIP: u32 = 16;

/// GeoKey directory: version 1.1.0 and four keys (key, location, count, value):
/// GTModelType = user-defined, GTRasterType = PixelIsPoint (PixelIsArea with `area`),
/// GTCitation in the ASCII parameters, ProjLinearUnits = metre.
fn geo_keys(citation_len: u16, area: bool) -> [u16; 20] {
    const ASCII_PARAMS: u16 = 34737;
    [
        1,
        1,
        0,
        4, //
        1024,
        0,
        1,
        32767, //
        1025,
        0,
        1,
        if area { 1 } else { 2 }, //
        1026,
        ASCII_PARAMS,
        citation_len,
        0, //
        3076,
        0,
        1,
        9001,
    ]
}

/// Encodes `grid` as a single-channel float TIFF, samples at the grid's corners.
pub fn write<W: Write + Seek>(w: W, grid: &Grid) -> std::io::Result<()> {
    write_as(w, grid, false)
}

/// Encodes `grid` as a single-channel float TIFF, samples tagged as texel centres
/// (PixelIsArea) when `area`.
pub fn write_as<W: Write + Seek>(w: W, grid: &Grid, area: bool) -> std::io::Result<()> {
    let nx = grid.spec.nx;
    write_strips(
        w,
        &grid.spec,
        area,
        ROWS_PER_STRIP as usize,
        |first, strip| {
            strip.copy_from_slice(&grid.data[first * nx..first * nx + strip.len()]);
            Ok(())
        },
    )
}

/// Files above this size are written as BigTIFF (64-bit offsets); classic TIFF's offsets
/// end at 4 GiB, and the tags and strip tables follow the samples.
pub const BIGTIFF_ABOVE_BYTES: u64 = (4 << 30) - (64 << 20);

/// Writes the float TIFF of a field of `spec` batch by batch, holding one batch in memory:
/// `fill(first_row, batch)` fills the rows `first_row..` (`batch.len()/nx` of them, a
/// multiple of the strip height except at the end), which are then written as strips.
/// BigTIFF when the samples exceed [`BIGTIFF_ABOVE_BYTES`].
pub fn write_strips<W: Write + Seek>(
    w: W,
    spec: &GridSpec,
    area: bool,
    batch_rows: usize,
    fill: impl FnMut(usize, &mut [f32]) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let err = |e: tiff::TiffError| std::io::Error::other(e.to_string());
    if spec.len() as u64 * 4 > BIGTIFF_ABOVE_BYTES {
        encode(
            TiffEncoder::new_big(w).map_err(err)?,
            spec,
            (area, batch_rows),
            fill,
        )
    } else {
        let enc = TiffEncoder::new(w).map_err(err)?;
        encode(enc, spec, (area, batch_rows), fill)
    }
}

fn encode<W: Write + Seek, K: TiffKind>(
    mut enc: TiffEncoder<W, K>,
    spec: &GridSpec,
    (area, batch_rows): (bool, usize),
    mut fill: impl FnMut(usize, &mut [f32]) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let err = |e: tiff::TiffError| std::io::Error::other(e.to_string());
    let (nx, ny) = (spec.nx, spec.ny);
    let too_big = || std::io::Error::other("TIFF sides are limited to 2^32 − 1 samples");
    let mut image = enc
        .new_image::<Gray32Float>(
            u32::try_from(nx).map_err(|_| too_big())?,
            u32::try_from(ny).map_err(|_| too_big())?,
        )
        .map_err(err)?;
    image.rows_per_strip(ROWS_PER_STRIP).map_err(err)?;
    let dir = image.encoder();
    let scale = [spec.dx_m(), spec.dy_m(), 0.0];
    dir.write_tag(Tag::ModelPixelScaleTag, &scale[..])
        .map_err(err)?;
    dir.write_tag(Tag::ModelTiepointTag, &[0.0f64; 6][..])
        .map_err(err)?;
    let citation = format!("{CRS_CITATION}|");
    dir.write_tag(
        Tag::GeoKeyDirectoryTag,
        &geo_keys(citation.len() as u16, area)[..],
    )
    .map_err(err)?;
    dir.write_tag(Tag::GeoAsciiParamsTag, citation.as_str())
        .map_err(err)?;
    let strip = ROWS_PER_STRIP as usize;
    let batch_rows = batch_rows.max(1).div_ceil(strip) * strip;
    let mut buf = Vec::new();
    let mut first = 0;
    while first < ny {
        let rows = batch_rows.min(ny - first);
        buf.resize(rows * nx, 0.0);
        fill(first, &mut buf)?;
        for s in buf.chunks(strip * nx) {
            image.write_strip(s).map_err(err)?;
        }
        first += rows;
    }
    image.finish().map_err(err)
}

/// Reads a single-channel float TIFF: (width, height, samples row by row).
pub fn read(path: &std::path::Path) -> std::io::Result<(usize, usize, Vec<f32>)> {
    let err = |e: tiff::TiffError| std::io::Error::other(e.to_string());
    let file = std::io::BufReader::new(std::fs::File::open(path)?);
    let mut dec = tiff::decoder::Decoder::new(file).map_err(err)?;
    let (w, h) = dec.dimensions().map_err(err)?;
    // The declared size is checked before anything is allocated; the decoder's own limit
    // (256 MiB) would refuse fields above 8192², so it becomes at most four 32-bit floats
    // per pixel (the RGB displacement maps have three): more channels or wider samples
    // (found by fuzzing: a header asking for 12.9 GB) are refused by the decoder.
    crate::limits::check_image_size(w as u64, h as u64, 4).map_err(std::io::Error::other)?;
    let four_channels = (w as usize).saturating_mul(h as usize).saturating_mul(16);
    let mut limits = tiff::decoder::Limits::default();
    limits.decoding_buffer_size = four_channels;
    limits.intermediate_buffer_size = limits.intermediate_buffer_size.max(four_channels);
    let mut dec = dec.with_limits(limits);
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

    #[test]
    fn geotiff_tags_give_the_spacing_in_meters_and_a_local_frame() {
        let g = Grid::zeros(GridSpec::new(8, 4, 20.0, 6.0));
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("g.tif");
        write(std::fs::File::create(&path).unwrap(), &g).unwrap();
        let file = std::io::BufReader::new(std::fs::File::open(&path).unwrap());
        let mut dec = tiff::decoder::Decoder::new(file).unwrap();
        assert_eq!(
            dec.get_tag_f64_vec(Tag::ModelPixelScaleTag).unwrap(),
            [2.5, 1.5, 0.0]
        );
        assert_eq!(
            dec.get_tag_f64_vec(Tag::ModelTiepointTag).unwrap(),
            [0.0; 6]
        );
        let keys = dec.get_tag_u16_vec(Tag::GeoKeyDirectoryTag).unwrap();
        assert_eq!(&keys[..4], [1, 1, 0, 4], "header: version and key count");
        assert!(
            keys.chunks(4).any(|k| k == [3076, 0, 1, 9001]),
            "metre units: {keys:?}"
        );
        let ascii = dec.get_tag_ascii_string(Tag::GeoAsciiParamsTag).unwrap();
        assert_eq!(ascii, format!("{CRS_CITATION}|"));
    }
}
