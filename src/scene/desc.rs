//! Presets: the serde description of a scene, as written in `presets/*.ron`.
//!
//! A preset states only what its scene needs; `#[serde(default)]` fills the rest. Unknown fields
//! are errors (a typo must not silently fall back to a default). Colours are linear RGB.

use crate::geometry::{Shading, Shape};
use crate::mapping::{Mapping, UvTransform};
use crate::math::{Rgb, Vec3};
use crate::sampler::{PixelFilter, PixelSampler};
use crate::texture::{Channel, DEFAULT_MAX_ANISOTROPY, Filter, Lookup, View, Wrap};
use serde::{Deserialize, Serialize};

/// The preset format version this build reads and writes.
pub const PRESET_VERSION: u32 = 1;

/// A whole scene: camera, lights, objects and render settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDesc {
    /// Preset format version ([`PRESET_VERSION`]).
    pub version: u32,
    /// One line saying what the scene shows.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// Where the eye is and what it sees; required (at least `eye`).
    pub camera: CameraDesc,
    /// Resolution, samples, seed, exposure; every field defaults (see [`RenderDesc`]).
    #[serde(default)]
    pub render: RenderDesc,
    /// Light from every direction, which lit materials scale by their `ka`; default white at
    /// `ls` 1.
    #[serde(default)]
    pub ambient: AmbientDesc,
    /// Directional and point lights, each added to the ambient term; default none.
    #[serde(default)]
    pub lights: Vec<LightDesc>,
    /// Required, but may be empty (the render is then all `render.background`). Each ray takes
    /// the nearest hit, so order matters only where two surfaces coincide (the earlier wins).
    pub objects: Vec<ObjectDesc>,
    /// Settings for `texplore snapshot`.
    #[serde(default)]
    pub snapshot: SnapshotDesc,
}

/// Camera placement and projection, in world space with y up. A preset writes
/// `camera: (eye: (0, 1, 4), look_at: (0, 0.5, 0), projection: Pinhole(fov: 50))`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Eye position in world units (y is up); required, and not equal to `look_at`.
    pub eye: Vec3,
    /// The point at the centre of the view, in world units; default the origin.
    #[serde(default)]
    pub look_at: Vec3,
    /// Which way is up on the film (default +y); need not be perpendicular to the view, must not
    /// be zero.
    #[serde(default = "default_up")]
    pub up: Vec3,
    /// Projection and its angles; default `Pinhole(fov: 45)`.
    #[serde(default)]
    pub projection: ProjectionDesc,
}

fn default_up() -> Vec3 {
    Vec3::Y
}

/// Camera projections. Angles in degrees.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ProjectionDesc {
    /// Perspective with a vertical field of view.
    Pinhole {
        /// Vertical field of view, degrees.
        fov: f32,
    },
    /// Equidistant fisheye with the full angle across the inscribed circle.
    Fisheye {
        /// Full field of view, degrees (360 sees everything).
        fov: f32,
    },
    /// Equirectangular panorama: x across the image is longitude, y is latitude.
    Spherical {
        /// Horizontal field of view, degrees (360 for all around).
        h_fov: f32,
        /// Vertical field of view, degrees (180 for pole to pole).
        v_fov: f32,
    },
    /// Parallel rays along the view direction, from the plane through the eye.
    Orthographic {
        /// Height of the view in world units (positive); the width follows the image's
        /// aspect ratio.
        height: f32,
    },
}

impl Default for ProjectionDesc {
    fn default() -> Self {
        ProjectionKind::Pinhole.default_desc()
    }
}

/// Image size, sampling, exposure and view. Every field has a default (written below), so a
/// preset lists only what it changes: `render: (width: 320, spp: 4)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderDesc {
    /// Image width in pixels, 1 to [`MAX_RESOLUTION`](super::MAX_RESOLUTION); default 640.
    pub width: u32,
    /// Image height in pixels, 1 to [`MAX_RESOLUTION`](super::MAX_RESOLUTION); default 480.
    pub height: u32,
    /// Samples per pixel, 1 to [`MAX_SPP`](super::MAX_SPP); default 16.
    pub spp: u32,
    /// Seed of every random number: the same seed gives the same image; default 0.
    pub seed: u32,
    /// Where samples go in a pixel; default `Jittered`.
    pub sampler: PixelSampler,
    /// Exposure in stops, -64 to 64 (multiplies radiance by 2^exposure before display); default 0.
    pub exposure: f32,
    /// Linear radiance of rays that hit nothing (not negative); default black.
    pub background: Rgb,
    /// How a pixel weighs its samples (the reconstruction filter); default `Box`.
    pub pixel_filter: PixelFilter,
    /// Adaptive sampling: after `spp` samples everywhere, more (up to `max_spp`) only where
    /// the image needs them; default `None` (off), on with `adaptive: Some((max_spp: 256))`.
    pub adaptive: Option<AdaptiveDesc>,
    /// What the render shows: the shaded image or a debug view; default `Shaded`.
    pub view: View,
    /// How many mirror bounces a ray may take (`Reflective` materials), 0 to
    /// [`MAX_REFLECTION_DEPTH`]; 0 shades a mirror as plain Phong; default 4.
    #[serde(skip_serializing_if = "is_default_depth")]
    pub reflection_depth: u32,
}

/// The default [`RenderDesc::reflection_depth`].
pub const DEFAULT_REFLECTION_DEPTH: u32 = 4;
/// The largest [`RenderDesc::reflection_depth`].
pub const MAX_REFLECTION_DEPTH: u32 = 64;

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_default_depth(d: &u32) -> bool {
    *d == DEFAULT_REFLECTION_DEPTH
}

impl Default for RenderDesc {
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            spp: 16,
            seed: 0,
            sampler: PixelSampler::Jittered,
            exposure: 0.0,
            background: Rgb::BLACK,
            pixel_filter: PixelFilter::Box,
            adaptive: None,
            view: View::Shaded,
            reflection_depth: DEFAULT_REFLECTION_DEPTH,
        }
    }
}

/// Adaptive sampling: after the first `render.spp` samples of every pixel, further passes
/// sample only pixels whose estimated error is above `threshold`, up to `max_spp` in all.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdaptiveDesc {
    /// Most samples a pixel may take, from `render.spp` to [`MAX_SPP`](super::MAX_SPP);
    /// required.
    pub max_spp: u32,
    /// Error tolerance in display units ((0, 1], sRGB-encoded luminance): a pixel keeps sampling
    /// while the standard error of its mean, or (after a single sample) its difference from a
    /// neighbour, exceeds this.
    #[serde(default = "default_threshold")]
    pub threshold: f32,
}

/// The default adaptive threshold: about 2.5 steps of 8-bit display colour.
pub const DEFAULT_ADAPTIVE_THRESHOLD: f32 = 0.01;

fn default_threshold() -> f32 {
    DEFAULT_ADAPTIVE_THRESHOLD
}

/// Settings `texplore snapshot` renders at (small and quick, but enough to see every feature).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SnapshotDesc {
    /// Width in pixels; default 320.
    pub width: u32,
    /// Height in pixels; default 240.
    pub height: u32,
    /// Samples per pixel; default 4.
    pub spp: u32,
}

impl Default for SnapshotDesc {
    fn default() -> Self {
        Self {
            width: 320,
            height: 240,
            spp: 4,
        }
    }
}

/// The ambient light: radiance `ls * color` from everywhere, scaled by each lit material's
/// `ka` (emissive materials ignore it).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AmbientDesc {
    /// Multiplier on `color` (finite, not negative); default 1.
    pub ls: f32,
    /// Linear RGB, `(r, g, b)`; default white `(1, 1, 1)`.
    pub color: Rgb,
}

impl Default for AmbientDesc {
    fn default() -> Self {
        Self {
            ls: 1.0,
            color: Rgb::WHITE,
        }
    }
}

