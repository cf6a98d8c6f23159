//! Single-channel 32-bit float TIFF (a height or luminance map), which the `image` crate
//! refuses: decoded with the `tiff` crate under the same limits into grey texels.

use super::{ImageRequest, Layout, MAX_IMAGE_BYTES, Sample, Storage};
use std::io::{BufRead, Seek, SeekFrom};
use tiff::ColorType;
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::{SampleFormat, Tag};

/// One float sample a pixel.
const GREY: Layout = Layout {
    channels: 1,
    sample: Sample::F32Ne,
};

/// Decodes `r` if it is a one-channel float TIFF; `Ok(None)` (and `r` rewound) otherwise.
///
/// The texture budget `req` leaves is checked from the header; the decoder's buffer holds at
/// most [`MAX_IMAGE_BYTES`].
///
/// # Errors
/// The TIFF is one-channel float but cannot be decoded, or it is above the limits.
pub(super) fn decode_gray_f32<R: BufRead + Seek>(
    r: &mut R,
    req: ImageRequest,
) -> Result<Option<Storage>, String> {
    let max_bytes = MAX_IMAGE_BYTES;
    let start = r.stream_position().map_err(|e| e.to_string())?;
    let found = {
        let mut limits = Limits::default();
        limits.decoding_buffer_size = usize::try_from(max_bytes).unwrap_or(usize::MAX);
        let Ok(decoder) = Decoder::new(&mut *r) else {
            r.seek(SeekFrom::Start(start)).map_err(|e| e.to_string())?;
            return Ok(None);
        };
        let mut decoder = decoder.with_limits(limits);
        let float = matches!(
            decoder.find_tag_unsigned_vec::<u16>(Tag::SampleFormat),
            Ok(Some(ref f)) if f.first().copied() == Some(SampleFormat::IEEEFP.to_u16())
        );
        if float && matches!(decoder.colortype(), Ok(ColorType::Gray(32))) {
            let (w, h) = decoder.dimensions().map_err(|e| e.to_string())?;
            let req = ImageRequest { srgb: false, ..req };
            let Some(storage) = Storage::new(w, h, GREY, req)? else {
                return Storage::stand_in(w, h, GREY, req).map(Some);
            };
            match decoder.read_image().map_err(|e| e.to_string())? {
                DecodingResult::F32(v) => Some((storage, v)),
                _ => return Err("a float TIFF did not decode to floats".into()),
            }
        } else {
            None
        }
    };
    let Some((mut storage, v)) = found else {
        r.seek(SeekFrom::Start(start)).map_err(|e| e.to_string())?;
        return Ok(None);
    };
    let width = storage.width as usize;
    if v.len() < width * storage.height as usize {
        return Err("the TIFF holds fewer samples than its size says".into());
    }
    // Row by row through one row of bytes, so the samples are never copied whole.
    let mut bytes = Vec::with_capacity(width * 4);
    for (row, line) in v
        .chunks_exact(width)
        .take(storage.height as usize)
        .enumerate()
    {
        bytes.clear();
        bytes.extend(line.iter().flat_map(|g| g.to_ne_bytes()));
        storage.put_row(row as u32, &bytes, GREY);
    }
    Ok(Some(storage))
}
