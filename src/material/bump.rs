//! Bump mapping: a height texture tilts the shading normal (Blinn's bump map, in the "surface
//! gradient" form): the height's gradient on the surface, from its filtered (u, v) derivatives
//! chained through the mapping's gradients of u and v, is subtracted from the normal.

use crate::mapping::TexCoord;
use crate::mapping::{AnyMapping, Mapping};
use crate::math::lanes::{MAX_LANES, to_array};
use crate::math::{Rgb, Vec3A};
use crate::texture::{Texture, TextureContext};
use pulp::Simd;

/// A height texture (its luminance, in world units times `scale`) that tilts the normal.
#[derive(Clone, Debug)]
pub struct Bump {
    /// The height field, with its own mapping, filter, wrap and (u, v) transform.
    pub height: Texture,
    /// Height of a texture value of 1, in the object's units.
    pub scale: f32,
}

/// The smallest (u, v) step of the height's finite differences: a footprint smaller than this
/// (or none, without differentials) reads the height over this step.
pub const MIN_BUMP_STEP: f32 = 5e-4;

/// Per lane, what a bump or normal map reads at a hit: the texture coordinates (mapped and
/// transformed, with their screen-space derivatives), the object-space gradients of the
/// transformed u and v ([`uv_gradients`]), the object-space hit point and unit normal.
/// Inactive lanes hold anything.
#[derive(Clone, Copy, Debug)]
pub struct UvLanes {
    /// Texture coordinates.
    pub tc: [TexCoord; MAX_LANES],
    /// Gradients of u.
    pub gu: [Vec3A; MAX_LANES],
    /// Gradients of v.
    pub gv: [Vec3A; MAX_LANES],
    /// Hit points (what a formula texture reads).
    pub p: [Vec3A; MAX_LANES],
    /// Normals to tilt.
    pub n: [Vec3A; MAX_LANES],
}

impl UvLanes {
    /// Lane 0 of a width-1 packet: the scalar path's one hit, and the lanes switched on.
    #[must_use]
    #[inline]
    pub fn one(
        tc: TexCoord,
        gu: Vec3A,
        gv: Vec3A,
        p: Vec3A,
        n: Vec3A,
    ) -> (Self, [bool; MAX_LANES]) {
        let mut at = Self {
            tc: [TexCoord::default(); MAX_LANES],
            gu: [Vec3A::ZERO; MAX_LANES],
            gv: [Vec3A::ZERO; MAX_LANES],
            p: [Vec3A::ZERO; MAX_LANES],
            n: [Vec3A::Y; MAX_LANES],
        };
        (at.tc[0], at.gu[0], at.gv[0], at.p[0], at.n[0]) = (tc, gu, gv, p, n);
        let mut on = [false; MAX_LANES];
        on[0] = true;
        (at, on)
    }
}

/// `tc` with `du` added to u and `dv` to v: where a height difference is read.
#[inline(always)]
fn shifted(tc: &TexCoord, du: f32, dv: f32) -> TexCoord {
    let mut t = *tc;
    t.uv.x += du;
    t.uv.y += dv;
    t
}

/// Each lane's luminance of `texture` at coordinates `tc` (see [`Texture::eval_tex_coord_lanes`]).
#[inline(always)]
fn heights<S: Simd>(
    s: S,
    texture: &Texture,
    tc: &[TexCoord; MAX_LANES],
    p: &[Vec3A; MAX_LANES],
    on: &[bool; MAX_LANES],
) -> [f32; MAX_LANES] {
    let c = texture.eval_tex_coord_lanes(s, tc, p, on);
    let (r, g, b) = (
        to_array::<S>(c[0]),
        to_array::<S>(c[1]),
        to_array::<S>(c[2]),
    );
    let mut h = [0.0; MAX_LANES];
    for i in 0..S::F32_LANES {
        h[i] = Rgb(r[i], g[i], b[i]).luminance();
    }
    h
}

