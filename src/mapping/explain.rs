//! The lecture's formulas with a hit point's numbers substituted, for `texplore map` and the
//! GUI's inspector.
//!
//! The worked formulas run in f64 (a teaching tool shows the lecture's arithmetic, not f32
//! rounding: a point such as (5e-324, 5e-324, 1) is not flushed to the axis), with the same
//! special cases as the renderer's f32 formulas in the parent module: the same (u, v) up to
//! f32 rounding (tested on many points), the same seam, poles and antipode.

use super::Mapping;
use glam::{DVec2, DVec3, Vec3A};
use std::f64::consts::{PI, TAU};

/// Below this polar angle (radians) from a pole, the spherical map's worked formula shows the
/// atan2 form the renderer runs instead of acos(y): 0.05 rad is where y = cos(theta) keeps only
/// three significant digits of theta's information in four decimals.
pub const POLE_THETA: f64 = 0.05;

/// A number as the worked formulas print it: four decimals, in scientific notation when that
/// would show nothing (below 1e-4, 1e6 and above), and in full when four decimals would round
/// to a whole number the value is not (0.99999994 is not 1: it picks a different texel).
#[must_use]
pub fn explain_number(x: f64) -> String {
    let a = x.abs();
    if x != 0.0 && a.is_finite() && !(1e-4..1e6).contains(&a) {
        return format!("{x:.4e}");
    }
    let short = format!("{x:.4}");
    let shown: f64 = short.parse().unwrap_or(x);
    if shown != x && shown.fract() == 0.0 {
        format!("{x}")
    } else {
        short
    }
}

/// The formula lines that take the local hit point `p` (f32, as the renderer has it) to (u, v)
/// under `mapping`, worked in f64 from the exact value of `p`.
#[must_use]
pub fn explain_mapping(mapping: Mapping, p: Vec3A) -> Vec<String> {
    explain_mapping_f64(mapping, p.as_dvec3()).0
}

/// (u, v) of `p` under `mapping` by the f64 formulas `texplore map` shows: the renderer's
/// [`Mapping::map_point`] up to f32 rounding.
#[must_use]
pub fn map_uv_f64(mapping: Mapping, p: DVec3) -> DVec2 {
    worked(mapping, p, &mut None)
}

/// The formula lines that take the local hit point `p` to (u, v) under `mapping`, in f64, and
/// the (u, v) they arrive at.
#[must_use]
pub fn explain_mapping_f64(mapping: Mapping, p: DVec3) -> (Vec<String>, DVec2) {
    let mut out = Some(Vec::new());
    let uv = worked(mapping, p, &mut out);
    (out.unwrap_or_default(), uv)
}

/// Pushes a line when lines are wanted (formatting is skipped for [`map_uv_f64`]).
macro_rules! line {
    ($out:expr, $($arg:tt)*) => {
        if let Some(lines) = $out.as_mut() {
            lines.push(format!($($arg)*));
        }
    };
}

