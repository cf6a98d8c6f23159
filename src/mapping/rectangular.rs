//! The rectangular map (the lecture's `RectangularMap`): the texture projected along y onto
//! the generic rectangle (x, z) in [-1, 1]^2, u = (z + 1) / 2, v = (x + 1) / 2. Points off the
//! rectangle give coordinates outside [0, 1] and the texture's wrap mode decides (so a plane
//! tiles).

use super::explain::{line, n};
use super::{Family, Map, Mapped, MappingAngles};
use crate::math::Vec3A;
use crate::math::lanes::V3;
use glam::{DVec2, DVec3};
use pulp::Simd;

/// See the module documentation.
pub(crate) struct Rectangular;

impl Map for Rectangular {
    const U_PERIODIC: bool = false;
    const V_CLAMPS: bool = false;
    const FAMILY: Family = Family::Rectangle;
    const LECTURE: Option<(&'static str, &'static str)> = Some(("(z + 1) / 2", "(x + 1) / 2"));

    #[inline(always)]
    fn lanes<S: Simd, const GRAD: bool>(s: S, p: &V3<S>) -> Mapped<S> {
        let (one, half) = (s.splat_f32s(1.0), s.splat_f32s(0.5));
        Mapped {
            u: s.mul_f32s(s.add_f32s(p.z, one), half),
            v: s.mul_f32s(s.add_f32s(p.x, one), half),
            grad_u: V3::splat(s, Vec3A::new(0.0, 0.0, 0.5)),
            grad_v: V3::splat(s, Vec3A::new(0.5, 0.0, 0.0)),
        }
    }

    fn worked(p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
        let (u, v) = ((p.z + 1.0) * 0.5, (p.x + 1.0) * 0.5);
        line!(out, "u = (z + 1) / 2 = ({} + 1) / 2 = {}", n(p.z), n(u));
        line!(out, "v = (x + 1) / 2 = ({} + 1) / 2 = {}", n(p.x), n(v));
        DVec2::new(u, v)
    }

    fn angles(_p: DVec3) -> MappingAngles {
        MappingAngles::default()
    }
}
