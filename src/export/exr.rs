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

use exr::image::write::layers::WritableLayers;
use exr::meta::Headers;
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
    // The ZIP writer takes the samples from `channels` itself: its layer only describes
    // the file.
    let zip = options.compression == ExrCompression::Zip;
    let list: SmallVec<[AnyChannel<FlatSamples>; 4]> = channels
        .iter()
        .map(|(name, v)| {
            let v = if zip { &[][..] } else { *v };
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
    if zip {
        let headers = image.layer_data.infer_headers(&image.attributes);
        return write_zip(w, size, channels, options.half, headers);
    }
    // PIZ blocks are compressed in parallel and written in line order: the same bytes at
    // any thread count. Uncompressed blocks gain nothing from threads.
    let writer = image.write();
    let writer = if options.compression == ExrCompression::None {
        writer.non_parallel()
    } else {
        writer
    };
    writer.to_unbuffered(w).map_err(std::io::Error::other)
}

/// Scan lines per block of a ZIP file (OpenEXR's ZIP, 16 lines).
const ZIP_LINES: usize = 16;

/// The deflate level of ZIP blocks: miniz's fastest, about four times faster than the
/// level 4 of the `exr` crate's own encoder for files ~5 % larger (see the formats page).
const ZIP_LEVEL: u8 = 1;

/// Writes a ZIP scan-line file with `headers` (inferred from the same layer): the blocks
/// of 16 lines are compressed on every thread of the pool, then written in line order, so
/// the file is the same bytes at any thread count.
fn write_zip<W: Write + Seek>(
    w: W,
    size: (usize, usize),
    channels: &[(&str, &[f32])],
    half: bool,
    headers: Headers,
) -> std::io::Result<()> {
    use exr::block::chunk::{Chunk, CompressedBlock, CompressedScanLineBlock};
    use exr::block::writer::ChunksWriter;
    use rayon::prelude::*;
    // OpenEXR stores the channels of each line in alphabetical order.
    let mut sorted: Vec<&(&str, &[f32])> = channels.iter().collect();
    sorted.sort_by_key(|(name, _)| *name);
    let planes: Vec<&[f32]> = sorted.iter().map(|(_, v)| *v).collect();
    let blocks: Vec<Vec<u8>> = (0..size.1.div_ceil(ZIP_LINES))
        .into_par_iter()
        .map(|b| {
            let lines = b * ZIP_LINES..((b + 1) * ZIP_LINES).min(size.1);
            zip_block(&block_bytes(&planes, size.0, lines, half))
        })
        .collect();
    let write = std::io::BufWriter::new(w);
    exr::block::write(write, headers, true, |_, chunks| {
        for (b, data) in blocks.into_iter().enumerate() {
            let block = CompressedScanLineBlock {
                y_coordinate: (b * ZIP_LINES) as i32,
                compressed_pixels_le: data,
            };
            let chunk = Chunk {
                layer_index: 0,
                compressed_block: CompressedBlock::ScanLine(block),
            };
            chunks.write_chunk(b, chunk)?;
        }
        Ok(())
    })
    .map_err(std::io::Error::other)
}

/// The uncompressed bytes of the scan lines `lines`: for each line, each channel's samples
/// in turn, little-endian f32 or f16.
fn block_bytes(
    planes: &[&[f32]],
    width: usize,
    lines: std::ops::Range<usize>,
    half: bool,
) -> Vec<u8> {
    let sample = if half { 2 } else { 4 };
    let mut out = Vec::with_capacity(lines.len() * planes.len() * width * sample);
    for y in lines {
        for plane in planes {
            let row = &plane[y * width..(y + 1) * width];
            if half {
                out.extend(row.iter().flat_map(|&v| f16::from_f32(v).to_le_bytes()));
            } else {
                out.extend(row.iter().flat_map(|&v| v.to_le_bytes()));
            }
        }
    }
    out
}

/// OpenEXR's ZIP block: the bytes split into even and odd positions, each byte replaced
/// by its difference to the one before (+ 128, wrapping), then zlib. A block that would
/// not shrink is stored as it is, as OpenEXR requires.
fn zip_block(raw: &[u8]) -> Vec<u8> {
    let half = raw.len().div_ceil(2);
    let mut split = vec![0u8; raw.len()];
    for (i, &v) in raw.iter().enumerate() {
        split[if i % 2 == 0 { i / 2 } else { half + i / 2 }] = v;
    }
    let mut previous = split.first().copied().unwrap_or(0);
    for v in split.iter_mut().skip(1) {
        let here = *v;
        *v = here.wrapping_sub(previous).wrapping_add(128);
        previous = here;
    }
    let packed = miniz_oxide::deflate::compress_to_vec_zlib(&split, ZIP_LEVEL);
    if packed.len() < raw.len() {
        packed
    } else {
        raw.to_vec()
    }
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
    fn zip_files_of_several_channels_decode_to_the_uncompressed_samples() {
        // 33 lines: two whole blocks of 16 and a last block of one line; the noise channel
        // does not shrink, so its blocks are stored as they are.
        let (nx, ny) = (29, 33);
        let wave = wavy(nx, ny).data;
        let noise: Vec<f32> = (0..nx * ny)
            .map(|i| f32::from_bits((i as u32).wrapping_mul(2_654_435_761) >> 2))
            .collect();
        let ramp: Vec<f32> = (0..nx * ny).map(|i| i as f32 * 0.25 - 7.0).collect();
        let ch = [("R", &wave[..]), ("A", &noise[..]), ("G", &ramp[..])];
        let dir = tempfile::tempdir().unwrap();
        for half in [false, true] {
            let read_back = |compression| {
                let path = dir.path().join(format!("{compression:?}{half}.exr"));
                let options = ExrOptions { compression, half };
                let f = std::fs::File::create(&path).unwrap();
                write_channels(f, (nx, ny), &ch, options, "test").unwrap();
                read_channels(&path).unwrap()
            };
            let plain = read_back(ExrCompression::None);
            let zip = read_back(ExrCompression::Zip);
            assert_eq!((zip.0, zip.1), (nx, ny));
            assert_eq!(plain.2.len(), 3);
            for ((na, a), (nb, b)) in plain.2.iter().zip(&zip.2) {
                assert_eq!(na, nb);
                let same = a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
                assert!(same, "channel {na}, half {half}: samples differ");
            }
        }
    }

    #[test]
    fn zip_blocks_that_do_not_shrink_are_stored_raw() {
        // xorshift64 bytes: nothing for deflate to find.
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let raw: Vec<u8> = (0..4096)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 56) as u8
            })
            .collect();
        assert_eq!(zip_block(&raw), raw);
        let flat = vec![7u8; 4096];
        assert!(zip_block(&flat).len() < 100);
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
