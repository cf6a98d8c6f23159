//! The generic shapes' intersections, written once over pulp's `Simd`: `S::F32_LANES` rays at
//! a time in the render kernel, one at a time (pulp's `Scalar`) in [`super::intersect_shape`].
//! Each selects instead of branching, and every lane gives the bits the width-1 instance gives.
//!
//! Sphere and cylinder solve a t^2 + 2 b' t + c = 0 with `a = d.d`, `half_b = o.d`, `c = o.o - 1`
//! and the discriminant `a - |o x d|^2` (Lagrange's identity: exact where `b'^2 - a c` cancels
//! far from the surface, Ray Tracing Gems ch. 7); `q` takes the sign of `-half_b` so the roots'
//! sum never cancels. Hit points are projected back onto the exact surface, which removes the
//! error of `o + t d` far from the origin.

use super::shapes::{CYLINDER_BOTTOM, CYLINDER_TOP, CYLINDER_WALL};
use crate::math::Vec3A;
use crate::math::lanes::{F, M, U, V3, neg};
use pulp::Simd;

/// The nearest hits of a packet with one generic shape, in its object space.
#[derive(Clone, Copy, Debug)]
pub struct ShapeHits<S: Simd> {
    /// The ray parameter of each lane's hit (meaningful where `hit`).
    pub t: F<S>,
    /// The hit point, on the exact surface.
    pub p: V3<S>,
    /// The outward normal.
    pub n: V3<S>,
    /// The part hit (a cylinder's wall or caps; 0 elsewhere).
    pub part: U<S>,
    /// Which lanes hit within (0, `t_max`).
    pub hit: M<S>,
}

/// Which part of the plane y = 0 a flat shape keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flat {
    /// All of it (`Shape::Plane`).
    Plane,
    /// (x, z) in [-1, 1]^2 (`Shape::Rectangle`).
    Rectangle,
    /// x^2 + z^2 <= 1 (`Shape::Disk`).
    Disk,
}

/// The two roots of a t^2 + 2 half_b t + c = 0 in increasing order, and whether they are real
/// (`a` > 0 and a discriminant `a - perp2a` not below 0). A double root at 0 (the ray starts on
/// the surface, tangent) comes out as t = 0, inf or NaN: no hit, as the scalar code's early
/// return gave.
#[inline(always)]
fn stable_roots<S: Simd>(s: S, a: F<S>, half_b: F<S>, c: F<S>, perp2a: F<S>) -> (F<S>, F<S>, M<S>) {
    let zero = s.splat_f32s(0.0);
    let disc = s.sub_f32s(a, perp2a);
    let real = s.not_m32s(s.or_m32s(
        s.less_than_f32s(disc, zero),
        s.less_than_or_equal_f32s(a, zero),
    ));
    let root = s.sqrt_f32s(disc);
    let nb = neg(s, half_b);
    let q = s.select_f32s(
        s.greater_than_f32s(half_b, zero),
        s.sub_f32s(nb, root),
        s.add_f32s(nb, root),
    );
    let (r0, r1) = (s.div_f32s(c, q), s.div_f32s(q, a));
    let lt = s.less_than_f32s(r0, r1);
    (s.select_f32s(lt, r0, r1), s.select_f32s(lt, r1, r0), real)
}

/// Whether `t` lies in (0, `t_max`).
#[inline(always)]
fn within<S: Simd>(s: S, t: F<S>, t_max: F<S>) -> M<S> {
    s.and_m32s(
        s.greater_than_f32s(t, s.splat_f32s(0.0)),
        s.less_than_f32s(t, t_max),
    )
}

/// Whether `o + t d` lies within the generic cylinder's height, y in [-1, 1].
#[inline(always)]
fn height<S: Simd>(s: S, o: &V3<S>, d: &V3<S>, t: F<S>) -> M<S> {
    let one = s.splat_f32s(1.0);
    let y = s.add_f32s(o.y, s.mul_f32s(t, d.y));
    s.and_m32s(
        s.greater_than_or_equal_f32s(y, neg(s, one)),
        s.less_than_or_equal_f32s(y, one),
    )
}

