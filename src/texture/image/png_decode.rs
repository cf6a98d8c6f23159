//! PNG textures through the `png` crate directly, so that the decoder skips what a texture does
//! not need and what can be a deflate bomb: the colour profile (`iCCP`, which `image`'s decoder
//! inflates up to its whole allocation limit) and the text chunks.

use image::{DynamicImage, ImageBuffer};
use std::io::BufRead;

/// The PNG decoder as textures are read: `max_bytes` of allocation, no colour profile, no
/// text, palettes and low bit depths expanded to 8 bits and `tRNS` to alpha (16 bits stay 16).
fn decoder<R: BufRead + std::io::Seek>(r: R, max_bytes: u64) -> png::Decoder<R> {
    let mut decoder = png::Decoder::new_with_limits(
        r,
        png::Limits {
            bytes: usize::try_from(max_bytes).unwrap_or(usize::MAX),
        },
    );
    decoder.set_ignore_iccp_chunk(true);
    decoder.set_ignore_text_chunk(true);
    decoder.set_transformations(png::Transformations::EXPAND);
    decoder
}

/// Decodes a PNG under `max_dimension` per side and `max_bytes` of allocation.
///
/// # Errors
/// What the decoder reports, or a size above the limits.
pub fn decode_png(
    r: impl BufRead + std::io::Seek,
    max_dimension: u32,
    max_bytes: u64,
) -> Result<DynamicImage, String> {
    let mut reader = decoder(r, max_bytes)
        .read_info()
        .map_err(|e| e.to_string())?;
    let (w, h) = (reader.info().width, reader.info().height);
    if w > max_dimension || h > max_dimension {
        return Err(format!(
            "{w} x {h} pixels is more than {max_dimension} per side"
        ));
    }
    let size = reader
        .output_buffer_size()
        .filter(|&n| n as u64 <= max_bytes)
        .ok_or_else(|| format!("{w} x {h} pixels needs more than {max_bytes} bytes"))?;
    let mut buf = vec![0; size];
    let frame = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
    buf.truncate(frame.buffer_size());
    let bad = || "the decoded PNG does not match its size".to_string();
    use png::{BitDepth, ColorType as C};
    Ok(match (frame.color_type, frame.bit_depth) {
        (C::Grayscale, BitDepth::Eight) => {
            DynamicImage::ImageLuma8(ImageBuffer::from_raw(w, h, buf).ok_or_else(bad)?)
        }
        (C::GrayscaleAlpha, BitDepth::Eight) => {
            DynamicImage::ImageLumaA8(ImageBuffer::from_raw(w, h, buf).ok_or_else(bad)?)
        }
        (C::Rgb, BitDepth::Eight) => {
            DynamicImage::ImageRgb8(ImageBuffer::from_raw(w, h, buf).ok_or_else(bad)?)
        }
        (C::Rgba, BitDepth::Eight) => {
            DynamicImage::ImageRgba8(ImageBuffer::from_raw(w, h, buf).ok_or_else(bad)?)
        }
        (color, BitDepth::Sixteen) => {
            let v: Vec<u16> = buf
                .chunks_exact(2)
                .map(|b| u16::from_be_bytes([b[0], b[1]]))
                .collect();
            match color {
                C::Grayscale => {
                    DynamicImage::ImageLuma16(ImageBuffer::from_raw(w, h, v).ok_or_else(bad)?)
                }
                C::GrayscaleAlpha => {
                    DynamicImage::ImageLumaA16(ImageBuffer::from_raw(w, h, v).ok_or_else(bad)?)
                }
                C::Rgb => DynamicImage::ImageRgb16(ImageBuffer::from_raw(w, h, v).ok_or_else(bad)?),
                C::Rgba => {
                    DynamicImage::ImageRgba16(ImageBuffer::from_raw(w, h, v).ok_or_else(bad)?)
                }
                C::Indexed => return Err("an indexed PNG was not expanded".into()),
            }
        }
        (color, depth) => return Err(format!("unexpected {color:?} at {depth:?} after expansion")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2 x 1 RGB PNG with an `iCCP` chunk whose profile inflates to `profile_bytes`.
    fn png_with_profile(profile_bytes: usize) -> Vec<u8> {
        let mut out = Vec::new();
        let mut info = png::Info::with_size(2, 1);
        info.color_type = png::ColorType::Rgb;
        info.bit_depth = png::BitDepth::Eight;
        info.icc_profile = Some(std::borrow::Cow::Owned(vec![0; profile_bytes]));
        let enc = png::Encoder::with_info(&mut out, info).unwrap();
        let mut w = enc.write_header().unwrap();
        w.write_image_data(&[10, 20, 30, 40, 50, 60]).unwrap();
        w.finish().unwrap();
        out
    }

    #[test]
    fn a_colour_profile_is_never_inflated() {
        let file = png_with_profile(8 << 20);
        assert!(file.len() < 64 << 10, "{} bytes", file.len());
        // A default decoder inflates all 8 MiB of it; the texture decoder does not.
        let plain = png::Decoder::new(std::io::Cursor::new(&file));
        let plain = plain.read_info().unwrap();
        assert_eq!(
            plain.info().icc_profile.as_ref().map(|p| p.len()),
            Some(8 << 20)
        );
        let ours = decoder(std::io::Cursor::new(&file), 1 << 20)
            .read_info()
            .unwrap();
        assert!(ours.info().icc_profile.is_none());
        let img = decode_png(std::io::Cursor::new(&file), 16, 1 << 20).unwrap();
        assert_eq!(img.to_rgb8().into_raw(), [10, 20, 30, 40, 50, 60]);
    }
}
