//! Unit tests of [`Mesh`](super::Mesh): building, the BVH order, the watertight test and the
//! interpolation.

use super::*;
use strum::VariantArray;

fn quad() -> MeshData {
    // The lecture's two triangles.
    MeshData {
        positions: vec![
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(1.0, -1.0, -1.0),
        ],
        uvs: vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        faces: 2,
        ..MeshData::default()
    }
}

fn down(x: f32, z: f32) -> Ray {
    Ray::new(Vec3A::new(x, 5.0, z), Vec3A::new(0.0, -1.0, 0.0))
}

/// On the lecture's triangles (u, v) = ((z + 1) / 2, (x + 1) / 2) everywhere: the vertex
/// values interpolate to the rectangular map of the square they cover.
#[test]
fn lecture_triangles_interpolate_uv() {
    let m = Mesh::new(quad(), Path::new("quad")).unwrap();
    for (x, z) in [
        (0.5, -0.5),
        (-0.7, 0.6),
        (0.9, 0.95),
        (-0.2, -0.9),
        (0.0, 0.0),
    ] {
        for &shading in Shading::VARIANTS {
            let h = m.intersect(&down(x, z), f32::INFINITY, shading).unwrap();
            let uv = h.uv.unwrap();
            assert!((uv - Vec2::new((z + 1.0) / 2.0, (x + 1.0) / 2.0)).length() < 1e-6);
            assert!((h.p.x - x).abs() < 1e-6 && (h.p.z - z).abs() < 1e-6);
            assert!(h.n.y > 0.0 && h.ns.y > 0.0);
        }
    }
    // Flat: the two faces' normals differ; smooth: they meet on the shared diagonal.
    let f1 = m.intersect(&down(0.3, -0.6), 1e9, Shading::Flat).unwrap();
    let f2 = m.intersect(&down(-0.3, 0.6), 1e9, Shading::Flat).unwrap();
    assert!((f1.ns - f2.ns).length() > 0.5);
    let s1 = m
        .intersect(&down(0.3001, 0.3), 1e9, Shading::Smooth)
        .unwrap();
    let s2 = m
        .intersect(&down(0.2999, 0.3), 1e9, Shading::Smooth)
        .unwrap();
    assert!((s1.ns - s2.ns).length() < 1e-3);
    assert_ne!(s1.part, s2.part);
    // dp/du points along +z (u grows with z), dp/dv along +x.
    let (dpdu, dpdv) = f1.dpduv.unwrap();
    assert!(dpdu.z > 1.9 && dpdv.x > 1.9, "{dpdu} {dpdv}");
}

/// Zero-area and zero-UV-area triangles neither crash nor give NaN.
#[test]
fn degenerate_triangles_are_harmless() {
    let mut d = quad();
    d.positions.push(Vec3::new(0.0, 0.0, 0.0));
    d.positions.push(Vec3::new(0.0, 0.0, 0.0));
    d.uvs.push(Vec2::ZERO);
    d.uvs.push(Vec2::ZERO);
    d.triangles.push([4, 5, 4]); // a point
    d.triangles.push([0, 4, 2]); // a line through the quad
    // Same (u, v) at every corner of a real triangle.
    d.uvs[3] = Vec2::ZERO;
    d.uvs[2] = Vec2::ZERO;
    assert_eq!(
        d.degenerate(),
        Degenerate {
            zero_area: 2,
            zero_uv_area: 4
        }
    );
    let m = Mesh::new(d, Path::new("degenerate")).unwrap();
    for k in 0..400 {
        let (x, z) = ((k % 20) as f32 / 10.0 - 0.95, (k / 20) as f32 / 10.0 - 0.95);
        for &shading in Shading::VARIANTS {
            if let Some(h) = m.intersect(&down(x, z), 1e9, shading) {
                assert!(h.p.is_finite() && h.n.is_finite() && h.ns.is_finite());
                assert!(h.uv.unwrap().is_finite());
                if let Some((a, b)) = h.dpduv {
                    assert!(a.is_finite() && b.is_finite());
                }
            }
        }
    }
    // The ray along the zero-area line still hits a real triangle.
    assert!(m.intersect(&down(0.0, 0.0), 1e9, Shading::Flat).is_some());
}

#[test]
fn out_of_range_indices_and_nan_are_refused() {
    let mut d = quad();
    d.triangles[1] = [0, 2, 4];
    let e = Mesh::new(d, Path::new("x.ply")).unwrap_err().to_string();
    assert!(
        e.contains("x.ply") && e.contains("triangle 1") && e.contains('4'),
        "{e}"
    );
    let mut d = quad();
    d.positions[2].y = f32::NAN;
    let e = Mesh::new(d, Path::new("x.ply")).unwrap_err().to_string();
    assert!(e.contains("vertex 2"), "{e}");
}

#[test]
fn rays_miss_beside_and_stop_at_t_max() {
    let m = Mesh::new(quad(), Path::new("quad")).unwrap();
    assert!(m.intersect(&down(1.01, 0.0), 1e9, Shading::Flat).is_none());
    assert!(m.intersect(&down(0.5, 0.5), 4.0, Shading::Flat).is_none());
    assert!(m.occluded(&down(0.5, 0.5), 1e9));
    assert!(!m.occluded(&down(0.5, 0.5), 4.0));
    // A zero direction is refused, not a NaN.
    assert!(
        m.intersect(&Ray::new(Vec3A::Y, Vec3A::ZERO), 1e9, Shading::Flat)
            .is_none()
    );
}
