//! The files a preset reads, and its asset paths rebased from one folder to another.

use super::super::object::ShapeDesc;
use super::super::texture::TextureDesc;
use super::SceneDesc;
use std::path::{Path, PathBuf};

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
        for (_, t) in o.textures() {
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
        for (_, t) in o.textures_mut() {
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
    // A page has no file system (wasm32): its files are mounted under paths relative to the
    // page, so they are made absolute lexically from there (`uploads/x.png` seen from
    // `presets/` is `../uploads/x.png`).
    #[cfg(target_arch = "wasm32")]
    return Path::new("/").join(crate::input::normalise(p));
    #[cfg(not(target_arch = "wasm32"))]
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
