//! The scene panel: the objects and, for the selected one, shape, transform, material, texture,
//! mapping, filter and wrap; globally the sampler, samples, camera, lights, exposure and the
//! resolution scale. Returns whether anything changed, so the app re-renders.
//!
//! One file per editor: [`object`] (shape and transform), [`material`], [`texture`] (with the
//! image path and the assets list), [`maps`] (clip, bump, normal and displacement maps), [`render`]
//! settings, [`camera`] and [`lights`]. The kinds each menu offers, their names, tooltips and
//! defaults come from [`crate::scene`].

mod camera;
mod formula;
mod formula_fields;
mod lights;
mod maps;
mod material;
mod object;
mod render;
mod texture;

use crate::geometry::Shading;
use crate::gui::document::ObjectId;
use crate::gui::files::{BrowseFor, Browser};
use crate::names::Named;
use crate::scene::{
    ObjectDesc, ProjectionDesc, ProjectionKind, SceneDesc, ShapeDesc, TextureDesc, TextureKind,
};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// What the scene panel keeps between frames (the selection, half-typed paths, a mesh being
/// chosen, the images the objects had, the asset list); the scene itself is the [`SceneDesc`]
/// passed to it.
#[derive(Default)]
pub struct ScenePanel {
    /// Index into `SceneDesc::objects` of the object the panel edits.
    pub selected: usize,
    /// The selected object's id: what the panel remembers about an object is kept under it,
    /// so it follows the object through removals, undo, redo and lessons.
    key: ObjectId,
    /// The image path being typed, applied with Enter or "Load".
    path_text: Option<PathText>,
    /// The mesh path being typed.
    mesh_text: Option<PathText>,
    /// Shape -> Mesh was chosen for this object: the file asked for before the shape changes.
    mesh_prompt: Option<(ObjectId, String)>,
    /// Per object, the image texture it had before its kind was switched away from Image, its
    /// path absolute (so a "Save as" into another folder does not break it).
    last_image: HashMap<ObjectId, TextureDesc>,
    /// The images in assets/, and the preset they were listed for (listed again when the scene
    /// moves to another folder, after *Save as* or opening another file).
    assets: Option<(PathBuf, Vec<PathBuf>)>,
    /// What the *Browse…* buttons ask.
    browser: Browser,
    /// Each camera projection as it was when switched away from (restored when switched back).
    projections: HashMap<ProjectionKind, ProjectionDesc>,
    /// The clip, bump, normal and displacement maps switched off, the bump/normal note, a
    /// displacement scale being dragged.
    maps: maps::MapMemory,
    /// The comparison of a formula mapping with a built-in one, and the scene shown.
    formula: formula::FormulaCheck,
}

/// What a texture editor needs to choose an image: the *Browse…* dialog, the preset its paths
/// are relative to, and the object edited (a half-typed path belongs to one object).
pub(super) struct ImagePicker<'a> {
    browser: &'a Browser,
    preset: &'a Path,
    /// The object's id as a number ([`ObjectId::number`]).
    object: usize,
}

/// The text of a path field: a view of one object's path in one preset, read again from the
/// scene whenever the object, the path or the preset changes, so it never shows a path the
/// scene does not have (after "Save as", opening another file, picking an asset).
struct PathText {
    object: ObjectId,
    path: String,
    preset: PathBuf,
    text: String,
}

impl PathText {
    /// The text for `object`'s `path` in `preset`: the typing kept in `slot` while it is about
    /// that same path, else the path itself.
    fn synced<'a>(
        slot: &'a mut Option<Self>,
        object: ObjectId,
        path: &str,
        preset: &Path,
    ) -> &'a mut String {
        if slot
            .as_ref()
            .is_some_and(|t| t.object != object || t.path != path || t.preset != preset)
        {
            *slot = None;
        }
        &mut slot
            .get_or_insert_with(|| Self {
                object,
                path: path.to_owned(),
                preset: preset.to_path_buf(),
                text: path.to_owned(),
            })
            .text
    }
}

fn object_label(i: usize, o: &ObjectDesc) -> String {
    if o.name.is_empty() {
        format!("{i}: {}", o.shape.kind().name())
    } else {
        format!("{i}: {}", o.name)
    }
}

impl ScenePanel {
    /// A panel whose *Browse…* buttons ask `browser`.
    #[must_use]
    pub fn with_browser(browser: Browser) -> Self {
        Self {
            browser,
            ..Self::default()
        }
    }

    /// Puts the image at `path` (relative to the preset) on the selected object, keeping its
    /// mapping.
    pub fn use_image(&mut self, desc: &mut SceneDesc, path: String) {
        let Some(obj) = desc.objects.get_mut(self.selected) else {
            return;
        };
        let tex = obj.material.texture_mut();
        if !matches!(tex, TextureDesc::Image { .. }) {
            *tex = tex.converted(TextureKind::Image);
        }
        if let TextureDesc::Image { path: p, .. } = tex {
            *p = path;
        }
        self.path_text = None;
    }