impl Bump {
    /// The object-space unit normal `n` at the hit of `ctx`, tilted by the height's slope.
    /// A constant (or flat) height returns `n` itself, bit for bit; the result is always
    /// finite and unit (where the slope is undefined, at a pole or a degenerate triangle, `n`).
    /// [`Bump::perturb_lanes`] at width 1.
    #[must_use]
    pub fn perturb(&self, ctx: &TextureContext, n: Vec3A) -> Vec3A {
        let Some((tc, gu, gv)) = uv_gradients(&self.height, ctx) else {
            return n;
        };
        let (at, on) = UvLanes::one(tc, gu, gv, ctx.p, n);
        self.perturb_lanes(pulp::Scalar, &at, &on)[0]
    }

    /// [`Bump::perturb`] for the lanes in `on` of a packet, each lane's coordinates and
    /// gradients given: the three height lookups of every lane in lanes
    /// ([`Texture::eval_tex_coord_lanes`]: an image's bilinear or trilinear filter runs in
    /// lanes), each lane's slope and tilted normal by `Bump::tilt`.
    #[must_use]
    #[inline(always)]
    pub fn perturb_lanes<S: Simd>(
        &self,
        s: S,
        at: &UvLanes,
        on: &[bool; MAX_LANES],
    ) -> [Vec3A; MAX_LANES] {
        let (mut du, mut dv) = ([0.0; MAX_LANES], [0.0; MAX_LANES]);
        let mut t = [[TexCoord::default(); MAX_LANES]; 3];
        for i in 0..S::F32_LANES {
            if on[i] {
                let tc = &at.tc[i];
                // Filtered finite differences over the pixel's footprint (at least
                // MIN_BUMP_STEP).
                du[i] = (0.5 * (tc.duvdx.x.abs() + tc.duvdy.x.abs())).max(MIN_BUMP_STEP);
                dv[i] = (0.5 * (tc.duvdx.y.abs() + tc.duvdy.y.abs())).max(MIN_BUMP_STEP);
                t[0][i] = shifted(tc, 0.0, 0.0);
                t[1][i] = shifted(tc, du[i], 0.0);
                t[2][i] = shifted(tc, 0.0, dv[i]);
            }
        }
        let h0 = heights(s, &self.height, &t[0], &at.p, on);
        let hu = heights(s, &self.height, &t[1], &at.p, on);
        let hv = heights(s, &self.height, &t[2], &at.p, on);
        let mut out = at.n;
        for i in 0..S::F32_LANES {
            if on[i] {
                out[i] = self.tilt(
                    [h0[i], hu[i], hv[i]],
                    (du[i], dv[i]),
                    (at.gu[i], at.gv[i]),
                    at.n[i],
                );
            }
        }
        out
    }

    /// The normal `n` tilted by the heights `h` read at (u, v), (u + du, v) and (u, v + dv),
    /// with `g` the gradients of u and v.
    #[inline(always)]
    fn tilt(&self, h: [f32; 3], (du, dv): (f32, f32), (gu, gv): (Vec3A, Vec3A), n: Vec3A) -> Vec3A {
        let h0 = h[0];
        // Differences at the level of f32 rounding (a filter averaging a flat texture) are no
        // slope: a flat height leaves the normal exactly as it was.
        let flat = 4.0 * f32::EPSILON * h0.abs().max(1.0);
        let step = |d: f32| if d.abs() <= flat { 0.0 } else { d };
        let dhdu = step(h[1] - h0) / du;
        let dhdv = step(h[2] - h0) / dv;
        if dhdu == 0.0 && dhdv == 0.0 {
            return n;
        }
        let grad = (dhdu * gu + dhdv * gv) * self.scale;
        let tangential = grad - grad.dot(n) * n;
        let bumped = (n - tangential).normalize_or(n);
        if bumped.is_finite() { bumped } else { n }
    }
}

