//! Lane-wise twins of the scalar kernels the packet path ([`super::packet`]) runs: the
//! polynomial atan2, the generic shapes' intersections and the mappings, each over
//! [`LANES`] rays held as struct-of-arrays (`[f32; LANES]` per component).
//!
//! Every function here is written as plain loops over the lanes with selects instead of
//! branches, and marked `#[inline(always)]`: inlined into the packet kernel, which runs inside
//! [`pulp::Arch::dispatch`]'s `#[target_feature]` function, they compile to AVX-512, AVX2 or SSE2
//! code for the CPU found at run time. Each follows its scalar twin operation for operation (the
//! same roundings in the same order; Rust never fuses a multiply and an add on its own), so a
//! lane gives the scalar path's number bit for bit: the tests in `tests/headless/simd.rs` and below
//! compare them on hard inputs.

// Lane loops index several arrays by the lane (`for i in 0..LANES`), the form the vectoriser
// reads best; `&` and `|` between lane conditions keep them branch-free (selects, not jumps).
#![allow(clippy::needless_range_loop, clippy::needless_bitwise_bool)]

use crate::math::{ATAN_POLY, Affine3A, PI, TAU, Vec3A};
use std::f32::consts::FRAC_PI_2;

/// Rays per packet: 16 f32 lanes fill an AVX-512 register (two AVX2 registers, four NEON or
/// SSE2 ones).
pub const LANES: usize = 16;

/// One f32 per lane.
pub type F = [f32; LANES];
/// One flag per lane.
pub type M = [bool; LANES];

/// A value in every lane.
#[must_use]
#[inline(always)]
pub fn splat(x: f32) -> F {
    [x; LANES]
}

/// Three coordinates per lane (points, directions, normals).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3 {
    /// x per lane.
    pub x: F,
    /// y per lane.
    pub y: F,
    /// z per lane.
    pub z: F,
}

impl V3 {
    /// `v` in every lane.
    #[must_use]
    #[inline(always)]
    pub fn splat(v: Vec3A) -> Self {
        Self {
            x: splat(v.x),
            y: splat(v.y),
            z: splat(v.z),
        }
    }

    /// Lane `i` as a glam vector.
    #[must_use]
    #[inline(always)]
    pub fn lane(&self, i: usize) -> Vec3A {
        Vec3A::new(self.x[i], self.y[i], self.z[i])
    }

    /// Sets lane `i`.
    #[inline(always)]
    pub fn set_lane(&mut self, i: usize, v: Vec3A) {
        (self.x[i], self.y[i], self.z[i]) = (v.x, v.y, v.z);
    }

    /// The dot product per lane, summed as glam's SSE2 `dot` sums: (x + y) + z.
    #[must_use]
    #[inline(always)]
    pub fn dot(&self, o: &Self) -> F {
        let mut r = [0.0; LANES];
        for i in 0..LANES {
            r[i] = (self.x[i] * o.x[i] + self.y[i] * o.y[i]) + self.z[i] * o.z[i];
        }
        r
    }

    /// The cross product per lane.
    #[must_use]
    #[inline(always)]
    pub fn cross(&self, o: &Self) -> Self {
        let mut r = *self;
        for i in 0..LANES {
            r.x[i] = self.y[i] * o.z[i] - o.y[i] * self.z[i];
            r.y[i] = self.z[i] * o.x[i] - o.z[i] * self.x[i];
            r.z[i] = self.x[i] * o.y[i] - o.x[i] * self.y[i];
        }
        r
    }

    /// `self + t d` per lane (`Ray::at`).
    #[must_use]
    #[inline(always)]
    pub fn at(&self, t: &F, d: &Self) -> Self {
        let mut r = *self;
        for i in 0..LANES {
            r.x[i] = self.x[i] + t[i] * d.x[i];
            r.y[i] = self.y[i] + t[i] * d.y[i];
            r.z[i] = self.z[i] + t[i] * d.z[i];
        }
        r
    }

    /// Unit length per lane, or `fallback` where the length is zero or not finite (glam's
    /// `normalize_or`: multiplied by 1 / length).
    #[must_use]
    #[inline(always)]
    pub fn normalize_or(&self, fallback: Vec3A) -> Self {
        let len2 = self.dot(self);
        let mut r = *self;
        for i in 0..LANES {
            let rcp = 1.0 / len2[i].sqrt();
            let ok = rcp.is_finite() & (rcp > 0.0);
            r.x[i] = if ok { self.x[i] * rcp } else { fallback.x };
            r.y[i] = if ok { self.y[i] * rcp } else { fallback.y };
            r.z[i] = if ok { self.z[i] * rcp } else { fallback.z };
        }
        r
    }

