//! Mapping values worked by hand from the lecture's formulas, singular points, and the analytic
//! gradients against central finite differences.

use super::*;
use crate::math::TAU;
use crate::names::Named as _;
use strum::VariantArray;

const EPS: f32 = 1e-6;

fn uv(m: Mapping, p: [f32; 3]) -> (f32, f32) {
    let r = m.map_point(Vec3A::from(p));
    (r.uv.x, r.uv.y)
}

fn close(a: (f32, f32), b: (f32, f32)) -> bool {
    (a.0 - b.0).abs() < 1e-5 && (a.1 - b.1).abs() < 1e-5
}

#[test]
fn spherical_by_hand() {
    let h = std::f32::consts::FRAC_1_SQRT_2;
    // phi = atan2(x, z); u = phi / 2pi; v = 1 - acos(y) / pi
    for (p, expected) in [
        ([0.0, 0.0, 1.0], (0.0, 0.5)),
        ([1.0, 0.0, 0.0], (0.25, 0.5)),
        ([0.0, 0.0, -1.0], (0.5, 0.5)),
        ([-1.0, 0.0, 0.0], (0.75, 0.5)),
        ([0.0, 1.0, 0.0], (0.0, 1.0)),
        ([0.0, -1.0, 0.0], (0.0, 0.0)),
        ([h, h, 0.0], (0.25, 0.75)),
        ([0.0, -h, h], (0.0, 0.25)),
    ] {
        assert!(
            close(uv(Mapping::Spherical, p), expected),
            "{p:?}: {:?}",
            uv(Mapping::Spherical, p)
        );
    }
}

#[test]
fn cylindrical_and_rectangular_by_hand() {
    assert!(close(
        uv(Mapping::Cylindrical, [1.0, 0.5, 0.0]),
        (0.25, 0.75)
    ));
    assert!(close(
        uv(Mapping::Cylindrical, [0.0, -1.0, 1.0]),
        (0.0, 0.0)
    ));
    assert!(close(
        uv(Mapping::Cylindrical, [0.0, 1.0, -1.0]),
        (0.5, 1.0)
    ));
    // u = (z + 1) / 2, v = (x + 1) / 2
    assert!(close(
        uv(Mapping::Rectangular, [0.5, 0.0, -0.5]),
        (0.25, 0.75)
    ));
    assert!(close(
        uv(Mapping::Rectangular, [-1.0, 0.0, 1.0]),
        (1.0, 0.0)
    ));
}

#[test]
fn light_probe_by_hand() {
    let h = std::f32::consts::FRAC_1_SQRT_2;
    // alpha = acos(z), r = alpha/pi, u = (1 + r cos b)/2, v = (1 + r sin b)/2
    for (p, expected) in [
        ([0.0, 0.0, 1.0], (0.5, 0.5)),
        ([1.0, 0.0, 0.0], (0.75, 0.5)),
        ([0.0, 1.0, 0.0], (0.5, 0.75)),
        ([0.0, -1.0, 0.0], (0.5, 0.25)),
        ([h, 0.0, h], (0.625, 0.5)),
        ([0.0, 0.0, -1.0], (1.0, 0.5)),
    ] {
        assert!(
            close(uv(Mapping::LightProbe, p), expected),
            "{p:?}: {:?}",
            uv(Mapping::LightProbe, p)
        );
    }
    // The panoramic flip: z -> -z.
    assert!(close(uv(Mapping::Panoramic, [0.0, 0.0, -1.0]), (0.5, 0.5)));
    assert!(close(uv(Mapping::Panoramic, [h, 0.0, -h]), (0.625, 0.5)));
    // Mirror ball: r = sin(alpha / 2).
    let r = (std::f32::consts::FRAC_PI_4).sin();
    assert!(close(
        uv(Mapping::MirrorBall, [1.0, 0.0, 0.0]),
        (0.5 + r / 2.0, 0.5)
    ));
    assert!(close(uv(Mapping::MirrorBall, [0.0, 0.0, 1.0]), (0.5, 0.5)));
}

