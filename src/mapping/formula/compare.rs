//! A formula mapping checked against a built-in one: the share of points where they agree,
//! and the common mistakes recognised by testing the formula against the built-in mapping
//! under each mistake's transformation (u and v swapped, u mirrored, atan2's arguments
//! exchanged, v upside down, u turned by a quarter or a half, degrees for radians), not by
//! reading the formula's text.

use super::FormulaMapping;
use crate::mapping::{Mapping, map_uv_f64};
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// Points where the lecture uses `mapping`, `n` along each side of a grid of cell centres
/// (no point lies exactly on a seam or a pole): the rectangle (y = 0) for the rectangular
/// map, the unit cylinder for the cylindrical, the unit sphere for the others. With each
/// point, the shape's own (u, v) (what `mesh_u`, `mesh_v` read there).
#[must_use]
pub fn sample_points(mapping: Mapping, n: usize) -> Vec<(DVec3, DVec2)> {
    let n = n.max(2);
    let mut out = Vec::with_capacity(2 * n * n);
    let centre = |i: usize, count: usize| (i as f64 + 0.5) / count as f64;
    match mapping {
        Mapping::Rectangular => {
            for i in 0..n {
                for j in 0..n {
                    let p = DVec3::new(2.0 * centre(i, n) - 1.0, 0.0, 2.0 * centre(j, n) - 1.0);
                    out.push((p, map_uv_f64(Mapping::Rectangular, p)));
                }
            }
        }
        Mapping::Cylindrical => {
            for i in 0..n {
                for j in 0..2 * n {
                    let phi = TAU * centre(j, 2 * n);
                    let p = DVec3::new(phi.sin(), 2.0 * centre(i, n) - 1.0, phi.cos());
                    out.push((p, map_uv_f64(Mapping::Cylindrical, p)));
                }
            }
        }
        Mapping::Spherical
        | Mapping::Uv
        | Mapping::LightProbe
        | Mapping::Panoramic
        | Mapping::MirrorBall => {
            for i in 0..n {
                let theta = PI * centre(i, n);
                for j in 0..2 * n {
                    let phi = TAU * centre(j, 2 * n);
                    let p = DVec3::new(
                        theta.sin() * phi.sin(),
                        theta.cos(),
                        theta.sin() * phi.cos(),
                    );
                    out.push((p, map_uv_f64(Mapping::Spherical, p)));
                }
            }
        }
    }
    out
}

/// How a formula compares with a built-in mapping over a set of points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Agreement {
    /// Points compared.
    pub points: usize,
    /// Points where |du| and |dv| are both within the tolerance.
    pub agreeing: usize,
    /// Points where the formula is NaN or infinite.
    pub non_finite: usize,
    /// The largest |du| and |dv| over the finite points (u across the seam of a periodic
    /// mapping is compared modulo 1: u = 0.999 and u = 0.001 are 0.002 apart).
    pub max_difference: DVec2,
}

impl Agreement {
    /// The share of points that agree, 0 to 1.
    #[must_use]
    pub fn share(&self) -> f64 {
        share_of(self.agreeing, self.points)
    }
}

/// `agreeing` out of `points` as a share, 0 to 1 (0 of none).
#[must_use]
pub fn share_of(agreeing: usize, points: usize) -> f64 {
    if points == 0 {
        0.0
    } else {
        agreeing as f64 / points as f64
    }
}

/// |du|, |dv| between two (u, v), u modulo 1 when the mapping's u is periodic.
#[must_use]
pub fn difference(mapping: Mapping, a: DVec2, b: DVec2) -> DVec2 {
    let d = a - b;
    let du = if mapping.u_is_periodic() {
        d.x - d.x.round()
    } else {
        d.x
    };
    DVec2::new(du.abs(), d.y.abs())
}

/// The tolerance of one texel of a `width` x `height` image, in (u, v).
#[must_use]
pub fn one_texel(width: u32, height: u32) -> DVec2 {
    DVec2::new(
        1.0 / f64::from(width.max(1)),
        1.0 / f64::from(height.max(1)),
    )
}

/// The formula against `mapping` at `points` (as [`sample_points`] gives them), within `tol`.
#[must_use]
pub fn agreement(
    formula: &FormulaMapping,
    mapping: Mapping,
    points: &[(DVec3, DVec2)],
    tol: DVec2,
) -> Agreement {
    let mut a = Agreement {
        points: points.len(),
        agreeing: 0,
        non_finite: 0,
        max_difference: DVec2::ZERO,
    };
    for &(p, mesh) in points {
        let got = formula.eval(&super::inputs_of(p, mesh));
        if !got.is_finite() {
            a.non_finite += 1;
            continue;
        }
        let d = difference(mapping, got, map_uv_f64(mapping, p));
        a.max_difference = a.max_difference.max(d);
        if d.x <= tol.x && d.y <= tol.y {
            a.agreeing += 1;
        }
    }
    a
}

