//! The PNG encoder of height, foam and normal maps: rows filtered with Up, the filtered
//! bytes cut into pieces of [`PIECE`] bytes (by size, never by thread count), each piece
//! deflated on its own in parallel with fdeflate's fast PNG coder and ended by a sync
//! flush (an empty stored block), the pieces joined into one zlib stream with one Adler-32
//! combined from the pieces' own, each piece in its own `IDAT` chunk.
//!
//! A piece's stream from fdeflate is one final dynamic-Huffman block whose end-of-block
//! code ends with a 1 bit; the final flag is cleared and the stored block appended after
//! that bit. A piece whose stream does not look so (another fdeflate) is stored instead,
//! so the file stays valid either way.

use std::io::Write;

use rayon::prelude::*;

/// Filtered bytes per independently deflated piece: small enough that a 1024² map keeps
/// both cores busy, large enough that the ~60 bytes of block header per piece are noise.
pub const PIECE: usize = 1 << 18;

/// The sample layouts seasynth writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// One 16-bit gray sample per pixel (big-endian, as PNG stores them).
    Gray16,
    /// Three 8-bit samples per pixel.
    Rgb8,
}

impl Layout {
    fn bytes_per_pixel(self) -> usize {
        match self {
            Layout::Gray16 => 2,
            Layout::Rgb8 => 3,
        }
    }

    /// (bit depth, color type) of the IHDR chunk.
    fn ihdr(self) -> (u8, u8) {
        match self {
            Layout::Gray16 => (16, 0),
            Layout::Rgb8 => (8, 2),
        }
    }
}

/// A PNG being written row by row: [`PngWriter::write_rows`] takes unfiltered rows in
/// order, [`PngWriter::finish`] checks that every row came and ends the file.
pub struct PngWriter<W: Write> {
    w: W,
    row_bytes: usize,
    rows_left: usize,
    /// The last row written (unfiltered), for the Up filter; empty before the first.
    prev: Vec<u8>,
    /// Filtered bytes not yet deflated (less than one piece between calls).
    pending: Vec<u8>,
    adler: u32,
}

impl<W: Write> PngWriter<W> {
    /// Writes the signature, the header and the `tEXt` chunks (keyword, Latin-1 text).
    pub fn new(
        mut w: W,
        (width, height): (usize, usize),
        layout: Layout,
        texts: &[(&str, &str)],
    ) -> std::io::Result<Self> {
        let side = |n: usize| {
            u32::try_from(n)
                .ok()
                .filter(|&v| (1..=i32::MAX as u32).contains(&v))
                .ok_or_else(|| std::io::Error::other("PNG sides are 1 to 2^31 − 1 samples"))
        };
        let (wd, ht) = (side(width)?, side(height)?);
        w.write_all(b"\x89PNG\r\n\x1a\n")?;
        let (depth, color) = layout.ihdr();
        let mut ihdr = Vec::with_capacity(13);
        ihdr.extend_from_slice(&wd.to_be_bytes());
        ihdr.extend_from_slice(&ht.to_be_bytes());
        ihdr.extend_from_slice(&[depth, color, 0, 0, 0]);
        chunk(&mut w, b"IHDR", &ihdr)?;
        for (key, text) in texts {
            let mut t = Vec::with_capacity(key.len() + 1 + text.len());
            t.extend_from_slice(key.as_bytes());
            t.push(0);
            t.extend_from_slice(text.as_bytes());
            chunk(&mut w, b"tEXt", &t)?;
        }
        // The zlib header (deflate, 32 KiB window, fastest), as fdeflate writes it.
        chunk(&mut w, b"IDAT", &[0x78, 0x01])?;
        Ok(Self {
            w,
            row_bytes: width * layout.bytes_per_pixel(),
            rows_left: height,
            prev: Vec::new(),
            pending: Vec::new(),
            adler: 1,
        })
    }

