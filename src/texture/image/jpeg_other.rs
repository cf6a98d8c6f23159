//! The JPEG variants `zune-jpeg` refuses or reads unlike libjpeg, through `jpeg-decoder`:
//! lossless (SOF3) up to 16 bits, and images under 16 pixels a side, whose edges are most of
//! them (zune-jpeg's 2 x 2 came out unlike libjpeg's). Of those, libjpeg replicates the chroma
//! of an image whose subsampled chroma is at most 2 samples wide where both Rust decoders
//! interpolate it (a 3 x 3 image's corner came out (52, 51, 95) where libjpeg-turbo gives
//! (41, 40, 176)): see [`replicated_chroma`]. Arithmetic-coded, hierarchical and 12-bit lossy
//! JPEG are named as not supported.

use super::{ImageRequest, Layout, MAX_IMAGE_BYTES, Sample, Storage};

/// What a JPEG's first start-of-frame marker says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Frame {
    /// The marker's second byte: 0xC0 baseline, 0xC1 extended, 0xC2 progressive, 0xC3
    /// lossless, 0xC5-0xC7 hierarchical, 0xC9-0xCF arithmetic-coded.
    pub(super) marker: u8,
    /// Bits per sample.
    pub(super) precision: u8,
    pub(super) width: u16,
    pub(super) height: u16,
    /// Where the start-of-frame marker is in the file.
    pub(super) at: usize,
}

/// The first start-of-frame segment of `data`, walking the segments from the start (an
/// embedded thumbnail sits inside an APP segment, so it is skipped whole).
pub(super) fn frame(data: &[u8]) -> Option<Frame> {
    let mut i = 2;
    while i + 4 <= data.len() {
        if data[i] != 0xFF {
            return None;
        }
        let m = data[i + 1];
        if m == 0xFF {
            i += 1;
            continue;
        }
        if m == 0x01 || (0xD0..=0xD8).contains(&m) {
            i += 2;
            continue;
        }
        let len = usize::from(u16::from_be_bytes([data[i + 2], data[i + 3]]));
        if (0xC0..=0xCF).contains(&m) && ![0xC4, 0xC8, 0xCC].contains(&m) {
            let s = data.get(i + 4..i + 9)?;
            return Some(Frame {
                marker: m,
                precision: s[0],
                height: u16::from_be_bytes([s[1], s[2]]),
                width: u16::from_be_bytes([s[3], s[4]]),
                at: i,
            });
        }
        if m == 0xDA {
            return None;
        }
        i += 2 + len;
    }
    None
}

/// Why `frame` is not decoded at all, in a user's words; `None` when it can be.
pub(super) fn unsupported(frame: Frame) -> Option<String> {
    match frame.marker {
        0xC9..=0xCB | 0xCD..=0xCF => Some("arithmetic-coded JPEG is not supported".into()),
        0xC5..=0xC7 => Some("hierarchical JPEG is not supported".into()),
        0xC3 => None,
        _ if frame.precision != 8 => Some(format!(
            "{}-bit lossy JPEG is not supported",
            frame.precision
        )),
        _ => None,
    }
}

/// Whether `frame` is decoded here rather than by zune-jpeg: lossless, or smaller than 16
/// pixels a side.
pub(super) fn wanted(frame: Frame) -> bool {
    frame.marker == 0xC3 || frame.width < 16 || frame.height < 16
}

/// Decodes `data` (a JPEG whose frame is `frame`) with `jpeg-decoder` into its storage, the
/// budget checked from the header first.
///
/// # Errors
/// A malformed file, a variant `jpeg-decoder` does not decode, or a size above the limits.
pub(super) fn decode(data: &[u8], frame: Frame, req: ImageRequest) -> Result<Storage, String> {
    let mut d = jpeg_decoder::Decoder::new(data);
    d.set_max_decoding_buffer_size(usize::try_from(MAX_IMAGE_BYTES).unwrap_or(usize::MAX));
    d.read_info().map_err(|e| message(&e, frame))?;
    let info = d.info().ok_or("the JPEG header has no size")?;
    let (w, h) = (u32::from(info.width), u32::from(info.height));
    let (channels, sample) = match info.pixel_format {
        jpeg_decoder::PixelFormat::L8 => (1, Sample::U8),
        jpeg_decoder::PixelFormat::L16 => (1, Sample::U16Ne),
        jpeg_decoder::PixelFormat::RGB24 if frame.precision == 8 => (3, Sample::U8),
        jpeg_decoder::PixelFormat::RGB24 => {
            return Err(format!(
                "{}-bit colour lossless JPEG is not supported",
                frame.precision
            ));
        }
        jpeg_decoder::PixelFormat::CMYK32 => (4, Sample::U8),
    };
    // CMYK is turned into RGB below: the storage takes three samples.
    let stored = Layout {
        channels: channels.min(3),
        sample,
    };
    let Some(mut storage) = Storage::new(w, h, stored, req)? else {
        return Storage::stand_in(w, h, stored, req);
    };
    if channels == 3
        && frame.precision == 8
        && let Some(pixels) = replicated_chroma(data, frame)?
    {
        storage.put_rows(&pixels, stored)?;
        return Ok(storage);
    }
    let mut pixels = d.decode().map_err(|e| message(&e, frame))?;
    if sample == Sample::U16Ne && frame.precision < 16 {
        // Samples of `precision` bits, scaled to the full 16 bits the storage reads.
        let max = f32::from(u16::MAX) / ((1u32 << frame.precision) - 1) as f32;
        for s in pixels.chunks_exact_mut(2) {
            let v = f32::from(u16::from_ne_bytes([s[0], s[1]]));
            s.copy_from_slice(&((v * max).round().min(65_535.0) as u16).to_ne_bytes());
        }
    }
    if channels == 4 {
        // Adobe's CMYK JPEG stores inverted samples: R = C K / 255 (naive, no profile).
        pixels = pixels
            .chunks_exact(4)
            .flat_map(|p| {
                let k = u16::from(p[3]);
                [0, 1, 2].map(|c| ((u16::from(p[c]) * k + 127) / 255) as u8)
            })
            .collect();
    }
    storage.put_rows(&pixels, stored)?;
    Ok(storage)
}

