//! The spherical (latitude-longitude, equirectangular) map, the lecture's `SphericalMap` and the
//! Earth's: u as the cylindrical map's, theta = acos(y) from the north pole, v = 1 - theta / pi.
//! u is periodic (the seam is the meridian u = 0 = 1) and v clamps at the poles, where the
//! whole top and bottom rows of the image meet.

use super::explain::rescaled as rescaled_f64;
use super::explain::{POLE_THETA, azimuth as worked_azimuth, line, n, phi, unit_direction};
use super::shared::{azimuth, rescaled};
use super::{Family, Map, Mapped, MappingAngles};
use crate::math::lanes::{V3, atan2, clamp, neg, select};
use crate::math::{PI, Vec3A};
use glam::{DVec2, DVec3};
use pulp::Simd;

/// See the module documentation.
pub(crate) struct Spherical;

impl Map for Spherical {
    const U_PERIODIC: bool = true;
    const V_CLAMPS: bool = true;
    const FAMILY: Family = Family::Sphere;
    const LECTURE: Option<(&'static str, &'static str)> = Some((
        "fract(atan2(x, z) / tau)",
        "1 - acos(y / sqrt(x*x + y*y + z*z)) / pi",
    ));

    #[inline(always)]
    fn lanes<S: Simd, const GRAD: bool>(s: S, p: &V3<S>) -> Mapped<S> {
        let zero = s.splat_f32s(0.0);
        let zero3 = V3::splat(s, Vec3A::ZERO);
        let (q, scale, ok) = rescaled(s, p);
        let (u, grad_u) = azimuth::<S, GRAD>(s, q.x, q.z);
        // theta = acos(y / |p|), written as atan2(rho, y): exact for points off the unit sphere
        // and never the NaN of acos(1 + 1e-12).
        let rho2 = s.add_f32s(s.mul_f32s(q.x, q.x), s.mul_f32s(q.z, q.z));
        let rho = s.sqrt_f32s(rho2);
        let theta = atan2(s, rho, q.y);
        let pi = s.splat_f32s(PI);
        let v = clamp(
            s,
            s.sub_f32s(s.splat_f32s(1.0), s.div_f32s(theta, pi)),
            0.0,
            1.0,
        );
        let (grad_u, grad_v) = if GRAD {
            // d theta / dq = (y x / rho, -rho, y z / rho) / r^2; v = 1 - theta / pi. Exactly at
            // a pole the direction of steepest change is undefined: zero.
            let k = s.mul_f32s(pi, s.add_f32s(rho2, s.mul_f32s(q.y, q.y)));
            let g = V3 {
                x: neg(s, s.div_f32s(s.mul_f32s(q.y, q.x), rho)),
                y: rho,
                z: neg(s, s.div_f32s(s.mul_f32s(q.y, q.z), rho)),
            }
            .div(s, k);
            let pole = s.not_m32s(s.greater_than_f32s(rho, zero));
            let g = V3::select(s, pole, &zero3, &g);
            (
                V3::select(s, ok, &grad_u.div(s, scale), &zero3),
                V3::select(s, ok, &g.div(s, scale), &zero3),
            )
        } else {
            (zero3, zero3)
        };
        Mapped {
            u: select(s, ok, u, zero),
            v: select(s, ok, v, s.splat_f32s(0.5)),
            grad_u,
            grad_v,
        }
    }

    fn worked(p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
        let Some((q, scale)) = rescaled_f64(p) else {
            line!(
                out,
                "p = (0, 0, 0) or not finite: no direction, (u, v) = (0, 0.5) as the renderer"
            );
            return DVec2::new(0.0, 0.5);
        };
        let nq = unit_direction(q, scale, out);
        let u = worked_azimuth(nq.x, nq.z, out);
        // theta = acos(y / |p|), computed as atan2(sqrt(x^2 + z^2), y) (exact off the sphere,
        // as the renderer).
        let theta = q.x.hypot(q.z).atan2(q.y);
        let pi = std::f64::consts::PI;
        if (theta.min(pi - theta)) < POLE_THETA {
            // acos is ill-conditioned at +-1: y = cos(0.0077) = 0.99997 prints as 1.0000, and
            // acos(1.0000) = 0.0077 looks wrong. Show the formula the renderer runs.
            line!(
                out,
                "near the {} pole: theta = atan2(sqrt(x^2 + z^2), y) = atan2({}, {}) = {} rad",
                if q.y > 0.0 { "north" } else { "south" },
                n(nq.x.hypot(nq.z)),
                n(nq.y),
                n(theta)
            );
            line!(
                out,
                "(acos(y) is the same angle, but y is within {} of {}1 here, where acos loses \
                 its digits: the renderer computes theta with atan2, exact at the poles)",
                n(1.0 - nq.y.abs()),
                if q.y > 0.0 { "" } else { "-" }
            );
        } else {
            line!(
                out,
                "theta = acos(y) = acos({}) = {} rad",
                n(nq.y.clamp(-1.0, 1.0)),
                n(theta)
            );
        }
        let v = (1.0 - theta / pi).clamp(0.0, 1.0);
        line!(out, "v = 1 - theta / pi = {}", n(v));
        DVec2::new(u, v)
    }

    fn angles(p: DVec3) -> MappingAngles {
        MappingAngles {
            phi: Some(phi(p)),
            theta: Some(p.x.hypot(p.z).atan2(p.y)),
            ..MappingAngles::default()
        }
    }
}
