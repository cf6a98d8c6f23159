//! The render settings: sampler, samples per pixel, exposure, resolution scale, seed and
//! background.

use crate::gui::resolution::ViewResolution;
use crate::gui::widgets::{colour, enum_combo};
use crate::scene::SceneDesc;

/// The render settings. Returns whether any changed.
pub(super) fn render_ui(
    ui: &mut egui::Ui,
    desc: &mut SceneDesc,
    resolution: &mut ViewResolution,
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
        let tip = format!(
            "Renders at this fraction of {} (a view setting, not saved)",
            resolution.of_what()
        );
        changed |= ui
            .add(
                egui::Slider::new(&mut resolution.scale, 0.125..=2.0)
                    .logarithmic(true)
                    .suffix(" x"),
            )
            .labelled_by(l.id)
            .on_hover_text(tip)
            .changed();
    });
    changed |= ui
        .checkbox(&mut resolution.follow_viewport, "follow the image pane")
        .on_hover_text(
            "On: render at the image pane's size in screen pixels, at the preset's aspect \
             ratio, so a larger window or a projector gets a sharper image. Off: render at the \
             preset's resolution (what Save and the CLI use)",
        )
        .changed();
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
