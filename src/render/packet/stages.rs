//! One packet traced in the stages of the scalar path, each named after its scalar twin:
//! [`PacketPlan::nearest_hit`] (`Scene::intersect`), [`PacketPlan::material_terms`]
//! (`Scene::resolve` and `Material::shade_point`), [`facing`] (the two-sided normal),
//! [`PacketPlan::direct_light`] (`Scene::shade_at_depth`'s light loop and shadow rays) and
//! [`finish`] (the glow and the finiteness check). Each stage computes lane-wise what its twin
//! computes per ray, operation for operation, so the films are bit-identical.

// Lane loops index several arrays by the lane (`for i in 0..LANES`), the form the vectoriser
// reads best; `&` and `|` between lane conditions keep them branch-free (selects, not jumps).
#![allow(clippy::needless_range_loop, clippy::needless_bitwise_bool)]

use super::super::lanes::{self, F, LANES, M, V3, splat};
use super::nearest::map_lanes;
use super::{Kind, PacketPlan, Response};
use crate::mapping::TexCoord;
use crate::material::{Light, ShadePoint};
use crate::math::{Ray, Rgb, Vec2, Vec3A};
use crate::scene::SHADOW_OFFSET_RELATIVE;
use crate::texture::TextureContext;

/// Three colour channels per lane.
type C3 = [F; 3];

/// The nearest hit per lane: the object's index (`u32::MAX` for a miss) and the object-space
/// point and normal.
struct Hits {
    object: [u32; LANES],
    point: V3,
    normal: V3,
}

/// What the material says at each shaded lane's hit, in world space.
struct Terms {
    /// World-space point and geometric normal (`Scene::resolve`).
    p: V3,
    ng: V3,
    /// The ambient term (or the emission), then the terms each light scales.
    base: C3,
    diffuse: C3,
    spec: C3,
    exponent: F,
    has_spec: M,
    glow: C3,
    /// Lanes whose material is lit (matte or Phong).
    lit_material: M,
    /// The object's translation's largest coordinate, for the shadow offset.
    trans: F,
    self_shadowing_sphere: M,
    /// Lanes whose texture was filtered over the pixel's footprint (the edge key's bit 31).
    prefiltered: M,
}

/// The direction toward the viewer and the normal turned to face it.
struct Facing {
    wo: V3,
    n: V3,
    front: M,
}

