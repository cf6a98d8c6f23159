//! Procedural textures: a checkerboard in (u, v) and the labelled UV test grid.

use super::{Filter, ImageData, TextureContext};
use crate::mapping::{AnyMapping, TexCoord, UvAffine};
use crate::math::{Rgb, floor_fast, srgb_to_linear};

/// A checkerboard of `squares.0 x squares.1` squares over the unit (u, v) square, repeating
/// outside it.
#[derive(Clone, Debug, PartialEq)]
pub struct Checker {
    /// How hit points become (u, v).
    pub mapping: AnyMapping,
    /// Squares along u and along v.
    pub squares: (f32, f32),
    /// The two colours (linear).
    pub colors: (Rgb, Rgb),
    /// Footprint filters ([`Filter::needs_footprint`]) use the closed-form box filter; the others
    /// point-sample.
    pub filter: Filter,
    /// The (u, v) transform after the mapping; `None` for none.
    pub transform: Option<UvAffine>,
}

impl Checker {
    /// The colour at a hit.
    #[must_use]
    #[inline]
    pub fn eval(&self, ctx: &TextureContext) -> Rgb {
        let tc = self.tex_coord(ctx);
        if !tc.uv.is_finite() {
            return super::mark();
        }
        if self.filter.needs_footprint() {
            self.box_filtered(&tc)
        } else {
            self.point(tc.uv)
        }
    }

    /// Texture coordinates of a hit: the mapping's, then the (u, v) transform if any.
    #[must_use]
    #[inline]
    pub fn tex_coord(&self, ctx: &TextureContext) -> TexCoord {
        ctx.transformed_tex_coord(&self.mapping, self.transform.as_ref())
    }

    /// The checker averaged over the bounding box of the pixel's footprint, in closed form
    /// (pbrt's `Checkerboard` with a box filter). Along one axis, the share of [s0, s1] lying in
    /// odd squares is `(I(s1) - I(s0)) / (s1 - s0)` with `I(x) = floor(x / 2) +
    /// 2 max(x / 2 - floor(x / 2) - 1 / 2, 0)` the integral of the odd-square indicator; the 2D
    /// share of the second colour is `a (1 - b) + b (1 - a)`. The box is the bounding box of the
    /// one-pixel parallelogram spanned by d(u, v)/dx and d(u, v)/dy. (Floors by [`floor_fast`]:
    /// this runs per lane outside the kernel's instruction set, where `f32::floor` is a call.)
    #[must_use]
    pub fn box_filtered(&self, tc: &TexCoord) -> Rgb {
        let (nu, nv) = self.squares;
        let (s, t) = (tc.uv.x * nu, tc.uv.y * nv);
        let ds = 0.5 * (tc.duvdx.x.abs() + tc.duvdy.x.abs()) * nu;
        let dt = 0.5 * (tc.duvdx.y.abs() + tc.duvdy.y.abs()) * nv;
        let (s0, s1, t0, t1) = (s - ds, s + ds, t - dt, t + dt);
        if !(s0.is_finite() && s1.is_finite() && t0.is_finite() && t1.is_finite())
            || (floor_fast(s0) == floor_fast(s1) && floor_fast(t0) == floor_fast(t1))
        {
            return self.point(tc.uv);
        }
        // Over many squares the average is the mean colour (and f32 loses the fraction).
        let share = |a: f32, b: f32, d: f32| {
            if d <= 0.0 {
                // Zero width: a point along this axis.
                if floor_fast(a).rem_euclid(2.0) < 0.5 {
                    0.0
                } else {
                    1.0
                }
            } else if d > 1e5 {
                0.5
            } else {
                ((odd_integral(b) - odd_integral(a)) / (2.0 * d)).clamp(0.0, 1.0)
            }
        };
        let a = share(s0, s1, ds);
        let b = share(t0, t1, dt);
        let second = a * (1.0 - b) + b * (1.0 - a);
        self.colors.0 * (1.0 - second) + self.colors.1 * second
    }

