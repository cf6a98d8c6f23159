//! Normal mapping: an RGB texture holds the shading normal itself, in the tangent frame of the
//! texture's mapping (T along dp/du, B along dp/dv, N the surface normal), as most painting and
//! baking tools write it: red along +u, green along +v (up in the image), blue out of the
//! surface.

use crate::math::lanes::{MAX_LANES, to_array};
use crate::math::{Rgb, Vec3A};
use crate::texture::{Texture, TextureContext};
use pulp::Simd;

use super::bump::{UvLanes, dual_basis, uv_gradients};

/// A tangent-space normal texture (read raw: its values are not colours) that replaces the
/// shading normal.
#[derive(Clone, Debug)]
pub struct NormalMap {
    /// The normals, with their own mapping, filter, wrap and (u, v) transform.
    pub map: Texture,
    /// Multiplier on the tangential (red and green) components: 0 flattens the map, 1 reads it
    /// as stored, 2 doubles its slopes; negative turns bumps into dents.
    pub strength: f32,
}

/// The tangent-space vector of a texel value: 8-bit convention, 128 is zero and 255 is +1
/// (`(255 c - 128) / 127`), so the usual flat texel (128, 128, 255) is exactly (0, 0, 1);
/// 0 reads as slightly below -1. Not normalised.
#[must_use]
#[inline]
pub fn decode_normal(c: Rgb) -> Vec3A {
    let f = |c: f32| (255.0 * c - 128.0) / 127.0;
    Vec3A::new(f(c.0), f(c.1), f(c.2))
}

/// The 8-bit texel of a tangent-space unit vector, the inverse of [`decode_normal`]: each
/// component `round(127 n + 128)`, clamped to 0..=255.
#[must_use]
pub fn encode_normal(n: Vec3A) -> [u8; 3] {
    let e = |x: f32| (127.0 * x + 128.0).round().clamp(0.0, 255.0) as u8;
    [e(n.x), e(n.y), e(n.z)]
}

/// Tangential components this small (f32 rounding of a flat texel through a filter) are none.
const FLAT: f32 = 1e-5;

impl NormalMap {
    /// The object-space unit normal at the hit of `ctx` read from the map, in the frame of the
    /// mapping's dp/du and dp/dv made orthonormal around `n` (Gram-Schmidt). The texel is the
    /// texture's filtered value (mip level or EWA over the pixel's footprint), renormalised.
    /// Where the frame is degenerate (a pole, a mesh triangle with a collapsed (u, v) layout)
    /// or the texel holds no direction, `n` itself; the result is always finite and unit.
    /// [`NormalMap::perturb_lanes`] at width 1.
    #[must_use]
    pub fn perturb(&self, ctx: &TextureContext, n: Vec3A) -> Vec3A {
        let Some((tc, gu, gv)) = uv_gradients(&self.map, ctx) else {
            return n;
        };
        let (at, on) = UvLanes::one(tc, gu, gv, ctx.p, n);
        self.perturb_lanes(pulp::Scalar, &at, &on)[0]
    }

    /// [`NormalMap::perturb`] for the lanes in `on` of a packet, each lane's coordinates and
    /// gradients given: each lane's tangent frame ([`tangent_frame`]), the map read in lanes
    /// where the frame is not degenerate ([`Texture::eval_tex_coord_lanes`]), each lane's
    /// normal by `NormalMap::tilt`.
    #[must_use]
    #[inline(always)]
    pub fn perturb_lanes<S: Simd>(
        &self,
        s: S,
        at: &UvLanes,
        on: &[bool; MAX_LANES],
    ) -> [Vec3A; MAX_LANES] {
        let mut frames = [(Vec3A::ZERO, Vec3A::ZERO); MAX_LANES];
        let mut read = [false; MAX_LANES];
        for i in 0..S::F32_LANES {
            if on[i]
                && let Some(f) = tangent_frame(at.gu[i], at.gv[i], at.n[i])
            {
                (frames[i], read[i]) = (f, true);
            }
        }
        let mut out = at.n;
        if !read[..S::F32_LANES].contains(&true) {
            return out;
        }
        let c = self.map.eval_tex_coord_lanes(s, &at.tc, &at.p, &read);
        let (r, g, b) = (
            to_array::<S>(c[0]),
            to_array::<S>(c[1]),
            to_array::<S>(c[2]),
        );
        for i in 0..S::F32_LANES {
            if read[i] {
                out[i] = self.tilt(Rgb(r[i], g[i], b[i]), frames[i], at.n[i]);
            }
        }
        out
    }

    /// The normal the texel `texel` holds in the tangent frame `(t, b)` around `n`.
    #[inline(always)]
    fn tilt(&self, texel: Rgb, (t, b): (Vec3A, Vec3A), n: Vec3A) -> Vec3A {
        let m = decode_normal(texel);
        let m = Vec3A::new(m.x * self.strength, m.y * self.strength, m.z);
        if m.x.abs() <= FLAT && m.y.abs() <= FLAT {
            // A flat texel (up to the rounding of 128 / 255): the normal exactly as it was.
            return n;
        }
        let mapped = (m.x * t + m.y * b + m.z * n).normalize_or(n);
        if mapped.is_finite() { mapped } else { n }
    }
}

/// The unit tangents T and B around the unit normal `n` of a mapping whose u and v have the
/// object-space gradients `gu`, `gv`: dp/du and dp/dv in the tangent plane (the dual basis of
/// the gradients projected onto the plane; a planar mapping's gradient need not lie in it),
/// made orthonormal by Gram-Schmidt (T along dp/du, B the part of dp/dv across T, keeping its
/// side, so a mirrored (u, v) layout reads its map mirrored too); `None` where degenerate.
#[must_use]
#[inline(always)]
pub fn tangent_frame(gu: Vec3A, gv: Vec3A, n: Vec3A) -> Option<(Vec3A, Vec3A)> {
    let (gu, gv) = (gu - gu.dot(n) * n, gv - gv.dot(n) * n);
    let (dpdu, dpdv) = dual_basis(gu, gv);
    let t = dpdu.normalize_or_zero();
    let b = (dpdv - dpdv.dot(t) * t).normalize_or_zero();
    if t == Vec3A::ZERO || b == Vec3A::ZERO {
        None
    } else {
        Some((t, b))
    }
}
