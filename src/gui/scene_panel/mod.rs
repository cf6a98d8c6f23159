//! The scene panel: the objects and, for the selected one, shape, transform, material, texture,
//! mapping, filter and wrap; globally the sampler, samples, camera, lights, exposure and the
//! resolution scale. Returns whether anything changed, so the app re-renders.
//!
//! One file per editor: [`object`] (shape and transform), [`material`], [`texture`] (with the
//! image path and the assets list), [`render`] settings, [`camera`] and [`lights`]. The kinds
//! each menu offers, their names, tooltips and defaults come from [`crate::scene`].

mod camera;
mod lights;
mod material;
mod object;
mod render;
mod texture;

use crate::geometry::Shading;
use crate::names::Named;
use crate::scene::{ObjectDesc, SceneDesc, ShapeDesc, TextureDesc, TextureKind};
use std::path::{Path, PathBuf};

/// What the scene panel keeps between frames (the selection, half-typed paths, the asset
/// list); the scene itself is the [`SceneDesc`] passed to it.
#[derive(Default)]
pub struct ScenePanel {
    /// Index into `SceneDesc::objects` of the object the panel edits.
    pub selected: usize,
    /// The image path being typed, applied with Enter or "Load".
    path_text: Option<(usize, String)>,
    /// The mesh path being typed.
    mesh_text: Option<(usize, String)>,
    assets: Option<Vec<PathBuf>>,
}

fn object_label(i: usize, o: &ObjectDesc) -> String {
    if o.name.is_empty() {
        format!("{i}: {}", o.shape.kind().name())
    } else {
        format!("{i}: {}", o.name)
    }
}

impl ScenePanel {
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

    /// Makes the selected object the mesh at `path` (relative to the preset).
    pub fn use_mesh(&mut self, desc: &mut SceneDesc, path: String) {
        if let Some(obj) = desc.objects.get_mut(self.selected) {
            obj.shape = ShapeDesc::Mesh {
                path,
                shading: Shading::default(),
            };
            self.mesh_text = None;
        }
    }

    /// The panel. Returns whether the scene changed.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        desc: &mut SceneDesc,
        resolution_scale: &mut f32,
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
            self.selected = self.selected.min(desc.objects.len().saturating_sub(1));
            changed = true;
        }
        if let Some(obj) = desc.objects.get_mut(self.selected) {
            ui.separator();
            changed |= self.object_ui(ui, obj, preset);
        }
        ui.separator();
        changed |= render::render_ui(ui, desc, resolution_scale);
        ui.separator();
        changed |= camera::camera_ui(ui, desc);
        ui.separator();
        changed |= lights::lights_ui(ui, desc);
        changed
    }
}

/// A labelled path field applied with Enter or "Load"; `text` holds the typing (keyed by
/// nothing more than being present: cleared when the path is applied).
fn path_field(
    ui: &mut egui::Ui,
    label: &str,
    path: &mut String,
    text: &mut Option<(usize, String)>,
) -> bool {
    let buf = &mut text.get_or_insert_with(|| (0, path.clone())).1;
    let mut changed = false;
    ui.horizontal(|ui| {
        let l = ui.label(label);
        let r = ui
            .add(egui::TextEdit::singleline(buf).desired_width(150.0))
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
    });
    if changed {
        *text = None;
    }
    changed
}
