//! Mappings: the lecture's `Mapping::get_texel_coordinates`, split into (u, v) with analytic
//! derivatives (this module) and the texel lookup (in [`crate::texture`]).
//!
//! Every mapping takes the hit point in the generic object's space and returns (u, v) in the
//! lecture's convention (v = 0 at the bottom of the image) together with their gradients with
//! respect to that point, by the chain rule; the screen-space derivatives follow from the hit's
//! dp/dx and dp/dy. No finite differences: those jump across the seam (u going 1 -> 0).

mod explain;
pub mod formula;

pub use explain::{explain_mapping, explain_mapping_f64, explain_number, map_uv_f64};
pub use formula::{DerivativeKind, FormulaError, FormulaMapping};

use crate::math::{PI, TAU, Vec2, Vec3A, atan2};
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

impl Mapping {
    /// Whether u wraps around (the seam of a closed surface): filters then read across it.
    #[must_use]
    pub const fn u_is_periodic(self) -> bool {
        matches!(self, Self::Cylindrical | Self::Spherical)
    }

    /// Whether v must clamp regardless of the wrap mode (the spherical map's poles).
    #[must_use]
    pub const fn v_clamps(self) -> bool {
        matches!(self, Self::Spherical)
    }

    /// (u, v) and their gradients with respect to the object-space point `p`.
    ///
    /// `Uv` is not handled here (it needs the shape's coordinates): see
    /// [`Mapping::map_with_differentials`].
    #[must_use]
    #[inline]
    pub fn map_point(self, p: Vec3A) -> MappedPoint {
        self.map_impl::<true>(p)
    }

    /// (u, v) alone, without gradients: what [`Mapping::map_point`] returns as `uv`, bit for
    /// bit, for renders whose filters need no footprint (skips the gradients' divisions).
    #[must_use]
    #[inline]
    pub fn map_uv(self, p: Vec3A) -> Vec2 {
        self.map_impl::<false>(p).uv
    }

