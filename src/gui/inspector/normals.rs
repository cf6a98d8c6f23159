//! Vectors at a surface point drawn in one plane, for the inspector: the geometric normal
//! against the shading normal a bump or normal map gives, and a mirror's view and reflected
//! directions about its normal.

use super::diagram::arc;
use crate::math::Vec3A;

/// The surface and its normal.
const SURFACE: egui::Color32 = egui::Color32::from_gray(150);

/// One vector of a [`surface_vectors`] drawing: its direction (world space), name, colour, and
/// whether the angle from the normal is marked.
pub(super) struct Arrow<'a> {
    pub dir: Vec3A,
    pub name: &'a str,
    pub colour: egui::Color32,
    pub marked: bool,
}

/// The surface at a point seen edge-on: its tangent line, `normal` straight up (named
/// `normal_name`), and `arrows` projected onto the plane through the normal that holds the
/// first arrow leaning away from it (the plane of the tilt, or of incidence). Angles from the
/// normal are true; a marked arrow gets an arc from the normal.
pub(super) fn surface_vectors(
    ui: &mut egui::Ui,
    caption: &str,
    normal: Vec3A,
    normal_name: &str,
    arrows: &[Arrow<'_>],
) {
    let up = normal.normalize_or(Vec3A::Y);
    // The drawing's horizontal: the first arrow's lean away from the normal, else any
    // direction across it.
    let side = arrows
        .iter()
        .map(|a| a.dir - a.dir.dot(up) * up)
        .find(|s| s.length() > 1e-6)
        .map_or_else(|| up.any_orthonormal_vector(), Vec3A::normalize);
    let size = (ui.available_width() - 8.0).clamp(140.0, 280.0);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(size, size * 0.62), egui::Sense::hover());
    let pa = ui.painter_at(rect);
    pa.rect_filled(rect, 4.0, egui::Color32::from_gray(24));
    let origin = egui::pos2(rect.center().x, rect.bottom() - size * 0.1);
    let len = size * 0.42;
    let to_screen = |v: Vec3A| {
        let v = v.normalize_or(up);
        origin + egui::vec2(v.dot(side), -v.dot(up)) * len
    };
    pa.line_segment(
        [
            egui::pos2(rect.left() + 8.0, origin.y),
            egui::pos2(rect.right() - 8.0, origin.y),
        ],
        egui::Stroke::new(2.0, SURFACE),
    );
    let tip = to_screen(up);
    pa.arrow(origin, tip - origin, egui::Stroke::new(1.5, SURFACE));
    // The normal's name above its tip, the arrows' names beside and below theirs: apart even
    // when an arrow lies close to the normal.
    label(
        &pa,
        tip + egui::vec2(0.0, -4.0),
        egui::Align2::CENTER_BOTTOM,
        normal_name,
        SURFACE,
    );
    for (k, a) in arrows.iter().enumerate() {
        let tip = to_screen(a.dir);
        pa.arrow(origin, tip - origin, egui::Stroke::new(2.0, a.colour));
        let (align, nudge) = if tip.x < origin.x - 1.0 {
            (egui::Align2::RIGHT_TOP, -6.0)
        } else {
            (egui::Align2::LEFT_TOP, 6.0)
        };
        label(&pa, tip + egui::vec2(nudge, 2.0), align, a.name, a.colour);
        if a.marked {
            let d = tip - origin;
            let to = d.y.atan2(d.x);
            let from = -std::f32::consts::FRAC_PI_2;
            arc(
                &pa,
                origin,
                len * (0.3 + 0.08 * k as f32),
                from,
                to - from,
                a.colour,
            );
        }
    }
    ui.label(caption);
}

/// A vector's name, in type large enough to read from the back of a room.
fn label(pa: &egui::Painter, at: egui::Pos2, align: egui::Align2, s: &str, c: egui::Color32) {
    pa.text(at, align, s, egui::FontId::proportional(15.0), c);
}
