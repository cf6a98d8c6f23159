//! Single-channel 32-bit float TIFF (a height or luminance map), which the `image` crate
//! refuses: decoded with the `tiff` crate under the same limits and returned as grey RGB.

use image::{DynamicImage, Rgb32FImage};
use std::io::{BufRead, Seek, SeekFrom};
use tiff::ColorType;
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::{SampleFormat, Tag};

/// Decodes `r` if it is a one-channel float TIFF; `Ok(None)` (and `r` rewound) otherwise.
///
/// # Errors
/// The TIFF is one-channel float but cannot be decoded, or it is above `max_dimension` or
/// `max_bytes`.
pub fn decode_gray_f32<R: BufRead + Seek>(
    r: &mut R,
    max_dimension: u32,
    max_bytes: u64,
) -> Result<Option<DynamicImage>, String> {
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
            if w == 0 || h == 0 || w > max_dimension || h > max_dimension {
                return Err(format!(
                    "{w} x {h} pixels is outside 1 to {max_dimension} per side"
                ));
            }
            // The grey values become RGB: three floats per pixel must fit too.
            if u64::from(w) * u64::from(h) * 12 > max_bytes {
                return Err(format!(
                    "{w} x {h} pixels needs more than {max_bytes} bytes"
                ));
            }
            match decoder.read_image().map_err(|e| e.to_string())? {
                DecodingResult::F32(v) => Some((w, h, v)),
                _ => return Err("a float TIFF did not decode to floats".into()),
            }
        } else {
            None
        }
    };
    let Some((w, h, v)) = found else {
        r.seek(SeekFrom::Start(start)).map_err(|e| e.to_string())?;
        return Ok(None);
    };
    if v.len() < w as usize * h as usize {
        return Err("the TIFF holds fewer samples than its size says".into());
    }
    let rgb: Vec<f32> = v[..w as usize * h as usize]
        .iter()
        .flat_map(|&g| [g; 3])
        .collect();
    Rgb32FImage::from_raw(w, h, rgb)
        .map(DynamicImage::ImageRgb32F)
        .map(Some)
        .ok_or_else(|| "the TIFF's size and samples disagree".into())
}
