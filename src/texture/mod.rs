//! Textures: the lecture's `Texture::get_color`, as one enum with one `match`.
//!
//! A texture is evaluated from a [`TextureContext`] (the object-space hit point, its screen-space
//! offsets and any coordinates the shape carries); image and procedural textures run their
//! mapping first, then look up or compute the colour.

mod debug;
mod explain;
pub mod footprint;
mod formula;
mod image;
mod lanes;
mod mip;
mod procedural;
mod summed;

pub use debug::{
    AGREE_COLOUR, Compare, DEFAULT_TEXELS, MAX_COMPARE_TOLERANCE, View, difference_color,
    mip_level_color,
};
pub use explain::{explain_lookup, explain_wrap};
pub use formula::{FormulaColour, FormulaTexture, mark};
pub(crate) use image::tiled_index;
pub use image::{
    ImageData, ImageRequest, MAX_IMAGE_BYTES, MAX_IMAGE_DIMENSION, TILE, Texels, approx_bytes,
    load_alpha, load_image, load_opened, save_png, save_png_checked,
};
pub use mip::{DEFAULT_MAX_ANISOTROPY, EWA_FOOTPRINT_SCALE, MAX_ANISOTROPY_LIMIT, MipPyramid};
pub use procedural::{Checker, uv_grid_image};
pub use summed::{
    MAX_HULL_TEXELS, MAX_TABLE_TEXELS, MAX_WIDE_TEXEL, MIN_WIDE_BITS, SummedArea, TablePlan,
};

use crate::mapping::{AnyMapping, Mapping, TexCoord, UvAffine};
use crate::math::{Rgb, Vec2, Vec3A};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Everything a texture may need about a hit.
#[derive(Clone, Copy, Debug)]
pub struct TextureContext {
    /// Hit point in the generic object's space (the lecture's `local_hit_point`).
    pub p: Vec3A,
    /// Object-space offset of the hit to the neighbouring pixel's on the right (zero if unknown).
    pub dpdx: Vec3A,
    /// Object-space offset of the hit to the neighbouring pixel's below (zero if unknown).
    pub dpdy: Vec3A,
    /// (u, v) carried by the shape (mesh vertices), with the triangle's dp/du and dp/dv.
    pub shape_uv: Option<(Vec2, Option<(Vec3A, Vec3A)>)>,
    /// The shape's natural parameterisation, used by [`Mapping::Uv`] when it carries none.
    pub natural: Mapping,
}

impl TextureContext {
    /// Coordinates and derivatives under `mapping` (NaN (u, v) where a formula is not finite).
    #[must_use]
    #[inline]
    pub fn tex_coord(&self, mapping: &AnyMapping) -> TexCoord {
        mapping.map_with_differentials(self.p, self.dpdx, self.dpdy, self.shape_uv, self.natural)
    }

    /// A texture's coordinates: `mapping`'s, then its (u, v) transform if it has one (not
    /// applied to a formula's NaN (u, v), which stays NaN and marks the pixel).
    #[must_use]
    #[inline]
    pub fn transformed_tex_coord(
        &self,
        mapping: &AnyMapping,
        transform: Option<&UvAffine>,
    ) -> TexCoord {
        transformed(self.tex_coord(mapping), transform)
    }
}

/// Coordinates `tc` as a mapping gave them after a texture's (u, v) transform, if it has one
/// (not applied to a formula's NaN (u, v), which stays NaN and marks the pixel).
#[must_use]
#[inline]
pub fn transformed(tc: TexCoord, transform: Option<&UvAffine>) -> TexCoord {
    match transform {
        Some(a) if tc.uv.is_finite() => a.apply(tc),
        _ => tc,
    }
}

/// How a texture becomes colour at a hit.
#[derive(Clone, Debug)]
pub enum Texture {
    /// The lecture's `ConstantColor`: the same colour everywhere.
    Constant(Rgb),
    /// The lecture's `ImageTexture`: an image read through a mapping.
    Image(ImageTexture),
    /// A procedural checkerboard in (u, v).
    Checker(Checker),
    /// A student's colour formulas over (u, v) and the hit point.
    Formula(FormulaTexture),
}

