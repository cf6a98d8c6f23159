//! Presets inside PNG files: renders and screenshots carry the preset that made them in a text
//! chunk, so opening the PNG restores the scene.

use super::{SceneDesc, ShapeDesc, TextureDesc};
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
        super::parse_preset(&text, path)
    } else {
        super::load_preset(path)
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
    preset_text(reader.info(), path)?.ok_or_else(|| {
        Error::invalid(
            path,
            format!("this PNG has no '{PRESET_CHUNK}' text chunk (it was not saved by texplore)"),
        )
    })
}

/// The preset in `info`'s text chunks, inflated under 16 MiB (`MAX_PRESET_BYTES`).
fn preset_text(info: &png::Info<'_>, path: &Path) -> Result<Option<String>> {
    let limit = super::build::MAX_PRESET_BYTES;
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
    super::check_numbers(desc)
        .map_err(|m| Error::invalid(path, format!("not saved: the preset's {m}")))?;
    let mut desc = desc.clone();
    rebase_assets(&mut desc, preset_dir, png_dir);
    save_png_checked(
        path,
        &all,
        image.width,
        image.height,
        &image.rgb(),
        &[(PRESET_CHUNK, &super::to_ron(&desc))],
    )
}

/// The files `desc` reads (images, meshes, and an OBJ's material libraries and their
/// `map_Kd` images), with its asset paths taken relative to `preset_dir`; each once, in the
/// order the preset names them.
#[must_use]
pub fn asset_paths(desc: &SceneDesc, preset_dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = Vec::new();
    let mut add = |p: PathBuf| {
        if !out.contains(&p) {
            out.push(p);
        }
    };
    for o in &desc.objects {
        let alpha = o.alpha.as_ref().and_then(|a| a.texture());
        let bump = o.bump.as_ref().map(|b| &b.height);
        let normal = o.normal.as_ref().map(|n| &n.map);
        let displace = o.displace.as_ref().map(|d| &d.height);
        for t in o
            .material
            .textures()
            .into_iter()
            .map(|(_, t)| t)
            .chain(alpha)
            .chain(bump)
            .chain(normal)
            .chain(displace)
        {
            if let TextureDesc::Image { path, .. } = t {
                add(preset_dir.join(path));
            }
        }
        if let ShapeDesc::Mesh { path, .. } = &o.shape {
            let mesh = preset_dir.join(path);
            let is_obj = mesh
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
            let materials = if is_obj {
                crate::meshio::material_files(&mesh)
            } else {
                Vec::new()
            };
            add(mesh);
            materials.into_iter().for_each(&mut add);
        }
    }
    out
}

/// Rewrites every asset path of `desc` from relative-to-`from` to relative-to-`to` (absolute
/// when the two share no root).
pub fn rebase_assets(desc: &mut SceneDesc, from: &Path, to: &Path) {
    let rebase = |path: &mut String| {
        let abs = absolute(&from.join(&*path));
        *path = relative_to(&abs, &absolute(to))
            .to_string_lossy()
            .into_owned();
    };
    for o in &mut desc.objects {
        let alpha = o.alpha.as_mut().and_then(super::ScalarDesc::texture_mut);
        let bump = o.bump.as_mut().map(|b| &mut b.height);
        let normal = o.normal.as_mut().map(|n| &mut n.map);
        let displace = o.displace.as_mut().map(|d| &mut d.height);
        for t in o
            .material
            .textures_mut()
            .into_iter()
            .chain(alpha)
            .chain(bump)
            .chain(normal)
            .chain(displace)
        {
            if let TextureDesc::Image { path, .. } = t {
                rebase(path);
            }
        }
        if let ShapeDesc::Mesh { path, .. } = &mut o.shape {
            rebase(path);
        }
    }
}

/// `asset` written relative to the folder `preset_dir`, as a preset stores asset paths
/// (absolute when the two share no root).
#[must_use]
pub fn relative_asset_path(asset: &Path, preset_dir: &Path) -> String {
    relative_to(&absolute(asset), &absolute(preset_dir))
        .to_string_lossy()
        .into_owned()
}

