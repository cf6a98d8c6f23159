//! The texture panel's drawing: the canvas's mapping between texels and screen points, the
//! texel grid, the inspected pixel's triangle, texel and footprint, and the masks and overlays
//! uploaded as textures.

use crate::coverage::{ISO_POLE, ISO_SEAM, ISO_U, ISO_V, IsoLines, PixelMask, TexelMask};
use crate::gui::overlay;
use crate::inspect::Inspection;
use crate::math::Vec2;

/// Largest side of the visible-region and selection images uploaded (bigger textures are
/// reduced: a texel of the reduced image is marked when any texel of its block is).
const MASK_MAX: u32 = 4096;

/// The footprint's colour.
pub(super) const MAGENTA: egui::Color32 = egui::Color32::from_rgb(255, 60, 255);

/// The canvas's mapping between texels (x right, y down from the top-left corner of the image)
/// and screen points.
pub(super) struct View {
    pub(super) rect: egui::Rect,
    /// Points per texel when the whole texture fits.
    pub(super) fit: f32,
    /// Points per texel.
    pub(super) scale: f32,
    /// The texel position at the canvas centre.
    pub(super) centre: egui::Vec2,
    width: f32,
    height: f32,
}

impl View {
    pub(super) fn new(
        rect: egui::Rect,
        (w, h): (u32, u32),
        zoom: f32,
        centre: Option<egui::Vec2>,
    ) -> Self {
        let fit = (rect.width() / w as f32)
            .min(rect.height() / h as f32)
            .max(1e-6);
        Self {
            rect,
            fit,
            scale: fit * zoom,
            centre: centre.unwrap_or(egui::vec2(w as f32 * 0.5, h as f32 * 0.5)),
            width: w as f32,
            height: h as f32,
        }
    }

    pub(super) fn to_screen(&self, x: f32, y: f32) -> egui::Pos2 {
        self.rect.center() + (egui::vec2(x, y) - self.centre) * self.scale
    }

    pub(super) fn to_texels(&self, p: egui::Pos2) -> egui::Vec2 {
        (p - self.rect.center()) / self.scale + self.centre
    }

    /// The screen point of texture coordinates (u, v) (v up).
    pub(super) fn uv(&self, uv: Vec2) -> egui::Pos2 {
        self.to_screen(uv.x * self.width, (1.0 - uv.y) * self.height)
    }
}

/// Texel borders, when texels are big enough to see them (only those on the canvas).
pub(super) fn draw_grid(painter: &egui::Painter, view: &View, (w, h): (u32, u32)) {
    let stroke = egui::Stroke::new(0.5, egui::Color32::from_black_alpha(110));
    let lo = view.to_texels(view.rect.min);
    let hi = view.to_texels(view.rect.max);
    let (x0, x1) = (
        lo.x.floor().max(0.0) as u32,
        hi.x.ceil().min(w as f32) as u32,
    );
    let (y0, y1) = (
        lo.y.floor().max(0.0) as u32,
        hi.y.ceil().min(h as f32) as u32,
    );
    for x in x0..=x1 {
        painter.line_segment(
            [
                view.to_screen(x as f32, y0 as f32),
                view.to_screen(x as f32, y1 as f32),
            ],
            stroke,
        );
    }
    for y in y0..=y1 {
        painter.line_segment(
            [
                view.to_screen(x0 as f32, y as f32),
                view.to_screen(x1 as f32, y as f32),
            ],
            stroke,
        );
    }
}

