//! Presets inside PNG files: renders and screenshots carry the preset that made them in a text
//! chunk, so opening the PNG restores the scene.

use super::SceneDesc;
use super::numbers::check_numbers;
use super::paths::{asset_paths, rebase_assets};
use super::text::{MAX_PRESET_BYTES, load_preset, parse_preset, to_ron};
use crate::error::{Error, Result};
use crate::math::DisplayImage;
use crate::texture::save_png_checked;
use std::path::{Path, PathBuf};

/// The PNG text-chunk keyword under which renders and screenshots carry their preset.
pub const PRESET_CHUNK: &str = "texplore-preset";

/// Reads a preset from a `.ron` file or from the text chunk of a PNG texplore saved.
///
/// # Errors
/// The file cannot be read or holds no valid preset.
pub fn read_preset_or_png(path: &Path) -> Result<SceneDesc> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        let text = read_png_preset(path)?;
        parse_preset(&text, path)
    } else {
        load_preset(path)
    }
}

/// Most bytes the PNG decoder may hold for a screenshot's ancillary chunks (text, the colour
/// profile is skipped) while looking for the preset: room for a preset of
/// 16 MiB (`MAX_PRESET_BYTES`) stored uncompressed, and no more.
pub const MAX_PNG_ANCILLARY_BYTES: usize = 64 << 20;

/// The preset embedded in a PNG's text chunk (`tEXt`, `zTXt` or `iTXt`, before or after the
/// image data), at most 16 MiB (`MAX_PRESET_BYTES`) once inflated.
///
/// # Errors
/// Not a regular file, not a PNG, no texplore preset inside, or a preset above the limit.
pub fn read_png_preset(path: &Path) -> Result<String> {
    let file = crate::input::open_input(path)?;
    let image_err = |e: png::DecodingError| Error::Image {
        path: path.to_path_buf(),
        message: match e {
            png::DecodingError::LimitsExceeded => format!(
                "its text chunks take more than {}",
                crate::input::human_bytes(MAX_PNG_ANCILLARY_BYTES as u64)
            ),
            e => e.to_string(),
        },
    };
    let mut decoder = png::Decoder::new_with_limits(
        std::io::BufReader::new(file),
        png::Limits {
            bytes: MAX_PNG_ANCILLARY_BYTES,
        },
    );
    // The colour profile is of no use here, and it can be a deflate bomb.
    decoder.set_ignore_iccp_chunk(true);
    let mut reader = decoder.read_info().map_err(image_err)?;
    if let Some(text) = preset_text(reader.info(), path)? {
        return Ok(text);
    }
    // Text chunks may also follow the image data.
    reader.finish().map_err(image_err)?;
    if let Some(text) = preset_text(reader.info(), path)? {
        return Ok(text);
    }
    // The decoder drops a text chunk it cannot read (an iTXt chunk that is not UTF-8): say that
    // the chunk is there but broken, rather than missing.
    if let Some(kind) = raw_text_chunk(path)? {
        return Err(Error::invalid(
            path,
            format!(
                "its '{PRESET_CHUNK}' {kind} chunk is not valid text (an iTXt chunk must be UTF-8, \
                 a tEXt or zTXt chunk Latin-1): the preset cannot be read"
            ),
        ));
    }
    Err(Error::invalid(
        path,
        format!("this PNG has no '{PRESET_CHUNK}' text chunk (it was not saved by texplore)"),
    ))
}

