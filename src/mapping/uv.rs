//! `uv`: the (u, v) the shape carries, a mesh's vertex coordinates interpolated by the hit's
//! barycentrics ([`super::Mapping::map_with_differentials`] reads them, with d(u, v) from the
//! triangle's dp/du and dp/dv), or, on a shape without its own, the shape's natural
//! parameterisation (spherical on spheres, cylindrical on cylinders, rectangular on planes).
//! Where a point alone is mapped (no shape at hand) it is the spherical map.

use super::explain::{line, rescaled};
use super::spherical::Spherical;
use super::{Family, Map, Mapped, MappingAngles};
use crate::math::lanes::V3;
use glam::{DVec2, DVec3};
use pulp::Simd;

/// See the module documentation.
pub(crate) struct Uv;

impl Map for Uv {
    const U_PERIODIC: bool = false;
    const V_CLAMPS: bool = false;
    const FAMILY: Family = Family::Sphere;
    const LECTURE: Option<(&'static str, &'static str)> = None;

    #[inline(always)]
    fn lanes<S: Simd, const GRAD: bool>(s: S, p: &V3<S>) -> Mapped<S> {
        Spherical::lanes::<S, GRAD>(s, p)
    }

    fn worked(p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
        let uv = Spherical::worked(p, out);
        if rescaled(p).is_some() {
            line!(
                out,
                "(uv: this shape carries no (u, v) of its own, so its natural spherical map is used)"
            );
        }
        uv
    }

    fn angles(_p: DVec3) -> MappingAngles {
        // `uv` in effect means (u, v) carried by the shape: no angle.
        MappingAngles::default()
    }
}