/// The f64 formulas, writing their lines to `out` when it is `Some`.
fn worked(mapping: Mapping, p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
    let n = explain_number;
    let uv = match mapping {
        Mapping::Rectangular => {
            let (u, v) = ((p.z + 1.0) * 0.5, (p.x + 1.0) * 0.5);
            line!(out, "u = (z + 1) / 2 = ({} + 1) / 2 = {}", n(p.z), n(u));
            line!(out, "v = (x + 1) / 2 = ({} + 1) / 2 = {}", n(p.x), n(v));
            DVec2::new(u, v)
        }
        Mapping::Cylindrical => {
            // The lecture's atan2(x, z) on the point as given (libm's atan2 is exact at any
            // scale); the renderer's rescaling only keeps its f32 squares finite.
            let u = if rescaled(DVec3::new(p.x, 0.0, p.z)).is_some() {
                azimuth(p.x, p.z, out)
            } else {
                line!(
                    out,
                    "x = z = 0 (on the axis): phi is undefined, u = 0 as the renderer"
                );
                0.0
            };
            let raw = (p.y + 1.0) * 0.5;
            line!(out, "v = (y + 1) / 2 = ({} + 1) / 2 = {}", n(p.y), n(raw));
            let v = if raw.is_nan() {
                0.5
            } else {
                raw.clamp(0.0, 1.0)
            };
            if v != raw {
                line!(
                    out,
                    "off the cylinder's height: v clamped into [0, 1], v = {}",
                    n(v)
                );
            }
            DVec2::new(u, v)
        }
        Mapping::Spherical | Mapping::Uv => {
            let Some((q, scale)) = rescaled(p) else {
                line!(
                    out,
                    "p = (0, 0, 0) or not finite: no direction, (u, v) = (0, 0.5) as the renderer"
                );
                return DVec2::new(0.0, 0.5);
            };
            let nq = unit_direction(q, scale, out);
            let u = azimuth(nq.x, nq.z, out);
            // theta = acos(y / |p|), computed as atan2(sqrt(x^2 + z^2), y) (exact off the
            // sphere, as the renderer).
            let theta = q.x.hypot(q.z).atan2(q.y);
            if (theta.min(PI - theta)) < POLE_THETA {
                // acos is ill-conditioned at +-1: y = cos(0.0077) = 0.99997 prints as 1.0000,
                // and acos(1.0000) = 0.0077 looks wrong. Show the formula the renderer runs.
                line!(
                    out,
                    "near the {} pole: theta = atan2(sqrt(x^2 + z^2), y) = atan2({}, {}) = {} rad",
                    if q.y > 0.0 { "north" } else { "south" },
                    n(nq.x.hypot(nq.z)),
                    n(nq.y),
                    n(theta)
                );
                line!(
                    out,
                    "(acos(y) is the same angle, but y is within {} of {}1 here, where acos loses \
                     its digits: the renderer computes theta with atan2, exact at the poles)",
                    n(1.0 - nq.y.abs()),
                    if q.y > 0.0 { "" } else { "-" }
                );
            } else {
                line!(
                    out,
                    "theta = acos(y) = acos({}) = {} rad",
                    n(nq.y.clamp(-1.0, 1.0)),
                    n(theta)
                );
            }
            let v = (1.0 - theta / PI).clamp(0.0, 1.0);
            line!(out, "v = 1 - theta / pi = {}", n(v));
            if mapping == Mapping::Uv {
                line!(
                    out,
                    "(uv: this shape carries no (u, v) of its own, so its natural spherical map is used)"
                );
            }
            DVec2::new(u, v)
        }
        Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall => probe(mapping, p, out),
    };
    if uv.is_finite() {
        uv
    } else {
        line!(
            out,
            "(u, v) is not finite: (0.5, 0.5), as the renderer answers for NaN and infinite input"
        );
        DVec2::splat(0.5)
    }
}

/// u = phi / 2 pi with phi = atan2(x, z) brought into [0, 2 pi), u in [0, 1): u = 1 is the
/// seam, read as u = 0 (the renderer's `azimuth`).
fn azimuth(x: f64, z: f64, out: &mut Option<Vec<String>>) -> f64 {
    let n = explain_number;
    let raw = x.atan2(z);
    line!(
        out,
        "phi = atan2(x, z) = atan2({}, {}) = {} rad",
        n(x),
        n(z),
        n(raw)
    );
    let phi = if raw < 0.0 {
        let phi = raw + TAU;
        line!(out, "phi < 0, so phi += 2 pi: phi = {} rad", n(phi));
        phi
    } else {
        raw
    };
    let u = phi / TAU;
    line!(out, "u = phi / (2 pi) = {}", n(u));
    if u < 1.0 {
        u.max(0.0) + 0.0
    } else {
        line!(
            out,
            "u = 1 is the seam u = 0 (u = 0 and u = 1 are one meridian): u = 0"
        );
        0.0
    }
}

