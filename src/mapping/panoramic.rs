//! The panoramic variant of the light-probe map: z flipped (alpha = acos(-z)), for probes made
//! from panorama photographs, which are mirror reversals of a photographed ball. Its formulas
//! are the light probe's (`light_probe.rs`).

use super::light_probe::{Curve, probe, probe_angles, worked_probe};
use super::{Family, Map, Mapped, MappingAngles};
use crate::math::lanes::V3;
use glam::{DVec2, DVec3};
use pulp::Simd;

/// See the module documentation.
pub(crate) struct Panoramic;

impl Map for Panoramic {
    const U_PERIODIC: bool = false;
    const V_CLAMPS: bool = false;
    const FAMILY: Family = Family::Probe;
    const LECTURE: Option<(&'static str, &'static str)> = None;

    #[inline(always)]
    fn lanes<S: Simd, const GRAD: bool>(s: S, p: &V3<S>) -> Mapped<S> {
        probe::<S, GRAD>(s, p, true, Curve::Angular)
    }

    fn worked(p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
        worked_probe(p, true, Curve::Angular, out)
    }

    fn angles(p: DVec3) -> MappingAngles {
        probe_angles(p, true, Curve::Angular)
    }
}
