//! TIFF layouts that libtiff reads and the `tiff` crate refuses, read here with the crate's help:
//!
//! - tiled images whose tiles are listed under the strip tags (`StripOffsets`,
//!   `StripByteCounts`), as libtiff wrote them before 3.0 (libtiff keeps tiles and strips in one
//!   field, so it reads both spellings): the two tags are renamed as the file is read;
//! - old-style LZW (libtiff before 5.0: codes least significant bit first, the code width
//!   growing one code later than TIFF 6.0's LZW), which libtiff recognises from a strip's first
//!   two bytes: the strips are decompressed here with `weezl`, which reads that bit order;
//! - CCITT Group 4 strips of more than 65,535 rows, past the crate's 16-bit count of a strip's
//!   rows: decoded here line by line with `fax`, the crate's own Group 4 decoder.
//!
//! The decompressed bytes are laid out as the crate lays out its own, so that the samples go
//! through the same conversion.

use super::MAX_IMAGE_BYTES;
use std::io::{self, Read, Seek, SeekFrom};
use tiff::decoder::Decoder;
use tiff::tags::{CompressionMethod, Predictor, Tag};

/// A TIFF file read with a few two-byte patches laid over it (the renamed tags).
pub(super) struct Patched<R> {
    inner: R,
    pos: u64,
    patches: Vec<(u64, [u8; 2])>,
}

impl<R: Read + Seek> Patched<R> {
    /// `r` with the strip tags of a tiled first image renamed to the tile tags, when its first
    /// directory has `TileWidth` and the strip tags but no tile tags. A file this cannot parse
    /// is passed on unchanged (the `tiff` crate says what is wrong with it).
    pub(super) fn new(mut inner: R) -> io::Result<Self> {
        let patches = strip_tags_of_tiles(&mut inner).unwrap_or_default();
        let pos = inner.seek(SeekFrom::Start(0))?;
        Ok(Self {
            inner,
            pos,
            patches,
        })
    }
}

/// Where to rename `StripOffsets` (273) to `TileOffsets` (324) and `StripByteCounts` (279) to
/// `TileByteCounts` (325) in a classic (not Big) TIFF's first directory: the tag numbers'
/// offsets and new bytes, or nothing when the directory is not a tiled one spelled with strips.
fn strip_tags_of_tiles<R: Read + Seek>(r: &mut R) -> io::Result<Vec<(u64, [u8; 2])>> {
    let mut head = [0u8; 8];
    r.seek(SeekFrom::Start(0))?;
    r.read_exact(&mut head)?;
    let big_endian = match &head[..4] {
        b"II*\0" => false,
        b"MM\0*" => true,
        _ => return Ok(Vec::new()),
    };
    let u16_of = |b: [u8; 2]| {
        if big_endian {
            u16::from_be_bytes(b)
        } else {
            u16::from_le_bytes(b)
        }
    };
    let bytes_of = |v: u16| {
        if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let ifd = u64::from(if big_endian {
        u32::from_be_bytes([head[4], head[5], head[6], head[7]])
    } else {
        u32::from_le_bytes([head[4], head[5], head[6], head[7]])
    });
    r.seek(SeekFrom::Start(ifd))?;
    let mut count = [0u8; 2];
    r.read_exact(&mut count)?;
    let mut tags = Vec::new();
    for i in 0..u64::from(u16_of(count)) {
        let mut entry = [0u8; 12];
        r.read_exact(&mut entry)?;
        tags.push((ifd + 2 + 12 * i, u16_of([entry[0], entry[1]])));
    }
    let has = |t: Tag| tags.iter().any(|&(_, tag)| tag == t.to_u16());
    if !has(Tag::TileWidth)
        || has(Tag::TileOffsets)
        || has(Tag::TileByteCounts)
        || !has(Tag::StripOffsets)
        || !has(Tag::StripByteCounts)
    {
        return Ok(Vec::new());
    }
    let rename = [
        (Tag::StripOffsets, Tag::TileOffsets),
        (Tag::StripByteCounts, Tag::TileByteCounts),
    ];
    Ok(tags
        .iter()
        .filter_map(|&(at, tag)| {
            let (_, to) = rename.iter().find(|(from, _)| from.to_u16() == tag)?;
            Some((at, bytes_of(to.to_u16())))
        })
        .collect())
}

impl<R: Read> Read for Patched<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        let (start, end) = (self.pos, self.pos + n as u64);
        for (at, bytes) in &self.patches {
            for (k, b) in bytes.iter().enumerate() {
                let p = at + k as u64;
                if (start..end).contains(&p) {
                    buf[(p - start) as usize] = *b;
                }
            }
        }
        self.pos = end;
        Ok(n)
    }
}