    /// The checker at one point.
    #[must_use]
    #[inline]
    pub fn point(&self, uv: crate::math::Vec2) -> Rgb {
        let (i, j) = (
            floor_fast(uv.x * self.squares.0),
            floor_fast(uv.y * self.squares.1),
        );
        let parity = (i + j).rem_euclid(2.0);
        if parity < 0.5 {
            self.colors.0
        } else {
            self.colors.1
        }
    }
}

/// The integral from 0 to `x` of the indicator of odd unit intervals.
#[inline]
fn odd_integral(x: f32) -> f32 {
    let h = x * 0.5;
    let f = floor_fast(h);
    f + 2.0 * (h - f - 0.5).max(0.0)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec2;

    fn checker(filter: Filter) -> Checker {
        Checker {
            transform: None,
            mapping: crate::mapping::Mapping::Rectangular.into(),
            squares: (4.0, 4.0),
            colors: (Rgb::grey(1.0), Rgb::grey(0.0)),
            filter,
        }
    }

    /// The box average by brute force: a 400 x 400 grid of point samples over the box.
    fn brute(c: &Checker, tc: &TexCoord) -> f32 {
        let hu = 0.5 * (tc.duvdx.x.abs() + tc.duvdy.x.abs());
        let hv = 0.5 * (tc.duvdx.y.abs() + tc.duvdy.y.abs());
        let n = 400;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let u = tc.uv.x - hu + 2.0 * hu * (i as f32 + 0.5) / n as f32;
                let v = tc.uv.y - hv + 2.0 * hv * (j as f32 + 0.5) / n as f32;
                sum += c.point(Vec2::new(u, v)).0;
            }
        }
        sum / (n * n) as f32
    }

    #[test]
    fn closed_form_box_filter_matches_brute_force() {
        let c = checker(Filter::Ewa);
        for (uv, dx, dy) in [
            (
                Vec2::new(0.3, 0.41),
                Vec2::new(0.1, 0.0),
                Vec2::new(0.0, 0.03),
            ),
            (
                Vec2::new(0.25, 0.25),
                Vec2::new(0.2, 0.05),
                Vec2::new(-0.04, 0.3),
            ),
            (
                Vec2::new(-1.37, 2.6),
                Vec2::new(0.9, 0.0),
                Vec2::new(0.0, 0.9),
            ),
            (
                Vec2::new(0.6, 0.1),
                Vec2::new(0.01, 0.0),
                Vec2::new(0.0, 0.5),
            ),
        ] {
            let tc = TexCoord {
                uv,
                duvdx: dx,
                duvdy: dy,
            };
            let exact = c.box_filtered(&tc).0;
            let b = brute(&c, &tc);
            assert!((exact - b).abs() < 0.01, "{uv} {dx} {dy}: {exact} vs {b}");
        }
    }

    #[test]
    fn closed_form_is_grey_far_away_and_exact_inside_a_square() {
        let c = checker(Filter::Trilinear);
        let far = TexCoord {
            uv: Vec2::new(0.3, 0.7),
            duvdx: Vec2::new(1e3, 0.0),
            duvdy: Vec2::new(0.0, 1e3),
        };
        assert!((c.box_filtered(&far).0 - 0.5).abs() < 1e-3);
        let inside = TexCoord {
            uv: Vec2::new(0.1, 0.1),
            duvdx: Vec2::new(0.01, 0.0),
            duvdy: Vec2::new(0.0, 0.01),
        };
        assert_eq!(c.box_filtered(&inside), c.point(inside.uv));
        // Point-sampling filters ignore the footprint.
        assert_eq!(checker(Filter::Nearest).eval_tc(&far), c.point(far.uv));
    }

    impl Checker {
        fn eval_tc(&self, tc: &TexCoord) -> Rgb {
            if self.filter.needs_footprint() {
                self.box_filtered(tc)
            } else {
                self.point(tc.uv)
            }
        }
    }
}
