//! Textures: the description ([`TextureDesc`]), the kinds with their defaults, and the check and
//! build of the runtime [`Texture`] (images through the [`AssetCache`]).

use super::assets::AssetCache;
use super::mapping::{MappingDesc, formula_refusal};
use super::values::{finite_non_negative, one, yes};
use crate::error::{Error, Result};
use crate::field::{FieldPath, Refusal};
use crate::mapping::{AnyMapping, Mapping, UvAffine, UvTransform};
use crate::math::Rgb;
use crate::texture::{
    Checker, DEFAULT_MAX_ANISOTROPY, Filter, ImageTexture, Lookup, MAX_ANISOTROPY_LIMIT, Texture,
    Wrap,
};
use crate::texture::{FormulaColour, FormulaTexture};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;

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
        mapping: MappingDesc,
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
        mapping: MappingDesc,
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
        mapping: MappingDesc,
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
        mapping: MappingDesc,
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
    /// Colour formulas over u, v and the local hit point x, y, z (see `mapping::formula`):
    /// one `grey`, or `r`, `g` and `b` (linear). Point-sampled; where a formula is NaN or
    /// infinite the pixel is magenta.
    Formula {
        /// How hit points become (u, v).
        #[serde(default)]
        mapping: MappingDesc,
        /// One formula for all three channels (leave r, g, b empty).
        #[serde(default, skip_serializing_if = "String::is_empty")]
        grey: String,
        /// The red channel's formula (with g and b, instead of grey).
        #[serde(default, skip_serializing_if = "String::is_empty")]
        r: String,
        /// The green channel's formula.
        #[serde(default, skip_serializing_if = "String::is_empty")]
        g: String,
        /// The blue channel's formula.
        #[serde(default, skip_serializing_if = "String::is_empty")]
        b: String,
        /// (u, v) scale, rotation and offset after the mapping; default none.
        #[serde(default, skip_serializing_if = "UvTransform::is_identity")]
        uv: UvTransform,
    },
}

fn uv_mapping() -> MappingDesc {
    MappingDesc::Builtin(Mapping::Uv)
}

/// The formula texture a menu pick starts from: the lecture's checker, written with `floor`.
pub const DEFAULT_GREY_FORMULA: &str = "0.05 + 0.75 * 2 * fract((floor(8 * u) + floor(8 * v)) / 2)";

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
    pub const fn mapping(&self) -> Option<&MappingDesc> {
        match self {
            Self::Constant(_) => None,
            Self::Image { mapping, .. }
            | Self::Checker { mapping, .. }
            | Self::MeshMaterial { mapping, .. }
            | Self::UvGrid { mapping, .. }
            | Self::Formula { mapping, .. } => Some(mapping),
        }
    }

    /// Sets the filter of a texture that has one (images, mesh materials, the UV grid, the
    /// checker).
    pub fn set_filter(&mut self, f: Filter) {
        match self {
            Self::Constant(_) | Self::Formula { .. } => {}
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
            | Self::UvGrid { uv, .. }
            | Self::Formula { uv, .. } => Some(*uv),
        }
    }

    /// The (u, v) transform, mutably.
    pub fn uv_transform_mut(&mut self) -> Option<&mut UvTransform> {
        match self {
            Self::Constant(_) => None,
            Self::Image { uv, .. }
            | Self::Checker { uv, .. }
            | Self::MeshMaterial { uv, .. }
            | Self::UvGrid { uv, .. }
            | Self::Formula { uv, .. } => Some(uv),
        }
    }

    /// Sets the mapping of a texture that has one.
    pub fn set_mapping(&mut self, m: MappingDesc) {
        match self {
            Self::Constant(_) => {}
            Self::Image { mapping, .. }
            | Self::Checker { mapping, .. }
            | Self::MeshMaterial { mapping, .. }
            | Self::UvGrid { mapping, .. }
            | Self::Formula { mapping, .. } => *mapping = m,
        }
    }
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
    /// [`TextureDesc::Formula`].
    #[strum(message = "Colour formulas over (u, v) and the hit point, written by you.")]
    Formula,
}

