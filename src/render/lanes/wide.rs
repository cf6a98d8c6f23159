//! The explicit 8-wide kernels: AVX2 `ymm` operations through pulp's safe `x86::V3` token
//! (present on AVX2 and AVX-512 CPUs), where LLVM's vectoriser left the lane loops of `lanes` narrow.
//! Each is its loop twin operation for operation: the same separate multiplies and adds (no
//! fused multiply-add), the ordered comparisons Rust's `<`, `<=`, `>` use (false on NaN) and
//! `blendv` selects for the `if`s, so every lane is bit for bit what the loop (and the scalar
//! path) gives.

use super::{F, LANES, M, V3};
use crate::math::{ATAN_POLY, PI, TAU};
use pulp::bytemuck::cast;
use pulp::x86::V3 as Avx2;
use pulp::{Simd, f32x8, m32x8};
use std::f32::consts::FRAC_PI_2;

/// A lane mask: all ones where set.
pub type W = m32x8;

/// The token, where the CPU has AVX2 and FMA (checked once per pass).
#[must_use]
pub fn token() -> Option<Avx2> {
    Avx2::try_new()
}

#[inline(always)]
fn v(a: &F) -> f32x8 {
    cast(*a)
}

/// (a . b) per lane, summed (x + y) + z as [`V3::dot`].
#[inline(always)]
fn dot(s: Avx2, a: [f32x8; 3], b: [f32x8; 3]) -> f32x8 {
    let xy = s.add_f32s(s.mul_f32s(a[0], b[0]), s.mul_f32s(a[1], b[1]));
    s.add_f32s(xy, s.mul_f32s(a[2], b[2]))
}

/// Whether any lane of `m` is set.
#[must_use]
#[inline(always)]
pub fn any(m: W) -> bool {
    let u: [u32; LANES] = cast(m);
    u.iter().fold(0, |a, b| a | b) != 0
}

/// `m` as flags.
#[cfg(test)]
#[must_use]
#[inline(always)]
pub fn flags(m: W) -> M {
    let u: [u32; LANES] = cast(m);
    u.map(|x| x != 0)
}

/// Flags as a mask.
#[must_use]
#[inline(always)]
pub fn mask(m: &M) -> W {
    cast(m.map(|b| if b { u32::MAX } else { 0 }))
}

/// [`super::sphere`] 8 wide: t per lane and the hit mask.
#[must_use]
#[inline(always)]
pub fn sphere(s: Avx2, o: &V3, d: &V3, t_max: &F) -> (F, W) {
    let o = [v(&o.x), v(&o.y), v(&o.z)];
    let d = [v(&d.x), v(&d.y), v(&d.z)];
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
    let hit = s.and_m32s(
        s.and_m32s(s.not_m32s(away), real),
        s.and_m32s(s.greater_than_f32s(t, zero), s.less_than_f32s(t, v(t_max))),
    );
    (cast(t), hit)
}

/// `x.is_sign_negative()` per lane: the sign bit.
#[inline(always)]
fn sign_negative(s: Avx2, x: f32x8) -> W {
    s.less_than_i32s(cast(x), s.splat_i32s(0))
}

/// `x.is_finite()` per lane: |x| < inf (false on NaN).
#[inline(always)]
fn finite(s: Avx2, x: f32x8) -> W {
    s.less_than_f32s(s.abs_f32s(x), s.splat_f32s(f32::INFINITY))
}

/// [`super::atan2`] 8 wide: the same polynomial, unfolding and libm fallback lanes.
#[must_use]
#[inline(always)]
pub fn atan2(s: Avx2, y: &F, x: &F) -> F {
    let (yv, xv) = (v(y), v(x));
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
        s.and_u32s(cast(a), s.not_u32s(sign)),
        s.and_u32s(cast(yv), sign),
    );
    let mut r: F = cast(bits);
    let nan = s.not_m32s(s.equal_f32s(t, t));
    if any(nan) {
        let ts: F = cast(t);
        for i in 0..LANES {
            if ts[i].is_nan() {
                r[i] = y[i].atan2(x[i]);
            }
        }
    }
    r
}

