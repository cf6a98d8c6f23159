//! Small math types shared by every stage: glam re-exports, rays with differentials, colour,
//! frames and a seeded, stateless random number source.

mod atan;
mod color;
pub mod lanes;
mod rng;

pub use atan::atan2;
pub use color::{
    DisplayImage, Rgb, encode_display, encode_srgb8, linear_to_srgb, linear_to_srgb8, quantize8,
    srgb_to_linear, srgb8_table, srgb8_to_linear, unorm8_table,
};
pub use glam::{Affine3A, Mat3, Mat3A, Quat, Vec2, Vec3, Vec3A};
pub use rng::{SampleRng, hash3, hash3_lanes, pcg_lanes, unit_f32};

/// 2 pi, the cylindrical and spherical maps' full turn.
pub const TAU: f32 = std::f32::consts::TAU;
/// pi, the range of the spherical map's polar angle (v = 1 - theta / pi).
pub const PI: f32 = std::f32::consts::PI;
/// 1 / pi, the Lambertian normalisation of the lecture's `SV_Lambertian::f`.
pub const INV_PI: f32 = std::f32::consts::FRAC_1_PI;

/// A ray `origin + t * dir`; `dir` need not be unit length (instance transforms scale it, and
/// keeping it unnormalised keeps `t` the same in world and object space).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3A,
    /// Its direction (any non-zero length).
    pub dir: Vec3A,
}

impl Ray {
    /// A ray from `origin` along `dir`.
    #[must_use]
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        Self { origin, dir }
    }

    /// The point at parameter `t`.
    #[must_use]
    #[inline]
    pub fn at(&self, t: f32) -> Vec3A {
        self.origin + t * self.dir
    }

    /// The ray carried through an affine transform (direction not renormalised).
    #[must_use]
    #[inline]
    pub fn transformed(&self, m: &Affine3A) -> Self {
        Self {
            origin: m.transform_point3a(self.origin),
            dir: m.transform_vector3a(self.dir),
        }
    }
}

/// The offsets of a camera ray's neighbours one pixel to the right (x) and one pixel down (y),
/// as pbrt's ray differentials: enough to find the footprint of a pixel on a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayDifferential {
    /// Origin of the ray one pixel to the right.
    pub rx_origin: Vec3A,
    /// Direction of the ray one pixel to the right.
    pub rx_dir: Vec3A,
    /// Origin of the ray one pixel down.
    pub ry_origin: Vec3A,
    /// Direction of the ray one pixel down.
    pub ry_dir: Vec3A,
}

impl RayDifferential {
    /// The differentials carried through an affine transform.
    #[must_use]
    #[inline]
    pub fn transformed(&self, m: &Affine3A) -> Self {
        Self {
            rx_origin: m.transform_point3a(self.rx_origin),
            rx_dir: m.transform_vector3a(self.rx_dir),
            ry_origin: m.transform_point3a(self.ry_origin),
            ry_dir: m.transform_vector3a(self.ry_dir),
        }
    }

    /// Scales the offsets from the main ray by `s` (used when a pixel takes several samples,
    /// so each sample's footprint shrinks with the sample spacing).
    #[must_use]
    pub fn scaled_about(&self, ray: &Ray, s: f32) -> Self {
        Self {
            rx_origin: ray.origin + (self.rx_origin - ray.origin) * s,
            rx_dir: ray.dir + (self.rx_dir - ray.dir) * s,
            ry_origin: ray.origin + (self.ry_origin - ray.origin) * s,
            ry_dir: ray.dir + (self.ry_dir - ray.dir) * s,
        }
    }