impl crate::names::Named for TextureKind {
    const WHAT: &'static str = "texture";
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
                mapping: MappingDesc::default(),
                filter: Filter::default(),
                lookup: Lookup::default(),
                wrap: Wrap::default(),
                scale: one(),
                srgb: yes(),
                max_anisotropy: default_max_anisotropy(),
                uv: UvTransform::IDENTITY,
            },
            Self::Checker => TextureDesc::Checker {
                mapping: MappingDesc::default(),
                squares: default_squares(),
                colors: default_checker_colors(),
                filter: Filter::default(),
                uv: UvTransform::IDENTITY,
            },
            Self::UvGrid => TextureDesc::UvGrid {
                mapping: MappingDesc::default(),
                filter: Filter::default(),
                wrap: Wrap::default(),
                max_anisotropy: default_max_anisotropy(),
                uv: UvTransform::IDENTITY,
            },
            Self::Formula => TextureDesc::Formula {
                mapping: MappingDesc::default(),
                grey: DEFAULT_GREY_FORMULA.into(),
                r: String::new(),
                g: String::new(),
                b: String::new(),
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
            Self::Formula { .. } => TextureKind::Formula,
        }
    }

    /// A texture of another kind with its defaults, keeping this one's mapping (but a mesh
    /// material starts from the mesh's own (u, v)).
    #[must_use]
    pub fn converted(&self, kind: TextureKind) -> Self {
        let mut t = kind.default_desc();
        if let (Some(mapping), false) = (self.mapping(), kind == TextureKind::MeshMaterial) {
            t.set_mapping(mapping.clone());
        }
        if let (Some(uv), Some(to)) = (self.uv_transform(), t.uv_transform_mut()) {
            *to = uv;
        }
        t
    }
}

/// An image's path must name a file: an empty one would name the preset's folder.
fn check_path(path: &str) -> std::result::Result<(), Refusal> {
    if path.is_empty() {
        Err(Refusal::new("path".into(), "is empty: name an image file"))
    } else {
        Ok(())
    }
}

/// A texture of field `what` (`ks`, `bump.height`, relative to the object or material), its
/// errors naming their fields below `what` (`ks.scale`); `build_object` puts the preset and
/// the object in front.
pub(super) fn param_texture(
    what: &FieldPath,
    t: &TextureDesc,
    base: &Path,
    cache: &mut AssetCache,
) -> Result<Texture> {
    texture(t, base, cache).map_err(|e| e.under(base, what))
}

/// The alpha channel of an `Image` texture, read through its mapping, filter, wrap and
/// (u, v) transform like its colour would be.
pub(super) fn alpha_texture(
    t: &TextureDesc,
    base: &Path,
    cache: &mut AssetCache,
) -> Result<Texture> {
    let TextureDesc::Image {
        path,
        mapping,
        filter,
        lookup,
        wrap,
        max_anisotropy,
        uv,
        ..
    } = t
    else {
        return Err(Error::refused(
            base,
            Refusal::new(
                FieldPath::root(),
                format!("channel Alpha needs an Image texture, not {}", t.kind()),
            ),
        ));
    };
    let refused = |r: Refusal| Error::refused(base, r);
    check_anisotropy(*max_anisotropy).map_err(refused)?;
    let transform = uv_transform(uv).map_err(refused)?;
    check_path(path).map_err(refused)?;
    let mapping = build_mapping(mapping).map_err(refused)?;
    let file = base.join(path);
    let image = cache.alpha(&file)?;
    let mip = pyramid(cache, &image, *filter, &file.display().to_string()).map_err(refused)?;
    Ok(Texture::Image(ImageTexture {
        image,
        mapping,
        filter: *filter,
        lookup: *lookup,
        wrap: *wrap,
        scale: 1.0,
        mip,
        max_anisotropy: *max_anisotropy,
        transform,
    }))
}