impl PacketPlan<'_> {
    /// Traces one packet: film positions `px`, `py` for the `active` lanes, the explicit
    /// kernels at `s`'s width. Returns the radiance (r, g, b per lane), the edge keys, and the
    /// lanes the scalar path must trace instead.
    #[inline(always)]
    pub(crate) fn trace<S: pulp::Simd>(
        &self,
        s: S,
        px: &F,
        py: &F,
        cells: &[Vec2; LANES],
        active: M,
    ) -> (C3, [u32; LANES], M) {
        let (o, d) = self.camera_rays(px, py);
        let hits = self.nearest_hit(s, &o, &d, active);

        // Background for misses; the scalar path for lanes whose object it must shade.
        let bg = self.scene.settings.background;
        let mut rgb = [splat(bg.0), splat(bg.1), splat(bg.2)];
        let mut fallback = [false; LANES];
        let mut shaded = [false; LANES];
        for i in 0..LANES {
            if hits.object[i] != u32::MAX {
                let has = self.objects[hits.object[i] as usize].shading.is_some();
                fallback[i] = !has;
                shaded[i] = has;
            }
        }
        if !shaded.contains(&true) {
            return (rgb, [0; LANES], fallback);
        }
        let terms = self.material_terms(s, &hits, shaded, (px, py, cells));
        let facing = facing(&d, terms.ng);
        let (l, lit, keys) = self.direct_light(s, &hits, &terms, &facing, shaded);
        finish(&mut rgb, shaded, &terms.glow, &l, &lit);
        (rgb, keys, fallback)
    }

    /// The nearest hit over the objects, in preset order (`Scene::intersect`): the explicit
    /// sphere and selects at `s`'s width, the lane loops where `s` is pulp's `Scalar`.
    #[inline(always)]
    fn nearest_hit<S: pulp::Simd>(&self, s: S, o: &V3, d: &V3, active: M) -> Hits {
        let mut t_best = [0.0_f32; LANES];
        for i in 0..LANES {
            t_best[i] = if active[i] { f32::INFINITY } else { 0.0 };
        }
        let mut object = [u32::MAX; LANES];
        let mut lp = V3::splat(Vec3A::ZERO);
        let mut ln = V3::splat(Vec3A::Y);
        for (k, ob) in self.objects.iter().enumerate() {
            let (oo, od) = if ob.identity {
                (*o, *d)
            } else {
                (
                    o.point(&ob.object_from_world),
                    d.linear(&ob.object_from_world.matrix3),
                )
            };
            if !S::IS_SCALAR {
                use lanes::wide;
                let (t, p, n, hit) = match ob.kind {
                    Kind::Sphere => {
                        let (t, hit) = wide::sphere(s, &oo, &od, &t_best);
                        if !wide::any(hit) {
                            continue;
                        }
                        let p = lanes::sphere_point(&oo, &od, &t);
                        (t, p, p, hit)
                    }
                    Kind::Flat(f) => {
                        let (t, p, hit) = lanes::flat(&oo, &od, &t_best, f);
                        (t, p, V3::splat(Vec3A::Y), wide::mask(&hit))
                    }
                };
                t_best = wide::select(s, hit, &t, &t_best);
                object = wide::select_u32(s, hit, &[k as u32; LANES], &object);
                lp = wide::select_v3(s, hit, &p, &lp);
                ln = wide::select_v3(s, hit, &n, &ln);
                continue;
            }
            let (t, p, n, hit) = match ob.kind {
                Kind::Sphere => {
                    let (t, hit) = lanes::sphere(&oo, &od, &t_best);
                    if !hit.contains(&true) {
                        continue;
                    }
                    let p = lanes::sphere_point(&oo, &od, &t);
                    (t, p, p, hit)
                }
                Kind::Flat(f) => {
                    let (t, p, hit) = lanes::flat(&oo, &od, &t_best, f);
                    (t, p, V3::splat(Vec3A::Y), hit)
                }
            };
            for i in 0..LANES {
                let h = hit[i];
                t_best[i] = if h { t[i] } else { t_best[i] };
                object[i] = if h { k as u32 } else { object[i] };
                lp.x[i] = if h { p.x[i] } else { lp.x[i] };
                lp.y[i] = if h { p.y[i] } else { lp.y[i] };
                lp.z[i] = if h { p.z[i] } else { lp.z[i] };
                ln.x[i] = if h { n.x[i] } else { ln.x[i] };
                ln.y[i] = if h { n.y[i] } else { ln.y[i] };
                ln.z[i] = if h { n.z[i] } else { ln.z[i] };
            }
        }
        Hits {
            object,
            point: lp,
            normal: ln,
        }
    }

    /// World-space point and normal per lane (`Scene::resolve`), the (u, v) and the material's
    /// terms (`Material::shade_point`), object by object for the objects this packet hit.
    #[inline(always)]
    fn material_terms<S: pulp::Simd>(
        &self,
        s: S,
        hits: &Hits,
        shaded: M,
        samples: (&F, &F, &[Vec2; LANES]),
    ) -> Terms {
        let (lp, ln) = (&hits.point, &hits.normal);
        let mut t = Terms {
            p: *lp,
            ng: *ln,
            base: [[0.0; LANES]; 3],
            diffuse: [[0.0; LANES]; 3],
            spec: [[0.0; LANES]; 3],
            exponent: [0.0; LANES],
            has_spec: [false; LANES],
            glow: [[0.0; LANES]; 3],
            lit_material: [false; LANES],
            trans: [0.0; LANES],
            self_shadowing_sphere: [false; LANES],
            prefiltered: [false; LANES],
        };
        let ambient = self.scene.ambient;
        let amb = [ambient.0, ambient.1, ambient.2];
        for (k, ob) in self.objects.iter().enumerate() {
            let Some(sh) = &ob.shading else { continue };
            let mut mine = [false; LANES];
            for i in 0..LANES {
                mine[i] = shaded[i] && hits.object[i] == k as u32;
            }
            if !mine.contains(&true) {
                continue;
            }
            if !ob.identity {
                let wp = lp.point(&ob.world_from_object);
                let mut wn = ln.linear(&ob.normal_to_world);
                if !ob.normal_orthonormal {
                    wn = wn.normalize_or(Vec3A::Y);
                }
                for i in 0..LANES {
                    if mine[i] {
                        t.p.set_lane(i, wp.lane(i));
                        t.ng.set_lane(i, wn.lane(i));
                    }
                }
            }
            let tex = if sh.footprint {
                for i in 0..LANES {
                    t.prefiltered[i] |= mine[i];
                }
                self.footprint_texels(ob, sh, hits, samples, mine)
            } else {
                Self::texels(s, sh, lp, mine)
            };
            match sh.response {
                Response::Lit {
                    ka,
                    kd_pi,
                    specular,
                    glow: g,
                } => {
                    let g = [g.0, g.1, g.2];
                    let (s, e) = specular.map_or(([0.0; 3], 0.0), |(s, e)| ([s.0, s.1, s.2], e));
                    for c in 0..3 {
                        for i in 0..LANES {
                            let m = mine[i];
                            // c ambient ka and c (kd / pi), as `Material::shade_point`.
                            t.base[c][i] = if m {
                                tex[c][i] * amb[c] * ka
                            } else {
                                t.base[c][i]
                            };
                            t.diffuse[c][i] = if m {
                                tex[c][i] * kd_pi
                            } else {
                                t.diffuse[c][i]
                            };
                            t.spec[c][i] = if m { s[c] } else { t.spec[c][i] };
                            t.glow[c][i] = if m { g[c] } else { t.glow[c][i] };
                        }
                    }
                    for i in 0..LANES {
                        let m = mine[i];
                        t.exponent[i] = if m { e } else { t.exponent[i] };
                        t.has_spec[i] = if m { specular.is_some() } else { t.has_spec[i] };
                        t.lit_material[i] |= m;
                    }
                }
                Response::Emissive { ls } => {
                    for c in 0..3 {
                        for i in 0..LANES {
                            t.base[c][i] = if mine[i] {
                                tex[c][i] * ls
                            } else {
                                t.base[c][i]
                            };
                        }
                    }
                }
            }
            for i in 0..LANES {
                let m = mine[i];
                t.trans[i] = if m {
                    ob.translation_max_abs
                } else {
                    t.trans[i]
                };
                t.self_shadowing_sphere[i] |= m & (ob.kind == Kind::Sphere);
            }
        }
        t
    }

    /// The texture's colour at the lanes in `mine` (object-space points `lp`): (u, v) under the
    /// mapping and the (u, v) transform, then the lane-wise nearest lookup where it applies,
    /// else the scalar filter per lane (a gather).
    #[inline(always)]
    fn texels<S: pulp::Simd>(s: S, sh: &super::Shading, lp: &V3, mine: M) -> C3 {
        // A function, not a closure: a closure this size stays out of line, compiled for the
        // baseline instead of the dispatched level.
        #[allow(clippy::manual_map)]
        let uv = match sh.mapping {
            Some(m) => Some(map_lanes(s, m, sh.affine.as_ref(), lp, mine)),
            None => None,
        };
        let mut tex = [[0.0; LANES]; 3];
        if let (Some(n), Some((u, v))) = (&sh.nearest, &uv) {
            tex = n.sample(u, v, mine);
            if matches!(sh.mapping, Some(super::LaneMapping::Formula(..))) {
                // Where a formula is not finite: the mark, as `ImageTexture::eval` gives it.
                let mark = crate::texture::mark();
                for i in 0..LANES {
                    if mine[i] && (u[i].is_nan() || v[i].is_nan()) {
                        (tex[0][i], tex[1][i], tex[2][i]) = (mark.0, mark.1, mark.2);
                    }
                }
            }
        }
        for i in 0..LANES {
            if !mine[i] || (sh.nearest.is_some() & uv.is_some()) {
                continue;
            }
            let p = Vec3A::new(lp.x[i], lp.y[i], lp.z[i]);
            let c = match &uv {
                Some((u, v)) => sh.texture.eval_tex_coord(
                    TexCoord {
                        uv: Vec2::new(u[i], v[i]),
                        duvdx: Vec2::ZERO,
                        duvdy: Vec2::ZERO,
                    },
                    p,
                ),
                None => sh.texture.eval_tex_coord(TexCoord::default(), p),
            };
            (tex[0][i], tex[1][i], tex[2][i]) = (c.0, c.1, c.2);
        }
        tex
    }

    /// The texture's colour at the lanes in `mine` for a texture filtered over the pixel's
    /// footprint, per lane as `Scene::texture_context` and `Texture::eval` give it on the scalar
    /// path: the sample's ray differentials ([`crate::render::footprint_ray`]) in object space,
    /// their footprint on the plane tangent at the hit, the mapping with its gradients, the
    /// filter.
    #[inline(always)]
    fn footprint_texels(
        &self,
        ob: &super::ObjectPlan,
        sh: &super::Shading,
        hits: &Hits,
        (px, py, cells): (&F, &F, &[Vec2; LANES]),
        mine: M,
    ) -> C3 {
        let mut tex = [[0.0; LANES]; 3];
        for i in 0..LANES {
            if !mine[i] {
                continue;
            }
            let p = hits.point.lane(i);
            let n = hits.normal.lane(i);
            let pos = Vec2::new(px[i], py[i]);
            let (dpdx, dpdy) = match crate::render::footprint_ray(self.scene, pos, cells[i]) {
                Some((_, d)) => {
                    let d = if ob.identity {
                        d
                    } else {
                        d.transformed(&ob.object_from_world)
                    };
                    d.footprint_on_plane(p, n)
                }
                None => (Vec3A::ZERO, Vec3A::ZERO),
            };
            let ctx = TextureContext {
                p,
                dpdx,
                dpdy,
                shape_uv: None,
                natural: sh.natural,
            };
            // An image's read inlined here, so it is compiled for the dispatched level.
            let c = match sh.texture {
                crate::texture::Texture::Image(t) => t.eval(&ctx),
                t => t.eval(&ctx),
            };
            (tex[0][i], tex[1][i], tex[2][i]) = (c.0, c.1, c.2);
        }
        tex
    }

    /// Direct light (`Scene::shade_at_depth`): the ambient term, then each light that reaches
    /// the point past its shadow ray. Returns the radiance, the sum of the lit cosines (for the
    /// glow's weight) and the edge keys (object, and one bit per shadowing light).
    #[inline(always)]
    fn direct_light<S: pulp::Simd>(
        &self,
        s: S,
        hits: &Hits,
        t: &Terms,
        f: &Facing,
        shaded: M,
    ) -> (C3, F, [u32; LANES]) {
        let (p, ns, ng, wo) = (&t.p, &f.n, &f.n, &f.wo);
        let mut l = t.base;
        let pmax = p.max_abs();
        let mut offset = [0.0; LANES];
        let mut keys = [0_u32; LANES];
        for i in 0..LANES {
            offset[i] = SHADOW_OFFSET_RELATIVE * (pmax[i] + t.trans[i]).max(f32::MIN_POSITIVE);
            keys[i] = if shaded[i] {
                (hits.object[i] + 1) & 0xffff | u32::from(t.prefiltered[i]) << 31
            } else {
                0
            };
        }
        let mut lit = [0.0; LANES];
        if !t.lit_material.contains(&true) {
            return (l, lit, keys);
        }
        for (li, light) in self.scene.lights.iter().enumerate() {
            let (wi, dist, radiance, shadows) = to_light(light, p);
            let ndotwi = ns.dot(&wi);
            let gdotwi = ng.dot(&wi);
            let mut reach = [false; LANES];
            for i in 0..LANES {
                reach[i] = t.lit_material[i] && !(ndotwi[i] <= 0.0 || gdotwi[i] <= 0.0);
            }
            if shadows {
                for i in 0..LANES {
                    if !reach[i] {
                        continue;
                    }
                    // A sphere hit from outside cannot shadow itself, nor can a flat shape.
                    let k = hits.object[i] as usize;
                    let skip = if t.self_shadowing_sphere[i] && !f.front[i] {
                        usize::MAX
                    } else {
                        k
                    };
                    let origin = p.lane(i) + ng.lane(i) * offset[i];
                    let t_max = if dist[i].is_finite() {
                        dist[i] - offset[i]
                    } else {
                        f32::INFINITY
                    };
                    if self
                        .scene
                        .occluded_except(&Ray::new(origin, wi.lane(i)), t_max, skip)
                    {
                        keys[i] |= (1 << (16 + li.min(14))) as u32;
                        reach[i] = false;
                    }
                }
            }
            let mut pw = [0.0; LANES];
            if t.has_spec.contains(&true) {
                for i in 0..LANES {
                    // r = -wi + 2 (n . wi) n; the highlight where r . wo > 0.
                    let two = 2.0 * ndotwi[i];
                    let rx = -wi.x[i] + two * ns.x[i];
                    let ry = -wi.y[i] + two * ns.y[i];
                    let rz = -wi.z[i] + two * ns.z[i];
                    let rdotwo = (rx * wo.x[i] + ry * wo.y[i]) + rz * wo.z[i];
                    if reach[i] && t.has_spec[i] && rdotwo > 0.0 {
                        pw[i] = rdotwo.powf(t.exponent[i]);
                    }
                }
            }
            let li_c = [radiance.0, radiance.1, radiance.2];
            if !S::IS_SCALAR {
                lanes::wide::add_light(
                    s,
                    &reach,
                    &t.has_spec,
                    &pw,
                    &t.diffuse,
                    &t.spec,
                    li_c,
                    &ndotwi,
                    &mut l,
                    &mut lit,
                );
                continue;
            }
            lanes::add_light(
                &reach,
                &t.has_spec,
                &pw,
                &t.diffuse,
                &t.spec,
                li_c,
                &ndotwi,
                &mut l,
                &mut lit,
            );
        }
        (l, lit, keys)
    }
}

