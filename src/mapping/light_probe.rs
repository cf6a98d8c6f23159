//! The light-probe (angular) map, the lecture's `LightProbe` mapping: with alpha = acos(z) the
//! angle from +z and beta the direction about it, r = alpha / pi, u = (1 + r cos beta) / 2,
//! v = (1 + r sin beta) / 2. Its panoramic and mirror-ball variants (`panoramic.rs`,
//! `mirror_ball.rs`) run the same formulas with z flipped or r = sin(alpha / 2).

use super::explain::{line, n, rescaled as rescaled_f64, unit_direction};
use super::shared::rescaled;
use super::{Family, Map, Mapped, MappingAngles};
use crate::math::lanes::{F, M, V3, atan2, clamp, neg, select};
use crate::math::{PI, Vec3A};
use glam::{DVec2, DVec3};
use pulp::Simd;

/// See the module documentation.
pub(crate) struct LightProbe;

impl Map for LightProbe {
    const U_PERIODIC: bool = false;
    const V_CLAMPS: bool = false;
    const FAMILY: Family = Family::Probe;
    const LECTURE: Option<(&'static str, &'static str)> = Some((
        "(1 + acos(z / sqrt(x*x + y*y + z*z)) / pi * x / sqrt(x*x + y*y)) / 2",
        "(1 + acos(z / sqrt(x*x + y*y + z*z)) / pi * y / sqrt(x*x + y*y)) / 2",
    ));

    #[inline(always)]
    fn lanes<S: Simd, const GRAD: bool>(s: S, p: &V3<S>) -> Mapped<S> {
        probe::<S, GRAD>(s, p, false, Curve::Angular)
    }

    fn worked(p: DVec3, out: &mut Option<Vec<String>>) -> DVec2 {
        worked_probe(p, false, Curve::Angular, out)
    }

    fn angles(p: DVec3) -> MappingAngles {
        probe_angles(p, false, Curve::Angular)
    }
}

/// How far from the image centre a direction lands.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Curve {
    /// r = alpha / pi (the lecture).
    Angular,
    /// r = sin(alpha / 2) (a photographed mirror ball).
    MirrorBall,
}

/// The light-probe maps per lane. With n = p / |p| and d = sqrt(nx^2 + ny^2), the lecture's
/// u = (1 + r(alpha) nx / d) / 2 is written as u = (1 + g nx) / 2 with g = r(alpha) / d, which
/// is smooth through the z axis (g -> 1 / pi): no division by zero where the lecture's cos beta
/// is 0 / 0. Only the antipode (alpha = pi), where the whole rim meets, is singular; it maps to
/// the rim point beta = 0, (u, v) = (1, 0.5). Every branch is computed and the lane's chosen by
/// selects.
#[inline(always)]
pub(super) fn probe<S: Simd, const GRAD: bool>(
    s: S,
    p: &V3<S>,
    flip_z: bool,
    curve: Curve,
) -> Mapped<S> {
    let (zero, one, half) = (s.splat_f32s(0.0), s.splat_f32s(1.0), s.splat_f32s(0.5));
    let zero3 = V3::splat(s, Vec3A::ZERO);
    let (q, scale, ok) = rescaled(s, p);
    let q_len = s.sqrt_f32s(q.dot(s, &q));
    let nv = q.div(s, q_len);
    let len = s.mul_f32s(q_len, scale);
    let (x, y) = (nv.x, nv.y);
    let z = if flip_z { neg(s, nv.z) } else { nv.z };
    let d = s.sqrt_f32s(s.add_f32s(s.mul_f32s(x, x), s.mul_f32s(y, y)));
    // g = r / d and its derivatives with respect to (x, y, z) of the unit vector; `antipode`
    // where the whole rim meets.
    let (g, dg_dd_over_d, dg_dz, antipode): (F<S>, F<S>, F<S>, M<S>) = match curve {
        Curve::Angular => {
            let alpha = atan2(s, d, z);
            let dd = s.mul_f32s(d, d);
            // Series about the axis: alpha / d = 1 + d^2 / 6 ..., dg/dd / d = (2/3 + d^2/5)/pi.
            let series = s.and_m32s(
                s.less_than_f32s(d, s.splat_f32s(1e-2)),
                s.greater_than_f32s(z, zero),
            );
            let g_series = s.div_f32s(
                s.add_f32s(one, s.div_f32s(dd, s.splat_f32s(6.0))),
                s.splat_f32s(PI),
            );
            let dgdd_series = s.div_f32s(
                neg(
                    s,
                    s.add_f32s(s.splat_f32s(2.0 / 3.0), s.div_f32s(dd, s.splat_f32s(5.0))),
                ),
                s.splat_f32s(PI),
            );
            let pid = s.mul_f32s(s.splat_f32s(PI), d);
            let g_far = s.div_f32s(alpha, pid);
            let dgdd_far = s.div_f32s(s.sub_f32s(z, s.div_f32s(alpha, d)), s.mul_f32s(pid, d));
            let off_axis = s.greater_than_f32s(d, zero);
            (
                select(s, series, g_series, g_far),
                select(s, series, dgdd_series, dgdd_far),
                s.splat_f32s(-1.0 / PI),
                s.not_m32s(s.or_m32s(series, off_axis)),
            )
        }
        Curve::MirrorBall => {
            // r = sin(alpha / 2) = sqrt((1 - z) / 2); g = r / d = 1 / (2 cos(alpha / 2))
            // = 1 / sqrt(2 (1 + z)).
            let s2 = s.mul_f32s(s.splat_f32s(2.0), s.add_f32s(one, z));
            let g = s.div_f32s(one, s.sqrt_f32s(s2));
            (
                g,
                zero,
                s.mul_f32s(s.mul_f32s(neg(s, g), g), g),
                s.less_than_or_equal_f32s(s2, s.splat_f32s(1e-12)),
            )
        }
    };
    let u = clamp(
        s,
        s.add_f32s(half, s.mul_f32s(s.mul_f32s(half, g), x)),
        0.0,
        1.0,
    );
    let v = clamp(
        s,
        s.add_f32s(half, s.mul_f32s(s.mul_f32s(half, g), y)),
        0.0,
        1.0,
    );
    let (grad_u, grad_v) = if GRAD {
        // The gradient with respect to n (x, y, z treated as free), then projected onto the
        // sphere's tangent plane and divided by |p|.
        let dz = if flip_z { neg(s, dg_dz) } else { dg_dz };
        let grad_g = V3 {
            x: s.mul_f32s(x, dg_dd_over_d),
            y: s.mul_f32s(y, dg_dd_over_d),
            z: dz,
        };
        let xg = grad_g.scale(s, x);
        let yg = grad_g.scale(s, y);
        let gu = V3 {
            x: s.add_f32s(g, xg.x),
            y: s.add_f32s(zero, xg.y),
            z: s.add_f32s(zero, xg.z),
        }
        .scale(s, half);
        let gv = V3 {
            x: s.add_f32s(zero, yg.x),
            y: s.add_f32s(g, yg.y),
            z: s.add_f32s(zero, yg.z),
        }
        .scale(s, half);
        (tangent(s, &gu, &nv, len), tangent(s, &gv, &nv, len))
    } else {
        (zero3, zero3)
    };
    let rim = s.and_m32s(ok, antipode);
    let keep = s.and_m32s(ok, s.not_m32s(antipode));
    Mapped {
        u: select(s, keep, u, select(s, rim, one, half)),
        v: select(s, keep, v, half),
        grad_u: V3::select(s, keep, &grad_u, &zero3),
        grad_v: V3::select(s, keep, &grad_v, &zero3),
    }
}