/// A common mistake in writing a mapping.
#[derive(Clone, Copy, Debug, PartialEq, Eq, strum::VariantArray)]
pub enum Mistake {
    /// u and v exchanged.
    Swapped,
    /// u mirrored: 1 - u.
    MirroredU,
    /// atan2's arguments exchanged: atan2(z, x) is a quarter turn minus phi.
    Atan2Arguments,
    /// v upside down: 1 - v (the spherical map's acos(y) without the flip).
    FlippedV,
    /// u turned by a quarter (either way).
    QuarterTurn,
    /// u turned by a half.
    HalfTurn,
    /// An angle in degrees where radians are meant (or the other way).
    Degrees,
}

impl Mistake {
    /// What to tell the student about `mapping`.
    #[must_use]
    pub fn hint(self, mapping: Mapping) -> String {
        let probe = matches!(
            mapping,
            Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall
        );
        match self {
            Self::Swapped => "u and v are swapped: exchange the two formulas".into(),
            Self::Atan2Arguments => "atan2's arguments are the wrong way round: texplore's phi = atan2(x, z), x first".into(),
            Self::MirroredU if probe => {
                "the image is mirrored left to right: u = (1 + r cos beta) / 2, with cos beta = x / sqrt(x^2 + y^2)".into()
            }
            Self::MirroredU => "u runs the wrong way (1 - u): phi = atan2(x, z) grows from +z toward +x".into(),
            Self::FlippedV if mapping == Mapping::Spherical || mapping == Mapping::Uv => {
                "v is upside down: acos(y) is 0 at the north pole, but v = 0 is the bottom of the image; write v = 1 - acos(y) / pi".into()
            }
            Self::FlippedV => "v is upside down (1 - v): v = 0 is the bottom of the image".into(),
            Self::QuarterTurn if probe => "the image is turned by a quarter: beta is measured from +x, toward +y".into(),
            Self::QuarterTurn => "u is a quarter turn off: phi = atan2(x, z) is 0 on +z (atan2 takes x first, then z)".into(),
            Self::HalfTurn if probe => "the image is turned by a half: beta is measured from +x, toward +y".into(),
            Self::HalfTurn => "u is a half turn off: atan2 is already the angle from +z; do not add 0.5 or pi to it, bring it into [0, 1) with fract(atan2(x, z) / tau)".into(),
            Self::Degrees => "an angle is in degrees where radians are meant: atan2, acos and asin give radians, so divide by tau or pi, not by 360 or 180".into(),
        }
    }

    /// Which coordinates this mistake is tested on: u only, v only, or both.
    const fn coords(self) -> (bool, bool) {
        match self {
            Self::Swapped | Self::Degrees => (true, true),
            Self::MirroredU | Self::Atan2Arguments | Self::QuarterTurn | Self::HalfTurn => {
                (true, false)
            }
            Self::FlippedV => (false, true),
        }
    }

    /// Whether this mistake applies to `mapping` at all.
    const fn applies(self, mapping: Mapping) -> bool {
        let periodic = mapping.u_is_periodic();
        let probe = matches!(
            mapping,
            Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall
        );
        match self {
            Self::QuarterTurn | Self::HalfTurn => periodic || probe,
            Self::Degrees | Self::Atan2Arguments => periodic,
            Self::Swapped | Self::MirroredU | Self::FlippedV => true,
        }
    }

