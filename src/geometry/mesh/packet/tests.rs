//! The packet traversal against its width-1 instance and against every triangle tested in
//! turn: the same hits, bit for bit, on coherent camera packets, mixed packets of hard values
//! (NaN and infinite origins, zero and subnormal directions), rays through shared edges and
//! vertices, axis-parallel rays in box faces and grazing rays in triangles' planes.

use super::super::{Mesh, MeshData, Shading, TriangleHit};
use super::*;
use crate::math::lanes::testing::{Walk, WidthCheck, at_every_width, bits};
use crate::math::lanes::{mask_from_array, to_array};
use crate::math::{Ray, Vec2, Vec3A};
use std::path::Path;
use strum::VariantArray;

/// A packet of 16 rays (narrower widths take it in slices).
#[derive(Clone, Copy)]
struct Packet {
    o: [[f32; 16]; 3],
    d: [[f32; 16]; 3],
    t_max: [f32; 16],
    active: [bool; 16],
}

impl Packet {
    fn new(rays: &[(Vec3A, Vec3A)], t_max: f32) -> Self {
        let mut p = Self {
            o: [[0.0; 16]; 3],
            d: [[0.0; 16]; 3],
            t_max: [t_max; 16],
            active: [true; 16],
        };
        for (i, (o, d)) in rays.iter().take(16).enumerate() {
            for k in 0..3 {
                p.o[k][i] = o[k];
                p.d[k][i] = d[k];
            }
        }
        p
    }

    /// Lanes `first ..` moved to the front, so narrow widths see every lane.
    fn from(&self, first: usize) -> Self {
        let shift = |a: &[f32; 16]| std::array::from_fn(|i| a[(i + first) % 16]);
        Self {
            o: self.o.each_ref().map(shift),
            d: self.d.each_ref().map(shift),
            t_max: shift(&self.t_max),
            active: std::array::from_fn(|i| self.active[(i + first) % 16]),
        }
    }

    fn ray(&self, i: usize) -> Ray {
        let v = |a: &[[f32; 16]; 3]| Vec3A::new(a[0][i], a[1][i], a[2][i]);
        Ray::new(v(&self.o), v(&self.d))
    }
}

/// Two triangles, each twice (a tie at every point: the lower index must win), and a
/// zero-area sliver along the diagonal.
fn twins() -> MeshData {
    let positions = vec![
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(-1.0, -0.5, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, -0.5, -1.0),
        Vec3::new(0.0, 0.0, 0.0),
    ];
    let uvs = vec![
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(0.0, 1.0),
        Vec2::new(0.5, 0.5),
    ];
    MeshData {
        positions,
        uvs,
        triangles: vec![[0, 1, 2], [0, 2, 3], [0, 1, 2], [0, 2, 3], [0, 4, 2]],
        faces: 5,
        ..MeshData::default()
    }
}

fn meshes() -> Vec<(&'static str, Mesh)> {
    let build = |d: MeshData, name: &'static str| (name, Mesh::new(d, Path::new(name)).unwrap());
    vec![
        build(crate::meshio::bumpy_sphere(24, 13, 0.05), "sphere"),
        build(crate::meshio::torus(20, 10, 1.0, 0.35), "torus"),
        build(twins(), "twins"),
    ]
}

