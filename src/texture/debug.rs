//! Debug views: what the texture stage did at each pixel, rendered as an image any viewer can
//! show: (u, v) as colour, the mip level the footprint selects, the texel grid, the seams, and
//! the difference between the texture's mapping (a student's formula) and a built-in one.

use super::{Texture, TextureContext};
use crate::mapping::formula::compare::difference;
use crate::mapping::{Mapping, TexCoord};
use crate::math::{Rgb, srgb_to_linear};
use serde::{Deserialize, Serialize};

/// What a render shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[derive(Serialize, Deserialize)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum View {
    /// The lit, textured image (the default): what a render shows unless a debug view is picked.
    #[default]
    #[strum(message = "The rendered image.")]
    Shaded,
    /// (u, v) as colour: red = u, green = v (after the wrap mode), so the PNG's 8-bit red and
    /// green values are u and v times 255. Untextured surfaces are dark grey.
    #[strum(message = "(u, v) as colour: red is u, green is v, after the wrap mode.")]
    Uv,
    /// The mip level the pixel's footprint selects, as a colour ramp: blue where the texture is
    /// magnified, then green (level 0), yellow, orange, red, magenta, white (level 5 and up).
    #[strum(
        message = "The mip level each pixel's footprint selects: blue magnified, then green, yellow, red, white for coarser levels."
    )]
    MipLevel,
    /// The shaded image with the texel grid drawn on it: the base texels up close, and far away
    /// the grid of the finest mip level whose texels span at least 4 pixels (lines in that
    /// level's colour from [`View::MipLevel`]).
    #[strum(
        message = "The image with the texel grid drawn on it (the base texels, or a mip level's far away)."
    )]
    TexelGrid,
    /// The shaded image with the mapping's seams: magenta where u wraps on a closed surface
    /// (the cylindrical and spherical seam), yellow at the spherical map's poles, cyan on the
    /// edges of the texture's tiles.
    #[strum(
        message = "The image with the mapping's seams: magenta where u wraps, yellow at the poles, cyan at tile edges."
    )]
    Seams,
    /// The texture's mapping (a student's formula) against the built-in mapping of
    /// `render.compare`: a heat map of |du| (red) and |dv| (green), dark blue where both are
    /// within the tolerance, brighter the larger the difference (on a log scale from the
    /// tolerance to half the texture), magenta where the formula is NaN or infinite.
    #[strum(
        message = "The texture's mapping against a built-in one: red |du|, green |dv|, dark blue where they agree."
    )]
    Difference,
}

/// What [`View::Difference`] compares the texture's mapping with, and how closely.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Compare {
    /// The built-in mapping; default `Spherical`.
    pub with: Mapping,
    /// How far apart (u, v) may be and still agree, in texels of the texture's image (of a
    /// 1024 x 1024 image for a texture without one); default 1.
    pub tolerance: f32,
}

impl Default for Compare {
    fn default() -> Self {
        Self {
            with: Mapping::Spherical,
            tolerance: 1.0,
        }
    }
}

/// The largest [`Compare::tolerance`], in texels.
pub const MAX_COMPARE_TOLERANCE: f32 = 1e6;

/// The texel size of a texture without an image, for [`Compare::tolerance`].
pub const DEFAULT_TEXELS: u32 = 1024;

/// The [`View::Difference`] colour of |du| and |dv| (in (u, v)) against the tolerance `tol`
/// (in (u, v)): dark blue where both are within it; else red for u and green for v, each
/// from 0.25 just above the tolerance to 1 at half the texture, on a log scale.
#[must_use]
pub fn difference_color(d: glam::DVec2, tol: glam::DVec2) -> Rgb {
    if !(d.is_finite() && tol.is_finite()) {
        return super::mark();
    }
    let level = |x: f64, t: f64| {
        let t = t.max(1e-12);
        if x <= t {
            0.0
        } else if t >= 0.5 {
            1.0
        } else {
            let s = ((x / t).log2() / (0.5 / t).log2()).clamp(0.0, 1.0);
            (0.25 + 0.75 * s) as f32
        }
    };
    let (r, g) = (level(d.x, tol.x), level(d.y, tol.y));
    if r == 0.0 && g == 0.0 {
        AGREE_COLOUR
    } else {
        Rgb(r, g, 0.0)
    }
}

/// The [`View::Difference`] colour where the mappings agree.
pub const AGREE_COLOUR: Rgb = Rgb(0.0, 0.01, 0.12);

impl crate::names::Named for View {
    const WHAT: &'static str = "view";
}

impl View {
    /// Whether this view needs ray differentials (every view but the shaded one).
    #[must_use]
    pub const fn needs_footprint(self) -> bool {
        !matches!(self, Self::Shaded)
    }
}

/// Colours of mip levels -1 (magnified) to 5, linear.
const LEVEL_COLORS: [Rgb; 7] = [
    Rgb(0.02, 0.05, 0.6),
    Rgb(0.02, 0.5, 0.04),
    Rgb(0.8, 0.8, 0.02),
    Rgb(0.9, 0.3, 0.0),
    Rgb(0.8, 0.02, 0.02),
    Rgb(0.6, 0.02, 0.6),
    Rgb(0.9, 0.9, 0.9),
];

