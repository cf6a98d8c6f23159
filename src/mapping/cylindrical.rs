//! The cylindrical map (the lecture's `CylindricalMap`): the texture wrapped once around the y
//! axis, phi = atan2(x, z) in [0, 2 pi), u = phi / 2 pi, and v = (y + 1) / 2 up the generic
//! cylinder's height, clamped into [0, 1]. u is periodic: its seam is the meridian u = 0 = 1.

use super::explain::{azimuth as worked_azimuth, line, n, phi, rescaled as rescaled_f64};
use super::shared::{azimuth, rescaled};
use super::{Family, Map, Mapped, MappingAngles};
use crate::math::Vec3A;
use crate::math::lanes::{V3, clamp, nan, select};
use glam::{DVec2, DVec3};
use pulp::Simd;

/// See the module documentation.
pub(crate) struct Cylindrical;

impl Map for Cylindrical {
    const U_PERIODIC: bool = true;
    const V_CLAMPS: bool = false;
    const FAMILY: Family = Family::Cylinder;
    const LECTURE: Option<(&'static str, &'static str)> =
        Some(("fract(atan2(x, z) / tau)", "clamp((y + 1) / 2)"));

    #[inline(always)]
    fn lanes<S: Simd, const GRAD: bool>(s: S, p: &V3<S>) -> Mapped<S> {
        let zero = s.splat_f32s(0.0);
        let flat = V3 {
            x: p.x,
            y: zero,
            z: p.z,
        };
        let (q, scale, ok) = rescaled(s, &flat);
        let (u, g) = azimuth::<S, GRAD>(s, q.x, q.z);
        let zero3 = V3::splat(s, Vec3A::ZERO);
        let w = s.mul_f32s(s.add_f32s(p.y, s.splat_f32s(1.0)), s.splat_f32s(0.5));
        Mapped {
            u: select(s, ok, u, zero),
            v: select(s, nan(s, w), s.splat_f32s(0.5), clamp(s, w, 0.0, 1.0)),
            grad_u: if GRAD {
                V3::select(s, ok, &g.div(s, scale), &zero3)
            } else {
                zero3
            },
            grad_v: V3::splat(s, Vec3A::new(0.0, 0.5, 0.0)),
        }
    }

    fn worked(p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
        // The lecture's atan2(x, z) on the point as given (libm's atan2 is exact at any
        // scale); the renderer's rescaling only keeps its f32 squares finite.
        let u = if rescaled_f64(DVec3::new(p.x, 0.0, p.z)).is_some() {
            worked_azimuth(p.x, p.z, out)
        } else {
            line!(
                out,
                "x = z = 0 (on the axis): phi is undefined, u = 0 as the renderer"
            );
            0.0
        };
        let raw = (p.y + 1.0) * 0.5;
        line!(out, "v = (y + 1) / 2 = ({} + 1) / 2 = {}", n(p.y), n(raw));
        let v = if raw.is_nan() {
            0.5
        } else {
            raw.clamp(0.0, 1.0)
        };
        if v != raw {
            line!(
                out,
                "off the cylinder's height: v clamped into [0, 1], v = {}",
                n(v)
            );
        }
        DVec2::new(u, v)
    }

    fn angles(p: DVec3) -> MappingAngles {
        MappingAngles {
            phi: Some(phi(p)),
            ..MappingAngles::default()
        }
    }
}
