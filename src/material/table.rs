//! The one table of every material kind's coefficients and colours: name (the field of the
//! runtime [`Material`](super::Material), of the preset's description and of the preset text),
//! the window's label and drag range, the type (coefficient or colour) and the default.
//!
//! The table is a macro, [`material_table!`], that hands its rows to a macro of the caller, so
//! every list over a kind's parameters is generated from it: [`Material::params`](super::Material::params)
//! here, and in `scene` the description's accessors, the kinds' defaults, the build of the
//! runtime material and the window's labels and ranges. The generated matches name every field
//! of a variant and no `..`, so a row without its field, or a field without its row, does not
//! compile; the colour texture (`cd`, or `ce` for emissive) is named beside the kind.

use crate::math::Rgb;

/// A parameter's type and default value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamDefault {
    /// A coefficient ([`Scalar`](super::Scalar)) and its default.
    Scalar(f32),
    /// A colour ([`Colour`](super::Colour)) and its default, linear.
    Colour(Rgb),
}

/// One row of a material kind's table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// The field's name in presets, in the description and in the runtime material (`ka`).
    pub name: &'static str,
    /// What the window calls it (`ka (ambient)`).
    pub label: &'static str,
    /// The largest value the window's drag reaches from 0 (a coefficient; a larger value from
    /// a preset is kept).
    pub max: f32,
    /// The window's drag speed, per pixel.
    pub speed: f64,
    /// Coefficient or colour, and the default a preset that leaves the field out reads.
    pub default: ParamDefault,
}

/// Hands the table to `$callback!`, one entry per kind:
/// `Kind (colour) { name: Type = default, "label", max, speed; ... }`, where `colour` is the
/// kind's colour texture field and `Type` is `Scalar` or `Colour`. Adding a parameter is one row
/// here, its field in `Material` and `MaterialDesc` (the compiler asks for both), and its use in
/// shading.
macro_rules! material_table {
    ($callback:ident) => {
        $callback! {
            Matte (cd) {
                ka: Scalar = 0.25, "ka (ambient)", 10.0, 0.01;
                kd: Scalar = 0.75, "kd (diffuse)", 10.0, 0.01;
            }
            Phong (cd) {
                ka: Scalar = 0.25, "ka (ambient)", 10.0, 0.01;
                kd: Scalar = 0.75, "kd (diffuse)", 10.0, 0.01;
                ks: Scalar = 0.25, "ks (specular)", 10.0, 0.01;
                cs: Colour = $crate::math::Rgb::WHITE, "specular colour", 1.0, 0.01;
                exp: Scalar = 20.0, "exponent", 10_000.0, 0.5;
                ce: Colour = $crate::math::Rgb::BLACK, "ce (night glow)", 1.0, 0.01;
            }
            Reflective (cd) {
                ka: Scalar = 0.25, "ka (ambient)", 10.0, 0.01;
                kd: Scalar = 0.75, "kd (diffuse)", 10.0, 0.01;
                ks: Scalar = 0.25, "ks (specular)", 10.0, 0.01;
                cs: Colour = $crate::math::Rgb::WHITE, "specular colour", 1.0, 0.01;
                exp: Scalar = 20.0, "exponent", 10_000.0, 0.5;
                kr: Scalar = 0.75, "kr (mirror)", 10.0, 0.01;
                cr: Colour = $crate::math::Rgb::WHITE, "mirror colour", 1.0, 0.01;
            }
            Emissive (ce) {
                ls: Scalar = 1.0, "ls (radiance)", 1e4, 0.01;
            }
        }
    };
}

pub(crate) use material_table;

/// [`Material::params`](super::Material::params) and
/// [`Material::param_specs`](super::Material::param_specs) from the table.
macro_rules! runtime_params {
    ($($kind:ident ($colour:ident) {
        $($name:ident : $ty:ident = $default:expr, $label:literal, $max:expr, $speed:expr;)*
    })*) => {
        impl super::Material {
            /// The coefficients and colours besides the colour texture (`cd`, or `ce` for an
            /// emissive material; Phong's glow `ce` is listed), by preset name, in table order.
            #[must_use]
            pub fn params(&self) -> Vec<(&'static str, super::Param<'_>)> {
                match self {
                    $(Self::$kind { $colour: _, $($name),* } => {
                        vec![$((stringify!($name), super::Param::$ty($name))),*]
                    })*
                }
            }

            /// The table's rows of this material's kind, in the order of
            /// [`Material::params`](super::Material::params).
            #[must_use]
            pub const fn param_specs(&self) -> &'static [ParamSpec] {
                match self {
                    $(Self::$kind { .. } => &[$(ParamSpec {
                        name: stringify!($name),
                        label: $label,
                        max: $max,
                        speed: $speed,
                        default: ParamDefault::$ty($default),
                    }),*],)*
                }
            }
        }
    };
}

material_table!(runtime_params);
