//! For tests: running a check at every width pulp can run here, and hard lane values.
//!
//! The widths: pulp's `Scalar` (1 lane: the scalar path), AVX2's 4-lane `V3_128b` (the width of
//! NEON, SSE and WebAssembly's simd128), 8-lane `V3`, 16-lane `V3_512b` (two registers) and
//! AVX-512's `V4` (16 lanes) where the CPU has them; NEON on aarch64.

use super::{F, MAX_LANES, V3, from_array, to_array};
use crate::math::Vec3A;
use pulp::{Simd, WithSimd};

/// A check that runs at one width.
pub(crate) trait WidthCheck {
    /// Runs the check with `s`, named `name` in failures.
    fn check<S: Simd>(&mut self, s: S, name: &'static str);
}

struct Run<'a, C>(&'a mut C, &'static str);

impl<C: WidthCheck> WithSimd for Run<'_, C> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, s: S) {
        self.0.check(s, self.1);
    }
}

/// Runs `c` at every width this machine has, each through its `#[target_feature]` entry as
/// the renderer runs it. Returns how many widths ran.
pub(crate) fn at_every_width(c: &mut impl WidthCheck) -> usize {
    let mut n = 0;
    Simd::vectorize(pulp::Scalar, Run(c, "Scalar (1 lane)"));
    n += 1;
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    {
        use pulp::x86::{V3 as Avx2, V3_128b, V3_512b, V4};
        if let Some(v3) = Avx2::try_new() {
            Simd::vectorize(
                V3_128b(v3),
                Run(c, "AVX2 at 4 lanes (the NEON, SSE and simd128 width)"),
            );
            Simd::vectorize(v3, Run(c, "AVX2 (8 lanes)"));
            Simd::vectorize(V3_512b(v3), Run(c, "AVX2 as 16 lanes (two registers)"));
            n += 3;
        }
        if let Some(v4) = V4::try_new() {
            Simd::vectorize(v4, Run(c, "AVX-512 (16 lanes)"));
            n += 1;
        }
    }
    #[cfg(target_arch = "aarch64")]
    if let Some(neon) = pulp::aarch64::Neon::try_new() {
        Simd::vectorize(neon, Run(c, "NEON (4 lanes)"));
        n += 1;
    }
    n
}

/// Hard lane values: zeros of both signs, infinities, NaN, subnormals, the extremes and the
/// values kernels branch at.
pub(crate) const HARD: [f32; 16] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    3.0,
    -7.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    1e-30,
    -1e-40,
    f32::MAX,
    f32::MIN_POSITIVE,
    0.999_999_9,
    -2.5e-8,
];

/// A deterministic walk over [`HARD`] and a smooth sweep, for filling lanes.
pub(crate) struct Walk(pub u32);

impl Walk {
    /// The next value.
    pub(crate) fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        let k = self.0 >> 8;
        if k.is_multiple_of(3) {
            (k as f32 * 1e-4).sin() * 2.5
        } else {
            HARD[(k % 16) as usize]
        }
    }

    /// A buffer of lanes.
    pub(crate) fn lanes(&mut self) -> [f32; MAX_LANES] {
        std::array::from_fn(|_| self.next())
    }

    /// Three buffers of lanes.
    pub(crate) fn v3(&mut self) -> [[f32; MAX_LANES]; 3] {
        [self.lanes(), self.lanes(), self.lanes()]
    }
}

/// A value's bits, every NaN as one: Rust leaves a NaN's sign and payload to the compiler, and
/// no NaN reaches the film.
pub(crate) fn bits(x: f32) -> u32 {
    if x.is_nan() {
        f32::NAN.to_bits()
    } else {
        x.to_bits()
    }
}

/// The first `S::F32_LANES` lanes of `a` at `S`'s width.
pub(crate) fn load<S: Simd>(a: &[f32; MAX_LANES]) -> F<S> {
    from_array::<S>(a)
}

/// The lanes of `v` at `S`'s width.
pub(crate) fn lanes<S: Simd>(v: F<S>) -> Vec<f32> {
    to_array::<S>(v)[..S::F32_LANES].to_vec()
}

/// Lane `i` of three buffers as a glam vector.
pub(crate) fn lane(a: &[[f32; MAX_LANES]; 3], i: usize) -> Vec3A {
    Vec3A::new(a[0][i], a[1][i], a[2][i])
}

/// Three buffers at `S`'s width.
pub(crate) fn load3<S: Simd>(a: &[[f32; MAX_LANES]; 3]) -> V3<S> {
    V3::from_arrays(a)
}
