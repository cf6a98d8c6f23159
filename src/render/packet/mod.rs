//! The packet path: coherent primary rays traced [`LANES`] at a time, struct-of-arrays, for
//! scenes made of what it supports; everything else takes the scalar path unchanged.
//!
//! A packet is up to [`LANES`] consecutive pixels of one row with the same sample index. Their
//! sample positions come from [`sample_position_and_cell`], as on the scalar path; the camera
//! rays, the transform into each object's space, the generic shapes' intersections, the nearest
//! hit, the world-space normal facing the viewer, the mapping, the (u, v) transform and the
//! shading (ambient, Lambert and Phong terms per light, glow) are computed lane-wise by the
//! kernels in [`super::lanes`], operation for operation as the scalar code computes them. Per
//! lane, the texel lookup (the existing `Texture::eval_tex_coord`: wrap, nearest or bilinear
//! index, the compact storage's decode) and each shadow ray (`Scene::occluded_except`, with the
//! same self-shadow rule as `Scene::shade_at_depth`) run the scalar code. A texture filtered
//! over the pixel's footprint (trilinear, EWA, footprint) is read per lane too, from the
//! lane's hit: its ray differentials ([`super::footprint_ray`], the sample's cell), their
//! footprint on the tangent plane and the scalar `Texture::eval`, as the scalar path reads it.
//!
//! Eligibility ([`PacketPlan::new`]) is decided once per pass from the scene: pinhole or
//! orthographic camera, the shaded view, no clip map, and only spheres, planes, rectangles and
//! disks. Within an eligible scene a lane whose hit
//! needs what the packet path lacks (a mirror, a textured coefficient, a bump or normal map) is
//! traced again by the scalar path ([`super::radiance_keyed_cell`]), exactly as before.
//!
//! Runtime dispatch: the pass runs inside [`pulp::Arch::dispatch`] (the token [`arch`] picks),
//! which calls it through a function compiled for the best instruction set the CPU has (AVX-512,
//! AVX2 + FMA, else the SSE2 baseline; NEON on aarch64), and hands the stages that token `S`:
//! the explicit kernels ([`super::lanes::wide`]) run `S::F32_LANES` lanes per instruction (16
//! on AVX-512, 8 on AVX2, 4 on NEON); under pulp's `Scalar` the stages take the lane loops.
//! Everything on the packet's hot path is `#[inline(always)]`, so it is compiled for that level.

// Lane loops index several arrays by the lane (`for i in 0..LANES`), the form the vectoriser
// reads best; `&` and `|` between lane conditions keep them branch-free (selects, not jumps).
#![allow(clippy::needless_range_loop)]

mod nearest;
mod stages;

use super::lanes::{self, F, Flat, LANES, V3};
use crate::camera::Projection;
use crate::geometry::Shape;
use crate::mapping::{AnyMapping, FormulaMapping, Mapping, UvAffine};
use crate::material::{Colour, Material, Scalar};
use crate::math::{Affine3A, INV_PI, Mat3A, Rgb, max_abs};
use crate::scene::{Scene, SimdMode, natural_mapping};
use crate::texture::{Texture, View};
use nearest::Nearest;
use std::fmt;

/// The instruction set the packet path runs on: pulp's best for this CPU
/// ([`pulp::Arch::new`]), except that AVX-512 gives way to AVX2 while a packet is narrower than
/// its 16 lanes (the explicit kernels would otherwise run every lane through pulp's `Scalar`).
#[must_use]
pub(crate) fn arch() -> pulp::Arch {
    let arch = pulp::Arch::new();
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    if let pulp::Arch::V4(v4) = arch
        && !LANES.is_multiple_of(16)
    {
        return pulp::Arch::V3(*v4);
    }
    arch
}

/// How wide `S` is, as [`simd_level`] says it.
struct Width;

impl pulp::WithSimd for Width {
    type Output = String;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> String {
        if S::IS_SCALAR {
            "the lane loops alone (no explicit kernels)".to_owned()
        } else {
            format!("explicit kernels {} lanes wide", S::F32_LANES)
        }
    }
}

/// The instruction set the packet path picks on this CPU and the explicit kernels' width
/// there, for `texplore bench`.
#[must_use]
pub fn simd_level() -> String {
    let arch = arch();
    let width = arch.dispatch(Width);
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    let name = match arch {
        pulp::Arch::V4(_) => "AVX-512 (x86-64-v4)",
        pulp::Arch::V3(_) => "AVX2 + FMA (x86-64-v3)",
        _ => "SSE2 (x86-64 baseline)",
    };
    #[cfg(target_arch = "aarch64")]
    let name = "NEON (aarch64)";
    #[cfg(not(any(target_arch = "x86", target_arch = "x86_64", target_arch = "aarch64")))]
    let name = "scalar (no SIMD dispatch on this architecture)";
    format!("{name}, {width}")
}

/// Why a scene takes the scalar path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ineligible(pub String);

