//! TIFF through the `tiff` crate directly, with the samples converted here: the `image` crate
//! refuses most of what TIFF stores (palettes, 2-7, 10, 12, 14 and 24-bit samples, 16 and 64-bit
//! floats, 32 and 64-bit integers, signed integers, CMYK, grey with alpha), although the `tiff`
//! crate decodes them. Its buffer holds the samples as the file stores them; turning them into
//! colours (scaling, palette, CMYK) is the small part written here.

use super::{ImageRequest, Layout, MAX_IMAGE_BYTES, Sample, Storage};
use std::io::{Read, Seek};
use tiff::ColorType;
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::{
    CompressionMethod, PhotometricInterpretation, PlanarConfiguration, SampleFormat, Tag,
};

/// How a pixel's samples become a colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Colour {
    /// Grey (black is zero; the `tiff` crate inverts white-is-zero), then maybe alpha.
    Grey,
    /// Red, green, blue, then maybe alpha.
    Rgb,
    /// An index into the colour map.
    Palette,
    /// Cyan, magenta, yellow, black (naive: no colour profile), then maybe alpha.
    Cmyk,
    /// Luma and chroma as a JPEG stores them: the `tiff` crate hands JPEG-compressed data over
    /// in the JPEG's own colour space, unconverted.
    YCbCr,
}

/// How one sample is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Uint,
    Int,
    Float,
}

/// Where the samples are in the decoded buffer and what they mean.
struct Samples<'a> {
    bytes: &'a [u8],
    bits: u32,
    format: Format,
    /// Samples per pixel.
    spp: usize,
    /// Each sample in its own plane (`PlanarConfiguration::Planar`).
    planar: bool,
    /// Bytes from one row to the next (within a plane).
    row_stride: usize,
    /// Bytes from one plane to the next.
    plane_stride: usize,
}

impl Samples<'_> {
    /// Sample `c` of pixel (`x`, `y`) as stored: an unsigned or signed integer, or a float.
    fn raw(&self, x: usize, y: usize, c: usize) -> f64 {
        let (base, index) = if self.planar {
            (c * self.plane_stride + y * self.row_stride, x)
        } else {
            (y * self.row_stride, x * self.spp + c)
        };
        let row = &self.bytes[base.min(self.bytes.len())..];
        match self.bits {
            8 | 16 | 32 | 64 => {
                let n = self.bits as usize / 8;
                let Some(b) = row.get(index * n..(index + 1) * n) else {
                    return 0.0;
                };
                aligned(b, self.format)
            }
            bits => {
                let v = packed(row, index as u64 * u64::from(bits), bits);
                match self.format {
                    // Sign-extended from `bits`.
                    Format::Int => ((v << (64 - bits)) as i64 >> (64 - bits)) as f64,
                    _ => v as f64,
                }
            }
        }
    }

    /// Sample `c` of pixel (`x`, `y`) in [0, 1] for integers (signed ones offset by half their
    /// range, as ImageMagick reads them), as it is for floats.
    fn value(&self, x: usize, y: usize, c: usize) -> f64 {
        let v = self.raw(x, y, c);
        let max = 2f64.powi(self.bits as i32) - 1.0;
        match self.format {
            Format::Uint => v / max,
            Format::Int => (v + 2f64.powi(self.bits as i32 - 1)) / max,
            Format::Float => v,
        }
    }
}

/// A byte-aligned sample (native-endian, as the `tiff` crate leaves it).
fn aligned(b: &[u8], format: Format) -> f64 {
    match (format, b.len()) {
        (Format::Uint, 1) => f64::from(b[0]),
        (Format::Int, 1) => f64::from(b[0] as i8),
        (Format::Uint, 2) => f64::from(u16::from_ne_bytes([b[0], b[1]])),
        (Format::Int, 2) => f64::from(i16::from_ne_bytes([b[0], b[1]])),
        (Format::Float, 2) => f64::from(f16_to_f32(u16::from_ne_bytes([b[0], b[1]]))),
        (Format::Uint, 4) => f64::from(u32::from_ne_bytes([b[0], b[1], b[2], b[3]])),
        (Format::Int, 4) => f64::from(i32::from_ne_bytes([b[0], b[1], b[2], b[3]])),
        (Format::Float, 4) => f64::from(f32::from_ne_bytes([b[0], b[1], b[2], b[3]])),
        (format, 8) => {
            let b: [u8; 8] = b.try_into().unwrap_or([0; 8]);
            match format {
                Format::Uint => u64::from_ne_bytes(b) as f64,
                Format::Int => i64::from_ne_bytes(b) as f64,
                Format::Float => f64::from_ne_bytes(b),
            }
        }
        _ => 0.0,
    }
}