/// A light source in `lights: [...]`. Its radiance `ls * color` reaches a surface undimmed
/// by distance, unless `shadows` is on and an object that casts shadows is in the way.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum LightDesc {
    /// Light from one direction (the sun).
    Directional {
        /// World-space direction from surfaces toward the light (need not be unit length, must not
        /// be zero).
        direction: Vec3,
        /// Multiplier on `color` (finite, not negative); default 1.
        #[serde(default = "one")]
        ls: f32,
        /// Linear RGB, `(r, g, b)`, not negative; default white.
        #[serde(default = "white")]
        color: Rgb,
        /// Whether objects cast shadows from it.
        #[serde(default = "yes")]
        shadows: bool,
    },
    /// Light from a point, without fall-off (the lecture's).
    Point {
        /// Position in world units.
        position: Vec3,
        /// Multiplier on `color` (finite, not negative); default 1.
        #[serde(default = "one")]
        ls: f32,
        /// Linear RGB, `(r, g, b)`, not negative; default white.
        #[serde(default = "white")]
        color: Rgb,
        /// Whether objects cast shadows from it.
        #[serde(default = "yes")]
        shadows: bool,
    },
}

fn one() -> f32 {
    1.0
}
fn white() -> Rgb {
    Rgb::WHITE
}
fn yes() -> bool {
    true
}

/// An object: a generic shape, where it is, and what it is made of.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDesc {
    /// A name for menus and messages; default empty, which names it by its shape (or mesh
    /// path) and index.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub name: String,
    /// The generic shape or a mesh file.
    pub shape: ShapeDesc,
    /// Scale, then rotate, then translate.
    #[serde(default)]
    pub transform: TransformDesc,
    /// How the surface shades; required.
    pub material: MaterialDesc,
    /// Whether it blocks shadow rays (default: yes, except emissive objects).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub casts_shadows: Option<bool>,
    /// A clip map: where the surface exists (1) or not (0), in between partly (a filtered
    /// edge); primary, mirrored and shadow rays all pass where it is below 1. Usually an
    /// image's alpha: `alpha: (texture: Image(path: "leaf.png", mapping: Rectangular),
    /// channel: Alpha)`; default none (solid everywhere).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        serialize_with = "bare_alpha",
        deserialize_with = "some_alpha"
    )]
    pub alpha: Option<ScalarDesc>,
    /// A bump map: a height texture that tilts the shading normal (the surface itself stays
    /// where it is): `bump: (height: Image(path: "bricks.png", mapping: Rectangular),
    /// scale: 0.02)`; default none.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        serialize_with = "bare_alpha",
        deserialize_with = "some_alpha"
    )]
    pub bump: Option<BumpDesc>,
    /// A normal map: an RGB texture of tangent-space normals that replaces the shading normal
    /// (read raw, whatever its `srgb` says): `normal: (map: Image(path: "bricks_normal.png",
    /// mapping: Rectangular), strength: 1)`; default none. An object has a bump map or a
    /// normal map, not both.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        serialize_with = "bare_alpha",
        deserialize_with = "some_alpha"
    )]
    pub normal: Option<NormalMapDesc>,
    /// A displacement map, meshes only: at load, every triangle is split into four `subdivide`
    /// times, then each vertex moves along its normal by the height texture there (the
    /// surface itself moves: silhouettes and shadows change): `displace: (height:
    /// Image(path: "gravel.png", mapping: Uv), scale: 0.05, subdivide: 3)`; default none.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        serialize_with = "bare_alpha",
        deserialize_with = "some_alpha"
    )]
    pub displace: Option<DisplaceDesc>,
}

/// A displacement map ([`ObjectDesc::displace`]), on a `Mesh` shape only (the generic shapes
/// are analytic; a bump map gives them the look). The mesh is subdivided, then every vertex
/// moves along its normal by `scale` times the height texture's luminance there (read at the
/// vertex's point, through the texture's own mapping, with no footprint), before the BVH is
/// built. At most [`MAX_DISPLACED_TRIANGLES`](crate::geometry::displace::MAX_DISPLACED_TRIANGLES)
/// triangles (4 M) after subdivision.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DisplaceDesc {
    /// The height field: its luminance, times `scale`, is how far a vertex moves (as a bump
    /// map's height).
    pub height: TextureDesc,
    /// How far a texture value of 1 moves the surface, in the mesh file's units (finite, at
    /// most 1e6 in size; negative pushes in); default 0.02.
    #[serde(default = "default_bump_scale")]
    pub scale: f32,
    /// How many times every triangle is split into four before moving the vertices (0 moves
    /// only the file's vertices); default 2.
    #[serde(default = "default_subdivide")]
    pub subdivide: u32,
}

/// The default [`DisplaceDesc::subdivide`].
pub const DEFAULT_SUBDIVIDE: u32 = 2;

fn default_subdivide() -> u32 {
    DEFAULT_SUBDIVIDE
}

/// A normal map ([`ObjectDesc::normal`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NormalMapDesc {
    /// The normals: red along +u, green along +v, blue out of the surface, 128 meaning 0 and
    /// 255 meaning 1 (so (128, 128, 255) is the unperturbed normal). Not a constant.
    pub map: TextureDesc,
    /// Multiplier on the tangential components (finite; 0 flattens, negative inverts);
    /// default 1.
    #[serde(default = "one")]
    pub strength: f32,
}

/// A bump map ([`ObjectDesc::bump`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BumpDesc {
    /// The height field: its luminance, times `scale`, is the height.
    pub height: TextureDesc,
    /// The height of a texture value of 1, in the object's own units (finite; negative
    /// engraves instead of embossing); default 0.02.
    #[serde(default = "default_bump_scale")]
    pub scale: f32,
}

fn default_bump_scale() -> f32 {
    0.02
}

/// Writes an optional field (`alpha`, `bump`, `normal`, `displace`) as its value itself, without RON's `Some(...)`,
/// as it is read.
#[allow(clippy::ref_option)] // serde's serialize_with passes a reference to the field
fn bare_alpha<S: serde::Serializer, T: Serialize>(a: &Option<T>, s: S) -> Result<S::Ok, S::Error> {
    match a {
        Some(a) => a.serialize(s),
        None => s.serialize_none(),
    }
}

/// Reads an optional field (`alpha`, `bump`, `normal`, `displace`) written as its value itself.
fn some_alpha<'de, D: serde::Deserializer<'de>, T: Deserialize<'de>>(
    d: D,
) -> Result<Option<T>, D::Error> {
    T::deserialize(d).map(Some)
}

/// Shapes: the lecture's generic objects, or a triangle mesh from a file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ShapeDesc {
    /// The unit sphere at the origin.
    Sphere,
    /// The cylinder x^2 + z^2 = 1 with y in [-1, 1]; `capped` closes it with two disks.
    Cylinder {
        /// Close the ends with disks at y = -1 and y = 1.
        #[serde(default)]
        capped: bool,
    },
    /// The infinite plane y = 0, normal +y.
    Plane,
    /// The generic rectangle (x, z) in [-1, 1]^2 in the plane y = 0, normal +y.
    Rectangle,
    /// The unit disk x^2 + z^2 <= 1 in the plane y = 0, normal +y.
    Disk,
    /// A triangle mesh from a PLY or OBJ file, in the file's coordinates. Instances of one file
    /// share the mesh and its BVH.
    Mesh {
        /// Path, relative to the preset file.
        path: String,
        /// Flat (one normal per triangle) or smooth (interpolated vertex normals).
        #[serde(default)]
        shading: Shading,
    },
}

