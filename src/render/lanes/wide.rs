//! The explicit kernels, generic over pulp's [`Simd`]: each walks the packet in chunks of
//! `S::F32_LANES` lanes (16 on AVX-512, 8 on AVX2, 4 on NEON and SSE, 1 for pulp's `Scalar`),
//! and any lanes a chunk does not fill run the same code through pulp's `Scalar`, one lane at a
//! time. They are here where LLVM's vectoriser left the lane loops of `lanes` narrow or branchy.
//!
//! Each is its loop twin operation for operation: the same separate multiplies and adds (no
//! fused multiply-add), the ordered comparisons Rust's `<`, `<=`, `>` use (false on NaN) and
//! selects for the `if`s, so every lane is bit for bit what the loop (and the scalar path)
//! gives, whatever the width.

use super::{F, LANES, M, V3};
use crate::math::{ATAN_POLY, PI, TAU};
use pulp::Simd;
use std::f32::consts::FRAC_PI_2;

/// A lane mask: all ones where set, zero elsewhere.
pub type W = [u32; LANES];

/// The AVX2 token, where the CPU has AVX2 and FMA (for the tests).
#[cfg(all(test, target_arch = "x86_64"))]
#[must_use]
pub fn token() -> Option<pulp::x86::V3> {
    pulp::x86::V3::try_new()
}

/// One chunk of a kernel: the lanes from `at`, as many as `S` holds.
trait Chunk {
    fn at<S: Simd>(&mut self, s: S, at: usize);
}

/// Runs `k` over the packet: whole registers of `S`, then any lanes left over one at a time
/// (pulp's `Scalar`: the same code, one lane wide).
#[inline(always)]
fn each<S: Simd, K: Chunk>(s: S, k: &mut K) {
    let w = S::F32_LANES;
    let full = LANES / w * w;
    let mut at = 0;
    while at < full {
        k.at(s, at);
        at += w;
    }
    for at in full..LANES {
        k.at(pulp::Scalar, at);
    }
}

/// The `S`-wide register of `a`'s lanes from `at`.
#[inline(always)]
fn ld<S: Simd>(a: &F, at: usize) -> S::f32s {
    S::as_simd_f32s(&a[at..at + S::F32_LANES]).0[0]
}

/// Stores `v` into `a`'s lanes from `at`.
#[inline(always)]
fn st<S: Simd>(a: &mut F, at: usize, v: S::f32s) {
    S::as_mut_simd_f32s(&mut a[at..at + S::F32_LANES]).0[0] = v;
}

/// `ld` for u32 lanes.
#[inline(always)]
fn ld_u32<S: Simd>(a: &[u32; LANES], at: usize) -> S::u32s {
    S::as_simd_u32s(&a[at..at + S::U32_LANES]).0[0]
}

/// `st` for u32 lanes.
#[inline(always)]
fn st_u32<S: Simd>(a: &mut [u32; LANES], at: usize, v: S::u32s) {
    S::as_mut_simd_u32s(&mut a[at..at + S::U32_LANES]).0[0] = v;
}

/// The mask `m`'s lanes from `at` as `S`'s mask (the sign bit: all ones or zero).
#[inline(always)]
fn ld_mask<S: Simd>(s: S, m: &W, at: usize) -> S::m32s {
    s.less_than_i32s(s.transmute_i32s_u32s(ld_u32::<S>(m, at)), s.splat_i32s(0))
}

/// Stores `S`'s mask `v` into `m`'s lanes from `at`.
#[inline(always)]
fn st_mask<S: Simd>(s: S, m: &mut W, at: usize, v: S::m32s) {
    let bits = s.select_u32s(v, s.splat_u32s(u32::MAX), s.splat_u32s(0));
    st_u32::<S>(m, at, bits);
}

/// (a . b) per lane, summed (x + y) + z as [`V3::dot`].
#[inline(always)]
fn dot<S: Simd>(s: S, a: [S::f32s; 3], b: [S::f32s; 3]) -> S::f32s {
    let xy = s.add_f32s(s.mul_f32s(a[0], b[0]), s.mul_f32s(a[1], b[1]));
    s.add_f32s(xy, s.mul_f32s(a[2], b[2]))
}

/// The three coordinates' registers from `at`.
#[inline(always)]
fn ld3<S: Simd>(v: &V3, at: usize) -> [S::f32s; 3] {
    [ld::<S>(&v.x, at), ld::<S>(&v.y, at), ld::<S>(&v.z, at)]
}

/// Whether any lane of `m` is set.
#[must_use]
#[inline(always)]
pub fn any(m: W) -> bool {
    m.iter().fold(0, |a, b| a | b) != 0
}

