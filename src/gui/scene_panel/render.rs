//! The render settings: sampler, samples per pixel, exposure, resolution scale, seed and
//! background.

use crate::gui::widgets::{colour, enum_combo};
use crate::scene::SceneDesc;

/// The render settings. Returns whether any changed.
pub(super) fn render_ui(
    ui: &mut egui::Ui,
    desc: &mut SceneDesc,
    resolution_scale: &mut f32,
) -> bool {
    let mut changed = false;
    ui.heading("Render");
    let r = &mut desc.render;
    changed |= enum_combo(ui, "Sampler", &mut r.sampler);
    ui.horizontal(|ui| {
        let l = ui.label("spp");
        changed |= ui
            .add(egui::Slider::new(&mut r.spp, 1..=1024).logarithmic(true))
            .labelled_by(l.id)
            .on_hover_text("Samples per pixel: the render refines pass by pass up to this")
            .changed();
    });
    ui.horizontal(|ui| {
        let l = ui.label("exposure");
        changed |= ui
            .add(egui::Slider::new(&mut r.exposure, -8.0..=8.0).suffix(" stops"))
            .labelled_by(l.id)
            .on_hover_text("Multiplies the radiance by 2^exposure before display")
            .changed();
    });
    ui.horizontal(|ui| {
        let l = ui.label("resolution");
        changed |= ui
            .add(
                egui::Slider::new(resolution_scale, 0.125..=2.0)
                    .logarithmic(true)
                    .suffix(" x"),
            )
            .labelled_by(l.id)
            .on_hover_text(
                "Renders at this fraction of the preset's resolution (a view setting, not saved)",
            )
            .changed();
    });
    ui.horizontal(|ui| {
        let l = ui.label("seed");
        changed |= ui
            .add(egui::DragValue::new(&mut r.seed))
            .labelled_by(l.id)
            .on_hover_text("Seed of every random number: the same seed renders the same image")
            .changed();
    });
    changed |= colour(ui, "background", &mut r.background);
    changed
}
