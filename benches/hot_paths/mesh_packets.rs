//! Meshes traced as packets against one ray at a time: the `texplore bench --mesh N` scene's
//! primary rays (its bumpy sphere and camera at 400x400), 16 consecutive pixels of a row a
//! packet, through `Mesh::closest_hit_lanes` at the width pulp dispatches (and at AVX2's 8
//! lanes) against 16 calls of `Mesh::closest_hit`; then shadow rays from the hits toward the
//! bench's light through `occluded_lanes` against `occluded`; then the hits' surface (point,
//! normals, (u, v)) lane-wise against `Mesh::surface` per ray.

use criterion::{Criterion, Throughput};
use pulp::{Simd, WithSimd};
use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;
use texplore::geometry::mesh::TriangleHit;
use texplore::geometry::{Mesh, Shading};
use texplore::math::lanes::{M, MAX_LANES, V3, mask_from_array, mask_to_array};
use texplore::math::{Ray, Vec2, Vec3A};
use texplore::scene::{AssetCache, Overrides, apply_overrides, build_scene, parse_preset};

const SIZE: u32 = 400;

/// 16 rays in lane buffers, and which lanes trace.
struct Packet {
    o: [[f32; MAX_LANES]; 3],
    d: [[f32; MAX_LANES]; 3],
    active: [bool; MAX_LANES],
}

impl Packet {
    fn new(rays: &[Option<Ray>]) -> Self {
        let mut p = Self {
            o: [[0.0; MAX_LANES]; 3],
            d: [[0.0; MAX_LANES]; 3],
            active: [false; MAX_LANES],
        };
        for (i, r) in rays.iter().enumerate() {
            if let Some(r) = r {
                for k in 0..3 {
                    p.o[k][i] = r.origin[k];
                    p.d[k][i] = r.dir[k];
                }
                p.active[i] = true;
            }
        }
        p
    }

    /// Lanes `first ..` of the packet at `S`'s width.
    #[inline(always)]
    fn lanes<S: Simd>(&self, s: S, first: usize) -> (V3<S>, V3<S>, M<S>) {
        let shift = |a: &[[f32; MAX_LANES]; 3]| {
            a.map(|c| std::array::from_fn(|i| c[(first + i) % MAX_LANES]))
        };
        let active = std::array::from_fn(|i| self.active[(first + i) % MAX_LANES]);
        (
            V3::from_arrays(&shift(&self.o)),
            V3::from_arrays(&shift(&self.d)),
            mask_from_array(s, &active),
        )
    }

    fn rays(&self) -> impl Iterator<Item = Option<Ray>> + '_ {
        (0..MAX_LANES).map(|i| {
            let v = |a: &[[f32; MAX_LANES]; 3]| Vec3A::new(a[0][i], a[1][i], a[2][i]);
            self.active[i].then(|| Ray::new(v(&self.o), v(&self.d)))
        })
    }
}

/// The bench's generated sphere of about `triangles` triangles and its 400x400 camera's rays
/// through pixel centres, 16 pixels of a row a packet.
fn scene(triangles: u32) -> (Arc<Mesh>, Vec<Packet>) {
    let rings = ((f64::from(triangles) / 4.0).sqrt().round() as u32).max(2) + 1;
    let data = texplore::meshio::bumpy_sphere(2 * (rings - 1), rings, 0.03);
    let path = Path::new("generated-sphere");
    let mesh = Arc::new(Mesh::new(data, path).expect("the sphere builds"));
    let mut cache = AssetCache::new();
    cache.insert_mesh(path, mesh.clone());
    let text = "(version: 1, camera: (eye: (0, 0, 2.2), projection: Pinhole(fov: 36)),
          lights: [Directional(direction: (1, 1, 2))],
          objects: [(shape: Mesh(path: \"generated-sphere\", shading: Smooth),
                     material: Matte(cd: UvGrid(mapping: Uv, filter: Bilinear)))])";
    let mut desc = parse_preset(text, Path::new("generated")).expect("the bench's preset");
    apply_overrides(
        &mut desc,
        Overrides {
            width: Some(SIZE),
            height: Some(SIZE),
            ..Overrides::default()
        },
    );
    let scene = build_scene(&desc, Path::new("generated"), &mut cache).expect("the scene");
    let mut packets = Vec::new();
    for y in 0..SIZE {
        for x0 in (0..SIZE).step_by(MAX_LANES) {
            let rays: Vec<_> = (x0..x0 + MAX_LANES as u32)
                .map(|x| {
                    let pos = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                    scene.camera.primary_ray(pos)
                })
                .collect();
            packets.push(Packet::new(&rays));
        }
    }
    (mesh, packets)
}

