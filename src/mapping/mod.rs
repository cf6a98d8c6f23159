//! Mappings: the lecture's `Mapping::get_texel_coordinates`, split into (u, v) with analytic
//! derivatives (this module) and the texel lookup (in [`crate::texture`]).
//!
//! Every mapping takes the hit point in the generic object's space and returns (u, v) in the
//! lecture's convention (v = 0 at the bottom of the image) together with their gradients with
//! respect to that point, by the chain rule; the screen-space derivatives follow from the hit's
//! dp/dx and dp/dy. No finite differences: those jump across the seam (u going 1 -> 0).

//!
//! Each mapping is one file (`rectangular.rs`, `cylindrical.rs`, `spherical.rs`,
//! `light_probe.rs`, `panoramic.rs`, `mirror_ball.rs`, `uv.rs`; a student's formulas in
//! `formula/`) implementing `Map`: its (u, v) with gradients, written once over pulp's `Simd`
//! so the renderer runs it at every width (1 lane on the scalar path, 16 on AVX-512), its worked
//! f64 formulas, the lecture's formula text, its diagram's angles, its family for the exercises'
//! hints and its seam and pole properties. `with_map!` is the one match from [`Mapping`] to
//! those files: a new mapping is a new file, a variant, and the arm the compiler asks for there.

mod cylindrical;
mod explain;
pub mod formula;
mod light_probe;
mod mirror_ball;
mod panoramic;
mod rectangular;
mod shared;
mod spherical;
mod uv;

pub use explain::{explain_mapping, explain_mapping_f64, explain_number, map_uv_f64};
pub use formula::{DerivativeKind, FormulaError, FormulaMapping};

use crate::math::lanes::{F, V3, finite, select};
use crate::math::{Vec2, Vec3A};
use glam::{DVec2, DVec3};
use pulp::Simd;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// A texture's mapping at run time: a built-in [`Mapping`] or a student's formulas, compiled
/// once when the scene is built.
#[derive(Clone, Debug, PartialEq)]
pub enum AnyMapping {
    /// One of the lecture's mappings.
    Builtin(Mapping),
    /// `u = ..., v = ...` as written (see [`formula`]).
    Formula(Arc<FormulaMapping>),
}

impl From<Mapping> for AnyMapping {
    fn from(m: Mapping) -> Self {
        Self::Builtin(m)
    }
}

impl AnyMapping {
    /// The menu name: the built-in mapping's, or `formula`.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::Builtin(m) => crate::names::Named::name(*m),
            Self::Formula(_) => "formula",
        }
    }

    /// The built-in mapping, `None` for a formula.
    #[must_use]
    pub const fn builtin(&self) -> Option<Mapping> {
        match self {
            Self::Builtin(m) => Some(*m),
            Self::Formula(_) => None,
        }
    }

    /// Whether u wraps around a seam regardless of the texture's wrap mode (a formula's
    /// coordinates follow the texture's own wrap mode).
    #[must_use]
    pub const fn u_is_periodic(&self) -> bool {
        match self {
            Self::Builtin(m) => m.u_is_periodic(),
            Self::Formula(_) => false,
        }
    }

    /// Whether v clamps regardless of the wrap mode.
    #[must_use]
    pub const fn v_clamps(&self) -> bool {
        match self {
            Self::Builtin(m) => m.v_clamps(),
            Self::Formula(_) => false,
        }
    }

    /// Texture coordinates of a hit with their screen-space derivatives, as
    /// [`Mapping::map_with_differentials`]. A formula reads the shape's own (u, v) as mesh_u,
    /// mesh_v (a mesh's vertex coordinates, else the `natural` mapping); where it is not
    /// finite, (u, v) is NaN (the texture marks the pixel).
    #[must_use]
    #[inline]
    pub fn map_with_differentials(
        &self,
        p: Vec3A,
        dpdx: Vec3A,
        dpdy: Vec3A,
        shape_uv: Option<(Vec2, Option<(Vec3A, Vec3A)>)>,
        natural: Mapping,
    ) -> TexCoord {
        match self {
            Self::Builtin(m) => m.map_with_differentials(p, dpdx, dpdy, shape_uv, natural),
            Self::Formula(f) => {
                let mesh = if f.reads_mesh() {
                    let tc = Mapping::Uv.map_with_differentials(p, dpdx, dpdy, shape_uv, natural);
                    (tc.uv, tc.duvdx, tc.duvdy)
                } else {
                    (Vec2::ZERO, Vec2::ZERO, Vec2::ZERO)
                };
                f.tex_coord(p, dpdx, dpdy, mesh)
            }
        }
    }
}

