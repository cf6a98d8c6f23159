//! OpenEXR: RGB(A) through the `image` crate; luminance-only (Y) and luminance-chroma (Y, RY, BY)
//! images, which `image` refuses, through the `exr` crate's channels, turned into RGB here.

use super::{F32_RGB, ImageRequest, MAX_IMAGE_BYTES, Storage, approx_bytes, from_decoder};
use exr::prelude::{ReadChannels, ReadLayers};
use std::io::{BufRead, Seek, SeekFrom};

/// Rec. 709's luminance weights of red, green and blue: OpenEXR's default primaries, with which
/// its luminance-chroma images are made (`RY = R / Y - 1`, `BY = B / Y - 1`).
const REC709: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// Decodes an OpenEXR file into its texel storage: RGB(A) as `image` reads it (the display
/// window, the first layer with R, G and B), else the first layer with a `Y` channel: grey, or
/// RGB from `Y`, `RY` and `BY`.
///
/// # Errors
/// A malformed file, a size above the limits, no colour channels, or chroma stored at a lower
/// resolution than luminance (named as not supported).
pub(super) fn decode_exr<R: BufRead + Seek>(
    mut r: R,
    req: ImageRequest,
) -> Result<Storage, String> {
    let start = r.stream_position().map_err(|e| e.to_string())?;
    let rgb = image::codecs::openexr::OpenExrDecoder::new(&mut r).and_then(|mut d| {
        image::ImageDecoder::set_limits(&mut d, super::limits())?;
        Ok(d)
    });
    let message = match rgb {
        Ok(decoder) => return from_decoder(decoder, req),
        Err(e) => e.to_string(),
    };
    if message.contains("subsampling") {
        return Err(
            "luminance-chroma OpenEXR with subsampled chroma (RY and BY at a lower resolution \
             than Y) is not supported"
                .into(),
        );
    }
    if !message.contains("rgb channels") {
        return Err(message);
    }
    r.seek(SeekFrom::Start(start)).map_err(|e| e.to_string())?;
    decode_luminance(r, req)
}

/// The Y (and RY, BY) layer of an OpenEXR file without R, G and B.
fn decode_luminance<R: BufRead + Seek>(mut r: R, req: ImageRequest) -> Result<Storage, String> {
    let start = r.stream_position().map_err(|e| e.to_string())?;
    // The budget from the header, before any pixel is decoded.
    let meta = exr::meta::MetaData::read_from_buffered(&mut r, false).map_err(|e| e.to_string())?;
    let has =
        |h: &exr::meta::header::Header, name: &str| h.channels.list.iter().any(|c| c.name.eq(name));
    let header = meta
        .headers
        .iter()
        .find(|h| !h.deep && has(h, "Y"))
        .ok_or("no R, G and B channels, and no luminance (Y) channel")?;
    let display = header.shared_attributes.display_window;
    let (w, h) = (display.size.width() as u32, display.size.height() as u32);
    let Some(mut storage) = Storage::new(w, h, F32_RGB, req)? else {
        return Storage::stand_in(w, h, F32_RGB, req);
    };
    let decoded: u64 = meta
        .headers
        .iter()
        .map(|h| h.layer_size.area() as u64 * h.channels.list.len() as u64 * 4)
        .sum();
    if decoded > MAX_IMAGE_BYTES {
        return Err(format!(
            "the decoder needs {}, above the {} limit",
            approx_bytes(decoded),
            approx_bytes(MAX_IMAGE_BYTES)
        ));
    }
    r.seek(SeekFrom::Start(start)).map_err(|e| e.to_string())?;
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .non_parallel()
        .from_buffered(r)
        .map_err(|e| e.to_string())?;
    let layer = image
        .layer_data
        .iter()
        .find(|l| l.channel_data.list.iter().any(|c| c.name.eq("Y")))
        .ok_or("no luminance (Y) channel")?;
    let channel = |name: &str| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.eq(name))
            .map(|c| c.sample_data.values_as_f32().collect::<Vec<f32>>())
    };
    let y = channel("Y").ok_or("no luminance (Y) channel")?;
    let chroma = channel("RY").zip(channel("BY"));
    let size = layer.size;
    // Where the layer's pixels are in the display window (the rest stays 0).
    let offset = layer.attributes.layer_position - display.position;
    let mut row = vec![0u8; w as usize * 12];
    for dy in 0..i64::from(h) {
        row.fill(0);
        let ly = dy - i64::from(offset.y());
        if ly >= 0 && (ly as usize) < size.height() {
            for dx in 0..i64::from(w) {
                let lx = dx - i64::from(offset.x());
                if lx < 0 || lx as usize >= size.width() {
                    continue;
                }
                let i = ly as usize * size.width() + lx as usize;
                let rgb = match &chroma {
                    None => [y[i]; 3],
                    Some((ry, by)) => {
                        let (r, b) = ((ry[i] + 1.0) * y[i], (by[i] + 1.0) * y[i]);
                        [r, (y[i] - REC709[0] * r - REC709[2] * b) / REC709[1], b]
                    }
                };
                let at = dx as usize * 12;
                for (k, v) in rgb.iter().enumerate() {
                    row[at + 4 * k..at + 4 * k + 4].copy_from_slice(&v.to_ne_bytes());
                }
            }
        }
        storage.put_row(dy as u32, &row, F32_RGB);
    }
    Ok(storage)
}
