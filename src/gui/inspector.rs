//! The inspector, the teaching core: hover or click a pixel to see the object hit, the local hit
//! point, the mapping's formula with this pixel's numbers, (u, v), the texel both lookups pick,
//! the footprint and mip level; the texture view marks the texel and draws the footprint.

use crate::inspect::{ImageRead, Inspection, mapping_angles, mapping_hints};
use crate::mapping::Mapping;
use crate::math::{Rgb, Vec2, linear_to_srgb8};
use crate::names::Named as _;
use crate::scene::Scene;
use crate::texture::{ImageData, Lookup};
use std::sync::Arc;

/// Largest side of the texture overview uploaded to the GPU (bigger images are subsampled).
const OVERVIEW_MAX: u32 = 4096;
/// Smallest and largest side of the zoomed texel view, in texels.
const ZOOM_TEXELS: (u32, u32) = (8, 64);

/// The inspector panel: the pixel pinned by a click or under the pointer, what the renderer did
/// there, and the texture views it draws.
pub struct Inspector {
    /// Whether the panel is shown.
    pub open: bool,
    pinned: Option<Vec2>,
    at: Option<Vec2>,
    shown: Option<Inspection>,
    /// Hints for the inspected object's texture ([`mapping_hints`]).
    hints: Vec<String>,
    overview: Option<(usize, egui::TextureHandle)>,
    zoom: Option<(ZoomKey, egui::TextureHandle)>,
}

#[derive(Clone, Copy, PartialEq)]
struct ZoomKey {
    image: usize,
    origin: (i64, i64),
    n: u32,
}

impl Default for Inspector {
    fn default() -> Self {
        Self {
            open: true,
            pinned: None,
            at: None,
            shown: None,
            hints: Vec::new(),
            overview: None,
            zoom: None,
        }
    }
}

pub(super) fn srgb(c: Rgb) -> egui::Color32 {
    let [r, g, b] = c.to_array().map(linear_to_srgb8);
    egui::Color32::from_rgb(r, g, b)
}

impl Inspector {
    /// Forgets the pixel (a new scene was opened).
    pub fn clear(&mut self) {
        self.pinned = None;
        self.at = None;
        self.shown = None;
    }

    /// Inspects the same pixel again in a rebuilt scene.
    pub fn refresh(&mut self, scene: Option<&Scene>) {
        if let (Some(scene), Some(at)) = (scene, self.at) {
            self.shown = scene.inspect(at);
            self.hints = self
                .shown
                .as_ref()
                .map_or_else(Vec::new, |i| mapping_hints(scene, i.object));
        }
    }

    /// Follows the pointer: a click pins a pixel (a second click on the image moves the pin);
    /// hovering inspects while nothing is pinned.
    pub fn pointer(&mut self, scene: &Scene, hover: Option<Vec2>, click: Option<Vec2>) {
        if let Some(c) = click {
            self.pinned = Some(c);
        }
        let at = self.pinned.or(hover);
        if at.is_some() && at != self.at {
            self.at = at;
            self.shown = at.and_then(|p| scene.inspect(p));
            self.hints = self
                .shown
                .as_ref()
                .map_or_else(Vec::new, |i| mapping_hints(scene, i.object));
        }
    }

    /// The inspection shown, if any.
    #[must_use]
    pub fn shown(&self) -> Option<&Inspection> {
        self.shown.as_ref()
    }