/// How a hit point becomes texture coordinates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[derive(Serialize, Deserialize)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum Mapping {
    /// The generic rectangle: u = (z + 1) / 2, v = (x + 1) / 2. Points off the rectangle give
    /// coordinates outside [0, 1] and the texture's wrap mode decides (so a plane tiles).
    #[strum(
        message = "Projects the texture along y onto the generic rectangle (x, z) in [-1, 1]^2."
    )]
    Rectangular,
    /// phi = atan2(x, z) in [0, 2 pi), u = phi / 2 pi, v = (y + 1) / 2.
    #[strum(
        message = "Wraps the texture once around the y axis; v follows the height y in [-1, 1]."
    )]
    Cylindrical,
    /// u as cylindrical, theta = acos(y), v = 1 - theta / pi (the Earth).
    #[default]
    #[strum(message = "Latitude-longitude (equirectangular) map: u is longitude, v is latitude.")]
    Spherical,
    /// The lecture's light-probe (angular) map: alpha = acos(z), r = alpha / pi,
    /// u = (1 + r cos beta) / 2, v = (1 + r sin beta) / 2.
    #[strum(
        message = "Angular light-probe map: the distance from the image centre is the angle from +z."
    )]
    LightProbe,
    /// The light-probe map with z flipped (alpha = acos(-z)), for probes made from panorama
    /// photographs, which are mirror reversals of a photographed ball.
    #[strum(message = "The light-probe map with z flipped, for probes made from panoramas.")]
    Panoramic,
    /// A mirror-ball probe seen from +z: r = sin(alpha / 2) instead of alpha / pi
    /// (reads `texplore probe --format mirror-ball`).
    #[strum(message = "Mirror-ball probe: the image of a reflective sphere photographed from +z.")]
    MirrorBall,
    /// The (u, v) the shape carries: a mesh's vertex coordinates, or the shape's own natural
    /// parameterisation (spherical on spheres, cylindrical on cylinders, rectangular on planes).
    #[strum(
        message = "The shape's own (u, v): a mesh's vertex coordinates, or its natural parameterisation."
    )]
    Uv,
}

impl crate::names::Named for Mapping {
    const WHAT: &'static str = "mapping";
}

/// One mapping, in its own file: everything texplore knows of it.
pub(crate) trait Map {
    /// Whether u wraps around (the seam of a closed surface): filters then read across it.
    const U_PERIODIC: bool;
    /// Whether v must clamp regardless of the wrap mode (the spherical map's poles).
    const V_CLAMPS: bool;
    /// Which family the exercises' hints speak of it as.
    const FAMILY: Family;
    /// The lecture's formulas for u and v in texplore's formula language (`None` where the
    /// lecture writes none out).
    const LECTURE: Option<(&'static str, &'static str)>;
    /// (u, v) per lane and, with `GRAD`, their gradients with respect to the object-space
    /// point (zero without): the renderer's formulas, the same bits at every width. Lanes
    /// whose (u, v) are not finite are made (0.5, 0.5) by [`Mapping::map_lanes`].
    fn lanes<S: Simd, const GRAD: bool>(s: S, p: &V3<S>) -> Mapped<S>;
    /// The formulas worked in f64 with `p`'s numbers, writing their lines to `out` when it is
    /// `Some` (the renderer's (u, v) up to f32 rounding).
    fn worked(p: DVec3, out: &mut Option<Vec<String>>) -> DVec2;
    /// The angles its formula goes through at `p`, for the mapping diagram.
    fn angles(p: DVec3) -> MappingAngles;
}

/// The families of built-in mappings, as the exercises' hints speak of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// The rectangular map: u from z, v from x.
    Rectangle,
    /// The cylindrical map: u around y, v up y.
    Cylinder,
    /// The spherical map (and `uv`, which is spherical on the sphere).
    Sphere,
    /// The light probe and its panoramic and mirror-ball variants.
    Probe,
}

