//! The kernel's first stage: each lane's nearest hit over the scene's objects, in preset order
//! (a nearer hit of a later object replaces an earlier one; equal distances keep the earlier).

use super::{Rays, lanes};
use crate::geometry::lanes::{Flat, ShapeHits, cylinder, flat, sphere};
use crate::geometry::mesh::{MeshSurface, TriangleHits};
use crate::geometry::{LocalHit, Shape};
use crate::math::lanes::{F, M, MAX_LANES, V3, mask_from_array, mask_to_array};
use crate::math::{Vec2, Vec3A};
use crate::scene::Scene;
use pulp::Simd;

/// Each lane's nearest hit, in its object's space.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hits<S: Simd> {
    /// Which lanes hit something.
    pub hit: M<S>,
    /// The ray parameter of the hit.
    pub t: F<S>,
    /// The object hit (`u32::MAX` for none).
    pub object: [u32; MAX_LANES],
    /// The object-space point, geometric normal and shading normal.
    pub p: V3<S>,
    pub n: V3<S>,
    pub ns: V3<S>,
    /// The part hit (a cylinder's wall or cap) and the triangle (a mesh's, in BVH order).
    pub part: [u32; MAX_LANES],
    pub prim: [u32; MAX_LANES],
    /// The (u, v) a mesh carries at the hit.
    pub uv: [Option<Vec2>; MAX_LANES],
}

impl<S: Simd> Hits<S> {
    /// The lanes that hit object `k`.
    #[inline(always)]
    pub fn of_object(&self, s: S, k: u32) -> M<S> {
        let mine: [bool; MAX_LANES] = crate::math::lanes::each_lane(|i| self.object[i] == k);
        s.and_m32s(self.hit, mask_from_array(s, &mine))
    }

    /// Lane `i`'s hit as the scalar code's record.
    #[inline(always)]
    pub fn local(
        &self,
        i: usize,
        p: &[[f32; MAX_LANES]; 3],
        n: &[[f32; MAX_LANES]; 3],
        ns: &[[f32; MAX_LANES]; 3],
        t: &[f32; MAX_LANES],
    ) -> LocalHit {
        let v = |a: &[[f32; MAX_LANES]; 3]| Vec3A::new(a[0][i], a[1][i], a[2][i]);
        LocalHit {
            t: t[i],
            p: v(p),
            n: v(n),
            ns: v(ns),
            uv: self.uv[i],
            dpduv: None,
            part: self.part[i],
            prim: self.prim[i],
        }
    }
}

impl Scene {
    /// The nearest hit of each active lane over the objects (`t` in (0, inf)).
    #[inline(always)]
    pub(crate) fn nearest_lanes<S: Simd>(&self, s: S, rays: &Rays<S>) -> Hits<S> {
        self.nearest_lanes_within(s, rays, f32::INFINITY)
    }

    /// The nearest hit of each active lane over the objects, `t` in (0, `t_max`).
    #[inline(always)]
    pub(crate) fn nearest_lanes_within<S: Simd>(
        &self,
        s: S,
        rays: &Rays<S>,
        t_max: f32,
    ) -> Hits<S> {
        let inf = s.splat_f32s(t_max);
        let zero3 = V3::splat(s, Vec3A::ZERO);
        let mut h = Hits {
            hit: crate::math::lanes::mask_splat(s, false),
            // Inactive lanes search (0, 0): nothing hits them.
            t: s.select_f32s(rays.active, inf, s.splat_f32s(0.0)),
            object: [u32::MAX; MAX_LANES],
            p: zero3,
            n: zero3,
            ns: zero3,
            part: [0; MAX_LANES],
            prim: [0; MAX_LANES],
            uv: [None; MAX_LANES],
        };
        for (k, ob) in self.objects.iter().enumerate() {
            let (o, d) = if ob.identity {
                (rays.o, rays.d)
            } else {
                (
                    rays.o.point(s, &ob.object_from_world),
                    rays.d.linear(s, &ob.object_from_world.matrix3),
                )
            };
            let found = match &ob.shape {
                Shape::Sphere => sphere(s, &o, &d, h.t),
                Shape::Plane => flat(s, &o, &d, h.t, Flat::Plane),
                Shape::Rectangle => flat(s, &o, &d, h.t, Flat::Rectangle),
                Shape::Disk => flat(s, &o, &d, h.t, Flat::Disk),
                Shape::Cylinder { capped } => cylinder(s, &o, &d, h.t, *capped),
                Shape::Mesh(m) => {
                    // The whole packet walks the BVH together (geometry::mesh::packet).
                    let th = m.mesh.closest_hit_lanes(s, &o, &d, h.t, rays.active);
                    if crate::math::lanes::any(s, th.hit) {
                        let ms = m.mesh.surface_lanes(s, &th, m.shading);
                        Self::take_mesh(s, &mut h, &th, &ms, k as u32);
                    }
                    continue;
                }
            };
            Self::take(s, &mut h, &found, k as u32);
        }
        h
    }

