//! OpenEXR (`.exr`): float images of the field and of its maps, scan lines in increasing
//! order (row 0, y = 0, is the top line, as in every format), 32-bit float by default or
//! 16-bit half with `--exr-half`, uncompressed by default or ZIP (blocks of 16 lines) or
//! PIZ with `--exr-compression`.
//!
//! | file | channels |
//! |---|---|
//! | `NAME.exr` | `Y`: height, m |
//! | `NAME.disp.exr` | `R`, `G`, `B`: the displacement vector in the output's axis convention (`--up y`: (λDx, h, −λDy); `--up z`: (λDx, λDy, h)), m; `A`: foam coverage 0..1 when the sea is choppy |
//! | `NAME.normal.exr` | `R`, `G`, `B`: the unit normal (nx, ny, nz) as the normal map's, unencoded |
//! | `NAME.foam.exr` | `Y`: foam coverage 0..1 |
//! | `NAME.jacobian.exr` | `Y`: the Jacobian J |
//!
//! `Y` is OpenEXR's name for a luminance-only image, which image tools read as grayscale.
//! Uncompressed files are the fastest to write; ZIP and PIZ trade write time for size
//! (figures in the formats page).

use std::io::{Seek, Write};

use exr::prelude::*;

pub use super::options::{ExrCompression, ExrOptions};
use super::sidecar::{EXR_CHANNEL as CHANNEL, ExrInfo, Sidecar};
use super::{Describe, Exporter, FieldOut, Format, WriteSeek};
use crate::grid::Grid;

impl ExrCompression {
    fn encoding(self) -> Encoding {
        let compression = match self {
            ExrCompression::None => Compression::Uncompressed,
            ExrCompression::Zip => Compression::ZIP16,
            ExrCompression::Piz => Compression::PIZ,
        };
        Encoding {
            compression,
            blocks: Blocks::ScanLines,
            line_order: LineOrder::Increasing,
        }
    }
}

/// The OpenEXR writer of heights.
pub struct Exr {
    pub options: ExrOptions,
}

impl Exporter for Exr {
    fn format(&self) -> Format {
        Format::Exr
    }

    fn write(
        &self,
        field: &FieldOut,
        _part: usize,
        _name: &str,
        out: &mut dyn WriteSeek,
    ) -> std::io::Result<()> {
        write_with(out, field.grid, self.options)
    }

    fn describe(&self, doc: &mut Sidecar, _cx: &Describe) {
        doc.exr = Some(ExrInfo {
            channel: CHANNEL,
            sample: self.options.describe(),
        });
    }
}

/// Encodes `grid` as a single-channel f32 EXR, uncompressed.
pub fn write<W: Write + Seek>(w: W, grid: &Grid) -> std::io::Result<()> {
    write_with(w, grid, ExrOptions::default())
}

/// Encodes `grid` as a single-channel EXR (`Y`) with `options`.
pub fn write_with<W: Write + Seek>(w: W, grid: &Grid, options: ExrOptions) -> std::io::Result<()> {
    let size = (grid.spec.nx, grid.spec.ny);
    write_channels(
        w,
        size,
        &[(CHANNEL, &grid.data)],
        options,
        "heights in meters; row 0 is y = 0; grid and parameters in the JSON sidecar",
    )
}

/// Writes named channels of `size` (row-major samples each) with `options`, and a
/// comment. Channels are stored in OpenEXR's alphabetical order, whatever the order given.
pub fn write_channels<W: Write + Seek>(
    w: W,
    size: (usize, usize),
    channels: &[(&str, &[f32])],
    options: ExrOptions,
    comment: &str,
) -> std::io::Result<()> {
    let list: SmallVec<[AnyChannel<FlatSamples>; 4]> = channels
        .iter()
        .map(|(name, v)| {
            let samples = if options.half {
                FlatSamples::F16(v.iter().map(|&x| f16::from_f32(x)).collect())
            } else {
                FlatSamples::F32(v.to_vec())
            };
            AnyChannel::new(*name, samples)
        })
        .collect();
    let attributes = LayerAttributes {
        software_name: Some(Text::from("seasynth")),
        comments: Some(Text::from(comment)),
        ..LayerAttributes::default()
    };
    let layer = Layer::new(
        size,
        attributes,
        options.compression.encoding(),
        AnyChannels::sort(list),
    );
    let image = Image::from_layer(layer);
    // Blocks are compressed in parallel and written in line order: the same bytes at any
    // thread count. Uncompressed blocks gain nothing from threads.
    let writer = image.write();
    let writer = if options.compression == ExrCompression::None {
        writer.non_parallel()
    } else {
        writer
    };
    writer.to_unbuffered(w).map_err(std::io::Error::other)
}