/// The [`View::MipLevel`] colour of a continuous level (clamped to -1 ..= 5, interpolated).
#[must_use]
pub fn mip_level_color(level: f32) -> Rgb {
    let x = if level.is_finite() {
        (level + 1.0).clamp(0.0, (LEVEL_COLORS.len() - 1) as f32)
    } else {
        0.0
    };
    let i = (x.floor() as usize).min(LEVEL_COLORS.len() - 2);
    let t = x - i as f32;
    LEVEL_COLORS[i] * (1.0 - t) + LEVEL_COLORS[i + 1] * t
}

/// How close (in pixels) a point is to the nearest integer of `x`, given the coordinate's
/// change per pixel `dx_dpixel`; infinite when the change is unknown.
fn pixels_to_integer(x: f32, dx_dpixel: f32) -> f32 {
    let d = (x - x.round()).abs();
    if dx_dpixel > 0.0 && dx_dpixel.is_finite() {
        d / dx_dpixel
    } else {
        f32::INFINITY
    }
}

/// Change of u and v per pixel along the worse screen axis (the footprint's bounding box).
fn per_pixel(tc: &TexCoord) -> (f32, f32) {
    (
        tc.duvdx.x.abs() + tc.duvdy.x.abs(),
        tc.duvdx.y.abs() + tc.duvdy.y.abs(),
    )
}

impl Texture {
    /// The texture's texel resolution for the debug views: the image's size, or the checker's
    /// squares over [0, 1]; `None` for a constant.
    fn resolution(&self) -> Option<(f32, f32)> {
        match self {
            // A formula texture has no texels either.
            Self::Constant(_) | Self::Formula(_) => None,
            Self::Image(t) => Some((t.image.width() as f32, t.image.height() as f32)),
            Self::Checker(c) => Some(c.squares),
        }
    }

    /// The size of one texel in (u, v): the image's, else of a [`DEFAULT_TEXELS`]-wide one.
    #[must_use]
    pub fn texel_size(&self) -> glam::DVec2 {
        let (w, h) = match self {
            Self::Image(t) => (t.image.width(), t.image.height()),
            _ => (DEFAULT_TEXELS, DEFAULT_TEXELS),
        };
        crate::mapping::formula::compare::one_texel(w, h)
    }

    /// The [`View::Difference`] colour at a hit: the texture's mapping against `compare.with`
    /// (both before the (u, v) transform); dark grey for a texture without a mapping.
    #[must_use]
    pub fn difference_view_color(&self, ctx: &TextureContext, compare: Compare) -> Rgb {
        let Some(mapping) = self.mapping() else {
            return Rgb::grey(0.02);
        };
        let got = ctx.tex_coord(mapping).uv.as_dvec2();
        let want = ctx.tex_coord(&compare.with.into()).uv.as_dvec2();
        let tol = self.texel_size() * f64::from(compare.tolerance);
        difference_color(difference(compare.with, got, want), tol)
    }