    /// dp/dx and dp/dy on the plane through `p` with normal `n`, where the main ray hit
    /// (pbrt's construction); zero where an offset ray runs parallel to the plane.
    #[must_use]
    #[inline]
    pub fn footprint_on_plane(&self, p: Vec3A, n: Vec3A) -> (Vec3A, Vec3A) {
        let d = n.dot(p);
        let offset = |o: Vec3A, dir: Vec3A| {
            let denom = n.dot(dir);
            if denom.abs() < 1e-20 {
                return Vec3A::ZERO;
            }
            let t = (d - n.dot(o)) / denom;
            let q = o + t * dir - p;
            if q.is_finite() { q } else { Vec3A::ZERO }
        };
        (
            offset(self.rx_origin, self.rx_dir),
            offset(self.ry_origin, self.ry_dir),
        )
    }
}

/// `x.floor()` without a libm call. On the x86-64 baseline (no SSE4.1 `roundss`) `f32::floor`
/// is a function call: 13 % of a footprint-filtered render went to it. Through an integer for
/// |x| < 2^31 (every float that large is already an integer below 2^23, so the conversion is
/// exact), `floor` itself otherwise. Equal to `x.floor()` for every input but the sign of a
/// zero result (-0.0 gives 0.0).
#[must_use]
#[inline(always)]
pub fn floor_fast(x: f32) -> f32 {
    if x.abs() < 2_147_483_648.0 {
        let t = x as i32 as f32;
        if t > x { t - 1.0 } else { t }
    } else {
        x.floor()
    }
}

/// [`floor_fast`] for `f64` (the footprint filter's summed-area table reads at `f64` texel
/// coordinates): through an integer for |x| < 2^52, where the conversion is exact.
#[must_use]
#[inline(always)]
pub fn floor_fast_f64(x: f64) -> f64 {
    if x.abs() < 4_503_599_627_370_496.0 {
        let t = x as i64 as f64;
        if t > x { t - 1.0 } else { t }
    } else {
        x.floor()
    }
}

/// The largest absolute component of `p`, used to scale offsets and tolerances with the size of
/// the numbers involved.
#[must_use]
#[inline]
pub fn max_abs(p: Vec3A) -> f32 {
    lanes::V3::one(p).max_abs(pulp::Scalar)
}

/// An orthonormal basis whose third axis is `n` (Duff et al. 2017, branchless).
#[must_use]
pub fn frame_from_normal(n: Vec3A) -> (Vec3A, Vec3A) {
    let sign = 1.0_f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3A::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3A::new(b, sign + n.y * n.y * a, -n.y),
    )
}

#[cfg(test)]
mod tests {
    #[test]
    fn floor_fast_is_floor() {
        let mut xs = vec![
            0.0_f32,
            0.5,
            -0.5,
            1.0,
            -1.0,
            0.999_999_9,
            -0.999_999_9,
            1e-30,
            -1e-30,
            8_388_607.5,
            -8_388_607.5,
            8_388_608.0,
            16_777_217.0,
            2_147_483_520.0,
            -2_147_483_648.0,
            2_147_483_648.0,
            3e9,
            -3e9,
            1e30,
            -1e30,
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        // Every bit pattern class: a xorshift walk through the floats.
        let mut s = 0x1234_5678_u32;
        for _ in 0..200_000 {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            xs.push(f32::from_bits(s));
        }
        for x in xs {
            let (a, b) = (super::floor_fast(x), x.floor());
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                "{x}: {a} vs {b}"
            );
        }
        // The one difference: a negative zero comes back positive.
        assert_eq!(super::floor_fast(-0.0).to_bits(), 0.0_f32.to_bits());
    }

    #[test]
    fn floor_fast_f64_is_floor() {
        let mut xs = vec![
            0.0_f64,
            0.5,
            -0.5,
            -1.0,
            0.999_999_999_999,
            -0.999_999_999_999,
            1e-300,
            -1e-300,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            9.3e18,
            -9.3e18,
            1e300,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let mut s = 0x1234_5678_9abc_def0_u64;
        for _ in 0..200_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            xs.push(f64::from_bits(s));
        }
        for x in xs {
            let (a, b) = (super::floor_fast_f64(x), x.floor());
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()) || (a == 0.0 && b == 0.0),
                "{x}: {a} vs {b}"
            );
        }
    }
}
