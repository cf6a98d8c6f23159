//! The viewport: the progressive image, orbit (drag), pan (right or middle drag, or shift +
//! drag), zoom (wheel), reset view; hovering and clicking report film positions to the
//! inspector. In A/B mode, two images side by side with a draggable divider.

use super::command::Command;
use super::compare::AbSplit;
use super::widgets::enum_combo;
use crate::math::{Quat, Ray, Vec2, Vec3};
use crate::scene::{Scene, SceneDesc, ShapeDesc};
use crate::texture::View;

/// The accessible name of the viewport's image (the A/B pair's too).
pub const IMAGE_LABEL: &str = "Rendered image";
/// The accessible name of the A/B divider (a slider: its value is the fraction left of it).
pub const DIVIDER_LABEL: &str = "A/B divider";

/// What the pointer did in the viewport this frame.
#[derive(Clone, Debug)]
pub struct ViewOutput {
    /// The camera edit a drag or the wheel asked for, if any.
    pub edit: Option<Command>,
    /// Film position under the pointer, in image pixels from the top-left corner (y down).
    pub hover: Option<Vec2>,
    /// Film position clicked, in the same pixels as `hover`.
    pub click: Option<Vec2>,
    /// The debug view was changed.
    pub view_changed: bool,
    /// The image pane's space below the toolbar, in points (`Rect::NOTHING` until drawn).
    pub avail: egui::Rect,
    /// The space the image is fitted into: `avail`, or less where presentation mode's captions
    /// take some of it.
    pub area: egui::Rect,
    /// The image as drawn (`Rect::NOTHING` until there is one).
    pub image: egui::Rect,
}

impl Default for ViewOutput {
    fn default() -> Self {
        Self {
            edit: None,
            hover: None,
            click: None,
            view_changed: false,
            avail: egui::Rect::NOTHING,
            area: egui::Rect::NOTHING,
            image: egui::Rect::NOTHING,
        }
    }
}

/// Wheel points to a zoom factor: one notch (about 50 points) is 10 %.
const ZOOM_PER_POINT: f32 = 0.002;

/// The eye after zooming by `scale` (below 1 comes closer) toward `look_at`.
///
/// One ray from the eye toward the look-at point finds the nearest surface in front of it
/// ([`Scene::intersect`], so any scene works: spheres, planes, meshes), and
/// [`crate::camera::zoom_toward_surface`] scales the gap to that surface instead of the
/// distance to the look-at point, stopping 5 % of that distance short of it. A ray rather than
/// the scene's bounds: a plane's bounds are infinite and a mesh's far too loose, while the
/// surface the eye would run into is exactly the one on that line. Without a scene the zoom
/// goes toward the look-at point as before.
#[must_use]
pub fn zoomed_eye(scene: Option<&Scene>, eye: Vec3, look_at: Vec3, scale: f32) -> Vec3 {
    let dir = (look_at - eye).normalize_or_zero();
    let surface = scene.filter(|_| dir != Vec3::ZERO).and_then(|s| {
        // A unit direction, so the hit's t is the distance.
        let ray = Ray::new(eye.into(), dir.into());
        s.intersect(&ray, f32::INFINITY).map(|(_, hit)| hit.t)
    });
    crate::camera::zoom_toward_surface(eye, look_at, surface, scale)
}

/// The hint under the toolbar.
pub const HINT: &str =
    "drag: orbit · right-drag or shift-drag: pan · wheel: zoom · click: pin the inspector";

fn toolbar(ui: &mut egui::Ui, out: &mut ViewOutput, view: Option<&mut View>) {
    ui.horizontal(|ui| {
        if let Some(view) = view {
            out.view_changed = enum_combo(ui, "View", view);
        }
        if ui
            .button("Reset view")
            .on_hover_text("Back to the camera the scene was opened with")
            .clicked()
        {
            out.edit = Some(Command::ResetView);
        }
    });
    // On its own line and wrapped: never cut off, and never asking the panels around the
    // viewport for width.
    ui.add(egui::Label::new(egui::RichText::new(HINT).weak()).wrap());
}