impl Texture {
    /// The colour at a hit (linear RGB).
    #[must_use]
    #[inline]
    pub fn eval(&self, ctx: &TextureContext) -> Rgb {
        match self {
            Self::Constant(c) => *c,
            Self::Image(t) => t.eval(ctx),
            Self::Checker(c) => c.eval(ctx),
            Self::Formula(f) => f.eval(ctx),
        }
    }

    /// Whether evaluating needs the hit's screen-space offsets (a filter with a footprint).
    #[must_use]
    pub fn needs_differentials(&self) -> bool {
        match self {
            Self::Constant(_) | Self::Formula(_) => false,
            Self::Checker(c) => c.filter.needs_footprint(),
            Self::Image(t) => t.filter.needs_footprint(),
        }
    }

    /// Texture coordinates of a hit under the texture's mapping and (u, v) transform; `None`
    /// for a constant.
    #[must_use]
    pub fn tex_coord(&self, ctx: &TextureContext) -> Option<TexCoord> {
        match self {
            Self::Constant(_) => None,
            Self::Image(t) => Some(t.tex_coord(ctx)),
            Self::Checker(c) => Some(c.tex_coord(ctx)),
            Self::Formula(f) => Some(f.tex_coord(ctx)),
        }
    }

    /// The colour at texture coordinates already mapped and transformed (as
    /// [`Texture::tex_coord`] gives them), through the texture's filter and wrap; `p` is the
    /// object-space hit point (a formula texture may read it). NaN (u, v) (a formula mapping
    /// that is not finite there) gives the [`mark`].
    #[must_use]
    pub fn eval_tex_coord(&self, tc: TexCoord, p: Vec3A) -> Rgb {
        if !tc.uv.is_finite() && !matches!(self, Self::Constant(_)) {
            return mark();
        }
        match self {
            Self::Constant(c) => *c,
            Self::Formula(f) => {
                let p = p.as_dvec3();
                f.at(tc.uv, [p.x, p.y, p.z])
            }
            Self::Image(t) => t.sample(tc) * t.scale,
            Self::Checker(c) => {
                if c.filter.needs_footprint() {
                    c.box_filtered(&tc)
                } else {
                    c.point(tc.uv)
                }
            }
        }
    }

    /// The (u, v) transform, if the texture has one that is not the identity.
    #[must_use]
    pub const fn uv_affine(&self) -> Option<UvAffine> {
        match self {
            Self::Constant(_) => None,
            Self::Image(t) => t.transform,
            Self::Checker(c) => c.transform,
            Self::Formula(f) => f.transform,
        }
    }

    /// The mapping, for textures that have one.
    #[must_use]
    pub const fn mapping(&self) -> Option<&AnyMapping> {
        match self {
            Self::Constant(_) => None,
            Self::Image(t) => Some(&t.mapping),
            Self::Checker(c) => Some(&c.mapping),
            Self::Formula(f) => Some(&f.mapping),
        }
    }

    /// How many hits a formula (mapping or colour) in this texture gave NaN or an infinity
    /// for (each such pixel is [`mark`]ed).
    #[must_use]
    pub fn non_finite_count(&self) -> u64 {
        let mapping = match self.mapping() {
            Some(AnyMapping::Formula(f)) => f.non_finite_count(),
            _ => 0,
        };
        let colour = match self {
            Self::Formula(f) => f.colour.non_finite_count(),
            _ => 0,
        };
        mapping + colour
    }
}

/// Which number a texture gives where a material wants one (a coefficient such as `ks`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[derive(Serialize, Deserialize)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
pub enum Channel {
    /// Rec. 709 luminance of the linear colour.
    #[default]
    #[strum(message = "Rec. 709 luminance of the linear colour.")]
    Luminance,
    /// The red channel.
    #[strum(message = "The red channel.")]
    Red,
    /// The green channel.
    #[strum(message = "The green channel.")]
    Green,
    /// The blue channel.
    #[strum(message = "The blue channel.")]
    Blue,
    /// The image file's alpha channel (an `Image` texture only; for clip maps).
    #[strum(message = "The image file's alpha (transparency) channel, for clip maps.")]
    Alpha,
}

impl crate::names::Named for Channel {
    const WHAT: &'static str = "channel";
}