impl fmt::Display for Ineligible {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// Which path a scene's primary rays take under `mode`: `Ok(())` for the packet path, or why
/// not.
///
/// # Errors
/// The reason the scene (or `mode`) sends it to the scalar path.
pub fn packet_eligibility(scene: &Scene, mode: SimdMode) -> Result<(), Ineligible> {
    PacketPlan::new(scene, mode).map(|_| ())
}

/// A generic shape the packet path intersects.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Sphere,
    Flat(Flat),
}

/// How the packet path shades one object's hits (constant coefficients).
#[derive(Clone, Copy, Debug)]
enum Response {
    /// Matte or Phong: ambient `ka`, `kd / pi`, the highlight and the glow.
    Lit {
        ka: f32,
        kd_pi: f32,
        specular: Option<(Rgb, f32)>,
        glow: Rgb,
    },
    /// Emissive: `ls` times the texture.
    Emissive { ls: f32 },
}

/// The texture and response of an object the packet path shades.
#[derive(Clone, Copy, Debug)]
struct Shading<'a> {
    texture: &'a Texture,
    /// The lane-wise nearest lookup, where the texture is an image read that way.
    nearest: Option<Nearest<'a>>,
    /// The mapping after `Uv` falls back to the shape's own (`None` for a constant).
    mapping: Option<LaneMapping<'a>>,
    affine: Option<UvAffine>,
    response: Response,
    /// Whether the texture is filtered over the pixel's footprint (trilinear, EWA, footprint):
    /// its lanes find their footprint from the ray differentials and read the texture per lane.
    footprint: bool,
    /// The shape's own mapping (what `Uv` and formulas read as mesh_u, mesh_v).
    natural: Mapping,
}

/// The mappings the packet path computes lane-wise ([`nearest::map_lanes`]); a texture under
/// any other mapping is shaded by the scalar path.
#[derive(Clone, Copy, Debug)]
enum LaneMapping<'a> {
    Spherical,
    Cylindrical,
    Rectangular,
    /// A student's formulas, run per lane on the compiled program (`FormulaMapping::map_uv`),
    /// with the shape's natural mapping as mesh_u, mesh_v.
    Formula(&'a FormulaMapping, Mapping),
}

impl LaneMapping<'_> {
    /// The lane-wise form of `mapping` on `shape` (`Uv` is the shape's own mapping), or `None`.
    /// Exhaustive on purpose: a new mapping must say here whether the packet path maps it.
    fn of(mapping: Mapping, shape: &Shape) -> Option<Self> {
        match mapping {
            Mapping::Spherical => Some(Self::Spherical),
            Mapping::Cylindrical => Some(Self::Cylindrical),
            Mapping::Rectangular => Some(Self::Rectangular),
            Mapping::Uv => match natural_mapping(shape) {
                Mapping::Uv => None,
                m => Self::of(m, shape),
            },
            Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall => None,
        }
    }
}

/// One object as the packet path sees it.
#[derive(Clone, Debug)]
struct ObjectPlan<'a> {
    kind: Kind,
    identity: bool,
    object_from_world: Affine3A,
    world_from_object: Affine3A,
    normal_to_world: Mat3A,
    normal_orthonormal: bool,
    /// The object's translation's largest coordinate, for the shadow offset.
    translation_max_abs: f32,
    /// `None`: lanes that hit this object take the scalar path.
    shading: Option<Shading<'a>>,
}

/// What the packet path needs of a scene, built once per pass.
#[derive(Clone, Debug)]
pub(crate) struct PacketPlan<'a> {
    scene: &'a Scene,
    orthographic: bool,
    objects: Vec<ObjectPlan<'a>>,
    /// Whether some object's shading has `footprint` set.
    footprint: bool,
}

fn constant(s: &Scalar) -> Option<f32> {
    match s {
        Scalar::Const(v) => Some(*v),
        Scalar::Texture(_) => None,
    }
}

fn constant_colour(c: &Colour) -> Option<Rgb> {
    match c {
        Colour::Const(v) => Some(*v),
        Colour::Texture(_) => None,
    }
}

/// The packet path's shading of `material` on `shape`, or `None` where it lacks something.
fn shading<'a>(material: &'a Material, shape: &Shape) -> Option<Shading<'a>> {
    let (texture, response) = match material {
        Material::Matte { ka, kd, cd } => (
            cd,
            Response::Lit {
                ka: constant(ka)?,
                kd_pi: constant(kd)? * INV_PI,
                specular: None,
                glow: Rgb::BLACK,
            },
        ),
        Material::Phong {
            ka,
            kd,
            cd,
            ks,
            cs,
            exp,
            ce,
        } => (
            cd,
            Response::Lit {
                ka: constant(ka)?,
                kd_pi: constant(kd)? * INV_PI,
                specular: Some((constant_colour(cs)? * constant(ks)?, constant(exp)?)),
                glow: constant_colour(ce)?,
            },
        ),
        Material::Emissive { ls, ce } => (ce, Response::Emissive { ls: constant(ls)? }),
        Material::Reflective { .. } => return None,
    };
    let mapping = match texture.mapping() {
        None => None,
        Some(AnyMapping::Builtin(m)) => Some(LaneMapping::of(*m, shape)?),
        Some(AnyMapping::Formula(f)) => Some(LaneMapping::Formula(f, natural_mapping(shape))),
    };
    Some(Shading {
        texture,
        nearest: Nearest::new(texture),
        mapping,
        affine: texture.uv_affine(),
        response,
        footprint: texture.needs_differentials(),
        natural: natural_mapping(shape),
    })
}