/// Why nothing of an object shows, when the reason is its orientation: a flat shape (plane,
/// rectangle, disk) whose plane passes through the eye is seen exactly edge-on and covers no
/// pixel.
#[must_use]
pub fn edge_on_hint(desc: &SceneDesc) -> Option<String> {
    let eye = desc.camera.eye;
    desc.objects.iter().enumerate().find_map(|(i, o)| {
        if !matches!(
            o.shape,
            ShapeDesc::Plane | ShapeDesc::Rectangle | ShapeDesc::Disk
        ) {
            return None;
        }
        let r = o.transform.rotate;
        let rotation = Quat::from_rotation_z(r.z.to_radians())
            * Quat::from_rotation_y(r.y.to_radians())
            * Quat::from_rotation_x(r.x.to_radians());
        // The generic flat shapes lie in y = 0; a scale keeps the normal's direction.
        let normal = rotation * Vec3::Y;
        let to_eye = eye - o.transform.translate;
        let distance = to_eye.dot(normal).abs();
        (distance <= 1e-3 * to_eye.length().max(1e-6)).then(|| {
            let name = if o.name.is_empty() {
                format!("object {i}")
            } else {
                o.name.clone()
            };
            format!(
                "{name} is edge-on to the camera: the eye lies in its plane, so it covers no \
                 pixel. Rotate it or move the camera."
            )
        })
    })
}

/// A small key to the colours of debug view `view`, drawn in the image's bottom-left corner.
fn colour_key(ui: &egui::Ui, image: egui::Rect, view: View) {
    let srgb = |c: crate::math::Rgb| {
        let e = |v: f32| crate::math::encode_srgb8(v);
        egui::Color32::from_rgb(e(c.0), e(c.1), e(c.2))
    };
    let levels = || {
        (-1..=5).map(move |l| {
            let name = match l {
                -1 => "magnified".to_owned(),
                5 => "5+".to_owned(),
                l => l.to_string(),
            };
            (srgb(crate::texture::mip_level_color(l as f32)), name)
        })
    };
    let entries: Vec<(egui::Color32, String)> = match view {
        View::Shaded => return,
        View::Uv => vec![
            (egui::Color32::from_rgb(255, 0, 0), "red: u".to_owned()),
            (egui::Color32::from_rgb(0, 255, 0), "green: v".to_owned()),
            (egui::Color32::from_rgb(255, 255, 0), "u = v = 1".to_owned()),
            (egui::Color32::from_gray(40), "no texture".to_owned()),
        ],
        View::MipLevel => levels().map(|(c, n)| (c, format!("level {n}"))).collect(),
        View::TexelGrid => std::iter::once((
            egui::Color32::WHITE,
            "lines: texel edges, in their level's colour".to_owned(),
        ))
        .chain(levels().map(|(c, n)| (c, format!("level {n}"))))
        .collect(),
        View::Difference => {
            let tol = glam::DVec2::splat(1e-3);
            let heat = |du: f64, dv: f64| {
                srgb(crate::texture::difference_color(
                    glam::DVec2::new(du, dv),
                    tol,
                ))
            };
            vec![
                (
                    srgb(crate::texture::AGREE_COLOUR),
                    "agree within the tolerance".to_owned(),
                ),
                (heat(2e-3, 0.0), "|du| just above the tolerance".to_owned()),
                (heat(0.5, 0.0), "|du| half the texture or more".to_owned()),
                (heat(0.0, 2e-3), "|dv| just above the tolerance".to_owned()),
                (heat(0.0, 0.5), "|dv| half the texture or more".to_owned()),
                (heat(0.5, 0.5), "both differ".to_owned()),
                (srgb(crate::texture::mark()), "NaN or infinite".to_owned()),
                (egui::Color32::from_gray(40), "no mapping".to_owned()),
            ]
        }
        View::Seams => vec![
            (
                egui::Color32::from_rgb(255, 0, 255),
                "seam: u wraps".to_owned(),
            ),
            (egui::Color32::from_rgb(255, 255, 0), "pole".to_owned()),
            (egui::Color32::from_rgb(0, 255, 255), "tile edge".to_owned()),
        ],
    };
    let font = egui::FontId::proportional(12.0);
    let painter = ui.painter().with_clip_rect(image);
    let row = 16.0;
    let width = entries
        .iter()
        .map(|(_, t)| {
            painter
                .layout_no_wrap(t.clone(), font.clone(), egui::Color32::WHITE)
                .size()
                .x
        })
        .fold(0.0_f32, f32::max)
        + 26.0;
    let height = row * entries.len() as f32 + 6.0;
    let key = egui::Rect::from_min_size(
        egui::pos2(image.left() + 6.0, image.bottom() - 6.0 - height),
        egui::vec2(width, height),
    );
    painter.rect_filled(key, 3.0, egui::Color32::from_black_alpha(170));
    for (i, (colour, text)) in entries.into_iter().enumerate() {
        let y = key.top() + 3.0 + row * i as f32 + row / 2.0;
        let swatch =
            egui::Rect::from_center_size(egui::pos2(key.left() + 11.0, y), egui::vec2(10.0, 10.0));
        painter.rect_filled(swatch, 1.0, colour);
        let r = painter.text(
            egui::pos2(key.left() + 22.0, y),
            egui::Align2::LEFT_CENTER,
            &text,
            font.clone(),
            egui::Color32::WHITE,
        );
        // Each entry is a label for screen readers (and the tests).
        let id = ui.scope_id().with(("colour-key", i));
        let response = ui.interact(r, id, egui::Sense::hover());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Label, true, &text));
    }
}