    /// The scene the viewport shows (its formula's NaN count and comparison are read from it).
    pub fn show_scene(&mut self, scene: Option<std::sync::Arc<crate::scene::Scene>>) {
        self.formula.shown = scene;
    }

    /// Forgets everything typed or remembered about the previous scene: called when another
    /// scene opens, so no field shows a file of the old one.
    pub fn scene_replaced(&mut self) {
        self.selected = 0;
        self.path_text = None;
        self.mesh_text = None;
        self.mesh_prompt = None;
        self.last_image.clear();
        self.assets = None;
        self.projections.clear();
        self.maps = maps::MapMemory::default();
    }

    /// Makes the selected object the mesh at `path` (relative to the preset).
    pub fn use_mesh(&mut self, desc: &mut SceneDesc, path: String) {
        if let Some(obj) = desc.objects.get_mut(self.selected) {
            obj.shape = ShapeDesc::Mesh {
                path,
                shading: Shading::default(),
            };
            self.mesh_text = None;
            self.mesh_prompt = None;
        }
    }

    /// The panel over `desc`, whose objects have the `ids` (an object removed here is removed
    /// from them; the app gives objects added at the end fresh ids). Returns whether the scene
    /// changed.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        desc: &mut SceneDesc,
        ids: &mut Vec<ObjectId>,
        resolution: &mut crate::gui::resolution::ViewResolution,
        preset: &Path,
    ) -> bool {
        let mut changed = false;
        ui.heading("Objects");
        let mut remove = None;
        for (i, o) in desc.objects.iter().enumerate() {
            if ui
                .selectable_label(self.selected == i, object_label(i, o))
                .clicked()
            {
                self.selected = i;
                self.path_text = None;
                self.mesh_text = None;
                self.mesh_prompt = None;
            }
        }
        ui.horizontal(|ui| {
            if ui
                .button("Duplicate")
                .on_hover_text("Adds a copy of the selected object, moved up by 2")
                .clicked()
                && let Some(o) = desc.objects.get(self.selected).cloned()
            {
                let mut o = o;
                o.transform.translate.y += 2.0;
                o.name = String::new();
                desc.objects.push(o);
                ids.push(ObjectId::fresh());
                self.selected = desc.objects.len() - 1;
                changed = true;
            }
            if desc.objects.len() > 1
                && ui
                    .button("Remove")
                    .on_hover_text("Removes the selected object")
                    .clicked()
            {
                remove = Some(self.selected);
            }
        });
        if let Some(i) = remove {
            desc.objects.remove(i);
            if i < ids.len() {
                ids.remove(i);
            }
            // What is remembered about the objects stays under their ids: the object removed
            // may come back with Undo.
            self.mesh_prompt = None;
            self.maps.object_removed();
            self.selected = self.selected.min(desc.objects.len().saturating_sub(1));
            changed = true;
        }
        self.key = ids.get(self.selected).copied().unwrap_or_default();
        if let Some(obj) = desc.objects.get_mut(self.selected) {
            ui.separator();
            changed |= self.object_ui(ui, obj, &mut desc.render, preset);
        }
        ui.separator();
        changed |= render::render_ui(ui, desc, resolution);
        ui.separator();
        changed |= camera::camera_ui(ui, desc, &mut self.projections);
        ui.separator();
        changed |= lights::lights_ui(ui, desc);
        changed
    }
}

/// A labelled path field for `object`'s `path` in `preset`, applied with Enter or "Load", or
/// chosen with *Browse…* (`browser`, for `what`); `text` holds the typing while it is about
/// that path (see [`PathText`]).
#[allow(clippy::too_many_arguments)]
fn path_field(
    ui: &mut egui::Ui,
    label: &str,
    path: &mut String,
    text: &mut Option<PathText>,
    object: ObjectId,
    preset: &Path,
    browser: &Browser,
    what: BrowseFor,
) -> bool {
    let buf = PathText::synced(text, object, path, preset);
    let mut changed = false;
    ui.horizontal(|ui| {
        let l = ui.label(label);
        let r = ui
            .add(
                egui::TextEdit::singleline(buf)
                    .desired_width((ui.available_width() - 130.0).max(80.0)),
            )
            .labelled_by(l.id)
            .on_hover_text("Path relative to the preset's folder; Enter loads it");
        let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        if (ui
            .button("Load")
            .on_hover_text("Load the file at this path")
            .clicked()
            || enter)
            && *buf != *path
        {
            path.clone_from(buf);
            changed = true;
        }
        if let Some(p) = browse_button(ui, browser, what, preset) {
            *path = p;
            changed = true;
        }
    });
    if changed {
        *text = None;
    }
    changed
}

/// A *Browse…* button: the file chosen, relative to `preset`'s folder.
fn browse_button(
    ui: &mut egui::Ui,
    browser: &Browser,
    what: BrowseFor,
    preset: &Path,
) -> Option<String> {
    let clicked = ui
        .button("Browse…")
        .on_hover_text("Choose the file in the system's file dialog")
        .clicked();
    if !clicked {
        return None;
    }
    let dir = preset
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let picked = browser.pick(what, dir, "")?;
    Some(crate::scene::relative_asset_path(&picked, dir))
}