    /// Filters and compresses whole unfiltered rows (`rows.len()` a multiple of the row
    /// length), the next ones of the image.
    pub fn write_rows(&mut self, rows: &[u8]) -> std::io::Result<()> {
        let rb = self.row_bytes;
        if rows.len() % rb != 0 || rows.len() / rb > self.rows_left {
            return Err(std::io::Error::other(
                "PNG rows do not match the image size",
            ));
        }
        let n = rows.len() / rb;
        if n == 0 {
            return Ok(());
        }
        self.rows_left -= n;
        let start = self.pending.len();
        self.pending.resize(start + n * (rb + 1), 0);
        let prev = &self.prev;
        self.pending[start..]
            .par_chunks_mut(rb + 1)
            .enumerate()
            .for_each(|(r, out)| {
                let row = &rows[r * rb..(r + 1) * rb];
                let above = if r > 0 {
                    &rows[(r - 1) * rb..r * rb]
                } else {
                    prev.as_slice()
                };
                out[0] = 2; // Up
                if above.is_empty() {
                    out[1..].copy_from_slice(row);
                } else {
                    for ((o, &a), &b) in out[1..].iter_mut().zip(row).zip(above) {
                        *o = a.wrapping_sub(b);
                    }
                }
            });
        self.prev.clear();
        self.prev.extend_from_slice(&rows[(n - 1) * rb..]);
        let whole = self.pending.len() / PIECE * PIECE;
        if whole > 0 {
            self.deflate(whole)?;
            self.pending.drain(..whole);
        }
        Ok(())
    }

    /// Deflates `pending[..len]` in pieces, in parallel, and writes them in order.
    fn deflate(&mut self, len: usize) -> std::io::Result<()> {
        let pieces: Vec<(Vec<u8>, u32, u32)> = self.pending[..len]
            .par_chunks(PIECE)
            .map(|p| {
                let (z, adler) = deflate_piece(p);
                (z, adler, p.len() as u32)
            })
            .collect();
        for (z, adler, n) in pieces {
            chunk(&mut self.w, b"IDAT", &z)?;
            self.adler = adler32_combine(self.adler, adler, n);
        }
        Ok(())
    }

    /// Deflates what is left, ends the zlib stream and the file; returns the writer.
    pub fn finish(mut self) -> std::io::Result<W> {
        if self.rows_left != 0 {
            return Err(std::io::Error::other(format!(
                "PNG ended {} rows short",
                self.rows_left
            )));
        }
        let len = self.pending.len();
        self.deflate(len)?;
        // A final empty block with fixed codes, then the Adler-32 of all the data.
        let mut end = vec![0x03, 0x00];
        end.extend_from_slice(&self.adler.to_be_bytes());
        chunk(&mut self.w, b"IDAT", &end)?;
        chunk(&mut self.w, b"IEND", &[])?;
        Ok(self.w)
    }
}

/// Writes one PNG chunk: length, type, data, CRC-32 of type and data.
fn chunk<W: Write>(w: &mut W, kind: &[u8; 4], data: &[u8]) -> std::io::Result<()> {
    let len = u32::try_from(data.len()).map_err(|_| std::io::Error::other("PNG chunk too big"))?;
    let mut crc = crc32fast::Hasher::new();
    crc.update(kind);
    crc.update(data);
    w.write_all(&len.to_be_bytes())?;
    w.write_all(kind)?;
    w.write_all(data)?;
    w.write_all(&crc.finalize().to_be_bytes())
}

/// One piece as raw deflate blocks ending byte-aligned and not final, and the piece's
/// Adler-32.
fn deflate_piece(data: &[u8]) -> (Vec<u8>, u32) {
    let mut z = fdeflate::compress_to_vec(data);
    let n = z.len();
    // zlib header (2 bytes), the block, Adler-32 (4 bytes). The block's first 3 bits:
    // BFINAL = 1, BTYPE = 2 (dynamic Huffman).
    if n > 6 && z[2] & 7 == 0b101 && z[n - 5] != 0 {
        let adler = u32::from_be_bytes([z[n - 4], z[n - 3], z[n - 2], z[n - 1]]);
        z.truncate(n - 4);
        z[2] &= !1;
        // The end-of-block code ends at the highest set bit of the last byte; the rest are
        // zero padding. An empty stored block's 3 header bits (all 0) go there if they
        // fit, else into one more zero byte; then LEN = 0, NLEN = !0.
        if z[n - 5].leading_zeros() < 3 {
            z.push(0);
        }
        z.extend_from_slice(&[0, 0, 0xff, 0xff]);
        z.drain(..2);
        (z, adler)
    } else {
        (stored(data), adler32(data))
    }
}

/// `data` as non-final stored blocks.
fn stored(data: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(data.len() + data.len() / 65535 * 5 + 5);
    for b in data.chunks(65535) {
        let len = b.len() as u16;
        out.push(0);
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&(!len).to_le_bytes());
        out.extend_from_slice(b);
    }
    out
}

const ADLER_MOD: u32 = 65521;

/// Adler-32 of `data` (RFC 1950).
pub fn adler32(data: &[u8]) -> u32 {
    let (mut a, mut b) = (1u32, 0u32);
    for block in data.chunks(5552) {
        for &x in block {
            a += x as u32;
            b += a;
        }
        a %= ADLER_MOD;
        b %= ADLER_MOD;
    }
    (b << 16) | a
}

