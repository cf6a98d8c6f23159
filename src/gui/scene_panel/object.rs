//! The object editor: the shape (with a cylinder's caps or a mesh's file and shading), the
//! transform, and the material, texture, map (clip, bump, normal) and displacement editors
//! below them.

use super::{ImagePicker, ScenePanel, browse_button, material::material_ui, path_field};
use crate::geometry::Shading;
use crate::gui::files::{BrowseFor, Browser};
use crate::gui::widgets::{enum_combo, vec3};
use crate::names::Named;
use crate::scene::{ObjectDesc, RenderDesc, ShapeDesc, ShapeKind};
use std::path::Path;

impl ScenePanel {
    pub(super) fn object_ui(
        &mut self,
        ui: &mut egui::Ui,
        obj: &mut ObjectDesc,
        render: &mut RenderDesc,
        preset: &Path,
    ) -> bool {
        let mut changed = false;
        egui::CollapsingHeader::new("Shape and transform")
            .default_open(true)
            .show(ui, |ui| {
                changed |= self.shape_ui(ui, &mut obj.shape, preset);
                if !matches!(obj.shape, ShapeDesc::Mesh { .. }) {
                    // A generic shape cannot be displaced: the map waits for a mesh again.
                    self.maps.keep_displacement(self.key, obj, preset);
                }
                let t = &mut obj.transform;
                changed |= vec3(ui, "translate", &mut t.translate, 0.02);
                changed |= vec3(ui, "rotate", &mut t.rotate, 0.5);
                let mut scale = t.scale;
                if vec3(ui, "scale", &mut scale, 0.01) {
                    // Zero scale is refused by the builder; keep it invertible while dragging.
                    t.scale = scale.map(|s| {
                        if s.abs() < 1e-3 {
                            1e-3_f32.copysign(s)
                        } else {
                            s
                        }
                    });
                    changed = true;
                }
            });
        let browser = self.browser.clone();
        let picker = ImagePicker {
            browser: &browser,
            preset,
            object: self.key.number(),
        };
        egui::CollapsingHeader::new("Material")
            .default_open(true)
            .show(ui, |ui| {
                changed |= material_ui(ui, &mut obj.material, &picker);
            });
        egui::CollapsingHeader::new("Texture")
            .default_open(true)
            .show(ui, |ui| {
                changed |= self.texture_ui(ui, obj.material.texture_mut(), render, preset);
            });
        egui::CollapsingHeader::new("Clip, bump and normal maps")
            .default_open(true)
            .show(ui, |ui| changed |= self.maps_ui(ui, obj, &picker));
        // Only a mesh can be displaced (a generic shape is an exact surface, with no vertices
        // to move; its bump map's tooltip says so).
        if matches!(obj.shape, ShapeDesc::Mesh { .. }) {
            egui::CollapsingHeader::new("Displacement")
                .default_open(true)
                .show(ui, |ui| changed |= self.displacement_ui(ui, obj, &picker));
        }
        changed
    }

    /// The shape menu and the chosen shape's own settings. Choosing Mesh asks for the file
    /// first: the shape stays as it is until a mesh path is loaded (a path that fails to load
    /// is rolled back by the app, so the prompt stays with the error shown).
    fn shape_ui(&mut self, ui: &mut egui::Ui, shape: &mut ShapeDesc, preset: &Path) -> bool {
        let mut changed = false;
        let key = self.key;
        if matches!(shape, ShapeDesc::Mesh { .. }) {
            // A mesh loaded (typed here or dropped on the window): the question is answered.
            self.mesh_prompt = None;
        }
        let mut kind = shape.kind();
        if enum_combo(ui, "Shape", &mut kind) {
            if kind == ShapeKind::Mesh {
                self.mesh_prompt = Some((key, String::new()));
            } else {
                *shape = kind.default_desc();
                self.mesh_prompt = None;
                changed = true;
            }
        }
        if let Some((k, mut text)) = self.mesh_prompt.take() {
            if k == key {
                let (loaded, keep) = mesh_prompt_ui(ui, shape, &mut text, &self.browser, preset);
                if keep {
                    self.mesh_prompt = Some((k, text));
                }
                return changed | loaded;
            }
            self.mesh_prompt = Some((k, text));
        }
        match shape {
            ShapeDesc::Cylinder { capped } => {
                changed |= ui
                    .checkbox(capped, "capped")
                    .on_hover_text("Close the cylinder's ends with disks")
                    .changed();
            }
            ShapeDesc::Mesh { path, shading } => {
                changed |= path_field(
                    ui,
                    "mesh file",
                    path,
                    &mut self.mesh_text,
                    key,
                    preset,
                    &self.browser,
                    BrowseFor::Mesh,
                );
                changed |= enum_combo(ui, "Shading", shading);
            }
            ShapeDesc::Sphere | ShapeDesc::Plane | ShapeDesc::Rectangle | ShapeDesc::Disk => {}
        }
        changed
    }
}

/// The question Shape -> Mesh asks: which file. "Load" (or Enter) makes the shape that mesh;
/// "Cancel" keeps the shape it was. Returns whether the shape changed and whether to keep
/// asking.
fn mesh_prompt_ui(
    ui: &mut egui::Ui,
    shape: &mut ShapeDesc,
    text: &mut String,
    browser: &Browser,
    preset: &Path,
) -> (bool, bool) {
    let mut changed = false;
    let mut cancel = false;
    ui.label(format!(
        "Which mesh? Type the path of a PLY or OBJ file (relative to the preset's folder) \
         and Load, or drop one on the window. The {} stays until it loads.",
        shape.kind().name().to_lowercase()
    ));
    ui.horizontal(|ui| {
        let l = ui.label("mesh file");
        let r = ui
            .add(
                egui::TextEdit::singleline(text)
                    .desired_width((ui.available_width() - 50.0).max(80.0)),
            )
            .labelled_by(l.id)
            .on_hover_text("Path relative to the preset's folder; Enter loads it");
        let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        let ready = !text.trim().is_empty();
        let load = ui
            .add_enabled(ready, egui::Button::new("Load"))
            .on_hover_text("Load the mesh at this path")
            .clicked();
        if (load || enter) && ready {
            *shape = ShapeDesc::Mesh {
                path: text.trim().to_owned(),
                shading: Shading::default(),
            };
            changed = true;
        }
    });
    // A second row, so that every button stays inside the panel's width.
    ui.horizontal(|ui| {
        if let Some(p) = browse_button(ui, browser, BrowseFor::Mesh, preset) {
            text.clone_from(&p);
            *shape = ShapeDesc::Mesh {
                path: p,
                shading: Shading::default(),
            };
            changed = true;
        }
        cancel = ui
            .button("Cancel")
            .on_hover_text("Keep the current shape")
            .clicked();
    });
    (changed, !cancel)
}