/// `bits` bits at bit `at` of a packed row, most significant first (TIFF's default fill order).
fn packed(row: &[u8], at: u64, bits: u32) -> u64 {
    let mut v = 0u64;
    for k in 0..u64::from(bits) {
        let bit = at + k;
        let byte = row.get((bit / 8) as usize).copied().unwrap_or(0);
        v = (v << 1) | u64::from((byte >> (7 - bit % 8)) & 1);
    }
    v
}

/// JFIF's full-range YCbCr to RGB (what libjpeg does, and so libtiff), in [0, 1].
fn ycbcr_to_rgb(y: f64, cb: f64, cr: f64) -> [f64; 3] {
    let (cb, cr) = (cb - 128.0 / 255.0, cr - 128.0 / 255.0);
    [
        y + 1.402 * cr,
        y - 0.344_136 * cb - 0.714_136 * cr,
        y + 1.772 * cb,
    ]
}

/// An IEEE half-precision float's value (a 16-bit float TIFF's samples).
fn f16_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 == 0 { 1.0 } else { -1.0 };
    let exp = i32::from((h >> 10) & 0x1f);
    let frac = f32::from(h & 0x3ff);
    match exp {
        0 => sign * frac * 2f32.powi(-24),
        31 if frac == 0.0 => sign * f32::INFINITY,
        31 => f32::NAN,
        e => sign * (1.0 + frac / 1024.0) * 2f32.powi(e - 15),
    }
}

/// What the `tiff` crate reports; the variants it cannot decode named as not supported.
fn tiff_err(e: &tiff::TiffError) -> String {
    use tiff::TiffUnsupportedError as U;
    let tiff::TiffError::UnsupportedError(u) = e else {
        return e.to_string();
    };
    match u {
        U::InterpretationWithBits(p, _) if *p == PhotometricInterpretation::RGBPalette => {
            "palette (colour-mapped) TIFF is not supported".into()
        }
        U::InterpretationWithBits(p, bits) => {
            format!("TIFF of {p:?} at {bits:?} bits per sample is not supported")
        }
        U::UnsupportedColorType(c) => {
            format!(
                "{}-bit TIFF samples ({c:?}) are not supported",
                c.bit_depth()
            )
        }
        U::UnsupportedCompressionMethod(m) => format!("{m:?}-compressed TIFF is not supported"),
        U::UnknownInterpretation => "white-is-zero TIFF at this bit depth is not supported".into(),
        other => format!("TIFF: {other} (not supported)"),
    }
}

/// Reads the image into `buf` as the `tiff` crate decodes it, packed samples of 9 to 31 bits put
/// back in the file's bit order; its rows' and planes' strides in bytes.
fn read_image<R: Read + Seek>(
    d: &mut Decoder<R>,
    buf: &mut DecodingResult,
    bits: u32,
) -> Result<(usize, usize), String> {
    let pref = d.read_image_to_buffer(buf).map_err(|e| tiff_err(&e))?;
    let order = d.byte_order();
    let mut view = buf.as_buffer(0);
    let bytes = view.as_bytes_mut();
    if bytes.len() < pref.complete_len {
        return Err("the TIFF's planes do not fit in the decoder's buffer".into());
    }
    // Packed 9-31-bit samples come byte-swapped in groups of 2 or 4 when the file's byte order
    // is not the machine's: undo that to read the bit stream as the file wrote it.
    if bits > 8 && ![16, 32].contains(&bits) && order != tiff::tags::ByteOrder::native() {
        let group = if bits <= 16 { 2 } else { 4 };
        for g in bytes.chunks_exact_mut(group) {
            g.reverse();
        }
    }
    let stride = |s: Option<std::num::NonZeroUsize>| s.map_or(0, std::num::NonZeroUsize::get);
    Ok((stride(pref.row_stride), stride(pref.plane_stride)))
}

