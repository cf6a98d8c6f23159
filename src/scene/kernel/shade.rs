//! The kernel's shading stage for one object's lanes: the hit resolved in world space and
//! faced toward the viewer (`Scene::resolve`'s steps), the texture and the material's terms,
//! a bump or normal map, the debug views, mirrors and clip maps.

use super::filtered::Mapped;
use super::nearest::Hits;
use super::{Diffs, Rays, lanes};
use crate::geometry::{LocalHit, Object};
use crate::mapping::Mapping;
use crate::material::{C3, Colour, ParamLanes, Scalar, splat_rgb};
use crate::math::lanes::{
    F, M, MAX_LANES, V3, from_array, mask_from_array, mask_to_array, max, to_array,
};
use crate::math::{Ray, RayDifferential, Rgb, Vec3A};
use crate::scene::Scene;
use crate::scene::trace::{MAX_CLIP_LAYERS, SHADOW_OFFSET_RELATIVE, SurfaceHit, mirror_lanes};
use crate::texture::{TextureContext, View};
use pulp::Simd;

/// One object's hits in world space: the point, the geometric and shading normals on the
/// viewer's side, the direction to the viewer, and which lanes see the outside.
#[derive(Clone, Copy)]
pub(super) struct Resolved<S: Simd> {
    pub p: V3<S>,
    pub ng: V3<S>,
    pub ns: V3<S>,
    pub wo: V3<S>,
    pub front: M<S>,
}

/// The per-lane records the scalar building blocks take, made when some part of the object's
/// shading runs per lane.
pub(super) struct PerLane {
    pub hits: [SurfaceHit; MAX_LANES],
    pub ctx: [TextureContext; MAX_LANES],
}

/// The material's parameters of the lanes being shaded: constants in every lane, textures per
/// lane from the lanes' texture contexts.
struct LaneParams<'a, S: Simd> {
    s: S,
    per: Option<&'a PerLane>,
    on: [bool; MAX_LANES],
    /// What an image under a built-in mapping of a generic shape is read in lanes from
    /// ([`Scene::filtered_lanes`]): the scene, the object, its hits and the rays' differentials.
    scene: &'a Scene,
    obj: &'a Object,
    hits: &'a Hits<S>,
    diffs: Option<&'a Diffs>,
    mask: M<S>,
    /// The lanes' coordinates under the last mapping an image was read through in lanes, for
    /// the next image under the same mapping.
    mapped: std::cell::RefCell<Option<(Mapping, Mapped)>>,
}

impl<S: Simd> LaneParams<'_, S> {
    /// `texture`'s colour in lanes, where it is an image [`Scene::filtered_in_lanes`] serves.
    #[inline(always)]
    fn in_lanes(&self, texture: &crate::texture::Texture) -> Option<C3<S>> {
        let (t, m) = Scene::filtered_in_lanes(self.obj, texture)?;
        let mut cache = self.mapped.borrow_mut();
        let known = cache.as_ref().filter(|(at, _)| *at == m).map(|(_, c)| c);
        let (c, mapped) = self.scene.filtered_lanes_call(
            self.s, self.obj, t, m, self.hits, self.diffs, self.mask, known,
        );
        if known.is_none() {
            *cache = Some((m, mapped));
        }
        Some(c)
    }
}

