//! The angles of the lecture's mapping formulas at a point, for the mapping diagram: each
//! mapping's own file says which it has (`Mapping::angles`).

use crate::mapping::Mapping;
pub use crate::mapping::MappingAngles;
use crate::math::Vec3A;

/// The angles of `mapping`'s formula at `p` (the point the mapping reads, see
/// [`Inspection::mapping_point`](super::Inspection::mapping_point)): phi for the cylindrical
/// map, phi and theta for the spherical, alpha, beta and r for the light probes. The
/// rectangular map and a mesh's own (u, v) have none.
#[must_use]
pub fn mapping_angles(mapping: Mapping, p: Vec3A) -> MappingAngles {
    mapping.angles(p)
}