/// Runs `$body` with `$M` naming the [`Map`] of `$mapping`: the one match from a [`Mapping`]
/// to its file.
macro_rules! with_map {
    ($mapping:expr, $M:ident => $body:expr) => {
        match $mapping {
            Mapping::Rectangular => {
                type $M = $crate::mapping::rectangular::Rectangular;
                $body
            }
            Mapping::Cylindrical => {
                type $M = $crate::mapping::cylindrical::Cylindrical;
                $body
            }
            Mapping::Spherical => {
                type $M = $crate::mapping::spherical::Spherical;
                $body
            }
            Mapping::LightProbe => {
                type $M = $crate::mapping::light_probe::LightProbe;
                $body
            }
            Mapping::Panoramic => {
                type $M = $crate::mapping::panoramic::Panoramic;
                $body
            }
            Mapping::MirrorBall => {
                type $M = $crate::mapping::mirror_ball::MirrorBall;
                $body
            }
            Mapping::Uv => {
                type $M = $crate::mapping::uv::Uv;
                $body
            }
        }
    };
}
pub(crate) use with_map;

/// (u, v) per lane with their gradients with respect to the object-space point.
#[derive(Clone, Copy, Debug)]
pub struct Mapped<S: Simd> {
    /// u per lane.
    pub u: F<S>,
    /// v per lane.
    pub v: F<S>,
    /// The gradient of u (zero unless asked for).
    pub grad_u: V3<S>,
    /// The gradient of v (zero unless asked for).
    pub grad_v: V3<S>,
}

/// The angles of the lecture's mapping formulas at one point, for the mapping diagram: what the
/// generic object's drawing marks. Each is `None` where the mapping has no such angle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MappingAngles {
    /// Azimuth about y from +z toward +x, in [0, 2 pi) (cylindrical, spherical).
    pub phi: Option<f64>,
    /// Polar angle from +y, in [0, pi] (spherical).
    pub theta: Option<f64>,
    /// Angle from the probe's axis (+z, or -z for the panoramic variant), in [0, pi].
    pub alpha: Option<f64>,
    /// Direction in the image disc, from +u toward +v (light probes).
    pub beta: Option<f64>,
    /// Distance from the image disc's centre, 0 to 1 (light probes).
    pub r: Option<f64>,
}

impl Mapping {
    /// Whether u wraps around (the seam of a closed surface): filters then read across it.
    #[must_use]
    pub const fn u_is_periodic(self) -> bool {
        with_map!(self, M => M::U_PERIODIC)
    }

    /// Whether v must clamp regardless of the wrap mode (the spherical map's poles).
    #[must_use]
    pub const fn v_clamps(self) -> bool {
        with_map!(self, M => M::V_CLAMPS)
    }

    /// The family the exercises' hints speak of.
    #[must_use]
    pub const fn family(self) -> Family {
        with_map!(self, M => M::FAMILY)
    }

    /// The lecture's formulas written in texplore's formula language: the same (u, v) as the
    /// built-in mapping to about 1e-15 on its surface. `None` for the mappings the lecture does
    /// not write out (the panoramic and mirror-ball variants, `uv`).
    ///
    /// The spherical and light-probe formulas divide by |p| before `acos`, as the renderer
    /// does: a hit point rounded to f32 can lie a hair outside the unit sphere, where
    /// acos(1.0000001) is NaN.
    #[must_use]
    pub const fn lecture_formula(self) -> Option<(&'static str, &'static str)> {
        with_map!(self, M => M::LECTURE)
    }

    /// The angles of the mapping's formula at `p` (the point the mapping reads): phi for the
    /// cylindrical map, phi and theta for the spherical, alpha, beta and r for the light
    /// probes; the rectangular map and a mesh's own (u, v) have none.
    #[must_use]
    pub fn angles(self, p: Vec3A) -> MappingAngles {
        let p = p.as_dvec3();
        with_map!(self, M => M::angles(p))
    }

    /// (u, v) and their gradients with respect to the object-space point `p`.
    ///
    /// `Uv` is not handled here (it needs the shape's coordinates): see
    /// [`Mapping::map_with_differentials`].
    #[must_use]
    #[inline]
    pub fn map_point(self, p: Vec3A) -> MappedPoint {
        self.map_one::<true>(p)
    }

    /// (u, v) alone, without gradients: what [`Mapping::map_point`] returns as `uv`, bit for
    /// bit, for renders whose filters need no footprint (skips the gradients' divisions).
    #[must_use]
    #[inline]
    pub fn map_uv(self, p: Vec3A) -> Vec2 {
        self.map_one::<false>(p).uv
    }

    /// [`Mapping::map_lanes`] at width 1.
    #[inline]
    fn map_one<const GRAD: bool>(self, p: Vec3A) -> MappedPoint {
        let m = self.map_lanes::<pulp::Scalar, GRAD>(pulp::Scalar, &V3::one(p));
        MappedPoint {
            uv: Vec2::new(m.u, m.v),
            grad_u: m.grad_u.vec(),
            grad_v: m.grad_v.vec(),
        }
    }