/// The type of a text chunk (`tEXt`, `zTXt`, `iTXt`) whose keyword is [`PRESET_CHUNK`], found
/// by walking the file's chunk headers (each chunk's data is skipped, not read; the walk ends
/// at `IEND`, at the end of the file or at a header that runs past it).
fn raw_text_chunk(path: &Path) -> Result<Option<&'static str>> {
    use std::io::{Read, Seek, SeekFrom};
    let mut file = crate::input::open_input(path)?;
    let io = |e: std::io::Error| Error::io(path, e);
    let len = file.seek(SeekFrom::End(0)).map_err(io)?;
    let mut pos = 8u64;
    let key = PRESET_CHUNK.as_bytes();
    while pos + 12 <= len {
        file.seek(SeekFrom::Start(pos)).map_err(io)?;
        let mut header = [0u8; 8];
        file.read_exact(&mut header).map_err(io)?;
        let size = u64::from(u32::from_be_bytes([
            header[0], header[1], header[2], header[3],
        ]));
        let kind = match &header[4..] {
            b"tEXt" => Some("tEXt"),
            b"zTXt" => Some("zTXt"),
            b"iTXt" => Some("iTXt"),
            b"IEND" => return Ok(None),
            _ => None,
        };
        if let Some(kind) = kind
            && size > key.len() as u64
        {
            let mut keyword = vec![0u8; key.len() + 1];
            file.read_exact(&mut keyword).map_err(io)?;
            if &keyword[..key.len()] == key && keyword[key.len()] == 0 {
                return Ok(Some(kind));
            }
        }
        pos += 12 + size;
    }
    Ok(None)
}

/// The preset in `info`'s text chunks, inflated under 16 MiB (`MAX_PRESET_BYTES`).
fn preset_text(info: &png::Info<'_>, path: &Path) -> Result<Option<String>> {
    let limit = MAX_PRESET_BYTES;
    let too_large = || {
        Error::invalid(
            path,
            format!(
                "the preset in its '{PRESET_CHUNK}' chunk is larger than {}",
                crate::input::human_bytes(limit)
            ),
        )
    };
    let inflate_err = |e: png::DecodingError| match e {
        png::DecodingError::Format(_) if e.to_string().contains("decompression space") => {
            too_large()
        }
        e => Error::invalid(
            path,
            format!("its '{PRESET_CHUNK}' chunk cannot be read: {e}"),
        ),
    };
    let text = if let Some(c) = info.utf8_text.iter().find(|c| c.keyword == PRESET_CHUNK) {
        let mut c = c.clone();
        c.decompress_text_with_limit(limit as usize)
            .map_err(inflate_err)?;
        c.get_text().map_err(inflate_err)?
    } else if let Some(c) = info
        .compressed_latin1_text
        .iter()
        .find(|c| c.keyword == PRESET_CHUNK)
    {
        let mut c = c.clone();
        c.decompress_text_with_limit(limit as usize)
            .map_err(inflate_err)?;
        c.get_text().map_err(inflate_err)?
    } else if let Some(c) = info
        .uncompressed_latin1_text
        .iter()
        .find(|c| c.keyword == PRESET_CHUNK)
    {
        c.text.clone()
    } else {
        return Ok(None);
    };
    if text.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(Some(text))
}

/// Writes a display image as an sRGB PNG with `desc` in a text chunk (atomically). `desc`'s
/// asset paths are relative to `preset_dir`; the embedded copy's are rewritten relative to the
/// PNG's folder, so opening the PNG from where it was saved finds the assets. The PNG never
/// replaces one of those assets.
///
/// # Errors
/// The PNG is refused or cannot be written: "cannot write FILE: reason".
pub fn save_render_png(
    path: &Path,
    image: &DisplayImage,
    desc: &SceneDesc,
    preset_dir: &Path,
) -> Result<()> {
    save_render_png_checked(path, &[], image, desc, preset_dir)
}

/// [`save_render_png`] that also refuses to write over any of `inputs` (the preset file).
///
/// # Errors
/// The PNG is refused or cannot be written: "cannot write FILE: reason".
pub fn save_render_png_checked(
    path: &Path,
    inputs: &[&Path],
    image: &DisplayImage,
    desc: &SceneDesc,
    preset_dir: &Path,
) -> Result<()> {
    let png_dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let assets = asset_paths(desc, preset_dir);
    let all: Vec<&Path> = inputs
        .iter()
        .copied()
        .chain(assets.iter().map(PathBuf::as_path))
        .collect();
    check_numbers(desc).map_err(|r| {
        let m = desc.refusal_message(&r);
        Error::invalid(path, format!("not saved: the preset's {m}"))
    })?;
    let mut desc = desc.clone();
    rebase_assets(&mut desc, preset_dir, png_dir);
    save_png_checked(
        path,
        &all,
        image.width,
        image.height,
        &image.rgb(),
        &[(PRESET_CHUNK, &to_ron(&desc))],
    )
}