/// `m` as flags.
#[cfg(test)]
#[must_use]
#[inline(always)]
pub fn flags(m: W) -> M {
    m.map(|x| x != 0)
}

/// Flags as a mask.
#[must_use]
#[inline(always)]
pub fn mask(m: &M) -> W {
    m.map(|b| if b { u32::MAX } else { 0 })
}

struct Sphere<'a> {
    o: &'a V3,
    d: &'a V3,
    t_max: &'a F,
    t: F,
    hit: W,
}

impl Chunk for Sphere<'_> {
    #[inline(always)]
    fn at<S: Simd>(&mut self, s: S, at: usize) {
        let (o, d) = (ld3::<S>(self.o, at), ld3::<S>(self.d, at));
        let oo = dot(s, o, o);
        let half_b = dot(s, o, d);
        let a = dot(s, d, d);
        // V3::cross: (oy dz - dy oz, oz dx - dz ox, ox dy - dx oy).
        let perp = [
            s.sub_f32s(s.mul_f32s(o[1], d[2]), s.mul_f32s(d[1], o[2])),
            s.sub_f32s(s.mul_f32s(o[2], d[0]), s.mul_f32s(d[2], o[0])),
            s.sub_f32s(s.mul_f32s(o[0], d[1]), s.mul_f32s(d[0], o[1])),
        ];
        let perp2a = dot(s, perp, perp);
        let zero = s.splat_f32s(0.0);
        let c = s.sub_f32s(oo, s.splat_f32s(1.0));
        let away = s.and_m32s(
            s.greater_than_f32s(c, zero),
            s.greater_than_or_equal_f32s(half_b, zero),
        );
        let disc = s.sub_f32s(a, perp2a);
        let real = s.not_m32s(s.or_m32s(
            s.less_than_f32s(disc, zero),
            s.less_than_or_equal_f32s(a, zero),
        ));
        let root = s.sqrt_f32s(disc);
        let nb = s.neg_f32s(half_b);
        let q = s.select_f32s(
            s.greater_than_f32s(half_b, zero),
            s.sub_f32s(nb, root),
            s.add_f32s(nb, root),
        );
        let (r0, r1) = (s.div_f32s(c, q), s.div_f32s(q, a));
        let lt = s.less_than_f32s(r0, r1);
        let (t0, t1) = (s.select_f32s(lt, r0, r1), s.select_f32s(lt, r1, r0));
        let t = s.select_f32s(s.greater_than_f32s(t0, zero), t0, t1);
        let t_max = ld::<S>(self.t_max, at);
        let hit = s.and_m32s(
            s.and_m32s(s.not_m32s(away), real),
            s.and_m32s(s.greater_than_f32s(t, zero), s.less_than_f32s(t, t_max)),
        );
        st::<S>(&mut self.t, at, t);
        st_mask(s, &mut self.hit, at, hit);
    }
}

/// [`super::sphere`] `S` wide: t per lane and the hit mask.
#[must_use]
#[inline(always)]
pub fn sphere<S: Simd>(s: S, o: &V3, d: &V3, t_max: &F) -> (F, W) {
    let mut k = Sphere {
        o,
        d,
        t_max,
        t: [0.0; LANES],
        hit: [0; LANES],
    };
    each(s, &mut k);
    (k.t, k.hit)
}

/// `x.is_sign_negative()` per lane: the sign bit.
#[inline(always)]
fn sign_negative<S: Simd>(s: S, x: S::f32s) -> S::m32s {
    s.less_than_i32s(s.transmute_i32s_f32s(x), s.splat_i32s(0))
}

/// `x.is_finite()` per lane: |x| < inf (false on NaN).
#[inline(always)]
fn finite<S: Simd>(s: S, x: S::f32s) -> S::m32s {
    s.less_than_f32s(s.abs_f32s(x), s.splat_f32s(f32::INFINITY))
}

struct Atan2<'a> {
    y: &'a F,
    x: &'a F,
    r: F,
    /// The reduced argument, NaN where libm decides.
    t: F,
}

