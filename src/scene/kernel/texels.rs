//! The kernel's texture stage for lanes whose texture needs no footprint: (u, v) by the
//! mapping's own lanes, the (u, v) transform, then the texels: the lane-wise nearest lookup of
//! an image under repeat or clamp wrapping (the Earth's), else the texture's filter per lane.

use super::nearest::Hits;
use crate::geometry::{Object, Shape};
use crate::mapping::{AnyMapping, Mapping, TexCoord};
use crate::material::{C3, splat_rgb};
use crate::math::lanes::{F, M, MAX_LANES, V3, from_array, mask_to_array, to_array};
use crate::math::{Vec2, Vec3A};
use crate::scene::{Scene, natural_mapping};
use crate::texture::{
    Filter, ImageData, Lookup, Texels, Texture, TextureContext, Wrap, tiled_index,
};
use pulp::Simd;

/// An image texture under the nearest filter with repeat or clamp wrapping: its wrap, texel
/// index and tile address lane by lane (`Wrap::coord`, `Lookup::index`, `ImageData::texel`'s
/// steps), then one load per lane.
#[derive(Clone, Copy, Debug)]
struct Nearest<'a> {
    image: &'a ImageData,
    lookup: Lookup,
    wu: Wrap,
    wv: Wrap,
    scale: f32,
}

impl<'a> Nearest<'a> {
    fn new(texture: &'a Texture) -> Option<Self> {
        let Texture::Image(t) = texture else {
            return None;
        };
        let (wu, wv) = t.wraps();
        let plain = |w: Wrap| matches!(w, Wrap::Repeat | Wrap::Clamp);
        (t.filter == Filter::Nearest && plain(wu) && plain(wv)).then_some(Self {
            image: &t.image,
            lookup: t.lookup,
            wu,
            wv,
            scale: t.scale,
        })
    }

    /// `Wrap::coord` per lane for repeat or clamp (never `None` for these).
    #[inline(always)]
    fn coord(wrap: Wrap, t: &mut [f32; MAX_LANES], n: usize) {
        let repeat = wrap == Wrap::Repeat;
        for x in &mut t[..n] {
            let v = *x;
            let inside = (0.0..=1.0).contains(&v);
            let f = v - v.floor();
            let wrapped = if repeat {
                if f < 1.0 { f } else { 0.0 }
            } else if v < 0.0 {
                0.0
            } else {
                1.0
            };
            let w = if v.is_nan() { 0.0 } else { wrapped };
            *x = if inside { v } else { w };
        }
    }

    /// `Lookup::index` per lane.
    #[inline(always)]
    fn index(lookup: Lookup, t: &[f32; MAX_LANES], n: u32, lanes: usize) -> [u32; MAX_LANES] {
        let last = n - 1;
        // The lecture's (hres - 1) u or the centred u hres.
        let nf = match lookup {
            Lookup::Lecture => last as f32,
            Lookup::Centred => n as f32,
        };
        let mut r = [0; MAX_LANES];
        for i in 0..lanes {
            r[i] = ((t[i] * nf) as u32).min(last);
        }
        r
    }

    /// The colours (times the texture's scale) at (u, v) for the lanes in `on`.
    #[inline(always)]
    fn sample<S: Simd>(&self, s: S, u: F<S>, v: F<S>, on: &[bool; MAX_LANES]) -> C3<S> {
        let n = S::F32_LANES;
        let (mut u, mut v) = (to_array::<S>(u), to_array::<S>(v));
        Self::coord(self.wu, &mut u, n);
        Self::coord(self.wv, &mut v, n);
        let (w, h) = (self.image.width(), self.image.height());
        let col = Self::index(self.lookup, &u, w, n);
        let row = Self::index(self.lookup, &v, h, n);
        let tiles_x = self.image.tiles_x();
        let mut c = [[0.0; MAX_LANES]; 3];
        let k = self.scale;
        if let Some((px, t)) = self.image.texels().bytes() {
            for i in 0..n {
                if on[i] {
                    // `ImageData::texel`: the row from the bottom to the file's from the top.
                    let [r, g, b, _] = px[tiled_index(tiles_x, col[i], h - 1 - row[i])];
                    c[0][i] = t[r as usize] * k;
                    c[1][i] = t[g as usize] * k;
                    c[2][i] = t[b as usize] * k;
                }
            }
        } else if let Texels::Linear(px) = self.image.texels() {
            for i in 0..n {
                if on[i] {
                    let [r, g, b] = px[tiled_index(tiles_x, col[i], h - 1 - row[i])];
                    c[0][i] = r * k;
                    c[1][i] = g * k;
                    c[2][i] = b * k;
                }
            }
        }
        let _ = s;
        crate::math::lanes::map3(c, |a| from_array::<S>(&a))
    }
}

/// `c` with the non-finite mark where (u, v) is not finite (a formula that is not finite
/// there), as `Texture::eval_tex_coord` gives it.
#[inline(always)]
fn marked<S: Simd>(
    s: S,
    c: C3<S>,
    u: &[f32; MAX_LANES],
    v: &[f32; MAX_LANES],
    flags: &[bool; MAX_LANES],
) -> C3<S> {
    let bad: [bool; MAX_LANES] =
        crate::math::lanes::each_lane(|i| flags[i] && !(u[i].is_finite() && v[i].is_finite()));
    if !bad[..S::F32_LANES].contains(&true) {
        return c;
    }
    let mark = crate::texture::mark();
    let m = crate::math::lanes::mask_from_array(s, &bad);
    [
        s.select_f32s(m, s.splat_f32s(mark.0), c[0]),
        s.select_f32s(m, s.splat_f32s(mark.1), c[1]),
        s.select_f32s(m, s.splat_f32s(mark.2), c[2]),
    ]
}

