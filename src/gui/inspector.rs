//! The inspector, the teaching core: hover or click a pixel to see the object hit, the local hit
//! point, the mapping's formula with this pixel's numbers, (u, v), the texel both lookups pick,
//! the footprint and mip level; the texture view marks the texel and draws the footprint.

use crate::inspect::{ImageRead, Inspection, mapping_hints};
use crate::mapping::Mapping;
use crate::math::{Rgb, Vec2, linear_to_srgb8};
use crate::names::Named as _;
use crate::scene::Scene;
use crate::texture::{ImageData, Lookup};
use std::sync::Arc;

mod answer;
mod diagram;
mod mirror;
mod normals;
use diagram::mapping_diagram;

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
    /// A pixel was pinned since the panel was last drawn: it scrolls back to the answer.
    scroll_to_top: bool,
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
            scroll_to_top: false,
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
            self.scroll_to_top = true;
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

    /// Whether a pixel was pinned since the last call (the panel then scrolls to its top).
    pub fn take_scroll_to_top(&mut self) -> bool {
        std::mem::take(&mut self.scroll_to_top)
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
        answer::answer(ui, &i);
        for h in &self.hints {
            ui.label(
                egui::RichText::new(format!("Hint: {h}"))
                    .color(egui::Color32::from_rgb(255, 200, 90)),
            );
        }
        hit_grid(ui, &i);
        if let Some(p) = &i.perturbation {
            normals::surface_vectors(
                ui,
                &format!(
                    "edge-on: the {} tilts the shading normal {:.1}° from the geometric one",
                    p.kind, p.tilt_degrees
                ),
                p.geometric,
                "geometric n",
                &[normals::Arrow {
                    dir: p.shading,
                    name: "shading n",
                    colour: egui::Color32::from_rgb(255, 150, 60),
                    marked: true,
                }],
            );
        }
        if let Some(m) = &i.mirror {
            mirror::mirror_section(ui, m);
        }
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

/// A bump or normal map's rows: the value read, its (u, v) frame, and the normals.
fn perturbation_rows(ui: &mut egui::Ui, p: &crate::inspect::PerturbationRead) {
    let v3 = |v: crate::math::Vec3A| format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z);
    ui.label(p.kind);
    // A normal map's texel and decoded normal is a long line: it wraps in a narrow pane.
    ui.add(egui::Label::new(egui::RichText::new(&p.value).monospace()).wrap());
    ui.end_row();
    if let Some((dpdu, dpdv)) = p.frame {
        ui.label("dp/du, dp/dv").on_hover_text(
            "The surface's directions of growing u and v (object space): the map's slopes and \
             tangent-space normals are read in this frame",
        );
        ui.label(format!("{}, {}", v3(dpdu), v3(dpdv)));
        ui.end_row();
    }
    ui.label("geometric normal");
    ui.label(v3(p.geometric));
    ui.end_row();
    ui.label("shading normal");
    ui.label(format!("{}, tilted {:.1}°", v3(p.shading), p.tilt_degrees))
        .on_hover_text(format!(
            "The normal the lighting uses, tilted from the geometric one by the {}; the surface \
             itself does not move",
            p.kind
        ));
    ui.end_row();
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
            for pass in &i.passed {
                ui.label("passed through");
                ui.label(format!(
                    "{}: alpha {:.2}, a hole; the ray went on",
                    pass.object_name, pass.alpha
                ))
                .on_hover_text(format!(
                    "At {}. Where a clip map's alpha is 0 the surface is not there: the \
                     renderer's ray goes on behind it, and so does the inspector's",
                    v3(pass.world_point)
                ));
                ui.end_row();
            }
            ui.label("object");
            ui.label(format!("{} ({})", i.object_name, i.shape));
            ui.end_row();
            if let Some(p) = &i.perturbation {
                perturbation_rows(ui, p);
            }
            if let Some(a) = i.alpha {
                ui.label("clip-map alpha");
                ui.label(if a >= 1.0 {
                    format!("{a:.2}: solid here")
                } else {
                    format!(
                        "{a:.2}: the pixel is {a:.2} of this surface and {:.2} of what lies \
                         behind it",
                        1.0 - a
                    )
                });
                ui.end_row();
            }
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
