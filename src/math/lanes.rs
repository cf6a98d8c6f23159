//! Lane-generic arithmetic: the values of the one render kernel, written once over pulp's
//! [`Simd`] and run at every width it has. `S::f32s` holds `S::F32_LANES` rays' numbers: 16 on
//! AVX-512, 8 on AVX2, 4 on NEON, SSE2 and WebAssembly's simd128, and 1 under pulp's
//! [`pulp::Scalar`], where `S::f32s` is `f32` itself and every function here is plain scalar
//! code. The scalar path is therefore this code at width 1, not a twin of it.
//!
//! Every operation is one IEEE operation per lane, in the order written (Rust never fuses a
//! multiply and an add), comparisons are the ordered ones Rust's `<`, `<=`, `>` use (false on
//! NaN), and `min`, `max` are written as selects with `f32::min`'s and `f32::max`'s NaN rule
//! (the instructions' own rules differ between instruction sets). So a lane gives the same bits
//! whatever the width: renders are the same for `--simd scalar` and `--simd auto`.

// atan(t) / t - 1 = t^2 (C1 + t^2 (C2 + ...)) on [0, 1] (see `math::atan`).
use super::atan::C as ATAN_POLY;
use super::{Affine3A, Mat3A, Vec3A};
use pulp::Simd;

/// The widest register the kernels use (AVX-512's 16 f32 lanes): per-lane buffers are this
/// long, and a width-`S::F32_LANES` register fills their first lanes.
pub const MAX_LANES: usize = 16;

/// One f32 per lane.
pub type F<S> = <S as Simd>::f32s;
/// One flag per lane.
pub type M<S> = <S as Simd>::m32s;
/// One u32 per lane.
pub type U<S> = <S as Simd>::u32s;

/// Three coordinates per lane (points, directions, normals).
#[derive(Clone, Copy, Debug)]
pub struct V3<S: Simd> {
    /// x per lane.
    pub x: S::f32s,
    /// y per lane.
    pub y: S::f32s,
    /// z per lane.
    pub z: S::f32s,
}

/// A colour per lane (linear RGB).
pub type C3<S> = [F<S>; 3];

/// `x` in every lane.
#[must_use]
#[inline(always)]
pub fn splat<S: Simd>(s: S, x: f32) -> F<S> {
    s.splat_f32s(x)
}

/// The lanes of `v`, in the first `S::F32_LANES` places of a buffer.
#[must_use]
#[inline(always)]
pub fn to_array<S: Simd>(v: F<S>) -> [f32; MAX_LANES] {
    let mut a = [0.0; MAX_LANES];
    S::as_mut_simd_f32s(&mut a[..S::F32_LANES]).0[0] = v;
    a
}

/// A register from the first `S::F32_LANES` places of `a`.
#[must_use]
#[inline(always)]
pub fn from_array<S: Simd>(a: &[f32; MAX_LANES]) -> F<S> {
    S::as_simd_f32s(&a[..S::F32_LANES]).0[0]
}

/// The lanes of a u32 register.
#[must_use]
#[inline(always)]
pub fn to_array_u32<S: Simd>(v: U<S>) -> [u32; MAX_LANES] {
    let mut a = [0; MAX_LANES];
    S::as_mut_simd_u32s(&mut a[..S::U32_LANES]).0[0] = v;
    a
}

/// A u32 register from the first places of `a`.
#[must_use]
#[inline(always)]
pub fn from_array_u32<S: Simd>(a: &[u32; MAX_LANES]) -> U<S> {
    S::as_simd_u32s(&a[..S::U32_LANES]).0[0]
}

/// `[f(a[0]), f(a[1]), f(a[2])]`, always inlined. The kernel uses this, not `<[T; 3]>::map`:
/// `map` goes through `try_map`, which LLVM does not always inline into the kernel's one large
/// dispatched function, and out of line it calls the SIMD intrinsics its closure uses as
/// functions compiled without the instruction set (a splat became a call in the mesh's
/// triangle test; small scenes lost 5-10% as the kernel grew).
#[must_use]
#[inline(always)]
pub fn map3<T, R>(a: [T; 3], mut f: impl FnMut(T) -> R) -> [R; 3] {
    let [x, y, z] = a;
    [f(x), f(y), f(z)]
}

/// `[f(0), f(1), ..]` over the lanes, always inlined: the kernel's `std::array::from_fn` (which
/// goes through `try_from_fn`, see [`map3`]).
#[must_use]
#[inline(always)]
pub fn each_lane<T: Copy + Default>(mut f: impl FnMut(usize) -> T) -> [T; MAX_LANES] {
    let mut out = [T::default(); MAX_LANES];
    for (i, o) in out.iter_mut().enumerate() {
        *o = f(i);
    }
    out
}