    /// The largest absolute coordinate per lane (`math::max_abs`).
    #[must_use]
    #[inline(always)]
    pub fn max_abs(&self) -> F {
        let mut r = [0.0; LANES];
        for i in 0..LANES {
            r[i] = self.x[i].abs().max(self.y[i].abs()).max(self.z[i].abs());
        }
        r
    }

    /// The linear part of `m` applied per lane, summed as glam's `Mat3A * Vec3A`:
    /// (c0 x + c1 y) + c2 z.
    #[must_use]
    #[inline(always)]
    pub fn linear(&self, m: &crate::math::Mat3A) -> Self {
        let (c0, c1, c2) = (m.x_axis, m.y_axis, m.z_axis);
        let mut r = *self;
        for i in 0..LANES {
            let (x, y, z) = (self.x[i], self.y[i], self.z[i]);
            r.x[i] = (c0.x * x + c1.x * y) + c2.x * z;
            r.y[i] = (c0.y * x + c1.y * y) + c2.y * z;
            r.z[i] = (c0.z * x + c1.z * y) + c2.z * z;
        }
        r
    }

    /// `m` applied to points per lane (`Affine3A::transform_point3a`).
    #[must_use]
    #[inline(always)]
    pub fn point(&self, m: &Affine3A) -> Self {
        let mut r = self.linear(&m.matrix3);
        let t = m.translation;
        for i in 0..LANES {
            r.x[i] += t.x;
            r.y[i] += t.y;
            r.z[i] += t.z;
        }
        r
    }
}

/// `y.atan2(x)` per lane: [`crate::math::atan2`] lane by lane, the same polynomial and octant
/// unfolding as selects. Lanes where the reduction is 0 / 0 or inf / inf (or NaN) take libm's
/// `atan2` as the scalar one does, after the vector part.
#[must_use]
#[inline(always)]
pub fn atan2(y: &F, x: &F) -> F {
    let mut r = [0.0; LANES];
    let mut ts = [0.0; LANES];
    for i in 0..LANES {
        let (ax, ay) = (x[i].abs(), y[i].abs());
        let swap = ay > ax;
        let (num, den) = if swap { (ax, ay) } else { (ay, ax) };
        let t = num / den;
        ts[i] = t;
        let s = t * t;
        let mut p = ATAN_POLY[7];
        p = p * s + ATAN_POLY[6];
        p = p * s + ATAN_POLY[5];
        p = p * s + ATAN_POLY[4];
        p = p * s + ATAN_POLY[3];
        p = p * s + ATAN_POLY[2];
        p = p * s + ATAN_POLY[1];
        p = p * s + ATAN_POLY[0];
        let mut a = t + t * s * p;
        a = if swap { FRAC_PI_2 - a } else { a };
        a = if x[i].is_sign_negative() { PI - a } else { a };
        r[i] = a.copysign(y[i]);
    }
    if ts.iter().any(|t| t.is_nan()) {
        for i in 0..LANES {
            if ts[i].is_nan() {
                r[i] = y[i].atan2(x[i]);
            }
        }
    }
    r
}

/// The azimuth u = atan2(x, z) / 2 pi in [0, 1) per lane (`mapping::azimuth` without its
/// gradient).
#[must_use]
#[inline(always)]
pub fn azimuth(x: &F, z: &F) -> F {
    let mut u = atan2(x, z);
    for ui in &mut u {
        let phi = if *ui < 0.0 { *ui + TAU } else { *ui };
        let v = phi / TAU;
        *ui = if v < 1.0 { v.max(0.0) + 0.0 } else { 0.0 };
    }
    u
}

/// `p` divided by its largest absolute coordinate per lane (`mapping::rescaled`), and whether
/// that coordinate was positive and finite (the scalar `Some`).
#[must_use]
#[inline(always)]
fn rescaled(p: &V3) -> (V3, M) {
    let s = p.max_abs();
    let mut q = *p;
    let mut ok = [false; LANES];
    for i in 0..LANES {
        ok[i] = (s[i] > 0.0) & s[i].is_finite();
        q.x[i] = p.x[i] / s[i];
        q.y[i] = p.y[i] / s[i];
        q.z[i] = p.z[i] / s[i];
    }
    (q, ok)
}

