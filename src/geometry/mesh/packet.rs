//! Meshes traced as packets: `S::F32_LANES` rays walk the BVH together ([`Bvh::walk`]) and each
//! triangle is tested for all of them at once, with the watertight test of Woop, Benthin and
//! Wald (2013) per lane: every lane has its own axis permutation and shear, chosen by selects.
//! One ray is the same code at width 1 ([`Mesh::closest_hit`], [`Mesh::occluded`]).
//!
//! A lane's answer is the same at every width and in every traversal order: the triangle with
//! the smallest t in (0, `t_max`), the lower index (BVH order) on equal t, and every triangle
//! that could be that answer is tested (the walk skips a box only where its entry along the
//! lane's dominant axis lies beyond the lane's nearest hit, and a triangle's t is clamped to
//! never lie before its nearest vertex along that axis: see [`crate::geometry::bvh`]'s walk).
//!
//! [`Bvh::walk`]: crate::geometry::bvh::Bvh::walk

use super::Mesh;
use crate::geometry::bvh::{BoxRays, Leaves, any_lane, dominant_axis, pick};
use crate::math::Vec3;
use crate::math::lanes::{
    F, M, MAX_LANES, U, V3, from_array, mask_splat, mask_to_array, to_array, to_array_u32,
};
use pulp::Simd;

/// The nearest triangle hits of a packet of rays ([`Mesh::closest_hit_lanes`]).
#[derive(Clone, Copy, Debug)]
pub struct TriangleHits<S: Simd> {
    /// The ray parameter of each lane's hit (`t_max` where it has none).
    pub t: F<S>,
    /// Which lanes hit a triangle within (0, `t_max`).
    pub hit: M<S>,
    /// Each lane's triangle, in BVH order ([`super::TriangleHit::triangle`]), in the first
    /// `S::F32_LANES` places (0 where the lane has no hit).
    pub triangle: [u32; MAX_LANES],
    /// The barycentric weights of the triangle's three vertices, per lane.
    pub bary: V3<S>,
}

/// A packet prepared for the watertight test: per lane, the axis permutation that makes the
/// direction's largest component the last (kz), swapping kx and ky where it is negative so the
/// winding is kept, and the shear that maps the ray onto that axis.
#[derive(Clone, Copy, Debug)]
pub(super) struct WoopRays<S: Simd> {
    /// kx, ky and kz per lane, each as the masks "is x" and "is y".
    k: [(M<S>, M<S>); 3],
    /// kx, ky and kz when every valid lane has the same (a coherent packet): a vertex's
    /// coordinates are then picked once for all lanes.
    uniform: Option<[usize; 3]>,
    /// The origin's coordinates along kx, ky and kz.
    o: V3<S>,
    sx: F<S>,
    sy: F<S>,
    sz: F<S>,
    /// The lanes that trace: asked for, with finite origin and direction, the direction not 0.
    pub(super) valid: M<S>,
}

impl<S: Simd> WoopRays<S> {
    #[inline(always)]
    pub(super) fn new(s: S, o: &V3<S>, d: &V3<S>, active: M<S>) -> Self {
        let (zx, zy) = dominant_axis(s, d);
        let zz = s.not_m32s(s.or_m32s(zx, zy));
        let dz = pick(s, zx, zy, d);
        let neg = s.less_than_f32s(dz, s.splat_f32s(0.0));
        let pos = s.not_m32s(neg);
        // kx = kz + 1, ky = kz + 2 (mod 3), the two swapped where d[kz] < 0.
        let kx = (either(s, zz, pos, zy, neg), either(s, zx, pos, zz, neg));
        let ky = (either(s, zy, pos, zz, neg), either(s, zz, pos, zx, neg));
        let (dx, dy) = (pick(s, kx.0, kx.1, d), pick(s, ky.0, ky.1, d));
        let valid = s.and_m32s(
            s.and_m32s(active, s.and_m32s(o.finite(s), d.finite(s))),
            s.not_m32s(s.equal_f32s(dz, s.splat_f32s(0.0))),
        );
        let codes = to_array_u32::<S>(
            s.add_u32s(s.add_u32s(code(s, zy, 1), code(s, zz, 2)), code(s, neg, 3)),
        );
        let lanes = mask_to_array(s, valid);
        let mut valid_codes = (0..S::F32_LANES).filter(|&i| lanes[i]).map(|i| codes[i]);
        let uniform = valid_codes.next().and_then(|first| {
            valid_codes.all(|c| c == first).then(|| {
                let (kz, neg) = ((first % 3) as usize, first >= 3);
                let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
                if neg { [ky, kx, kz] } else { [kx, ky, kz] }
            })
        });
        let one = s.splat_f32s(1.0);
        Self {
            k: [kx, ky, (zx, zy)],
            uniform,
            o: V3 {
                x: pick(s, kx.0, kx.1, o),
                y: pick(s, ky.0, ky.1, o),
                z: pick(s, zx, zy, o),
            },
            sx: s.div_f32s(dx, dz),
            sy: s.div_f32s(dy, dz),
            sz: s.div_f32s(one, dz),
            valid,
        }
    }

