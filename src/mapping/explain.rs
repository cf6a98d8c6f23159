//! The lecture's formulas with a hit point's numbers substituted, for `texplore map` and the
//! GUI's inspector.
//!
//! The worked formulas run in f64 (a teaching tool shows the lecture's arithmetic, not f32
//! rounding: a point such as (5e-324, 5e-324, 1) is not flushed to the axis), with the same
//! special cases as the renderer's f32 formulas in the parent module: the same (u, v) up to
//! f32 rounding (tested on many points), the same seam, poles and antipode.

use super::{Map, Mapping, with_map};
use glam::{DVec2, DVec3, Vec3A};
use std::f64::consts::TAU;

/// Below this polar angle (radians) from a pole, the spherical map's worked formula shows the
/// atan2 form the renderer runs instead of acos(y): 0.05 rad is where y = cos(theta) keeps only
/// three significant digits of theta's information in four decimals.
pub(super) const POLE_THETA: f64 = 0.05;

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
pub(super) use line;

/// [`explain_number`], as the worked formulas write it.
pub(super) fn n(x: f64) -> String {
    explain_number(x)
}

/// The f64 formulas of `mapping`'s file, writing their lines to `out` when it is `Some`.
fn worked(mapping: Mapping, p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
    let uv = with_map!(mapping, M => M::worked(p, out));
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

/// The azimuth phi = atan2(x, z) brought into [0, 2 pi), for the mapping diagram.
pub(super) fn phi(p: DVec3) -> f64 {
    let a = p.x.atan2(p.z);
    if a < 0.0 { a + TAU } else { a }
}

/// u = phi / 2 pi with phi = atan2(x, z) brought into [0, 2 pi), u in [0, 1): u = 1 is the
/// seam, read as u = 0 (the renderer's `azimuth`).
pub(super) fn azimuth(x: f64, z: f64, out: &mut Option<Vec<String>>) -> f64 {
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

/// The unit direction of a point from its rescaled copy `q` and the scale [`rescaled`] divided
/// it by, saying so when the point was off the unit sphere. |p| comes from the rescaled point:
/// `p.length()` would square 1e300 into infinity.
pub(super) fn unit_direction(q: DVec3, scale: f64, out: &mut Option<Vec<String>>) -> DVec3 {
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

/// `p` divided by its largest component (squares neither overflow nor underflow), `None` for
/// the origin and for NaN or infinite input: the renderer's `rescaled`.
pub(super) fn rescaled(p: DVec3) -> Option<(DVec3, f64)> {
    let s = p.abs().max_element();
    (s > 0.0 && s.is_finite()).then(|| (p / s, s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

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