/// The direction to `light` from each lane's point `p`, the distance (infinite for a
/// directional light), the radiance and whether it casts shadows (`Light::incidence`).
#[inline(always)]
fn to_light(light: &Light, p: &V3) -> (V3, F, Rgb, bool) {
    let mut wi = V3::splat(Vec3A::ZERO);
    let mut dist = [f32::INFINITY; LANES];
    let (radiance, shadows) = match *light {
        Light::Directional {
            to_light,
            radiance,
            shadows,
        } => {
            wi = V3::splat(to_light);
            (radiance, shadows)
        }
        Light::Point {
            position,
            radiance,
            shadows,
        } => {
            let mut dv = *p;
            for i in 0..LANES {
                dv.x[i] = position.x - p.x[i];
                dv.y[i] = position.y - p.y[i];
                dv.z[i] = position.z - p.z[i];
            }
            let len2 = dv.dot(&dv);
            for i in 0..LANES {
                let dl = len2[i].sqrt();
                dist[i] = dl;
                let pos = dl > 0.0;
                wi.x[i] = if pos { dv.x[i] / dl } else { 0.0 };
                wi.y[i] = if pos { dv.y[i] / dl } else { 1.0 };
                wi.z[i] = if pos { dv.z[i] / dl } else { 0.0 };
            }
            (radiance, shadows)
        }
    };
    (wi, dist, radiance, shadows)
}