impl ShapeDesc {
    /// The runtime shape of a generic object (`None` for a mesh, which needs loading).
    #[must_use]
    pub const fn generic(&self) -> Option<Shape> {
        Some(match *self {
            Self::Sphere => Shape::Sphere,
            Self::Cylinder { capped } => Shape::Cylinder { capped },
            Self::Plane => Shape::Plane,
            Self::Rectangle => Shape::Rectangle,
            Self::Disk => Shape::Disk,
            Self::Mesh { .. } => return None,
        })
    }
}

/// An instance transform: scale, then rotate (degrees about x, then y, then z), then translate.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TransformDesc {
    /// Where the object's origin goes, in world units; default `(0, 0, 0)`.
    pub translate: Vec3,
    /// Rotation in degrees about x, then y, then z; default `(0, 0, 0)`.
    pub rotate: Vec3,
    /// Scale along each axis of the object (negative mirrors; zero is refused); default
    /// `(1, 1, 1)`.
    pub scale: Vec3,
}

impl Default for TransformDesc {
    fn default() -> Self {
        Self {
            translate: Vec3::ZERO,
            rotate: Vec3::ZERO,
            scale: Vec3::ONE,
        }
    }
}

/// How a surface shades, given its textured colour `cd`. Coefficients are finite and not
/// negative. A lit material's radiance is the ambient term `ka cd L_ambient` plus, per light
/// of radiance `L` arriving along `wi`, `(kd cd / pi + ks cs (r . wo)^exp) L (n . wi)`.
///
/// Every coefficient (`ka`, `kd`, `ks`, `exp`, `ls`) is a [`ScalarDesc`] and every colour
/// besides `cd` and `ce` (`cs`) a [`ColorDesc`]: a plain number or colour, as before, or a
/// texture with its own mapping, filter and wrap (`ks: Image(path: "mask.png")`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum MaterialDesc {
    /// The lecture's `SV_Matte`: ambient + diffuse with a textured colour.
    Matte {
        /// Share of the ambient light reflected; default 0.25.
        #[serde(default = "default_ka")]
        ka: ScalarDesc,
        /// Share of direct light reflected diffusely; default 0.75.
        #[serde(default = "default_kd")]
        kd: ScalarDesc,
        /// The surface colour (linear reflectance, usually in [0, 1]); required.
        cd: TextureDesc,
    },
    /// Matte with a Phong highlight.
    Phong {
        /// Share of the ambient light reflected; default 0.25.
        #[serde(default = "default_ka")]
        ka: ScalarDesc,
        /// Share of direct light reflected diffusely; default 0.75.
        #[serde(default = "default_kd")]
        kd: ScalarDesc,
        /// The surface colour (linear reflectance, usually in [0, 1]); required.
        cd: TextureDesc,
        /// Strength of the highlight; default 0.25.
        #[serde(default = "default_ks")]
        ks: ScalarDesc,
        /// Colour of the highlight, linear RGB; default white (the light's own colour).
        #[serde(default = "white_param")]
        cs: ColorDesc,
        /// Phong exponent: larger is a smaller, sharper highlight; default 20.
        #[serde(default = "default_exp")]
        exp: ScalarDesc,
        /// Glow on the dark side (city lights at night): linear radiance added where direct
        /// light does not reach, fading in over the first 0.2 of the lights' summed `n . wi`
        /// past the terminator (and fully where every light is shadowed); default black (none).
        #[serde(default = "black_param", skip_serializing_if = "ColorDesc::is_black")]
        ce: ColorDesc,
    },
    /// The book's `Reflective`: Phong plus a perfect mirror, which adds `kr cr` times the
    /// radiance seen along the mirrored ray (traced up to `render.reflection_depth` bounces).
    Reflective {
        /// Share of the ambient light reflected; default 0.25.
        #[serde(default = "default_ka")]
        ka: ScalarDesc,
        /// Share of direct light reflected diffusely; default 0.75.
        #[serde(default = "default_kd")]
        kd: ScalarDesc,
        /// The surface colour (linear reflectance, usually in [0, 1]); required.
        cd: TextureDesc,
        /// Strength of the highlight; default 0.25.
        #[serde(default = "default_ks")]
        ks: ScalarDesc,
        /// Colour of the highlight, linear RGB; default white (the light's own colour).
        #[serde(default = "white_param")]
        cs: ColorDesc,
        /// Phong exponent: larger is a smaller, sharper highlight; default 20.
        #[serde(default = "default_exp")]
        exp: ScalarDesc,
        /// Share of the mirrored radiance reflected; default 0.75.
        #[serde(default = "default_kr")]
        kr: ScalarDesc,
        /// Colour of the mirror, linear RGB; default white.
        #[serde(default = "white_param")]
        cr: ColorDesc,
    },
    /// The lecture's `SV_Emissive`: glows with a textured colour, ignores lights.
    Emissive {
        /// Multiplier on the emitted colour (finite, not negative); default 1.
        #[serde(default = "one_param")]
        ls: ScalarDesc,
        /// The emitted colour as linear radiance (may exceed 1); required.
        ce: TextureDesc,
    },
}

/// A coefficient of a material: a plain number (`ks: 0.25`, a constant, costing nothing), or
/// a texture read as one number, by default its luminance (`ks: Image(path: "mask.png")`),
/// or one channel of it (`ks: (texture: Image(path: "mask.png"), channel: Red)`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "a number, a texture (Constant((r, g, b)), Image(path: \"...\"), Checker(), UvGrid()) or (texture: ..., channel: Red)"
)]
pub enum ScalarDesc {
    /// The same number everywhere.
    Value(f32),
    /// A texture's Rec. 709 luminance.
    Texture(#[serde(deserialize_with = "texture_in_param")] TextureDesc),
    /// One channel (or the luminance) of a texture.
    Channel(ChannelDesc),
}

/// A texture read as one number: [`ScalarDesc::Channel`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChannelDesc {
    /// The texture read.
    #[serde(deserialize_with = "texture_in_param")]
    pub texture: TextureDesc,
    /// Which channel of it; default `Luminance`.
    #[serde(default)]
    pub channel: Channel,
}

/// A colour of a material other than `cd` and `ce`: a plain linear colour (`cs: (1, 1, 1)`, a
/// constant costing nothing) or a texture (`cs: Image(path: "tint.png")`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "a colour (r, g, b) or a texture (Constant((r, g, b)), Image(path: \"...\"), Checker(), UvGrid())"
)]
pub enum ColorDesc {
    /// The same linear colour everywhere.
    Value(Rgb),
    /// A texture.
    Texture(#[serde(deserialize_with = "texture_in_param")] TextureDesc),
}

/// Reads a [`TextureDesc`] inside an untagged parameter. There serde buffers the value first
/// and RON hands it over as `{variant: body}` ("JSON enum semantics"); a texture written with
/// no fields (`UvGrid()`, `Checker`) then has a unit body, which a struct variant refuses. This
/// reads the variant's name and gives such a body the empty field list it stands for.
fn texture_in_param<'de, D: serde::Deserializer<'de>>(d: D) -> Result<TextureDesc, D::Error> {
    use serde::de::{self, IntoDeserializer, MapAccess, SeqAccess, Visitor};
    use std::fmt;

    /// `name()`: the texture with every field at its default.
    fn defaults<E: de::Error>(name: &str) -> Result<TextureDesc, E> {
        ron::from_str(&format!("{name}()")).map_err(|e| E::custom(format!("{name}: {}", e.code)))
    }

    /// The body of variant `name`.
    struct Body(String);

    impl<'de> de::DeserializeSeed<'de> for Body {
        type Value = TextureDesc;
        fn deserialize<D2: serde::Deserializer<'de>>(
            self,
            d: D2,
        ) -> Result<TextureDesc, D2::Error> {
            d.deserialize_any(self)
        }
    }

    /// Variant `name` with its body still to read, as serde's enum access.
    struct Variant<A>(String, A);