    /// A vertex in each lane's sheared frame: (v[kx] - sx v[kz], v[ky] - sy v[kz], sz v[kz])
    /// with v = p - o, each coordinate transformed alone so a shared edge has the same edge
    /// function in both triangles.
    #[inline(always)]
    fn vertex(&self, s: S, p: Vec3) -> V3<S> {
        let [px, py, pz] = if let Some(k) = self.uniform {
            crate::math::lanes::map3(k, |k| s.splat_f32s(p[k]))
        } else {
            let v = V3 {
                x: s.splat_f32s(p.x),
                y: s.splat_f32s(p.y),
                z: s.splat_f32s(p.z),
            };
            crate::math::lanes::map3(self.k, |(is_x, is_y)| pick(s, is_x, is_y, &v))
        };
        let vz = s.sub_f32s(pz, self.o.z);
        V3 {
            x: s.sub_f32s(s.sub_f32s(px, self.o.x), s.mul_f32s(self.sx, vz)),
            y: s.sub_f32s(s.sub_f32s(py, self.o.y), s.mul_f32s(self.sy, vz)),
            z: s.mul_f32s(self.sz, vz),
        }
    }

    /// The triangle (p0, p1, p2) for the rays of `lanes`: which hit it at some t > 0, their t
    /// and barycentrics. Exact zeros of an edge function are recomputed in f64 (exact for
    /// products of f32), so the sign test never lets a ray through a crack. t is clamped to
    /// the nearest vertex's `(p[kz] - o[kz]) / d[kz]`, where exact arithmetic keeps it (the
    /// barycentrics are non-negative): what makes the walk's box skipping safe.
    #[inline(always)]
    pub(super) fn test(&self, s: S, p0: Vec3, p1: Vec3, p2: Vec3, lanes: M<S>) -> Hit<S> {
        let (a, b, c) = (self.vertex(s, p0), self.vertex(s, p1), self.vertex(s, p2));
        let (mut u, mut v, mut w) = (edge(s, &c, &b), edge(s, &a, &c), edge(s, &b, &a));
        let zero = s.splat_f32s(0.0);
        let exact = s.and_m32s(
            lanes,
            s.or_m32s(
                s.or_m32s(s.equal_f32s(u, zero), s.equal_f32s(v, zero)),
                s.equal_f32s(w, zero),
            ),
        );
        if any_lane(s, exact) {
            (u, v, w) = exact_edges(s, exact, (&a, &b, &c), (u, v, w));
        }
        let outside = s.and_m32s(
            s.or_m32s(
                s.or_m32s(s.less_than_f32s(u, zero), s.less_than_f32s(v, zero)),
                s.less_than_f32s(w, zero),
            ),
            s.or_m32s(
                s.or_m32s(s.greater_than_f32s(u, zero), s.greater_than_f32s(v, zero)),
                s.greater_than_f32s(w, zero),
            ),
        );
        let inside = s.and_m32s(lanes, s.not_m32s(outside));
        if !any_lane(s, inside) {
            // Most tests end here; the lanes' answers are the same without the rest.
            return Hit {
                ok: inside,
                t: zero,
                bary: V3 {
                    x: zero,
                    y: zero,
                    z: zero,
                },
            };
        }
        let det = s.add_f32s(s.add_f32s(u, v), w);
        let t_scaled = s.add_f32s(
            s.add_f32s(s.mul_f32s(u, a.z), s.mul_f32s(v, b.z)),
            s.mul_f32s(w, c.z),
        );
        let inv = s.div_f32s(s.splat_f32s(1.0), det);
        let t = s.mul_f32s(t_scaled, inv);
        let nearest = s.select_f32s(s.less_than_f32s(b.z, a.z), b.z, a.z);
        let nearest = s.select_f32s(s.less_than_f32s(c.z, nearest), c.z, nearest);
        let t = s.select_f32s(s.less_than_f32s(t, nearest), nearest, t);
        let ok = s.and_m32s(
            inside,
            s.and_m32s(
                s.not_m32s(s.equal_f32s(det, zero)),
                s.greater_than_f32s(t, zero),
            ),
        );
        Hit {
            ok,
            t,
            bary: V3 {
                x: s.mul_f32s(u, inv),
                y: s.mul_f32s(v, inv),
                z: s.mul_f32s(w, inv),
            },
        }
    }
}