impl<S: Simd> ParamLanes<S> for LaneParams<'_, S> {
    #[inline(always)]
    fn scalar(&self, p: &Scalar) -> F<S> {
        if let Scalar::Texture(t) = p
            && let Some(c) = self.in_lanes(&t.texture)
        {
            // `ScalarTexture::eval`: the channel of the colour, per lane.
            let c = crate::math::lanes::map3(c, to_array::<S>);
            let mut a = [0.0; MAX_LANES];
            for i in 0..S::F32_LANES {
                if self.on[i] {
                    a[i] = t.channel.of(Rgb(c[0][i], c[1][i], c[2][i]));
                }
            }
            return from_array::<S>(&a);
        }
        match (p, self.per) {
            (Scalar::Const(v), _) => self.s.splat_f32s(*v),
            (Scalar::Texture(t), Some(pl)) => {
                let mut a = [0.0; MAX_LANES];
                for i in 0..S::F32_LANES {
                    if self.on[i] {
                        a[i] = t.eval(&pl.ctx[i]);
                    }
                }
                from_array::<S>(&a)
            }
            // Unreachable: a textured parameter not read in lanes makes the lanes' records.
            (Scalar::Texture(_), None) => self.s.splat_f32s(0.0),
        }
    }

    #[inline(always)]
    fn colour(&self, p: &Colour) -> C3<S> {
        if let Colour::Texture(t) = p
            && let Some(c) = self.in_lanes(t)
        {
            return c;
        }
        match (p, self.per) {
            (Colour::Const(c), _) => splat_rgb(self.s, *c),
            (Colour::Texture(_), Some(pl)) => {
                let mut a = [[0.0; MAX_LANES]; 3];
                for i in 0..S::F32_LANES {
                    if self.on[i] {
                        let c = p.eval(&pl.ctx[i]);
                        (a[0][i], a[1][i], a[2][i]) = (c.0, c.1, c.2);
                    }
                }
                crate::math::lanes::map3(a, |c| from_array::<S>(&c))
            }
            (Colour::Texture(_), None) => splat_rgb(self.s, Rgb::BLACK),
        }
    }
}

/// `n` of object space to world space per lane (`Object::normal_to_world`).
#[inline(always)]
fn normal_to_world<S: Simd>(s: S, obj: &Object, n: &V3<S>) -> V3<S> {
    if obj.identity {
        *n
    } else if obj.normal_orthonormal {
        n.linear(s, &obj.normal_to_world)
    } else {
        n.linear(s, &obj.normal_to_world).normalize_or(s, Vec3A::Y)
    }
}

impl Scene {
    /// Object `obj`'s hits in world space, faced toward the viewer (`Scene::resolve`).
    #[inline(always)]
    pub(super) fn resolve_lanes<S: Simd>(
        s: S,
        obj: &Object,
        hits: &Hits<S>,
        d: &V3<S>,
    ) -> Resolved<S> {
        let p = if obj.identity {
            hits.p
        } else {
            hits.p.point(s, &obj.world_from_object)
        };
        let ng = normal_to_world(s, obj, &hits.n);
        let same = s.and_m32s(
            s.and_m32s(
                s.equal_f32s(hits.ns.x, hits.n.x),
                s.equal_f32s(hits.ns.y, hits.n.y),
            ),
            s.equal_f32s(hits.ns.z, hits.n.z),
        );
        let ns = if crate::math::lanes::all(s, same) {
            ng
        } else {
            V3::select(s, same, &ng, &normal_to_world(s, obj, &hits.ns))
        };
        let wo = d.neg(s).normalize_or(s, Vec3A::Z);
        // Two-sided surfaces: shade the side the ray came from.
        let back = s.less_than_f32s(ng.dot(s, &wo), s.splat_f32s(0.0));
        Resolved {
            p,
            ng: V3::select(s, back, &ng.neg(s), &ng),
            ns: V3::select(s, back, &ns.neg(s), &ns),
            wo,
            front: s.not_m32s(back),
        }
    }

    /// How far rays leave each lane's hit (`Scene::offset_at`): [`SHADOW_OFFSET_RELATIVE`] of
    /// the coordinates' size.
    #[inline(always)]
    pub(super) fn offset_lanes<S: Simd>(s: S, obj: &Object, p: &V3<S>) -> F<S> {
        let size = s.add_f32s(
            p.max_abs(s),
            s.splat_f32s(crate::math::max_abs(obj.world_from_object.translation)),
        );
        s.mul_f32s(
            s.splat_f32s(SHADOW_OFFSET_RELATIVE),
            max(s, size, s.splat_f32s(f32::MIN_POSITIVE)),
        )
    }

