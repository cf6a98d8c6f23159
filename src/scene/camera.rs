//! The camera: its description ([`CameraDesc`], [`ProjectionDesc`]), the projection kinds with
//! their defaults, and the check and build of the runtime [`Camera`].

use super::values::finite_vec;
use crate::camera::{Camera, Projection};
use crate::field::{FieldPath, Refusal};
use crate::math::Vec3;
use serde::{Deserialize, Serialize};

/// Camera placement and projection, in world space with y up. A preset writes
/// `camera: (eye: (0, 1, 4), look_at: (0, 0.5, 0), projection: Pinhole(fov: 50))`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Eye position in world units (y is up); required, and not equal to `look_at`.
    pub eye: Vec3,
    /// The point at the centre of the view, in world units; default the origin.
    #[serde(default)]
    pub look_at: Vec3,
    /// Which way is up on the film (default +y); need not be perpendicular to the view, must not
    /// be zero.
    #[serde(default = "default_up")]
    pub up: Vec3,
    /// Projection and its angles; default `Pinhole(fov: 45)`.
    #[serde(default)]
    pub projection: ProjectionDesc,
}

fn default_up() -> Vec3 {
    Vec3::Y
}

/// Camera projections. Angles in degrees.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ProjectionDesc {
    /// Perspective with a vertical field of view.
    Pinhole {
        /// Vertical field of view, degrees.
        fov: f32,
    },
    /// Equidistant fisheye with the full angle across the inscribed circle.
    Fisheye {
        /// Full field of view, degrees (360 sees everything).
        fov: f32,
    },
    /// Equirectangular panorama: x across the image is longitude, y is latitude.
    Spherical {
        /// Horizontal field of view, degrees (360 for all around).
        h_fov: f32,
        /// Vertical field of view, degrees (180 for pole to pole).
        v_fov: f32,
    },
    /// Parallel rays along the view direction, from the plane through the eye.
    Orthographic {
        /// Height of the view in world units (positive); the width follows the image's
        /// aspect ratio.
        height: f32,
    },
}

impl Default for ProjectionDesc {
    fn default() -> Self {
        ProjectionKind::Pinhole.default_desc()
    }
}

/// The kinds of [`ProjectionDesc`], as the camera menu names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
pub enum ProjectionKind {
    /// [`ProjectionDesc::Pinhole`].
    #[strum(message = "Perspective with a vertical field of view.")]
    Pinhole,
    /// [`ProjectionDesc::Fisheye`].
    #[strum(message = "Equidistant fisheye: the angle from the axis grows linearly to the rim.")]
    Fisheye,
    /// [`ProjectionDesc::Spherical`].
    #[strum(message = "Equirectangular panorama: longitude across, latitude up.")]
    Spherical,
    /// [`ProjectionDesc::Orthographic`].
    #[strum(
        message = "Parallel projection: no perspective; the view is a fixed height in world units."
    )]
    Orthographic,
}

impl crate::names::Named for ProjectionKind {
    const WHAT: &'static str = "camera";
}

impl ProjectionKind {
    /// The projection with its usual angles: 45 degrees for the pinhole, the half sphere for the
    /// fisheye, everything for the panorama; 2 world units high (a unit sphere fills it) for
    /// the orthographic camera.
    #[must_use]
    pub const fn default_desc(self) -> ProjectionDesc {
        match self {
            Self::Pinhole => ProjectionDesc::Pinhole { fov: 45.0 },
            Self::Fisheye => ProjectionDesc::Fisheye { fov: 180.0 },
            Self::Spherical => ProjectionDesc::Spherical {
                h_fov: 360.0,
                v_fov: 180.0,
            },
            Self::Orthographic => ProjectionDesc::Orthographic { height: 2.0 },
        }
    }
}

impl ProjectionDesc {
    /// Which kind of projection this is.
    #[must_use]
    pub const fn kind(&self) -> ProjectionKind {
        match self {
            Self::Pinhole { .. } => ProjectionKind::Pinhole,
            Self::Fisheye { .. } => ProjectionKind::Fisheye,
            Self::Spherical { .. } => ProjectionKind::Spherical,
            Self::Orthographic { .. } => ProjectionKind::Orthographic,
        }
    }
}

pub(super) fn camera(
    c: &CameraDesc,
    width: u32,
    height: u32,
) -> std::result::Result<Camera, Refusal> {
    let at = |field: FieldPath, m: String| Refusal::new(FieldPath::field("camera").join(&field), m);
    let camera = FieldPath::field("camera");
    let eye = finite_vec("eye", c.eye).map_err(|r| r.under(&camera))?;
    let look_at = finite_vec("look_at", c.look_at).map_err(|r| r.under(&camera))?;
    let up = finite_vec("up", c.up).map_err(|r| r.under(&camera))?;
    if (eye - look_at).length_squared() == 0.0 {
        return Err(at(
            FieldPath::root(),
            "eye and look_at are the same point".into(),
        ));
    }
    if up.length_squared() == 0.0 {
        return Err(at("up".into(), "must not be zero".into()));
    }
    let in_range = |what: &str, v: f32, max: f32| {
        if v > 0.0 && v <= max {
            Ok(v.to_radians())
        } else {
            Err(at(
                FieldPath::field("projection").then(what),
                format!("{v} degrees is out of range (0, {max}]"),
            ))
        }
    };
    let projection = match c.projection {
        ProjectionDesc::Pinhole { fov } => {
            let fov_y = in_range("fov", fov, 179.0)?;
            Projection::Pinhole { fov_y }
        }
        ProjectionDesc::Fisheye { fov } => Projection::Fisheye {
            psi_max: in_range("fov", fov, 360.0)? * 0.5,
        },
        ProjectionDesc::Spherical { h_fov, v_fov } => Projection::Spherical {
            lambda_max: in_range("h_fov", h_fov, 360.0)? * 0.5,
            psi_max: in_range("v_fov", v_fov, 180.0)? * 0.5,
        },
        ProjectionDesc::Orthographic { height } => {
            if !(height > 0.0 && height <= 1e9) {
                return Err(at(
                    FieldPath::field("projection").then("height"),
                    format!("{height} is out of range (0, 1e9] world units"),
                ));
            }
            Projection::Orthographic { height }
        }
    };
    Ok(Camera::new(eye, look_at, up, projection, width, height))
}