/// A triangle test's answer per lane.
pub(super) struct Hit<S: Simd> {
    /// The lanes that hit at some t > 0.
    pub(super) ok: M<S>,
    pub(super) t: F<S>,
    pub(super) bary: V3<S>,
}

impl Mesh {
    /// Triangle `i`'s three corners, indexed directly (an array `map` with a closure was a
    /// call per triangle tested: 5% of a mesh pass).
    #[inline(always)]
    fn corners(&self, i: u32) -> [Vec3; 3] {
        let [a, b, c] = self.triangles[i as usize];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }
}

/// `(a and b) or (c and e)` per lane.
#[inline(always)]
fn either<S: Simd>(s: S, a: M<S>, b: M<S>, c: M<S>, e: M<S>) -> M<S> {
    s.or_m32s(s.and_m32s(a, b), s.and_m32s(c, e))
}

/// `k` where `m`, else 0, per lane.
#[inline(always)]
fn code<S: Simd>(s: S, m: M<S>, k: u32) -> U<S> {
    s.select_u32s(m, s.splat_u32s(k), s.splat_u32s(0))
}

/// The edge functions of the lanes of `exact` recomputed in f64, where one of them was exactly
/// 0 in f32 (rare: a ray through an edge or a vertex). Per lane: each lane gives what it gives
/// alone.
#[cold]
#[inline(never)]
fn exact_edges<S: Simd>(
    s: S,
    exact: M<S>,
    (a, b, c): (&V3<S>, &V3<S>, &V3<S>),
    (u, v, w): (F<S>, F<S>, F<S>),
) -> (F<S>, F<S>, F<S>) {
    let (a, b, c) = (a.to_arrays(), b.to_arrays(), c.to_arrays());
    let (mut u, mut v, mut w) = (to_array::<S>(u), to_array::<S>(v), to_array::<S>(w));
    let exact = mask_to_array(s, exact);
    let f = f64::from;
    for i in 0..S::F32_LANES {
        if exact[i] {
            let (ax, ay, bx, by, cx, cy) = (a[0][i], a[1][i], b[0][i], b[1][i], c[0][i], c[1][i]);
            u[i] = (f(cx) * f(by) - f(cy) * f(bx)) as f32;
            v[i] = (f(ax) * f(cy) - f(ay) * f(cx)) as f32;
            w[i] = (f(bx) * f(ay) - f(by) * f(ax)) as f32;
        }
    }
    (
        from_array::<S>(&u),
        from_array::<S>(&v),
        from_array::<S>(&w),
    )
}

/// The closest-hit walk's state: each lane's nearest hit so far.
struct Nearest<'m, S: Simd> {
    mesh: &'m Mesh,
    woop: WoopRays<S>,
    t: F<S>,
    triangle: U<S>,
    bary: V3<S>,
    found: M<S>,
}

impl<S: Simd> Leaves<S> for Nearest<'_, S> {
    #[inline(always)]
    fn leaf(&mut self, s: S, first: u32, count: u32, lanes: M<S>) {
        for i in first..first + count {
            let [a, b, c] = self.mesh.corners(i);
            let h = self.woop.test(s, a, b, c, lanes);
            // Nearer, or as near with a lower index: the same winner in any order.
            let index = s.splat_u32s(i);
            let tie = s.and_m32s(
                s.and_m32s(self.found, s.equal_f32s(h.t, self.t)),
                s.less_than_u32s(index, self.triangle),
            );
            let better = s.and_m32s(h.ok, s.or_m32s(s.less_than_f32s(h.t, self.t), tie));
            self.t = s.select_f32s(better, h.t, self.t);
            self.triangle = s.select_u32s(better, index, self.triangle);
            self.bary = V3::select(s, better, &h.bary, &self.bary);
            self.found = s.or_m32s(self.found, better);
        }
    }

    #[inline(always)]
    fn bound(&self, _: S) -> F<S> {
        self.t
    }

    #[inline(always)]
    fn searching(&self, _: S) -> M<S> {
        self.woop.valid
    }
}