    impl<'de, A: MapAccess<'de>> de::EnumAccess<'de> for Variant<A> {
        type Error = A::Error;
        type Variant = Self;
        fn variant_seed<V: de::DeserializeSeed<'de>>(
            self,
            seed: V,
        ) -> Result<(V::Value, Self), A::Error> {
            let v = seed.deserialize(self.0.as_str().into_deserializer())?;
            Ok((v, self))
        }
    }

    impl<'de, A: MapAccess<'de>> de::VariantAccess<'de> for Variant<A> {
        type Error = A::Error;
        fn unit_variant(self) -> Result<(), A::Error> {
            Err(de::Error::custom(format!("{}: fields expected", self.0)))
        }
        fn newtype_variant_seed<T: de::DeserializeSeed<'de>>(
            self,
            seed: T,
        ) -> Result<T::Value, A::Error> {
            seed.deserialize(de::value::MapAccessDeserializer::new(self.1))
        }
        fn tuple_variant<V: Visitor<'de>>(self, _len: usize, v: V) -> Result<V::Value, A::Error> {
            v.visit_map(self.1)
        }
        fn struct_variant<V: Visitor<'de>>(
            self,
            _fields: &'static [&'static str],
            v: V,
        ) -> Result<V::Value, A::Error> {
            v.visit_map(self.1)
        }
    }

    /// Variant `name` whose body is a sequence (`Constant((r, g, b))`).
    struct SeqVariant<A>(String, A);

    impl<'de, A: SeqAccess<'de>> de::EnumAccess<'de> for SeqVariant<A> {
        type Error = A::Error;
        type Variant = Self;
        fn variant_seed<V: de::DeserializeSeed<'de>>(
            self,
            seed: V,
        ) -> Result<(V::Value, Self), A::Error> {
            let v = seed.deserialize(self.0.as_str().into_deserializer())?;
            Ok((v, self))
        }
    }

    impl<'de, A: SeqAccess<'de>> de::VariantAccess<'de> for SeqVariant<A> {
        type Error = A::Error;
        fn unit_variant(self) -> Result<(), A::Error> {
            Err(de::Error::custom(format!("{}: a value expected", self.0)))
        }
        fn newtype_variant_seed<T: de::DeserializeSeed<'de>>(
            self,
            seed: T,
        ) -> Result<T::Value, A::Error> {
            seed.deserialize(de::value::SeqAccessDeserializer::new(self.1))
        }
        fn tuple_variant<V: Visitor<'de>>(self, _len: usize, v: V) -> Result<V::Value, A::Error> {
            v.visit_seq(self.1)
        }
        fn struct_variant<V: Visitor<'de>>(
            self,
            _fields: &'static [&'static str],
            v: V,
        ) -> Result<V::Value, A::Error> {
            v.visit_seq(self.1)
        }
    }

    impl<'de> Visitor<'de> for Body {
        type Value = TextureDesc;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write!(f, "the fields of {}", self.0)
        }
        fn visit_unit<E: de::Error>(self) -> Result<TextureDesc, E> {
            defaults(&self.0)
        }
        fn visit_map<A: MapAccess<'de>>(self, m: A) -> Result<TextureDesc, A::Error> {
            TextureDesc::deserialize(de::value::EnumAccessDeserializer::new(Variant(self.0, m)))
        }
        fn visit_seq<A: SeqAccess<'de>>(self, s: A) -> Result<TextureDesc, A::Error> {
            TextureDesc::deserialize(de::value::EnumAccessDeserializer::new(SeqVariant(
                self.0, s,
            )))
        }
    }

    /// The outer `{variant: body}`, or a bare variant name.
    struct Outer;

    impl<'de> Visitor<'de> for Outer {
        type Value = TextureDesc;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("a texture")
        }
        fn visit_str<E: de::Error>(self, name: &str) -> Result<TextureDesc, E> {
            defaults(name)
        }
        fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<TextureDesc, A::Error> {
            let name: String = m
                .next_key()?
                .ok_or_else(|| de::Error::custom("a texture needs a kind"))?;
            let t = m.next_value_seed(Body(name))?;
            if m.next_key::<de::IgnoredAny>()?.is_some() {
                return Err(de::Error::custom("one texture expected"));
            }
            Ok(t)
        }
    }

    d.deserialize_any(Outer)
}

impl ScalarDesc {
    /// The texture this coefficient reads, if it is not a plain number.
    #[must_use]
    pub const fn texture(&self) -> Option<&TextureDesc> {
        match self {
            Self::Value(_) => None,
            Self::Texture(t) | Self::Channel(ChannelDesc { texture: t, .. }) => Some(t),
        }
    }

    /// The texture this coefficient reads, mutably.
    pub const fn texture_mut(&mut self) -> Option<&mut TextureDesc> {
        match self {
            Self::Value(_) => None,
            Self::Texture(t) | Self::Channel(ChannelDesc { texture: t, .. }) => Some(t),
        }
    }

    /// The channel read from the texture (luminance for a bare texture); `None` for a number.
    #[must_use]
    pub const fn channel(&self) -> Option<Channel> {
        match self {
            Self::Value(_) => None,
            Self::Texture(_) => Some(Channel::Luminance),
            Self::Channel(c) => Some(c.channel),
        }
    }
}

impl ColorDesc {
    /// Whether this is the plain colour black (a glow that is off).
    #[must_use]
    pub fn is_black(&self) -> bool {
        *self == Self::Value(Rgb::BLACK)
    }

    /// The texture this colour reads, if it is not a plain colour.
    #[must_use]
    pub const fn texture(&self) -> Option<&TextureDesc> {
        match self {
            Self::Value(_) => None,
            Self::Texture(t) => Some(t),
        }
    }

    /// The texture this colour reads, mutably.
    pub const fn texture_mut(&mut self) -> Option<&mut TextureDesc> {
        match self {
            Self::Value(_) => None,
            Self::Texture(t) => Some(t),
        }
    }
}

impl From<f32> for ScalarDesc {
    fn from(v: f32) -> Self {
        Self::Value(v)
    }
}

impl From<Rgb> for ColorDesc {
    fn from(c: Rgb) -> Self {
        Self::Value(c)
    }
}

fn black_param() -> ColorDesc {
    ColorDesc::Value(Rgb::BLACK)
}
fn white_param() -> ColorDesc {
    ColorDesc::Value(Rgb::WHITE)
}
fn one_param() -> ScalarDesc {
    ScalarDesc::Value(1.0)
}
fn default_ka() -> ScalarDesc {
    ScalarDesc::Value(0.25)
}
fn default_kd() -> ScalarDesc {
    ScalarDesc::Value(0.75)
}
fn default_ks() -> ScalarDesc {
    ScalarDesc::Value(0.25)
}
fn default_exp() -> ScalarDesc {
    ScalarDesc::Value(20.0)
}
fn default_kr() -> ScalarDesc {
    ScalarDesc::Value(0.75)
}

