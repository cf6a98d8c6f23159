//! The texture panel, beside the viewport: the whole texture, zoomable (wheel) and pannable
//! (drag), with the region the pixels read tinted, the hovered pixel's footprint at its true
//! size and shape, on a mesh the hit triangle and the whole UV layout; hovering, clicking or
//! brushing (shift + drag) texels highlights in the viewport every pixel that reads them.
//!
//! What it draws is computed by [`crate::coverage`] on the render pool: one (u, v) pass per
//! scene, then a reverse lookup per choice of texels. The panel also publishes the viewport's
//! overlay (iso-lines, highlighted pixels) through [`super::overlay`].

use super::inspector::overview;
use super::overlay::{self, HIGHLIGHT_COLOUR, Overlay};
use crate::coverage::{
    DEFAULT_ISO_DIVISIONS, IsoLines, PixelMask, TexelMask, UvField, iso_lines, object_image,
    pixels_reading, textured_objects, visible_region,
};
use crate::geometry::Shape;
use crate::inspect::{Inspection, mapping_hints};
use crate::names::Named as _;
use crate::render::Task;
use crate::scene::Scene;
use std::sync::Arc;

mod draw;
use draw::{
    MAGENTA, View, draw_grid, draw_hit, region_colours, upload_highlight, upload_iso, upload_mask,
};

/// The accessible name of the panel's texture image.
pub const TEXTURE_LABEL: &str = "Texture panel image";

/// UV layouts with more triangles than this are drawn one triangle in `n`.
const MAX_LAYOUT_TRIANGLES: usize = 30_000;
/// Up to this many highlighted pixels also get a ring in the viewport.
const MAX_MARKERS: usize = 64;
/// Brush radius, in screen points.
const BRUSH_POINTS: f32 = 8.0;

/// What one (u, v) pass gave, for one scene.
struct Computed {
    field: Arc<UvField>,
    iso: IsoLines,
    /// Each image-textured object's visible region.
    regions: Vec<(usize, TexelMask)>,
}

/// Which texels the reverse lookup is asked about.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
struct Ask {
    object: usize,
    /// Bumped on every change of the brushed or clicked texels.
    selection: u64,
    /// The texel hovered when nothing is chosen.
    hover: Option<(u32, u32)>,
}

/// The texture panel's state.
pub struct TexturePanel {
    /// Whether the panel is shown.
    pub open: bool,
    /// The scene computed (or being computed), by address.
    scene_key: usize,
    scene: Option<Arc<Scene>>,
    job: Option<Task<Computed>>,
    computed: Option<Arc<Computed>>,
    object: usize,
    /// Zoom over the fitted view (1: the whole texture fits).
    zoom: f32,
    /// The texel position at the canvas centre (x right, y down, in texels); `None`: centred.
    centre: Option<egui::Vec2>,
    selection: Option<TexelMask>,
    selection_version: u64,
    hover: Option<(u32, u32)>,
    /// The object the inspector showed last: the panel follows it when it changes.
    followed: Option<usize>,
    asked: Option<Ask>,
    reverse: Option<Task<PixelMask>>,
    highlight: Option<(Ask, PixelMask)>,
    image_tex: Option<(usize, egui::TextureHandle)>,
    region_tex: Option<((usize, usize), egui::TextureHandle)>,
    selection_tex: Option<(u64, egui::TextureHandle)>,
    iso_tex: Option<(usize, egui::TextureHandle)>,
    highlight_tex: Option<(Ask, egui::TextureHandle)>,
    error: Option<String>,
}

impl Default for TexturePanel {
    fn default() -> Self {
        Self {
            open: false,
            scene_key: 0,
            scene: None,
            job: None,
            computed: None,
            object: 0,
            zoom: 1.0,
            centre: None,
            selection: None,
            selection_version: 0,
            hover: None,
            followed: None,
            asked: None,
            reverse: None,
            highlight: None,
            image_tex: None,
            region_tex: None,
            selection_tex: None,
            iso_tex: None,
            highlight_tex: None,
            error: None,
        }
    }
}

impl TexturePanel {
    /// Once a frame, before the panels: starts the (u, v) pass for a new scene when the panel or
    /// the iso-lines need it, collects finished work, and publishes the viewport's overlay.
    pub fn update(&mut self, ctx: &egui::Context, scene: Option<&Arc<Scene>>) {
        let wanted = self.open || overlay::iso_on(ctx);
        if let Some(scene) = scene.filter(|_| wanted) {
            let key = Arc::as_ptr(scene) as usize;
            if key != self.scene_key {
                self.start(scene.clone());
            }
        }
        if let Some(job) = &self.job
            && let Some(c) = job.take()
        {
            self.job = None;
            self.computed = Some(Arc::new(c));
            self.iso_tex = None;
            self.asked = None;
        }
        self.poll_reverse();
        if self.job.is_some() || self.reverse.is_some() {
            ctx.request_repaint_after(std::time::Duration::from_millis(30));
        }
        self.publish(ctx);
    }