/// The unit sphere's nearest hit per lane for t in (0, `t_max`).
#[must_use]
#[inline(always)]
pub fn sphere<S: Simd>(s: S, o: &V3<S>, d: &V3<S>, t_max: F<S>) -> ShapeHits<S> {
    let zero = s.splat_f32s(0.0);
    let c = s.sub_f32s(o.dot(s, o), s.splat_f32s(1.0));
    let half_b = o.dot(s, d);
    // Outside and heading away: both roots are behind the origin.
    let away = s.and_m32s(
        s.greater_than_f32s(c, zero),
        s.greater_than_or_equal_f32s(half_b, zero),
    );
    let perp = o.cross(s, d);
    let (t0, t1, real) = stable_roots(s, d.dot(s, d), half_b, c, perp.dot(s, &perp));
    let t = s.select_f32s(s.greater_than_f32s(t0, zero), t0, t1);
    let hit = s.and_m32s(s.and_m32s(s.not_m32s(away), real), within(s, t, t_max));
    let p = o.at(s, t, d).normalize_or(s, Vec3A::Y);
    ShapeHits {
        t,
        p,
        n: p,
        part: s.splat_u32s(0),
        hit,
    }
}

/// The plane y = 0's hit per lane for t in (0, `t_max`), kept where `flat` says.
#[must_use]
#[inline(always)]
pub fn flat<S: Simd>(s: S, o: &V3<S>, d: &V3<S>, t_max: F<S>, flat: Flat) -> ShapeHits<S> {
    let zero = s.splat_f32s(0.0);
    let one = s.splat_f32s(1.0);
    let t = s.div_f32s(neg(s, o.y), d.y);
    let q = o.at(s, t, d);
    let inside = match flat {
        Flat::Plane => s.equal_f32s(zero, zero),
        Flat::Rectangle => s.and_m32s(
            s.less_than_or_equal_f32s(s.abs_f32s(q.x), one),
            s.less_than_or_equal_f32s(s.abs_f32s(q.z), one),
        ),
        Flat::Disk => {
            s.less_than_or_equal_f32s(s.add_f32s(s.mul_f32s(q.x, q.x), s.mul_f32s(q.z, q.z)), one)
        }
    };
    let parallel = s.equal_f32s(d.y, zero);
    let hit = s.and_m32s(
        s.and_m32s(s.not_m32s(parallel), within(s, t, t_max)),
        inside,
    );
    ShapeHits {
        t,
        p: V3 {
            x: q.x,
            y: zero,
            z: q.z,
        },
        n: V3::splat(s, Vec3A::Y),
        part: s.splat_u32s(0),
        hit,
    }
}