/// Where a material's colour comes from. Colours and texel values are linear RGB.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum TextureDesc {
    /// One linear RGB colour everywhere: `Constant((0.7, 0.7, 0.7))`.
    Constant(Rgb),
    /// An image file through a mapping.
    Image {
        /// Path, relative to the preset file.
        path: String,
        /// How hit points become (u, v).
        #[serde(default)]
        mapping: Mapping,
        /// How texels are combined.
        #[serde(default)]
        filter: Filter,
        /// Which texel the nearest filter picks.
        #[serde(default)]
        lookup: Lookup,
        /// What (u, v) outside [0, 1] reads; default `Repeat`.
        #[serde(default)]
        wrap: Wrap,
        /// Multiplier on the texel values.
        #[serde(default = "one")]
        scale: f32,
        /// Whether 8- and 16-bit files are sRGB-encoded (almost always).
        #[serde(default = "yes")]
        srgb: bool,
        /// The longest footprint the EWA filter follows (major / minor axis, 1 to 64).
        #[serde(default = "default_max_anisotropy")]
        max_anisotropy: f32,
        /// (u, v) scale, rotation and offset after the mapping; default none.
        #[serde(default, skip_serializing_if = "UvTransform::is_identity")]
        uv: UvTransform,
    },
    /// A checkerboard in (u, v).
    Checker {
        /// How hit points become (u, v).
        #[serde(default)]
        mapping: Mapping,
        /// Squares along u and along v over [0, 1].
        #[serde(default = "default_squares")]
        squares: (f32, f32),
        /// The colour of the square at the (u, v) origin, then the other's; default light grey 0.8
        /// and near-black 0.05.
        #[serde(default = "default_checker_colors")]
        colors: (Rgb, Rgb),
        /// `Trilinear` or `Ewa`: box-filtered over the pixel's footprint in closed form;
        /// otherwise point-sampled.
        #[serde(default)]
        filter: Filter,
        /// (u, v) scale, rotation and offset after the mapping; default none.
        #[serde(default, skip_serializing_if = "UvTransform::is_identity")]
        uv: UvTransform,
    },
    /// The image (`map_Kd`) or colour (`Kd`) of the material a mesh file names (an OBJ's .mtl),
    /// read through the mesh's (u, v) by default. Only on `Mesh` shapes.
    MeshMaterial {
        /// How hit points become (u, v).
        #[serde(default = "uv_mapping")]
        mapping: Mapping,
        /// How texels are combined.
        #[serde(default)]
        filter: Filter,
        /// Which texel the nearest filter picks.
        #[serde(default)]
        lookup: Lookup,
        /// What (u, v) outside [0, 1] reads; default `Repeat`.
        #[serde(default)]
        wrap: Wrap,
        /// Longest-to-shortest axis ratio the EWA filter honours (see the `Image` texture).
        #[serde(default = "default_max_anisotropy")]
        max_anisotropy: f32,
        /// (u, v) scale, rotation and offset after the mapping; default none.
        #[serde(default, skip_serializing_if = "UvTransform::is_identity")]
        uv: UvTransform,
    },
    /// The labelled UV test grid (cells A1 to H8).
    UvGrid {
        /// How hit points become (u, v).
        #[serde(default)]
        mapping: Mapping,
        /// How texels are combined.
        #[serde(default)]
        filter: Filter,
        /// What (u, v) outside [0, 1] reads; default `Repeat`.
        #[serde(default)]
        wrap: Wrap,
        /// The longest footprint the EWA filter follows (major / minor axis, 1 to 64).
        #[serde(default = "default_max_anisotropy")]
        max_anisotropy: f32,
        /// (u, v) scale, rotation and offset after the mapping; default none.
        #[serde(default, skip_serializing_if = "UvTransform::is_identity")]
        uv: UvTransform,
    },
}

fn uv_mapping() -> Mapping {
    Mapping::Uv
}

fn default_max_anisotropy() -> f32 {
    DEFAULT_MAX_ANISOTROPY
}

fn default_squares() -> (f32, f32) {
    (8.0, 8.0)
}
fn default_checker_colors() -> (Rgb, Rgb) {
    (Rgb::grey(0.8), Rgb::grey(0.05))
}

impl TextureDesc {
    /// The mapping, for textures that have one.
    #[must_use]
    pub fn mapping(&self) -> Option<Mapping> {
        match self {
            Self::Constant(_) => None,
            Self::Image { mapping, .. }
            | Self::Checker { mapping, .. }
            | Self::MeshMaterial { mapping, .. }
            | Self::UvGrid { mapping, .. } => Some(*mapping),
        }
    }

    /// Sets the filter of a texture that has one (images, mesh materials, the UV grid, the
    /// checker).
    pub fn set_filter(&mut self, f: Filter) {
        match self {
            Self::Constant(_) => {}
            Self::Image { filter, .. }
            | Self::Checker { filter, .. }
            | Self::MeshMaterial { filter, .. }
            | Self::UvGrid { filter, .. } => *filter = f,
        }
    }

    /// The (u, v) transform, for textures that have one.
    #[must_use]
    pub fn uv_transform(&self) -> Option<UvTransform> {
        match self {
            Self::Constant(_) => None,
            Self::Image { uv, .. }
            | Self::Checker { uv, .. }
            | Self::MeshMaterial { uv, .. }
            | Self::UvGrid { uv, .. } => Some(*uv),
        }
    }

    /// The (u, v) transform, mutably.
    pub fn uv_transform_mut(&mut self) -> Option<&mut UvTransform> {
        match self {
            Self::Constant(_) => None,
            Self::Image { uv, .. }
            | Self::Checker { uv, .. }
            | Self::MeshMaterial { uv, .. }
            | Self::UvGrid { uv, .. } => Some(uv),
        }
    }

    /// Sets the mapping of a texture that has one.
    pub fn set_mapping(&mut self, m: Mapping) {
        match self {
            Self::Constant(_) => {}
            Self::Image { mapping, .. }
            | Self::Checker { mapping, .. }
            | Self::MeshMaterial { mapping, .. }
            | Self::UvGrid { mapping, .. } => *mapping = m,
        }
    }
}

impl MaterialDesc {
    /// The texture giving the surface its colour: `cd`, or `ce` for an emissive material.
    #[must_use]
    pub fn texture(&self) -> &TextureDesc {
        match self {
            Self::Matte { cd, .. } | Self::Phong { cd, .. } | Self::Reflective { cd, .. } => cd,
            Self::Emissive { ce, .. } => ce,
        }
    }

    /// The colour texture, mutably.
    pub fn texture_mut(&mut self) -> &mut TextureDesc {
        match self {
            Self::Matte { cd, .. } | Self::Phong { cd, .. } | Self::Reflective { cd, .. } => cd,
            Self::Emissive { ce, .. } => ce,
        }
    }

    /// Every coefficient and colour besides the texture colour (`cd`, or an emissive material's
    /// `ce`; Phong's glow `ce` is listed), by its preset name, in preset order.
    #[must_use]
    pub fn params(&self) -> Vec<(&'static str, ParamRef<'_>)> {
        use ParamRef::{Color, Scalar};
        match self {
            Self::Matte { ka, kd, .. } => vec![("ka", Scalar(ka)), ("kd", Scalar(kd))],
            Self::Phong {
                ka,
                kd,
                ks,
                cs,
                exp,
                ce,
                ..
            } => vec![
                ("ka", Scalar(ka)),
                ("kd", Scalar(kd)),
                ("ks", Scalar(ks)),
                ("cs", Color(cs)),
                ("exp", Scalar(exp)),
                ("ce", Color(ce)),
            ],
            Self::Reflective {
                ka,
                kd,
                ks,
                cs,
                exp,
                kr,
                cr,
                ..
            } => vec![
                ("ka", Scalar(ka)),
                ("kd", Scalar(kd)),
                ("ks", Scalar(ks)),
                ("cs", Color(cs)),
                ("exp", Scalar(exp)),
                ("kr", Scalar(kr)),
                ("cr", Color(cr)),
            ],
            Self::Emissive { ls, .. } => vec![("ls", Scalar(ls))],
        }
    }

