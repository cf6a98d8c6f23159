//! A formula mapping checked against a built-in one: the share of points where they agree, u
//! and v judged separately ([`Verdict`]), and the common mistakes recognised by testing each
//! formula against the built-in mapping under each mistake's transformation (u and v swapped,
//! u mirrored, atan2's arguments exchanged, v upside down, u turned by a quarter or a half,
//! degrees for radians, a missing 2 pi or `(y + 1) / 2`, asin for acos, the wrong axis), not by
//! reading the formula's text. Each mistake's hint comes in two steps (`hints.rs`): what is
//! wrong, then the fix.

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
    /// v upside down: 1 - v (the spherical map's acos(y) without the `1 -`).
    FlippedV,
    /// u turned by a quarter (either way); a probe image turned about its centre.
    QuarterTurn,
    /// u turned by a half; a probe image turned about its centre.
    HalfTurn,
    /// An angle in degrees where radians are meant (or the other way).
    Degrees,
    /// An angle around the axis not divided by a whole turn: atan2's radians as u, or
    /// divided by pi instead of 2 pi.
    MissingTwoPi,
    /// A coordinate of [-1, 1] not brought into [0, 1]: `(y + 1) / 2` missing, or half of it.
    MissingShift,
    /// asin where acos is meant: the latitude instead of the angle from the north pole.
    AsinForAcos,
    /// The formula follows the wrong axis: two of x, y and z exchanged.
    WrongAxis,
}

/// Which of the two formulas a mistake is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum On {
    /// The u formula.
    U,
    /// The v formula.
    V,
    /// Both: the mistake ties them together (swapped, an image turned).
    Both,
}

impl On {
    /// `u`, `v`, or `u and v`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::U => "u",
            Self::V => "v",
            Self::Both => "u and v",
        }
    }
}

/// A mistake found in one formula (or in both together).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Finding {
    /// What the formula does wrong.
    pub mistake: Mistake,
    /// In which formula.
    pub on: On,
}

/// A hint in two steps: what is wrong (with which formula agrees), then how to fix it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Hint {
    /// What is wrong, starting with which formula agrees: `u agrees; v is upside down ...`.
    pub what: String,
    /// The fix (`write v = 1 - acos(y) / pi`), when one is known.
    pub fix: Option<String>,
}

/// The families of built-in mappings, as the hints speak of them (each mapping's file names
/// its own).
use crate::mapping::Family as Kind;

const fn kind(mapping: Mapping) -> Kind {
    mapping.family()
}

/// The mistakes tried on both formulas together, in order.
const BOTH: [Mistake; 3] = [Mistake::Swapped, Mistake::QuarterTurn, Mistake::HalfTurn];
/// The mistakes tried on the u formula alone, in order: the first that fits is the one named.
const ON_U: [Mistake; 8] = [
    Mistake::MirroredU,
    Mistake::Atan2Arguments,
    Mistake::QuarterTurn,
    Mistake::HalfTurn,
    Mistake::MissingTwoPi,
    Mistake::Degrees,
    Mistake::MissingShift,
    Mistake::WrongAxis,
];
/// The mistakes tried on the v formula alone, in order.
const ON_V: [Mistake; 5] = [
    Mistake::FlippedV,
    Mistake::MissingShift,
    Mistake::AsinForAcos,
    Mistake::Degrees,
    Mistake::WrongAxis,
];

impl Mistake {
    /// What to tell the student about `mapping`, both steps at once: what is wrong, then the
    /// fix (what the scene panel's comparison shows).
    #[must_use]
    pub fn hint(self, mapping: Mapping) -> String {
        // Without the formula it was found in: the mistakes that may be in either are told
        // of both.
        let on = match self {
            Self::Swapped | Self::Degrees | Self::MissingShift | Self::WrongAxis => On::Both,
            Self::QuarterTurn | Self::HalfTurn if kind(mapping) == Kind::Probe => On::Both,
            Self::FlippedV | Self::AsinForAcos => On::V,
            _ => On::U,
        };
        let f = Finding { mistake: self, on };
        match hints::fix(f, mapping) {
            Some(fix) => format!("{}; {fix}", hints::what(f, mapping)),
            None => hints::what(f, mapping),
        }
    }