/// Decodes a TIFF (its first image) into its texel storage, the budget checked from the header
/// before anything is decoded; the decoder's buffer holds at most [`MAX_IMAGE_BYTES`].
///
/// # Errors
/// A malformed file, a variant named as not supported, or a size above the limits.
pub(super) fn decode_tiff<R: Read + Seek>(r: R, req: ImageRequest) -> Result<Storage, String> {
    let mut limits = Limits::default();
    limits.decoding_buffer_size = usize::try_from(MAX_IMAGE_BYTES).unwrap_or(usize::MAX);
    let r = super::tiff_old::Patched::new(r).map_err(|e| e.to_string())?;
    let mut d = Decoder::new(r)
        .map_err(|e| tiff_err(&e))?
        .with_limits(limits);
    let (w, h) = d.dimensions().map_err(|e| tiff_err(&e))?;
    let color = d.colortype().map_err(|e| tiff_err(&e))?;
    let tag = |d: &mut Decoder<_>, t: Tag| d.find_tag_unsigned_vec::<u16>(t).ok().flatten();
    let format = match tag(&mut d, Tag::SampleFormat).and_then(|v| v.first().copied()) {
        None => Format::Uint,
        Some(f) if f == SampleFormat::Uint.to_u16() => Format::Uint,
        Some(f) if f == SampleFormat::Int.to_u16() => Format::Int,
        Some(f) if f == SampleFormat::IEEEFP.to_u16() => Format::Float,
        Some(f) => return Err(format!("TIFF sample format {f} is not supported")),
    };
    let planar = tag(&mut d, Tag::PlanarConfiguration).and_then(|v| v.first().copied())
        == Some(PlanarConfiguration::Planar.to_u16());
    let compression = tag(&mut d, Tag::Compression).and_then(|v| v.first().copied());
    let jpeg = [CompressionMethod::ModernJPEG.to_u16(), 6]
        .map(Some)
        .contains(&compression);
    let photometric = tag(&mut d, Tag::PhotometricInterpretation).and_then(|v| v.first().copied());
    let (colour, spp, bits) = match color {
        ColorType::Gray(b) => (Colour::Grey, 1, b),
        ColorType::GrayA(b) => (Colour::Grey, 2, b),
        ColorType::RGB(b) => (Colour::Rgb, 3, b),
        ColorType::RGBA(b) => (Colour::Rgb, 4, b),
        ColorType::Palette(b) => (Colour::Palette, 1, b),
        ColorType::CMYK(b) => (Colour::Cmyk, 4, b),
        ColorType::CMYKA(b) => (Colour::Cmyk, 5, b),
        // JPEG-compressed YCbCr comes as the JPEG stores it (converted to RGB below).
        ColorType::YCbCr(b) if jpeg => (Colour::YCbCr, 3, b),
        ColorType::YCbCr(_) => return Err("uncompressed YCbCr TIFF is not supported".into()),
        ColorType::Lab(_) => return Err("CIE L*a*b* TIFF is not supported".into()),
        ColorType::Multiband {
            bit_depth,
            num_samples,
        } if photometric == Some(PhotometricInterpretation::BlackIsZero.to_u16())
            || photometric == Some(PhotometricInterpretation::WhiteIsZero.to_u16()) =>
        {
            (Colour::Grey, usize::from(num_samples), bit_depth)
        }
        other => return Err(format!("TIFF colour type {other:?} is not supported")),
    };
    let bits = u32::from(bits);
    if bits == 0 || bits > 64 || (format == Format::Float && ![16, 32, 64].contains(&bits)) {
        return Err(format!("{bits}-bit TIFF samples are not supported"));
    }
    let has_alpha = match colour {
        Colour::Grey => spp >= 2,
        Colour::Rgb => spp >= 4,
        Colour::Cmyk => spp >= 5,
        Colour::Palette | Colour::YCbCr => false,
    };
    let cmap = if colour == Colour::Palette {
        let map = d
            .get_tag_u16_vec(Tag::ColorMap)
            .map_err(|e| format!("the palette (ColorMap): {}", tiff_err(&e)))?;
        if bits > 16 || map.len() < 3 << bits {
            return Err(format!(
                "the palette (ColorMap) has {} entries, a {bits}-bit palette needs {}",
                map.len(),
                3u64 << bits.min(16)
            ));
        }
        map
    } else {
        Vec::new()
    };
    // What the storage is given: 8-bit samples stay 8-bit (compact sRGB texels), other integers
    // go through 16 bits (linear texels), floats as they are.
    let sample = match (format, bits, colour) {
        (Format::Float, ..) => Sample::F32Ne,
        (_, 1..=8, c) if c != Colour::Palette => Sample::U8,
        _ => Sample::U16Ne,
    };
    let layout = Layout {
        channels: if has_alpha { 4 } else { 3 },
        sample,
    };
    let Some(mut storage) = Storage::new(w, h, layout, req)? else {
        return Storage::stand_in(w, h, layout, req);
    };
    let mut buf = DecodingResult::U8(Vec::new());
    let mut view;
    let mut own: Vec<u8>;
    let (bytes, spp_stored, row_stride, plane_stride): (&mut [u8], usize, usize, usize) =
        if let Some(codec) = super::tiff_old::own_codec(&mut d, bits, h)? {
            // Decompressed here (see `tiff_old`), in the crate's layout.
            let white = photometric == Some(PhotometricInterpretation::WhiteIsZero.to_u16());
            let strips =
                super::tiff_old::decode_strips(&mut d, codec, (w, h), (spp, planar), bits, white)?;
            own = strips.bytes;
            (
                &mut own[..],
                strips.spp,
                strips.row_stride,
                strips.plane_stride,
            )
        } else {
            let (row_stride, plane_stride) = read_image(&mut d, &mut buf, bits)?;
            view = buf.as_buffer(0);
            let chunk_spp = if planar { 1 } else { spp };
            (view.as_bytes_mut(), chunk_spp, row_stride, plane_stride)
        };
    let samples = Samples {
        bytes: &*bytes,
        bits,
        format,
        spp: spp_stored,
        planar,
        row_stride,
        plane_stride,
    };
    let n = cmap.len() / 3;
    let mut row_bytes = Vec::with_capacity(w as usize * layout.bytes_per_pixel());
    for y in 0..h as usize {
        row_bytes.clear();
        for x in 0..w as usize {
            let v = |c: usize| samples.value(x, y, c);
            let (rgb, a) = match colour {
                Colour::Grey => ([v(0); 3], has_alpha.then(|| v(1))),
                Colour::Rgb => ([v(0), v(1), v(2)], has_alpha.then(|| v(3))),
                Colour::Palette => {
                    let i = (samples.raw(x, y, 0) as usize).min(n - 1);
                    let c = |k: usize| f64::from(cmap[k * n + i]) / 65_535.0;
                    ([c(0), c(1), c(2)], None)
                }
                Colour::YCbCr => (ycbcr_to_rgb(v(0), v(1), v(2)), None),
                Colour::Cmyk => {
                    let k = 1.0 - v(3);
                    (
                        [(1.0 - v(0)) * k, (1.0 - v(1)) * k, (1.0 - v(2)) * k],
                        has_alpha.then(|| v(4)),
                    )
                }
            };
            for s in rgb.into_iter().chain(a) {
                match sample {
                    Sample::U8 => row_bytes.push((s.clamp(0.0, 1.0) * 255.0).round() as u8),
                    Sample::F32Ne => row_bytes.extend((s as f32).to_ne_bytes()),
                    _ => row_bytes
                        .extend(((s.clamp(0.0, 1.0) * 65_535.0).round() as u16).to_ne_bytes()),
                }
            }
        }
        storage.put_row(y as u32, &row_bytes, layout);
    }
    Ok(storage)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_floats_and_packed_bits() {
        assert_eq!(f16_to_f32(0x3c00), 1.0);
        assert_eq!(f16_to_f32(0xc000), -2.0);
        assert_eq!(f16_to_f32(0x0001), 2f32.powi(-24));
        // 0b101_011_11 0b1_100_0000: 3-bit samples 5, 3, 7 (across the byte), then 4.
        let row = [0b1010_1111, 0b1100_0000];
        let got: Vec<u64> = (0..4).map(|i| packed(&row, i * 3, 3)).collect();
        assert_eq!(got, [5, 3, 7, 4]);
    }
}