#[test]
fn probe_is_continuous_through_its_axis() {
    // The lecture divides by sqrt(x^2 + y^2) = 0 here; ours approaches the centre smoothly.
    for tiny in [0.0, 1e-30, 1e-12, 1e-7, 1e-4] {
        let (u, v) = uv(Mapping::LightProbe, [tiny, -tiny, 1.0]);
        assert!(
            (u - 0.5).abs() < 1e-4 && (v - 0.5).abs() < 1e-4,
            "{tiny}: {u} {v}"
        );
    }
}

#[test]
fn singular_points_are_defined() {
    let specials = [
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [-0.0, 1.0, -0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [-0.0, 0.0, -1.0],
        [1e-45, 1.0, -1e-45],
        [0.0, 1.0 + 1e-7, 0.0],
        [0.0, -1.0 - 1e-7, 0.0],
        [-1e-8, 0.0, 1.0],
        [1e-8, 0.0, 1.0],
        [0.0, 0.0, -1.0 - 1e-7],
        [3e38, 3e38, -3e38],
        [1e-40, 2e-40, 0.0],
        [f32::NAN, 0.0, 1.0],
        [f32::INFINITY, 0.0, 0.0],
    ];
    for &m in Mapping::VARIANTS {
        for p in specials {
            let r = m.map_point(Vec3A::from(p));
            let t = m.map_with_differentials(
                Vec3A::from(p),
                Vec3A::new(1e-3, 1e-3, 1e-3),
                Vec3A::new(-1e-3, 2e-3, 0.0),
                None,
                Mapping::Spherical,
            );
            assert!(t.duvdx.is_finite() && t.duvdy.is_finite(), "{m} at {p:?}");
            assert!(t.duvdx.abs().max_element() <= MAX_FOOTPRINT);
            if m == Mapping::Rectangular {
                continue; // unbounded by design: the wrap mode decides
            }
            assert!(r.uv.is_finite(), "{m} at {p:?}: {:?}", r.uv);
            assert!(
                (0.0..=1.0).contains(&r.uv.x) && (0.0..=1.0).contains(&r.uv.y),
                "{m} at {p:?}: {:?}",
                r.uv
            );
        }
    }
}

/// Finite differences of u and v along a tangent direction against grad . dir.
#[test]
fn analytic_gradients_match_finite_differences() {
    let mut rng = crate::math::SampleRng::new(42, 0, 0);
    for m in [
        Mapping::Rectangular,
        Mapping::Cylindrical,
        Mapping::Spherical,
        Mapping::LightProbe,
        Mapping::Panoramic,
        Mapping::MirrorBall,
    ] {
        let mut checked = 0;
        while checked < 200 {
            let p = Vec3A::new(
                rng.next_f32() * 2.0 - 1.0,
                rng.next_f32() * 2.0 - 1.0,
                rng.next_f32() * 2.0 - 1.0,
            );
            let Some(p) = p.try_normalize() else { continue };
            let dir = Vec3A::new(
                rng.next_f32() - 0.5,
                rng.next_f32() - 0.5,
                rng.next_f32() - 0.5,
            );
            // Stay away from the seam, the poles and the probe's antipode, where u jumps or the
            // derivative is unbounded.
            let a = m.map_point(p);
            if a.uv.x < 0.05
                || a.uv.x > 0.95
                || p.y.abs() > 0.95
                || p.z < -0.9
                || p.z > 0.9 && m == Mapping::Panoramic
            {
                continue;
            }
            let h = 1e-3;
            let (fp, fm) = (m.map_point(p + h * dir), m.map_point(p - h * dir));
            let fd = (fp.uv - fm.uv) / (2.0 * h);
            let an = Vec2::new(a.grad_u.dot(dir), a.grad_v.dot(dir));
            let tol = 2e-3 * (1.0 + an.abs().max_element());
            assert!(
                (fd - an).abs().max_element() < tol,
                "{m} at {p:?} along {dir:?}: fd {fd:?} analytic {an:?}"
            );
            checked += 1;
        }
    }
}

#[test]
fn spherical_seam_derivatives_do_not_jump() {
    // Either side of the seam u is near 0 or near 1, but du/dx is the same small number.
    let dpdx = Vec3A::new(1e-3, 0.0, 0.0);
    let left = Mapping::Spherical.map_with_differentials(
        Vec3A::new(-1e-4, 0.0, 1.0),
        dpdx,
        Vec3A::ZERO,
        None,
        Mapping::Spherical,
    );
    let right = Mapping::Spherical.map_with_differentials(
        Vec3A::new(1e-4, 0.0, 1.0),
        dpdx,
        Vec3A::ZERO,
        None,
        Mapping::Spherical,
    );
    assert!(left.uv.x > 0.99 && right.uv.x < 0.01);
    assert!((left.duvdx.x - right.duvdx.x).abs() < 1e-6);
    assert!((left.duvdx.x - 1e-3 / TAU).abs() < 1e-6);
}

#[test]
fn uv_mapping_uses_mesh_coordinates_and_their_derivatives() {
    let dpdu = Vec3A::new(2.0, 0.0, 0.0);
    let dpdv = Vec3A::new(0.0, 0.0, 4.0);
    let t = Mapping::Uv.map_with_differentials(
        Vec3A::ZERO,
        Vec3A::new(0.2, 0.0, 0.0),
        Vec3A::new(0.0, 0.0, 0.4),
        Some((Vec2::new(0.3, 0.6), Some((dpdu, dpdv)))),
        Mapping::Spherical,
    );
    assert_eq!(t.uv, Vec2::new(0.3, 0.6));
    assert!((t.duvdx - Vec2::new(0.1, 0.0)).length() < EPS);
    assert!((t.duvdy - Vec2::new(0.0, 0.1)).length() < EPS);
    // Without mesh coordinates it falls back to the shape's natural mapping.
    let t = Mapping::Uv.map_with_differentials(
        Vec3A::X,
        Vec3A::ZERO,
        Vec3A::ZERO,
        None,
        Mapping::Spherical,
    );
    assert!((t.uv - Vec2::new(0.25, 0.5)).length() < EPS);
}

#[test]
fn names_round_trip() {
    for &m in Mapping::VARIANTS {
        assert_eq!(m.name().parse::<Mapping>().unwrap(), m);
    }
    assert!(
        Mapping::from_name("sphere")
            .unwrap_err()
            .contains("spherical")
    );
}

#[test]
fn map_uv_is_map_point_without_gradients_bit_for_bit() {
    let mut rng = crate::math::SampleRng::new(3, 1, 4);
    let mut points = vec![
        Vec3A::ZERO,
        Vec3A::Y,
        -Vec3A::Y,
        Vec3A::Z,
        -Vec3A::Z,
        Vec3A::new(1e30, -1e30, 1e-30),
        Vec3A::new(f32::NAN, 0.0, 1.0),
        Vec3A::new(1e-40, 0.0, -1e-40),
    ];
    for _ in 0..2000 {
        points.push(Vec3A::new(
            rng.next_f32() * 4.0 - 2.0,
            rng.next_f32() * 4.0 - 2.0,
            rng.next_f32() * 4.0 - 2.0,
        ));
    }
    for &m in Mapping::VARIANTS {
        for &p in &points {
            let full = m.map_point(p).uv;
            let fast = m.map_uv(p);
            assert!(
                full.x.to_bits() == fast.x.to_bits() && full.y.to_bits() == fast.y.to_bits(),
                "{m:?} at {p}: {full} != {fast}"
            );
            // And the zero-footprint path of map_with_differentials returns the same.
            let tc =
                m.map_with_differentials(p, Vec3A::ZERO, Vec3A::ZERO, None, Mapping::Spherical);
            assert_eq!(tc.uv.x.to_bits(), full.x.to_bits());
            assert_eq!(tc.duvdx, Vec2::ZERO);
        }
    }
}

#[test]
fn periodic_u_is_below_1_and_its_seam_is_0() {
    let tiny = f32::from_bits(1);
    for m in [Mapping::Cylindrical, Mapping::Spherical] {
        for y in [-0.999, -0.5, 0.0, 0.5, 0.999] {
            let r = (1.0f32 - y * y).sqrt();
            // Just west of the seam phi + 2 pi rounds to 2 pi: u = 1, the seam, read as u = 0.
            for x in [-tiny, -1e-30, -0.0, 0.0] {
                let (u, _) = uv(m, [x, y, r]);
                assert_eq!(u.to_bits(), 0, "{m} at ({x}, {y}, {r}): u = {u}");
            }
            // Just east of it, u is 0 or just above (tiny / 2 pi underflows).
            let (u, _) = uv(m, [tiny, y, r]);
            assert!((0.0..1e-30).contains(&u), "{m}: {u}");
            // A micro-radian west, u stays below 1.
            let (u, _) = uv(m, [-1e-6 * r, y, r]);
            assert!(u < 1.0 && u > 0.999_999, "{m}: {u}");
        }
    }
}

/// The points the f32 renderer and the f64 worked formulas are compared on: every octant, many
/// magnitudes, the axes, the seam and the poles.
fn comparison_points() -> Vec<Vec3A> {
    let mut rng = crate::math::SampleRng::new(5, 6, 7);
    let mut points = vec![
        Vec3A::ZERO,
        Vec3A::X,
        Vec3A::Y,
        -Vec3A::Y,
        Vec3A::Z,
        -Vec3A::Z,
        Vec3A::new(-1e-30, 0.2, 0.9),
        Vec3A::new(1e-40, 1.0, 1e-40),
        Vec3A::new(f32::from_bits(1), f32::from_bits(1), 1.0),
        Vec3A::new(1.0, 0.0, 1.0),
        Vec3A::new(-1.0, 0.0, -1.0),
        Vec3A::new(1.0, 1.0, 1.0),
    ];
    for i in 0..20_000 {
        let d = Vec3A::new(
            rng.next_f32() * 2.0 - 1.0,
            rng.next_f32() * 2.0 - 1.0,
            rng.next_f32() * 2.0 - 1.0,
        );
        let scale = match i % 4 {
            0 => 1.0,
            1 => 10f32.powi((i % 61) - 30),
            2 => 1.0 / d.length(), // on the unit sphere
            _ => rng.next_f32() * 2.0,
        };
        points.push(d * scale);
    }
    points
}

/// Distance between two values of u, across the seam for periodic mappings.
fn u_distance(m: Mapping, a: f64, b: f64) -> f64 {
    let d = (a - b).abs();
    if m.u_is_periodic() || m == Mapping::Uv {
        d.min(1.0 - d)
    } else {
        d
    }
}

#[test]
fn f64_worked_formulas_agree_with_the_renderer_to_f32_rounding() {
    for &m in Mapping::VARIANTS {
        let mut worst = (0.0f64, Vec3A::ZERO);
        for p in comparison_points() {
            let r = m.map_uv(p);
            let e = map_uv_f64(m, p.as_dvec3());
            // The probe maps' antipode is a singular point (the whole rim meets there), and the
            // mirror ball's 1 + z cancels in f32 next to it: compared away from it.
            let n = p.as_dvec3().normalize_or_zero();
            let z = if m == Mapping::Panoramic { -n.z } else { n.z };
            let probe = matches!(
                m,
                Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall
            );
            if probe && 1.0 + z < 1e-2 {
                continue;
            }
            // Relative beyond 1: the rectangular map is unbounded.
            let mut err = (u_distance(m, f64::from(r.x), e.x) / e.x.abs().max(1.0))
                .max((f64::from(r.y) - e.y).abs() / e.y.abs().max(1.0));
            if m == Mapping::MirrorBall {
                // r = sin(alpha / 2) is computed as d / sqrt(2 (1 + z)): an f32 rounding of z
                // (6e-8) weighs 1 / (1 + z) times more towards the antipode.
                err *= (1.0 + z).min(1.0);
            }
            if err > worst.0 {
                worst = (err, p);
            }
        }
        // A few f32 ulps (6e-8 near 1); measured at most 1.1e-7.
        assert!(
            worst.0 < 2e-7,
            "{m}: f32 and f64 differ by {} at {}",
            worst.0,
            worst.1
        );
    }
}

#[test]
fn worked_formulas_keep_tiny_coordinates() {
    // Read as f64, (5e-324, 5e-324, 1) is not on the axis: beta is 45 degrees.
    let p = glam::DVec3::new(5e-324, 5e-324, 1.0);
    let (lines, uv) = explain_mapping_f64(Mapping::LightProbe, p);
    assert!(
        lines.iter().any(|l| l
            == "sin beta = y / sqrt(x^2 + y^2) = 0.7071, cos beta = x / sqrt(x^2 + y^2) = 0.7071"),
        "{lines:#?}"
    );
    assert_eq!(uv, glam::DVec2::splat(0.5));
    let (lines, _) = explain_mapping_f64(Mapping::Rectangular, p);
    assert_eq!(lines[1], "v = (x + 1) / 2 = (4.9407e-324 + 1) / 2 = 0.5000");
    let (lines, uv) = explain_mapping_f64(Mapping::Spherical, p);
    assert!(
        lines[0].starts_with("phi = atan2(x, z) = atan2(4.9407e-324, 1.0000) = 4.9407e-324 rad"),
        "{lines:#?}"
    );
    assert_eq!(uv.x, 5e-324 / std::f64::consts::TAU);
    // At the seam the lines say why u is 0.
    let (lines, uv) =
        explain_mapping_f64(Mapping::Cylindrical, glam::DVec3::new(-1e-300, 0.0, 1.0));
    assert_eq!(uv.x, 0.0);
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("u = 1 is the seam u = 0")),
        "{lines:#?}"
    );
}