    /// Whether this mistake is tried on `on` of `mapping` at all.
    const fn applies(self, mapping: Mapping, on: On) -> bool {
        // What the family has, named once per family (exhaustive: a new family must say).
        let (around, probe, sphere, rectangle) = match kind(mapping) {
            Kind::Rectangle => (false, false, false, true),
            Kind::Cylinder => (true, false, false, false),
            Kind::Sphere => (true, false, true, false),
            Kind::Probe => (false, true, false, false),
        };
        match (self, on) {
            (Self::Swapped, On::Both)
            | (Self::MirroredU, On::U)
            | (Self::FlippedV, On::V)
            | (Self::WrongAxis, On::U | On::V) => true,
            (Self::QuarterTurn | Self::HalfTurn, On::Both) => probe,
            (
                Self::QuarterTurn
                | Self::HalfTurn
                | Self::Atan2Arguments
                | Self::MissingTwoPi
                | Self::Degrees,
                On::U,
            ) => around,
            (Self::Degrees | Self::AsinForAcos, On::V) => sphere,
            (Self::MissingShift, On::U) => rectangle | probe,
            (Self::MissingShift, On::V) => !sphere,
            _ => false,
        }
    }

    /// The (u, v) a formula with this mistake gives at the point `p`, where `mapping` gives
    /// `uv`: one or more candidates (a quarter turn either way; degrees from an angle in
    /// [0, 2 pi) or signed). Only the coordinates the mistake is tried on are compared.
    fn candidates(self, mapping: Mapping, p: DVec3, uv: DVec2) -> Vec<DVec2> {
        let (u, v) = (uv.x, uv.y);
        let probe = kind(mapping) == Kind::Probe;
        // A probe image turned about its centre by k quarter turns.
        let turn = |k: u32| {
            let (mut a, mut b) = (u - 0.5, v - 0.5);
            for _ in 0..k {
                (a, b) = (-b, a);
            }
            DVec2::new(a + 0.5, b + 0.5)
        };
        // u as atan2 gives it, signed: in (-1/2, 1/2].
        let signed = if u > 0.5 { u - 1.0 } else { u };
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
                let mut out = Vec::new();
                for k in [PI / 180.0, 180.0 / PI] {
                    // u from phi * k, v from theta * k (theta = (1 - v) pi).
                    let theta = k * (1.0 - v);
                    out.extend([
                        DVec2::new(k * u, v),
                        DVec2::new(k * signed, v),
                        DVec2::new(u, 1.0 - theta),
                        DVec2::new(u, theta),
                    ]);
                }
                out
            }
            // phi itself (no division), or phi / pi.
            Self::MissingTwoPi => [TAU, 2.0]
                .into_iter()
                .flat_map(|k| [DVec2::new(k * u, v), DVec2::new(k * signed, v)])
                .collect(),
            // t for (t + 1) / 2, t + 1 for it without the / 2, t / 2 without the + 1: on
            // either coordinate (only the one tried is compared).
            Self::MissingShift => [(2.0, -1.0), (2.0, 0.0), (1.0, -0.5)]
                .into_iter()
                .map(|(a, b)| DVec2::new(a * u + b, a * v + b))
                .collect(),
            // asin(y) / pi, 1 - asin(y) / pi.
            Self::AsinForAcos => vec![DVec2::new(u, v - 0.5), DVec2::new(u, 1.5 - v)],
            Self::WrongAxis => [
                DVec3::new(p.y, p.x, p.z),
                DVec3::new(p.x, p.z, p.y),
                DVec3::new(p.z, p.y, p.x),
            ]
            .into_iter()
            .map(|q| map_uv_f64(mapping, q))
            .collect(),
        }
    }
}

/// A share of points at or above which a mistake's transformation is taken as what the
/// formula does.
pub const HINT_SHARE: f64 = 0.9;

/// At or above this share of agreeing points, a formula is correct and gets no hint; at or
/// above it on one coordinate, that formula agrees.
pub const CORRECT_SHARE: f64 = 0.99;

/// u and v judged separately against a built-in mapping, and the mistakes found.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// Both together.
    pub agreement: Agreement,
    /// Points where u alone agrees.
    pub u_agreeing: usize,
    /// Points where v alone agrees.
    pub v_agreeing: usize,
    /// At most one mistake per formula (or one for both), none for a correct formula.
    pub findings: Vec<Finding>,
}

