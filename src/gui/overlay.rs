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
    /// The seam's pixels (film pixels), drawn thick.
    pub seam: Vec<egui::Pos2>,
    /// The poles (film pixels), each drawn as a large ring.
    pub poles: Vec<egui::Pos2>,
    /// The pixels that read the chosen texels, as an image of the film's size.
    pub highlight: Option<egui::TextureHandle>,
    /// When few pixels read them, their centres (film pixels): each gets a ring, since one
    /// pixel of a film shown smaller than its size would not be seen.
    pub markers: Vec<egui::Pos2>,
}

/// The ring drawn around a pole, in points.
const POLE_RADIUS: f32 = 12.0;
/// The dark margin around a label's text, in points.
const LABEL_PAD: f32 = 1.5;

/// Where each label goes: beside its anchor point (above right, below right, above left or
/// below left, the first that fits), inside `bounds` and overlapping no label placed before it;
/// `None` for a label that fits nowhere (it is left out rather than drawn over another).
/// `labels` are the anchors and the text sizes; the boxes returned include the margin.
#[must_use]
pub fn place_labels(
    labels: &[(egui::Pos2, egui::Vec2)],
    bounds: egui::Rect,
) -> Vec<Option<egui::Rect>> {
    let mut placed: Vec<egui::Rect> = Vec::new();
    labels
        .iter()
        .map(|&(p, size)| {
            let size = size + egui::vec2(2.0 * LABEL_PAD, 2.0 * LABEL_PAD);
            let candidates = [
                (egui::Align2::LEFT_BOTTOM, egui::vec2(3.0, -2.0)),
                (egui::Align2::LEFT_TOP, egui::vec2(3.0, 2.0)),
                (egui::Align2::RIGHT_BOTTOM, egui::vec2(-3.0, -2.0)),
                (egui::Align2::RIGHT_TOP, egui::vec2(-3.0, 2.0)),
            ];
            let r = candidates
                .iter()
                .map(|(align, off)| align.anchor_size(p + *off, size))
                .find(|r| bounds.contains_rect(*r) && !placed.iter().any(|q| q.intersects(*r)))?;
            placed.push(r);
            Some(r)
        })
        .collect()
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
            let to_screen = |at: egui::Pos2| rect.min + at.to_vec2() / o.film * rect.size();
            // The seam and the poles, drawn large enough to be seen from the back of a room: a
            // line 4 points wide with a dark edge, and a ring around each pole.
            let dark = egui::Color32::from_black_alpha(200);
            for s in &o.seam {
                painter.circle_filled(to_screen(*s), 3.0, dark);
            }
            for s in &o.seam {
                painter.circle_filled(to_screen(*s), 2.0, SEAM_COLOUR);
            }
            for pole in &o.poles {
                let c = to_screen(*pole);
                painter.circle_stroke(c, POLE_RADIUS, egui::Stroke::new(6.0, dark));
                painter.circle_stroke(c, POLE_RADIUS, egui::Stroke::new(3.5, POLE_COLOUR));
                painter.circle_filled(c, 4.0, POLE_COLOUR);
            }
            let font = egui::FontId::proportional(12.0);
            let galleys: Vec<_> = o
                .labels
                .iter()
                .map(|(at, text, colour)| {
                    let g = painter.layout_no_wrap(text.clone(), font.clone(), *colour);
                    (to_screen(*at), g, *colour)
                })
                .collect();
            let boxes = place_labels(
                &galleys
                    .iter()
                    .map(|(p, g, _)| (*p, g.size()))
                    .collect::<Vec<_>>(),
                rect,
            );
            for ((_, g, colour), r) in galleys.into_iter().zip(boxes) {
                if let Some(r) = r {
                    painter.rect_filled(r, 2.0, egui::Color32::from_black_alpha(170));
                    painter.galley(r.min + egui::vec2(LABEL_PAD, LABEL_PAD), g, colour);
                }
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

#[cfg(test)]
mod tests {
    use super::place_labels;

    #[test]
    fn labels_never_overlap_and_stay_inside() {
        let bounds = egui::Rect::from_min_size(egui::pos2(0.0, 0.0), egui::vec2(200.0, 100.0));
        // Eight labels at nearly the same point (the lines meeting at a pole), and a row of
        // labels along a line, each as wide as three of its spacings.
        let mut labels: Vec<(egui::Pos2, egui::Vec2)> = (0..8)
            .map(|i| {
                (
                    egui::pos2(100.0 + i as f32 * 0.5, 50.0),
                    egui::vec2(50.0, 12.0),
                )
            })
            .collect();
        labels.extend((0..12).map(|i| (egui::pos2(i as f32 * 16.0, 90.0), egui::vec2(48.0, 12.0))));
        labels.push((egui::pos2(199.0, 1.0), egui::vec2(40.0, 12.0)));
        let boxes = place_labels(&labels, bounds);
        let placed: Vec<egui::Rect> = boxes.iter().flatten().copied().collect();
        for (i, a) in placed.iter().enumerate() {
            assert!(bounds.contains_rect(*a), "{a:?}");
            for b in &placed[i + 1..] {
                assert!(!a.intersects(*b), "{a:?} overlaps {b:?}");
            }
        }
        // Four fit around the crowded point (one per side), and the corner label moved inside.
        assert_eq!(boxes[..8].iter().flatten().count(), 4);
        assert!(boxes[20].is_some());
    }
}
