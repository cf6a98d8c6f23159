//! What several mappings' lane formulas share: the rescaling that keeps squares finite and
//! the azimuth about the y axis.

use crate::math::lanes::{F, M, V3, finite, max, select};
use crate::math::{TAU, Vec3A};
use pulp::Simd;

/// `p` divided by its largest absolute coordinate per lane, so squares neither overflow (huge
/// points) nor underflow (subnormal ones), that coordinate, and whether it was positive and
/// finite (false for the origin and for NaN or infinite input).
#[inline(always)]
pub(super) fn rescaled<S: Simd>(s: S, p: &V3<S>) -> (V3<S>, F<S>, M<S>) {
    let scale = p.max_abs(s);
    let ok = s.and_m32s(
        s.greater_than_f32s(scale, s.splat_f32s(0.0)),
        finite(s, scale),
    );
    (p.div(s, scale), scale, ok)
}

/// The azimuth u = atan2(x, z) / 2 pi in [0, 1) per lane and, with `GRAD`, its gradient
/// (z, 0, -x) / (2 pi (x^2 + z^2)), zero exactly on the axis where u is undefined.
#[inline(always)]
pub(super) fn azimuth<S: Simd, const GRAD: bool>(s: S, x: F<S>, z: F<S>) -> (F<S>, V3<S>) {
    let zero = s.splat_f32s(0.0);
    let tau = s.splat_f32s(TAU);
    let a = crate::math::lanes::atan2(s, x, z);
    let phi = select(s, s.less_than_f32s(a, zero), s.add_f32s(a, tau), a);
    // u in [0, 1): u = 1 and u = 0 are one seam, read as u = 0 (the texture's first column).
    // phi + 2 pi can round up to exactly 2 pi; `+ 0` turns the -0 of atan2(-0, z) into 0.
    let u = s.div_f32s(phi, tau);
    let kept = s.add_f32s(max(s, u, zero), zero);
    let u = select(s, s.less_than_f32s(u, s.splat_f32s(1.0)), kept, zero);
    if !GRAD {
        return (u, V3::splat(s, Vec3A::ZERO));
    }
    let rho2 = s.add_f32s(s.mul_f32s(x, x), s.mul_f32s(z, z));
    let k = s.mul_f32s(tau, rho2);
    let g = V3 {
        x: z,
        y: zero,
        z: crate::math::lanes::neg(s, x),
    }
    .div(s, k);
    let on_axis = s.not_m32s(s.greater_than_f32s(rho2, zero));
    (u, V3::select(s, on_axis, &V3::splat(s, Vec3A::ZERO), &g))
}
