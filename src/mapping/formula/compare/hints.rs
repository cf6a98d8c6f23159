//! The hints' words, in two steps: what is wrong (which the student can act on alone), then
//! the fix. Each step names the formula it is about (`v is upside down at the poles ...`,
//! `... write v = 1 - acos(y) / pi`), so the steps of two formulas can stand side by side.

use super::{Finding, Hint, Kind, Mistake, On, Verdict, kind, lecture_formula};
use crate::mapping::Mapping;

/// The formula of `on` written short, in texplore's conventions (the light probe's as the
/// lecture writes it); none where the lecture writes none (the panoramic and mirror-ball
/// probes) or for both formulas at once.
fn formula(mapping: Mapping, on: On) -> Option<&'static str> {
    match (kind(mapping), on) {
        (_, On::Both) => None,
        (Kind::Rectangle, On::U) => Some("(z + 1) / 2"),
        (Kind::Rectangle, On::V) => Some("(x + 1) / 2"),
        (Kind::Cylinder | Kind::Sphere, On::U) => Some("fract(atan2(x, z) / tau)"),
        (Kind::Cylinder, On::V) => Some("(y + 1) / 2"),
        (Kind::Sphere, On::V) => Some("1 - acos(y) / pi"),
        (Kind::Probe, On::U) => lecture_formula(mapping).map(|f| f.0),
        (Kind::Probe, On::V) => lecture_formula(mapping).map(|f| f.1),
    }
}

/// `reason: write u = ...`, or the reason alone where there is no formula to write.
fn write(reason: &str, mapping: Mapping, on: On) -> String {
    match formula(mapping, on) {
        Some(f) => format!("{reason}: write {} = {f}", on.name()),
        None => reason.to_owned(),
    }
}

/// Step 1 of a finding: what is wrong, starting with the formula it is in.
pub(super) fn what(f: Finding, mapping: Mapping) -> String {
    let k = kind(mapping);
    let c = f.on.name();
    let shape = match k {
        Kind::Rectangle => "across the rectangle",
        Kind::Cylinder => "up the cylinder",
        Kind::Sphere => "from pole to pole",
        Kind::Probe => "across the probe's disc",
    };
    match (f.mistake, k) {
        (Mistake::Swapped, _) => {
            "u and v are swapped (your u gives what v should, and your v what u should)".into()
        }
        (Mistake::MirroredU, Kind::Probe) => "the image is mirrored left to right (u runs the wrong way)".into(),
        (Mistake::MirroredU, _) => "u runs the wrong way (the image is mirrored left to right)".into(),
        (Mistake::Atan2Arguments, _) => {
            "u is measured from the wrong axis (it starts on +x and runs toward +z)".into()
        }
        (Mistake::FlippedV, Kind::Sphere) => "v is upside down at the poles (your v is 0 at the north pole, where the image's top row is)".into(),
        (Mistake::FlippedV, Kind::Cylinder) => "v is upside down (your v is 0 at the top of the cylinder, where the image's top row is)".into(),
        (Mistake::FlippedV, _) => "v is upside down (the image is flipped top to bottom)".into(),
        (Mistake::QuarterTurn, Kind::Probe) => "the image is turned by a quarter turn about its centre".into(),
        (Mistake::QuarterTurn, _) => "u is a quarter turn off (u = 0 is not on +z)".into(),
        (Mistake::HalfTurn, Kind::Probe) => "the image is turned by a half turn about its centre".into(),
        (Mistake::HalfTurn, _) => "u is a half turn off (u = 0 is on -z, at the back, not on +z)".into(),
        (Mistake::Degrees, _) if f.on == On::Both => {
            "an angle is in degrees where radians are meant (or the other way)".into()
        }
        (Mistake::Degrees, _) => format!("{c} mixes degrees and radians"),
        (Mistake::MissingTwoPi, _) => "u is not a share of a whole turn (it goes from 0 to 1 more than once, or only half way, once around)".into(),
        (Mistake::MissingShift, Kind::Cylinder) => format!("v runs over the wrong range ({shape} it must go from 0 at the bottom to 1 at the top)"),
        (Mistake::MissingShift, _) if f.on == On::Both => {
            format!("a coordinate runs over the wrong range ({shape} u and v must go from 0 to 1)")
        }
        (Mistake::MissingShift, _) => {
            format!("{c} runs over the wrong range ({shape} it must go from 0 to 1)")
        }
        (Mistake::AsinForAcos, _) => {
            "v is measured from the equator, not from the north pole".into()
        }
        (Mistake::WrongAxis, _) if f.on == On::Both => "a formula follows the wrong axis".into(),
        (Mistake::WrongAxis, _) => format!("{c} follows the wrong axis"),
    }
}

