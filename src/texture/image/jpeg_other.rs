//! The JPEG variants `zune-jpeg` refuses or gets wrong, through `jpeg-decoder`: lossless (SOF3)
//! up to 16 bits, and images under 16 pixels a side (zune-jpeg's chroma upsampling is wrong at
//! their edges: a 3 x 3 image's corner came out (52, 51, 95) where libjpeg-turbo gives
//! (41, 40, 176)). Arithmetic-coded, hierarchical and 12-bit lossy JPEG are named as not
//! supported.

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