    /// The pixel colour of debug view `view` at a hit whose shaded radiance is `shaded`
    /// ([`View::Difference`] needs its comparison: [`Texture::difference_view_color`]).
    #[must_use]
    pub fn debug_color(&self, ctx: &TextureContext, view: View, shaded: Rgb) -> Rgb {
        if matches!(view, View::Shaded | View::Difference) {
            return shaded;
        }
        let (Some(mapping), Some((w, h))) = (self.mapping(), self.resolution()) else {
            return match view {
                View::Uv | View::MipLevel => Rgb::grey(0.02),
                View::Shaded | View::TexelGrid | View::Seams | View::Difference => shaded,
            };
        };
        let tc = ctx.tex_coord(mapping);
        let (du, dv) = per_pixel(&tc);
        let level = {
            let width = (tc.duvdx * glam::Vec2::new(w, h))
                .length()
                .max((tc.duvdy * glam::Vec2::new(w, h)).length());
            if width > 0.0 && width.is_finite() {
                width.log2()
            } else {
                -8.0
            }
        };
        match view {
            View::Shaded | View::Difference => shaded,
            View::Uv => {
                let (u, v) = match self {
                    Self::Image(t) => {
                        let (wu, wv) = t.wraps();
                        (wu.coord(tc.uv.x), wv.coord(tc.uv.y))
                    }
                    _ => (
                        Some(tc.uv.x - tc.uv.x.floor()),
                        Some(tc.uv.y - tc.uv.y.floor()),
                    ),
                };
                match (u, v) {
                    (Some(u), Some(v)) => Rgb(srgb_to_linear(u), srgb_to_linear(v), 0.0),
                    _ => Rgb::BLACK,
                }
            }
            View::MipLevel => mip_level_color(level),
            View::TexelGrid => {
                // The finest level whose texels are at least 4 pixels wide.
                let grid_level = (level + 2.0).ceil().max(0.0);
                let scale = grid_level.exp2();
                let (gw, gh) = ((w / scale).max(1.0), (h / scale).max(1.0));
                let near = pixels_to_integer(tc.uv.x * gw, du * gw)
                    .min(pixels_to_integer(tc.uv.y * gh, dv * gh));
                if near < 0.5 {
                    mip_level_color(grid_level) * 0.5
                } else {
                    shaded
                }
            }
            View::Seams => {
                let near_u = pixels_to_integer(tc.uv.x, du);
                let near_v = pixels_to_integer(tc.uv.y, dv);
                // Poles first: there every meridian, the seam included, meets.
                if mapping.v_clamps() && near_v < 1.0 {
                    Rgb(0.9, 0.8, 0.0)
                } else if mapping.u_is_periodic() && near_u < 1.0 {
                    Rgb(0.9, 0.0, 0.9)
                } else if near_u < 1.0 || near_v < 1.0 {
                    Rgb(0.0, 0.8, 0.9)
                } else {
                    shaded
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mapping::Mapping;
    use crate::math::Vec3A;
    use crate::texture::{Checker, Filter};

    fn ctx(p: Vec3A, dpdx: Vec3A, dpdy: Vec3A) -> TextureContext {
        TextureContext {
            p,
            dpdx,
            dpdy,
            shape_uv: None,
            natural: Mapping::Spherical,
        }
    }

    fn checker() -> Texture {
        Texture::Checker(Checker {
            mapping: Mapping::Spherical.into(),
            squares: (16.0, 8.0),
            colors: (Rgb::WHITE, Rgb::BLACK),
            filter: Filter::Nearest,
            transform: None,
        })
    }

    #[test]
    fn uv_view_encodes_u_and_v_as_display_values() {
        let t = checker();
        // (1, 0, 0) on the unit sphere: u = 0.25, v = 0.5.
        let c = t.debug_color(
            &ctx(Vec3A::X, Vec3A::ZERO, Vec3A::ZERO),
            View::Uv,
            Rgb::BLACK,
        );
        let enc = |x: f32| crate::math::linear_to_srgb(x);
        assert!(
            (enc(c.0) - 0.25).abs() < 1e-4 && (enc(c.1) - 0.5).abs() < 1e-4,
            "{c:?}"
        );
    }

    #[test]
    fn seams_view_marks_the_spherical_seam_and_poles_only() {
        let t = checker();
        let d = Vec3A::new(1e-3, 0.0, 0.0);
        let e = Vec3A::new(0.0, 1e-3, 0.0);
        let shaded = Rgb::grey(0.3);
        // On the seam (x = 0, z > 0): magenta.
        let c = t.debug_color(&ctx(Vec3A::new(0.0, 0.0, 1.0), d, e), View::Seams, shaded);
        assert_eq!(c, Rgb(0.9, 0.0, 0.9));
        // Near the north pole: yellow.
        let p = Vec3A::new(0.3, 1.0, 0.2).normalize() * 1.0;
        let near_pole = Vec3A::new(1e-4, 1.0, 1e-4).normalize();
        let c = t.debug_color(
            &ctx(near_pole, d, Vec3A::new(0.0, 0.0, 1e-3)),
            View::Seams,
            shaded,
        );
        assert_eq!(c, Rgb(0.9, 0.8, 0.0));
        // Elsewhere: the shaded colour.
        let c = t.debug_color(&ctx(p, d * 0.01, e * 0.01), View::Seams, shaded);
        assert_eq!(c, shaded);
    }

    #[test]
    fn difference_colours_name_the_coordinate_that_differs() {
        let tol = glam::DVec2::splat(1e-3);
        let c = |du: f64, dv: f64| difference_color(glam::DVec2::new(du, dv), tol);
        assert_eq!(c(1e-3, 0.0), AGREE_COLOUR);
        assert_eq!(c(0.5, 0.0), Rgb(1.0, 0.0, 0.0));
        assert_eq!(c(0.0, 0.7), Rgb(0.0, 1.0, 0.0));
        let just = c(0.0, 1.1e-3);
        assert!(just.0 == 0.0 && (0.25..0.3).contains(&just.1), "{just:?}");
        assert!(
            c(0.01, 0.0).0 < c(0.1, 0.0).0,
            "brighter with the difference"
        );
        assert_eq!(c(f64::NAN, 0.0), crate::texture::mark());
    }

    #[test]
    fn mip_colours_follow_the_ramp() {
        assert_eq!(mip_level_color(-5.0), LEVEL_COLORS[0]);
        assert_eq!(mip_level_color(0.0), LEVEL_COLORS[1]);
        assert_eq!(mip_level_color(50.0), LEVEL_COLORS[6]);
        assert!(mip_level_color(f32::NAN).is_finite());
        let mid = mip_level_color(0.5);
        assert!((mid.0 - 0.41).abs() < 1e-3);
    }
}