/// A checker's squares (positive, at most 1e6 along each side) and colours (finite, not
/// negative), as a preset's are checked when its scene is built; a lesson's exercise target
/// is checked by the same rule. The refusal names `squares` or `colors`.
///
/// # Errors
/// The first of them out of range.
pub fn check_checker(squares: (f32, f32), colors: &(Rgb, Rgb)) -> std::result::Result<(), Refusal> {
    let ok = |s: f32| s.is_finite() && s > 0.0 && s <= 1e6;
    if !ok(squares.0) || !ok(squares.1) {
        return Err(Refusal::new(
            "squares".into(),
            format!("{squares:?} must be positive and at most 1e6"),
        ));
    }
    finite_non_negative(
        "colors",
        &[colors.0.to_array(), colors.1.to_array()].concat(),
    )
}

/// The mip pyramid a texture read with `filter` needs (none unless [`Filter::needs_mip`]),
/// counted against the scene's budget; `what` names the image in notices.
fn pyramid(
    cache: &mut AssetCache,
    image: &Arc<crate::texture::ImageData>,
    filter: Filter,
    what: &str,
) -> std::result::Result<Option<Arc<crate::texture::MipPyramid>>, Refusal> {
    if !filter.needs_mip() {
        return Ok(None);
    }
    cache
        .mip(image, filter, what)
        .map(Some)
        .map_err(|m| Refusal::new("filter".into(), m))
}

/// The runtime texture; errors name their fields relative to the texture's (`scale`,
/// `mapping.u`), or no field for the texture's own.
pub(super) fn texture(t: &TextureDesc, base: &Path, cache: &mut AssetCache) -> Result<Texture> {
    let invalid = |r: Refusal| Error::refused(base, r);
    Ok(match t {
        TextureDesc::Constant(c) => {
            finite_non_negative(FieldPath::root(), &c.to_array()).map_err(invalid)?;
            Texture::Constant(*c)
        }
        TextureDesc::Image {
            path,
            mapping,
            filter,
            lookup,
            wrap,
            scale,
            srgb,
            max_anisotropy,
            uv,
        } => {
            finite_non_negative("scale", &[*scale]).map_err(invalid)?;
            let transform = uv_transform(uv).map_err(invalid)?;
            check_anisotropy(*max_anisotropy).map_err(invalid)?;
            check_path(path).map_err(invalid)?;
            let mapping = build_mapping(mapping).map_err(invalid)?;
            let file = base.join(path);
            let image = cache.image(&file, *srgb)?;
            let mip =
                pyramid(cache, &image, *filter, &file.display().to_string()).map_err(invalid)?;
            Texture::Image(ImageTexture {
                image,
                mapping,
                filter: *filter,
                lookup: *lookup,
                wrap: *wrap,
                scale: *scale,
                mip,
                max_anisotropy: *max_anisotropy,
                transform,
            })
        }
        TextureDesc::Checker {
            mapping,
            squares,
            colors,
            filter,
            uv,
        } => {
            let transform = uv_transform(uv).map_err(invalid)?;
            check_checker(*squares, colors).map_err(invalid)?;
            Texture::Checker(Checker {
                mapping: build_mapping(mapping).map_err(invalid)?,
                squares: *squares,
                colors: *colors,
                filter: *filter,
                transform,
            })
        }
        TextureDesc::MeshMaterial { .. } => {
            return Err(invalid(Refusal::new(
                FieldPath::root(),
                "MeshMaterial: only a Mesh shape names a material",
            )));
        }
        TextureDesc::UvGrid {
            mapping,
            filter,
            wrap,
            max_anisotropy,
            uv,
        } => {
            check_anisotropy(*max_anisotropy).map_err(invalid)?;
            let transform = uv_transform(uv).map_err(invalid)?;
            let mapping = build_mapping(mapping).map_err(invalid)?;
            let image = cache.uv_grid();
            let mip = pyramid(cache, &image, *filter, "the UV grid").map_err(invalid)?;
            Texture::Image(ImageTexture {
                image,
                mapping,
                filter: *filter,
                lookup: Lookup::Centred,
                wrap: *wrap,
                scale: 1.0,
                mip,
                max_anisotropy: *max_anisotropy,
                transform,
            })
        }
        TextureDesc::Formula {
            mapping,
            grey,
            r,
            g,
            b,
            uv,
        } => {
            let transform = uv_transform(uv).map_err(invalid)?;
            let mapping = build_mapping(mapping).map_err(invalid)?;
            let colour = formula_colour(grey, [r, g, b]).map_err(invalid)?;
            Texture::Formula(FormulaTexture {
                mapping,
                colour: Arc::new(colour),
                transform,
            })
        }
    })
}

