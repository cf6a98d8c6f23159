//! The mirror-ball probe: the image of a reflective sphere photographed from +z, r =
//! sin(alpha / 2) instead of the light probe's alpha / pi (reads `texplore probe --format
//! mirror-ball`). Its formulas are the light probe's (`light_probe.rs`).

use super::light_probe::{Curve, probe, probe_angles, worked_probe};
use super::{Family, Map, Mapped, MappingAngles};
use crate::math::lanes::V3;
use glam::{DVec2, DVec3};
use pulp::Simd;

/// See the module documentation.
pub(crate) struct MirrorBall;

impl Map for MirrorBall {
    const U_PERIODIC: bool = false;
    const V_CLAMPS: bool = false;
    const FAMILY: Family = Family::Probe;
    const LECTURE: Option<(&'static str, &'static str)> = None;

    #[inline(always)]
    fn lanes<S: Simd, const GRAD: bool>(s: S, p: &V3<S>) -> Mapped<S> {
        probe::<S, GRAD>(s, p, false, Curve::MirrorBall)
    }

    fn worked(p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
        worked_probe(p, false, Curve::MirrorBall, out)
    }

    fn angles(p: DVec3) -> MappingAngles {
        probe_angles(p, false, Curve::MirrorBall)
    }
}
