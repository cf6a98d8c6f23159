//! Normal mapping: an RGB texture holds the shading normal itself, in the tangent frame of the
//! texture's mapping (T along dp/du, B along dp/dv, N the surface normal), as most painting and
//! baking tools write it: red along +u, green along +v (up in the image), blue out of the
//! surface.

use crate::math::{Rgb, Vec3A};
use crate::texture::{Texture, TextureContext};

use super::bump::{dual_basis, uv_gradients};

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
    #[must_use]
    pub fn perturb(&self, ctx: &TextureContext, n: Vec3A) -> Vec3A {
        let Some((tc, gu, gv)) = uv_gradients(&self.map, ctx) else {
            return n;
        };
        // dp/du and dp/dv in the tangent plane: the dual basis of the gradients of u and v
        // (projected onto the plane; a planar mapping's gradient need not lie in it).
        let (gu, gv) = (gu - gu.dot(n) * n, gv - gv.dot(n) * n);
        let (dpdu, dpdv) = dual_basis(gu, gv);
        // Gram-Schmidt: T along dp/du, B the part of dp/dv across T (keeping its side, so a
        // mirrored (u, v) layout reads its map mirrored too).
        let t = dpdu.normalize_or_zero();
        let b = (dpdv - dpdv.dot(t) * t).normalize_or_zero();
        if t == Vec3A::ZERO || b == Vec3A::ZERO {
            return n;
        }
        let m = decode_normal(self.map.eval_tex_coord(tc, ctx.p));
        let m = Vec3A::new(m.x * self.strength, m.y * self.strength, m.z);
        if m.x.abs() <= FLAT && m.y.abs() <= FLAT {
            // A flat texel (up to the rounding of 128 / 255): the normal exactly as it was.
            return n;
        }
        let mapped = (m.x * t + m.y * b + m.z * n).normalize_or(n);
        if mapped.is_finite() { mapped } else { n }
    }
}
