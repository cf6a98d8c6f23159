//! What an object's surface carries besides its material: clip, bump, normal and displacement
//! maps ([`BumpDesc`], [`NormalMapDesc`], [`DisplaceDesc`]), and the build of the runtime bump
//! and normal maps.

use super::super::assets::AssetCache;
use super::super::texture::{TextureDesc, param_texture};
use super::super::values::one;
use crate::error::{Error, Result};
use crate::field::{FieldPath, Refusal};
use crate::material::{Bump, NormalMap};
use crate::texture::Texture;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A displacement map ([`ObjectDesc::displace`](super::ObjectDesc::displace)), on a `Mesh` shape only (the generic shapes
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

/// A normal map ([`ObjectDesc::normal`](super::ObjectDesc::normal)).
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

/// A bump map ([`ObjectDesc::bump`](super::ObjectDesc::bump)).
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
pub(super) fn bare_alpha<S: serde::Serializer, T: Serialize>(
    a: &Option<T>,
    s: S,
) -> Result<S::Ok, S::Error> {
    match a {
        Some(a) => a.serialize(s),
        None => s.serialize_none(),
    }
}

/// Reads an optional field (`alpha`, `bump`, `normal`, `displace`) written as its value itself.
pub(super) fn some_alpha<'de, D: serde::Deserializer<'de>, T: Deserialize<'de>>(
    d: D,
) -> Result<Option<T>, D::Error> {
    T::deserialize(d).map(Some)
}

/// A normal map: its texture read raw (normals are not colours), never a constant (which has
/// no mapping, so no tangent frame).
pub(super) fn normal_map(
    n: &NormalMapDesc,
    base: &Path,
    cache: &mut AssetCache,
) -> Result<NormalMap> {
    let normal = FieldPath::field("normal");
    if !n.strength.is_finite() {
        return Err(Error::refused(
            base,
            Refusal::new(
                normal.clone().then("strength"),
                format!("{} is not finite", n.strength),
            ),
        ));
    }
    let mut raw = n.map.clone();
    if let TextureDesc::Image { srgb, .. } = &mut raw {
        *srgb = false;
    }
    let field = normal.then("map");
    match param_texture(&field, &raw, base, cache)? {
        Texture::Constant(_) => Err(Error::refused(
            base,
            Refusal::new(
                field,
                "a constant has no (u, v) mapping, so no tangent frame; use an image",
            ),
        )),
        map => Ok(NormalMap {
            map,
            strength: n.strength,
        }),
    }
}

/// A bump map, or `None` for a constant height (which has no slope). Errors name their fields
/// relative to the object (`bump.scale`); the caller puts the object in front.
pub(super) fn bump(b: &BumpDesc, base: &Path, cache: &mut AssetCache) -> Result<Option<Bump>> {
    let bump = FieldPath::field("bump");
    if !b.scale.is_finite() {
        return Err(Error::refused(
            base,
            Refusal::new(bump.then("scale"), format!("{} is not finite", b.scale)),
        ));
    }
    Ok(
        match param_texture(&bump.then("height"), &b.height, base, cache)? {
            Texture::Constant(_) => None,
            height => Some(Bump {
                height,
                scale: b.scale,
            }),
        },
    )
}