/// Step 2 of a finding: the fix, ending with the formula to write where there is one.
pub(super) fn fix(f: Finding, mapping: Mapping) -> Option<String> {
    let k = kind(mapping);
    let on = f.on;
    let around = "phi = atan2(x, z) is 0 on +z and grows toward +x, and u = phi / 2 pi";
    Some(match (f.mistake, k) {
        (Mistake::Swapped, Kind::Rectangle) => {
            "exchange the two formulas: u follows z and v follows x, u = (z + 1) / 2 and v = (x + 1) / 2".into()
        }
        (Mistake::Swapped, _) => "exchange the two formulas".into(),
        (Mistake::MirroredU, Kind::Rectangle) => write("u grows with z", mapping, On::U),
        (Mistake::MirroredU, Kind::Probe) => write(
            "u = (1 + r cos beta) / 2 with cos beta = x / sqrt(x^2 + y^2): plus r cos beta, not minus",
            mapping,
            On::U,
        ),
        (Mistake::MirroredU, _) => write(around, mapping, On::U),
        (Mistake::Atan2Arguments, _) => write(
            "texplore's phi = atan2(x, z), x first: 0 on +z, growing toward +x",
            mapping,
            On::U,
        ),
        (Mistake::FlippedV, Kind::Sphere) => write(
            "theta = acos(y) is 0 at the north pole, but v = 0 is the bottom of the image",
            mapping,
            On::V,
        ),
        (Mistake::FlippedV, Kind::Cylinder) => {
            write("y grows upward, as v does", mapping, On::V)
        }
        (Mistake::FlippedV, Kind::Rectangle) => write("v grows with x", mapping, On::V),
        (Mistake::FlippedV, Kind::Probe) => write(
            "v = (1 + r sin beta) / 2 with sin beta = y / sqrt(x^2 + y^2): v = 0 is the bottom of the image",
            mapping,
            On::V,
        ),
        (Mistake::QuarterTurn | Mistake::HalfTurn, Kind::Probe) => {
            "beta is measured from +x toward +y: cos beta = x / sqrt(x^2 + y^2) goes in u, sin beta = y / sqrt(x^2 + y^2) in v".into()
        }
        (Mistake::QuarterTurn, _) => write(
            "atan2(x, z) is already 0 on +z: add or take away no quarter",
            mapping,
            On::U,
        ),
        (Mistake::HalfTurn, _) => write(
            "atan2 is already the angle from +z; do not add 0.5 or pi to it, bring it into [0, 1) with fract",
            mapping,
            On::U,
        ),
        (Mistake::Degrees, _) if on == On::Both => "atan2, acos and asin give radians, so divide by tau or pi, not by 360 or 180".into(),
        (Mistake::Degrees, _) if on == On::V => {
            write("acos gives radians: divide by pi, not 180", mapping, On::V)
        }
        (Mistake::Degrees, _) => write(
            "atan2 gives radians: divide by tau (2 pi), not 360",
            mapping,
            On::U,
        ),
        (Mistake::MissingTwoPi, _) => write(
            "atan2 gives radians, from -pi to pi, and a whole turn is 2 pi (tau); fract brings the result into [0, 1)",
            mapping,
            On::U,
        ),
        (Mistake::MissingShift, Kind::Cylinder) => {
            write("y runs from -1 to 1, so bring it into [0, 1]", mapping, On::V)
        }
        (Mistake::MissingShift, Kind::Rectangle) if on != On::Both => write(
            if on == On::U {
                "z runs from -1 to 1, so bring it into [0, 1]"
            } else {
                "x runs from -1 to 1, so bring it into [0, 1]"
            },
            mapping,
            on,
        ),
        (Mistake::MissingShift, _) => {
            write("(t + 1) / 2 takes t from [-1, 1] into [0, 1]", mapping, on)
        }
        (Mistake::AsinForAcos, _) => write(
            "asin(y) is the latitude, 0 at the equator; theta = acos(y) is the angle from the north pole (or use 0.5 + asin(y) / pi)",
            mapping,
            On::V,
        ),
        (Mistake::WrongAxis, Kind::Cylinder | Kind::Sphere) if on == On::U => write(
            "u is the angle around the y axis, phi = atan2(x, z)",
            mapping,
            On::U,
        ),
        (Mistake::WrongAxis, Kind::Cylinder) if on == On::V => {
            write("v is the height along the cylinder's axis, y", mapping, On::V)
        }
        (Mistake::WrongAxis, Kind::Sphere) if on == On::V => write(
            "theta is measured from the north pole, on +y",
            mapping,
            On::V,
        ),
        (Mistake::WrongAxis, Kind::Rectangle) if on != On::Both => write(
            "on the rectangle u follows z and v follows x",
            mapping,
            on,
        ),
        (Mistake::WrongAxis, Kind::Probe) if on != On::Both => write(
            "the probe looks along +z: alpha = acos(z), and beta comes from x and y",
            mapping,
            on,
        ),
        (Mistake::WrongAxis, _) => return None,
    })
}

/// The lecture's formula of a formula that fits no common mistake, as its fix.
fn lecture(mapping: Mapping, on: On) -> Option<String> {
    formula(mapping, on).map(|f| format!("the lecture's {} = {f}", on.name()))
}

/// The verdict's two steps (for a formula that is not correct).
pub(super) fn two_steps(v: &Verdict, mapping: Mapping) -> Hint {
    let (wrong, prefix): (Vec<On>, &str) = match (v.u_agrees(), v.v_agrees()) {
        (true, true) => {
            return Hint {
                what: format!("{}: compare them in the difference view", v.judgement()),
                fix: None,
            };
        }
        (true, false) => (vec![On::V], "u agrees; "),
        (false, true) => (vec![On::U], "v agrees; "),
        (false, false) => (vec![On::U, On::V], "neither u nor v agrees: "),
    };
    let both = v.findings.iter().find(|f| f.on == On::Both);
    let (whats, fixes): (Vec<String>, Vec<Option<String>>) = match both {
        Some(&f) => (vec![what(f, mapping)], vec![fix(f, mapping)]),
        None => wrong
            .iter()
            .map(|&on| match v.findings.iter().find(|f| f.on == on) {
                Some(&f) => (what(f, mapping), fix(f, mapping)),
                None => (
                    format!("{} fits no common mistake", on.name()),
                    lecture(mapping, on),
                ),
            })
            .unzip(),
    };
    let fixes: Vec<String> = fixes.into_iter().flatten().collect();
    Hint {
        what: format!("{prefix}{}", whats.join("; ")),
        fix: (!fixes.is_empty()).then(|| fixes.join("; ")),
    }
}
