//! The material editor: the kind (matte, Phong, emissive) and its coefficients.

use crate::gui::widgets::{colour, enum_combo, number};
use crate::scene::MaterialDesc;

/// The material menu and the chosen material's coefficients. Returns whether it changed.
pub(super) fn material_ui(ui: &mut egui::Ui, m: &mut MaterialDesc) -> bool {
    let mut changed = false;
    let mut kind = m.kind();
    if enum_combo(ui, "Material", &mut kind) {
        *m = m.converted(kind);
        changed = true;
    }
    match m {
        MaterialDesc::Matte { ka, kd, .. } => {
            changed |= number(ui, "ka (ambient)", ka, 0.0..=10.0, 0.01);
            changed |= number(ui, "kd (diffuse)", kd, 0.0..=10.0, 0.01);
        }
        MaterialDesc::Phong {
            ka,
            kd,
            ks,
            cs,
            exp,
            ..
        } => {
            changed |= number(ui, "ka (ambient)", ka, 0.0..=10.0, 0.01);
            changed |= number(ui, "kd (diffuse)", kd, 0.0..=10.0, 0.01);
            changed |= number(ui, "ks (specular)", ks, 0.0..=10.0, 0.01);
            changed |= number(ui, "exponent", exp, 0.0..=10_000.0, 0.5);
            changed |= colour(ui, "specular colour", cs);
        }
        MaterialDesc::Emissive { ls, .. } => {
            changed |= number(ui, "ls (radiance)", ls, 0.0..=1e4, 0.01);
        }
    }
    changed
}
