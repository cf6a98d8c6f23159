//! Small pieces the concepts share: serde defaults every concept writes the same way, and the
//! checks of finite and non-negative numbers.

use crate::field::{FieldPath, Refusal};
use crate::math::{Rgb, Vec3, Vec3A};

pub(super) fn one() -> f32 {
    1.0
}

pub(super) fn white() -> Rgb {
    Rgb::WHITE
}

pub(super) fn yes() -> bool {
    true
}

/// `v` if it is finite, else the refusal of `field`.
pub(super) fn finite_vec(
    field: impl Into<FieldPath>,
    v: Vec3,
) -> std::result::Result<Vec3A, Refusal> {
    if v.is_finite() {
        Ok(v.into())
    } else {
        Err(Refusal::new(field.into(), format!("{v} is not finite")))
    }
}

/// The refusal of `field` unless every value is finite and not negative.
pub(super) fn finite_non_negative(
    field: impl Into<FieldPath>,
    values: &[f32],
) -> std::result::Result<(), Refusal> {
    match values.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
        Some(v) => Err(Refusal::new(
            field.into(),
            format!("{v} must be finite and not negative"),
        )),
        None => Ok(()),
    }
}
