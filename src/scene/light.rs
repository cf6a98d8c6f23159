//! Lights: the ambient light ([`AmbientDesc`]), directional and point lights ([`LightDesc`]),
//! their kinds with defaults, and the check and build of the runtime [`Light`].

use super::values::{finite_non_negative, finite_vec, one, white, yes};
use crate::field::{FieldPath, Refusal};
use crate::material::Light;
use crate::math::{Rgb, Vec3};
use serde::{Deserialize, Serialize};

/// The ambient light: radiance `ls * color` from everywhere, scaled by each lit material's
/// `ka` (emissive materials ignore it).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AmbientDesc {
    /// Multiplier on `color` (finite, not negative); default 1.
    pub ls: f32,
    /// Linear RGB, `(r, g, b)`; default white `(1, 1, 1)`.
    pub color: Rgb,
}

impl Default for AmbientDesc {
    fn default() -> Self {
        Self {
            ls: 1.0,
            color: Rgb::WHITE,
        }
    }
}

/// A light source in `lights: [...]`. Its radiance `ls * color` reaches a surface undimmed
/// by distance, unless `shadows` is on and an object that casts shadows is in the way.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum LightDesc {
    /// Light from one direction (the sun).
    Directional {
        /// World-space direction from surfaces toward the light (need not be unit length, must not
        /// be zero).
        direction: Vec3,
        /// Multiplier on `color` (finite, not negative); default 1.
        #[serde(default = "one")]
        ls: f32,
        /// Linear RGB, `(r, g, b)`, not negative; default white.
        #[serde(default = "white")]
        color: Rgb,
        /// Whether objects cast shadows from it.
        #[serde(default = "yes")]
        shadows: bool,
    },
    /// Light from a point, without fall-off (the lecture's).
    Point {
        /// Position in world units.
        position: Vec3,
        /// Multiplier on `color` (finite, not negative); default 1.
        #[serde(default = "one")]
        ls: f32,
        /// Linear RGB, `(r, g, b)`, not negative; default white.
        #[serde(default = "white")]
        color: Rgb,
        /// Whether objects cast shadows from it.
        #[serde(default = "yes")]
        shadows: bool,
    },
}

/// The kinds of [`LightDesc`], as the lights panel names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
pub enum LightKind {
    /// [`LightDesc::Directional`].
    #[strum(
        serialize = "directional",
        message = "A light from one direction, like the sun."
    )]
    Directional,
    /// [`LightDesc::Point`].
    #[strum(
        serialize = "point",
        message = "A light from a point, without fall-off."
    )]
    Point,
}

impl crate::names::Named for LightKind {
    const WHAT: &'static str = "light";
}

impl LightKind {
    /// A new light of this kind: white, casting shadows, from above and in front of the origin.
    #[must_use]
    pub fn default_desc(self) -> LightDesc {
        match self {
            Self::Directional => LightDesc::Directional {
                direction: Vec3::new(1.0, 1.0, 1.0),
                ls: one(),
                color: white(),
                shadows: yes(),
            },
            Self::Point => LightDesc::Point {
                position: Vec3::new(0.0, 4.0, 4.0),
                ls: one(),
                color: white(),
                shadows: yes(),
            },
        }
    }
}

impl LightDesc {
    /// Which kind of light this is.
    #[must_use]
    pub const fn kind(&self) -> LightKind {
        match self {
            Self::Directional { .. } => LightKind::Directional,
            Self::Point { .. } => LightKind::Point,
        }
    }
}

/// The runtime light; a refusal names the field relative to the light (`color`).
pub(super) fn light(l: &LightDesc) -> std::result::Result<Light, Refusal> {
    Ok(match *l {
        LightDesc::Directional {
            direction,
            ls,
            color,
            shadows,
        } => {
            let d = finite_vec("direction", direction)?;
            let to_light = d
                .try_normalize()
                .ok_or_else(|| Refusal::new("direction".into(), "must not be zero"))?;
            finite_non_negative("ls", &[ls])?;
            finite_non_negative("color", &color.to_array())?;
            Light::Directional {
                to_light,
                radiance: color * ls,
                shadows,
            }
        }
        LightDesc::Point {
            position,
            ls,
            color,
            shadows,
        } => {
            finite_non_negative("ls", &[ls])?;
            finite_non_negative("color", &color.to_array())?;
            Light::Point {
                position: finite_vec("position", position)?,
                radiance: color * ls,
                shadows,
            }
        }
    })
}

/// The ambient radiance `ls * color`, both finite and not negative.
pub(super) fn ambient(a: &AmbientDesc) -> std::result::Result<Rgb, Refusal> {
    let ambient = FieldPath::field("ambient");
    finite_non_negative("ls", &[a.ls]).map_err(|r| r.under(&ambient))?;
    finite_non_negative("color", &a.color.to_array()).map_err(|r| r.under(&ambient))?;
    Ok(a.color * a.ls)
}