impl Chunk for Atan2<'_> {
    #[inline(always)]
    fn at<S: Simd>(&mut self, s: S, at: usize) {
        let (yv, xv) = (ld::<S>(self.y, at), ld::<S>(self.x, at));
        let (ax, ay) = (s.abs_f32s(xv), s.abs_f32s(yv));
        let swap = s.greater_than_f32s(ay, ax);
        let num = s.select_f32s(swap, ax, ay);
        let den = s.select_f32s(swap, ay, ax);
        let t = s.div_f32s(num, den);
        let sq = s.mul_f32s(t, t);
        let mut p = s.splat_f32s(ATAN_POLY[7]);
        for k in (0..7).rev() {
            p = s.add_f32s(s.mul_f32s(p, sq), s.splat_f32s(ATAN_POLY[k]));
        }
        // t + t s p, multiplied left to right.
        let mut a = s.add_f32s(t, s.mul_f32s(s.mul_f32s(t, sq), p));
        a = s.select_f32s(swap, s.sub_f32s(s.splat_f32s(FRAC_PI_2), a), a);
        a = s.select_f32s(sign_negative(s, xv), s.sub_f32s(s.splat_f32s(PI), a), a);
        // copysign(a, y): a's magnitude, y's sign bit.
        let sign = s.splat_u32s(0x8000_0000);
        let bits = s.or_u32s(
            s.and_u32s(s.transmute_u32s_f32s(a), s.not_u32s(sign)),
            s.and_u32s(s.transmute_u32s_f32s(yv), sign),
        );
        st::<S>(&mut self.r, at, s.transmute_f32s_u32s(bits));
        st::<S>(&mut self.t, at, t);
    }
}

/// [`super::atan2`] `S` wide: the same polynomial, unfolding and libm fallback lanes.
#[must_use]
#[inline(always)]
pub fn atan2<S: Simd>(s: S, y: &F, x: &F) -> F {
    let mut k = Atan2 {
        y,
        x,
        r: [0.0; LANES],
        t: [0.0; LANES],
    };
    each(s, &mut k);
    if k.t.iter().any(|t| t.is_nan()) {
        for i in 0..LANES {
            if k.t[i].is_nan() {
                k.r[i] = y[i].atan2(x[i]);
            }
        }
    }
    k.r
}

/// sqrt(x^2 + z^2) per lane.
struct Rho<'a> {
    q: &'a V3,
    rho: F,
}

impl Chunk for Rho<'_> {
    #[inline(always)]
    fn at<S: Simd>(&mut self, s: S, at: usize) {
        let (qx, qz) = (ld::<S>(&self.q.x, at), ld::<S>(&self.q.z, at));
        let r = s.sqrt_f32s(s.add_f32s(s.mul_f32s(qx, qx), s.mul_f32s(qz, qz)));
        st::<S>(&mut self.rho, at, r);
    }
}

/// The spherical map's last steps from the azimuth's atan2 `a`, the polar angle `theta` and
/// the rescaling's `ok`.
struct SphericalUv<'a> {
    a: &'a F,
    theta: &'a F,
    ok: &'a W,
    u: F,
    v: F,
}

impl Chunk for SphericalUv<'_> {
    #[inline(always)]
    fn at<S: Simd>(&mut self, s: S, at: usize) {
        let (zero, one, half) = (s.splat_f32s(0.0), s.splat_f32s(1.0), s.splat_f32s(0.5));
        // [`super::azimuth`]'s wrap into [0, 1).
        let a = ld::<S>(self.a, at);
        let tau = s.splat_f32s(TAU);
        let phi = s.select_f32s(s.less_than_f32s(a, zero), s.add_f32s(a, tau), a);
        let u = s.div_f32s(phi, tau);
        // Below 1 the lane is not NaN, where `max` and the instructions agree (+ 0 clears -0).
        let kept = s.add_f32s(s.max_f32s(u, zero), zero);
        let u = s.select_f32s(s.less_than_f32s(u, one), kept, zero);
        // (1 - theta / pi).clamp(0, 1): NaN stays NaN.
        let theta = ld::<S>(self.theta, at);
        let w = s.sub_f32s(one, s.div_f32s(theta, s.splat_f32s(PI)));
        let w = s.select_f32s(s.less_than_f32s(w, zero), zero, w);
        let w = s.select_f32s(s.greater_than_f32s(w, one), one, w);
        let ok = ld_mask(s, self.ok, at);
        let u = s.select_f32s(ok, u, zero);
        let w = s.select_f32s(ok, w, half);
        // finite_or_centre.
        let fine = s.and_m32s(finite(s, u), finite(s, w));
        st::<S>(&mut self.u, at, s.select_f32s(fine, u, half));
        st::<S>(&mut self.v, at, s.select_f32s(fine, w, half));
    }
}