/// The texture coordinates of `texture` at the hit of `ctx` and the object-space gradients of
/// its (transformed) u and v: the mapping's analytic gradients, or on a mesh the dual basis of
/// the triangle's dp/du and dp/dv; `None` for a texture without a mapping (a constant) or a
/// mesh triangle without a (u, v) layout.
#[must_use]
pub fn uv_gradients(texture: &Texture, ctx: &TextureContext) -> Option<(TexCoord, Vec3A, Vec3A)> {
    let (Some(mapping), Some(tc)) = (texture.mapping(), texture.tex_coord(ctx)) else {
        return None;
    };
    // Gradients of the shape's own (u, v) with respect to the object-space point.
    let own = || match ctx.shape_uv {
        Some((_, Some((dpdu, dpdv)))) => Some(dual_basis(dpdu, dpdv)),
        Some((_, None)) => None,
        None => {
            let m = ctx.natural.map_point(ctx.p);
            Some((m.grad_u, m.grad_v))
        }
    };
    // Gradients of the mapping's u and v with respect to the object-space point.
    let (gu, gv) = match mapping {
        AnyMapping::Builtin(Mapping::Uv) => own()?,
        AnyMapping::Builtin(m) => {
            let m = m.map_point(ctx.p);
            (m.grad_u, m.grad_v)
        }
        AnyMapping::Formula(f) => {
            // The chain rule through mesh_u, mesh_v where the formula reads them.
            let (mu, mv) = if f.reads_mesh() {
                own()?
            } else {
                (Vec3A::ZERO, Vec3A::ZERO)
            };
            let mesh = Mapping::Uv
                .map_with_differentials(ctx.p, Vec3A::ZERO, Vec3A::ZERO, ctx.shape_uv, ctx.natural)
                .uv;
            let p = ctx.p.as_dvec3();
            let g = f.gradients(&[p.x, p.y, p.z, f64::from(mesh.x), f64::from(mesh.y)]);
            let grad = |r: &[f64; 5]| {
                let direct = Vec3A::new(r[0] as f32, r[1] as f32, r[2] as f32);
                let g = direct + r[3] as f32 * mu + r[4] as f32 * mv;
                if g.is_finite() { g } else { Vec3A::ZERO }
            };
            (grad(&g[0]), grad(&g[1]))
        }
    };
    let (gu, gv) = through_transform(texture, gu, gv);
    Some((tc, gu, gv))
}

/// The object-space gradients `gu`, `gv` of a mapping's u and v through `texture`'s (u, v)
/// transform, u' = a u + b v, v' = c u + d v: the gradients of the texture's own u and v.
#[must_use]
#[inline]
pub fn through_transform(texture: &Texture, gu: Vec3A, gv: Vec3A) -> (Vec3A, Vec3A) {
    match texture.uv_affine() {
        Some(t) => {
            let (x, y) = (t.matrix.x_axis, t.matrix.y_axis);
            (x.x * gu + y.x * gv, x.y * gu + y.y * gv)
        }
        None => (gu, gv),
    }
}

/// The gradients of u and v on a surface whose tangents are `dpdu` and `dpdv`: the vectors in
/// their plane with `gu . dpdu = 1`, `gu . dpdv = 0`, `gv . dpdu = 0`, `gv . dpdv = 1`; zero
/// for a degenerate (u, v) layout.
#[must_use]
pub fn dual_basis(dpdu: Vec3A, dpdv: Vec3A) -> (Vec3A, Vec3A) {
    let (a, b, c) = (dpdu.dot(dpdu), dpdu.dot(dpdv), dpdv.dot(dpdv));
    let det = a * c - b * b;
    if !det.is_finite() || det.abs() <= 1e-30 {
        return (Vec3A::ZERO, Vec3A::ZERO);
    }
    let gu = (c * dpdu - b * dpdv) / det;
    let gv = (a * dpdv - b * dpdu) / det;
    if gu.is_finite() && gv.is_finite() {
        (gu, gv)
    } else {
        (Vec3A::ZERO, Vec3A::ZERO)
    }
}
