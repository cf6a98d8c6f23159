//! Presets: the whole scene's description ([`SceneDesc`]), in text ([`text`]) and in PNG files
//! ([`png`]), the files it names, the check of its numbers, and [`build_scene`], which builds the
//! runtime [`Scene`] from one.

mod numbers;
mod paths;
mod png;
mod text;

pub use numbers::check_numbers;
pub use paths::{asset_paths, rebase_assets, relative_asset_path};
pub use png::{
    MAX_PNG_ANCILLARY_BYTES, PRESET_CHUNK, read_png_preset, read_preset_or_png, save_render_png,
    save_render_png_checked,
};
pub use text::{MAX_PRESET_BYTES, load_preset, parse_preset, save_preset, to_ron};

use super::assets::AssetCache;
use super::camera::{CameraDesc, camera};
use super::light::{AmbientDesc, LightDesc, ambient, light};
use super::object::{ObjectDesc, build_object};
use super::settings::{RenderDesc, SnapshotDesc, render_settings};
use super::trace::Scene;
use crate::error::{Error, Result};
use crate::field::{FieldPath, Refusal, field_name};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The preset format version this build reads and writes.
pub const PRESET_VERSION: u32 = 1;

/// A whole scene: camera, lights, objects and render settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDesc {
    /// Preset format version ([`PRESET_VERSION`]).
    pub version: u32,
    /// One line saying what the scene shows.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// Where the eye is and what it sees; required (at least `eye`).
    pub camera: CameraDesc,
    /// Resolution, samples, seed, exposure; every field defaults (see [`RenderDesc`]).
    #[serde(default)]
    pub render: RenderDesc,
    /// Light from every direction, which lit materials scale by their `ka`; default white at
    /// `ls` 1.
    #[serde(default)]
    pub ambient: AmbientDesc,
    /// Directional and point lights, each added to the ambient term; default none.
    #[serde(default)]
    pub lights: Vec<LightDesc>,
    /// Required, but may be empty (the render is then all `render.background`). Each ray takes
    /// the nearest hit, so order matters only where two surfaces coincide (the earlier wins).
    pub objects: Vec<ObjectDesc>,
    /// Settings for `texplore snapshot`.
    #[serde(default)]
    pub snapshot: SnapshotDesc,
}

impl SceneDesc {
    /// The name of the object `path` is in, if the path is in an object that has a name.
    #[must_use]
    pub fn object_name(&self, path: &FieldPath) -> Option<&str> {
        path.object()
            .and_then(|i| self.objects.get(i))
            .map(|o| o.name.as_str())
            .filter(|n| !n.is_empty())
    }

    /// Field `path` as every message names it ([`field_name`]): `objects[0].material.ka
    /// (object "Ball")`.
    #[must_use]
    pub fn name_field(&self, path: &FieldPath) -> String {
        field_name(path, self.object_name(path))
    }

    /// A refusal of one of this description's fields as a message: the field named by
    /// [`SceneDesc::name_field`], then why.
    #[must_use]
    pub fn refusal_message(&self, r: &Refusal) -> String {
        if r.field.steps().is_empty() {
            r.message.clone()
        } else {
            format!("{}: {}", self.name_field(&r.field), r.message)
        }
    }
}

/// Builds the runtime scene. `preset_path` names the file in errors; asset paths are resolved
/// relative to its directory. The scene's images together must fit
/// [`MAX_SCENE_TEXEL_BYTES`](super::MAX_SCENE_TEXEL_BYTES) and its displaced meshes
/// [`MAX_SCENE_DISPLACED_TRIANGLES`](super::MAX_SCENE_DISPLACED_TRIANGLES), each file counted
/// once however its path is spelled.
///
/// # Errors
/// An out-of-range value (naming the field), an asset that cannot be loaded, or one that does
/// not fit what the scene's other assets leave of its budget (naming the field).
pub fn build_scene(desc: &SceneDesc, preset_path: &Path, cache: &mut AssetCache) -> Result<Scene> {
    cache.scene(|cache| build(desc, preset_path, cache))
}

fn build(desc: &SceneDesc, preset_path: &Path, cache: &mut AssetCache) -> Result<Scene> {
    let bad = |r: Refusal| {
        let object = desc.object_name(&r.field).unwrap_or_default();
        Error::refused(preset_path, r).in_object(object)
    };
    check_numbers(desc).map_err(bad)?;
    let settings = render_settings(&desc.render).map_err(bad)?;
    let camera = camera(&desc.camera, settings.width, settings.height).map_err(bad)?;
    let ambient = ambient(&desc.ambient).map_err(bad)?;

    let mut lights = Vec::with_capacity(desc.lights.len());
    for (i, l) in desc.lights.iter().enumerate() {
        let here = FieldPath::field("lights").at(i);
        lights.push(light(l).map_err(|r| bad(r.under(&here)))?);
    }

    let mut objects = Vec::with_capacity(desc.objects.len());
    let mut materials = Vec::with_capacity(desc.objects.len());
    let mut needs_differentials = false;
    let mut surfaces = Vec::with_capacity(desc.objects.len());
    for (i, o) in desc.objects.iter().enumerate() {
        let built = build_object(o, i, materials.len(), preset_path, cache)?;
        needs_differentials |= built.needs_differentials || settings.view.needs_footprint();
        objects.push(built.object);
        materials.push(built.material);
        surfaces.push(built.surface);
    }
    let has_clips = surfaces.iter().any(|s| s.clip.is_some());
    let has_perturbations = surfaces.iter().any(|s| s.perturbation.is_some());
    Ok(Scene {
        objects,
        materials,
        lights,
        ambient,
        camera,
        settings,
        surfaces,
        needs_differentials,
        has_clips,
        has_perturbations,
    })
}

/// The presets in `dir` (`*.ron`), sorted by name.
///
/// # Errors
/// The directory cannot be read.
pub fn list_presets(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut v: Vec<PathBuf> = crate::input::list_dir(dir)?
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    v.sort();
    Ok(v)
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
    let mut presets = list_presets(dir).unwrap_or_default();
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
            let description = load_preset(&p).map(|d| d.description).unwrap_or_default();
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