/// [`super::spherical`] `S` wide (the rescaling stays the loop: `f32::max`'s NaN rule).
#[must_use]
#[inline(always)]
pub fn spherical<S: Simd>(s: S, p: &V3) -> (F, F) {
    let (q, ok) = super::rescaled(p);
    let ok = mask(&ok);
    let a = atan2(s, &q.x, &q.z);
    let mut rho = Rho {
        q: &q,
        rho: [0.0; LANES],
    };
    each(s, &mut rho);
    let theta = atan2(s, &rho.rho, &q.y);
    let mut k = SphericalUv {
        a: &a,
        theta: &theta,
        ok: &ok,
        u: [0.0; LANES],
        v: [0.0; LANES],
    };
    each(s, &mut k);
    (k.u, k.v)
}

struct AddLight<'a> {
    reach: W,
    has_spec: W,
    pw: &'a F,
    diffuse: &'a [F; 3],
    spec: &'a [F; 3],
    li: [f32; 3],
    ndotwi: &'a F,
    l: &'a mut [F; 3],
    lit: &'a mut F,
}

impl Chunk for AddLight<'_> {
    #[inline(always)]
    fn at<S: Simd>(&mut self, s: S, at: usize) {
        let reach = ld_mask(s, &self.reach, at);
        let pw = ld::<S>(self.pw, at);
        let on = s.and_m32s(
            ld_mask(s, &self.has_spec, at),
            s.not_m32s(s.equal_f32s(pw, s.splat_f32s(0.0))),
        );
        let n = ld::<S>(self.ndotwi, at);
        for c in 0..3 {
            let d = ld::<S>(&self.diffuse[c], at);
            let sc = ld::<S>(&self.spec[c], at);
            let f = s.select_f32s(on, s.add_f32s(d, s.mul_f32s(sc, pw)), d);
            let add = s.mul_f32s(s.mul_f32s(f, s.splat_f32s(self.li[c])), n);
            let lc = ld::<S>(&self.l[c], at);
            st::<S>(
                &mut self.l[c],
                at,
                s.select_f32s(reach, s.add_f32s(lc, add), lc),
            );
        }
        let lt = ld::<S>(self.lit, at);
        st::<S>(self.lit, at, s.select_f32s(reach, s.add_f32s(lt, n), lt));
    }
}

/// One light's term added to the radiance `l` and the cosine sum `lit` where `reach`
/// (`PacketPlan::trace`'s light loop): `f = diffuse + spec pw` where the highlight is on,
/// else `diffuse`; `l += f li (n . wi)`; `lit += n . wi`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn add_light<S: Simd>(
    s: S,
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
    let mut k = AddLight {
        reach: mask(reach),
        has_spec: mask(has_spec),
        pw,
        diffuse,
        spec,
        li,
        ndotwi,
        l,
        lit,
    };
    each(s, &mut k);
}

/// `if m { a } else { b }` per lane into `out`, for f32 or u32 lanes.
struct Select<'a, T> {
    m: &'a W,
    a: &'a [T; LANES],
    b: &'a [T; LANES],
    out: [T; LANES],
}

impl Chunk for Select<'_, f32> {
    #[inline(always)]
    fn at<S: Simd>(&mut self, s: S, at: usize) {
        let m = ld_mask(s, self.m, at);
        let v = s.select_f32s(m, ld::<S>(self.a, at), ld::<S>(self.b, at));
        st::<S>(&mut self.out, at, v);
    }
}

impl Chunk for Select<'_, u32> {
    #[inline(always)]
    fn at<S: Simd>(&mut self, s: S, at: usize) {
        let m = ld_mask(s, self.m, at);
        let v = s.select_u32s(m, ld_u32::<S>(self.a, at), ld_u32::<S>(self.b, at));
        st_u32::<S>(&mut self.out, at, v);
    }
}

/// `if m { a } else { b }` per lane.
#[must_use]
#[inline(always)]
pub fn select<S: Simd>(s: S, m: W, a: &F, b: &F) -> F {
    let mut k = Select {
        m: &m,
        a,
        b,
        out: [0.0; LANES],
    };
    each(s, &mut k);
    k.out
}

/// `if m { a } else { b }` per lane, for u32 lanes.
#[must_use]
#[inline(always)]
pub fn select_u32<S: Simd>(s: S, m: W, a: &[u32; LANES], b: &[u32; LANES]) -> [u32; LANES] {
    let mut k = Select {
        m: &m,
        a,
        b,
        out: [0; LANES],
    };
    each(s, &mut k);
    k.out
}

/// `if m { a } else { b }` per lane, for points.
#[must_use]
#[inline(always)]
pub fn select_v3<S: Simd>(s: S, m: W, a: &V3, b: &V3) -> V3 {
    V3 {
        x: select(s, m, &a.x, &b.x),
        y: select(s, m, &a.y, &b.y),
        z: select(s, m, &a.z, &b.z),
    }
}

#[cfg(test)]
mod tests;