/// The colour formulas: `grey` alone, or all three channels.
fn formula_colour(
    grey: &str,
    [r, g, b]: [&String; 3],
) -> std::result::Result<FormulaColour, Refusal> {
    let channels = [("r", r), ("g", g), ("b", b)];
    let given: Vec<&str> = channels
        .iter()
        .filter(|(_, t)| !t.trim().is_empty())
        .map(|(n, _)| *n)
        .collect();
    let colour = match (grey.trim().is_empty(), given.len()) {
        (false, 0) => FormulaColour::grey(grey),
        (true, 3) => FormulaColour::rgb(r, g, b),
        (false, _) => {
            return Err(Refusal::new(
                FieldPath::root(),
                format!(
                    "Formula: grey and {} both given; write grey alone, or r, g and b",
                    given.join(", ")
                ),
            ));
        }
        (true, _) => {
            let missing: Vec<&str> = channels
                .iter()
                .filter(|(_, t)| t.trim().is_empty())
                .map(|(n, _)| *n)
                .collect();
            return Err(Refusal::new(
                FieldPath::root(),
                format!(
                    "Formula: {} missing; write grey alone, or r, g and b",
                    missing.join(", ")
                ),
            ));
        }
    };
    colour.map_err(|e| formula_refusal(&e))
}

/// A texture's mapping, its formulas' mistakes named below `mapping` (`mapping.u`).
fn build_mapping(m: &MappingDesc) -> std::result::Result<AnyMapping, Refusal> {
    m.build().map_err(|r| r.under(&"mapping".into()))
}

/// The runtime (u, v) transform (`None` for the identity); the scale must be finite and at
/// least 1e-6 in size on both axes, the rest finite.
fn uv_transform(t: &UvTransform) -> std::result::Result<Option<UvAffine>, Refusal> {
    let ok = |s: f32| s.is_finite() && s.abs() >= 1e-6 && s.abs() <= 1e6;
    if !ok(t.scale.x) || !ok(t.scale.y) {
        return Err(Refusal::new(
            FieldPath::field("uv").then("scale"),
            format!("{} must be non-zero, between 1e-6 and 1e6 in size", t.scale),
        ));
    }
    if !t.rotate.is_finite() || !t.offset.is_finite() {
        return Err(Refusal::new(
            "uv".into(),
            "rotate and offset must be finite",
        ));
    }
    Ok(t.affine())
}

fn check_anisotropy(a: f32) -> std::result::Result<(), Refusal> {
    if (1.0..=MAX_ANISOTROPY_LIMIT).contains(&a) {
        Ok(())
    } else {
        Err(Refusal::new(
            "max_anisotropy".into(),
            format!("{a} is out of range (1 to {MAX_ANISOTROPY_LIMIT})"),
        ))
    }
}

/// A texture in a few words, for the inspector: an image's file name, else its kind.
pub(super) fn texture_words(t: &TextureDesc) -> String {
    match t {
        TextureDesc::Image { path, .. } => Path::new(path)
            .file_name()
            .map_or_else(|| path.clone(), |n| n.to_string_lossy().into_owned()),
        TextureDesc::Constant(c) => format!("a constant {:?}", c.to_array()),
        other => format!("a {} texture", other.kind()),
    }
}