/// `jpeg-decoder`'s error, an unsupported feature named as such.
fn message(e: &jpeg_decoder::Error, frame: Frame) -> String {
    match e {
        jpeg_decoder::Error::Unsupported(feature) => {
            format!(
                "{feature:?} in a JPEG (SOF{:X}) is not supported",
                frame.marker & 0x0F
            )
        }
        other => other.to_string(),
    }
}

/// libjpeg's pixels for a YCbCr image whose chroma is subsampled horizontally to at most 2
/// samples (and vertically, if at all, to at most 2): libjpeg replicates such chroma
/// (`jdsample.c` interpolates only planes wider than 2 samples), `jpeg-decoder` interpolates
/// it. Its interpolation keeps each chroma sample exact at the plane's corners, so the frame is
/// widened (and heightened) to whole chroma samples, decoded as YCbCr, the samples read at the
/// corners and replicated here, and the pixels converted as libjpeg converts them. `None` for
/// any other image (8-bit lossy YCbCr with 2:1 horizontal chroma only).
///
/// Written by hand because neither Rust decoder offers replication or the raw chroma planes.
fn replicated_chroma(data: &[u8], frame: Frame) -> Result<Option<Vec<u8>>, String> {
    let (w, h) = (usize::from(frame.width), usize::from(frame.height));
    let c = |k: usize| data.get(frame.at + 10 + 3 * k..frame.at + 13 + 3 * k);
    let (Some(y), Some(cb), Some(cr)) = (c(0), c(1), c(2)) else {
        return Ok(None);
    };
    let v2 = match (y[1], cb[1], cr[1]) {
        (0x21, 0x11, 0x11) => false,
        (0x22, 0x11, 0x11) => true,
        _ => return Ok(None),
    };
    // YCbCr unless an Adobe segment says RGB (transform 0) or the components are named so.
    let adobe_rgb = data
        .windows(12)
        .take(frame.at)
        .any(|m| m[..2] == [0xFF, 0xEE] && &m[4..9] == b"Adobe" && m[11] == 0);
    let (cw, ch) = (w.div_ceil(2), h.div_ceil(2));
    if !(0xC0..=0xC2).contains(&data[frame.at + 1])
        || data.get(frame.at + 9) != Some(&3)
        || adobe_rgb
        || [y[0], cb[0], cr[0]] == *b"RGB"
        || cw > 2
        || (v2 && ch > 2)
    {
        return Ok(None);
    }
    let (pw, ph) = (2 * cw, if v2 { 2 * ch } else { h });
    let mut widened = data.to_vec();
    widened[frame.at + 5..frame.at + 7].copy_from_slice(&(ph as u16).to_be_bytes());
    widened[frame.at + 7..frame.at + 9].copy_from_slice(&(pw as u16).to_be_bytes());
    let mut d = jpeg_decoder::Decoder::new(&widened[..]);
    // "RGB" hands the components over unconverted, interleaved ("None" concatenates them).
    d.set_color_transform(jpeg_decoder::ColorTransform::RGB);
    let ycc = d.decode().map_err(|e| message(&e, frame))?;
    if ycc.len() < pw * ph * 3 {
        return Ok(None);
    }
    let at = |x: usize, y: usize, k: usize| ycc[(y * pw + x) * 3 + k];
    // Chroma sample (i, j) sits at the widened plane's corner (or row, unsubsampled).
    let chroma = |i: usize, j: usize, k: usize| {
        let x = if i == 0 { 0 } else { pw - 1 };
        let y = match (v2, j) {
            (false, _) => j,
            (true, 0) => 0,
            (true, _) => ph - 1,
        };
        at(x, y, k)
    };
    let mut out = Vec::with_capacity(w * h * 3);
    for y in 0..h {
        for x in 0..w {
            let j = if v2 { y / 2 } else { y };
            let rgb = ycc_to_rgb(at(x, y, 0), chroma(x / 2, j, 1), chroma(x / 2, j, 2));
            out.extend(rgb);
        }
    }
    Ok(Some(out))
}

/// JFIF's YCbCr to RGB in libjpeg's fixed point (`jdcolor.c`: 16 fractional bits, each term
/// rounded as its tables round it), so that the pixels are libjpeg's.
fn ycc_to_rgb(y: u8, cb: u8, cr: u8) -> [u8; 3] {
    const ONE_HALF: i32 = 1 << 15;
    let fix = |x: f64| (x * 65_536.0 + 0.5) as i32;
    let (y, cb, cr) = (i32::from(y), i32::from(cb) - 128, i32::from(cr) - 128);
    let r = y + ((fix(1.402) * cr + ONE_HALF) >> 16);
    let g = y + ((-fix(0.344_14) * cb - fix(0.714_14) * cr + ONE_HALF) >> 16);
    let b = y + ((fix(1.772) * cb + ONE_HALF) >> 16);
    [r, g, b].map(|v| v.clamp(0, 255) as u8)
}