impl<R: Seek> Seek for Patched<R> {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        self.pos = self.inner.seek(to)?;
        Ok(self.pos)
    }
}

/// How a strip is decompressed here.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum OwnCodec {
    /// Old-style LZW.
    OldLzw,
    /// CCITT Group 4, strips too tall for the crate.
    Fax4,
}

/// Whether the image `d` is at is one decoded here, and how; an error names a variant of these
/// that is not supported (tiles, or samples of more than 8 bits, in old-style LZW).
pub(super) fn own_codec<R: Read + Seek>(
    d: &mut Decoder<R>,
    bits: u32,
    height: u32,
) -> Result<Option<OwnCodec>, String> {
    let compression = d.find_tag_unsigned::<u16>(Tag::Compression).ok().flatten();
    if compression == Some(CompressionMethod::Fax4.to_u16()) {
        let rows = d
            .find_tag_unsigned::<u32>(Tag::RowsPerStrip)
            .ok()
            .flatten()
            .unwrap_or(height)
            .min(height);
        let strips = d.find_tag(Tag::StripOffsets).ok().flatten().is_some();
        return Ok((strips && rows > u32::from(u16::MAX)).then_some(OwnCodec::Fax4));
    }
    if compression != Some(CompressionMethod::LZW.to_u16()) {
        return Ok(None);
    }
    let tiled = d.find_tag(Tag::TileOffsets).ok().flatten().is_some();
    let first = d
        .find_tag_unsigned_vec::<u64>(if tiled {
            Tag::TileOffsets
        } else {
            Tag::StripOffsets
        })
        .ok()
        .flatten()
        .and_then(|v| v.first().copied());
    let Some(first) = first else {
        return Ok(None);
    };
    let mut two = [0u8; 2];
    let r = d.inner();
    if r.seek(SeekFrom::Start(first)).is_err() || r.read_exact(&mut two).is_err() {
        return Ok(None);
    }
    // libtiff's test (LZWPreDecode): new-style data starts with the clear code, 256, most
    // significant bit first (0x80); old-style data with it least significant bit first.
    if !(two[0] == 0 && two[1] & 1 == 1) {
        return Ok(None);
    }
    if tiled {
        return Err("old-style LZW in a tiled TIFF is not supported".into());
    }
    if bits > 8 {
        return Err(format!(
            "old-style LZW TIFF of {bits}-bit samples is not supported"
        ));
    }
    Ok(Some(OwnCodec::OldLzw))
}

/// An image's samples decompressed here, laid out as the crate lays out its own.
pub(super) struct Strips {
    pub(super) bytes: Vec<u8>,
    /// Samples per pixel in a plane (1 when each sample has its plane).
    pub(super) spp: usize,
    /// Bytes from one row to the next (within a plane).
    pub(super) row_stride: usize,
    /// Bytes from one plane to the next.
    pub(super) plane_stride: usize,
}