/// The generic cylinder's nearest hit per lane for t in (0, `t_max`): the wall x^2 + z^2 = 1
/// for y in [-1, 1] (the nearer root whose point is within the height, else the farther), then,
/// when `capped`, the disks at y = -1 and y = 1 where they are nearer.
#[must_use]
#[inline(always)]
pub fn cylinder<S: Simd>(s: S, o: &V3<S>, d: &V3<S>, t_max: F<S>, capped: bool) -> ShapeHits<S> {
    let zero = s.splat_f32s(0.0);
    let one = s.splat_f32s(1.0);
    let oxz = V3 {
        x: o.x,
        y: zero,
        z: o.z,
    };
    let dxz = V3 {
        x: d.x,
        y: zero,
        z: d.z,
    };
    let a = dxz.dot(s, &dxz);
    let half_b = oxz.dot(s, &dxz);
    let c = s.sub_f32s(oxz.dot(s, &oxz), one);
    let cross = s.sub_f32s(s.mul_f32s(o.z, d.x), s.mul_f32s(o.x, d.z));
    let (t0, t1, real) = stable_roots(s, a, half_b, c, s.mul_f32s(cross, cross));
    let wall_ok = s.and_m32s(real, s.greater_than_f32s(a, zero));
    let near = s.and_m32s(
        wall_ok,
        s.and_m32s(within(s, t0, t_max), height(s, o, d, t0)),
    );
    let far = s.and_m32s(
        wall_ok,
        s.and_m32s(within(s, t1, t_max), height(s, o, d, t1)),
    );
    let mut t = s.select_f32s(near, t0, t1);
    let mut hit = s.or_m32s(near, far);
    let q = o.at(s, t, d);
    let radial = V3 {
        x: q.x,
        y: zero,
        z: q.z,
    }
    .normalize_or(s, Vec3A::Z);
    let mut p = V3 {
        x: radial.x,
        y: q.y,
        z: radial.z,
    };
    let mut n = radial;
    let mut part = s.splat_u32s(CYLINDER_WALL);
    if capped {
        let moving = s.not_m32s(s.equal_f32s(d.y, zero));
        for (y, id) in [(-1.0_f32, CYLINDER_BOTTOM), (1.0, CYLINDER_TOP)] {
            let tc = s.div_f32s(s.sub_f32s(s.splat_f32s(y), o.y), d.y);
            let t_best = s.select_f32s(hit, t, t_max);
            let qc = o.at(s, tc, d);
            let on_disk = s.less_than_or_equal_f32s(
                s.add_f32s(s.mul_f32s(qc.x, qc.x), s.mul_f32s(qc.z, qc.z)),
                one,
            );
            let cap = s.and_m32s(s.and_m32s(moving, within(s, tc, t_best)), on_disk);
            t = s.select_f32s(cap, tc, t);
            p = V3::select(
                s,
                cap,
                &V3 {
                    x: qc.x,
                    y: s.splat_f32s(y),
                    z: qc.z,
                },
                &p,
            );
            n = V3::select(s, cap, &V3::splat(s, Vec3A::new(0.0, y, 0.0)), &n);
            part = s.select_u32s(cap, s.splat_u32s(id), part);
            hit = s.or_m32s(hit, cap);
        }
    }
    ShapeHits { t, p, n, part, hit }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::lanes::testing::{Walk, WidthCheck, at_every_width, bits, lane, load, load3};
    use crate::math::lanes::{mask_to_array, to_array, to_array_u32};

    /// Every shape at every width against its width-1 instance, lane by lane, on rays from
    /// hard origins along hard directions (and many aimed at the shape), with hard `t_max`.
    struct Agree;

    impl WidthCheck for Agree {
        fn check<S: Simd>(&mut self, s: S, name: &'static str) {
            let mut walk = Walk(3);
            for round in 0..3000 {
                let (mut o, mut d) = (walk.v3(), walk.v3());
                if round % 2 == 0 {
                    for i in 0..16 {
                        o[2][i] += 2.0;
                        d[2][i] = -1.0;
                    }
                }
                let tm: [f32; 16] = std::array::from_fn(|i| {
                    [f32::INFINITY, 1.5, 2.0, 0.0, f32::NAN, 1.0][(round + i) % 6]
                });
                let (vo, vd, vt) = (load3::<S>(&o), load3::<S>(&d), load::<S>(&tm));
                let kinds: [(&str, ShapeHits<S>, ShapeHitsOne); 6] = [
                    ("sphere", sphere(s, &vo, &vd, vt), |o, d, t| {
                        sphere(pulp::Scalar, o, d, t)
                    }),
                    ("plane", flat(s, &vo, &vd, vt, Flat::Plane), |o, d, t| {
                        flat(pulp::Scalar, o, d, t, Flat::Plane)
                    }),
                    (
                        "rectangle",
                        flat(s, &vo, &vd, vt, Flat::Rectangle),
                        |o, d, t| flat(pulp::Scalar, o, d, t, Flat::Rectangle),
                    ),
                    ("disk", flat(s, &vo, &vd, vt, Flat::Disk), |o, d, t| {
                        flat(pulp::Scalar, o, d, t, Flat::Disk)
                    }),
                    ("cylinder", cylinder(s, &vo, &vd, vt, false), |o, d, t| {
                        cylinder(pulp::Scalar, o, d, t, false)
                    }),
                    (
                        "capped cylinder",
                        cylinder(s, &vo, &vd, vt, true),
                        |o, d, t| cylinder(pulp::Scalar, o, d, t, true),
                    ),
                ];
                for (what, h, one) in kinds {
                    let hit = mask_to_array(s, h.hit);
                    let t = to_array::<S>(h.t);
                    let (p, n) = (h.p.to_arrays(), h.n.to_arrays());
                    let part = to_array_u32::<S>(h.part);
                    for i in 0..S::F32_LANES {
                        let w = one(&V3::one(lane(&o, i)), &V3::one(lane(&d, i)), tm[i]);
                        assert_eq!(hit[i], w.hit, "{name}: {what} lane {i}");
                        if w.hit {
                            assert_eq!(bits(t[i]), bits(w.t), "{name}: {what} t");
                            assert_eq!(
                                lane(&p, i).to_array().map(bits),
                                w.p.vec().to_array().map(bits)
                            );
                            assert_eq!(
                                lane(&n, i).to_array().map(bits),
                                w.n.vec().to_array().map(bits)
                            );
                            assert_eq!(part[i], w.part, "{name}: {what} part");
                        }
                    }
                }
            }
        }
    }

    type ShapeHitsOne = fn(&V3<pulp::Scalar>, &V3<pulp::Scalar>, f32) -> ShapeHits<pulp::Scalar>;

    #[test]
    fn every_shape_gives_the_same_hits_at_every_width() {
        assert!(at_every_width(&mut Agree) >= 1);
    }
}