/// Every kind of packet for `mesh`.
fn packets(mesh: &Mesh, seed: u32) -> Vec<Packet> {
    let mut out = Vec::new();
    // Coherent: 16 consecutive pixels of rows of a camera at (0, 0, 2.2) (the bench's view).
    for row in (0..64).step_by(3) {
        for x0 in [0, 16, 24, 40] {
            let rays: Vec<_> = (0..16)
                .map(|i| {
                    let (x, y) = ((x0 + i) as f32 / 64.0 - 0.5, 0.5 - row as f32 / 64.0);
                    (
                        Vec3A::new(0.0, 0.0, 2.2),
                        Vec3A::new(x * 1.3, y * 1.3, -2.0),
                    )
                })
                .collect();
            out.push(Packet::new(&rays, f32::INFINITY));
        }
    }
    // Hard lanes: origins and directions from the hard values, half aimed at the mesh.
    let mut walk = Walk(seed);
    for round in 0..120 {
        let mut p = Packet::new(&[], 0.0);
        (p.o, p.d) = (walk.v3(), walk.v3());
        for i in 0..16 {
            if (round + i) % 2 == 0 {
                p.o[2][i] += 3.0;
                let target = [p.d[0][i], p.d[1][i], 0.3].map(|x| x.clamp(-1.0, 1.0));
                for (k, target) in target.iter().enumerate() {
                    p.d[k][i] = target - p.o[k][i];
                }
            }
            p.t_max[i] = [f32::INFINITY, 2.5, 3.0, 0.0, f32::NAN, 4.0, 1e30][(round + i) % 7];
            p.active[i] = (round + i) % 11 != 0;
        }
        out.push(p);
    }
    // Through shared vertices and edge points, from directions around the mesh, mixed axes.
    let (positions, triangles) = (&mesh.positions, &mesh.triangles);
    let mut k = seed as usize;
    for _ in 0..40 {
        let rays: Vec<_> = (0..16)
            .map(|i| {
                k = k.wrapping_mul(2_654_435_761).wrapping_add(97);
                let t = triangles[k % triangles.len()].map(|v| Vec3A::from(positions[v as usize]));
                let f = [0.0, 0.5, 0.25, 1.0 / 3.0][i % 4];
                let target = t[0] + (t[(i / 4) % 3] - t[0]) * f;
                let from = Vec3A::new(
                    ((k >> 3) % 7) as f32 - 3.0,
                    ((k >> 6) % 5) as f32 - 2.0,
                    ((k >> 9) % 9) as f32 - 4.0,
                ) + Vec3A::splat(0.1);
                (from, target - from)
            })
            .collect();
        out.push(Packet::new(&rays, f32::INFINITY));
        // The same rays stopping just before and at their target.
        out.push(Packet::new(&rays, 1.0));
    }
    // Axis-parallel rays, starting on vertex coordinates (in box faces), both ways.
    for axis in 0..3 {
        for sign in [-1.0_f32, 1.0] {
            let rays: Vec<_> = (0..16)
                .map(|i| {
                    let v = Vec3A::from(positions[(i * 7 + axis) % positions.len()]);
                    let mut d = Vec3A::ZERO;
                    d[axis] = sign;
                    let mut o = v;
                    o[axis] -= sign * 3.0;
                    (o, d)
                })
                .collect();
            out.push(Packet::new(&rays, f32::INFINITY));
        }
    }
    // Grazing: in a triangle's plane, along an edge and across it.
    let rays: Vec<_> = (0..16)
        .map(|i| {
            let t =
                triangles[(i * 13) % triangles.len()].map(|v| Vec3A::from(positions[v as usize]));
            let along = if i % 2 == 0 {
                t[1] - t[0]
            } else {
                t[2] - t[0] + (t[1] - t[0]) * 0.5
            };
            (t[0] - along * 2.0, along)
        })
        .collect();
    out.push(Packet::new(&rays, f32::INFINITY));
    out
}

/// Whether two width-1 hits are the same bits.
fn same(a: Option<TriangleHit>, b: Option<TriangleHit>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            a.triangle == b.triangle
                && bits(a.t) == bits(b.t)
                && a.bary.to_array().map(bits) == b.bary.to_array().map(bits)
        }
        _ => false,
    }
}