/// The flags of a mask.
#[must_use]
#[inline(always)]
pub fn mask_to_array<S: Simd>(s: S, m: M<S>) -> [bool; MAX_LANES] {
    let bits = to_array_u32::<S>(s.select_u32s(m, s.splat_u32s(1), s.splat_u32s(0)));
    each_lane(|i| bits[i] != 0)
}

/// A mask from flags.
#[must_use]
#[inline(always)]
pub fn mask_from_array<S: Simd>(s: S, a: &[bool; MAX_LANES]) -> M<S> {
    let bits = from_array_u32::<S>(&each_lane(|i| u32::from(a[i])));
    s.equal_u32s(bits, s.splat_u32s(1))
}

/// Whether any lane of `m` is set.
#[must_use]
#[inline(always)]
pub fn any<S: Simd>(s: S, m: M<S>) -> bool {
    s.first_true_m32s(m) < S::F32_LANES
}

/// Whether every lane of `m` is set.
#[must_use]
#[inline(always)]
pub fn all<S: Simd>(s: S, m: M<S>) -> bool {
    !any(s, s.not_m32s(m))
}

/// A mask with every lane set or none.
#[must_use]
#[inline(always)]
pub fn mask_splat<S: Simd>(s: S, b: bool) -> M<S> {
    let z = s.splat_u32s(0);
    if b {
        s.equal_u32s(z, z)
    } else {
        s.not_m32s(s.equal_u32s(z, z))
    }
}

/// `if m { a } else { b }` per lane.
#[must_use]
#[inline(always)]
pub fn select<S: Simd>(s: S, m: M<S>, a: F<S>, b: F<S>) -> F<S> {
    s.select_f32s(m, a, b)
}

/// `x.is_finite()` per lane: |x| < inf (false on NaN).
#[must_use]
#[inline(always)]
pub fn finite<S: Simd>(s: S, x: F<S>) -> M<S> {
    s.less_than_f32s(s.abs_f32s(x), s.splat_f32s(f32::INFINITY))
}

/// `x.is_nan()` per lane.
#[must_use]
#[inline(always)]
pub fn nan<S: Simd>(s: S, x: F<S>) -> M<S> {
    s.not_m32s(s.equal_f32s(x, x))
}

/// `x.is_sign_negative()` per lane: the sign bit.
#[must_use]
#[inline(always)]
pub fn sign_negative<S: Simd>(s: S, x: F<S>) -> M<S> {
    s.less_than_i32s(s.transmute_i32s_f32s(x), s.splat_i32s(0))
}

/// `a.copysign(b)` per lane: `a`'s magnitude, `b`'s sign bit.
#[must_use]
#[inline(always)]
pub fn copysign<S: Simd>(s: S, a: F<S>, b: F<S>) -> F<S> {
    let sign = s.splat_u32s(0x8000_0000);
    let bits = s.or_u32s(
        s.and_u32s(s.transmute_u32s_f32s(a), s.not_u32s(sign)),
        s.and_u32s(s.transmute_u32s_f32s(b), sign),
    );
    s.transmute_f32s_u32s(bits)
}

/// `a.max(b)` per lane, with `f32::max`'s rule: a NaN operand gives the other.
#[must_use]
#[inline(always)]
pub fn max<S: Simd>(s: S, a: F<S>, b: F<S>) -> F<S> {
    s.select_f32s(s.or_m32s(s.greater_than_f32s(b, a), nan(s, a)), b, a)
}

/// `a.min(b)` per lane, with `f32::min`'s rule: a NaN operand gives the other.
#[must_use]
#[inline(always)]
pub fn min<S: Simd>(s: S, a: F<S>, b: F<S>) -> F<S> {
    s.select_f32s(s.or_m32s(s.less_than_f32s(b, a), nan(s, a)), b, a)
}

/// `a > b ? a : b` per lane: the SSE `maxps` rule (a NaN operand gives `b`).
#[must_use]
#[inline(always)]
pub fn sse_max<S: Simd>(s: S, a: F<S>, b: F<S>) -> F<S> {
    s.select_f32s(s.greater_than_f32s(a, b), a, b)
}

/// `x.clamp(lo, hi)` per lane, as `f32::clamp`: NaN stays NaN.
#[must_use]
#[inline(always)]
pub fn clamp<S: Simd>(s: S, x: F<S>, lo: f32, hi: f32) -> F<S> {
    let x = s.select_f32s(s.less_than_f32s(x, s.splat_f32s(lo)), s.splat_f32s(lo), x);
    s.select_f32s(
        s.greater_than_f32s(x, s.splat_f32s(hi)),
        s.splat_f32s(hi),
        x,
    )
}

/// `x * x` per lane.
#[must_use]
#[inline(always)]
pub fn sq<S: Simd>(s: S, x: F<S>) -> F<S> {
    s.mul_f32s(x, x)
}