    /// Starts the pass for `scene`, cancelling any older one.
    fn start(&mut self, scene: Arc<Scene>) {
        self.scene_key = Arc::as_ptr(&scene) as usize;
        let same_image =
            |a: &Scene, b: &Scene, o: usize| match (object_image(a, o), object_image(b, o)) {
                (Some(x), Some(y)) => Arc::ptr_eq(&x.image, &y.image),
                _ => false,
            };
        // Keep the chosen texels while the object's image stays.
        if !self
            .scene
            .as_ref()
            .is_some_and(|old| same_image(old, &scene, self.object))
        {
            self.selection = None;
            self.selection_version += 1;
            self.centre = None;
            self.zoom = 1.0;
        }
        let objects = textured_objects(&scene);
        if !objects.contains(&self.object) {
            self.object = objects.first().copied().unwrap_or(0);
        }
        self.scene = Some(scene.clone());
        self.highlight = None;
        self.reverse = None;
        self.asked = None;
        let work = move |cancel: &std::sync::atomic::AtomicBool| {
            let field = UvField::compute(&scene, cancel).ok()?;
            let iso = iso_lines(&field, DEFAULT_ISO_DIVISIONS);
            let regions = textured_objects(&scene)
                .into_iter()
                .filter_map(|o| Some((o, visible_region(&scene, &field, o)?)))
                .collect();
            Some(Computed {
                field: Arc::new(field),
                iso,
                regions,
            })
        };
        match Task::spawn(work) {
            Ok(job) => {
                self.job = Some(job);
                self.error = None;
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// The texels the viewport highlights the readers of: the chosen ones, else the hovered one.
    fn ask(&self) -> Option<Ask> {
        let hover = if self.selection.is_some() {
            None
        } else {
            Some(self.hover?)
        };
        Some(Ask {
            object: self.object,
            selection: self.selection_version,
            hover,
        })
    }

    /// Starts the reverse lookup when the texels asked about changed; collects its result.
    fn poll_reverse(&mut self) {
        if let Some(r) = &self.reverse
            && let Some(mask) = r.take()
        {
            self.reverse = None;
            if let Some(a) = self.asked {
                self.highlight = Some((a, mask));
            }
        }
        let ask = self.ask();
        if ask == self.asked {
            return;
        }
        self.asked = ask;
        self.reverse = None;
        let (Some(ask), Some(c), Some(scene)) = (ask, &self.computed, &self.scene) else {
            self.highlight = None;
            return;
        };
        let Some(tex) = object_image(scene, ask.object) else {
            return;
        };
        let mask = match (ask.hover, &self.selection) {
            (Some((col, row)), _) => {
                let mut m = TexelMask::new(tex.image.width(), tex.image.height());
                m.insert(col, row);
                m
            }
            (None, Some(sel)) => sel.clone(),
            (None, None) => return,
        };
        let (scene, field) = (scene.clone(), c.field.clone());
        match Task::spawn(move |_| Some(pixels_reading(&scene, &field, ask.object, &mask))) {
            Ok(job) => self.reverse = Some(job),
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// The overlay the viewport draws: iso-lines when ticked, the highlighted pixels.
    fn publish(&mut self, ctx: &egui::Context) {
        let mut o = Overlay::default();
        if let Some(c) = &self.computed {
            let iso = &c.iso;
            o.film = egui::vec2(iso.width as f32, iso.height as f32);
            if overlay::iso_on(ctx) {
                let key = Arc::as_ptr(c) as usize;
                if self.iso_tex.as_ref().is_none_or(|(k, _)| *k != key) {
                    self.iso_tex = Some((key, upload_iso(ctx, iso)));
                }
                o.iso = self.iso_tex.as_ref().map(|(_, t)| t.clone());
                o.labels = iso
                    .labels
                    .iter()
                    .map(|l| {
                        let colour = if l.is_u {
                            overlay::U_COLOUR
                        } else {
                            overlay::V_COLOUR
                        };
                        let at = egui::pos2(l.pixel.0 as f32 + 0.5, l.pixel.1 as f32 + 0.5);
                        (at, l.text.clone(), colour)
                    })
                    .collect();
                o.seam = iso
                    .seam
                    .iter()
                    .map(|&(x, y)| egui::pos2(x as f32 + 0.5, y as f32 + 0.5))
                    .collect();
                o.poles = iso.poles.iter().map(|&(x, y)| egui::pos2(x, y)).collect();
            }
            if let Some((ask, mask)) = &self.highlight
                && Some(*ask) == self.asked
                && (self.open || self.selection.is_some())
            {
                if self.highlight_tex.as_ref().is_none_or(|(k, _)| k != ask) {
                    self.highlight_tex = Some((*ask, upload_highlight(ctx, mask)));
                }
                o.highlight = self.highlight_tex.as_ref().map(|(_, t)| t.clone());
                if mask.count() <= MAX_MARKERS {
                    o.markers = mask
                        .bits
                        .iter()
                        .enumerate()
                        .filter(|&(_, &b)| b)
                        .map(|(k, _)| {
                            let (x, y) = (k as u32 % mask.width, k as u32 / mask.width);
                            egui::pos2(x as f32 + 0.5, y as f32 + 0.5)
                        })
                        .collect();
                }
            }
        }
        overlay::publish(ctx, o);
    }

    /// How many pixels read the texels asked about, once known.
    fn readers(&self) -> Option<usize> {
        let (ask, mask) = self.highlight.as_ref()?;
        (Some(*ask) == self.asked).then(|| mask.count())
    }

    /// Draws the panel; `shown` is the inspector's pixel (its footprint and triangle).
    pub fn ui(&mut self, ui: &mut egui::Ui, shown: Option<&Inspection>) {
        ui.heading("Texture");
        if let Some(e) = &self.error {
            ui.colored_label(ui.visuals().error_fg_color, e);
        }
        let Some(scene) = self.scene.clone() else {
            ui.label("No scene.");
            return;
        };
        let objects = textured_objects(&scene);
        if objects.is_empty() {
            ui.label("No object of this scene reads an image: the panel shows image textures.");
            return;
        }
        // Follow the inspector to another textured object (the picker still overrides).
        let inspected = shown.map(|i| i.object);
        if inspected.is_some() && inspected != self.followed {
            self.followed = inspected;
            if let Some(o) = inspected.filter(|o| objects.contains(o) && *o != self.object) {
                self.object = o;
                self.selection = None;
                self.selection_version += 1;
                self.centre = None;
                self.zoom = 1.0;
            }
        }
        if objects.len() > 1 {
            let name = |o: usize| scene.objects[o].name.clone();
            let before = self.object;
            egui::ComboBox::from_label("Object")
                .selected_text(name(self.object))
                .show_ui(ui, |ui| {
                    for &o in &objects {
                        ui.selectable_value(&mut self.object, o, name(o));
                    }
                });
            if self.object != before {
                self.selection = None;
                self.selection_version += 1;
                self.centre = None;
                self.zoom = 1.0;
            }
        }
        let Some(tex) = object_image(&scene, self.object) else {
            return;
        };
        let img = tex.image.clone();
        let (w, h) = (img.width(), img.height());
        ui.label(format!(
            "{} ({w} x {h}), {} mapping, {} filter",
            img.name,
            tex.mapping.name(),
            tex.filter.name()
        ));
        for hint in mapping_hints(&scene, self.object) {
            ui.label(
                egui::RichText::new(format!("Hint: {hint}"))
                    .color(egui::Color32::from_rgb(255, 200, 90)),
            );
        }
        let computed = self.computed.clone();
        let region = computed
            .as_ref()
            .and_then(|c| c.regions.iter().find(|(o, _)| *o == self.object))
            .map(|(_, m)| m);
        match region {
            Some(r) => {
                let n = r.count();
                ui.label(format!(
                    "Visible region (tinted): {n} texels, {:.1} % of the image, read by the pixels",
                    100.0 * n as f64 / (f64::from(w) * f64::from(h))
                ));
            }
            None => {
                ui.horizontal(|ui| {
                    ui.spinner();
                    ui.label("finding the texels the pixels read…");
                });
            }
        }
        ui.horizontal(|ui| {
            if ui
                .button("Fit")
                .on_hover_text("Show the whole texture")
                .clicked()
            {
                self.zoom = 1.0;
                self.centre = None;
            }
            if ui
                .add_enabled(self.selection.is_some(), egui::Button::new("Clear texels"))
                .on_hover_text("Forget the clicked or brushed texels")
                .clicked()
            {
                self.selection = None;
                self.selection_version += 1;
            }
            let mut iso = overlay::iso_on(ui.ctx());
            if ui
                .checkbox(&mut iso, "Iso-lines on the image")
                .on_hover_text("Lines of constant u and v every 1/8 over the viewport's image")
                .changed()
            {
                overlay::set_iso(ui.ctx(), iso);
            }
        });
        ui.label(
            egui::RichText::new(
                "wheel: zoom · drag: pan · click a texel: pick it · shift-drag: brush texels",
            )
            .weak(),
        );
        self.canvas(ui, &scene, &img, region, shown);
        self.footer(ui, shown);
    }

    /// The texture with the visible region, the chosen texels, the grid, a mesh's UV layout and
    /// the inspected pixel; the pointer's zoom, pan, pick and brush.
    fn canvas(
        &mut self,
        ui: &mut egui::Ui,
        scene: &Scene,
        img: &Arc<crate::texture::ImageData>,
        region: Option<&TexelMask>,
        shown: Option<&Inspection>,
    ) {
        let (w, h) = (img.width(), img.height());
        let computed = self.computed.clone();
        let key = Arc::as_ptr(img) as usize;
        if self.image_tex.as_ref().is_none_or(|(k, _)| *k != key) {
            let t = ui.ctx().load_texture(
                "texture-panel-image",
                overview(img),
                egui::TextureOptions::NEAREST,
            );
            self.image_tex = Some((key, t));
        }
        let info_height = 44.0;
        let size = egui::vec2(
            ui.available_width(),
            (ui.available_height() - info_height).max(160.0),
        );
        let (rect, response) = ui.allocate_exact_size(size, egui::Sense::click_and_drag());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, TEXTURE_LABEL));
        let view = View::new(rect, (w, h), self.zoom, self.centre);
        self.pointer(ui, &response, &view, (w, h));
        let view = View::new(rect, (w, h), self.zoom, self.centre);
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 0.0, egui::Color32::from_gray(20));
        let unit = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        let image_rect =
            egui::Rect::from_min_max(view.to_screen(0.0, 0.0), view.to_screen(w as f32, h as f32));
        if let Some((_, t)) = &self.image_tex {
            painter.image(t.id(), image_rect, unit, egui::Color32::WHITE);
        }
        if let Some(r) = region {
            let rkey = (
                computed.as_ref().map_or(0, |c| Arc::as_ptr(c) as usize),
                self.object,
            );
            if self.region_tex.as_ref().is_none_or(|(k, _)| *k != rkey) {
                self.region_tex = Some((
                    rkey,
                    upload_mask(ui.ctx(), "texture-panel-region", r, region_colours),
                ));
            }
            if let Some((_, t)) = &self.region_tex {
                painter.image(t.id(), image_rect, unit, egui::Color32::WHITE);
            }
        }
        if let Some(sel) = &self.selection {
            if self
                .selection_tex
                .as_ref()
                .is_none_or(|(k, _)| *k != self.selection_version)
            {
                let t = upload_mask(ui.ctx(), "texture-panel-selection", sel, |on| {
                    if on {
                        egui::Color32::from_rgba_unmultiplied(255, 240, 0, 170)
                    } else {
                        egui::Color32::TRANSPARENT
                    }
                });
                self.selection_tex = Some((self.selection_version, t));
            }
            if let Some((_, t)) = &self.selection_tex {
                painter.image(t.id(), image_rect, unit, egui::Color32::WHITE);
            }
        }
        if view.scale >= 6.0 {
            draw_grid(&painter, &view, (w, h));
        }
        if let Shape::Mesh(m) = &scene.objects[self.object].shape {
            let stroke = egui::Stroke::new(0.6, egui::Color32::from_white_alpha(110));
            let n = m.mesh.triangle_count();
            let every = n.div_ceil(MAX_LAYOUT_TRIANGLES).max(1);
            for t in m.mesh.uv_triangles().step_by(every) {
                let p = t.map(|uv| view.uv(uv));
                painter.add(egui::Shape::closed_line(p.to_vec(), stroke));
            }
        }
        if let Some(i) = shown.filter(|i| i.object == self.object) {
            draw_hit(&painter, &view, i, (w, h));
        }
        if let Some((c, r)) = self.hover {
            let (x, y) = (c as f32, (h - 1 - r) as f32);
            let q =
                egui::Rect::from_min_max(view.to_screen(x, y), view.to_screen(x + 1.0, y + 1.0));
            painter.rect_stroke(
                q.expand(1.0),
                0.0,
                egui::Stroke::new(1.5, HIGHLIGHT_COLOUR),
                egui::StrokeKind::Outside,
            );
        }
    }

    /// What the pointer chose and how many pixels read it; the footprint's size.
    fn footer(&self, ui: &mut egui::Ui, shown: Option<&Inspection>) {
        let what = match (&self.selection, self.hover) {
            (Some(s), _) => Some(match s.count() {
                1 => "1 texel chosen".to_owned(),
                n => format!("{n} texels chosen"),
            }),
            (None, Some((c, r))) => Some(format!("texel ({c}, {r} from the bottom)")),
            _ => None,
        };
        if let Some(what) = what {
            let readers = self.readers().map_or_else(
                || "…".to_owned(),
                |n| match n {
                    0 => {
                        "no pixel reads it: it is off screen or between the pixels' lookups".into()
                    }
                    1 => "1 pixel reads it (highlighted in the viewport)".into(),
                    n => format!("{n} pixels read it (highlighted in the viewport)"),
                },
            );
            ui.label(format!("{what}: {readers}"));
        } else {
            ui.label("Hover or click a texel to see the pixels that read it.");
        }
        if let Some(i) = shown.filter(|i| i.object == self.object)
            && let Some(f) = i.footprint
            && let Some((a, b)) = f.axes_texels
        {
            ui.label(
                egui::RichText::new(format!(
                    "magenta: pixel ({:.0}, {:.0})'s footprint, {a:.1} x {b:.1} texels",
                    i.pixel.x.floor(),
                    i.pixel.y.floor()
                ))
                .color(MAGENTA),
            );
        }
    }

    /// Wheel zoom about the pointer, drag to pan, click to pick a texel, shift-drag to brush.
    fn pointer(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        view: &View,
        (w, h): (u32, u32),
    ) {
        let texel_at = |p: egui::Pos2| {
            let t = view.to_texels(p);
            (t.x >= 0.0 && t.y >= 0.0 && t.x < w as f32 && t.y < h as f32)
                .then(|| (t.x as u32, h - 1 - t.y as u32))
        };
        self.hover = response.hover_pos().and_then(texel_at);
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0
                && let Some(p) = response.hover_pos()
            {
                let before = view.to_texels(p);
                let zoom = (self.zoom * (scroll * 0.004).exp()).clamp(0.25, 4096.0);
                let scale = view.fit * zoom;
                // Keep the texel under the pointer where it is.
                let centre = before - (p - view.rect.center()) / scale;
                self.zoom = zoom;
                self.centre = Some(centre);
            }
        }
        let shift = ui.input(|i| i.modifiers.shift);
        if response.dragged() {
            if shift {
                if let Some(p) = response.interact_pointer_pos() {
                    let sel = self.selection.get_or_insert_with(|| TexelMask::new(w, h));
                    let r = (BRUSH_POINTS / view.scale).max(0.5);
                    // Stamp along the segment the pointer moved this frame, not only at its
                    // end: a fast stroke leaves no gaps.
                    let to = view.to_texels(p);
                    let from = view.to_texels(p - response.drag_delta());
                    let steps = ((to - from).length() / (r * 0.5)).ceil().clamp(1.0, 512.0) as u32;
                    for k in 0..=steps {
                        let c = from + (to - from) * (k as f32 / steps as f32);
                        brush(sel, c, r);
                    }
                    self.selection_version += 1;
                }
            } else {
                let d = response.drag_delta();
                if d != egui::Vec2::ZERO {
                    let centre = self.centre.unwrap_or(view.centre);
                    self.centre = Some(centre - d / view.scale);
                }
            }
        }
        if response.clicked()
            && let Some(t) = response.interact_pointer_pos().and_then(texel_at)
        {
            let same = self
                .selection
                .as_ref()
                .is_some_and(|s| s.count() == 1 && s.contains(t.0, t.1));
            self.selection = (!same).then(|| {
                let mut m = TexelMask::new(w, h);
                m.insert(t.0, t.1);
                m
            });
            self.selection_version += 1;
        }
    }
}

/// Adds the texels whose centres lie within `r` texels of `c` (x right, y down) to `sel`.
fn brush(sel: &mut TexelMask, c: egui::Vec2, r: f32) {
    let (w, h) = (i64::from(sel.width), i64::from(sel.height));
    let (x0, x1) = ((c.x - r).floor() as i64, (c.x + r).ceil() as i64);
    let (y0, y1) = ((c.y - r).floor() as i64, (c.y + r).ceil() as i64);
    for y in y0.max(0)..y1.min(h) {
        for x in x0.max(0)..x1.min(w) {
            let d = egui::vec2(x as f32 + 0.5, y as f32 + 0.5) - c;
            if d.length() <= r {
                sel.insert(x as u32, (h - 1 - y) as u32);
            }
        }
    }
}