    /// Keeps a mesh's hits `th` (with their surface `ms`) of object `k` where it hit.
    #[inline(always)]
    fn take_mesh<S: Simd>(
        s: S,
        h: &mut Hits<S>,
        th: &TriangleHits<S>,
        ms: &MeshSurface<S>,
        k: u32,
    ) {
        h.t = s.select_f32s(th.hit, th.t, h.t);
        h.p = V3::select(s, th.hit, &ms.p, &h.p);
        h.n = V3::select(s, th.hit, &ms.n, &h.n);
        h.ns = V3::select(s, th.hit, &ms.ns, &h.ns);
        h.hit = s.or_m32s(h.hit, th.hit);
        let won = mask_to_array(s, th.hit);
        let (u, v) = (lanes::<S>(ms.u), lanes::<S>(ms.v));
        for i in 0..S::F32_LANES {
            if won[i] {
                h.object[i] = k;
                h.part[i] = ms.part[i];
                h.prim[i] = th.triangle[i];
                h.uv[i] = ms.has_uv.then(|| Vec2::new(u[i], v[i]));
            }
        }
    }

    /// Which lanes of `rays` some shadow-casting object blocks within (0, `t_max`), leaving
    /// out object `skip[i]` for lane `i` (`usize::MAX`: none): the shadow rays of a packet,
    /// traced together; each lane stops at its first blocker, the packet when all have.
    #[inline(always)]
    pub(crate) fn occluded_lanes<S: Simd>(
        &self,
        s: S,
        rays: &Rays<S>,
        t_max: F<S>,
        skip: &[usize; MAX_LANES],
    ) -> M<S> {
        let zero = s.splat_f32s(0.0);
        let mut blocked = crate::math::lanes::mask_splat(s, false);
        for (k, ob) in self.objects.iter().enumerate() {
            if !ob.casts_shadows {
                continue;
            }
            let others: [bool; MAX_LANES] = crate::math::lanes::each_lane(|i| skip[i] != k);
            let open = s.and_m32s(
                s.and_m32s(rays.active, mask_from_array(s, &others)),
                s.not_m32s(blocked),
            );
            if !crate::math::lanes::any(s, open) {
                continue;
            }
            // Closed lanes search (0, 0): nothing hits them.
            let t = s.select_f32s(open, t_max, zero);
            let (o, d) = if ob.identity {
                (rays.o, rays.d)
            } else {
                (
                    rays.o.point(s, &ob.object_from_world),
                    rays.d.linear(s, &ob.object_from_world.matrix3),
                )
            };
            let hit = match &ob.shape {
                Shape::Sphere => sphere(s, &o, &d, t).hit,
                Shape::Plane => flat(s, &o, &d, t, Flat::Plane).hit,
                Shape::Rectangle => flat(s, &o, &d, t, Flat::Rectangle).hit,
                Shape::Disk => flat(s, &o, &d, t, Flat::Disk).hit,
                Shape::Cylinder { capped } => cylinder(s, &o, &d, t, *capped).hit,
                Shape::Mesh(m) => m.mesh.occluded_lanes(s, &o, &d, t, open),
            };
            blocked = s.or_m32s(blocked, s.and_m32s(open, hit));
        }
        blocked
    }

    /// Keeps a generic shape's hits `f` of object `k` where it hit (nearer than before).
    #[inline(always)]
    fn take<S: Simd>(s: S, h: &mut Hits<S>, f: &ShapeHits<S>, k: u32) {
        if !crate::math::lanes::any(s, f.hit) {
            return;
        }
        h.t = s.select_f32s(f.hit, f.t, h.t);
        h.p = V3::select(s, f.hit, &f.p, &h.p);
        h.n = V3::select(s, f.hit, &f.n, &h.n);
        h.ns = V3::select(s, f.hit, &f.n, &h.ns);
        h.hit = s.or_m32s(h.hit, f.hit);
        let won = mask_to_array(s, f.hit);
        let part = crate::math::lanes::to_array_u32::<S>(f.part);
        for i in 0..S::F32_LANES {
            if won[i] {
                h.object[i] = k;
                h.part[i] = part[i];
                h.prim[i] = 0;
                h.uv[i] = None;
            }
        }
    }
}