    /// The records of the lanes in `on` for the scalar building blocks: each lane's
    /// [`SurfaceHit`] and texture context (`Scene::texture_context`, with the lane's ray
    /// differentials where the scene has them).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn per_lane<S: Simd>(
        &self,
        s: S,
        k: usize,
        hits: &Hits<S>,
        r: &Resolved<S>,
        on: M<S>,
        diffs: Option<&Diffs>,
    ) -> Box<PerLane> {
        let flags = mask_to_array(s, on);
        let (lp, ln, lns, t) = (
            hits.p.to_arrays(),
            hits.n.to_arrays(),
            hits.ns.to_arrays(),
            to_array::<S>(hits.t),
        );
        let (p, ng, ns, wo) = (
            r.p.to_arrays(),
            r.ng.to_arrays(),
            r.ns.to_arrays(),
            r.wo.to_arrays(),
        );
        let front = mask_to_array(s, r.front);
        let v = |a: &[[f32; MAX_LANES]; 3], i: usize| Vec3A::new(a[0][i], a[1][i], a[2][i]);
        let blank = SurfaceHit {
            object: k,
            local: LocalHit {
                t: 0.0,
                p: Vec3A::ZERO,
                n: Vec3A::Y,
                ns: Vec3A::Y,
                uv: None,
                dpduv: None,
                part: 0,
                prim: 0,
            },
            p: Vec3A::ZERO,
            ng: Vec3A::Y,
            ns: Vec3A::Y,
            wo: Vec3A::Z,
            front_face: true,
        };
        let obj = &self.objects[k];
        let mut out = Box::new(PerLane {
            hits: [blank; MAX_LANES],
            ctx: [Self::plain_context(obj, Vec3A::ZERO, None); MAX_LANES],
        });
        for i in 0..S::F32_LANES {
            if !flags[i] {
                continue;
            }
            let hit = SurfaceHit {
                object: k,
                local: hits.local(i, &lp, &ln, &lns, &t),
                p: v(&p, i),
                ng: v(&ng, i),
                ns: v(&ns, i),
                wo: v(&wo, i),
                front_face: front[i],
            };
            out.ctx[i] = self.texture_context(&hit, diffs.map(|d| &d[i]));
            out.hits[i] = hit;
        }
        out
    }

    /// Radiance and edge keys of object `k`'s lanes `mine` (a packet mirrored `depth` times,
    /// through `layer` clip-mapped surfaces): `Scene::shade_at_depth` for every lane at once,
    /// what lies behind a clip map blended in.
    #[allow(clippy::too_many_arguments, clippy::too_many_lines)]
    #[inline(always)]
    pub(super) fn shade_object<S: Simd>(
        &self,
        s: S,
        k: usize,
        rays: &Rays<S>,
        hits: &Hits<S>,
        mine: M<S>,
        diffs: Option<&Diffs>,
        depth: u32,
        layer: u32,
    ) -> (C3<S>, [u32; MAX_LANES]) {
        let obj = &self.objects[k];
        let material = &self.materials[obj.material];
        let texture = material.texture();
        let surface = &self.surfaces[k];
        let view = self.settings.view;
        let mut r = Self::resolve_lanes(s, obj, hits, &rays.d);
        let filtered = diffs.is_some() && texture.needs_differentials();
        // A filtered image under a built-in mapping is read in lanes, without per-lane records.
        let in_lanes = match diffs {
            Some(d) if filtered => Self::filtered_in_lanes(obj, texture).map(|(t, m)| (t, m, d)),
            _ => None,
        };
        let clip = surface.clip.as_ref().filter(|_| self.has_clips);
        let perturbation = surface
            .perturbation
            .as_ref()
            .filter(|_| self.has_perturbations);
        // Textured coefficients and colours are read in lanes where each is an image under a
        // built-in mapping of a generic shape (`LaneParams`); others need the per-lane records.
        let textured = material.has_textured_params()
            && !material.textured_params_all(|t| Self::filtered_in_lanes(obj, t).is_some());
        // A mirror's ray is made in lanes; its ray differentials per lane (`Scene::mirror_ray`).
        let reflective = matches!(material, crate::material::Material::Reflective { .. });
        let needs_lanes = (filtered && in_lanes.is_none())
            || clip.is_some()
            || perturbation.is_some_and(|p| !self.perturbation_in_lanes(k, p))
            || textured
            || (reflective && diffs.is_some())
            || view != View::Shaded;
        let mut per = needs_lanes.then(|| self.per_lane(s, k, hits, &r, mine, diffs));
        let flags = mask_to_array(s, mine);
        let key = (k as u32 + 1) & 0xffff | u32::from(filtered) << 31;
        let mut keys = [key; MAX_LANES];
        let offset = Self::offset_lanes(s, obj, &r.p);

        // A clip map's alpha per lane; lanes it leaves wholly transparent are not shaded.
        let mut alpha = [1.0_f32; MAX_LANES];
        let mut shade_on = mine;
        if let (Some(clip), Some(per)) = (clip, &per) {
            for i in 0..S::F32_LANES {
                if flags[i] {
                    alpha[i] = clip.eval(&per.ctx[i]).clamp(0.0, 1.0);
                }
            }
            let gone: [bool; MAX_LANES] = crate::math::lanes::each_lane(|i| alpha[i] <= 0.0);
            shade_on = s.and_m32s(mine, s.not_m32s(mask_from_array(s, &gone)));
        }
        let on = mask_to_array(s, shade_on);

        // Per-lane values of the lanes being shaded.
        let each = |f: &dyn Fn(usize) -> Rgb| -> C3<S> {
            let mut c = [[0.0; MAX_LANES]; 3];
            for i in 0..S::F32_LANES {
                if on[i] {
                    let v = f(i);
                    (c[0][i], c[1][i], c[2][i]) = (v.0, v.1, v.2);
                }
            }
            crate::math::lanes::map3(c, |a| from_array::<S>(&a))
        };

        let mut l = if let (true, Some(p)) = (
            matches!(view, View::Uv | View::MipLevel | View::Difference),
            &per,
        ) {
            // Debug views that show the texture alone.
            let compare = self.settings.compare;
            each(&|i| {
                if view == View::Difference {
                    texture.difference_view_color(&p.ctx[i], compare)
                } else {
                    texture.debug_color(&p.ctx[i], view, Rgb::BLACK)
                }
            })
        } else {
            let mut mapped = None;
            let cd = if let Some((t, m, d)) = in_lanes {
                let (c, at) = self.filtered_lanes(s, obj, t, m, hits, Some(d), shade_on);
                mapped = Some((m, at));
                c
            } else if let (Some(p), true) = (&per, filtered) {
                each(&|i| texture.eval(&p.ctx[i]))
            } else {
                let q = Self::mapping_point(s, obj, &hits.p);
                Self::texels_lanes(s, obj, texture, hits, &q, shade_on)
            };
            let params = LaneParams {
                s,
                per: per.as_deref(),
                on,
                scene: self,
                obj,
                hits,
                diffs,
                mask: shade_on,
                mapped: std::cell::RefCell::new(mapped),
            };
            let terms = material.terms(s, &cd, self.ambient, &params);
            // A bump or normal map tilts the shading normal.
            if let Some(p) = perturbation {
                self.perturb_lanes(s, k, p, hits, &mut r, per.as_deref_mut(), diffs, &on);
            }
            if terms.lit {
                let mut l = self.direct_lanes(s, k, &terms, &r, shade_on, offset, &mut keys);
                if let (Some((m, mirrors)), true) =
                    (terms.mirror, depth < self.settings.reflection_depth)
                {
                    let bounce = s.and_m32s(shade_on, mirrors);
                    // (A mirror with ray differentials makes the lanes' records.)
                    let seen = match (crate::math::lanes::any(s, bounce), diffs, &per) {
                        (true, None, _) => Some(self.mirrored_lanes(s, &r, bounce, offset, depth)),
                        (true, Some(_), Some(pl)) => {
                            Some(self.reflected_lanes(s, pl, bounce, diffs, offset, depth))
                        }
                        _ => None,
                    };
                    if let Some(seen) = seen {
                        for c in 0..3 {
                            let add = s.add_f32s(l[c], s.mul_f32s(m[c], seen[c]));
                            l[c] = s.select_f32s(bounce, add, l[c]);
                        }
                    }
                }
                match (view, &per) {
                    (View::Shaded, _) | (_, None) => l,
                    (_, Some(pl)) => {
                        let la = crate::math::lanes::map3(l, to_array::<S>);
                        each(&|i| {
                            texture.debug_color(&pl.ctx[i], view, Rgb(la[0][i], la[1][i], la[2][i]))
                        })
                    }
                }
            } else {
                match (view, &per) {
                    (View::Shaded, _) | (_, None) => terms.base,
                    (_, Some(pl)) => {
                        let b = crate::math::lanes::map3(terms.base, to_array::<S>);
                        each(&|i| {
                            texture.debug_color(&pl.ctx[i], view, Rgb(b[0][i], b[1][i], b[2][i]))
                        })
                    }
                }
            }
        };

        // What lies behind a partly transparent surface, traced on and blended in.
        if clip.is_some() {
            let see_through: [bool; MAX_LANES] =
                crate::math::lanes::each_lane(|i| flags[i] && alpha[i] < 1.0);
            if see_through.contains(&true) {
                let behind = if layer + 1 < MAX_CLIP_LAYERS {
                    let on = mask_from_array(s, &see_through);
                    let through = Rays {
                        o: r.p
                            .add(s, &rays.d.normalize_or(s, Vec3A::ZERO).scale(s, offset)),
                        d: rays.d,
                        active: on,
                    };
                    self.radiance_nested(s, &through, diffs, depth, layer + 1)
                } else {
                    super::Traced {
                        rgb: splat_rgb(s, Rgb::BLACK),
                        keys: [0; MAX_LANES],
                    }
                };
                let a = from_array::<S>(&alpha);
                let one_minus = s.sub_f32s(s.splat_f32s(1.0), a);
                let blend = mask_from_array(s, &see_through);
                let gone: [bool; MAX_LANES] =
                    crate::math::lanes::each_lane(|i| see_through[i] && alpha[i] <= 0.0);
                let gone_m = mask_from_array(s, &gone);
                for c in 0..3 {
                    let mixed =
                        s.add_f32s(s.mul_f32s(l[c], a), s.mul_f32s(behind.rgb[c], one_minus));
                    let v = s.select_f32s(gone_m, behind.rgb[c], mixed);
                    l[c] = s.select_f32s(blend, v, l[c]);
                }
                for i in 0..S::F32_LANES {
                    if gone[i] {
                        keys[i] = behind.keys[i];
                    }
                }
            }
        }
        (l, keys)
    }

    /// The radiance the mirrors of lanes `bounce` reflect where the rays carry no
    /// differentials: each lane's mirrored ray (`mirror_lanes`, which `Scene::mirror_ray` runs
    /// at width 1), traced as a packet one bounce deeper.
    #[inline(always)]
    fn mirrored_lanes<S: Simd>(
        &self,
        s: S,
        r: &Resolved<S>,
        bounce: M<S>,
        offset: F<S>,
        depth: u32,
    ) -> C3<S> {
        let (o, d) = mirror_lanes(s, &r.p, &r.ng, &r.ns, &r.wo, offset);
        let rays = Rays {
            o,
            d,
            active: bounce,
        };
        self.radiance_nested(s, &rays, None, depth + 1, 0).rgb
    }

    /// The radiance the mirrors of lanes `bounce` reflect: each lane's mirrored ray and ray
    /// differentials (`Scene::mirror_ray`, per lane), traced as a packet one bounce deeper.
    #[inline(always)]
    fn reflected_lanes<S: Simd>(
        &self,
        s: S,
        pl: &PerLane,
        bounce: M<S>,
        diffs: Option<&Diffs>,
        offset: F<S>,
        depth: u32,
    ) -> C3<S> {
        let on = mask_to_array(s, bounce);
        let off = lanes::<S>(offset);
        let (mut o, mut d) = ([[0.0; MAX_LANES]; 3], [[0.0; MAX_LANES]; 3]);
        let blank = RayDifferential {
            rx_origin: Vec3A::ZERO,
            rx_dir: Vec3A::Z,
            ry_origin: Vec3A::ZERO,
            ry_dir: Vec3A::Z,
        };
        let mut mirrored = [blank; MAX_LANES];
        for i in 0..S::F32_LANES {
            if !on[i] {
                continue;
            }
            let (ray, md): (Ray, Option<RayDifferential>) =
                self.mirror_ray(&pl.hits[i], diffs.map(|d| &d[i]), off[i]);
            (o[0][i], o[1][i], o[2][i]) = (ray.origin.x, ray.origin.y, ray.origin.z);
            (d[0][i], d[1][i], d[2][i]) = (ray.dir.x, ray.dir.y, ray.dir.z);
            if let Some(md) = md {
                mirrored[i] = md;
            }
        }
        let rays = Rays {
            o: V3::from_arrays(&o),
            d: V3::from_arrays(&d),
            active: bounce,
        };
        let nested = self.radiance_nested(s, &rays, diffs.map(|_| &mirrored), depth + 1, 0);
        nested.rgb
    }
}