impl Channel {
    /// The number this channel reads from a linear colour. A grey's luminance is its grey
    /// exactly (the weighted sum could round it), so `Constant((v, v, v))` means `v`.
    #[must_use]
    #[inline]
    pub fn of(self, c: Rgb) -> f32 {
        match self {
            Self::Luminance if c.0 == c.1 && c.1 == c.2 => c.0,
            Self::Luminance => c.luminance(),
            // An alpha texture holds alpha in every channel.
            Self::Red | Self::Alpha => c.0,
            Self::Green => c.1,
            Self::Blue => c.2,
        }
    }
}

/// Which texel the nearest lookup picks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[derive(Serialize, Deserialize)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum Lookup {
    /// The lecture's `column = (int)((hres - 1) u)`: stretches the image by hres / (hres - 1) and
    /// reaches the last column only at u == 1 exactly. What the book renders.
    #[strum(
        message = "The lecture's column = (int)((hres - 1) u): stretches the image by hres / (hres - 1)."
    )]
    Lecture,
    /// Texel-centred: `column = min(floor(u hres), hres - 1)`; every texel covers an equal
    /// share of [0, 1].
    #[default]
    #[strum(message = "column = min(floor(u hres), hres - 1): every texel covers an equal share.")]
    Centred,
}

impl crate::names::Named for Lookup {
    const WHAT: &'static str = "lookup";
}

impl Lookup {
    /// The texel index along an axis of `n` texels for a coordinate already wrapped to [0, 1]
    /// (closed: t == 1 is the last texel under both lookups). Generic over [`Real`] so that the
    /// renderer (f32) and `texplore map` (f64) run one formula.
    #[must_use]
    #[inline]
    pub fn index<T: Real>(self, t: T, n: u32) -> u32 {
        let last = n - 1;
        let i = match self {
            Self::Lecture => (T::from_u32(last) * t).trunc_u32(), // as the C++ (int) cast
            Self::Centred => (t * T::from_u32(n)).trunc_u32(),
        };
        i.min(last)
    }
}

/// What happens outside [0, 1].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[derive(Serialize, Deserialize)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum Wrap {
    /// Tile the texture.
    #[default]
    #[strum(message = "Tiles the texture outside [0, 1].")]
    Repeat,
    /// Extend the edge texels.
    #[strum(message = "Extends the edge texels outside [0, 1].")]
    Clamp,
    /// Tile with every other copy mirrored, so edges meet seamlessly.
    #[strum(message = "Tiles with every other copy mirrored, so the edges meet seamlessly.")]
    Mirror,
    /// Black outside the texture.
    #[strum(message = "Black outside [0, 1], to show where the mapping leaves the texture.")]
    Black,
}

impl crate::names::Named for Wrap {
    const WHAT: &'static str = "wrap mode";
}

impl Wrap {
    /// A continuous coordinate brought into [0, 1], or `None` outside under [`Wrap::Black`].
    ///
    /// The square is closed: t in [0, 1], both ends included, is returned as it is under every
    /// mode, so u == 1 reaches the last texel (the lecture's far edge); only coordinates
    /// outside are wrapped. (The periodic mappings never return u == 1: their seam is u = 0.)
    #[must_use]
    #[inline]
    pub fn coord<T: Real>(self, t: T) -> Option<T> {
        if t >= T::ZERO && t <= T::ONE {
            return Some(t);
        }
        if t.is_nan() {
            return Some(T::ZERO);
        }
        match self {
            Self::Repeat => {
                let f = t - t.floor();
                Some(if f < T::ONE { f } else { T::ZERO }) // -1e-9 - floor rounds up to 1.0
            }
            Self::Clamp => Some(if t < T::ZERO { T::ZERO } else { T::ONE }),
            Self::Mirror => {
                let f = t.rem_euclid(T::TWO);
                Some(if f > T::ONE { T::TWO - f } else { f })
            }
            Self::Black => None,
        }
    }