/// [`super::azimuth`] 8 wide.
#[inline(always)]
fn azimuth(s: Avx2, x: &F, z: &F) -> f32x8 {
    let a = v(&atan2(s, x, z));
    let zero = s.splat_f32s(0.0);
    let tau = s.splat_f32s(TAU);
    let phi = s.select_f32s(s.less_than_f32s(a, zero), s.add_f32s(a, tau), a);
    let u = s.div_f32s(phi, tau);
    // Below 1 the lane is not NaN, where `max` and `maxps` agree (and + 0 clears -0).
    let kept = s.add_f32s(s.max_f32s(u, zero), zero);
    s.select_f32s(s.less_than_f32s(u, s.splat_f32s(1.0)), kept, zero)
}

/// [`super::spherical`] 8 wide (the rescaling stays the loop: `f32::max`'s NaN rule).
#[must_use]
#[inline(always)]
pub fn spherical(s: Avx2, p: &V3) -> (F, F) {
    let (q, ok) = super::rescaled(p);
    let ok = mask(&ok);
    let u = azimuth(s, &q.x, &q.z);
    let (qx, qz) = (v(&q.x), v(&q.z));
    let rho: F = cast(s.sqrt_f32s(s.add_f32s(s.mul_f32s(qx, qx), s.mul_f32s(qz, qz))));
    let theta = v(&atan2(s, &rho, &q.y));
    let (zero, one) = (s.splat_f32s(0.0), s.splat_f32s(1.0));
    // (1 - theta / pi).clamp(0, 1): NaN stays NaN.
    let w = s.sub_f32s(one, s.div_f32s(theta, s.splat_f32s(PI)));
    let w = s.select_f32s(s.less_than_f32s(w, zero), zero, w);
    let w = s.select_f32s(s.greater_than_f32s(w, one), one, w);
    let u = s.select_f32s(ok, u, zero);
    let w = s.select_f32s(ok, w, s.splat_f32s(0.5));
    // finite_or_centre.
    let fine = s.and_m32s(finite(s, u), finite(s, w));
    let half = s.splat_f32s(0.5);
    (
        cast(s.select_f32s(fine, u, half)),
        cast(s.select_f32s(fine, w, half)),
    )
}

/// One light's term added to the radiance `l` and the cosine sum `lit` where `reach`
/// (`PacketPlan::trace`'s light loop): `f = diffuse + spec pw` where the highlight is on,
/// else `diffuse`; `l += f li (n . wi)`; `lit += n . wi`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn add_light(
    s: Avx2,
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
    let reach = mask(reach);
    let pw = v(pw);
    let on = s.and_m32s(
        mask(has_spec),
        s.not_m32s(s.equal_f32s(pw, s.splat_f32s(0.0))),
    );
    let n = v(ndotwi);
    for c in 0..3 {
        let d = v(&diffuse[c]);
        let f = s.select_f32s(on, s.add_f32s(d, s.mul_f32s(v(&spec[c]), pw)), d);
        let add = s.mul_f32s(s.mul_f32s(f, s.splat_f32s(li[c])), n);
        let lc = v(&l[c]);
        l[c] = cast(s.select_f32s(reach, s.add_f32s(lc, add), lc));
    }
    let lt = v(lit);
    *lit = cast(s.select_f32s(reach, s.add_f32s(lt, n), lt));
}

/// `if m { a } else { b }` per lane.
#[must_use]
#[inline(always)]
pub fn select(s: Avx2, m: W, a: &F, b: &F) -> F {
    cast(s.select_f32s(m, v(a), v(b)))
}

/// `if m { a } else { b }` per lane, for u32 lanes.
#[must_use]
#[inline(always)]
pub fn select_u32(s: Avx2, m: W, a: &[u32; LANES], b: &[u32; LANES]) -> [u32; LANES] {
    cast(s.select_u32s(m, cast(*a), cast(*b)))
}

/// `if m { a } else { b }` per lane, for points.
#[must_use]
#[inline(always)]
pub fn select_v3(s: Avx2, m: W, a: &V3, b: &V3) -> V3 {
    V3 {
        x: select(s, m, &a.x, &b.x),
        y: select(s, m, &a.y, &b.y),
        z: select(s, m, &a.z, &b.z),
    }
}