/// The inspected pixel on the texture: the triangle it hit on a mesh, the texel the lookup in
/// use picks, and its footprint at true size: the parallelogram the pixel square maps to and
/// the ellipse inside it (half of d(u,v)/dx and d(u,v)/dy either side of the hit).
pub(super) fn draw_hit(painter: &egui::Painter, view: &View, i: &Inspection, (w, h): (u32, u32)) {
    if let Some(t) = i.mesh.as_ref().and_then(|m| m.uvs) {
        let p = t.map(|uv| view.uv(uv));
        painter.add(egui::Shape::closed_line(
            p.to_vec(),
            egui::Stroke::new(2.0, egui::Color32::from_rgb(90, 255, 120)),
        ));
    }
    if let Some(read) = &i.image
        && read.filter == crate::texture::Filter::Nearest
        && let Some(pick) = i.texels.iter().find(|t| t.lookup == read.lookup)
    {
        let (x, y) = (pick.column as f32, pick.file_row as f32);
        painter.rect_stroke(
            egui::Rect::from_min_max(view.to_screen(x, y), view.to_screen(x + 1.0, y + 1.0)),
            0.0,
            egui::Stroke::new(1.5, egui::Color32::YELLOW),
            egui::StrokeKind::Outside,
        );
    }
    let (Some(uv), Some(f)) = (i.wrapped_uv, i.footprint) else {
        return;
    };
    let (wf, hf) = (w as f32, h as f32);
    let c = egui::vec2(uv.x * wf, (1.0 - uv.y) * hf);
    let ax = egui::vec2(f.duvdx.x * wf, -f.duvdx.y * hf) * 0.5;
    let ay = egui::vec2(f.duvdy.x * wf, -f.duvdy.y * hf) * 0.5;
    let at = |q: egui::Vec2| view.to_screen(q.x, q.y);
    let corners = vec![
        at(c + ax + ay),
        at(c + ax - ay),
        at(c - ax - ay),
        at(c - ax + ay),
    ];
    painter.add(egui::Shape::closed_line(
        corners,
        egui::Stroke::new(1.0, MAGENTA.gamma_multiply(0.7)),
    ));
    let ellipse: Vec<egui::Pos2> = (0..64)
        .map(|k| {
            let t = k as f32 / 64.0 * std::f32::consts::TAU;
            at(c + ax * t.cos() + ay * t.sin())
        })
        .collect();
    painter.add(egui::Shape::closed_line(
        ellipse,
        egui::Stroke::new(2.0, MAGENTA),
    ));
    painter.circle_filled(at(c), 3.0, MAGENTA);
}

/// The visible region's look: texels no pixel reads are darkened, the others lightly tinted.
pub(super) fn region_colours(on: bool) -> egui::Color32 {
    if on {
        egui::Color32::from_rgba_unmultiplied(80, 255, 120, 40)
    } else {
        egui::Color32::from_rgba_unmultiplied(0, 0, 0, 160)
    }
}

/// A texel mask as an image over the texture (file rows, top first), reduced to at most
/// [`MASK_MAX`] a side: a reduced texel is on when any texel of its block is.
pub(super) fn upload_mask(
    ctx: &egui::Context,
    name: &str,
    mask: &TexelMask,
    colour: fn(bool) -> egui::Color32,
) -> egui::TextureHandle {
    let (w, h) = (mask.width, mask.height);
    let step = w.max(h).div_ceil(MASK_MAX).max(1);
    let (ow, oh) = (w.div_ceil(step), h.div_ceil(step));
    let mut on = vec![false; (ow * oh) as usize];
    for row in 0..h {
        let y = (h - 1 - row) / step;
        for col in 0..w {
            if mask.contains(col, row) {
                on[(y * ow + col / step) as usize] = true;
            }
        }
    }
    let pixels = on.into_iter().map(colour).collect();
    let image = egui::ColorImage::new([ow as usize, oh as usize], pixels);
    ctx.load_texture(name, image, egui::TextureOptions::NEAREST)
}

/// The iso-lines as an image of the film's size.
pub(super) fn upload_iso(ctx: &egui::Context, iso: &IsoLines) -> egui::TextureHandle {
    let pixels = iso
        .flags
        .iter()
        .map(|&f| {
            if f & ISO_POLE != 0 {
                overlay::POLE_COLOUR
            } else if f & ISO_SEAM != 0 {
                overlay::SEAM_COLOUR
            } else if f & ISO_U != 0 {
                overlay::U_COLOUR
            } else if f & ISO_V != 0 {
                overlay::V_COLOUR
            } else {
                egui::Color32::TRANSPARENT
            }
        })
        .collect();
    let image = egui::ColorImage::new([iso.width as usize, iso.height as usize], pixels);
    // Linear: the viewport usually shows the film smaller than its size, and a nearest
    // minification would drop most of a one-pixel line.
    ctx.load_texture("iso-lines", image, egui::TextureOptions::LINEAR)
}

/// The pixels that read the chosen texels, as an image of the film's size.
pub(super) fn upload_highlight(ctx: &egui::Context, mask: &PixelMask) -> egui::TextureHandle {
    let on = egui::Color32::from_rgba_unmultiplied(255, 240, 0, 150);
    let pixels = mask
        .bits
        .iter()
        .map(|&b| if b { on } else { egui::Color32::TRANSPARENT })
        .collect();
    let image = egui::ColorImage::new([mask.width as usize, mask.height as usize], pixels);
    ctx.load_texture("reverse-lookup", image, egui::TextureOptions::LINEAR)
}