    /// (u, v) per lane of `p` and, with `GRAD`, their gradients: the mapping's own file's
    /// formulas, then (0.5, 0.5) with zero gradients wherever (u, v) is not finite (NaN input:
    /// a corrupt vertex, an overflowed transform: still a defined answer).
    #[must_use]
    #[inline(always)]
    pub fn map_lanes<S: Simd, const GRAD: bool>(self, s: S, p: &V3<S>) -> Mapped<S> {
        let m = with_map!(self, M => M::lanes::<S, GRAD>(s, p));
        let ok = s.and_m32s(finite(s, m.u), finite(s, m.v));
        let (half, zero) = (s.splat_f32s(0.5), V3::splat(s, Vec3A::ZERO));
        Mapped {
            u: select(s, ok, m.u, half),
            v: select(s, ok, m.v, half),
            grad_u: if GRAD {
                V3::select(s, ok, &m.grad_u, &zero)
            } else {
                zero
            },
            grad_v: if GRAD {
                V3::select(s, ok, &m.grad_v, &zero)
            } else {
                zero
            },
        }
    }

    /// Texture coordinates of a hit with their screen-space derivatives.
    ///
    /// `p` is the object-space hit point, `dpdx`/`dpdy` its offsets to the neighbouring pixels'
    /// hits (zero when unknown), `shape_uv` the coordinates the shape carries (mesh vertices) with
    /// the triangle's dp/du and dp/dv, and `natural` the mapping that is the shape's own
    /// parameterisation, which [`Mapping::Uv`] uses when the shape carries none.
    #[must_use]
    #[inline]
    pub fn map_with_differentials(
        self,
        p: Vec3A,
        dpdx: Vec3A,
        dpdy: Vec3A,
        shape_uv: Option<(Vec2, Option<(Vec3A, Vec3A)>)>,
        natural: Self,
    ) -> TexCoord {
        let mapping = match (self, shape_uv) {
            (Self::Uv, Some((uv, dpduv))) => {
                let (duvdx, duvdy) = match dpduv {
                    Some((dpdu, dpdv)) => (
                        solve_uv_offset(dpdu, dpdv, dpdx),
                        solve_uv_offset(dpdu, dpdv, dpdy),
                    ),
                    None => (Vec2::ZERO, Vec2::ZERO),
                };
                return TexCoord { uv, duvdx, duvdy };
            }
            (Self::Uv, None) => natural,
            (m, _) => m,
        };
        if dpdx == Vec3A::ZERO && dpdy == Vec3A::ZERO {
            // No footprint asked for (nearest and bilinear filters): the derivatives would be
            // zero anyway, so skip the gradients.
            return TexCoord {
                uv: mapping.map_uv(p),
                duvdx: Vec2::ZERO,
                duvdy: Vec2::ZERO,
            };
        }
        let m = mapping.map_point(p);
        TexCoord::from_gradients(m.uv, m.grad_u, m.grad_v, dpdx, dpdy)
    }
}

/// (u, v) at a point with the gradients of u and v with respect to the object-space point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MappedPoint {
    /// Texture coordinates, v = 0 at the bottom of the image.
    pub uv: Vec2,
    /// Gradient of u with respect to the object-space hit point.
    pub grad_u: Vec3A,
    /// Gradient of v with respect to the object-space hit point.
    pub grad_v: Vec3A,
}

/// Texture coordinates with their derivatives along the screen's x and y (one pixel each).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TexCoord {
    /// Texture coordinates, v = 0 at the bottom of the image.
    pub uv: Vec2,
    /// d(u, v)/dx: change to the pixel on the right.
    pub duvdx: Vec2,
    /// d(u, v)/dy: change to the pixel below.
    pub duvdy: Vec2,
}

/// A texture's (u, v) transform, applied after the mapping: scale, then rotate (degrees,
/// counter-clockwise about the origin of (u, v)), then offset. `scale: (4, 4)` tiles the
/// texture four times across the mapping's unit square (the wrap mode then decides what lies
/// beyond 1, on every shape). A preset writes `uv: (scale: (4, 2), rotate: 30, offset: (0.5, 0))`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct UvTransform {
    /// Multiplies u and v (not zero); default `(1, 1)`.
    pub scale: Vec2,
    /// Counter-clockwise rotation of the scaled (u, v), degrees; default 0.
    pub rotate: f32,
    /// Added last; default `(0, 0)`.
    pub offset: Vec2,
}