/// The image's strips decompressed with `codec`, in the crate's layout (at least `spp` samples
/// a pixel, or the file's `SamplesPerPixel`; `planar`: each sample in its plane), inverted when
/// `white_is_zero` as the crate inverts its own (samples of at most 8 bits here).
///
/// # Errors
/// Unreadable strips, a compressed stream that is not what `codec` reads, or a predictor other
/// than none or horizontal differencing.
pub(super) fn decode_strips<R: Read + Seek>(
    d: &mut Decoder<R>,
    codec: OwnCodec,
    (width, height): (u32, u32),
    (spp, planar): (usize, bool),
    bits: u32,
    white_is_zero: bool,
) -> Result<Strips, String> {
    let file_spp = d
        .find_tag_unsigned::<u16>(Tag::SamplesPerPixel)
        .ok()
        .flatten()
        .map_or(1, usize::from)
        .max(spp);
    let (spp, planes) = if planar { (1, file_spp) } else { (file_spp, 1) };
    let row_stride = (width as usize * spp * bits as usize).div_ceil(8);
    let plane_stride = row_stride * height as usize;
    let tag = |d: &mut Decoder<R>, t: Tag| d.get_tag_u64_vec(t).map_err(|e| format!("{t:?}: {e}"));
    let offsets = tag(d, Tag::StripOffsets)?;
    let counts = tag(d, Tag::StripByteCounts)?;
    let rows_per_strip = d
        .find_tag_unsigned::<u32>(Tag::RowsPerStrip)
        .ok()
        .flatten()
        .unwrap_or(height)
        .clamp(1, height.max(1));
    let predictor = d.find_tag_unsigned::<u16>(Tag::Predictor).ok().flatten();
    let horizontal = match predictor {
        None | Some(1) => false,
        Some(p) if p == Predictor::Horizontal.to_u16() && codec == OwnCodec::OldLzw => true,
        Some(p) => {
            return Err(format!(
                "TIFF predictor {p} with {codec:?} is not supported"
            ));
        }
    };
    let strips_per_plane = height.div_ceil(rows_per_strip) as usize;
    if offsets.len() != counts.len() || offsets.len() < strips_per_plane * planes {
        return Err(format!(
            "{} strip offsets and {} byte counts for {} strips",
            offsets.len(),
            counts.len(),
            strips_per_plane * planes
        ));
    }
    let len = plane_stride * (planes - 1) + row_stride * height as usize;
    let mut out = super::zeroed::<u8>(len, "the decoder")?;
    for (i, (&offset, &count)) in offsets
        .iter()
        .zip(&counts)
        .take(strips_per_plane * planes)
        .enumerate()
    {
        let (plane, strip) = (i / strips_per_plane, i % strips_per_plane);
        let first_row = strip * rows_per_strip as usize;
        let rows = (rows_per_strip as usize).min(height as usize - first_row);
        let start = plane * plane_stride + first_row * row_stride;
        let target = &mut out[start..start + rows * row_stride];
        let mut data = Vec::new();
        let r = d.inner();
        r.seek(SeekFrom::Start(offset))
            .and_then(|_| r.take(count.min(MAX_IMAGE_BYTES)).read_to_end(&mut data))
            .map_err(|e| format!("strip {i}: {e}"))?;
        match codec {
            OwnCodec::OldLzw => old_lzw(&data, target).map_err(|e| format!("strip {i}: {e}"))?,
            OwnCodec::Fax4 => {
                fax4(&data, width, target, row_stride).map_err(|e| format!("strip {i}: {e}"))?;
            }
        }
        if horizontal {
            for row in target.chunks_exact_mut(row_stride) {
                for x in spp..(width as usize * spp).min(row.len()) {
                    row[x] = row[x].wrapping_add(row[x - spp]);
                }
            }
        }
    }
    if white_is_zero {
        for b in &mut out {
            *b = !*b;
        }
    }
    Ok(Strips {
        bytes: out,
        spp,
        row_stride,
        plane_stride,
    })
}

/// Old-style LZW `data` decompressed into `out` (a short strip leaves the rest zero, as libtiff
/// does, with a warning there).
fn old_lzw(data: &[u8], out: &mut [u8]) -> Result<(), String> {
    let mut lzw = weezl::decode::Decoder::new(weezl::BitOrder::Lsb, 8);
    let (mut read, mut written) = (0, 0);
    while written < out.len() {
        let r = lzw.decode_bytes(&data[read..], &mut out[written..]);
        read += r.consumed_in;
        written += r.consumed_out;
        match r.status {
            Ok(weezl::LzwStatus::Ok) => {}
            Ok(weezl::LzwStatus::Done | weezl::LzwStatus::NoProgress) => break,
            Err(e) => return Err(format!("old-style LZW: {e}")),
        }
    }
    Ok(())
}

/// CCITT Group 4 `data` decoded into `out`, one bit a pixel, most significant first, black 1
/// (as libtiff and the `tiff` crate fill a line: a fax "white" run is zeros).
fn fax4(data: &[u8], width: u32, out: &mut [u8], row_stride: usize) -> Result<(), String> {
    let width = u16::try_from(width)
        .map_err(|_| "CCITT Group 4 TIFF wider than 65,535 pixels is not supported")?;
    let mut fax = fax::decoder::Group4Decoder::new(data.iter().map(|&b| Ok::<u8, ()>(b)), width)
        .map_err(|()| "CCITT Group 4: no data")?;
    for row in out.chunks_exact_mut(row_stride) {
        match fax.advance() {
            Ok(fax::decoder::DecodeStatus::Incomplete) => {}
            Ok(fax::decoder::DecodeStatus::End) => break,
            Err(e) => return Err(format!("CCITT Group 4: {e:?}")),
        }
        for (x, colour) in fax::decoder::pels(fax.transition(), width).enumerate() {
            if colour == fax::Color::Black {
                row[x / 8] |= 0x80 >> (x % 8);
            }
        }
    }
    Ok(())
}