/// Reads the first f32 channel of an EXR: (width, height, channel name, samples).
pub fn read(path: &std::path::Path) -> std::io::Result<(usize, usize, String, Vec<f32>)> {
    let (w, h, mut channels) = read_channels(path)?;
    let (name, v) = channels
        .drain(..)
        .next()
        .ok_or_else(|| std::io::Error::other("no channel"))?;
    Ok((w, h, name, v))
}

/// Reads every channel of an EXR's first layer as f32 (half samples widened), in the
/// file's (alphabetical) order: (width, height, [(name, samples)]).
pub type Channels = (usize, usize, Vec<(String, Vec<f32>)>);

/// See [`Channels`].
pub fn read_channels(path: &std::path::Path) -> std::io::Result<Channels> {
    let image = read_first_flat_layer_from_file(path).map_err(std::io::Error::other)?;
    let layer = image.layer_data;
    let size = layer.size;
    let mut out = Vec::new();
    for channel in layer.channel_data.list {
        let v = match channel.sample_data {
            FlatSamples::F32(v) => v,
            FlatSamples::F16(v) => v.iter().map(|x| x.to_f32()).collect(),
            FlatSamples::U32(_) => return Err(std::io::Error::other("expected float samples")),
        };
        out.push((channel.name.to_string(), v));
    }
    Ok((size.x(), size.y(), out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::GridSpec;

    fn wavy(nx: usize, ny: usize) -> Grid {
        Grid::new(
            GridSpec::new(nx, ny, 1.0, 1.0),
            (0..nx * ny)
                .map(|v| (v as f32 * 0.37).sin() * 3.0 + 1e-7 * v as f32)
                .collect(),
        )
    }

    #[test]
    fn reads_back_bit_exactly_in_one_channel_named_y() {
        let g = wavy(37, 11);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.exr");
        write(std::fs::File::create(&path).unwrap(), &g).unwrap();
        let (w, h, name, v) = read(&path).unwrap();
        assert_eq!((w, h, name.as_str()), (37, 11, "Y"));
        assert!(
            v.iter()
                .zip(&g.data)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "samples differ"
        );
    }

    #[test]
    fn every_compression_is_lossless_and_half_rounds_to_the_nearest_half() {
        let g = wavy(40, 33);
        let dir = tempfile::tempdir().unwrap();
        for compression in [
            ExrCompression::None,
            ExrCompression::Zip,
            ExrCompression::Piz,
        ] {
            for half in [false, true] {
                let path = dir.path().join(format!("{compression:?}{half}.exr"));
                let options = ExrOptions { compression, half };
                let f = std::fs::File::create(&path).unwrap();
                write_with(f, &g, options).unwrap();
                let (_, _, _, v) = read(&path).unwrap();
                for (k, (a, b)) in v.iter().zip(&g.data).enumerate() {
                    let want = if half { f16::from_f32(*b).to_f32() } else { *b };
                    assert_eq!(a.to_bits(), want.to_bits(), "{options:?} sample {k}");
                }
            }
        }
    }

    #[test]
    fn channels_keep_their_names_in_alphabetical_order() {
        let (r, g, b) = (vec![1.0f32; 6], vec![2.0f32; 6], vec![3.0f32; 6]);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rgb.exr");
        let f = std::fs::File::create(&path).unwrap();
        let options = ExrOptions::default();
        write_channels(f, (3, 2), &[("R", &r), ("G", &g), ("B", &b)], options, "").unwrap();
        let (_, _, ch) = read_channels(&path).unwrap();
        let got: Vec<(&str, f32)> = ch.iter().map(|(n, v)| (n.as_str(), v[5])).collect();
        assert_eq!(got, vec![("B", 3.0), ("G", 2.0), ("R", 1.0)]);
    }
}
