//! The angles of the lecture's mapping formulas at a point, for the mapping diagram.

use crate::mapping::Mapping;
use crate::math::Vec3A;

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

/// The angles of `mapping`'s formula at `p` (the point the mapping reads, see
/// [`Inspection::mapping_point`](super::Inspection::mapping_point)): phi for the cylindrical
/// map, phi and theta for the spherical, alpha, beta and r for the light probes. The
/// rectangular map and a mesh's own (u, v) have none.
#[must_use]
pub fn mapping_angles(mapping: Mapping, p: Vec3A) -> MappingAngles {
    let p = p.as_dvec3();
    let phi = || {
        let a = p.x.atan2(p.z);
        if a < 0.0 {
            a + std::f64::consts::TAU
        } else {
            a
        }
    };
    match mapping {
        Mapping::Cylindrical => MappingAngles {
            phi: Some(phi()),
            ..MappingAngles::default()
        },
        Mapping::Spherical => MappingAngles {
            phi: Some(phi()),
            theta: Some(p.x.hypot(p.z).atan2(p.y)),
            ..MappingAngles::default()
        },
        Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall => {
            let z = if mapping == Mapping::Panoramic {
                -p.z
            } else {
                p.z
            };
            let alpha = p.x.hypot(p.y).atan2(z);
            let r = if mapping == Mapping::MirrorBall {
                (alpha * 0.5).sin()
            } else {
                alpha / std::f64::consts::PI
            };
            MappingAngles {
                alpha: Some(alpha),
                beta: Some(p.y.atan2(p.x)),
                r: Some(r),
                ..MappingAngles::default()
            }
        }
        // `Uv` in effect means (u, v) carried by the shape: no angle.
        Mapping::Rectangular | Mapping::Uv => MappingAngles::default(),
    }
}