    /// The same parameters as [`MaterialDesc::params`], mutably. (Two matches, because Rust
    /// cannot derive a mutable borrow list from a shared one.)
    pub fn params_mut(&mut self) -> Vec<(&'static str, ParamMut<'_>)> {
        use ParamMut::{Color, Scalar};
        match self {
            Self::Matte { ka, kd, .. } => vec![("ka", Scalar(ka)), ("kd", Scalar(kd))],
            Self::Phong {
                ka,
                kd,
                ks,
                cs,
                exp,
                ce,
                ..
            } => vec![
                ("ka", Scalar(ka)),
                ("kd", Scalar(kd)),
                ("ks", Scalar(ks)),
                ("cs", Color(cs)),
                ("exp", Scalar(exp)),
                ("ce", Color(ce)),
            ],
            Self::Reflective {
                ka,
                kd,
                ks,
                cs,
                exp,
                kr,
                cr,
                ..
            } => vec![
                ("ka", Scalar(ka)),
                ("kd", Scalar(kd)),
                ("ks", Scalar(ks)),
                ("cs", Color(cs)),
                ("exp", Scalar(exp)),
                ("kr", Scalar(kr)),
                ("cr", Color(cr)),
            ],
            Self::Emissive { ls, .. } => vec![("ls", Scalar(ls))],
        }
    }

    /// Every texture the material reads, by parameter name: the colour (`cd` or `ce`) first,
    /// then each textured coefficient and colour.
    #[must_use]
    pub fn textures(&self) -> Vec<(&'static str, &TextureDesc)> {
        let colour = match self {
            Self::Emissive { .. } => "ce",
            _ => "cd",
        };
        let mut v = vec![(colour, self.texture())];
        v.extend(
            self.params()
                .into_iter()
                .filter_map(|(name, p)| p.texture().map(|t| (name, t))),
        );
        v
    }

    /// Every texture the material reads, mutably, in the order of [`MaterialDesc::textures`].
    pub fn textures_mut(&mut self) -> Vec<&mut TextureDesc> {
        let (colour, params): (&mut TextureDesc, Vec<ParamMut<'_>>) = match self {
            Self::Matte { ka, kd, cd } => (cd, vec![ParamMut::Scalar(ka), ParamMut::Scalar(kd)]),
            Self::Phong {
                ka,
                kd,
                cd,
                ks,
                cs,
                exp,
                ce,
            } => (
                cd,
                vec![
                    ParamMut::Scalar(ka),
                    ParamMut::Scalar(kd),
                    ParamMut::Scalar(ks),
                    ParamMut::Color(cs),
                    ParamMut::Scalar(exp),
                    ParamMut::Color(ce),
                ],
            ),
            Self::Reflective {
                ka,
                kd,
                cd,
                ks,
                cs,
                exp,
                kr,
                cr,
            } => (
                cd,
                vec![
                    ParamMut::Scalar(ka),
                    ParamMut::Scalar(kd),
                    ParamMut::Scalar(ks),
                    ParamMut::Color(cs),
                    ParamMut::Scalar(exp),
                    ParamMut::Scalar(kr),
                    ParamMut::Color(cr),
                ],
            ),
            Self::Emissive { ls, ce } => (ce, vec![ParamMut::Scalar(ls)]),
        };
        let mut v = vec![colour];
        v.extend(params.into_iter().filter_map(ParamMut::into_texture));
        v
    }
}

/// A material's coefficient or colour, read ([`MaterialDesc::params`]).
#[derive(Clone, Copy, Debug)]
pub enum ParamRef<'a> {
    /// A coefficient.
    Scalar(&'a ScalarDesc),
    /// A colour.
    Color(&'a ColorDesc),
}

impl<'a> ParamRef<'a> {
    /// The texture it reads, if it is not a plain value.
    #[must_use]
    pub const fn texture(self) -> Option<&'a TextureDesc> {
        match self {
            Self::Scalar(s) => s.texture(),
            Self::Color(c) => c.texture(),
        }
    }
}

/// A material's coefficient or colour, to edit ([`MaterialDesc::params_mut`]).
#[derive(Debug)]
pub enum ParamMut<'a> {
    /// A coefficient.
    Scalar(&'a mut ScalarDesc),
    /// A colour.
    Color(&'a mut ColorDesc),
}

impl<'a> ParamMut<'a> {
    /// The texture it reads, if it is not a plain value.
    #[must_use]
    pub fn into_texture(self) -> Option<&'a mut TextureDesc> {
        match self {
            Self::Scalar(s) => s.texture_mut(),
            Self::Color(c) => c.texture_mut(),
        }
    }
}

/// The kinds of [`ShapeDesc`], as the shape menu names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
pub enum ShapeKind {
    /// [`ShapeDesc::Sphere`].
    #[strum(message = "The unit sphere at the origin (place it with the transform).")]
    Sphere,
    /// [`ShapeDesc::Cylinder`].
    #[strum(message = "The open cylinder of radius 1 around y, from y = -1 to 1.")]
    Cylinder,
    /// [`ShapeDesc::Plane`].
    #[strum(message = "The infinite plane y = 0.")]
    Plane,
    /// [`ShapeDesc::Rectangle`].
    #[strum(message = "The generic rectangle (x, z) in [-1, 1]^2 in the plane y = 0.")]
    Rectangle,
    /// [`ShapeDesc::Disk`].
    #[strum(message = "The unit disk in the plane y = 0.")]
    Disk,
    /// [`ShapeDesc::Mesh`].
    #[strum(
        message = "A triangle mesh from a PLY or OBJ file: type its path or drop the file on the window."
    )]
    Mesh,
}

impl crate::names::Named for ShapeKind {
    const WHAT: &'static str = "shape";
}

/// The kinds of [`TextureDesc`], as the texture menu names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
pub enum TextureKind {
    /// [`TextureDesc::Constant`].
    #[strum(message = "One colour everywhere.")]
    Constant,
    /// [`TextureDesc::Image`].
    #[strum(message = "An image file read through a mapping.")]
    Image,
    /// [`TextureDesc::Checker`].
    #[strum(message = "A procedural checkerboard in (u, v).")]
    Checker,
    /// [`TextureDesc::UvGrid`].
    #[strum(
        serialize = "UV grid",
        message = "The labelled UV test grid: cells A1 (u = v = 0) to H8."
    )]
    UvGrid,
    /// [`TextureDesc::MeshMaterial`].
    #[strum(
        serialize = "Mesh material",
        message = "The image or colour the mesh file's material names (OBJ .mtl); meshes only."
    )]
    MeshMaterial,
}

impl crate::names::Named for TextureKind {
    const WHAT: &'static str = "texture";
}

/// The kinds of [`MaterialDesc`], as the material menu names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
pub enum MaterialKind {
    /// [`MaterialDesc::Matte`].
    #[strum(
        message = "The lecture's SV_Matte: ambient plus Lambertian diffuse with a textured colour."
    )]
    Matte,
    /// [`MaterialDesc::Phong`].
    #[strum(message = "Matte with a Phong highlight.")]
    Phong,
    /// [`MaterialDesc::Reflective`].
    #[strum(message = "Phong plus a perfect mirror kr cr: shows what the mirrored ray sees.")]
    Reflective,
    /// [`MaterialDesc::Emissive`].
    #[strum(message = "The lecture's SV_Emissive: glows with its texture and ignores the lights.")]
    Emissive,
}

impl crate::names::Named for MaterialKind {
    const WHAT: &'static str = "material";
}

/// The kinds of [`LightDesc`], as the lights panel names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
pub enum LightKind {
    /// [`LightDesc::Directional`].
    #[strum(
        serialize = "directional",
        message = "A light from one direction, like the sun."
    )]
    Directional,
    /// [`LightDesc::Point`].
    #[strum(
        serialize = "point",
        message = "A light from a point, without fall-off."
    )]
    Point,
}

impl crate::names::Named for LightKind {
    const WHAT: &'static str = "light";
}

/// The kinds of [`ProjectionDesc`], as the camera menu names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
pub enum ProjectionKind {
    /// [`ProjectionDesc::Pinhole`].
    #[strum(message = "Perspective with a vertical field of view.")]
    Pinhole,
    /// [`ProjectionDesc::Fisheye`].
    #[strum(message = "Equidistant fisheye: the angle from the axis grows linearly to the rim.")]
    Fisheye,
    /// [`ProjectionDesc::Spherical`].
    #[strum(message = "Equirectangular panorama: longitude across, latitude up.")]
    Spherical,
    /// [`ProjectionDesc::Orthographic`].
    #[strum(
        message = "Parallel projection: no perspective; the view is a fixed height in world units."
    )]
    Orthographic,
}