    /// Draws the inspector panel: the pinned or hovered pixel's hit, (u, v) and texel.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        ui.heading("Inspector");
        if let Some(p) = self.pinned {
            ui.horizontal(|ui| {
                ui.label(format!(
                    "pinned at ({:.0}, {:.0})",
                    p.x.floor(),
                    p.y.floor()
                ));
                if ui
                    .button("Unpin")
                    .on_hover_text("Follow the pointer again")
                    .clicked()
                {
                    self.pinned = None;
                }
            });
        }
        let Some(i) = self.shown.clone() else {
            ui.label("Hover the image to see what the renderer did at a pixel; click to pin it.");
            if self.at.is_some() {
                ui.label("(this pixel's ray hits nothing: it shows the background)");
            }
            return;
        };
        for h in &self.hints {
            ui.label(
                egui::RichText::new(format!("Hint: {h}"))
                    .color(egui::Color32::from_rgb(255, 200, 90)),
            );
        }
        hit_grid(ui, &i);
        if let Some(m) = &i.mesh {
            mesh_section(ui, m);
        }
        if !i.mapping_lines.is_empty() {
            ui.separator();
            ui.strong("Mapping, with this pixel's numbers");
            for l in &i.mapping_lines {
                ui.monospace(l);
            }
            // `uv` here is (u, v) carried by a mesh: its interpolation is shown above instead.
            if let Some(m) = i.mapping.filter(|&m| m != Mapping::Uv) {
                mapping_diagram(ui, m, i.mapping_point);
            }
        }
        if let Some(t) = i.tex {
            ui.separator();
            egui::Grid::new("inspect-uv").num_columns(2).show(ui, |ui| {
                ui.label("(u, v)");
                ui.monospace(format!("({:.5}, {:.5})", t.uv.x, t.uv.y));
                ui.end_row();
                if let Some(w) = i.wrapped_uv
                    && w != t.uv
                {
                    ui.label("after wrap");
                    ui.monospace(format!("({:.5}, {:.5})", w.x, w.y));
                    ui.end_row();
                }
                ui.label("d(u,v)/dx");
                ui.monospace(format!("({:+.2e}, {:+.2e})", t.duvdx.x, t.duvdx.y));
                ui.end_row();
                ui.label("d(u,v)/dy");
                ui.monospace(format!("({:+.2e}, {:+.2e})", t.duvdy.x, t.duvdy.y));
                ui.end_row();
                if let Some(f) = i.footprint
                    && let (Some((a, b)), Some(level)) = (f.axes_texels, f.mip_level)
                {
                    ui.label("footprint");
                    ui.monospace(format!("{a:.2} x {b:.2} texels"))
                        .on_hover_text(
                        "Lengths of the two axes of the pixel's footprint ellipse in the texture",
                    );
                    ui.end_row();
                    ui.label("mip level");
                    ui.monospace(format!("{level:.2}")).on_hover_text(
                        "log2 of the longest footprint axis in texels: \
                         the level a trilinear mip filter reads",
                    );
                    ui.end_row();
                }
            });
        }
        if i.image.is_some() {
            ui.separator();
            self.texture_views(ui, &i);
        }
        if let Some(read) = &i.image {
            ui.separator();
            ui.strong(format!(
                "Texel in {} ({} x {}, filter {})",
                read.image.name,
                read.image.width(),
                read.image.height(),
                read.filter.name()
            ));
            for pick in &i.texels {
                let active = pick.lookup == read.lookup;
                ui.label(format!(
                    "{} lookup{}: column {}, row {} from the bottom (file row {})",
                    pick.lookup.name(),
                    if active { " (in use)" } else { "" },
                    pick.column,
                    pick.row_from_bottom,
                    pick.file_row
                ));
                for l in &pick.lines {
                    ui.monospace(format!("  {l}"));
                }
            }
        }
    }

    /// The whole texture with a cross at (u, v), and a zoom on the texels around it with both
    /// lookups' texels outlined and the footprint ellipse, side by side.
    fn texture_views(&mut self, ui: &mut egui::Ui, i: &Inspection) {
        let (Some(read), Some(uv)) = (&i.image, i.wrapped_uv) else {
            return;
        };
        let img = &read.image;
        let key = Arc::as_ptr(img) as usize;
        if self.overview.as_ref().is_none_or(|(k, _)| *k != key) {
            let tex = ui.ctx().load_texture(
                "inspector-overview",
                overview(img),
                egui::TextureOptions::LINEAR,
            );
            self.overview = Some((key, tex));
        }
        let col = ((ui.available_width() - 8.0) * 0.5).max(120.0);
        ui.horizontal_top(|ui| {
            ui.vertical(|ui| {
                ui.set_width(col);
                if let Some((_, tex)) = &self.overview {
                    draw_overview(ui, tex, img, uv, col);
                }
                ui.label(
                    "Right: the texels around the hit. Yellow: the centred lookup's texel; \
                     cyan: the lecture's; magenta: the pixel's footprint.",
                );
            });
            let zoom = Zoom::around(i, img, uv);
            let tex = self.zoom_texture(ui.ctx(), key, &zoom, read);
            zoom.draw(ui, &tex, i, col);
        });
    }

    /// The zoom's texels as a texture, uploaded again only when the square moves.
    fn zoom_texture(
        &mut self,
        ctx: &egui::Context,
        image: usize,
        zoom: &Zoom,
        read: &ImageRead,
    ) -> egui::TextureHandle {
        let key = ZoomKey {
            image,
            origin: zoom.origin,
            n: zoom.n,
        };
        if let Some((k, tex)) = &self.zoom
            && *k == key
        {
            return tex.clone();
        }
        let img = &read.image;
        let (w, h) = (img.width(), img.height());
        let (wu, wv) = read.wraps;
        let n = zoom.n;
        let mut pixels = Vec::with_capacity((n * n) as usize);
        for y in 0..n {
            for x in 0..n {
                let col = wu.index(zoom.origin.0 + i64::from(x), w);
                // Wrap in v works on rows from the bottom.
                let from_bottom = i64::from(h) - 1 - (zoom.origin.1 + i64::from(y));
                let row = wv.index(from_bottom, h);
                pixels.push(match (col, row) {
                    (Some(c), Some(r)) => srgb(img.texel(c, r)),
                    _ => egui::Color32::BLACK,
                });
            }
        }
        let image = egui::ColorImage::new([n as usize, n as usize], pixels);
        let tex = ctx.load_texture("inspector-zoom", image, egui::TextureOptions::NEAREST);
        self.zoom = Some((key, tex.clone()));
        tex
    }
}