    /// `t` moved by whole periods of the wrap into a small range that reads the same texels,
    /// so every filter's texel arithmetic stays in range whatever the size of (u, v).
    ///
    /// [0, 1] is returned as it is. Outside, `Repeat` takes the fractional part and `Mirror`
    /// the remainder modulo 2; both are exact in floating point (an f32 beyond 2^23 is a whole
    /// number, so its place in the tile is exactly 0). `Clamp` and `Black` keep t within
    /// [`Wrap::REDUCED_MARGIN`] of the square: further out they read the edge texels, or
    /// nothing, either way, even for the widest footprint a filter is given
    /// ([`crate::mapping::MAX_FOOTPRINT`]). NaN is returned as it is (the filters' fallback
    /// handles it).
    #[must_use]
    #[inline]
    pub fn reduce(self, t: f32) -> f32 {
        if (0.0..=1.0).contains(&t) || t.is_nan() {
            return t;
        }
        match self {
            Self::Repeat => {
                // `floor_fast` is `floor` bit for bit here (only -0.0 differs, and it returned
                // above), without a libm call on x86-64's baseline.
                let f = t - crate::math::floor_fast(t);
                if f.is_finite() { f } else { 0.0 }
            }
            Self::Mirror => {
                let f = t.rem_euclid(2.0);
                if f.is_finite() { f } else { 0.0 }
            }
            Self::Clamp | Self::Black => t.clamp(-Self::REDUCED_MARGIN, 1.0 + Self::REDUCED_MARGIN),
        }
    }

    /// How far outside [0, 1] [`Wrap::reduce`] leaves a clamped or black coordinate: more than
    /// a footprint can reach ([`crate::mapping::MAX_FOOTPRINT`] on each of two edges, widened
    /// by EWA's scale).
    pub const REDUCED_MARGIN: f32 = 8.0;

    /// (u, v) reduced along each axis by its own wrap ([`Wrap::reduce`]).
    #[must_use]
    #[inline]
    pub fn reduce_uv(wu: Self, wv: Self, uv: Vec2) -> Vec2 {
        Vec2::new(wu.reduce(uv.x), wv.reduce(uv.y))
    }

    /// An integer texel index brought into [0, n), or `None` outside under [`Wrap::Black`].
    ///
    /// Wrap-free near the image: an index within one period of [0, n) (every index a filter
    /// reads after [`Wrap::reduce`], unless the image is narrower than its kernel) is wrapped
    /// by one comparison and one addition or subtraction; only indices further out take an
    /// integer remainder.
    #[must_use]
    #[inline]
    pub fn index(self, i: i64, n: u32) -> Option<u32> {
        let n64 = i64::from(n);
        match self {
            Self::Repeat => Some(wrap_near(i, n64) as u32),
            Self::Clamp => Some(i.clamp(0, n64 - 1) as u32),
            Self::Mirror => {
                let m = wrap_near(i, 2 * n64);
                Some(if m >= n64 { 2 * n64 - 1 - m } else { m } as u32)
            }
            Self::Black => (0..n64).contains(&i).then_some(i as u32),
        }
    }
}

/// `i.rem_euclid(n)` (n > 0), without a division for i in [-n, 2n).
#[inline(always)]
const fn wrap_near(i: i64, n: i64) -> i64 {
    if i < 0 {
        if i >= -n { i + n } else { i.rem_euclid(n) }
    } else if i < n {
        i
    } else if i < 2 * n {
        i - n
    } else {
        i.rem_euclid(n)
    }
}

/// How texels are combined into one colour.
///
/// On the procedural checker, which has no texels, `Nearest`, `Bilinear` and `Bicubic` all
/// point-sample, and `Trilinear`, `Ewa` and `Footprint` use the closed-form box filter of the
/// checker over the footprint's bounding box (pbrt's analytically filtered checkerboard).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[derive(Serialize, Deserialize)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum Filter {
    /// One texel, chosen by the [`Lookup`].
    #[default]
    #[strum(message = "One texel per sample: blocky when magnified, aliases when minified.")]
    Nearest,
    /// The four nearest texel centres, weighted by distance.
    #[strum(message = "Blends the four nearest texels: smooth up close, still aliases far away.")]
    Bilinear,
    /// Catmull-Rom bicubic over the 4 x 4 nearest texel centres (sharper magnification).
    #[strum(message = "Catmull-Rom over 4 x 4 texels: sharper than bilinear up close.")]
    Bicubic,
    /// Trilinear mip-mapping: bilinear in the two mip levels around the pixel's footprint size,
    /// blended (isotropic: blurs footprints that are long and thin).
    #[strum(
        message = "Mip-mapping: averages as many texels as the pixel covers, but isotropically (blurs at grazing angles)."
    )]
    Trilinear,
    /// Elliptically weighted average over the mip pyramid: follows long, thin footprints (a
    /// plane seen at a grazing angle) up to the texture's `max_anisotropy`.
    #[strum(
        message = "Elliptical weighted average: follows the pixel's stretched footprint; sharp and alias-free."
    )]
    Ewa,
    /// The mean of the bilinear texture over the pixel's footprint parallelogram (from a
    /// summed-area table, `footprint.rs`): one sample per pixel converges to the box-filtered
    /// image.
    #[strum(
        message = "Integrates the texture over the pixel's footprint: one sample gives the supersampled pixel, no blur."
    )]
    Footprint,
}