/// The shadow walk's state: which lanes found a triangle.
struct Blocked<'m, S: Simd> {
    mesh: &'m Mesh,
    woop: WoopRays<S>,
    t_max: F<S>,
    found: M<S>,
}

impl<S: Simd> Leaves<S> for Blocked<'_, S> {
    #[inline(always)]
    fn leaf(&mut self, s: S, first: u32, count: u32, lanes: M<S>) {
        for i in first..first + count {
            let open = s.and_m32s(lanes, s.not_m32s(self.found));
            if !any_lane(s, open) {
                return;
            }
            let [a, b, c] = self.mesh.corners(i);
            let h = self.woop.test(s, a, b, c, open);
            let hit = s.and_m32s(h.ok, s.less_than_f32s(h.t, self.t_max));
            self.found = s.or_m32s(self.found, hit);
        }
    }

    #[inline(always)]
    fn bound(&self, _: S) -> F<S> {
        self.t_max
    }

    #[inline(always)]
    fn searching(&self, s: S) -> M<S> {
        s.and_m32s(self.woop.valid, s.not_m32s(self.found))
    }
}

impl Mesh {
    /// The nearest triangle hit in (0, `t_max`) of each of the packet's object-space rays
    /// `o + t d` in `active`: one walk of the BVH for the whole packet, each triangle tested
    /// for every lane at once. Equal t go to the lower triangle index, so each lane's answer is
    /// the same bits at every width and in every traversal order; [`Mesh::closest_hit`] is the
    /// width-1 instance. Lanes with a non-finite origin or direction, or a zero direction, do
    /// not hit.
    #[must_use]
    #[inline(always)]
    pub fn closest_hit_lanes<S: Simd>(
        &self,
        s: S,
        o: &V3<S>,
        d: &V3<S>,
        t_max: F<S>,
        active: M<S>,
    ) -> TriangleHits<S> {
        let woop = WoopRays::new(s, o, d, active);
        let valid = woop.valid;
        let zero = s.splat_f32s(0.0);
        let mut nearest = Nearest {
            mesh: self,
            woop,
            t: t_max,
            triangle: s.splat_u32s(0),
            bary: V3 {
                x: zero,
                y: zero,
                z: zero,
            },
            found: mask_splat(s, false),
        };
        if any_lane(s, valid) {
            let rays = BoxRays::new(s, o, d, valid);
            self.bvh.walk(s, &rays, t_max, valid, &mut nearest);
        }
        TriangleHits {
            t: nearest.t,
            hit: nearest.found,
            triangle: to_array_u32::<S>(nearest.triangle),
            bary: nearest.bary,
        }
    }

    /// Whether any triangle lies on each of the packet's object-space rays within
    /// (0, `t_max`), for the lanes of `active` (shadow rays): each lane stops at its first hit,
    /// the packet when every lane has stopped. [`Mesh::occluded`] is the width-1 instance.
    #[must_use]
    #[inline(always)]
    pub fn occluded_lanes<S: Simd>(
        &self,
        s: S,
        o: &V3<S>,
        d: &V3<S>,
        t_max: F<S>,
        active: M<S>,
    ) -> M<S> {
        let woop = WoopRays::new(s, o, d, active);
        let valid = woop.valid;
        let mut blocked = Blocked {
            mesh: self,
            woop,
            t_max,
            found: mask_splat(s, false),
        };
        if any_lane(s, valid) {
            let rays = BoxRays::new(s, o, d, valid);
            self.bvh.walk(s, &rays, t_max, valid, &mut blocked);
        }
        blocked.found
    }
}

/// The edge function `p.x q.y - p.y q.x` per lane (a function, not a closure: closures are
/// compiled outside the dispatched instruction set and call each SIMD operation).
#[inline(always)]
fn edge<S: Simd>(s: S, p: &V3<S>, q: &V3<S>) -> F<S> {
    s.sub_f32s(s.mul_f32s(p.x, q.y), s.mul_f32s(p.y, q.x))
}

#[cfg(test)]
mod tests;
