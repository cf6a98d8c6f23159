//! The mapping's formula drawn, for the inspector: the generic object in one or two views
//! with the point the mapping reads and its angles (phi, theta, alpha, beta), as the lecture
//! draws them.

use crate::inspect::mapping_angles;
use crate::mapping::Mapping;

/// Colours of the diagram: the generic object, the hit point and its angles.
const OBJECT: egui::Color32 = egui::Color32::from_gray(150);
const POINT: egui::Color32 = egui::Color32::from_rgb(255, 220, 0);
const ANGLE: egui::Color32 = egui::Color32::from_rgb(90, 220, 255);
const SEAM: egui::Color32 = egui::Color32::from_rgb(255, 60, 255);

/// The mapping's formula drawn: the generic object in two views with the hit point `p` (the
/// point the mapping reads) and its angles (phi, theta, alpha, beta), as the lecture draws them.
pub(super) fn mapping_diagram(ui: &mut egui::Ui, mapping: Mapping, p: crate::math::Vec3A) {
    let a = mapping_angles(mapping, p);
    let side = ((ui.available_width() - 12.0) * 0.5).clamp(100.0, 170.0);
    ui.add_space(4.0);
    ui.horizontal(|ui| {
        let view = |ui: &mut egui::Ui, caption: &str, draw: &dyn Fn(&egui::Painter, egui::Rect)| {
            ui.vertical(|ui| {
                let (rect, _) =
                    ui.allocate_exact_size(egui::vec2(side, side), egui::Sense::hover());
                let painter = ui.painter_at(rect);
                painter.rect_filled(rect, 4.0, egui::Color32::from_gray(24));
                draw(&painter, rect.shrink(side * 0.14));
                ui.label(egui::RichText::new(caption).small());
            });
        };
        let deg = |x: f64| format!("{:.1} deg", x.to_degrees());
        match mapping {
            Mapping::Rectangular => {
                view(
                    ui,
                    "the rectangle, seen along -y: u from z, v from x",
                    &|pa, r| {
                        rectangular(pa, r, p);
                    },
                );
            }
            Mapping::Uv => {}
            Mapping::Cylindrical | Mapping::Spherical => {
                let phi = a.phi.unwrap_or(0.0);
                view(ui, &format!("from above: phi = {}", deg(phi)), &|pa, r| {
                    from_above(pa, r, p, phi);
                });
                if let Some(theta) = a.theta {
                    view(
                        ui,
                        &format!("meridian: theta = {}", deg(theta)),
                        &|pa, r| {
                            meridian(pa, r, theta);
                        },
                    );
                } else {
                    view(ui, &format!("from the side: y = {:.3}", p.y), &|pa, r| {
                        cylinder_side(pa, r, p.y);
                    });
                }
            }
            Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall => {
                let (alpha, beta, rr) = (
                    a.alpha.unwrap_or(0.0),
                    a.beta.unwrap_or(0.0),
                    a.r.unwrap_or(0.0),
                );
                let axis = if mapping == Mapping::Panoramic {
                    "-z"
                } else {
                    "+z"
                };
                view(
                    ui,
                    &format!("alpha = {} from {axis}", deg(alpha)),
                    &|pa, r| {
                        probe_side(pa, r, alpha, axis);
                    },
                );
                view(
                    ui,
                    &format!("image disc: beta = {}, r = {rr:.3}", deg(beta)),
                    &|pa, r| probe_disc(pa, r, beta, rr),
                );
            }
        }
    });
}

pub(super) fn text(
    pa: &egui::Painter,
    at: egui::Pos2,
    align: egui::Align2,
    s: &str,
    c: egui::Color32,
) {
    pa.text(at, align, s, egui::FontId::proportional(11.0), c);
}

/// An arc about `c` of radius `r` from screen angle `a0` sweeping `sweep` radians (y down).
pub(super) fn arc(
    pa: &egui::Painter,
    c: egui::Pos2,
    r: f32,
    a0: f32,
    sweep: f32,
    colour: egui::Color32,
) {
    let n = ((sweep.abs() * 16.0).ceil() as usize).max(2);
    let pts = (0..=n)
        .map(|k| {
            let t = a0 + sweep * k as f32 / n as f32;
            c + egui::vec2(t.cos(), t.sin()) * r
        })
        .collect();
    pa.add(egui::Shape::line(pts, egui::Stroke::new(1.5, colour)));
}