/// Shadow rays from each primary hit (pushed off along the normal) toward the bench's light.
fn shadow_packets(mesh: &Mesh, primary: &[Packet]) -> Vec<Packet> {
    let light = Vec3A::new(1.0, 1.0, 2.0).normalize();
    primary
        .iter()
        .map(|p| {
            let rays: Vec<_> = p
                .rays()
                .map(|r| {
                    let r = r?;
                    let h = mesh.intersect_point(&r, f32::INFINITY, Shading::Smooth)?;
                    Some(Ray::new(h.p + h.n * 1e-4, light))
                })
                .collect();
            Packet::new(&rays)
        })
        .collect()
}

/// What a pass over the packets does at one width.
#[derive(Clone, Copy)]
enum Work {
    Nearest,
    Surface,
    Shadow,
}

struct Pass<'a> {
    mesh: &'a Mesh,
    packets: &'a [Packet],
    work: Work,
}

impl WithSimd for Pass<'_> {
    type Output = u32;

    #[inline(always)]
    fn with_simd<S: Simd>(self, s: S) -> u32 {
        let mut hits = 0;
        let inf = s.splat_f32s(f32::INFINITY);
        for p in self.packets {
            for first in (0..MAX_LANES).step_by(S::F32_LANES) {
                let (o, d, active) = p.lanes(s, first);
                let m = match self.work {
                    Work::Nearest => self.mesh.closest_hit_lanes(s, &o, &d, inf, active).hit,
                    Work::Surface => {
                        let h = self.mesh.closest_hit_lanes(s, &o, &d, inf, active);
                        let m = self.mesh.surface_lanes(s, &h, Shading::Smooth);
                        black_box(&m);
                        h.hit
                    }
                    Work::Shadow => self.mesh.occluded_lanes(s, &o, &d, inf, active),
                };
                hits += mask_to_array(s, m).iter().filter(|b| **b).count() as u32;
            }
        }
        hits
    }
}

/// The same rays one at a time.
#[inline(never)]
fn one_at_a_time(mesh: &Mesh, packets: &[Packet], work: Work) -> u32 {
    let mut hits = 0;
    for p in packets {
        for r in p.rays().flatten() {
            let hit = match work {
                Work::Nearest => mesh.closest_hit(&r, f32::INFINITY).is_some(),
                Work::Surface => mesh
                    .closest_hit(&r, f32::INFINITY)
                    .map(|h: TriangleHit| black_box(mesh.surface(h, Shading::Smooth)))
                    .is_some(),
                Work::Shadow => mesh.occluded(&r, f32::INFINITY),
            };
            hits += u32::from(hit);
        }
    }
    hits
}

pub fn mesh_packets(c: &mut Criterion) {
    let arch = pulp::Arch::new();
    let width = arch.dispatch(Width);
    let sizes: Vec<u32> = std::env::var("MESH_SIZES").map_or_else(
        |_| vec![10_000, 100_000, 1_000_000],
        |v| v.split(',').filter_map(|n| n.parse().ok()).collect(),
    );
    for triangles in sizes {
        let (mesh, packets) = scene(triangles);
        let shadows = shadow_packets(&mesh, &packets);
        let mut g = c.benchmark_group(format!("mesh-{triangles}"));
        g.sample_size(10);
        g.throughput(Throughput::Elements(u64::from(SIZE * SIZE)));
        for (name, work, packets) in [
            ("primary", Work::Nearest, &packets),
            ("surface", Work::Surface, &packets),
            ("shadow", Work::Shadow, &shadows),
        ] {
            let expected = one_at_a_time(&mesh, packets, work);
            assert_eq!(
                arch.dispatch(Pass {
                    mesh: &mesh,
                    packets,
                    work
                }),
                expected
            );
            g.bench_function(format!("{name}-packets-of-{width}"), |b| {
                b.iter(|| {
                    arch.dispatch(Pass {
                        mesh: &mesh,
                        packets,
                        work,
                    })
                });
            });
            #[cfg(target_arch = "x86_64")]
            if let Some(v3) = pulp::x86::V3::try_new() {
                g.bench_function(format!("{name}-packets-of-8-avx2"), |b| {
                    b.iter(|| {
                        Simd::vectorize(
                            v3,
                            Pass {
                                mesh: &mesh,
                                packets,
                                work,
                            },
                        )
                    });
                });
            }
            g.bench_function(format!("{name}-one-at-a-time"), |b| {
                b.iter(|| one_at_a_time(&mesh, packets, work));
            });
        }
        g.finish();
    }
}

/// The dispatched width.
struct Width;

impl WithSimd for Width {
    type Output = usize;

    #[inline(always)]
    fn with_simd<S: Simd>(self, _: S) -> usize {
        S::F32_LANES
    }
}