/// The light-probe maps: alpha = acos(z) (of -z for the panoramic), r = alpha / pi (sin(alpha
/// / 2) for the mirror ball), u = (1 + r cos beta) / 2, v = (1 + r sin beta) / 2.
fn probe(mapping: Mapping, p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
    let n = explain_number;
    let Some((q, scale)) = rescaled(p) else {
        line!(
            out,
            "p = (0, 0, 0) or not finite: no direction, (u, v) = (0.5, 0.5) as the renderer"
        );
        return DVec2::splat(0.5);
    };
    let nq = unit_direction(q, scale, out);
    let flip = mapping == Mapping::Panoramic;
    let z = if flip { -nq.z } else { nq.z };
    let d = nq.x.hypot(nq.y);
    let alpha = d.atan2(z);
    if flip {
        line!(
            out,
            "alpha = acos(-z) = acos({}) = {} rad (panoramic: z flipped)",
            n(z),
            n(alpha)
        );
    } else {
        line!(out, "alpha = acos(z) = acos({}) = {} rad", n(z), n(alpha));
    }
    let r = if mapping == Mapping::MirrorBall {
        (alpha * 0.5).sin()
    } else {
        alpha / PI
    };
    // beta from (x, y) rescaled on its own, so tiny x and y keep their direction.
    let (cos_b, sin_b) = match rescaled(DVec3::new(nq.x, nq.y, 0.0)) {
        Some((b, _)) => {
            let h = b.x.hypot(b.y);
            let (c, s) = (b.x / h, b.y / h);
            line!(
                out,
                "sin beta = y / sqrt(x^2 + y^2) = {}, cos beta = x / sqrt(x^2 + y^2) = {}",
                n(s),
                n(c)
            );
            (c, s)
        }
        None if z > 0.0 => {
            line!(
                out,
                "x = y = 0: beta is undefined (the lecture divides by zero), but r = 0 here: the image centre"
            );
            (0.0, 0.0)
        }
        None => {
            line!(
                out,
                "x = y = 0 at the antipode: beta is undefined (the whole rim meets here); the rim point beta = 0 is used"
            );
            (1.0, 0.0)
        }
    };
    if mapping == Mapping::MirrorBall {
        line!(out, "r = sin(alpha / 2) = {} (mirror ball)", n(r));
    } else {
        line!(out, "r = alpha / pi = {}", n(r));
    }
    let u = (0.5 + 0.5 * r * cos_b).clamp(0.0, 1.0);
    let v = (0.5 + 0.5 * r * sin_b).clamp(0.0, 1.0);
    line!(out, "u = (1 + r cos beta) / 2 = {}", n(u));
    line!(out, "v = (1 + r sin beta) / 2 = {}", n(v));
    DVec2::new(u, v)
}

/// `p` divided by its largest component (squares neither overflow nor underflow), `None` for
/// the origin and for NaN or infinite input: the renderer's `rescaled`.
/// The unit direction of a point from its rescaled copy `q` and the scale [`rescaled`] divided
/// it by, saying so when the point was off the unit sphere. |p| comes from the rescaled point:
/// `p.length()` would square 1e300 into infinity.
fn unit_direction(q: DVec3, scale: f64, out: &mut Option<Vec<String>>) -> DVec3 {
    let n = explain_number;
    let len = q.length();
    let nq = q / len;
    let length = len * scale;
    if ((length - 1.0).abs()) >= 1e-4 {
        line!(
            out,
            "|p| = {}: normalised to the unit sphere, ({}, {}, {})",
            n(length),
            n(nq.x),
            n(nq.y),
            n(nq.z)
        );
    }
    nq
}

fn rescaled(p: DVec3) -> Option<(DVec3, f64)> {
    let s = p.abs().max_element();
    (s > 0.0 && s.is_finite()).then(|| (p / s, s))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_a_pole_the_worked_formula_is_the_atan2_the_renderer_runs() {
        // 0.0077 rad from the north pole: y = cos(0.0077) = 0.99997.
        let t: f64 = 0.0077;
        let p = DVec3::new(t.sin(), t.cos(), 0.0);
        let (lines, uv) = explain_mapping_f64(Mapping::Spherical, p);
        let theta = lines
            .iter()
            .find(|l| l.contains("theta ="))
            .expect("a theta line");
        assert!(
            theta.starts_with("near the north pole: theta = atan2(sqrt(x^2 + z^2), y)"),
            "{theta}"
        );
        assert!(theta.ends_with("= 0.0077 rad"), "{theta}");
        assert!(
            !lines.iter().any(|l| l.contains("acos(1.0000)")),
            "{lines:?}"
        );
        assert!(
            lines
                .iter()
                .any(|l| l.contains("atan2, exact at the poles"))
        );
        assert!((uv.y - (1.0 - t / PI)).abs() < 1e-12);
        // South.
        let (lines, _) = explain_mapping_f64(Mapping::Spherical, DVec3::new(0.01, -1.0, 0.0));
        assert!(lines.iter().any(|l| l.starts_with("near the south pole")));
        // Away from the poles the lecture's acos stays.
        let (lines, _) = explain_mapping_f64(Mapping::Spherical, DVec3::new(0.6, 0.8, 0.0));
        assert!(
            lines
                .iter()
                .any(|l| l == "theta = acos(y) = acos(0.8000) = 0.6435 rad")
        );
    }
}