/// A message over the top of the image (why nothing renders).
fn image_hint(ui: &egui::Ui, image: egui::Rect, hint: &str) {
    let painter = ui.painter().with_clip_rect(image);
    let galley = painter.layout(
        hint.to_owned(),
        egui::FontId::proportional(14.0),
        egui::Color32::from_rgb(255, 220, 120),
        (image.width() - 24.0).max(40.0),
    );
    let pos = egui::pos2(image.center().x - galley.size().x / 2.0, image.top() + 10.0);
    let back = egui::Rect::from_min_size(pos, galley.size()).expand(5.0);
    painter.rect_filled(back, 3.0, egui::Color32::from_black_alpha(190));
    let response = ui.interact(back, ui.scope_id().with("image-hint"), egui::Sense::hover());
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Label, true, hint));
    painter.galley(pos, galley, egui::Color32::WHITE);
}

/// The rectangle an image of `size` pixels takes, fitted and centred in `avail`.
fn fit(avail: egui::Rect, size: Vec2) -> egui::Rect {
    let scale = (avail.width() / size.x)
        .min(avail.height() / size.y)
        .max(1e-3);
    egui::Rect::from_center_size(avail.center(), egui::vec2(size.x, size.y) * scale)
}

/// Pointer handling over the image rectangle.
fn interact(
    ui: &mut egui::Ui,
    rect: egui::Rect,
    size: Vec2,
    out: &mut ViewOutput,
) -> egui::Response {
    let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, IMAGE_LABEL));
    let to_film = |p: egui::Pos2| {
        let f = (p - rect.min) / rect.size();
        Vec2::new(f.x * size.x, f.y * size.y)
    };
    let shift = ui.input(|i| i.modifiers.shift);
    if response.dragged() {
        let d = response.drag_delta();
        if d != egui::Vec2::ZERO {
            let pan = shift
                || response.dragged_by(egui::PointerButton::Secondary)
                || response.dragged_by(egui::PointerButton::Middle);
            out.edit = Some(if pan {
                Command::Pan(Vec2::new(d.x, d.y) / rect.height())
            } else {
                Command::Orbit(Vec2::new(d.x, d.y))
            });
        }
    }
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            out.edit = Some(Command::Zoom((-scroll * ZOOM_PER_POINT).exp()));
        }
        out.hover = response.hover_pos().map(to_film);
    }
    if response.clicked() {
        out.click = response.interact_pointer_pos().map(to_film);
    }
    response
}

/// Draws the toolbar and `texture` (an image of `size` pixels) fitted and centred in the space
/// `area` leaves of the space below the toolbar (all of it but where presentation mode puts
/// its captions), or a spinner until there is one, with the debug view's colour key and
/// `hint` over it; returns what the pointer did over it.
pub fn show(
    ui: &mut egui::Ui,
    texture: Option<&egui::TextureHandle>,
    size: Option<Vec2>,
    view: Option<&mut View>,
    hint: Option<&str>,
    area: &mut dyn FnMut(egui::Rect) -> egui::Rect,
) -> ViewOutput {
    let mut out = ViewOutput::default();
    let shown_view = view.as_deref().copied().unwrap_or_default();
    toolbar(ui, &mut out, view);
    let avail = ui.available_rect_before_wrap();
    out.avail = avail;
    out.area = area(avail);
    let (Some(t), Some(size)) = (texture, size) else {
        ui.centered_and_justified(egui::Ui::spinner);
        return out;
    };
    let rect = fit(out.area, size);
    out.image = rect;
    interact(ui, rect, size, &mut out);
    ui.painter().image(
        t.id(),
        rect,
        egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
        egui::Color32::WHITE,
    );
    super::overlay::paint(ui, rect);
    colour_key(ui, rect, shown_view);
    if let Some(hint) = hint {
        image_hint(ui, rect, hint);
    }
    out
}