impl crate::names::Named for ProjectionKind {
    const WHAT: &'static str = "camera";
}

impl ShapeKind {
    /// The shape a menu pick makes: a mesh starts with no path (it builds nothing until one is
    /// given).
    #[must_use]
    pub fn default_desc(self) -> ShapeDesc {
        match self {
            Self::Sphere => ShapeDesc::Sphere,
            Self::Cylinder => ShapeDesc::Cylinder { capped: false },
            Self::Plane => ShapeDesc::Plane,
            Self::Rectangle => ShapeDesc::Rectangle,
            Self::Disk => ShapeDesc::Disk,
            Self::Mesh => ShapeDesc::Mesh {
                path: String::new(),
                shading: Shading::default(),
            },
        }
    }
}

impl ShapeDesc {
    /// Which kind of shape this is.
    #[must_use]
    pub const fn kind(&self) -> ShapeKind {
        match self {
            Self::Sphere => ShapeKind::Sphere,
            Self::Cylinder { .. } => ShapeKind::Cylinder,
            Self::Plane => ShapeKind::Plane,
            Self::Rectangle => ShapeKind::Rectangle,
            Self::Disk => ShapeKind::Disk,
            Self::Mesh { .. } => ShapeKind::Mesh,
        }
    }
}

impl TextureKind {
    /// The texture with a preset's defaults for every field it may leave out; an image starts
    /// with no path.
    #[must_use]
    pub fn default_desc(self) -> TextureDesc {
        match self {
            Self::Constant => TextureDesc::Constant(Rgb::grey(0.7)),
            Self::Image => TextureDesc::Image {
                path: String::new(),
                mapping: Mapping::default(),
                filter: Filter::default(),
                lookup: Lookup::default(),
                wrap: Wrap::default(),
                scale: one(),
                srgb: yes(),
                max_anisotropy: default_max_anisotropy(),
                uv: UvTransform::IDENTITY,
            },
            Self::Checker => TextureDesc::Checker {
                mapping: Mapping::default(),
                squares: default_squares(),
                colors: default_checker_colors(),
                filter: Filter::default(),
                uv: UvTransform::IDENTITY,
            },
            Self::UvGrid => TextureDesc::UvGrid {
                mapping: Mapping::default(),
                filter: Filter::default(),
                wrap: Wrap::default(),
                max_anisotropy: default_max_anisotropy(),
                uv: UvTransform::IDENTITY,
            },
            Self::MeshMaterial => TextureDesc::MeshMaterial {
                mapping: uv_mapping(),
                filter: Filter::default(),
                lookup: Lookup::default(),
                wrap: Wrap::default(),
                max_anisotropy: default_max_anisotropy(),
                uv: UvTransform::IDENTITY,
            },
        }
    }
}

impl TextureDesc {
    /// Which kind of texture this is.
    #[must_use]
    pub const fn kind(&self) -> TextureKind {
        match self {
            Self::Constant(_) => TextureKind::Constant,
            Self::Image { .. } => TextureKind::Image,
            Self::Checker { .. } => TextureKind::Checker,
            Self::UvGrid { .. } => TextureKind::UvGrid,
            Self::MeshMaterial { .. } => TextureKind::MeshMaterial,
        }
    }

    /// A texture of another kind with its defaults, keeping this one's mapping (but a mesh
    /// material starts from the mesh's own (u, v)).
    #[must_use]
    pub fn converted(&self, kind: TextureKind) -> Self {
        let mut t = kind.default_desc();
        if let (Some(mapping), false) = (self.mapping(), kind == TextureKind::MeshMaterial) {
            t.set_mapping(mapping);
        }
        if let (Some(uv), Some(to)) = (self.uv_transform(), t.uv_transform_mut()) {
            *to = uv;
        }
        t
    }
}

impl MaterialKind {
    /// The material with a preset's defaults and a constant grey colour.
    #[must_use]
    pub fn default_desc(self) -> MaterialDesc {
        let colour = TextureKind::Constant.default_desc();
        match self {
            Self::Matte => MaterialDesc::Matte {
                ka: default_ka(),
                kd: default_kd(),
                cd: colour,
            },
            Self::Phong => MaterialDesc::Phong {
                ka: default_ka(),
                kd: default_kd(),
                cd: colour,
                ks: default_ks(),
                cs: white_param(),
                exp: default_exp(),
                ce: black_param(),
            },
            Self::Reflective => MaterialDesc::Reflective {
                ka: default_ka(),
                kd: default_kd(),
                cd: colour.clone(),
                ks: default_ks(),
                cs: white_param(),
                exp: default_exp(),
                kr: default_kr(),
                cr: white_param(),
            },
            Self::Emissive => MaterialDesc::Emissive {
                ls: one_param(),
                ce: colour,
            },
        }
    }
}

impl MaterialDesc {
    /// Which kind of material this is.
    #[must_use]
    pub const fn kind(&self) -> MaterialKind {
        match self {
            Self::Matte { .. } => MaterialKind::Matte,
            Self::Phong { .. } => MaterialKind::Phong,
            Self::Reflective { .. } => MaterialKind::Reflective,
            Self::Emissive { .. } => MaterialKind::Emissive,
        }
    }