fn axis(pa: &egui::Painter, from: egui::Pos2, to: egui::Pos2, name: &str) {
    pa.arrow(
        from,
        to - from,
        egui::Stroke::new(1.0, egui::Color32::from_gray(110)),
    );
    text(
        pa,
        to,
        egui::Align2::CENTER_CENTER,
        name,
        egui::Color32::from_gray(170),
    );
}

/// The square [-1, 1]^2 with z right and x up: u = (z + 1) / 2, v = (x + 1) / 2.
fn rectangular(pa: &egui::Painter, r: egui::Rect, p: crate::math::Vec3A) {
    pa.rect_stroke(
        r,
        0.0,
        egui::Stroke::new(1.5, OBJECT),
        egui::StrokeKind::Middle,
    );
    let at = egui::pos2(
        r.center().x + p.z.clamp(-1.0, 1.0) * r.width() * 0.5,
        r.center().y - p.x.clamp(-1.0, 1.0) * r.height() * 0.5,
    );
    let dash = egui::Stroke::new(1.0, ANGLE);
    pa.line_segment([at, egui::pos2(at.x, r.bottom())], dash);
    pa.line_segment([at, egui::pos2(r.left(), at.y)], dash);
    text(
        pa,
        egui::pos2(at.x, r.bottom() + 8.0),
        egui::Align2::CENTER_CENTER,
        &format!("u {:.2}", (p.z + 1.0) * 0.5),
        ANGLE,
    );
    text(
        pa,
        egui::pos2(r.left() - 2.0, at.y),
        egui::Align2::RIGHT_CENTER,
        &format!("v {:.2}", (p.x + 1.0) * 0.5),
        ANGLE,
    );
    text(
        pa,
        egui::pos2(r.right(), r.bottom() + 8.0),
        egui::Align2::RIGHT_CENTER,
        "z",
        OBJECT,
    );
    text(
        pa,
        egui::pos2(r.left() - 2.0, r.top()),
        egui::Align2::RIGHT_CENTER,
        "x",
        OBJECT,
    );
    pa.circle_filled(at, 4.0, POINT);
}

/// Looking down y: x right, z down the screen; phi from +z toward +x, the seam at +z.
fn from_above(pa: &egui::Painter, r: egui::Rect, p: crate::math::Vec3A, phi: f64) {
    let c = r.center();
    let rad = r.width() * 0.5;
    pa.circle_stroke(c, rad, egui::Stroke::new(1.5, OBJECT));
    axis(pa, c, c + egui::vec2(rad + 10.0, 0.0), "x");
    axis(pa, c, c + egui::vec2(0.0, rad + 10.0), "z");
    // The seam: x = 0, z > 0 (u = 0 and u = 1).
    pa.line_segment(
        [
            c + egui::vec2(0.0, rad - 6.0),
            c + egui::vec2(0.0, rad + 4.0),
        ],
        egui::Stroke::new(3.0, SEAM),
    );
    let phi = phi as f32;
    let start = std::f32::consts::FRAC_PI_2;
    arc(pa, c, rad * 0.35, start, -phi, ANGLE);
    let dir = egui::vec2((start - phi).cos(), (start - phi).sin());
    pa.line_segment([c, c + dir * rad], egui::Stroke::new(1.0, POINT));
    let h = p.x.hypot(p.z);
    if h > 0.0 {
        pa.circle_filled(c + dir * rad * (h / h.max(1.0)), 4.0, POINT);
    }
    let mid = start - phi * 0.5;
    text(
        pa,
        c + egui::vec2(mid.cos(), mid.sin()) * rad * 0.5,
        egui::Align2::CENTER_CENTER,
        "phi",
        ANGLE,
    );
}

