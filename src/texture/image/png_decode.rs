//! PNG textures through the `png` crate directly, so that the decoder skips what a texture does
//! not need and what can be a deflate bomb: the colour profile (`iCCP`, which `image`'s decoder
//! inflates up to its whole allocation limit) and the text chunks.

use super::{ImageRequest, Layout, Sample, Storage};
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

/// Decodes a PNG into its texel storage, the budget checked from the header. A plain PNG is
/// converted row by row as it is inflated (the peak is the storage and one row); an interlaced
/// one through one buffer of the whole image (its rows arrive in seven passes).
///
/// # Errors
/// What the decoder reports (missing data, a bad checksum), or a size above the limits.
pub(super) fn decode_png(
    r: impl BufRead + std::io::Seek,
    req: ImageRequest,
) -> Result<Storage, String> {
    let max_bytes = super::MAX_IMAGE_BYTES;
    let mut reader = decoder(r, max_bytes)
        .read_info()
        .map_err(|e| e.to_string())?;
    let (w, h) = (reader.info().width, reader.info().height);
    let (color, depth) = reader.output_color_type();
    let sample = match depth {
        png::BitDepth::Eight => Sample::U8,
        png::BitDepth::Sixteen => Sample::U16Be,
        _ => return Err(format!("unexpected {color:?} at {depth:?} after expansion")),
    };
    if color == png::ColorType::Indexed {
        return Err("an indexed PNG was not expanded".into());
    }
    let layout = Layout {
        channels: color.samples(),
        sample,
    };
    let Some(mut storage) = Storage::new(w, h, layout, req)? else {
        return Storage::stand_in(w, h, layout, req);
    };
    if reader.info().interlaced {
        let size = reader
            .output_buffer_size()
            .filter(|&n| n as u64 <= max_bytes)
            .ok_or_else(|| format!("{w} x {h} pixels needs more than {max_bytes} bytes"))?;
        let mut buf = super::zeroed::<u8>(size, "the decoder")?;
        let frame = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
        storage.put_rows(&buf[..frame.buffer_size().min(size)], layout)?;
    } else {
        let mut row = 0;
        while row < h {
            let Some(line) = reader.next_row().map_err(|e| e.to_string())? else {
                return Err("truncated image data".into());
            };
            storage.put_row(row, line.data(), layout);
            row += 1;
        }
        check_image_data_crc(&mut reader)?;
    }
    Ok(storage)
}

/// Reads past the last row to the end of the file, so that the checksum of the image data's last
/// chunk is checked: the rows are all decoded before it is reached, and a corrupt image would
/// otherwise be accepted (PngSuite's `xcsn0g01.png`). Only a bad `IDAT` checksum is refused;
/// what follows the image data (text, a missing `IEND`) cannot change the pixels, so problems
/// there are ignored as browsers ignore them.
fn check_image_data_crc<R: BufRead + std::io::Seek>(
    reader: &mut png::Reader<R>,
) -> Result<(), String> {
    match reader.finish() {
        Err(e) if e.to_string().contains("CRC error") && e.to_string().contains("IDAT") => {
            Err("the image data is corrupt: an IDAT chunk's checksum (CRC) is wrong".into())
        }
        _ => Ok(()),
    }
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
        let img = decode_png(std::io::Cursor::new(&file), ImageRequest::colour(true)).unwrap();
        let super::super::Texels::Srgb8(texels) = &img.texels else {
            panic!("8-bit sRGB texels expected");
        };
        assert_eq!(texels[..2], [[10, 20, 30, 255], [40, 50, 60, 255]]);
    }
}