impl Default for UvTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl UvTransform {
    /// Leaves (u, v) as the mapping gives them.
    pub const IDENTITY: Self = Self {
        scale: Vec2::ONE,
        rotate: 0.0,
        offset: Vec2::ZERO,
    };

    /// Whether this is [`UvTransform::IDENTITY`] (a preset then leaves it out).
    #[must_use]
    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }

    /// The affine map this stands for, or `None` for the identity (which then costs nothing).
    #[must_use]
    pub fn affine(&self) -> Option<UvAffine> {
        if self.is_identity() {
            return None;
        }
        let (sin, cos) = self.rotate.to_radians().sin_cos();
        let (su, sv) = (self.scale.x, self.scale.y);
        // Rotation times diagonal scale, by columns.
        let matrix = glam::Mat2::from_cols(
            Vec2::new(cos * su, sin * su),
            Vec2::new(-sin * sv, cos * sv),
        );
        Some(UvAffine {
            matrix,
            offset: self.offset,
        })
    }
}

/// The affine map of a [`UvTransform`]: `uv' = matrix uv + offset`. Derivatives transform by
/// the matrix alone (the chain rule), so filters see the transformed footprint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvAffine {
    /// Scale then rotation.
    pub matrix: glam::Mat2,
    /// Added after the matrix.
    pub offset: Vec2,
}

impl UvAffine {
    /// (u, v) and their screen-space derivatives after the transform.
    #[must_use]
    #[inline]
    pub fn apply(&self, tc: TexCoord) -> TexCoord {
        let uv = self.matrix * tc.uv + self.offset;
        TexCoord {
            uv: if uv.is_finite() { uv } else { Vec2::ZERO },
            duvdx: self.matrix * tc.duvdx,
            duvdy: self.matrix * tc.duvdy,
        }
        .bounded()
    }
}

/// The largest footprint a filter is asked for: the whole texture. Singular points (the poles,
/// the probe's rim) have unbounded derivatives; this keeps every footprint finite.
pub const MAX_FOOTPRINT: f32 = 1.0;

impl TexCoord {
    /// (u, v) with their screen-space derivatives from the gradients of u and v and the
    /// object-space offsets `dpdx`, `dpdy` to the neighbouring pixels' hits, [bounded]: zero
    /// derivatives where there is no footprint (both offsets zero), whatever the gradients.
    ///
    /// [bounded]: TexCoord::bounded
    #[must_use]
    #[inline]
    pub fn from_gradients(
        uv: Vec2,
        grad_u: Vec3A,
        grad_v: Vec3A,
        dpdx: Vec3A,
        dpdy: Vec3A,
    ) -> Self {
        if dpdx == Vec3A::ZERO && dpdy == Vec3A::ZERO {
            return Self {
                uv,
                duvdx: Vec2::ZERO,
                duvdy: Vec2::ZERO,
            };
        }
        Self {
            uv,
            duvdx: Vec2::new(grad_u.dot(dpdx), grad_v.dot(dpdx)),
            duvdy: Vec2::new(grad_u.dot(dpdy), grad_v.dot(dpdy)),
        }
        .bounded()
    }

    /// Derivatives clamped to [`MAX_FOOTPRINT`] and cleaned of NaN.
    #[must_use]
    #[inline]
    pub fn bounded(self) -> Self {
        let clean = |d: Vec2| {
            let d = Vec2::new(
                if d.x.is_finite() { d.x } else { 0.0 },
                if d.y.is_finite() { d.y } else { 0.0 },
            );
            d.clamp(Vec2::splat(-MAX_FOOTPRINT), Vec2::splat(MAX_FOOTPRINT))
        };
        Self {
            uv: self.uv,
            duvdx: clean(self.duvdx),
            duvdy: clean(self.duvdy),
        }
    }
}

/// Solves `dpdu * du + dpdv * dv = dp` in the least-squares sense (pbrt's approach for meshes).
fn solve_uv_offset(dpdu: Vec3A, dpdv: Vec3A, dp: Vec3A) -> Vec2 {
    let (a, b, c) = (dpdu.dot(dpdu), dpdu.dot(dpdv), dpdv.dot(dpdv));
    let det = a * c - b * b;
    if det.abs() < 1e-30 || !det.is_finite() {
        return Vec2::ZERO;
    }
    let (r0, r1) = (dpdu.dot(dp), dpdv.dot(dp));
    let out = Vec2::new(c * r0 - b * r1, a * r1 - b * r0) / det;
    if out.is_finite() { out } else { Vec2::ZERO }
}

#[cfg(test)]
mod tests;