/// The meridian plane: y up, the distance from the axis right; theta from +y; the poles.
fn meridian(pa: &egui::Painter, r: egui::Rect, theta: f64) {
    let c = r.center();
    let rad = r.width() * 0.5;
    pa.circle_stroke(c, rad, egui::Stroke::new(1.5, OBJECT));
    axis(pa, c, c + egui::vec2(0.0, -rad - 10.0), "y");
    for y in [-rad, rad] {
        pa.circle_filled(c + egui::vec2(0.0, y), 3.5, egui::Color32::YELLOW);
    }
    let theta = theta as f32;
    let start = -std::f32::consts::FRAC_PI_2;
    arc(pa, c, rad * 0.35, start, theta, ANGLE);
    let dir = egui::vec2((start + theta).cos(), (start + theta).sin());
    pa.line_segment([c, c + dir * rad], egui::Stroke::new(1.0, POINT));
    pa.circle_filled(c + dir * rad, 4.0, POINT);
    let mid = start + theta * 0.5;
    text(
        pa,
        c + egui::vec2(mid.cos(), mid.sin()) * rad * 0.52,
        egui::Align2::CENTER_CENTER,
        "theta",
        ANGLE,
    );
    text(
        pa,
        egui::pos2(r.right(), r.bottom() + 6.0),
        egui::Align2::RIGHT_CENTER,
        &format!(
            "v = 1 - theta/pi = {:.3}",
            1.0 - theta / std::f32::consts::PI
        ),
        ANGLE,
    );
}

/// The cylinder from the side: height -1 to 1, v = (y + 1) / 2.
fn cylinder_side(pa: &egui::Painter, r: egui::Rect, y: f32) {
    let body = egui::Rect::from_center_size(r.center(), egui::vec2(r.width() * 0.6, r.height()));
    pa.rect_stroke(
        body,
        0.0,
        egui::Stroke::new(1.5, OBJECT),
        egui::StrokeKind::Middle,
    );
    let at = egui::pos2(
        body.center().x,
        body.center().y - y.clamp(-1.0, 1.0) * body.height() * 0.5,
    );
    pa.line_segment(
        [
            egui::pos2(body.left(), at.y),
            egui::pos2(body.right(), at.y),
        ],
        egui::Stroke::new(1.0, ANGLE),
    );
    pa.circle_filled(at, 4.0, POINT);
    text(
        pa,
        egui::pos2(body.right() + 3.0, at.y),
        egui::Align2::LEFT_CENTER,
        &format!("v {:.2}", (y + 1.0) * 0.5),
        ANGLE,
    );
}

/// The probe's directions: the axis (+z, or -z for the panoramic variant) right, alpha from it.
fn probe_side(pa: &egui::Painter, r: egui::Rect, alpha: f64, axis_name: &str) {
    let c = r.center();
    let rad = r.width() * 0.5;
    pa.circle_stroke(c, rad, egui::Stroke::new(1.5, OBJECT));
    axis(pa, c, c + egui::vec2(rad + 10.0, 0.0), axis_name);
    let alpha = alpha as f32;
    arc(pa, c, rad * 0.35, 0.0, -alpha, ANGLE);
    let dir = egui::vec2((-alpha).cos(), (-alpha).sin());
    pa.line_segment([c, c + dir * rad], egui::Stroke::new(1.0, POINT));
    pa.circle_filled(c + dir * rad, 4.0, POINT);
    let mid = -alpha * 0.5;
    text(
        pa,
        c + egui::vec2(mid.cos(), mid.sin()) * rad * 0.52,
        egui::Align2::CENTER_CENTER,
        "alpha",
        ANGLE,
    );
}

/// The image disc: u right, v up; the point at radius r in direction beta.
fn probe_disc(pa: &egui::Painter, r: egui::Rect, beta: f64, rr: f64) {
    let c = r.center();
    let rad = r.width() * 0.5;
    pa.rect_stroke(
        r,
        0.0,
        egui::Stroke::new(1.0, egui::Color32::from_gray(80)),
        egui::StrokeKind::Middle,
    );
    pa.circle_stroke(c, rad, egui::Stroke::new(1.5, OBJECT));
    axis(pa, c, c + egui::vec2(rad + 10.0, 0.0), "u");
    axis(pa, c, c + egui::vec2(0.0, -rad - 10.0), "v");
    let beta = beta as f32;
    arc(pa, c, rad * 0.25, 0.0, -beta, ANGLE);
    let at = c + egui::vec2(beta.cos(), -beta.sin()) * rad * rr as f32;
    pa.line_segment([c, at], egui::Stroke::new(1.0, POINT));
    pa.circle_filled(at, 4.0, POINT);
    let mid = -beta * 0.5;
    text(
        pa,
        c + egui::vec2(mid.cos(), mid.sin()) * rad * 0.4,
        egui::Align2::CENTER_CENTER,
        "beta",
        ANGLE,
    );
}