/// (u, v) per lane where both are finite; (0.5, 0.5) elsewhere, as `Mapping::map_impl` does.
#[inline(always)]
fn finite_or_centre(u: &mut F, v: &mut F) {
    for i in 0..LANES {
        let ok = u[i].is_finite() & v[i].is_finite();
        u[i] = if ok { u[i] } else { 0.5 };
        v[i] = if ok { v[i] } else { 0.5 };
    }
}

/// The spherical map's (u, v) per lane (`Mapping::Spherical.map_uv`).
#[must_use]
#[inline(always)]
pub fn spherical(p: &V3) -> (F, F) {
    let (q, ok) = rescaled(p);
    let mut u = azimuth(&q.x, &q.z);
    let mut rho = [0.0; LANES];
    for i in 0..LANES {
        rho[i] = (q.x[i] * q.x[i] + q.z[i] * q.z[i]).sqrt();
    }
    let theta = atan2(&rho, &q.y);
    let mut v = [0.0; LANES];
    for i in 0..LANES {
        v[i] = (1.0 - theta[i] / PI).clamp(0.0, 1.0);
        u[i] = if ok[i] { u[i] } else { 0.0 };
        v[i] = if ok[i] { v[i] } else { 0.5 };
    }
    finite_or_centre(&mut u, &mut v);
    (u, v)
}

/// The cylindrical map's (u, v) per lane (`Mapping::Cylindrical.map_uv`).
#[must_use]
#[inline(always)]
pub fn cylindrical(p: &V3) -> (F, F) {
    let flat = V3 {
        x: p.x,
        y: splat(0.0),
        z: p.z,
    };
    let (q, ok) = rescaled(&flat);
    let mut u = azimuth(&q.x, &q.z);
    let mut v = [0.0; LANES];
    for i in 0..LANES {
        u[i] = if ok[i] { u[i] } else { 0.0 };
        let w = (p.y[i] + 1.0) * 0.5;
        v[i] = if w.is_nan() { 0.5 } else { w.clamp(0.0, 1.0) };
    }
    finite_or_centre(&mut u, &mut v);
    (u, v)
}

/// The rectangular map's (u, v) per lane (`Mapping::Rectangular.map_uv`).
#[must_use]
#[inline(always)]
pub fn rectangular(p: &V3) -> (F, F) {
    let (mut u, mut v) = ([0.0; LANES], [0.0; LANES]);
    for i in 0..LANES {
        u[i] = (p.z[i] + 1.0) * 0.5;
        v[i] = (p.x[i] + 1.0) * 0.5;
    }
    finite_or_centre(&mut u, &mut v);
    (u, v)
}

/// The unit sphere's nearest hit per lane for t in (0, `t_max`) (`geometry`'s `sphere`: the
/// stable quadratic with Lagrange's discriminant, then the hit point projected back onto the
/// sphere). Returns t (meaningful where hit) and the hit flags; the point is
/// [`sphere_point`].
#[must_use]
#[inline(always)]
pub fn sphere(o: &V3, d: &V3, t_max: &F) -> (F, M) {
    let oo = o.dot(o);
    let half_b = o.dot(d);
    let a = d.dot(d);
    let perp = o.cross(d);
    let perp2a = perp.dot(&perp);
    let mut t = [0.0; LANES];
    let mut hit = [false; LANES];
    for i in 0..LANES {
        let c = oo[i] - 1.0;
        let away = (c > 0.0) & (half_b[i] >= 0.0);
        let disc = a[i] - perp2a[i];
        let real = !((disc < 0.0) | (a[i] <= 0.0));
        let root = disc.sqrt();
        let q = if half_b[i] > 0.0 {
            -half_b[i] - root
        } else {
            -half_b[i] + root
        };
        let (r0, r1) = (c / q, q / a[i]);
        let (t0, t1) = if r0 < r1 { (r0, r1) } else { (r1, r0) };
        // q == 0 is the scalar path's double root at 0, which is no hit. Here c / 0 is
        // +-inf or NaN and 0 / a is 0, so t is 0, inf or NaN: no hit either, without a branch
        // (which kept the divisions from vectorising).
        let ti = if t0 > 0.0 { t0 } else { t1 };
        hit[i] = !away & real & (ti > 0.0) & (ti < t_max[i]);
        t[i] = ti;
    }
    (t, hit)
}

