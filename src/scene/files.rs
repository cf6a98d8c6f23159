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

/// The preset embedded in a PNG's text chunk.
///
/// # Errors
/// Not a PNG, or no texplore preset inside.
pub fn read_png_preset(path: &Path) -> Result<String> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let decoder = png::Decoder::new(std::io::BufReader::new(file));
    let reader = decoder.read_info().map_err(|e| Error::Image {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let info = reader.info();
    let found = info
        .utf8_text
        .iter()
        .find(|c| c.keyword == PRESET_CHUNK)
        .and_then(|c| c.get_text().ok())
        .or_else(|| {
            info.uncompressed_latin1_text
                .iter()
                .find(|c| c.keyword == PRESET_CHUNK)
                .map(|c| c.text.clone())
        });
    found.ok_or_else(|| {
        Error::invalid(
            path,
            format!("this PNG has no '{PRESET_CHUNK}' text chunk (it was not saved by texplore)"),
        )
    })
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

/// The files `desc` reads (images and meshes), with its asset paths taken relative to
/// `preset_dir`.
#[must_use]
pub fn asset_paths(desc: &SceneDesc, preset_dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for o in &desc.objects {
        if let TextureDesc::Image { path, .. } = o.material.texture() {
            out.push(preset_dir.join(path));
        }
        if let ShapeDesc::Mesh { path, .. } = &o.shape {
            out.push(preset_dir.join(path));
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
        if let TextureDesc::Image { path, .. } = o.material.texture_mut() {
            rebase(path);
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
