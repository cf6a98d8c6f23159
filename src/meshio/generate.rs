//! Procedural meshes with real (u, v) and seams. Seam vertices are duplicated with bit-identical
//! positions (the angle is taken from the index modulo the period), so the surface stays
//! watertight while (u, v) jump.

use crate::geometry::MeshData;
use crate::math::{PI, TAU, Vec2, Vec3};

/// Appends the triangles of a `cols` x `rows` grid of quads over a vertex grid of
/// (`cols` + 1) x (`rows` + 1) starting at `base`, counter-clockwise seen from where `flip`
/// says (false: the side the (u, v) axes' cross product points to).
fn grid(tris: &mut Vec<[u32; 3]>, base: u32, cols: u32, rows: u32, flip: bool) {
    let at = |i: u32, j: u32| base + j * (cols + 1) + i;
    for j in 0..rows {
        for i in 0..cols {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if flip {
                tris.push([a, c, b]);
                tris.push([a, d, c]);
            } else {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
    }
}

/// A torus around the y axis (major radius `big`, tube radius `small`) with `n_major` x
/// `n_minor` quads: u goes once around y, v once around the tube; two seams.
#[must_use]
pub fn torus(n_major: u32, n_minor: u32, big: f32, small: f32) -> MeshData {
    let (n_major, n_minor) = (n_major.max(3), n_minor.max(3));
    let mut d = MeshData {
        format: "generated torus".into(),
        ..MeshData::default()
    };
    for j in 0..=n_minor {
        let b = TAU * (j % n_minor) as f32 / n_minor as f32;
        for i in 0..=n_major {
            let a = TAU * (i % n_major) as f32 / n_major as f32;
            let ring = big + small * b.cos();
            d.positions
                .push(Vec3::new(ring * a.sin(), small * b.sin(), ring * a.cos()));
            d.normals
                .push(Vec3::new(b.cos() * a.sin(), b.sin(), b.cos() * a.cos()));
            d.uvs.push(Vec2::new(
                i as f32 / n_major as f32,
                j as f32 / n_minor as f32,
            ));
        }
    }
    grid(&mut d.triangles, 0, n_major, n_minor, false);
    d.faces = d.triangles.len();
    d
}

/// A sphere of radius about 1 with gentle bumps (`bump` of the radius) in `segments` x `rings`
/// quads (the pole rows become triangles), (u, v) of the spherical map: 2 segments (rings - 1)
/// triangles. The benchmark's mesh: fine, closed, with a seam at u = 0.
#[must_use]
pub fn bumpy_sphere(segments: u32, rings: u32, bump: f32) -> MeshData {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let mut d = MeshData {
        format: "generated sphere".into(),
        ..MeshData::default()
    };
    for j in 0..=rings {
        let theta = PI * j as f32 / rings as f32; // from the north pole
        for i in 0..=segments {
            let phi = TAU * (i % segments) as f32 / segments as f32;
            let r = 1.0 + bump * (7.0 * phi).sin() * (6.0 * theta).sin();
            let (s, c) = if j == 0 {
                (0.0, 1.0)
            } else if j == rings {
                (0.0, -1.0)
            } else {
                theta.sin_cos()
            };
            let p = Vec3::new(s * phi.sin(), c, s * phi.cos()) * r;
            d.positions.push(p);
            d.uvs.push(Vec2::new(
                i as f32 / segments as f32,
                1.0 - j as f32 / rings as f32,
            ));
        }
    }
    let at = |i: u32, j: u32| j * (segments + 1) + i;
    for j in 0..rings {
        for i in 0..segments {
            let (a, b, c, e) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if j > 0 {
                d.triangles.push([a, e, b]);
            }
            if j + 1 < rings {
                d.triangles.push([b, e, c]);
            }
        }
    }
    d.faces = d.triangles.len();
    d
}