    /// Both of the above; with `GRAD` false the spherical and cylindrical maps leave the
    /// gradients zero instead of computing them.
    #[inline]
    fn map_impl<const GRAD: bool>(self, p: Vec3A) -> MappedPoint {
        let m = match self {
            Self::Rectangular => rectangular(p),
            Self::Cylindrical => cylindrical::<GRAD>(p),
            Self::Spherical | Self::Uv => spherical::<GRAD>(p),
            Self::LightProbe => probe(p, false, ProbeCurve::Angular),
            Self::Panoramic => probe(p, true, ProbeCurve::Angular),
            Self::MirrorBall => probe(p, false, ProbeCurve::MirrorBall),
        };
        if m.uv.is_finite() {
            m
        } else {
            // NaN input (a corrupt vertex, an overflowed transform): still a defined answer.
            MappedPoint {
                uv: Vec2::splat(0.5),
                grad_u: Vec3A::ZERO,
                grad_v: Vec3A::ZERO,
            }
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
        TexCoord {
            uv: m.uv,
            duvdx: Vec2::new(m.grad_u.dot(dpdx), m.grad_v.dot(dpdx)),
            duvdy: Vec2::new(m.grad_u.dot(dpdy), m.grad_v.dot(dpdy)),
        }
        .bounded()
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

fn rectangular(p: Vec3A) -> MappedPoint {
    MappedPoint {
        uv: Vec2::new((p.z + 1.0) * 0.5, (p.x + 1.0) * 0.5),
        grad_u: Vec3A::new(0.0, 0.0, 0.5),
        grad_v: Vec3A::new(0.5, 0.0, 0.0),
    }
}

/// The azimuth u = atan2(x, z) / 2 pi in [0, 1], and its gradient; bounded on the axis.
#[inline]
fn azimuth<const GRAD: bool>(x: f32, z: f32) -> (f32, Vec3A) {
    let mut phi = atan2(x, z);
    if phi < 0.0 {
        phi += TAU;
    }
    // u in [0, 1): u = 1 and u = 0 are one seam, read as u = 0 (the texture's first column,
    // where the wrap used to send u = 1 before [0, 1] was closed). phi + 2 pi can round up to
    // exactly 2 pi; `+ 0.0` turns the -0 of atan2(-0, z) into 0.
    let u = phi / TAU;
    let u = if u < 1.0 { u.max(0.0) + 0.0 } else { 0.0 };
    let rho2 = x * x + z * z;
    let grad = if !GRAD {
        Vec3A::ZERO
    } else if rho2 > 0.0 {
        Vec3A::new(z, 0.0, -x) / (TAU * rho2)
    } else {
        Vec3A::ZERO // exactly on the axis u is undefined; any value is as good
    };
    (u, grad)
}

#[inline]
fn cylindrical<const GRAD: bool>(p: Vec3A) -> MappedPoint {
    let (u, grad_u) = match rescaled(Vec3A::new(p.x, 0.0, p.z)) {
        Some((q, scale)) => {
            let (u, g) = azimuth::<GRAD>(q.x, q.z);
            (u, g / scale)
        }
        None => (0.0, Vec3A::ZERO),
    };
    let v = (p.y + 1.0) * 0.5;
    MappedPoint {
        uv: Vec2::new(u, if v.is_nan() { 0.5 } else { v.clamp(0.0, 1.0) }),
        grad_u,
        grad_v: Vec3A::new(0.0, 0.5, 0.0),
    }
}

#[inline]
fn spherical<const GRAD: bool>(p: Vec3A) -> MappedPoint {
    let Some((q, scale)) = rescaled(p) else {
        return MappedPoint {
            uv: Vec2::new(0.0, 0.5),
            grad_u: Vec3A::ZERO,
            grad_v: Vec3A::ZERO,
        };
    };
    let (u, grad_u) = azimuth::<GRAD>(q.x, q.z);
    // theta = acos(y / |p|), written as atan2(rho, y): exact for points off the unit sphere
    // and never the NaN of acos(1 + 1e-12).
    let rho2 = q.x * q.x + q.z * q.z;
    let rho = rho2.sqrt();
    let r2 = rho2 + q.y * q.y;
    let theta = atan2(rho, q.y);
    let v = (1.0 - theta / PI).clamp(0.0, 1.0);
    let grad_v = if !GRAD {
        Vec3A::ZERO
    } else if rho > 0.0 {
        // d theta/dq = (y x / rho, -rho, y z / rho) / r^2 ; v = 1 - theta / pi
        -Vec3A::new(q.y * q.x / rho, -rho, q.y * q.z / rho) / (PI * r2)
    } else {
        Vec3A::ZERO // exactly at a pole the direction of steepest change is undefined
    };
    MappedPoint {
        uv: Vec2::new(u, v),
        grad_u: grad_u / scale,
        grad_v: grad_v / scale,
    }
}

/// `p` divided by its largest component, so squares neither overflow (huge points) nor
/// underflow (subnormal ones); `None` for the origin and for NaN or infinite input.
#[inline]
fn rescaled(p: Vec3A) -> Option<(Vec3A, f32)> {
    let s = p.abs().max_element();
    (s > 0.0 && s.is_finite()).then(|| (p / s, s))
}

#[derive(Clone, Copy)]
enum ProbeCurve {
    /// r = alpha / pi (the lecture).
    Angular,
    /// r = sin(alpha / 2).
    MirrorBall,
}

/// The light-probe maps. With n = p / |p| and d = sqrt(nx^2 + ny^2), the lecture's
/// u = (1 + r(alpha) nx / d) / 2 is written as u = (1 + g nx) / 2 with g = r(alpha) / d, which is
/// smooth through the z axis (g -> 1 / pi): no division by zero where the lecture's cos beta
/// is 0 / 0. Only the antipode (alpha = pi), where the whole rim meets, is singular; it maps to
/// the rim point beta = 0, (u, v) = (1, 0.5).
fn probe(p: Vec3A, flip_z: bool, curve: ProbeCurve) -> MappedPoint {
    let Some((q, scale)) = rescaled(p) else {
        return MappedPoint {
            uv: Vec2::splat(0.5),
            grad_u: Vec3A::ZERO,
            grad_v: Vec3A::ZERO,
        };
    };
    let q_len = q.length();
    let n = q / q_len;
    let len = q_len * scale;
    let (x, y) = (n.x, n.y);
    let z = if flip_z { -n.z } else { n.z };
    let d = (x * x + y * y).sqrt();
    let alpha = atan2(d, z);
    // g = r / d and its derivatives with respect to (x, y, z) of the unit vector.
    let (g, dg_dd_over_d, dg_dz) = match curve {
        ProbeCurve::Angular => {
            if d < 1e-2 && z > 0.0 {
                // Series about the axis: alpha / d = 1 + d^2 / 6 ..., dg/dd / d = (2/3 + d^2/5)/pi
                let g = (1.0 + d * d / 6.0) / PI;
                (g, -(2.0 / 3.0 + d * d / 5.0) / PI, -1.0 / PI)
            } else if d > 0.0 {
                let g = alpha / (PI * d);
                (g, (z - alpha / d) / (PI * d * d), -1.0 / PI)
            } else {
                return antipode(flip_z);
            }
        }
        ProbeCurve::MirrorBall => {
            // r = sin(alpha / 2) = sqrt((1 - z) / 2); g = r / d = 1 / (2 cos(alpha / 2))
            // = 1 / sqrt(2 (1 + z)).
            let s2 = 2.0 * (1.0 + z);
            if s2 <= 1e-12 {
                return antipode(flip_z);
            }
            let g = 1.0 / s2.sqrt();
            (g, 0.0, -g * g * g)
        }
    };
    let half = 0.5;
    let u = (half + half * g * x).clamp(0.0, 1.0);
    let v = (half + half * g * y).clamp(0.0, 1.0);
    // Gradient with respect to n (x, y, z treated as free), then projected onto the sphere's
    // tangent plane and divided by |p|.
    let dz = if flip_z { -dg_dz } else { dg_dz };
    let grad_g = Vec3A::new(x * dg_dd_over_d, y * dg_dd_over_d, dz);
    let gu = half * (Vec3A::new(g, 0.0, 0.0) + x * grad_g);
    let gv = half * (Vec3A::new(0.0, g, 0.0) + y * grad_g);
    let tangent = |gr: Vec3A| {
        let t = (gr - n * n.dot(gr)) / len;
        if t.is_finite() { t } else { Vec3A::ZERO }
    };
    MappedPoint {
        uv: Vec2::new(u, v),
        grad_u: tangent(gu),
        grad_v: tangent(gv),
    }
}

fn antipode(_flip_z: bool) -> MappedPoint {
    MappedPoint {
        uv: Vec2::new(1.0, 0.5),
        grad_u: Vec3A::ZERO,
        grad_v: Vec3A::ZERO,
    }
}

#[cfg(test)]
mod tests;