/// The A/B viewport: A left of the divider, B right of it; the divider drags (`area` as for
/// [`show`]).
pub fn show_split(
    ui: &mut egui::Ui,
    ab: &mut AbSplit,
    size: Option<Vec2>,
    view: Option<&mut View>,
    hint: Option<&str>,
    area: &mut dyn FnMut(egui::Rect) -> egui::Rect,
) -> ViewOutput {
    let mut out = ViewOutput::default();
    let shown_view = view.as_deref().copied().unwrap_or_default();
    toolbar(ui, &mut out, view);
    ab.controls(ui);
    let avail = ui.available_rect_before_wrap();
    out.avail = avail;
    out.area = area(avail);
    let Some(size) = size else {
        return out;
    };
    let rect = fit(out.area, size);
    out.image = rect;
    // The images first, the divider after: egui gives a drag to the topmost widget under the
    // pointer, and a widget registered later lies on top. Registered the other way round (as
    // before issue 16), the images took every drag, the camera orbited and the divider stayed.
    interact(ui, rect, size, &mut out);
    let handle = egui::Rect::from_center_size(
        egui::pos2(rect.left() + rect.width() * ab.split, rect.center().y),
        egui::vec2(12.0, rect.height()),
    );
    let divider = ui
        .interact(
            handle,
            ui.scope_id().with("ab-divider"),
            egui::Sense::drag(),
        )
        .on_hover_cursor(egui::CursorIcon::ResizeHorizontal);
    divider.widget_info(|| egui::WidgetInfo::slider(true, f64::from(ab.split), DIVIDER_LABEL));
    if divider.dragged()
        && let Some(p) = divider.interact_pointer_pos()
    {
        // Under the pointer, wherever the drag started on the handle.
        ab.split = ((p.x - rect.left()) / rect.width()).clamp(0.0, 1.0);
    }
    let x = rect.left() + rect.width() * ab.split;
    let left = egui::Rect::from_min_max(rect.min, egui::pos2(x, rect.max.y));
    let right = egui::Rect::from_min_max(egui::pos2(x, rect.min.y), rect.max);
    let painter = ui.painter();
    for (side, r, uv) in [
        (
            0,
            left,
            egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(ab.split, 1.0)),
        ),
        (
            1,
            right,
            egui::Rect::from_min_max(egui::pos2(ab.split, 0.0), egui::pos2(1.0, 1.0)),
        ),
    ] {
        if let Some(t) = ab.texture(side) {
            painter.image(t.id(), r, uv, egui::Color32::WHITE);
        }
    }
    painter.line_segment(
        [egui::pos2(x, rect.top()), egui::pos2(x, rect.bottom())],
        egui::Stroke::new(2.0, egui::Color32::WHITE),
    );
    let font = egui::FontId::proportional(14.0);
    for (side, anchor, align) in [
        (
            0,
            rect.left_top() + egui::vec2(6.0, 6.0),
            egui::Align2::LEFT_TOP,
        ),
        (
            1,
            // B at the bottom, so long captions never overlap.
            rect.right_bottom() + egui::vec2(-6.0, -6.0),
            egui::Align2::RIGHT_BOTTOM,
        ),
    ] {
        let text = ab.caption(side);
        let galley_rect = painter.text(anchor, align, &text, font.clone(), egui::Color32::WHITE);
        painter.rect_filled(
            galley_rect.expand(3.0),
            3.0,
            egui::Color32::from_black_alpha(160),
        );
        painter.text(anchor, align, text, font.clone(), egui::Color32::WHITE);
    }
    colour_key(ui, rect, shown_view);
    if let Some(hint) = hint {
        image_hint(ui, rect, hint);
    }
    out
}