fn absolute(p: &Path) -> PathBuf {
    std::fs::canonicalize(p)
        .unwrap_or_else(|_| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf()))
}

/// `target` relative to the directory `base` (both absolute).
fn relative_to(target: &Path, base: &Path) -> PathBuf {
    let t: Vec<_> = target.components().collect();
    let b: Vec<_> = base.components().collect();
    let common = t.iter().zip(&b).take_while(|(x, y)| x == y).count();
    if common == 0 {
        return target.to_path_buf();
    }
    let mut out = PathBuf::new();
    for _ in common..b.len() {
        out.push("..");
    }
    for c in &t[common..] {
        out.push(c);
    }
    out
}

/// The built-in presets in the order the lecture meets them: the Earth (its running example,
/// and the window's first scene), texel coordinates, spatially varying materials (the Earth by
/// day and night), the rectangular, cylindrical and spherical maps side by side on the UV grid,
/// the light probe, the panorama camera and the mirror ball, the triangle meshes with their own
/// (u, v), then beyond the lecture the checkers that show aliasing, bump and clip maps, and the
/// scene shared with Mitsuba. Menus list the presets in this order; a preset not named here
/// comes after them, by name.
pub const LECTURE_ORDER: [&str; 17] = [
    "earth",
    "texels",
    "earth-day-night",
    "rectangle",
    "cylinder",
    "uv-grid",
    "light-probe",
    "panorama",
    "mirror-ball-probe",
    "two-triangles",
    "mesh",
    "checker",
    "checker-plane",
    "bumps",
    "displaced",
    "cutout",
    "peer-sphere",
];

/// The presets (`*.ron`) in `dir` in [`LECTURE_ORDER`], each with its description (empty for a
/// file that does not parse); a missing folder lists none.
#[must_use]
pub fn presets_in_lecture_order(dir: &Path) -> Vec<(PathBuf, String)> {
    let mut presets = super::list_presets(dir).unwrap_or_default();
    let rank = |p: &PathBuf| {
        let stem = p.file_stem().map(|s| s.to_string_lossy().into_owned());
        let at = stem
            .as_deref()
            .and_then(|s| LECTURE_ORDER.iter().position(|o| *o == s));
        (at.unwrap_or(LECTURE_ORDER.len()), p.clone())
    };
    presets.sort_by_key(rank);
    presets
        .into_iter()
        .map(|p| {
            let description = super::load_preset(&p)
                .map(|d| d.description)
                .unwrap_or_default();
            (p, description)
        })
        .collect()
}

#[cfg(test)]
mod lecture_order_tests {
    use super::*;

    #[test]
    fn the_built_in_presets_come_in_the_lecture_order_with_their_descriptions() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
        let listed = presets_in_lecture_order(&dir);
        let stems: Vec<String> = listed
            .iter()
            .map(|(p, _)| p.file_stem().expect("stem").to_string_lossy().into_owned())
            .collect();
        // Every built-in preset has its place in the order (a new one must be given one).
        assert_eq!(stems, LECTURE_ORDER, "presets/ and LECTURE_ORDER differ");
        for (p, d) in &listed {
            assert!(!d.is_empty(), "{} has no description", p.display());
        }
        assert_eq!(
            listed[0].1,
            "The Blue Marble under the spherical map: the lecture's Earth"
        );
    }

    #[test]
    fn presets_not_in_the_order_follow_it_by_name() {
        let dir = tempfile::tempdir().expect("temp dir");
        for name in ["zebra", "cylinder", "apple", "earth"] {
            std::fs::write(
                dir.path().join(format!("{name}.ron")),
                format!("(version: 1, description: \"{name}\", objects: [])"),
            )
            .expect("write");
        }
        std::fs::write(dir.path().join("notes.txt"), "not a preset").expect("write");
        let stems: Vec<String> = presets_in_lecture_order(dir.path())
            .into_iter()
            .map(|(p, _)| p.file_stem().expect("stem").to_string_lossy().into_owned())
            .collect();
        assert_eq!(stems, ["earth", "cylinder", "apple", "zebra"]);
    }
}