/// `-x` per lane (the sign bit flipped, as Rust's `-`).
#[must_use]
#[inline(always)]
pub fn neg<S: Simd>(s: S, x: F<S>) -> F<S> {
    s.transmute_f32s_u32s(s.xor_u32s(s.transmute_u32s_f32s(x), s.splat_u32s(0x8000_0000)))
}

impl<S: Simd> V3<S> {
    /// `v` in every lane.
    #[must_use]
    #[inline(always)]
    pub fn splat(s: S, v: Vec3A) -> Self {
        Self {
            x: s.splat_f32s(v.x),
            y: s.splat_f32s(v.y),
            z: s.splat_f32s(v.z),
        }
    }

    /// The lanes of each coordinate, in per-lane buffers.
    #[must_use]
    #[inline(always)]
    pub fn to_arrays(&self) -> [[f32; MAX_LANES]; 3] {
        [
            to_array::<S>(self.x),
            to_array::<S>(self.y),
            to_array::<S>(self.z),
        ]
    }

    /// A vector from three per-lane buffers.
    #[must_use]
    #[inline(always)]
    pub fn from_arrays(a: &[[f32; MAX_LANES]; 3]) -> Self {
        Self {
            x: from_array::<S>(&a[0]),
            y: from_array::<S>(&a[1]),
            z: from_array::<S>(&a[2]),
        }
    }

    /// The dot product per lane, summed as glam's `dot`: (x + y) + z.
    #[must_use]
    #[inline(always)]
    pub fn dot(&self, s: S, o: &Self) -> F<S> {
        let xy = s.add_f32s(s.mul_f32s(self.x, o.x), s.mul_f32s(self.y, o.y));
        s.add_f32s(xy, s.mul_f32s(self.z, o.z))
    }

    /// The cross product per lane, as glam's.
    #[must_use]
    #[inline(always)]
    pub fn cross(&self, s: S, o: &Self) -> Self {
        Self {
            x: s.sub_f32s(s.mul_f32s(self.y, o.z), s.mul_f32s(o.y, self.z)),
            y: s.sub_f32s(s.mul_f32s(self.z, o.x), s.mul_f32s(o.z, self.x)),
            z: s.sub_f32s(s.mul_f32s(self.x, o.y), s.mul_f32s(o.x, self.y)),
        }
    }

    /// `self + o` per lane.
    #[must_use]
    #[inline(always)]
    pub fn add(&self, s: S, o: &Self) -> Self {
        Self {
            x: s.add_f32s(self.x, o.x),
            y: s.add_f32s(self.y, o.y),
            z: s.add_f32s(self.z, o.z),
        }
    }

    /// `self - o` per lane.
    #[must_use]
    #[inline(always)]
    pub fn sub(&self, s: S, o: &Self) -> Self {
        Self {
            x: s.sub_f32s(self.x, o.x),
            y: s.sub_f32s(self.y, o.y),
            z: s.sub_f32s(self.z, o.z),
        }
    }

    /// `self * k` per lane.
    #[must_use]
    #[inline(always)]
    pub fn scale(&self, s: S, k: F<S>) -> Self {
        Self {
            x: s.mul_f32s(self.x, k),
            y: s.mul_f32s(self.y, k),
            z: s.mul_f32s(self.z, k),
        }
    }

    /// `self / k` per lane.
    #[must_use]
    #[inline(always)]
    pub fn div(&self, s: S, k: F<S>) -> Self {
        Self {
            x: s.div_f32s(self.x, k),
            y: s.div_f32s(self.y, k),
            z: s.div_f32s(self.z, k),
        }
    }

    /// `-self` per lane.
    #[must_use]
    #[inline(always)]
    pub fn neg(&self, s: S) -> Self {
        Self {
            x: neg(s, self.x),
            y: neg(s, self.y),
            z: neg(s, self.z),
        }
    }

    /// `self + t d` per lane (`Ray::at`).
    #[must_use]
    #[inline(always)]
    pub fn at(&self, s: S, t: F<S>, d: &Self) -> Self {
        Self {
            x: s.add_f32s(self.x, s.mul_f32s(t, d.x)),
            y: s.add_f32s(self.y, s.mul_f32s(t, d.y)),
            z: s.add_f32s(self.z, s.mul_f32s(t, d.z)),
        }
    }

    /// `if m { a } else { b }` per lane.
    #[must_use]
    #[inline(always)]
    pub fn select(s: S, m: M<S>, a: &Self, b: &Self) -> Self {
        Self {
            x: s.select_f32s(m, a.x, b.x),
            y: s.select_f32s(m, a.y, b.y),
            z: s.select_f32s(m, a.z, b.z),
        }
    }

    /// Unit length per lane, or `fallback` where the length is zero or not finite (glam's
    /// `normalize_or`: multiplied by 1 / length).
    #[must_use]
    #[inline(always)]
    pub fn normalize_or(&self, s: S, fallback: Vec3A) -> Self {
        self.normalize_or_lanes(s, &Self::splat(s, fallback))
    }