/// The explicit kernels, generic over pulp's `Simd` (16 lanes per instruction on AVX-512, 8 on
/// AVX2, 4 on NEON), each bit for bit its loop twin here.
pub mod wide;

/// The sphere's hit point per lane: `o + t d` projected onto the unit sphere (also its normal).
#[must_use]
#[inline(always)]
pub fn sphere_point(o: &V3, d: &V3, t: &F) -> V3 {
    o.at(t, d).normalize_or(Vec3A::Y)
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

/// The plane y = 0's hit per lane for t in (0, `t_max`), kept where `flat` says
/// (`geometry`'s `plane`). Returns t, the hit point (y = 0) and the hit flags.
#[must_use]
#[inline(always)]
pub fn flat(o: &V3, d: &V3, t_max: &F, flat: Flat) -> (F, V3, M) {
    let mut t = [0.0; LANES];
    let mut hit = [false; LANES];
    for i in 0..LANES {
        t[i] = -o.y[i] / d.y[i];
    }
    let mut p = o.at(&t, d);
    for i in 0..LANES {
        let (x, z) = (p.x[i], p.z[i]);
        let inside = match flat {
            Flat::Plane => true,
            Flat::Rectangle => (x.abs() <= 1.0) & (z.abs() <= 1.0),
            Flat::Disk => x * x + z * z <= 1.0,
        };
        hit[i] = (d.y[i] != 0.0) & (t[i] > 0.0) & (t[i] < t_max[i]) & inside;
        p.y[i] = 0.0;
    }
    (t, p, hit)
}

/// One light's term added to the radiance `l` and the cosine sum `lit` where `reach` (the
/// light loop of the packet path's direct light): `f = diffuse + spec pw` where the highlight
/// is on, else `diffuse`; `l += f li (n . wi)`; `lit += n . wi`. `wide::add_light` is its
/// explicit twin, generic over pulp's `Simd`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn add_light(
    reach: &M,
    has_spec: &M,
    pw: &F,
    diffuse: &[F; 3],
    spec: &[F; 3],
    li: [f32; 3],
    ndotwi: &F,
    l: &mut [F; 3],
    lit: &mut F,
) {
    for c in 0..3 {
        for i in 0..LANES {
            let f = if has_spec[i] && pw[i] != 0.0 {
                diffuse[c][i] + spec[c][i] * pw[i]
            } else {
                diffuse[c][i]
            };
            let add = f * li[c] * ndotwi[i];
            l[c][i] = if reach[i] { l[c][i] + add } else { l[c][i] };
        }
    }
    for i in 0..LANES {
        lit[i] = if reach[i] { lit[i] + ndotwi[i] } else { lit[i] };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Shape, intersect_shape};
    use crate::mapping::Mapping;
    use crate::math::{Ray, Vec2};

    fn lanes(v: &[f32]) -> F {
        let mut r = [0.0; LANES];
        for (i, x) in r.iter_mut().enumerate() {
            *x = v[i % v.len()];
        }
        r
    }

    #[test]
    fn atan2_lanes_match_the_scalar_bit_for_bit_on_hard_inputs() {
        let specials = [
            0.0,
            -0.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            1.0,
            -1.0,
            1e-40,
            -3.3e38,
            f32::NAN,
            0.3,
        ];
        for &y in &specials {
            for chunk in specials.chunks(4) {
                let xs = lanes(chunk);
                let got = atan2(&splat(y), &xs);
                #[cfg(target_arch = "x86_64")]
                if let Some(s) = wide::token() {
                    let w = wide::atan2(s, &splat(y), &xs);
                    assert_eq!(w.map(f32::to_bits), got.map(f32::to_bits), "8-wide atan2");
                    let w = wide::atan2(s, &xs, &splat(y));
                    let l = atan2(&xs, &splat(y));
                    assert_eq!(w.map(f32::to_bits), l.map(f32::to_bits), "8-wide atan2");
                }
                for i in 0..LANES {
                    let want = crate::math::atan2(y, xs[i]);
                    assert!(
                        got[i].to_bits() == want.to_bits() || (got[i].is_nan() && want.is_nan()),
                        "atan2({y}, {}) = {} lane-wise, {} scalar",
                        xs[i],
                        got[i],
                        want
                    );
                }
            }
        }
    }

    #[test]
    fn spherical_lanes_match_the_scalar_at_the_seam_and_the_poles() {
        let pts = [
            Vec3A::new(0.0, 0.0, 1.0),
            Vec3A::new(-0.0, 0.0, -1.0), // the seam from behind
            Vec3A::new(-1e-8, 0.0, -1.0),
            Vec3A::new(1e-8, 0.0, -1.0),
            Vec3A::new(0.0, 1.0, 0.0), // north pole
            Vec3A::new(0.0, -1.0, 0.0),
            Vec3A::new(-0.0, -1.0, -0.0),
            Vec3A::ZERO,
            Vec3A::new(f32::NAN, 0.2, 0.3),
            Vec3A::new(3e38, -3e38, 1.0),
            Vec3A::new(0.6, 0.0, 0.8),
            Vec3A::new(-f32::MIN_POSITIVE, 0.5, 0.0),
        ];
        for chunk in pts.chunks(LANES) {
            let mut p = V3::splat(Vec3A::ZERO);
            for (i, &q) in chunk.iter().enumerate() {
                p.set_lane(i, q);
            }
            for (mapping, f) in [
                (Mapping::Spherical, spherical as fn(&V3) -> (F, F)),
                (Mapping::Cylindrical, cylindrical),
                (Mapping::Rectangular, rectangular),
            ] {
                let (u, v) = f(&p);
                #[cfg(target_arch = "x86_64")]
                if let (Mapping::Spherical, Some(s)) = (mapping, wide::token()) {
                    let (wu, wv) = wide::spherical(s, &p);
                    assert_eq!(wu.map(f32::to_bits), u.map(f32::to_bits), "8-wide u");
                    assert_eq!(wv.map(f32::to_bits), v.map(f32::to_bits), "8-wide v");
                }
                for (i, &q) in chunk.iter().enumerate() {
                    let want = mapping.map_uv(q);
                    assert_eq!(
                        (u[i].to_bits(), v[i].to_bits()),
                        (want.x.to_bits(), want.y.to_bits()),
                        "{mapping} at {q}: ({}, {}) lane-wise, {want} scalar",
                        u[i],
                        v[i]
                    );
                }
            }
        }
        // The seam: u = 1 - ulp stays below 1 and the wrap keeps it in the last column.
        let below_one = 1.0 - f32::EPSILON / 2.0;
        assert!(below_one < 1.0);
        assert_eq!(
            crate::texture::Wrap::Repeat.coord(below_one),
            Some(below_one)
        );
        let _ = Vec2::ZERO;
    }

    fn check_shape(shape: &Shape, rays: &[(Vec3A, Vec3A)]) {
        for chunk in rays.chunks(LANES) {
            let (mut o, mut d) = (V3::splat(Vec3A::ZERO), V3::splat(Vec3A::Z));
            for (i, &(a, b)) in chunk.iter().enumerate() {
                o.set_lane(i, a);
                d.set_lane(i, b);
            }
            let t_max = splat(f32::INFINITY);
            let (t, p, hit) = match shape {
                Shape::Sphere => {
                    let (t, hit) = sphere(&o, &d, &t_max);
                    (t, sphere_point(&o, &d, &t), hit)
                }
                Shape::Plane => flat(&o, &d, &t_max, Flat::Plane),
                Shape::Rectangle => flat(&o, &d, &t_max, Flat::Rectangle),
                _ => flat(&o, &d, &t_max, Flat::Disk),
            };
            // The explicit 8-wide sphere gives the loop's t and hit flags bit for bit, the
            // unused lanes (past the chunk) included.
            #[cfg(target_arch = "x86_64")]
            if let (Shape::Sphere, Some(s)) = (shape, wide::token()) {
                let (tw, hw) = wide::sphere(s, &o, &d, &t_max);
                let (tl, hl) = sphere(&o, &d, &t_max);
                assert_eq!(wide::flags(hw), hl, "8-wide sphere hits, rays {chunk:?}");
                assert_eq!(tw.map(f32::to_bits), tl.map(f32::to_bits), "8-wide t");
            }
            for (i, &(a, b)) in chunk.iter().enumerate() {
                let want = intersect_shape(shape, &Ray::new(a, b), f32::INFINITY);
                assert_eq!(hit[i], want.is_some(), "{shape:?} from {a} along {b}");
                if let Some(h) = want {
                    assert_eq!(t[i].to_bits(), h.t.to_bits(), "t from {a} along {b}");
                    assert_eq!(p.lane(i), h.p, "point from {a} along {b}");
                }
            }
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn wide_sphere_and_selects_match_the_lane_loops_on_nan_inf_and_near_t_max() {
        let Some(s) = wide::token() else { return };
        let vals = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            3.0,
            -7.0,
            f32::NAN,
            f32::INFINITY,
            1e-30,
        ];
        let mut n = 0_usize;
        let mut next = || {
            n = (n * 7 + 3) % vals.len();
            vals[n]
        };
        for round in 0..200 {
            let mut o = V3::splat(Vec3A::ZERO);
            let mut d = V3::splat(Vec3A::ZERO);
            let mut t_max = splat(f32::INFINITY);
            for i in 0..LANES {
                o.set_lane(i, Vec3A::new(next(), next(), next() + 2.0));
                d.set_lane(i, Vec3A::new(next() * 0.1, next() * 0.1, -1.0));
                t_max[i] = [f32::INFINITY, 1.5, 2.0, 0.0][(round + i) % 4];
            }
            let (tw, hw) = wide::sphere(s, &o, &d, &t_max);
            let (tl, hl) = sphere(&o, &d, &t_max);
            assert_eq!(wide::flags(hw), hl, "hits from {o:?} along {d:?}");
            assert_eq!(tw.map(f32::to_bits), tl.map(f32::to_bits), "t from {o:?}");
            assert_eq!(wide::flags(wide::mask(&hl)), hl);
            assert_eq!(wide::any(hw), hl.contains(&true));
            let picked = wide::select(s, hw, &tw, &t_max);
            for i in 0..LANES {
                let want = if hl[i] { tl[i] } else { t_max[i] };
                assert_eq!(picked[i].to_bits(), want.to_bits(), "select lane {i}");
            }
            let ids = wide::select_u32(s, hw, &[7; LANES], &[u32::MAX; LANES]);
            assert_eq!(ids, hl.map(|h| if h { 7 } else { u32::MAX }));
        }
        // The spherical map over a sweep of the unit sphere and beyond it, octant by octant.
        for k in 0..4000_u32 {
            let mut p = V3::splat(Vec3A::ZERO);
            for i in 0..LANES {
                let j = (k * LANES as u32 + i as u32) as f32;
                let (a, b) = (j * 0.618_034, j * 0.001_3);
                p.set_lane(
                    i,
                    Vec3A::new(a.sin() * b.cos(), b.sin(), a.cos() * (1.0 + b)),
                );
            }
            let (wu, wv) = wide::spherical(s, &p);
            let (u, v) = spherical(&p);
            assert_eq!(wu.map(f32::to_bits), u.map(f32::to_bits), "u at {p:?}");
            assert_eq!(wv.map(f32::to_bits), v.map(f32::to_bits), "v at {p:?}");
        }
    }

    #[test]
    fn shape_lanes_match_the_scalar_on_grazing_inside_and_missing_rays() {
        let z = Vec3A::new(0.0, 0.0, -1.0);
        let rays = [
            (Vec3A::new(0.0, 0.0, 5.0), z),                           // head-on
            (Vec3A::new(1.0, 0.0, 5.0), z),                           // tangent at x = 1
            (Vec3A::new(0.999_999, 0.0, 5.0), z),                     // grazing
            (Vec3A::new(1.000_1, 0.0, 5.0), z),                       // just past
            (Vec3A::ZERO, Vec3A::X),                                  // from the centre
            (Vec3A::new(0.3, -0.2, 0.1), Vec3A::new(1.0, 2.0, -0.5)), // from inside
            (Vec3A::new(0.0, 0.0, 5.0), -z),                          // heading away
            (Vec3A::new(0.0, 0.0, 1.0), z),                           // starting on the surface
            (Vec3A::X, z), // on the surface and tangent: the double root at 0
            (Vec3A::new(0.0, 3.0, 0.0), Vec3A::new(0.0, -1.0, 0.0)),
            (Vec3A::new(0.5, 1.0, 0.5), Vec3A::new(0.0, 0.0, 1.0)), // parallel to y = 0
            (Vec3A::new(0.9, 2.0, 0.9), Vec3A::new(0.1, -1.0, 0.1)),
            (Vec3A::new(-3.0, 0.5, 0.2), Vec3A::new(1.0, -0.1, 0.0)),
            (Vec3A::new(0.3, 0.2, 1.0 + 1e4 / 1e6), z / 1e6), // a huge sphere, scaled
        ];
        for shape in [Shape::Sphere, Shape::Plane, Shape::Rectangle, Shape::Disk] {
            check_shape(&shape, &rays);
        }
    }
}