impl Scene {
    /// The point the object's mappings read (a mesh's fitted into the generic objects'
    /// [-1, 1]^3, as `Scene::texture_context_at` gives it).
    #[inline(always)]
    pub(super) fn mapping_point<S: Simd>(s: S, obj: &Object, p: &V3<S>) -> V3<S> {
        match &obj.shape {
            Shape::Mesh(m) => {
                let (centre, scale) = m.mesh.mapping_frame();
                p.sub(s, &V3::splat(s, centre))
                    .scale(s, s.splat_f32s(scale))
            }
            _ => *p,
        }
    }

    /// The texture context of lane `i` without a footprint: the mapping point `q`, the mesh's
    /// (u, v) there and the shape's natural mapping (`Scene::texture_context_at` with zero
    /// offsets).
    #[inline(always)]
    pub(super) fn plain_context(obj: &Object, q: Vec3A, uv: Option<Vec2>) -> TextureContext {
        TextureContext {
            p: q,
            dpdx: Vec3A::ZERO,
            dpdy: Vec3A::ZERO,
            shape_uv: uv.map(|uv| (uv, None)),
            natural: natural_mapping(&obj.shape),
        }
    }

    /// `texture`'s colour at the lanes in `on` of object `obj` for a texture read without a
    /// footprint: (u, v) in lanes where the mapping is a built-in one on a point (per lane for
    /// a formula or a mesh's own (u, v)), the (u, v) transform, then the texels.
    #[inline(always)]
    pub(super) fn texels_lanes<S: Simd>(
        s: S,
        obj: &Object,
        texture: &Texture,
        hits: &Hits<S>,
        q: &V3<S>,
        on: M<S>,
    ) -> C3<S> {
        let mapping = match (texture, texture.mapping()) {
            (Texture::Constant(c), _) => return splat_rgb(s, *c),
            (_, Some(m)) => m,
            (_, None) => {
                return splat_rgb(
                    s,
                    texture.eval(&Self::plain_context(obj, Vec3A::ZERO, None)),
                );
            }
        };
        let n = S::F32_LANES;
        let flags = mask_to_array(s, on);
        let qa = q.to_arrays();
        let lane_q = |i: usize| Vec3A::new(qa[0][i], qa[1][i], qa[2][i]);
        // (u, v) per lane: a built-in mapping of the point in lanes; a mesh's own (u, v) or a
        // formula per lane, through the scalar mapping.
        let builtin = match mapping {
            AnyMapping::Builtin(Mapping::Uv) => match &obj.shape {
                Shape::Mesh(_) => None,
                shape => Some(natural_mapping(shape)),
            },
            AnyMapping::Builtin(m) => Some(*m),
            AnyMapping::Formula(_) => None,
        };
        let (mut u, mut v) = if let Some(m) = builtin {
            let mapped = m.map_lanes::<S, false>(s, q);
            (to_array::<S>(mapped.u), to_array::<S>(mapped.v))
        } else {
            let (mut u, mut v) = ([0.0; MAX_LANES], [0.0; MAX_LANES]);
            for i in 0..n {
                if flags[i] {
                    let ctx = Self::plain_context(obj, lane_q(i), hits.uv[i]);
                    let tc = ctx.tex_coord(mapping);
                    (u[i], v[i]) = (tc.uv.x, tc.uv.y);
                }
            }
            (u, v)
        };
        // The (u, v) transform, where (u, v) is finite (a formula's NaN stays NaN: marked).
        if let Some(a) = texture.uv_affine() {
            for i in 0..n {
                let tc = TexCoord {
                    uv: Vec2::new(u[i], v[i]),
                    ..TexCoord::default()
                };
                if flags[i] && tc.uv.is_finite() {
                    let t = a.apply(tc);
                    (u[i], v[i]) = (t.uv.x, t.uv.y);
                }
            }
        }
        let lanes = if let Some(near) = Nearest::new(texture) {
            Some(near.sample(s, from_array::<S>(&u), from_array::<S>(&v), &flags))
        } else {
            match texture {
                Texture::Image(t)
                    if matches!(
                        (t.filter, &t.mip),
                        (Filter::Bilinear, _) | (Filter::Trilinear | Filter::Ewa, None)
                    ) =>
                {
                    let (wu, wv) = t.wraps();
                    let c = t.image.bilinear_lanes(
                        s,
                        from_array::<S>(&u),
                        from_array::<S>(&v),
                        wu,
                        wv,
                        &flags,
                    );
                    let k = s.splat_f32s(t.scale);
                    Some(crate::math::lanes::map3(c, |c| s.mul_f32s(c, k)))
                }
                _ => None,
            }
        };
        if let Some(c) = lanes {
            return marked(s, c, &u, &v, &flags);
        }
        let mut c = [[0.0; MAX_LANES]; 3];
        for i in 0..n {
            if flags[i] {
                let tc = TexCoord {
                    uv: Vec2::new(u[i], v[i]),
                    ..TexCoord::default()
                };
                let rgb = texture.eval_tex_coord(tc, lane_q(i));
                (c[0][i], c[1][i], c[2][i]) = (rgb.0, rgb.1, rgb.2);
            }
        }
        crate::math::lanes::map3(c, |a| from_array::<S>(&a))
    }
}