/// The whole texture, `width` wide, with a cross and a circle at (u, v).
fn draw_overview(
    ui: &mut egui::Ui,
    tex: &egui::TextureHandle,
    img: &ImageData,
    uv: Vec2,
    width: f32,
) {
    let size = egui::vec2(width, width * img.height() as f32 / img.width() as f32);
    let (rect, _) = ui.allocate_exact_size(size, egui::Sense::hover());
    let p = ui.painter_at(rect);
    p.image(tex.id(), rect, UNIT_UV, egui::Color32::WHITE);
    let at = rect.min + egui::vec2(uv.x * rect.width(), (1.0 - uv.y) * rect.height());
    let line = egui::Stroke::new(1.0, egui::Color32::from_white_alpha(120));
    p.line_segment(
        [
            egui::pos2(rect.left(), at.y),
            egui::pos2(rect.right(), at.y),
        ],
        line,
    );
    p.line_segment(
        [
            egui::pos2(at.x, rect.top()),
            egui::pos2(at.x, rect.bottom()),
        ],
        line,
    );
    p.circle_stroke(at, 5.0, egui::Stroke::new(1.5, egui::Color32::YELLOW));
}

/// The whole of a texture, in egui's texture coordinates.
const UNIT_UV: egui::Rect = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));

/// The footprint's colour.
const MAGENTA: egui::Color32 = egui::Color32::from_rgb(255, 60, 255);

/// The square of texels the zoom shows: `n` a side from `origin`, in file texels (y down).
struct Zoom {
    /// The hit in file texels (x right, y down).
    texel_xy: Vec2,
    origin: (i64, i64),
    n: u32,
    /// The image's size in texels.
    size: (u32, u32),
}

impl Zoom {
    /// A square around the hit at `uv`, big enough for the footprint.
    fn around(i: &Inspection, img: &ImageData, uv: Vec2) -> Self {
        let (w, h) = (img.width(), img.height());
        let texel_xy = Vec2::new(uv.x * w as f32, (1.0 - uv.y) * h as f32);
        let major = i
            .footprint
            .and_then(|f| f.axes_texels)
            .map_or(1.0, |(a, _)| a);
        let n = ((major * 2.5).ceil() as u32).clamp(ZOOM_TEXELS.0, ZOOM_TEXELS.1);
        let origin = (
            texel_xy.x.floor() as i64 - i64::from(n / 2),
            texel_xy.y.floor() as i64 - i64::from(n / 2),
        );
        Self {
            texel_xy,
            origin,
            n,
            size: (w, h),
        }
    }

