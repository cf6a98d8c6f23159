//! Small pieces the concepts share: serde defaults every concept writes the same way, and the
//! checks of finite and non-negative numbers.

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

pub(super) fn finite_vec(what: &str, v: Vec3) -> std::result::Result<Vec3A, String> {
    if v.is_finite() {
        Ok(v.into())
    } else {
        Err(format!("{what}: {v} is not finite"))
    }
}

pub(super) fn finite_non_negative(what: &str, values: &[f32]) -> std::result::Result<(), String> {
    match values.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
        Some(v) => Err(format!("{what}: {v} must be finite and not negative")),
        None => Ok(()),
    }
}
