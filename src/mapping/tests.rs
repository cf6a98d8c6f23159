//! Mapping values worked by hand from the lecture's formulas, singular points, and the analytic
//! gradients against central finite differences.

use super::*;
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
        "sphere"
            .parse::<Mapping>()
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