    /// A material of another kind with its defaults, keeping this one's texture and every
    /// coefficient and colour both kinds have (ambient and diffuse; Phong's highlight).
    #[must_use]
    pub fn converted(&self, kind: MaterialKind) -> Self {
        let mut m = kind.default_desc();
        *m.texture_mut() = self.texture().clone();
        // Parameters both kinds have keep their values.
        let from: Vec<(&str, ParamRef<'_>)> = self.params();
        for (name, to) in m.params_mut() {
            match (from.iter().find(|(n, _)| *n == name).map(|(_, p)| *p), to) {
                (Some(ParamRef::Scalar(f)), ParamMut::Scalar(t)) => *t = f.clone(),
                (Some(ParamRef::Color(f)), ParamMut::Color(t)) => *t = f.clone(),
                _ => {}
            }
        }
        m
    }
}

impl LightKind {
    /// A new light of this kind: white, casting shadows, from above and in front of the origin.
    #[must_use]
    pub fn default_desc(self) -> LightDesc {
        match self {
            Self::Directional => LightDesc::Directional {
                direction: Vec3::new(1.0, 1.0, 1.0),
                ls: one(),
                color: white(),
                shadows: yes(),
            },
            Self::Point => LightDesc::Point {
                position: Vec3::new(0.0, 4.0, 4.0),
                ls: one(),
                color: white(),
                shadows: yes(),
            },
        }
    }
}

impl LightDesc {
    /// Which kind of light this is.
    #[must_use]
    pub const fn kind(&self) -> LightKind {
        match self {
            Self::Directional { .. } => LightKind::Directional,
            Self::Point { .. } => LightKind::Point,
        }
    }
}

impl ProjectionKind {
    /// The projection with its usual angles: 45 degrees for the pinhole, the half sphere for the
    /// fisheye, everything for the panorama; 2 world units high (a unit sphere fills it) for
    /// the orthographic camera.
    #[must_use]
    pub const fn default_desc(self) -> ProjectionDesc {
        match self {
            Self::Pinhole => ProjectionDesc::Pinhole { fov: 45.0 },
            Self::Fisheye => ProjectionDesc::Fisheye { fov: 180.0 },
            Self::Spherical => ProjectionDesc::Spherical {
                h_fov: 360.0,
                v_fov: 180.0,
            },
            Self::Orthographic => ProjectionDesc::Orthographic { height: 2.0 },
        }
    }
}

impl ProjectionDesc {
    /// Which kind of projection this is.
    #[must_use]
    pub const fn kind(&self) -> ProjectionKind {
        match self {
            Self::Pinhole { .. } => ProjectionKind::Pinhole,
            Self::Fisheye { .. } => ProjectionKind::Fisheye,
            Self::Spherical { .. } => ProjectionKind::Spherical,
            Self::Orthographic { .. } => ProjectionKind::Orthographic,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use strum::VariantArray;

    /// What a menu pick makes is of the kind picked.
    #[test]
    fn every_kind_defaults_to_a_desc_of_that_kind() {
        for &k in ShapeKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
        for &k in TextureKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
        for &k in MaterialKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
        for &k in LightKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
        for &k in ProjectionKind::VARIANTS {
            assert_eq!(k.default_desc().kind(), k);
        }
    }

    /// A kind's defaults are what a preset that leaves every optional field out reads as.
    #[test]
    fn kind_defaults_match_the_preset_defaults() {
        let checker: TextureDesc = ron::from_str("Checker()").expect("checker");
        assert_eq!(checker, TextureKind::Checker.default_desc());
        let grid: TextureDesc = ron::from_str("UvGrid()").expect("uv grid");
        assert_eq!(grid, TextureKind::UvGrid.default_desc());
        let mesh: TextureDesc = ron::from_str("MeshMaterial()").expect("mesh material");
        assert_eq!(mesh, TextureKind::MeshMaterial.default_desc());
        let image: TextureDesc = ron::from_str(r#"Image(path: "")"#).expect("image");
        assert_eq!(image, TextureKind::Image.default_desc());
        let phong: MaterialDesc =
            ron::from_str("Phong(cd: Constant((0.7, 0.7, 0.7)))").expect("phong");
        assert_eq!(phong, MaterialKind::Phong.default_desc());
    }

    #[test]
    fn switching_kinds_keeps_the_mapping_texture_and_coefficients() {
        let earth = TextureDesc::Image {
            path: "earth.jpg".into(),
            mapping: Mapping::Cylindrical,
            filter: Filter::Ewa,
            lookup: Lookup::Lecture,
            wrap: Wrap::Clamp,
            scale: 2.0,
            srgb: true,
            max_anisotropy: 4.0,
            uv: UvTransform::IDENTITY,
        };
        assert_eq!(
            earth.converted(TextureKind::Checker).mapping(),
            Some(Mapping::Cylindrical)
        );
        // A mesh's material is read through the mesh's (u, v) unless told otherwise.
        assert_eq!(
            earth.converted(TextureKind::MeshMaterial).mapping(),
            Some(Mapping::Uv)
        );
        let phong = MaterialDesc::Phong {
            ka: 0.1.into(),
            kd: 0.9.into(),
            cd: earth.clone(),
            ks: 0.5.into(),
            cs: Rgb::WHITE.into(),
            exp: 50.0.into(),
            ce: Rgb::BLACK.into(),
        };
        assert_eq!(
            phong.converted(MaterialKind::Matte),
            MaterialDesc::Matte {
                ka: 0.1.into(),
                kd: 0.9.into(),
                cd: earth.clone()
            }
        );
        assert_eq!(
            phong.converted(MaterialKind::Emissive),
            MaterialDesc::Emissive {
                ls: 1.0.into(),
                ce: earth
            }
        );
    }

    /// Plain numbers and colours keep their meaning; textures, a channel of one, NaN and
    /// integers read as the format says, and each writes back as it was read.
    #[test]
    fn coefficients_read_as_numbers_or_textures() {
        let m: MaterialDesc = ron::from_str(
            r#"Phong(cd: Constant((0.5, 0.5, 0.5)), ka: 1, kd: 0.5,
                ks: Image(path: "mask.png", mapping: Spherical, filter: Ewa),
                cs: Checker(squares: (2, 2)),
                exp: (texture: UvGrid(wrap: Clamp), channel: Green))"#,
        )
        .expect("phong");
        let MaterialDesc::Phong {
            ka,
            kd,
            ks,
            cs,
            exp,
            ..
        } = &m
        else {
            panic!("not Phong: {m:?}")
        };
        assert_eq!(*ka, ScalarDesc::Value(1.0));
        assert_eq!(*kd, ScalarDesc::Value(0.5));
        let Some(TextureDesc::Image {
            path,
            mapping,
            filter,
            ..
        }) = ks.texture()
        else {
            panic!("ks: {ks:?}")
        };
        assert_eq!(
            (path.as_str(), *mapping, *filter),
            ("mask.png", Mapping::Spherical, Filter::Ewa)
        );
        assert_eq!(ks.channel(), Some(Channel::Luminance));
        assert!(matches!(
            cs,
            ColorDesc::Texture(TextureDesc::Checker {
                squares: (2.0, 2.0),
                ..
            })
        ));
        assert_eq!(exp.channel(), Some(Channel::Green));
        assert_eq!(
            exp.texture().map(TextureDesc::kind),
            Some(TextureKind::UvGrid)
        );
        let text = ron::to_string(&m).expect("write");
        assert_eq!(ron::from_str::<MaterialDesc>(&text).expect("read back"), m);
        let nan: MaterialDesc = ron::from_str("Matte(ka: NaN, cd: Constant((1, 1, 1)))").unwrap();
        assert!(matches!(nan, MaterialDesc::Matte { ka: ScalarDesc::Value(v), .. } if v.is_nan()));
        let plain: MaterialDesc =
            ron::from_str("Phong(cs: (1, 0.5, 0), cd: Constant((1, 1, 1)))").unwrap();
        assert!(matches!(
            plain,
            MaterialDesc::Phong {
                cs: ColorDesc::Value(Rgb(1.0, 0.5, 0.0)),
                ..
            }
        ));
    }

    /// A texture inside a coefficient reads exactly as the same text does as `cd`, also with
    /// every field left out (`UvGrid()`) and for a constant.
    #[test]
    fn a_texture_in_a_coefficient_reads_as_it_does_as_cd() {
        for t in [
            "UvGrid(wrap: Clamp)",
            "UvGrid()",
            "Checker()",
            "Checker(squares: (2, 4), colors: ((1, 0, 0), (0, 0, 1)))",
            "Constant((0.2, 0.4, 0.6))",
            r#"Image(path: "x.png", mapping: Cylindrical, filter: Trilinear, scale: 2)"#,
        ] {
            let as_cd: TextureDesc = ron::from_str(t).expect(t);
            let s: ScalarDesc = ron::from_str(t).expect(t);
            assert_eq!(s, ScalarDesc::Texture(as_cd.clone()), "{t}");
            let c: ColorDesc = ron::from_str(t).expect(t);
            assert_eq!(c, ColorDesc::Texture(as_cd.clone()), "{t}");
            let ch: ScalarDesc = ron::from_str(&format!("(texture: {t}, channel: Blue)")).expect(t);
            assert_eq!(
                ch,
                ScalarDesc::Channel(ChannelDesc {
                    texture: as_cd,
                    channel: Channel::Blue
                }),
                "{t}"
            );
        }
    }

    /// A value that is neither a number nor a texture says what it may be.
    #[test]
    fn a_bad_coefficient_says_what_is_expected() {
        let e = ron::from_str::<MaterialDesc>(r#"Phong(ks: "shiny", cd: Constant((1, 1, 1)))"#)
            .expect_err("a string is no coefficient");
        let msg = e.to_string();
        assert!(msg.contains("a number, a texture"), "{msg}");
        let e = ron::from_str::<MaterialDesc>(
            r#"Phong(cs: Imag(path: "x.png"), cd: Constant((1, 1, 1)))"#,
        )
        .expect_err("no such texture");
        assert!(
            e.to_string().contains("a colour (r, g, b) or a texture"),
            "{e}"
        );
    }
}