/// Two-sided surfaces shade the side the ray (directions `d`) came from: the normal `ng`
/// turned toward the viewer, and which lanes see the front.
#[inline(always)]
fn facing(d: &V3, mut ng: V3) -> Facing {
    let mut wo = *d;
    for i in 0..LANES {
        wo.x[i] = -d.x[i];
        wo.y[i] = -d.y[i];
        wo.z[i] = -d.z[i];
    }
    let wo = wo.normalize_or(Vec3A::Z);
    let cos = ng.dot(&wo);
    let mut front = [true; LANES];
    for i in 0..LANES {
        let back = cos[i] < 0.0;
        front[i] = !back;
        ng.x[i] = if back { -ng.x[i] } else { ng.x[i] };
        ng.y[i] = if back { -ng.y[i] } else { ng.y[i] };
        ng.z[i] = if back { -ng.z[i] } else { ng.z[i] };
    }
    Facing { wo, n: ng, front }
}

/// The shaded lanes' radiance `l` plus the glow weighted by the lit cosines `lit`
/// (`ShadePoint::glow_weight`), black where not finite, into `rgb`.
#[inline(always)]
fn finish(rgb: &mut C3, shaded: M, glow: &C3, l: &C3, lit: &F) {
    for i in 0..LANES {
        if !shaded[i] {
            continue;
        }
        let g = Rgb(glow[0][i], glow[1][i], glow[2][i]);
        let mut v = Rgb(l[0][i], l[1][i], l[2][i]);
        if g != Rgb::BLACK {
            v += g * ShadePoint::glow_weight(lit[i]);
        }
        if !v.is_finite() {
            v = Rgb::BLACK;
        }
        (rgb[0][i], rgb[1][i], rgb[2][i]) = (v.0, v.1, v.2);
    }
}
