//! The lights editor: the ambient light, each light's placement, strength, colour and shadows,
//! and a button to add a light of each kind.

use crate::gui::widgets::{colour, number, vec3};
use crate::math::Vec3;
use crate::names::Named;
use crate::scene::{LightDesc, LightKind, SceneDesc};
use strum::VariantArray;

/// The lights. Returns whether any changed.
pub(super) fn lights_ui(ui: &mut egui::Ui, desc: &mut SceneDesc) -> bool {
    let mut changed = false;
    ui.heading("Lights");
    changed |= number(ui, "ambient ls", &mut desc.ambient.ls, 0.0..=100.0, 0.01);
    changed |= colour(ui, "ambient colour", &mut desc.ambient.color);
    let mut remove = None;
    for (i, l) in desc.lights.iter_mut().enumerate() {
        ui.push_id(i, |ui| {
            ui.horizontal(|ui| {
                ui.strong(format!("light {i}: {}", l.kind().name()));
                if ui
                    .button("Remove")
                    .on_hover_text("Removes this light")
                    .clicked()
                {
                    remove = Some(i);
                }
            });
            changed |= light_ui(ui, l);
        });
    }
    if let Some(i) = remove {
        desc.lights.remove(i);
        changed = true;
    }
    ui.horizontal(|ui| {
        for &kind in LightKind::VARIANTS {
            if ui
                .button(format!("Add {}", kind.name()))
                .on_hover_text(kind.description())
                .clicked()
            {
                desc.lights.push(kind.default_desc());
                changed = true;
            }
        }
    });
    changed
}

/// One light's settings. Returns whether any changed.
fn light_ui(ui: &mut egui::Ui, l: &mut LightDesc) -> bool {
    let mut changed = false;
    // A direction must not be zero; a position may be anywhere.
    let (label, may_be_zero, at, ls, color, shadows) = match l {
        LightDesc::Directional {
            direction,
            ls,
            color,
            shadows,
        } => ("direction", false, direction, ls, color, shadows),
        LightDesc::Point {
            position,
            ls,
            color,
            shadows,
        } => ("position", true, position, ls, color, shadows),
    };
    let mut v = *at;
    if vec3(ui, label, &mut v, 0.02) && (may_be_zero || v != Vec3::ZERO) {
        *at = v;
        changed = true;
    }
    changed |= number(ui, "ls", ls, 0.0..=1e4, 0.01);
    changed |= colour(ui, "colour", color);
    changed |= ui
        .checkbox(shadows, "shadows")
        .on_hover_text("Objects cast shadows from this light")
        .changed();
    changed
}
