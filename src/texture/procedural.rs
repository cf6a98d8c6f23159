//! Procedural textures: a checkerboard in (u, v) and the labelled UV test grid.

use super::{ImageData, TextureContext};
use crate::mapping::Mapping;
use crate::math::{Rgb, srgb_to_linear};

/// A checkerboard of `squares.0 x squares.1` squares over the unit (u, v) square, repeating
/// outside it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checker {
    /// How hit points become (u, v).
    pub mapping: Mapping,
    /// Squares along u and along v.
    pub squares: (f32, f32),
    /// The two colours (linear).
    pub colors: (Rgb, Rgb),
}

impl Checker {
    /// The colour at a hit.
    #[must_use]
    #[inline]
    pub fn eval(&self, ctx: &TextureContext) -> Rgb {
        let uv = ctx.tex_coord(self.mapping).uv;
        let (i, j) = (
            (uv.x * self.squares.0).floor(),
            (uv.y * self.squares.1).floor(),
        );
        let parity = (i + j).rem_euclid(2.0);
        if parity < 0.5 {
            self.colors.0
        } else {
            self.colors.1
        }
    }
}

/// 5x7 glyphs, one row per byte, bit 4 = leftmost pixel.
const GLYPHS: [(char, [u8; 7]); 18] = [
    ('A', [0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11]),
    ('B', [0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E]),
    ('C', [0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E]),
    ('D', [0x1E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1E]),
    ('E', [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F]),
    ('F', [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10]),
    ('G', [0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F]),
    ('H', [0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11]),
    ('1', [0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E]),
    ('2', [0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F]),
    ('3', [0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E]),
    ('4', [0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02]),
    ('5', [0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E]),
    ('6', [0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E]),
    ('7', [0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08]),
    ('8', [0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E]),
    ('u', [0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D]),
    ('v', [0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04]),
];

fn glyph(c: char) -> Option<&'static [u8; 7]> {
    GLYPHS.iter().find(|(g, _)| *g == c).map(|(_, b)| b)
}

/// Whether pixel (x, y) of a cell of `size` pixels lies on the text `label`, drawn centred
/// with glyph pixels of `scale` screen pixels.
fn on_label(label: &str, x: u32, y: u32, size: u32, scale: u32) -> bool {
    let n = label.chars().count() as u32;
    let (gw, gh) = (5 * scale, 7 * scale);
    let total_w = n * gw + (n.saturating_sub(1)) * scale;
    let (x0, y0) = (
        (size.saturating_sub(total_w)) / 2,
        (size.saturating_sub(gh)) / 2,
    );
    if x < x0 || y < y0 || y >= y0 + gh || x >= x0 + total_w {
        return false;
    }
    let (lx, ly) = (x - x0, y - y0);
    let k = lx / (gw + scale);
    let gx = lx % (gw + scale);
    if gx >= gw {
        return false;
    }
    let Some(bits) = label.chars().nth(k as usize).and_then(glyph) else {
        return false;
    };
    let (col, row) = (gx / scale, ly / scale);
    bits[row as usize] & (0x10 >> col) != 0
}

/// The labelled UV test grid: 8 x 8 cells named A1 (bottom left, u = v = 0) to H8 (top right),
/// tinted red along u and green along v, with a bold frame on the u = 0 and v = 0 edges and
/// "u" / "v" arrows' letters, so orientation, mirroring and seams are visible at a glance.
#[must_use]
pub fn uv_grid_image(size: u32) -> ImageData {
    const CELLS: u32 = 8;
    let cell = (size / CELLS).max(8);
    let size = cell * CELLS;
    let scale = (cell / 16).max(1);
    ImageData::from_fn(size, size, "uv-grid", |x, y_top| {
        let y = size - 1 - y_top; // count rows from the bottom, as v does
        let (ci, cj) = (x / cell, y / cell);
        let (lx, ly) = (x % cell, y % cell);
        let (u, v) = (
            (ci as f32 + 0.5) / CELLS as f32,
            (cj as f32 + 0.5) / CELLS as f32,
        );
        let shade = if (ci + cj) % 2 == 0 { 0.85 } else { 0.65 };
        let mut c = [0.35 + 0.6 * u, 0.35 + 0.6 * v, 0.55].map(|k| k * shade);
        let line = cell / 64 + 1;
        let edge = lx < line || ly < line || lx >= cell - line || ly >= cell - line;
        let label = format!(
            "{}{}",
            char::from(b'A' + ci as u8),
            char::from(b'1' + cj as u8)
        );
        // The cell's label, upright when the image is seen with v up.
        if on_label(&label, lx, cell - 1 - ly, cell, scale) {
            c = [0.05, 0.05, 0.08];
        } else if edge {
            c = [0.1, 0.1, 0.1];
        }
        // Bold red frame on u = 0, bold green on v = 0, with a 'u' / 'v' letter beside them.
        if x < 3 * line {
            c = [0.9, 0.1, 0.1];
        }
        if y < 3 * line {
            c = [0.1, 0.8, 0.1];
        }
        if ci == CELLS - 1 && cj == 0 && on_label("u", lx, cell - 1 - ly, cell / 3, scale) {
            c = [0.9, 0.1, 0.1];
        }
        if ci == 0 && cj == CELLS - 1 && on_label("v", lx, cell - 1 - ly, cell / 3, scale) {
            c = [0.1, 0.6, 0.1];
        }
        Rgb(
            srgb_to_linear(c[0]),
            srgb_to_linear(c[1]),
            srgb_to_linear(c[2]),
        )
    })
}