#[test]
fn numbers_in_worked_formulas() {
    assert_eq!(explain_number(0.25), "0.2500");
    assert_eq!(explain_number(1.0), "1.0000");
    assert_eq!(explain_number(0.0), "0.0000");
    assert_eq!(explain_number(2e-5), "2.0000e-5");
    assert_eq!(explain_number(3e7), "3.0000e7");
    assert_eq!(explain_number(0.999_999_999), "0.999999999");
    assert_eq!(explain_number(0.999_999), "0.999999");
    assert_eq!(explain_number(0.123_456), "0.1235");
}

/// Every mapping's lanes at every width give the width-1 (scalar path's) numbers, bit for bit:
/// (u, v) and both gradients, on hard points (signed zeros, infinities, NaN, subnormals, the
/// seams, the poles, the probes' axis and antipode).
#[test]
fn every_mapping_gives_the_same_bits_at_every_width() {
    use crate::math::lanes::testing::{Walk, WidthCheck, at_every_width, bits, lane, load3};
    use crate::math::lanes::{V3, to_array};
    struct Agree;
    impl WidthCheck for Agree {
        fn check<S: pulp::Simd>(&mut self, s: S, name: &'static str) {
            let mut walk = Walk(5);
            let special = [
                Vec3A::new(-0.0, 0.0, -1.0),
                Vec3A::new(1e-8, 0.0, -1.0),
                Vec3A::new(0.0, 1.0, 0.0),
                Vec3A::new(0.0, 0.0, -1.0),
                Vec3A::new(1e-3, -2e-3, 1.0),
                Vec3A::ZERO,
                Vec3A::new(3e38, -3e38, 1.0),
                Vec3A::new(-f32::MIN_POSITIVE, 0.5, 0.0),
            ];
            for round in 0..1500 {
                let mut p = walk.v3();
                if round == 0 {
                    for (i, q) in special.iter().cycle().take(16).enumerate() {
                        (p[0][i], p[1][i], p[2][i]) = (q.x, q.y, q.z);
                    }
                }
                let v = load3::<S>(&p);
                for &m in Mapping::VARIANTS {
                    let g = m.map_lanes::<S, true>(s, &v);
                    let f = m.map_lanes::<S, false>(s, &v);
                    let (gu, gv) = (to_array::<S>(g.u), to_array::<S>(g.v));
                    let (fu, fv) = (to_array::<S>(f.u), to_array::<S>(f.v));
                    let (du, dv) = (g.grad_u.to_arrays(), g.grad_v.to_arrays());
                    for i in 0..S::F32_LANES {
                        let q = lane(&p, i);
                        let one = m.map_lanes::<pulp::Scalar, true>(pulp::Scalar, &V3::one(q));
                        let want = [one.u, one.v].map(bits);
                        assert_eq!([gu[i], gv[i]].map(bits), want, "{name}: {m:?} at {q:?}");
                        assert_eq!([fu[i], fv[i]].map(bits), want, "{name}: {m:?} at {q:?}");
                        assert_eq!(
                            [du[0][i], du[1][i], du[2][i], dv[0][i], dv[1][i], dv[2][i]].map(bits),
                            [
                                one.grad_u.x,
                                one.grad_u.y,
                                one.grad_u.z,
                                one.grad_v.x,
                                one.grad_v.y,
                                one.grad_v.z
                            ]
                            .map(bits),
                            "{name}: {m:?} gradients at {q:?}"
                        );
                    }
                }
            }
        }
    }
    assert!(at_every_width(&mut Agree) >= 1);
}
