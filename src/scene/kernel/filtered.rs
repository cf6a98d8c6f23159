//! The kernel's texture stage for an image filtered over the pixel's footprint (trilinear, EWA,
//! the footprint filter) under a built-in mapping of a generic shape: (u, v) and their
//! gradients by the mapping's own lanes, then per lane the footprint on the tangent plane, the
//! screen-space derivatives and the (u, v) transform, then the filter: trilinear in lanes
//! (`MipPyramid::trilinear_lanes`), EWA and the footprint filter per lane.
//!
//! The same steps as `Scene::texture_context` then `ImageTexture::eval`, in the same order and
//! with the same functions (the mapping at width 1 is `Mapping::map_point`), so a lane's colour
//! is the scalar code's bit for bit; what it saves is the per-lane hit record, the texture
//! context and the mapping's per-lane call.

use super::Diffs;
use super::nearest::Hits;
use crate::geometry::{Object, Shape};
use crate::mapping::{AnyMapping, Mapping, TexCoord};
use crate::material::C3;
use crate::math::lanes::{M, MAX_LANES, V3, from_array, mask_to_array, to_array};
use crate::math::{Vec2, Vec3A};
use crate::scene::Scene;
use crate::texture::{ImageTexture, Texture, transformed};
use pulp::Simd;