    /// [`V3::normalize_or`] with a fallback of its own in each lane.
    #[must_use]
    #[inline(always)]
    pub fn normalize_or_lanes(&self, s: S, fallback: &Self) -> Self {
        let rcp = s.div_f32s(s.splat_f32s(1.0), s.sqrt_f32s(self.dot(s, self)));
        let ok = s.and_m32s(finite(s, rcp), s.greater_than_f32s(rcp, s.splat_f32s(0.0)));
        Self::select(s, ok, &self.scale(s, rcp), fallback)
    }

    /// The largest absolute coordinate per lane, as `math::max_abs` (glam's `max_element`)
    /// takes it: max(max(|x|, |z|), max(|y|, |z|)), each max `a > b ? a : b` (the SSE
    /// instruction's rule, so a NaN coordinate gives what the scalar code always gave).
    #[must_use]
    #[inline(always)]
    pub fn max_abs(&self, s: S) -> F<S> {
        let (x, y, z) = (s.abs_f32s(self.x), s.abs_f32s(self.y), s.abs_f32s(self.z));
        sse_max(s, sse_max(s, x, z), sse_max(s, y, z))
    }

    /// Whether every coordinate is finite, per lane.
    #[must_use]
    #[inline(always)]
    pub fn finite(&self, s: S) -> M<S> {
        s.and_m32s(
            s.and_m32s(finite(s, self.x), finite(s, self.y)),
            finite(s, self.z),
        )
    }

    /// The linear part `m` applied per lane, summed as glam's `Mat3A * Vec3A`:
    /// (c0 x + c1 y) + c2 z.
    #[must_use]
    #[inline(always)]
    pub fn linear(&self, s: S, m: &Mat3A) -> Self {
        let (c0, c1, c2) = (m.x_axis, m.y_axis, m.z_axis);
        Self {
            x: self.row(s, c0.x, c1.x, c2.x),
            y: self.row(s, c0.y, c1.y, c2.y),
            z: self.row(s, c0.z, c1.z, c2.z),
        }
    }

    /// (a x + b y) + c z per lane: one row of a matrix product, as glam sums it.
    #[inline(always)]
    fn row(&self, s: S, a: f32, b: f32, c: f32) -> F<S> {
        let xy = s.add_f32s(
            s.mul_f32s(s.splat_f32s(a), self.x),
            s.mul_f32s(s.splat_f32s(b), self.y),
        );
        s.add_f32s(xy, s.mul_f32s(s.splat_f32s(c), self.z))
    }

    /// `m` applied to points per lane (`Affine3A::transform_point3a`).
    #[must_use]
    #[inline(always)]
    pub fn point(&self, s: S, m: &Affine3A) -> Self {
        self.linear(s, &m.matrix3)
            .add(s, &Self::splat(s, m.translation))
    }
}

impl V3<pulp::Scalar> {
    /// A glam vector as the width-1 lane type.
    #[must_use]
    #[inline(always)]
    pub fn one(v: Vec3A) -> Self {
        Self {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }

    /// Back to a glam vector.
    #[must_use]
    #[inline(always)]
    pub fn vec(self) -> Vec3A {
        Vec3A::new(self.x, self.y, self.z)
    }
}

/// `y.atan2(x)` per lane, within 3e-7 rad of the exact value (`math::atan`): t = min / max of
/// |y|, |x| in [0, 1], a degree-17 odd polynomial there, the octant unfolded by selects. Lanes
/// where the reduction is 0 / 0, inf / inf or NaN take libm's `atan2`, which defines those
/// cases with care.
#[must_use]
#[inline(always)]
pub fn atan2<S: Simd>(s: S, y: F<S>, x: F<S>) -> F<S> {
    let (ax, ay) = (s.abs_f32s(x), s.abs_f32s(y));
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
    a = s.select_f32s(
        swap,
        s.sub_f32s(s.splat_f32s(std::f32::consts::FRAC_PI_2), a),
        a,
    );
    a = s.select_f32s(
        sign_negative(s, x),
        s.sub_f32s(s.splat_f32s(std::f32::consts::PI), a),
        a,
    );
    let r = copysign(s, a, y);
    let odd = nan(s, t);
    if !any(s, odd) {
        return r;
    }
    let (ys, xs, mut rs, odd) = (
        to_array::<S>(y),
        to_array::<S>(x),
        to_array::<S>(r),
        mask_to_array(s, odd),
    );
    for i in 0..S::F32_LANES {
        if odd[i] {
            rs[i] = ys[i].atan2(xs[i]);
        }
    }
    from_array::<S>(&rs)
}

#[cfg(test)]
pub(crate) mod testing;
#[cfg(test)]
mod tests;