impl Verdict {
    /// The formula against `mapping` at `points` (as [`sample_points`] gives them), within
    /// `tol`: where u agrees, where v agrees, and for a formula that does not, the first of
    /// the common mistakes whose transformation of the built-in mapping it follows at
    /// [`HINT_SHARE`] of the points, on that formula (or on both, for the mistakes that tie
    /// them together).
    #[must_use]
    pub fn judge(
        formula: &FormulaMapping,
        mapping: Mapping,
        points: &[(DVec3, DVec2)],
        tol: DVec2,
    ) -> Self {
        let agreement = agreement(formula, mapping, points, tol);
        let values: Vec<(DVec3, DVec2, DVec2)> = points
            .iter()
            .map(|&(p, mesh)| {
                (
                    p,
                    formula.eval(&super::inputs_of(p, mesh)),
                    map_uv_f64(mapping, p),
                )
            })
            .collect();
        let share = |test: &dyn Fn(DVec3, DVec2, DVec2) -> bool| {
            let n = values
                .iter()
                .filter(|(p, got, want)| got.is_finite() && test(*p, *got, *want))
                .count();
            share_of(n, values.len())
        };
        let within = |got: DVec2, want: DVec2, on: On| {
            let d = difference(mapping, got, want);
            match on {
                On::U => d.x <= tol.x,
                On::V => d.y <= tol.y,
                On::Both => d.x <= tol.x && d.y <= tol.y,
            }
        };
        let count = |on: On| {
            values
                .iter()
                .filter(|(_, got, want)| got.is_finite() && within(*got, *want, on))
                .count()
        };
        let (u_agreeing, v_agreeing) = (count(On::U), count(On::V));
        let mut verdict = Self {
            agreement,
            u_agreeing,
            v_agreeing,
            findings: Vec::new(),
        };
        if agreement.share() >= CORRECT_SHARE {
            return verdict;
        }
        let follows = |m: Mistake, on: On| {
            m.applies(mapping, on)
                && share(&|p, got, want| {
                    m.candidates(mapping, p, want)
                        .into_iter()
                        .any(|c| within(got, c, on))
                }) >= HINT_SHARE
        };
        let (u_ok, v_ok) = (verdict.u_agrees(), verdict.v_agrees());
        if !u_ok
            && !v_ok
            && let Some(&m) = BOTH.iter().find(|&&m| follows(m, On::Both))
        {
            verdict.findings.push(Finding {
                mistake: m,
                on: On::Both,
            });
            return verdict;
        }
        for (ok, on, list) in [(u_ok, On::U, &ON_U[..]), (v_ok, On::V, &ON_V[..])] {
            if let Some(&m) = list.iter().find(|&&m| !ok && follows(m, on)) {
                verdict.findings.push(Finding { mistake: m, on });
            }
        }
        verdict
    }

    /// Whether u agrees on at least [`CORRECT_SHARE`] of the points.
    #[must_use]
    pub fn u_agrees(&self) -> bool {
        share_of(self.u_agreeing, self.agreement.points) >= CORRECT_SHARE
    }

    /// Whether v agrees on at least [`CORRECT_SHARE`] of the points.
    #[must_use]
    pub fn v_agrees(&self) -> bool {
        share_of(self.v_agreeing, self.agreement.points) >= CORRECT_SHARE
    }

    /// Whether the formula is correct: u and v together agree on [`CORRECT_SHARE`].
    #[must_use]
    pub fn correct(&self) -> bool {
        self.agreement.share() >= CORRECT_SHARE
    }

    /// The mistakes found, without the formula they are in.
    #[must_use]
    pub fn mistakes(&self) -> Vec<Mistake> {
        self.findings.iter().map(|f| f.mistake).collect()
    }

    /// `u agrees; v does not`, `neither u nor v agrees`, ...
    #[must_use]
    pub fn judgement(&self) -> &'static str {
        match (self.u_agrees(), self.v_agrees()) {
            (true, true) if self.correct() => "u and v agree",
            (true, true) => "u and v each agree almost everywhere, but not at the same points",
            (true, false) => "u agrees; v does not",
            (false, true) => "v agrees; u does not",
            (false, false) => "neither u nor v agrees",
        }
    }

    /// The hint in two steps, none for a correct formula: which formula agrees and what is
    /// wrong with the other (or both), then the fix. A formula that fits no common mistake
    /// is named as such, with the lecture's formula as its fix where there is one.
    #[must_use]
    pub fn hint(&self, mapping: Mapping) -> Option<Hint> {
        if self.correct() {
            return None;
        }
        Some(hints::two_steps(self, mapping))
    }
}

/// The mistakes the formula makes against `mapping` (as [`Verdict::judge`] finds them), none
/// for a correct formula.
#[must_use]
pub fn mistakes(
    formula: &FormulaMapping,
    mapping: Mapping,
    points: &[(DVec3, DVec2)],
    tol: DVec2,
) -> Vec<Mistake> {
    Verdict::judge(formula, mapping, points, tol).mistakes()
}

mod hints;

/// The lecture's mappings written as formulas in texplore's conventions (what the README
/// shows): each mapping's file holds its own ([`Mapping::lecture_formula`]).
#[must_use]
pub const fn lecture_formula(mapping: Mapping) -> Option<(&'static str, &'static str)> {
    mapping.lecture_formula()
}