impl crate::names::Named for Filter {
    const WHAT: &'static str = "filter";
}

impl Filter {
    /// Whether this filter needs the pixel's footprint in texture space (ray differentials).
    #[must_use]
    pub const fn needs_footprint(self) -> bool {
        matches!(self, Self::Trilinear | Self::Ewa | Self::Footprint)
    }

    /// Whether this filter reads a mip pyramid (built only then).
    #[must_use]
    pub const fn needs_mip(self) -> bool {
        matches!(self, Self::Trilinear | Self::Ewa | Self::Footprint)
    }
}

/// An image read through a mapping with a filter and wrap mode.
#[derive(Clone, Debug)]
pub struct ImageTexture {
    /// The decoded image, shared (through the asset cache) with every texture that reads the
    /// same file with the same `srgb` setting.
    pub image: Arc<ImageData>,
    /// How hit points become (u, v).
    pub mapping: AnyMapping,
    /// How texels are combined.
    pub filter: Filter,
    /// Which texel the nearest filter picks.
    pub lookup: Lookup,
    /// What happens outside [0, 1].
    pub wrap: Wrap,
    /// A multiplier on the texel values (brightens or dims an HDR image).
    pub scale: f32,
    /// The mip pyramid, present when the filter needs one ([`Filter::needs_mip`]); without it
    /// mip filters fall back to bilinear.
    pub mip: Option<Arc<MipPyramid>>,
    /// The longest footprint EWA follows, as a ratio of major to minor axis.
    pub max_anisotropy: f32,
    /// The (u, v) transform after the mapping; `None` for none (costs nothing).
    pub transform: Option<UvAffine>,
}

impl ImageTexture {
    /// The wrap modes along u and v: periodic mappings wrap u across their seam, the spherical
    /// map clamps v at its poles, whatever the texture's own mode.
    #[must_use]
    #[inline]
    ///
    /// A texture with a (u, v) transform uses its own wrap mode on both axes: tiled or rotated,
    /// its coordinates no longer follow the mapping's seam and poles.
    pub fn wraps(&self) -> (Wrap, Wrap) {
        match (&self.transform, &self.mapping) {
            (None, AnyMapping::Builtin(m)) => Wrap::for_mapping(*m, self.wrap),
            _ => (self.wrap, self.wrap),
        }
    }

    /// Texture coordinates of a hit: the mapping's, then the (u, v) transform if any.
    #[must_use]
    #[inline]
    pub fn tex_coord(&self, ctx: &TextureContext) -> TexCoord {
        ctx.transformed_tex_coord(&self.mapping, self.transform.as_ref())
    }

    /// The colour at a hit; the [`mark`] where a formula mapping is not finite.
    #[must_use]
    #[inline(always)]
    pub fn eval(&self, ctx: &TextureContext) -> Rgb {
        self.eval_mapped(ctx.tex_coord(&self.mapping))
    }

    /// The colour at coordinates `tc` as the mapping gave them, before the (u, v) transform
    /// (which is applied here); the [`mark`] where they are not finite.
    #[must_use]
    #[inline(always)]
    pub fn eval_mapped(&self, tc: TexCoord) -> Rgb {
        let tc = match &self.transform {
            Some(a) if tc.uv.is_finite() => a.apply(tc),
            _ => tc,
        };
        if tc.uv.is_finite() {
            self.sample(tc) * self.scale
        } else {
            mark()
        }
    }

