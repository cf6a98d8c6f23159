//! What is drawn over the viewport's shaded image (not instead of it, as the `uv` debug view
//! does): the iso-lines of u and v with their labels, the seam and the poles, and the pixels
//! that read the texels chosen in the texture panel. The texture panel publishes an [`Overlay`]
//! each frame; the viewport calls [`paint`] once after drawing its image.

use std::sync::Arc;

/// The accessible name of the iso-lines checkbox drawn over the image.
pub const ISO_CHECKBOX: &str = "Iso-lines";

/// Colour of the lines of constant u.
pub const U_COLOUR: egui::Color32 = egui::Color32::from_rgb(255, 150, 40);
/// Colour of the lines of constant v.
pub const V_COLOUR: egui::Color32 = egui::Color32::from_rgb(60, 220, 255);
/// Colour of the seam (u wraps from 1 to 0).
pub const SEAM_COLOUR: egui::Color32 = egui::Color32::from_rgb(255, 60, 255);
/// Colour of the poles.
pub const POLE_COLOUR: egui::Color32 = egui::Color32::from_rgb(255, 255, 0);
/// Colour of the pixels that read the chosen texels.
pub const HIGHLIGHT_COLOUR: egui::Color32 = egui::Color32::from_rgb(255, 240, 0);

/// What to draw over the image, in film pixels.
#[derive(Clone, Default)]
pub struct Overlay {
    /// Film size in pixels (the image the viewport fits into its rectangle).
    pub film: egui::Vec2,
    /// The iso-lines as an image of the film's size (transparent elsewhere).
    pub iso: Option<egui::TextureHandle>,
    /// Labels: film position, text, colour.
    pub labels: Vec<(egui::Pos2, String, egui::Color32)>,
    /// The pixels that read the chosen texels, as an image of the film's size.
    pub highlight: Option<egui::TextureHandle>,
    /// When few pixels read them, their centres (film pixels): each gets a ring, since one
    /// pixel of a film shown smaller than its size would not be seen.
    pub markers: Vec<egui::Pos2>,
}

fn overlay_id() -> egui::Id {
    egui::Id::unique("texplore-overlay")
}

fn iso_id() -> egui::Id {
    egui::Id::unique("texplore-iso-lines-on")
}

/// Hands this frame's overlay to the viewport.
pub fn publish(ctx: &egui::Context, overlay: Overlay) {
    ctx.data_mut(|d| d.insert_temp(overlay_id(), Arc::new(overlay)));
}

/// Whether the iso-lines checkbox is ticked.
#[must_use]
pub fn iso_on(ctx: &egui::Context) -> bool {
    ctx.data(|d| d.get_temp(iso_id()).unwrap_or(false))
}

/// Ticks or clears the iso-lines checkbox.
pub fn set_iso(ctx: &egui::Context, on: bool) {
    ctx.data_mut(|d| d.insert_temp(iso_id(), on));
}

/// Draws the iso-lines checkbox in the image's top-left corner and the published overlay over
/// the image shown in `rect`.
pub fn paint(ui: &mut egui::Ui, rect: egui::Rect) {
    let ctx = ui.ctx().clone();
    let mut on = iso_on(&ctx);
    let overlay: Option<Arc<Overlay>> = ctx.data(|d| d.get_temp(overlay_id()));
    let painter = ui.painter_at(rect);
    if let Some(o) = overlay.filter(|o| o.film.x > 0.0 && o.film.y > 0.0) {
        let unit = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        if let Some(h) = &o.highlight {
            painter.image(h.id(), rect, unit, egui::Color32::WHITE);
        }
        for m in &o.markers {
            let p = rect.min + m.to_vec2() / o.film * rect.size();
            painter.circle_stroke(p, 7.0, egui::Stroke::new(2.0, HIGHLIGHT_COLOUR));
        }
        if on && let Some(iso) = &o.iso {
            painter.image(iso.id(), rect, unit, egui::Color32::WHITE);
            let font = egui::FontId::proportional(12.0);
            for (at, text, colour) in &o.labels {
                let p = rect.min + at.to_vec2() / o.film * rect.size();
                let g = painter.layout_no_wrap(text.clone(), font.clone(), *colour);
                let r = egui::Align2::LEFT_BOTTOM.anchor_size(p + egui::vec2(3.0, -2.0), g.size());
                painter.rect_filled(r.expand(1.5), 2.0, egui::Color32::from_black_alpha(170));
                painter.galley(r.min, g, *colour);
            }
        }
    }
    let at = egui::Rect::from_min_size(rect.min + egui::vec2(6.0, 6.0), egui::vec2(84.0, 20.0));
    painter.rect_filled(at.expand(2.0), 3.0, egui::Color32::from_black_alpha(170));
    let r = ui
        .put(at, egui::Checkbox::new(&mut on, ISO_CHECKBOX))
        .on_hover_text(
            "Lines of constant u (orange) and v (blue) every 1/8, labelled, over the image; \
             the seam in magenta, the poles in yellow",
        );
    if r.changed() {
        set_iso(&ctx, on);
    }
}