struct Agree<'a>(&'a [(&'static str, Mesh)], u32);

impl WidthCheck for Agree<'_> {
    fn check<S: Simd>(&mut self, s: S, name: &'static str) {
        for (what, mesh) in self.0 {
            for packet in packets(mesh, self.1) {
                for first in (0..16).step_by(S::F32_LANES) {
                    let p = packet.from(first);
                    agree_on(s, name, what, mesh, &p);
                }
            }
        }
    }
}

/// One packet at `S`'s width against each of its lanes alone.
fn agree_on<S: Simd>(s: S, name: &str, what: &str, mesh: &Mesh, p: &Packet) {
    let (o, d) = (V3::<S>::from_arrays(&p.o), V3::<S>::from_arrays(&p.d));
    let (t_max, active) = (from_array::<S>(&p.t_max), mask_from_array(s, &p.active));
    let h = mesh.closest_hit_lanes(s, &o, &d, t_max, active);
    let blocked = mask_to_array(s, mesh.occluded_lanes(s, &o, &d, t_max, active));
    let (hit, t, bary) = (
        mask_to_array(s, h.hit),
        to_array::<S>(h.t),
        h.bary.to_arrays(),
    );
    let surfaces: Vec<_> = Shading::VARIANTS
        .iter()
        .map(|&shading| mesh.surface_lanes(s, &h, shading))
        .collect();
    for i in 0..S::F32_LANES {
        let ray = p.ray(i);
        let lane = hit[i].then(|| TriangleHit {
            triangle: h.triangle[i],
            t: t[i],
            bary: Vec3::new(bary[0][i], bary[1][i], bary[2][i]),
        });
        let alone = if p.active[i] {
            mesh.closest_hit(&ray, p.t_max[i])
        } else {
            None
        };
        assert!(
            same(lane, alone),
            "{name}, {what}: lane {i} {ray:?} t_max {}: {lane:?} vs {alone:?}",
            p.t_max[i]
        );
        let shadow = p.active[i] && mesh.occluded(&ray, p.t_max[i]);
        assert_eq!(
            blocked[i], shadow,
            "{name}, {what}: shadow lane {i} {ray:?}"
        );
        assert_eq!(shadow, alone.is_some(), "{what}: any hit is a nearest hit");
        let Some(alone) = alone else { continue };
        for (k, &shading) in Shading::VARIANTS.iter().enumerate() {
            let m = &surfaces[k];
            let one = mesh.surface(alone, shading);
            for (lanes, one) in [(&m.p, one.p), (&m.n, one.n), (&m.ns, one.ns)] {
                assert_eq!(
                    lanes.to_arrays().map(|a| bits(a[i])),
                    one.to_array().map(bits),
                    "{name}, {what}: surface lane {i} {shading}"
                );
            }
            let uv = (to_array::<S>(m.u)[i], to_array::<S>(m.v)[i]);
            let one_uv = one.uv.unwrap_or_default();
            assert_eq!((bits(uv.0), bits(uv.1)), (bits(one_uv.x), bits(one_uv.y)));
            assert_eq!(m.part[i], one.part, "{name}, {what}: part");
        }
    }
}

#[test]
fn packets_give_the_same_hits_at_every_width() {
    let meshes = meshes();
    assert!(at_every_width(&mut Agree(&meshes, 17)) >= 1);
}

/// The nearest hit by testing every triangle in index order: the answer every traversal must
/// give (the smallest t, the lower index on equal t).
fn every_triangle(mesh: &Mesh, ray: &Ray, t_max: f32) -> (Option<TriangleHit>, bool) {
    let s = pulp::Scalar;
    let (o, d) = (V3::one(ray.origin), V3::one(ray.dir));
    let woop = WoopRays::new(s, &o, &d, true);
    let mut best: Option<TriangleHit> = None;
    for (i, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|k| mesh.positions[k as usize]);
        let h = woop.test(s, a, b, c, woop.valid);
        if h.ok && h.t < t_max && best.is_none_or(|b| h.t < b.t) {
            best = Some(TriangleHit {
                triangle: i as u32,
                t: h.t,
                bary: Vec3::new(h.bary.x, h.bary.y, h.bary.z),
            });
        }
    }
    (best, best.is_some())
}

/// The BVH walk finds what testing every triangle finds, bit for bit: no box it skips holds
/// a nearer (or as near, lower-index) hit, whatever the order it visits them in.
#[test]
fn the_walk_finds_what_every_triangle_finds() {
    for (what, mesh) in meshes() {
        for p in packets(&mesh, 5) {
            for i in 0..16 {
                if !p.active[i] {
                    continue;
                }
                let ray = p.ray(i);
                let (nearest, any) = every_triangle(&mesh, &ray, p.t_max[i]);
                let walked = mesh.closest_hit(&ray, p.t_max[i]);
                assert!(
                    same(walked, nearest),
                    "{what}: {ray:?} t_max {}: {walked:?} vs {nearest:?}",
                    p.t_max[i]
                );
                assert_eq!(mesh.occluded(&ray, p.t_max[i]), any, "{what}: {ray:?}");
            }
        }
    }
}

/// Equal t: the lower triangle index wins (the twins mesh holds each triangle twice).
#[test]
fn ties_go_to_the_lower_index() {
    let m = Mesh::new(twins(), Path::new("twins")).unwrap();
    let mut seen = 0;
    for k in 0..64 {
        let (x, z) = ((k % 8) as f32 / 5.0 - 0.9, (k / 8) as f32 / 5.0 - 0.9);
        let ray = Ray::new(Vec3A::new(x, 3.0, z), Vec3A::new(0.1, -1.0, 0.05));
        let h = m.closest_hit(&ray, f32::INFINITY).unwrap();
        let twin = (0..m.triangle_count() as u32).filter(|&t| {
            t != h.triangle && m.triangles[t as usize] == m.triangles[h.triangle as usize]
        });
        for t in twin {
            assert!(
                h.triangle < t,
                "{x} {z}: {} won over its twin {t}",
                h.triangle
            );
            seen += 1;
        }
    }
    assert!(seen >= 60, "{seen} ties");
}