    /// The filtered colour at texture coordinates (before `scale`).
    #[must_use]
    #[inline(always)]
    pub fn sample(&self, tc: TexCoord) -> Rgb {
        let (wu, wv) = self.wraps();
        match (self.filter, &self.mip) {
            (Filter::Nearest, _) => self.image.nearest(tc.uv, self.lookup, wu, wv),
            (Filter::Bilinear, _) | (Filter::Trilinear | Filter::Ewa, None) => {
                self.image.bilinear(tc.uv, wu, wv)
            }
            (Filter::Bicubic, _) => self.image.bicubic(tc.uv, wu, wv),
            (Filter::Trilinear, Some(m)) => m.trilinear(tc.uv, tc.duvdx, tc.duvdy, wu, wv),
            (Filter::Ewa, Some(m)) => m.ewa(tc.uv, tc.duvdx, tc.duvdy, self.max_anisotropy, wu, wv),
            (Filter::Footprint, m) => footprint::footprint(
                m.as_deref(),
                &self.image,
                tc.uv,
                tc.duvdx,
                tc.duvdy,
                wu,
                wv,
                self.max_anisotropy,
            ),
        }
    }

    /// The continuous mip level the footprint of `tc` selects (0 at full resolution or when
    /// magnified; negative values say how much the texture is magnified).
    #[must_use]
    pub fn footprint_level(&self, tc: &TexCoord) -> f32 {
        let size = Vec2::new(self.image.width() as f32, self.image.height() as f32);
        let width = (tc.duvdx * size).length().max((tc.duvdy * size).length());
        if width > 0.0 && width.is_finite() {
            width.log2()
        } else {
            -8.0
        }
    }
}

impl Wrap {
    /// The wrap modes along u and v of a texture with wrap mode `wrap` under `mapping`: periodic
    /// mappings wrap u across their seam, the spherical map clamps v at its poles.
    #[must_use]
    #[inline]
    pub const fn for_mapping(mapping: Mapping, wrap: Self) -> (Self, Self) {
        let wu = if mapping.u_is_periodic() {
            Self::Repeat
        } else {
            wrap
        };
        let wv = if mapping.v_clamps() {
            Self::Clamp
        } else {
            wrap
        };
        (wu, wv)
    }
}

/// The floating-point types the wrap and lookup formulas run in: `f32` in the renderer, `f64` in
/// `texplore map`, which shows the lecture's arithmetic without f32 rounding. One formula for
/// both ([`Wrap::coord`], [`Lookup::index`]), monomorphised, so the renderer pays nothing.
pub trait Real:
    Copy + PartialOrd + std::ops::Sub<Output = Self> + std::ops::Mul<Output = Self>
{
    const ZERO: Self;
    const ONE: Self;
    const TWO: Self;
    /// The largest integer not above `self`.
    #[must_use]
    fn floor(self) -> Self;
    /// The least non-negative remainder of `self` divided by `m`.
    #[must_use]
    fn rem_euclid(self, m: Self) -> Self;
    /// Whether `self` is NaN.
    fn is_nan(self) -> bool;
    /// `n` as this type (rounded to nearest, as `as`).
    fn from_u32(n: u32) -> Self;
    /// Truncated towards zero and saturated to `u32` (0 for NaN): the C++ `(int)` cast on the
    /// range lookups use.
    fn trunc_u32(self) -> u32;
    /// As `f64`, exactly (for printing).
    fn to_f64(self) -> f64;
}

macro_rules! impl_real {
    ($t:ty) => {
        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const TWO: Self = 2.0;
            #[inline]
            fn floor(self) -> Self {
                <$t>::floor(self)
            }
            #[inline]
            fn rem_euclid(self, m: Self) -> Self {
                <$t>::rem_euclid(self, m)
            }
            #[inline]
            fn is_nan(self) -> bool {
                <$t>::is_nan(self)
            }
            #[inline]
            fn from_u32(n: u32) -> Self {
                n as $t
            }
            #[inline]
            fn trunc_u32(self) -> u32 {
                self as u32
            }
            #[inline]
            fn to_f64(self) -> f64 {
                f64::from(self)
            }
        }
    };
}
impl_real!(f32);
impl_real!(f64);

#[cfg(test)]
mod fetch_tests;
#[cfg(test)]
mod tests;