impl<'a> PacketPlan<'a> {
    /// The plan for `scene`, or why it takes the scalar path.
    pub(crate) fn new(scene: &'a Scene, mode: SimdMode) -> Result<Self, Ineligible> {
        let no = |why: &str| Err(Ineligible(why.to_owned()));
        if mode == SimdMode::Scalar {
            return no("the scalar path was asked for");
        }
        if scene.settings.view != View::Shaded {
            return no("a debug view");
        }
        if scene.has_clips() {
            return no("a clip map");
        }
        let orthographic = match scene.camera.projection {
            Projection::Pinhole { .. } => false,
            Projection::Orthographic { .. } => true,
            Projection::Fisheye { .. } | Projection::Spherical { .. } => {
                return no("a fisheye or spherical camera");
            }
        };
        if scene.objects.len() >= 0xffff {
            return no("more objects than edge keys");
        }
        let mut objects = Vec::with_capacity(scene.objects.len());
        for (i, o) in scene.objects.iter().enumerate() {
            let kind = match o.shape {
                Shape::Sphere => Kind::Sphere,
                Shape::Plane => Kind::Flat(Flat::Plane),
                Shape::Rectangle => Kind::Flat(Flat::Rectangle),
                Shape::Disk => Kind::Flat(Flat::Disk),
                Shape::Cylinder { .. } => return no("a cylinder"),
                Shape::Mesh(_) => return no("a mesh"),
            };
            let perturbed = scene
                .surfaces
                .get(i)
                .is_some_and(|s| s.perturbation.is_some());
            let shading = if perturbed {
                None
            } else {
                shading(&scene.materials[o.material], &o.shape)
            };
            objects.push(ObjectPlan {
                kind,
                identity: o.identity,
                object_from_world: o.object_from_world,
                world_from_object: o.world_from_object,
                normal_to_world: o.normal_to_world,
                normal_orthonormal: o.normal_orthonormal,
                translation_max_abs: max_abs(o.world_from_object.translation),
                shading,
            });
        }
        let footprint = objects
            .iter()
            .any(|o| o.shading.is_some_and(|s| s.footprint));
        Ok(Self {
            scene,
            orthographic,
            objects,
            footprint,
        })
    }

    /// Whether some object's texture is filtered over the pixel's footprint: then
    /// [`PacketPlan::trace`] needs each lane's sample cell.
    pub(crate) const fn needs_cells(&self) -> bool {
        self.footprint
    }

    /// The spherical map per lane: the explicit kernel at `S`'s width, or the lane loops
    /// where `S` is pulp's `Scalar` (which LLVM vectorises for the baseline instruction set).
    #[inline(always)]
    fn spherical<S: pulp::Simd>(s: S, p: &V3) -> (F, F) {
        if S::IS_SCALAR {
            lanes::spherical(p)
        } else {
            lanes::wide::spherical(s, p)
        }
    }

    /// The camera rays through the lanes' film positions (`Camera::primary_ray`).
    #[inline(always)]
    fn camera_rays(&self, px: &F, py: &F) -> (V3, V3) {
        let cam = &self.scene.camera;
        let (w, h) = (cam.width as f32, cam.height as f32);
        let scale = cam.pixel_scale();
        let [u, v, back] = cam.frame;
        let (mut x, mut y) = ([0.0; LANES], [0.0; LANES]);
        for i in 0..LANES {
            x[i] = (px[i] - 0.5 * w) * scale;
            y[i] = (0.5 * h - py[i]) * scale;
        }
        let mut o = V3::splat(cam.eye);
        let mut d = V3::splat(-back);
        if self.orthographic {
            // eye + x u + y v, summed left to right as glam does.
            for i in 0..LANES {
                o.x[i] = (cam.eye.x + x[i] * u.x) + y[i] * v.x;
                o.y[i] = (cam.eye.y + x[i] * u.y) + y[i] * v.y;
                o.z[i] = (cam.eye.z + x[i] * u.z) + y[i] * v.z;
            }
        } else {
            // x u + y v - back.
            for i in 0..LANES {
                d.x[i] = (x[i] * u.x + y[i] * v.x) - back.x;
                d.y[i] = (x[i] * u.y + y[i] * v.y) - back.y;
                d.z[i] = (x[i] * u.z + y[i] * v.z) - back.z;
            }
        }
        (o, d)
    }
}
