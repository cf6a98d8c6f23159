//! JPEG through `zune-jpeg` directly, the decoder the `image` crate wraps, so that missing data
//! is an error: `image` decodes leniently and fills what a truncated file lacks with grey.

use super::{
    ImageRequest, Layout, MAX_IMAGE_BYTES, MAX_IMAGE_DIMENSION, Sample, Storage, approx_bytes,
    zeroed,
};
use std::io::Read;
use zune_core::bytestream::ZCursor;
use zune_core::colorspace::ColorSpace;
use zune_core::options::DecoderOptions;
use zune_jpeg::JpegDecoder;
use zune_jpeg::errors::DecodeErrors;

/// The decoder's options: `strict` or lenient, at most [`MAX_IMAGE_DIMENSION`] a side.
fn options(strict: bool) -> DecoderOptions {
    DecoderOptions::default()
        .set_strict_mode(strict)
        .set_max_width(MAX_IMAGE_DIMENSION as usize)
        .set_max_height(MAX_IMAGE_DIMENSION as usize)
}

/// Whether a strict decoder's error means the file ends before its image data does.
fn is_truncation(e: &DecodeErrors) -> bool {
    if matches!(e, DecodeErrors::ExhaustedData | DecodeErrors::IoErrors(_)) {
        return true;
    }
    // The rest are messages ("Premature end of buffer", "Premature End of image").
    e.to_string().to_ascii_lowercase().contains("premature end")
}

/// Whether the image data ends: an end-of-image marker (`FF D9`) after the last start of scan
/// (`FF DA`). Inside the entropy-coded data an `FF` byte is always followed by `00` or a restart
/// marker, so `FF D9` there is the end; an embedded thumbnail's markers come before the main
/// image's scans.
fn has_end(data: &[u8]) -> bool {
    let Some(sos) = data.windows(2).rposition(|m| m == [0xFF, 0xDA]) else {
        return false;
    };
    data[sos..].windows(2).any(|m| m == [0xFF, 0xD9])
}

/// Whether the bytes from the first start of scan (`FF DA`) on can hold the entropy-coded data
/// of a `width` x `height` image: every 8 x 8 block of the first component takes at least one
/// bit (its DC difference's code), so fewer bytes than blocks / 8 mean the data is missing even
/// when an end-of-image marker follows, which the decoder would fill with grey.
fn can_hold(data: &[u8], width: usize, height: usize) -> bool {
    let Some(sos) = data.windows(2).position(|m| m == [0xFF, 0xDA]) else {
        return false;
    };
    let blocks = width.div_ceil(8) as u64 * height.div_ceil(8) as u64;
    blocks <= (data.len() - sos) as u64 * 8
}

/// Decodes a JPEG of at most [`MAX_IMAGE_BYTES`] into its texel storage, the budget checked from the
/// header before anything is decoded. The pixels are decoded into one buffer (grey or RGB, 1 or
/// 3 bytes a pixel) and converted into the storage.
///
/// A file whose data ends early is refused ("truncated image data"): the strict decoder runs out
/// of data, the file has no end-of-image marker after its last scan, or it is too short for its
/// size (see [`can_hold`]). Other departures from
/// the standard that the strict decoder refuses (stray bytes between segments, say) in a file
/// that does end are decoded leniently, as `image` and browsers do.
///
/// # Errors
/// A malformed or truncated file, or a size above the limits.
pub(super) fn decode_jpeg(r: impl Read, req: ImageRequest) -> Result<Storage, String> {
    let max_bytes = MAX_IMAGE_BYTES;
    let mut data = Vec::new();
    r.take(max_bytes + 1)
        .read_to_end(&mut data)
        .map_err(|e| e.to_string())?;
    if data.len() as u64 > max_bytes {
        return Err(format!("larger than {}", approx_bytes(max_bytes)));
    }
    if let Some(frame) = super::jpeg_other::frame(&data) {
        if let Some(why) = super::jpeg_other::unsupported(frame) {
            return Err(why);
        }
        if super::jpeg_other::wanted(frame) {
            return super::jpeg_other::decode(&data, frame, req);
        }
    }
    let mut header = JpegDecoder::new_with_options(ZCursor::new(&data[..]), options(false));
    header.decode_headers().map_err(|e| {
        if is_truncation(&e) {
            "truncated image data (in the header)".to_string()
        } else {
            e.to_string()
        }
    })?;
    let ((w, h), input) = header
        .dimensions()
        .zip(header.input_colorspace())
        .ok_or("the JPEG header has no size")?;
    // As `image` decodes: grey and RGB (with or without alpha) as they are, anything else (YCbCr,
    // CMYK, YCCK) converted to RGB.
    let colour = match input {
        ColorSpace::RGB | ColorSpace::RGBA | ColorSpace::Luma | ColorSpace::LumaA => input,
        _ => ColorSpace::RGB,
    };
    let layout = Layout {
        channels: colour.num_components(),
        sample: Sample::U8,
    };
    let (w, h) = (
        u32::try_from(w).map_err(|_| "too wide")?,
        u32::try_from(h).map_err(|_| "too tall")?,
    );
    // The budget, then whether the data can be there at all, before allocating anything.
    Storage::check(w, h, layout, req)?;
    if !can_hold(&data, w as usize, h as usize) {
        return Err("truncated image data".into());
    }
    let Some(mut storage) = Storage::new(w, h, layout, req)? else {
        return Storage::stand_in(w, h, layout, req);
    };
    let mut buf = zeroed::<u8>(
        w as usize * h as usize * layout.bytes_per_pixel(),
        "the decoder",
    )?;
    let mut decode = |strict: bool| {
        let options = options(strict).jpeg_set_out_colorspace(colour);
        JpegDecoder::new_with_options(ZCursor::new(&data[..]), options).decode_into(&mut buf)
    };
    match decode(true) {
        Ok(()) => {}
        Err(e) if is_truncation(&e) => return Err("truncated image data".into()),
        Err(_) if !has_end(&data) => return Err("truncated image data".into()),
        Err(_) => decode(false).map_err(|e| e.to_string())?,
    }
    storage.put_rows(&buf, layout)?;
    Ok(storage)
}