/// The Adler-32 of A followed by B from those of A and of B (B `len_b` bytes long).
pub fn adler32_combine(adler_a: u32, adler_b: u32, len_b: u32) -> u32 {
    let m = ADLER_MOD as u64;
    let rem = len_b as u64 % m;
    let (a1, b1) = ((adler_a & 0xffff) as u64, (adler_a >> 16) as u64);
    let (a2, b2) = ((adler_b & 0xffff) as u64, (adler_b >> 16) as u64);
    let a = (a1 + a2 + m - 1) % m;
    let b = (b1 + b2 + rem * a1 + m - rem) % m;
    ((b << 16) | a) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lcg(n: usize, seed: u64) -> Vec<u8> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (s >> 56) as u8
            })
            .collect()
    }

    /// Encodes `rows` in `batches` calls and decodes the file with the png crate.
    fn roundtrip(layout: Layout, (w, h): (usize, usize), data: &[u8], batches: usize) -> Vec<u8> {
        let mut enc = PngWriter::new(Vec::new(), (w, h), layout, &[("Comment", "a test")]).unwrap();
        let rb = w * layout.bytes_per_pixel();
        let per = h.div_ceil(batches).max(1);
        for rows in data.chunks(per * rb) {
            enc.write_rows(rows).unwrap();
        }
        let file = enc.finish().unwrap();
        let mut reader = png::Decoder::new(std::io::Cursor::new(&file))
            .read_info()
            .unwrap();
        let texts: Vec<_> = reader
            .info()
            .uncompressed_latin1_text
            .iter()
            .map(|t| (t.keyword.clone(), t.text.clone()))
            .collect();
        assert_eq!(texts, [("Comment".to_string(), "a test".to_string())]);
        let mut out = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut out).unwrap();
        assert_eq!((info.width as usize, info.height as usize), (w, h));
        out.truncate(info.buffer_size());
        assert_eq!(out, data, "{layout:?} {w}×{h} in {batches} batches");
        file
    }

    #[test]
    fn decodes_to_the_same_samples_across_pieces_and_batches() {
        // Random (stored-like), smooth, zeros (long runs across piece boundaries), and
        // sizes that cut pieces mid-row; the file bytes do not depend on the batches.
        let cases: Vec<(Layout, (usize, usize), Vec<u8>)> = vec![
            (Layout::Gray16, (300, 700), lcg(300 * 700 * 2, 1)),
            (Layout::Rgb8, (513, 401), lcg(513 * 401 * 3, 2)),
            (Layout::Gray16, (1024, 300), vec![0; 1024 * 300 * 2]),
            (
                Layout::Gray16,
                (777, 333),
                (0..777 * 333)
                    .map(|i| {
                        (((i % 777) as f64 * 0.01 + (i / 777) as f64 * 0.005).sin() * 30000.0
                            + 32768.0) as u16
                    })
                    .flat_map(|v| v.to_be_bytes())
                    .collect(),
            ),
            (Layout::Rgb8, (1, 1), vec![1, 2, 3]),
        ];
        for (layout, size, data) in cases {
            let one = roundtrip(layout, size, &data, 1);
            let many = roundtrip(layout, size, &data, 7);
            assert_eq!(one, many, "bytes independent of the batching");
        }
    }

    #[test]
    fn every_end_of_piece_padding_joins() {
        // Pieces ending at every bit position of their last byte: data lengths around a
        // piece boundary.
        for extra in 0..24 {
            let w = 64;
            let h = (2 * PIECE) / (w * 2 + 1) + 1 + extra;
            let data = lcg(w * h * 2, extra as u64 + 10);
            roundtrip(Layout::Gray16, (w, h), &data, 3);
        }
    }

    #[test]
    fn adler_of_a_join_is_the_combination() {
        let data = lcg(100_000, 7);
        for cut in [0, 1, 5552, 65521, 99_999, 100_000] {
            let (a, b) = data.split_at(cut);
            assert_eq!(
                adler32_combine(adler32(a), adler32(b), b.len() as u32),
                adler32(&data),
                "cut at {cut}"
            );
        }
        assert_eq!(adler32(b"Wikipedia"), 0x11E6_0398);
    }

    #[test]
    fn rows_must_fit_the_image() {
        let mut enc = PngWriter::new(Vec::new(), (4, 2), Layout::Rgb8, &[]).unwrap();
        assert!(enc.write_rows(&[0; 13]).is_err());
        enc.write_rows(&[0; 12]).unwrap();
        assert!(enc.finish().is_err(), "a missing row is an error");
    }
}