    /// The zoom `side` points square: the texels, their grid when big enough, the texels both
    /// lookups pick and the footprint ellipse.
    fn draw(&self, ui: &mut egui::Ui, tex: &egui::TextureHandle, i: &Inspection, side: f32) {
        let (rect, _) = ui.allocate_exact_size(egui::vec2(side, side), egui::Sense::hover());
        let p = ui.painter_at(rect);
        p.image(tex.id(), rect, UNIT_UV, egui::Color32::WHITE);
        let scale = side / self.n as f32;
        let to_screen = |x: f32, y: f32| {
            rect.min
                + egui::vec2(
                    (x - self.origin.0 as f32) * scale,
                    (y - self.origin.1 as f32) * scale,
                )
        };
        if scale >= 6.0 {
            let grid = egui::Stroke::new(0.5, egui::Color32::from_black_alpha(90));
            for k in 0..=self.n {
                let o = k as f32 * scale;
                p.line_segment(
                    [
                        rect.min + egui::vec2(o, 0.0),
                        rect.min + egui::vec2(o, side),
                    ],
                    grid,
                );
                p.line_segment(
                    [
                        rect.min + egui::vec2(0.0, o),
                        rect.min + egui::vec2(side, o),
                    ],
                    grid,
                );
            }
        }
        for pick in &i.texels {
            let colour = match pick.lookup {
                Lookup::Centred => egui::Color32::YELLOW,
                Lookup::Lecture => egui::Color32::from_rgb(0, 220, 255),
            };
            let (x, y) = self.nearest_copy(pick.column, pick.file_row);
            let r = egui::Rect::from_min_max(to_screen(x, y), to_screen(x + 1.0, y + 1.0));
            p.rect_stroke(
                r.shrink(1.0),
                0.0,
                egui::Stroke::new(2.0, colour),
                egui::StrokeKind::Inside,
            );
        }
        // The footprint: the image of the unit circle under d(u,v)/dx, d(u,v)/dy, in texels
        // (y down).
        if let Some(f) = i.footprint {
            let (w, h) = (self.size.0 as f32, self.size.1 as f32);
            let ax = Vec2::new(f.duvdx.x * w, -f.duvdx.y * h);
            let ay = Vec2::new(f.duvdy.x * w, -f.duvdy.y * h);
            let pts: Vec<egui::Pos2> = (0..=64)
                .map(|k| {
                    let t = k as f32 / 64.0 * std::f32::consts::TAU;
                    let q = self.texel_xy + ax * (0.5 * t.cos()) + ay * (0.5 * t.sin());
                    to_screen(q.x, q.y)
                })
                .collect();
            p.add(egui::Shape::line(pts, egui::Stroke::new(2.0, MAGENTA)));
            p.circle_filled(to_screen(self.texel_xy.x, self.texel_xy.y), 2.5, MAGENTA);
        }
    }

    /// Where to draw the texel a lookup picked (in [0, w) x [0, h) already): the copy of it
    /// nearest the hit, since a wrap can put the hit a period away.
    fn nearest_copy(&self, column: u32, file_row: u32) -> (f32, f32) {
        let unwrap = |t: f32, at: f32, period: f32| t + ((at - t) / period).round() * period;
        (
            unwrap(column as f32, self.texel_xy.x, self.size.0 as f32),
            unwrap(file_row as f32, self.texel_xy.y, self.size.1 as f32),
        )
    }
}

/// The image as an sRGB texture, subsampled to at most [`OVERVIEW_MAX`] a side.
pub(super) fn overview(img: &ImageData) -> egui::ColorImage {
    let (w, h) = (img.width(), img.height());
    let step = w.max(h).div_ceil(OVERVIEW_MAX).max(1);
    let (ow, oh) = (w.div_ceil(step), h.div_ceil(step));
    let mut pixels = Vec::with_capacity((ow * oh) as usize);
    for y in 0..oh {
        for x in 0..ow {
            pixels.push(srgb(
                img.texel_top((x * step).min(w - 1), (y * step).min(h - 1)),
            ));
        }
    }
    egui::ColorImage::new([ow as usize, oh as usize], pixels)
}