/// A gradient `gr` with respect to the unit direction `n` projected onto the sphere's tangent
/// plane and divided by |p|; zero where that is not finite.
#[inline(always)]
fn tangent<S: Simd>(s: S, gr: &V3<S>, n: &V3<S>, len: F<S>) -> V3<S> {
    let t = gr.sub(s, &n.scale(s, n.dot(s, gr))).div(s, len);
    V3::select(s, t.finite(s), &t, &V3::splat(s, Vec3A::ZERO))
}

/// The light-probe maps worked in f64: alpha = acos(z) (of -z for the panoramic), r = alpha /
/// pi (sin(alpha / 2) for the mirror ball), u = (1 + r cos beta) / 2, v = (1 + r sin beta) / 2.
pub(super) fn worked_probe(
    p: DVec3,
    flip: bool,
    curve: Curve,
    out: &mut Option<Vec<String>>,
) -> DVec2 {
    let Some((q, scale)) = rescaled_f64(p) else {
        line!(
            out,
            "p = (0, 0, 0) or not finite: no direction, (u, v) = (0.5, 0.5) as the renderer"
        );
        return DVec2::splat(0.5);
    };
    let nq = unit_direction(q, scale, out);
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
    let r = match curve {
        Curve::MirrorBall => (alpha * 0.5).sin(),
        Curve::Angular => alpha / std::f64::consts::PI,
    };
    // beta from (x, y) rescaled on its own, so tiny x and y keep their direction.
    let (cos_b, sin_b) = match rescaled_f64(DVec3::new(nq.x, nq.y, 0.0)) {
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
    match curve {
        Curve::MirrorBall => line!(out, "r = sin(alpha / 2) = {} (mirror ball)", n(r)),
        Curve::Angular => line!(out, "r = alpha / pi = {}", n(r)),
    }
    let u = (0.5 + 0.5 * r * cos_b).clamp(0.0, 1.0);
    let v = (0.5 + 0.5 * r * sin_b).clamp(0.0, 1.0);
    line!(out, "u = (1 + r cos beta) / 2 = {}", n(u));
    line!(out, "v = (1 + r sin beta) / 2 = {}", n(v));
    DVec2::new(u, v)
}

/// The probes' diagram angles: alpha from the axis, beta about it, r in the image disc.
pub(super) fn probe_angles(p: DVec3, flip: bool, curve: Curve) -> MappingAngles {
    let z = if flip { -p.z } else { p.z };
    let alpha = p.x.hypot(p.y).atan2(z);
    let r = match curve {
        Curve::MirrorBall => (alpha * 0.5).sin(),
        Curve::Angular => alpha / std::f64::consts::PI,
    };
    MappingAngles {
        alpha: Some(alpha),
        beta: Some(p.y.atan2(p.x)),
        r: Some(r),
        ..MappingAngles::default()
    }
}
