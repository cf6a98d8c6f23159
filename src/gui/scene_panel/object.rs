//! The object editor: the shape (with a cylinder's caps or a mesh's file and shading), the
//! transform, and the material and texture editors below them.

use super::{ScenePanel, material::material_ui, path_field};
use crate::gui::widgets::{enum_combo, vec3};
use crate::scene::{ObjectDesc, ShapeDesc};
use std::path::Path;

impl ScenePanel {
    pub(super) fn object_ui(
        &mut self,
        ui: &mut egui::Ui,
        obj: &mut ObjectDesc,
        preset: &Path,
    ) -> bool {
        let mut changed = false;
        egui::CollapsingHeader::new("Shape and transform")
            .default_open(true)
            .show(ui, |ui| {
                changed |= self.shape_ui(ui, &mut obj.shape);
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
        egui::CollapsingHeader::new("Material")
            .default_open(true)
            .show(ui, |ui| changed |= material_ui(ui, &mut obj.material));
        egui::CollapsingHeader::new("Texture")
            .default_open(true)
            .show(ui, |ui| {
                changed |= self.texture_ui(ui, obj.material.texture_mut(), preset);
            });
        changed
    }

    /// The shape menu and the chosen shape's own settings.
    fn shape_ui(&mut self, ui: &mut egui::Ui, shape: &mut ShapeDesc) -> bool {
        let mut changed = false;
        let mut kind = shape.kind();
        if enum_combo(ui, "Shape", &mut kind) {
            *shape = kind.default_desc();
            // An empty mesh path builds nothing: wait for a path before re-rendering.
            changed = !matches!(shape, ShapeDesc::Mesh { path, .. } if path.is_empty());
        }
        match shape {
            ShapeDesc::Cylinder { capped } => {
                changed |= ui
                    .checkbox(capped, "capped")
                    .on_hover_text("Close the cylinder's ends with disks")
                    .changed();
            }
            ShapeDesc::Mesh { path, shading } => {
                changed |= path_field(ui, "mesh file", path, &mut self.mesh_text);
                changed |= enum_combo(ui, "Shading", shading);
            }
            ShapeDesc::Sphere | ShapeDesc::Plane | ShapeDesc::Rectangle | ShapeDesc::Disk => {}
        }
        changed
    }
}