/// The hit: pixel, object, points, texture, mapping, colour, radiance and debug value.
fn hit_grid(ui: &mut egui::Ui, i: &Inspection) {
    let v3 = |v: crate::math::Vec3A| format!("({:.4}, {:.4}, {:.4})", v.x, v.y, v.z);
    egui::Grid::new("inspect-hit")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            ui.label("pixel");
            ui.label(format!(
                "({:.0}, {:.0})",
                i.pixel.x.floor(),
                i.pixel.y.floor()
            ));
            ui.end_row();
            ui.label("object");
            ui.label(format!("{} ({})", i.object_name, i.shape));
            ui.end_row();
            ui.label("world hit point");
            ui.label(v3(i.world_point));
            ui.end_row();
            ui.label("local hit point");
            ui.label(v3(i.local_point)).on_hover_text(
                "The lecture's local_hit_point: the hit in the generic object's own space, \
                 which the mapping reads",
            );
            ui.end_row();
            ui.label("texture");
            ui.label(i.texture_kind);
            ui.end_row();
            if let Some(m) = i.mapping {
                ui.label("mapping");
                ui.label(m.name()).on_hover_text(m.description());
                ui.end_row();
            }
            ui.label("texture colour");
            ui.horizontal(|ui| {
                let (r, _) = ui.allocate_exact_size(egui::vec2(28.0, 14.0), egui::Sense::hover());
                ui.painter().rect_filled(r, 2.0, srgb(i.texture_colour));
                let c = i.texture_colour;
                ui.label(format!("({:.3}, {:.3}, {:.3}) linear", c.0, c.1, c.2));
            });
            ui.end_row();
            for (name, v) in &i.parameters {
                ui.label(*name)
                    .on_hover_text("this material parameter's texture, here");
                ui.monospace(v.to_string());
                ui.end_row();
            }
            ui.label("shaded radiance");
            let c = i.radiance;
            ui.label(format!("({:.3}, {:.3}, {:.3}) linear", c.0, c.1, c.2))
                .on_hover_text(
                    "The lit, textured colour of the ray through this pixel (before \
                     exposure), whatever debug view the viewport shows",
                );
            ui.end_row();
            if let Some((view, c)) = i.debug_value {
                ui.label(format!("{} view shows", view.name()));
                ui.label(format!("({:.3}, {:.3}, {:.3})", c.0, c.1, c.2))
                    .on_hover_text(view.description());
                ui.end_row();
            }
        });
}

/// A mesh hit: the triangle's vertices' (u, v), the weights and the interpolation worked.
fn mesh_section(ui: &mut egui::Ui, m: &crate::inspect::MeshPoint) {
    ui.separator();
    ui.strong(format!("Triangle {} of the mesh", m.triangle));
    egui::Grid::new("inspect-mesh")
        .num_columns(3)
        .striped(true)
        .show(ui, |ui| {
            ui.label("vertex");
            ui.label("(u, v)");
            ui.label("weight");
            ui.end_row();
            for k in 0..3 {
                ui.label(format!("{k}"));
                match m.uvs {
                    Some(t) => ui.monospace(format!("({:.4}, {:.4})", t[k].x, t[k].y)),
                    None => ui.label("none in the file"),
                };
                ui.monospace(format!("w{k} = {:.4}", m.bary[k]));
                ui.end_row();
            }
        });
    for l in &m.lines {
        ui.monospace(l);
    }
}

/// Colours of the diagram: the generic object, the hit point and its angles.
const OBJECT: egui::Color32 = egui::Color32::from_gray(150);
const POINT: egui::Color32 = egui::Color32::from_rgb(255, 220, 0);
const ANGLE: egui::Color32 = egui::Color32::from_rgb(90, 220, 255);
const SEAM: egui::Color32 = egui::Color32::from_rgb(255, 60, 255);

/// The mapping's formula drawn: the generic object in two views with the hit point `p` (the
/// point the mapping reads) and its angles (phi, theta, alpha, beta), as the lecture draws them.
fn mapping_diagram(ui: &mut egui::Ui, mapping: Mapping, p: crate::math::Vec3A) {
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

fn text(pa: &egui::Painter, at: egui::Pos2, align: egui::Align2, s: &str, c: egui::Color32) {
    pa.text(at, align, s, egui::FontId::proportional(11.0), c);
}

/// An arc about `c` of radius `r` from screen angle `a0` sweeping `sweep` radians (y down).
fn arc(pa: &egui::Painter, c: egui::Pos2, r: f32, a0: f32, sweep: f32, colour: egui::Color32) {
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