impl Scene {
    /// The image texture and its built-in mapping, where [`Scene::filtered_lanes`] serves
    /// `texture` on `obj`: an image under a built-in mapping of the point (not a mesh's own
    /// (u, v), not a formula) on a generic shape (a mesh's mapping point and dp/du need its
    /// triangle).
    #[inline(always)]
    pub(super) fn filtered_in_lanes<'a>(
        obj: &Object,
        texture: &'a Texture,
    ) -> Option<(&'a ImageTexture, Mapping)> {
        match (texture, &obj.shape) {
            (_, Shape::Mesh(_)) => None,
            (Texture::Image(t), _) => match t.mapping {
                AnyMapping::Builtin(Mapping::Uv) | AnyMapping::Formula(_) => None,
                AnyMapping::Builtin(m) => Some((t, m)),
            },
            _ => None,
        }
    }

    /// [`Scene::filtered_lanes`] as a call of its own, entered through `s`'s `#[target_feature]`
    /// entry as `Scene::radiance_nested` is: a material reads up to seven textured coefficients
    /// and colours, and the stage inlined at each would multiply the kernel's code (and its
    /// build time) by as much.
    ///
    /// `mapped` holds the lanes' coordinates under `mapping` where another texture of the same
    /// object has already computed them (the Earth's colour, ocean mask and night lights share
    /// one spherical map): they are read, not computed again. The coordinates are returned.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    pub(super) fn filtered_lanes_call<S: Simd>(
        &self,
        s: S,
        obj: &Object,
        t: &ImageTexture,
        mapping: Mapping,
        hits: &Hits<S>,
        diffs: Option<&Diffs>,
        on: M<S>,
        mapped: Option<&Mapped>,
    ) -> (C3<S>, Mapped) {
        /// The stage's inputs as per-lane buffers (pulp's `WithSimd` hands `with_simd` a token
        /// of its own type parameter).
        struct Call<'a> {
            scene: &'a Scene,
            obj: &'a Object,
            t: &'a ImageTexture,
            mapping: Mapping,
            p: [[f32; MAX_LANES]; 3],
            n: [[f32; MAX_LANES]; 3],
            diffs: Option<&'a Diffs>,
            on: [bool; MAX_LANES],
            mapped: Option<&'a Mapped>,
        }
        impl pulp::WithSimd for Call<'_> {
            type Output = ([[f32; MAX_LANES]; 3], Mapped);
            #[inline(always)]
            fn with_simd<S: Simd>(self, s: S) -> Self::Output {
                let mapped = if let Some(m) = self.mapped {
                    *m
                } else {
                    let (p, n) = (V3::from_arrays(&self.p), V3::from_arrays(&self.n));
                    self.scene
                        .mapped_lanes(s, self.obj, self.mapping, &p, &n, self.diffs, &self.on)
                };
                let c = eval_mapped(s, self.t, &mapped, &self.on);
                (crate::math::lanes::map3(c, to_array::<S>), mapped)
            }
        }
        let (c, mapped) = s.vectorize(Call {
            scene: self,
            obj,
            t,
            mapping,
            p: hits.p.to_arrays(),
            n: hits.n.to_arrays(),
            diffs,
            on: mask_to_array(s, on),
            mapped,
        });
        (crate::math::lanes::map3(c, |a| from_array::<S>(&a)), mapped)
    }

    /// The filtered colour of `t` (mapped by `mapping`, see [`Scene::filtered_in_lanes`]) at
    /// the lanes in `on` of object `obj`, with each lane's ray differentials from `diffs`; and
    /// the lanes' coordinates under `mapping`, for other textures of the object to reuse.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn filtered_lanes<S: Simd>(
        &self,
        s: S,
        obj: &Object,
        t: &ImageTexture,
        mapping: Mapping,
        hits: &Hits<S>,
        diffs: Option<&Diffs>,
        on: M<S>,
    ) -> (C3<S>, Mapped) {
        let flags = mask_to_array(s, on);
        let mapped = self.mapped_lanes(s, obj, mapping, &hits.p, &hits.n, diffs, &flags);
        (eval_mapped(s, t, &mapped, &flags), mapped)
    }

    /// The texture coordinates and their screen-space derivatives under `mapping` at the
    /// object-space points `p` with normals `n` of the lanes in `flags`, before any texture's
    /// (u, v) transform.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn mapped_lanes<S: Simd>(
        &self,
        s: S,
        obj: &Object,
        mapping: Mapping,
        p: &V3<S>,
        n: &V3<S>,
        diffs: Option<&Diffs>,
        flags: &[bool; MAX_LANES],
    ) -> Mapped {
        let (lp, ln) = (p.to_arrays(), n.to_arrays());
        let m = mapping.map_lanes::<S, true>(s, p);
        let (u, v) = (to_array::<S>(m.u), to_array::<S>(m.v));
        let (gu, gv) = (m.grad_u.to_arrays(), m.grad_v.to_arrays());
        let vec = |a: &[[f32; MAX_LANES]; 3], i: usize| Vec3A::new(a[0][i], a[1][i], a[2][i]);
        let mut tc = [TexCoord::default(); MAX_LANES];
        for i in 0..S::F32_LANES {
            if !flags[i] {
                continue;
            }
            // `Scene::texture_context`: the footprint on the hit's tangent plane; then
            // `Mapping::map_with_differentials` for a built-in mapping of the point.
            let (dpdx, dpdy) =
                self.footprint_at(obj, diffs.map(|d| &d[i]), vec(&lp, i), vec(&ln, i));
            tc[i] = TexCoord::from_gradients(
                Vec2::new(u[i], v[i]),
                vec(&gu, i),
                vec(&gv, i),
                dpdx,
                dpdy,
            );
        }
        tc
    }
}

/// The lanes' texture coordinates under one mapping, before a texture's (u, v) transform.
pub(super) type Mapped = [TexCoord; MAX_LANES];

/// `ImageTexture::eval_mapped` of the lanes in `flags` at the coordinates `mapped`: the
/// texture's (u, v) transform, then the filter (trilinear in lanes, the others per lane).
#[inline(always)]
fn eval_mapped<S: Simd>(
    s: S,
    t: &ImageTexture,
    mapped: &Mapped,
    flags: &[bool; MAX_LANES],
) -> C3<S> {
    let mut tc = [TexCoord::default(); MAX_LANES];
    for i in 0..S::F32_LANES {
        if flags[i] {
            tc[i] = transformed(mapped[i], t.transform.as_ref());
        }
    }
    t.eval_lanes(s, &tc, flags)
}
