//! Objects: the description ([`ObjectDesc`]: shape, transform, material and surface maps), the
//! shape kinds with their defaults, and the build of one runtime [`Object`].

mod displace;
mod maps;
mod mesh;
mod walk;

pub use maps::{BumpDesc, DEFAULT_SUBDIVIDE, DisplaceDesc, NormalMapDesc};

use super::assets::AssetCache;
use super::material::{MaterialDesc, ScalarDesc, material, scalar};
use super::trace::{Perturbation, Surface};
use super::values::finite_vec;
use crate::error::{Error, Result};
use crate::field::{FieldPath, Refusal};
use crate::geometry::{MeshShape, Object, Shading, Shape};
use crate::material::{Material, Scalar};
use crate::math::{Affine3A, Quat, Vec3};
use displace::displaced_mesh;
use maps::{bare_alpha, bump, normal_map, some_alpha};
use mesh::{check_uv_mapping, no_uv, resolve_mesh_material};
use serde::{Deserialize, Serialize};
use std::path::Path;

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

fn transform(t: &TransformDesc) -> std::result::Result<Affine3A, Refusal> {
    let translate = finite_vec("translate", t.translate)?;
    let rotate = finite_vec("rotate", t.rotate)?;
    let scale = finite_vec("scale", t.scale)?;
    if scale.abs().min_element() < 1e-30 || scale.abs().max_element() > 1e30 {
        return Err(Refusal::new(
            "scale".into(),
            format!("{} must be non-zero and below 1e30 on every axis", t.scale),
        ));
    }
    let r = Quat::from_rotation_z(rotate.z.to_radians())
        * Quat::from_rotation_y(rotate.y.to_radians())
        * Quat::from_rotation_x(rotate.x.to_radians());
    Ok(Affine3A::from_scale_rotation_translation(
        scale.into(),
        r,
        translate.into(),
    ))
}

/// One object built: the runtime object, its material and its surface maps.
pub(super) struct BuiltObject {
    /// The shape placed in the world, its material index the one given.
    pub object: Object,
    /// Its material.
    pub material: Material,
    /// Its clip map (unless it is solid everywhere) and its bump map (unless it has none or a
    /// constant height) or normal map.
    pub surface: Surface,
    /// Whether any of its textures needs ray differentials.
    pub needs_differentials: bool,
}

/// Builds object `i` of a preset, with `material_index` as its material's index. Errors name
/// the preset file `preset_path`, the field and the object (`objects[2].material.kd (object
/// "floor"): ...`); asset paths are relative to the preset's folder.
pub(super) fn build_object(
    o: &ObjectDesc,
    i: usize,
    material_index: usize,
    preset_path: &Path,
    cache: &mut AssetCache,
) -> Result<BuiltObject> {
    let base = preset_path.parent().unwrap_or(Path::new("."));
    let here = FieldPath::field("objects").at(i);
    // A refusal of a field of the object (relative to it), as the preset's error.
    let bad = |r: Refusal| Error::refused(preset_path, r.under(&here)).in_object(&o.name);
    // An error met building the field `field` of the object (`material`, or none for the
    // object's own maps, whose errors name `bump.height`): its field below the object's, a
    // file's error (an image or mesh that cannot be read) the error of that field.
    let within = |field: Option<&'static str>| {
        let prefix = field.map_or_else(|| here.clone(), |f| here.clone().then(f));
        move |e: Error| e.under(preset_path, &prefix).in_object(&o.name)
    };
    let transform = transform(&o.transform).map_err(|r| bad(r.under(&"transform".into())))?;
    let shape = match (&o.shape, &o.displace) {
        (ShapeDesc::Mesh { path, shading }, displace) => {
            if path.is_empty() {
                return Err(bad(Refusal::new(
                    FieldPath::field("shape").then("path"),
                    "is empty: name a PLY or OBJ file",
                )));
            }
            let file = base.join(path);
            let mut mesh = cache.mesh(&file).map_err(within(Some("shape")))?;
            if let Some(d) = displace {
                mesh = displaced_mesh(&mesh, &file, d, base, cache)
                    .map_err(within(Some("displace")))?;
            }
            Shape::Mesh(MeshShape {
                mesh,
                shading: *shading,
            })
        }
        (generic, Some(_)) => {
            return Err(bad(Refusal::new(
                "displace".into(),
                format!(
                    "a displacement map needs a Mesh shape, and {} is a generic shape; use a \
                     mesh (which is subdivided and displaced at load), or a bump map (bump: \
                     ...) for the look without moving the surface",
                    generic.kind()
                ),
            )));
        }
        (generic, None) => generic.generic().ok_or_else(|| {
            bad(Refusal::new(
                "shape".into(),
                format!("{generic:?} is not a generic shape"),
            ))
        })?,
    };
    let mesh = match &shape {
        Shape::Mesh(m) => Some(&*m.mesh),
        _ => None,
    };
    let in_material = |r: Refusal| bad(r.under(&"material".into()));
    let material_desc = resolve_mesh_material(&o.material, mesh).map_err(in_material)?;
    if let Some(mesh) = mesh {
        check_uv_mapping(&material_desc, mesh).map_err(in_material)?;
        // The maps read (u, v) the same way: a clip, bump or normal map under `Uv` on a mesh
        // without it is refused like the material's textures.
        if !mesh.has_uv()
            && let Some((field, what)) = o.textures().into_iter().find_map(|(f, t)| {
                let what = t.mapping()?.reads_shape_uv()?;
                (!f.to_string().starts_with("material")).then_some((f, what))
            })
        {
            return Err(bad(no_uv(field, mesh, what)));
        }
    }
    let material = material(&material_desc, base, cache).map_err(within(Some("material")))?;
    let name = match (&o.shape, o.name.is_empty()) {
        (_, false) => o.name.clone(),
        (ShapeDesc::Mesh { path, .. }, true) => format!("{path} {i}"),
        (s, true) => format!("{s:?} {i}"),
    };
    let clip = match &o.alpha {
        None => None,
        Some(a) => match scalar("alpha", a, base, cache).map_err(within(None))? {
            // Solid everywhere: no clip map at all.
            Scalar::Const(v) if v >= 1.0 => None,
            s => Some(s),
        },
    };
    let bump = match &o.bump {
        None => None,
        Some(b) => bump(b, base, cache).map_err(within(None))?,
    };
    let normal_map = match &o.normal {
        None => None,
        Some(_) if o.bump.is_some() => {
            return Err(bad(Refusal::new(
                FieldPath::root(),
                "has both a bump map and a normal map; an object has one or the other",
            )));
        }
        Some(n) => Some(normal_map(n, base, cache).map_err(within(None))?),
    };
    let perturbation = bump
        .map(Perturbation::Bump)
        .or(normal_map.map(Perturbation::Normal));
    let needs_differentials = material.needs_differentials()
        || clip.as_ref().is_some_and(Scalar::needs_differentials)
        || perturbation
            .as_ref()
            .is_some_and(Perturbation::needs_differentials);
    let mut object = Object::new(shape, transform, material_index, name);
    object.casts_shadows = o.casts_shadows.unwrap_or(material.is_lit());
    Ok(BuiltObject {
        object,
        material,
        surface: Surface { clip, perturbation },
        needs_differentials,
    })
}