    /// The (u, v) a formula with this mistake gives where `mapping` gives `uv`: one or more
    /// candidates (a quarter turn either way; degrees from an angle in [0, 2 pi) or signed).
    fn candidates(self, mapping: Mapping, uv: DVec2) -> Vec<DVec2> {
        let (u, v) = (uv.x, uv.y);
        let probe = !mapping.u_is_periodic();
        // A probe image turned about its centre by k quarter turns.
        let turn = |k: u32| {
            let (mut a, mut b) = (u - 0.5, v - 0.5);
            for _ in 0..k {
                (a, b) = (-b, a);
            }
            DVec2::new(a + 0.5, b + 0.5)
        };
        match self {
            Self::Swapped => vec![DVec2::new(v, u)],
            Self::MirroredU => vec![DVec2::new(1.0 - u, v)],
            Self::Atan2Arguments => vec![DVec2::new(0.25 - u, v)],
            Self::FlippedV => vec![DVec2::new(u, 1.0 - v)],
            Self::QuarterTurn if probe => vec![turn(1), turn(3)],
            Self::HalfTurn if probe => vec![turn(2)],
            Self::QuarterTurn => vec![DVec2::new(u + 0.25, v), DVec2::new(u - 0.25, v)],
            Self::HalfTurn => vec![DVec2::new(u + 0.5, v)],
            Self::Degrees => {
                let signed = if u > 0.5 { u - 1.0 } else { u };
                let mut out = Vec::new();
                for k in [PI / 180.0, 180.0 / PI] {
                    // u from phi * k, v from theta * k (theta = (1 - v) pi).
                    let dv = 1.0 - k * (1.0 - v);
                    out.extend([
                        DVec2::new(k * u, v),
                        DVec2::new(k * signed, v),
                        DVec2::new(u, dv),
                        DVec2::new(k * u, dv),
                        DVec2::new(k * signed, dv),
                    ]);
                }
                out
            }
        }
    }
}

/// A share of points at or above which a mistake's transformation is taken as what the
/// formula does.
pub const HINT_SHARE: f64 = 0.9;

/// At or above this share of agreeing points, a formula is correct and gets no hint.
pub const CORRECT_SHARE: f64 = 0.99;

/// The mistakes the formula makes against `mapping`: for each, the transformation of the
/// built-in mapping that the formula follows at [`HINT_SHARE`] of the points, on the
/// coordinates the mistake concerns, where it disagrees with the built-in one. None for a
/// correct formula.
#[must_use]
pub fn mistakes(
    formula: &FormulaMapping,
    mapping: Mapping,
    points: &[(DVec3, DVec2)],
    tol: DVec2,
) -> Vec<Mistake> {
    if agreement(formula, mapping, points, tol).share() >= CORRECT_SHARE {
        return Vec::new();
    }
    let values: Vec<(DVec2, DVec2)> = points
        .iter()
        .map(|&(p, mesh)| {
            (
                formula.eval(&super::inputs_of(p, mesh)),
                map_uv_f64(mapping, p),
            )
        })
        .collect();
    let share = |test: &dyn Fn(DVec2, DVec2) -> bool| {
        let n = values
            .iter()
            .filter(|(got, want)| test(*got, *want))
            .count();
        n as f64 / values.len().max(1) as f64
    };
    let within = |got: DVec2, want: DVec2, (on_u, on_v): (bool, bool)| {
        let d = difference(mapping, got, want);
        (!on_u || d.x <= tol.x) && (!on_v || d.y <= tol.y)
    };
    <Mistake as strum::VariantArray>::VARIANTS
        .iter()
        .copied()
        .filter(|m| m.applies(mapping))
        .filter(|&m| {
            let coords = m.coords();
            let already_right = share(&|got, want| within(got, want, coords)) >= CORRECT_SHARE;
            !already_right
                && share(&|got, want| {
                    m.candidates(mapping, want)
                        .into_iter()
                        .any(|c| within(got, c, coords))
                }) >= HINT_SHARE
        })
        .collect()
}

/// The lecture's mappings written as formulas in texplore's conventions (what the README
/// shows): the same (u, v) as the built-in mapping to about 1e-15 on its surface. `None` for
/// the mappings the lecture does not write out (the panoramic and mirror-ball variants, `uv`).
///
/// The spherical and light-probe formulas divide by |p| before `acos`, as the renderer does:
/// a hit point rounded to f32 can lie a hair outside the unit sphere, where acos(1.0000001)
/// is NaN.
#[must_use]
pub const fn lecture_formula(mapping: Mapping) -> Option<(&'static str, &'static str)> {
    match mapping {
        Mapping::Rectangular => Some(("(z + 1) / 2", "(x + 1) / 2")),
        Mapping::Cylindrical => Some(("fract(atan2(x, z) / tau)", "clamp((y + 1) / 2)")),
        Mapping::Spherical => Some((
            "fract(atan2(x, z) / tau)",
            "1 - acos(y / sqrt(x*x + y*y + z*z)) / pi",
        )),
        Mapping::LightProbe => Some((
            "(1 + acos(z / sqrt(x*x + y*y + z*z)) / pi * x / sqrt(x*x + y*y)) / 2",
            "(1 + acos(z / sqrt(x*x + y*y + z*z)) / pi * y / sqrt(x*x + y*y)) / 2",
        )),
        Mapping::Panoramic | Mapping::MirrorBall | Mapping::Uv => None,
    }
}
