//! The immutable runtime [`Scene`] the renderer traces: intersection, the hit resolved in world
//! space, its texture context, and the lecture's shading with shadows, clip maps, bump and normal
//! maps and mirrors.

use super::settings::RenderSettings;
use crate::camera::Camera;
use crate::geometry::{LocalHit, Object, Shape};
use crate::mapping::Mapping;
use crate::material::{Bump, Light, Material, NormalMap, Scalar};
use crate::math::lanes::{F, V3};
use crate::math::{Ray, RayDifferential, Rgb, Vec3A, max_abs};
use crate::texture::TextureContext;
use pulp::Simd;

/// Shadow-ray origins are pushed off the surface along its geometric normal by this fraction of
/// the magnitude of the coordinates involved (hit point and the object's translation): about a
/// hundred f32 ulps of the numbers the hit point was computed from. Hit points are reprojected
/// onto the exact surface in object space, so the only error left is that of the transform,
/// which scales the same way: the offset is scale-invariant (the same scene scaled by 1e-3 or
/// 1e3 shadows the same) and clears self-intersection ("shadow acne").
pub const SHADOW_OFFSET_RELATIVE: f32 = 1e-5;

/// An immutable, ready-to-trace scene.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The objects with their world transforms, in preset order; [`SurfaceHit::object`]
    /// indexes this.
    pub objects: Vec<Object>,
    /// Materials, indexed by `Object::material`.
    pub materials: Vec<Material>,
    /// Directional and point lights.
    pub lights: Vec<Light>,
    /// Ambient radiance, linear (`ambient.ls * ambient.color` of the preset).
    pub ambient: Rgb,
    /// Makes the primary rays, for a film of `settings.width` x `settings.height` pixels.
    pub camera: Camera,
    /// Resolution, sampling, exposure and view, checked against their ranges.
    pub settings: RenderSettings,
    /// Per object (as `objects`), what its surface adds to its shape and material: a clip map
    /// and a bump or normal map.
    pub surfaces: Vec<Surface>,
    /// Whether any texture needs ray differentials (computed only then).
    pub(crate) needs_differentials: bool,
    /// Whether any object has a clip map; without one every ray takes the solid-surface path.
    pub(crate) has_clips: bool,
    /// Whether any object has a bump or normal map; without one no hit looks them up.
    pub(crate) has_perturbations: bool,
}

/// How an object's shading normal is tilted: by a bump map or by a normal map, never both (a
/// preset naming both is refused when the scene is built).
#[derive(Clone, Debug)]
pub enum Perturbation {
    /// Height slopes through the mapping's gradients.
    Bump(Bump),
    /// Tangent-space normals read from an image.
    Normal(NormalMap),
}

impl Perturbation {
    /// The texture it reads: the height field or the normals.
    #[must_use]
    pub const fn texture(&self) -> &crate::texture::Texture {
        match self {
            Self::Bump(b) => &b.height,
            Self::Normal(n) => &n.map,
        }
    }

    /// Whether its texture needs ray differentials.
    #[must_use]
    pub fn needs_differentials(&self) -> bool {
        match self {
            Self::Bump(b) => b.height.needs_differentials(),
            Self::Normal(n) => n.map.needs_differentials(),
        }
    }
}

/// What an object's surface adds to its shape and material.
#[derive(Clone, Debug, Default)]
pub struct Surface {
    /// Where the surface exists (alpha), unless it is solid everywhere.
    pub clip: Option<Scalar>,
    /// Its bump or normal map, if any.
    pub perturbation: Option<Perturbation>,
}

impl Scene {
    /// Whether any texture needs ray differentials (a footprint filter or a debug view that
    /// shows one): rays then carry their differentials.
    #[must_use]
    pub const fn needs_differentials(&self) -> bool {
        self.needs_differentials
    }

    /// Whether any object has a clip map.
    #[must_use]
    pub const fn has_clips(&self) -> bool {
        self.has_clips
    }

    /// Whether any object has a bump or normal map.
    #[must_use]
    pub const fn has_perturbations(&self) -> bool {
        self.has_perturbations
    }
}

/// The most clip-mapped surfaces one ray (or shadow ray) passes through before it stops: what
/// lies behind more than this many partly transparent layers is taken as black (or, for a
/// shadow ray, as blocked).
pub const MAX_CLIP_LAYERS: u32 = 16;

/// A hit resolved in world space, with what the shading step needs.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    /// Index of the object hit.
    pub object: usize,
    /// The hit in object space.
    pub local: LocalHit,
    /// World-space hit point.
    pub p: Vec3A,
    /// World-space geometric normal, facing the incoming ray.
    pub ng: Vec3A,
    /// World-space shading normal, on the same side as `ng`.
    pub ns: Vec3A,
    /// Unit vector toward the viewer.
    pub wo: Vec3A,
    /// Whether the ray met the outside of the surface (its outward normal faced the ray); a
    /// sphere or capped cylinder hit from inside has this false.
    pub front_face: bool,
}

impl Scene {
    /// The nearest object hit by `ray` within (0, `t_max`): the kernel's nearest-hit stage at
    /// width 1.
    #[must_use]
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(usize, LocalHit)> {
        use crate::math::lanes::{V3, to_array};
        let s = pulp::Scalar;
        let rays = super::kernel::Rays {
            o: V3::one(ray.origin),
            d: V3::one(ray.dir),
            active: true,
        };
        let h = self.nearest_lanes_within(s, &rays, t_max);
        h.hit.then(|| {
            let local = h.local(
                0,
                &h.p.to_arrays(),
                &h.n.to_arrays(),
                &h.ns.to_arrays(),
                &to_array::<pulp::Scalar>(h.t),
            );
            (h.object[0] as usize, local)
        })
    }

    /// Whether anything that casts shadows lies on `ray` within (0, `t_max`).
    #[must_use]
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.objects
            .iter()
            .any(|o| o.casts_shadows && o.occludes(ray, t_max))
    }

    /// Whether anything that casts shadows, other than object `skip`, lies on `ray` within
    /// (0, `t_max`).
    #[must_use]
    #[inline]
    pub fn occluded_except(&self, ray: &Ray, t_max: f32, skip: usize) -> bool {
        self.objects
            .iter()
            .enumerate()
            .any(|(i, o)| i != skip && o.casts_shadows && o.intersect(ray, t_max).is_some())
    }

    /// Finds the nearest hit and resolves it in world space.
    #[must_use]
    #[inline]
    pub fn hit(&self, ray: &Ray) -> Option<SurfaceHit> {
        let (object, local) = self.intersect(ray, f32::INFINITY)?;
        Some(self.resolve(object, local, ray))
    }

    /// An object-space hit of `object` by `ray` resolved in world space.
    #[must_use]
    #[inline]
    pub fn resolve(&self, object: usize, local: LocalHit, ray: &Ray) -> SurfaceHit {
        let obj = &self.objects[object];
        let p = obj.point_to_world(local.p);
        let mut ng = obj.normal_to_world(local.n);
        let mut ns = if local.ns == local.n {
            ng
        } else {
            obj.normal_to_world(local.ns)
        };
        let wo = (-ray.dir).normalize_or(Vec3A::Z);
        // Two-sided surfaces: shade the side the ray came from.
        let back_face = ng.dot(wo) < 0.0;
        if back_face {
            ng = -ng;
            ns = -ns;
        }
        SurfaceHit {
            object,
            local,
            p,
            ng,
            ns,
            wo,
            front_face: !back_face,
        }
    }

    /// The texture context of a hit: object-space point and, when a filter needs them, the
    /// object-space offsets to the neighbouring pixels' hits.
    #[must_use]
    #[inline(always)]
    pub fn texture_context(
        &self,
        hit: &SurfaceHit,
        diff: Option<&RayDifferential>,
    ) -> TextureContext {
        let (dpdx, dpdy) =
            self.footprint_at(&self.objects[hit.object], diff, hit.local.p, hit.local.n);
        self.texture_context_at(hit, dpdx, dpdy)
    }

    /// The object-space offsets from the object-space hit `p` (normal `n`) of `obj` to the
    /// neighbouring pixels' hits on its tangent plane, from the ray differentials `diff`
    /// (zero without them, or when no filter needs a footprint).
    #[must_use]
    #[inline(always)]
    pub(crate) fn footprint_at(
        &self,
        obj: &Object,
        diff: Option<&RayDifferential>,
        p: Vec3A,
        n: Vec3A,
    ) -> (Vec3A, Vec3A) {
        match diff {
            Some(d) if self.needs_differentials => {
                let d = if obj.identity {
                    *d
                } else {
                    d.transformed(&obj.object_from_world)
                };
                d.footprint_on_plane(p, n)
            }
            _ => (Vec3A::ZERO, Vec3A::ZERO),
        }
    }

    /// The texture context of a hit given the object-space offsets `dpdx`, `dpdy` to the
    /// neighbouring pixels' hits (zero: no footprint). A mesh's dp/du and dp/dv are computed
    /// here, and only when there is a footprint to map through them.
    #[must_use]
    #[inline]
    pub fn texture_context_at(&self, hit: &SurfaceHit, dpdx: Vec3A, dpdy: Vec3A) -> TextureContext {
        let obj = &self.objects[hit.object];
        let footprint = dpdx != Vec3A::ZERO || dpdy != Vec3A::ZERO;
        let dpduv = match (&obj.shape, hit.local.dpduv) {
            (Shape::Mesh(m), None) if footprint => m.mesh.uv_derivatives(hit.local.prim),
            (_, d) => d,
        };
        let mut ctx = TextureContext {
            p: hit.local.p,
            dpdx,
            dpdy,
            shape_uv: hit.local.uv.map(|uv| (uv, dpduv)),
            natural: natural_mapping(&obj.shape),
        };
        if let Shape::Mesh(m) = &obj.shape {
            // Generated mappings see the model fitted into the generic objects' [-1, 1]^3.
            let (p, s) = m.mesh.to_mapping_frame(ctx.p);
            ctx.p = p;
            ctx.dpdx *= s;
            ctx.dpdy *= s;
            ctx.shape_uv = ctx
                .shape_uv
                .map(|(uv, d)| (uv, d.map(|(du, dv)| (du * s, dv * s))));
        }
        ctx
    }

    /// Radiance along a camera ray: the lecture's shading (ambient + direct light with shadows,
    /// or emission), no global illumination. Never NaN or infinite.
    #[must_use]
    #[inline]
    pub fn trace(&self, ray: &Ray, diff: Option<&RayDifferential>) -> Rgb {
        self.trace_keyed(ray, diff).0
    }

    /// Like [`Scene::trace`], with an edge key for adaptive sampling: neighbouring pixels
    /// whose keys differ straddle an object or shadow edge. The key holds the object hit
    /// (0 for the background) in the low 16 bits, one bit per light whose shadow ray was
    /// blocked above them, and in bit 31 whether the texture there was filtered over the pixel's
    /// footprint (so its contrast is already antialiased). The render kernel at width 1
    /// ([`Scene::trace_lanes`]).
    #[must_use]
    #[inline]
    pub fn trace_keyed(&self, ray: &Ray, diff: Option<&RayDifferential>) -> (Rgb, u32) {
        self.radiance_one(ray, diff, 0, true)
    }

    /// Radiance along a ray that has already been mirrored `depth` times (0 for a camera ray),
    /// not made finite.
    pub(crate) fn trace_at_depth(
        &self,
        ray: &Ray,
        diff: Option<&RayDifferential>,
        depth: u32,
    ) -> Rgb {
        self.radiance_one(ray, diff, depth, false).0
    }

    /// The shading normal of `hit` after its object's bump or normal map, or `None` if it has
    /// neither (the common case: one flag tested, no per-object lookup).
    #[inline]
    pub(crate) fn perturbed_normal_at(
        &self,
        hit: &SurfaceHit,
        ctx: &TextureContext,
    ) -> Option<Vec3A> {
        if !self.has_perturbations {
            return None;
        }
        match &self.surfaces[hit.object].perturbation {
            Some(Perturbation::Bump(b)) => Some(self.bumped_normal(hit, b, ctx)),
            Some(Perturbation::Normal(m)) => Some(self.normal_mapped(hit, m, ctx)),
            None => None,
        }
    }

    /// The world shading normal of `hit` tilted by bump map `b`: on the viewer's side of the
    /// surface, and, if the tilt would turn it away from the viewer (which would shade black),
    /// bent back until it faces the viewer just enough (pbrt's fix for shading normals).
    #[must_use]
    #[inline(never)]
    pub fn bumped_normal(&self, hit: &SurfaceHit, b: &Bump, ctx: &TextureContext) -> Vec3A {
        self.perturbed_normal(hit, |n| b.perturb(ctx, n))
    }

    /// The world shading normal of `hit` read from normal map `m`, on the viewer's side as
    /// [`Scene::bumped_normal`]'s.
    #[must_use]
    #[inline(never)]
    pub fn normal_mapped(&self, hit: &SurfaceHit, m: &NormalMap, ctx: &TextureContext) -> Vec3A {
        self.perturbed_normal(hit, |n| m.perturb(ctx, n))
    }

    /// The world shading normal of `hit` after `perturb` turns its object-space normal: on the
    /// viewer's side, bent back towards the viewer if it would face away.
    fn perturbed_normal(&self, hit: &SurfaceHit, perturb: impl Fn(Vec3A) -> Vec3A) -> Vec3A {
        let obj = &self.objects[hit.object];
        let n_local = if hit.local.ns == hit.local.n {
            hit.local.n
        } else {
            hit.local.ns
        };
        let tilted = perturb(n_local);
        Self::tilted_to_world(obj, n_local, tilted, hit.ns, hit.wo, hit.front_face)
    }

    /// The world shading normal of a hit of `obj` whose object-space normal `n_local` a bump
    /// or normal map turned to `tilted` (`ns`, `wo` and `front` the hit's shading normal,
    /// direction to the viewer and side): `ns` itself if nothing turned, else on the viewer's
    /// side, bent back towards the viewer if it would face away.
    #[must_use]
    #[inline(always)]
    pub(crate) fn tilted_to_world(
        obj: &Object,
        n_local: Vec3A,
        tilted: Vec3A,
        ns: Vec3A,
        wo: Vec3A,
        front: bool,
    ) -> Vec3A {
        if tilted == n_local {
            return ns;
        }
        let side = if front { 1.0 } else { -1.0 };
        let mut n = (obj.normal_to_world(tilted) * side).normalize_or(ns);
        let facing = n.dot(wo);
        if facing < 1e-3 {
            n = (n + (1e-3 - facing) * wo).normalize_or(ns);
        }
        if n.is_finite() { n } else { ns }
    }

    /// How far rays leave a hit point: [`SHADOW_OFFSET_RELATIVE`] of the coordinates' size.
    #[inline]
    pub(crate) fn offset_at(&self, hit: &SurfaceHit) -> f32 {
        let obj = &self.objects[hit.object];
        SHADOW_OFFSET_RELATIVE
            * (max_abs(hit.p) + max_abs(obj.world_from_object.translation)).max(f32::MIN_POSITIVE)
    }

    /// The share of light that passes along a shadow ray within (0, `t_max`), ignoring object
    /// `skip`: 0 behind a solid occluder, `1 - alpha` through each clip-mapped surface met
    /// (its alpha point-sampled where the ray crosses it), so a cut-out casts a cut-out shadow.
    #[must_use]
    pub fn transmittance(&self, ray: &Ray, t_max: f32, skip: usize) -> f32 {
        let mut tr = 1.0;
        for (i, o) in self.objects.iter().enumerate() {
            if i == skip || !o.casts_shadows {
                continue;
            }
            let Some(clip) = &self.surfaces[i].clip else {
                if o.intersect(ray, t_max).is_some() {
                    return 0.0;
                }
                continue;
            };
            let mut r = *ray;
            let mut t_left = t_max;
            for _ in 0..MAX_CLIP_LAYERS {
                let Some(h) = o.intersect(&r, t_left) else {
                    break;
                };
                let hit = self.resolve(i, h, &r);
                let ctx = self.texture_context_at(&hit, Vec3A::ZERO, Vec3A::ZERO);
                tr *= 1.0 - clip.eval(&ctx).clamp(0.0, 1.0);
                if tr <= 0.0 {
                    return 0.0;
                }
                let origin = hit.p + r.dir.normalize_or_zero() * self.offset_at(&hit);
                let len = r.dir.length();
                if len <= 0.0 {
                    break;
                }
                t_left -= (origin - r.origin).length() / len;
                if t_left <= 0.0 {
                    break;
                }
                r = Ray::new(origin, r.dir);
            }
        }
        tr
    }
}

impl Scene {
    /// The ray a mirror at `hit` reflects the viewer's ray into, `wi = 2 (n . wo) n - wo` about
    /// the shading normal, leaving `offset` off the surface on the side it goes to; and, when
    /// the hit carries ray differentials, the mirrored differentials (pbrt's specular
    /// reflection differentials).
    pub(crate) fn mirror_ray(
        &self,
        hit: &SurfaceHit,
        diff: Option<&RayDifferential>,
        offset: f32,
    ) -> (Ray, Option<RayDifferential>) {
        let (n, wo) = (hit.ns, hit.wo);
        let cos = n.dot(wo);
        let one = V3::<pulp::Scalar>::one;
        let (origin, wi) = mirror_lanes(
            pulp::Scalar,
            &one(hit.p),
            &one(hit.ng),
            &one(n),
            &one(wo),
            offset,
        );
        let (origin, wi) = (origin.vec(), wi.vec());
        let ray = Ray::new(origin, wi);
        let mirrored = diff.map(|d| {
            let (dpdx, dpdy) = d.footprint_on_plane(hit.p, hit.ng);
            let mirror = |dp: Vec3A, dir: Vec3A| {
                let dn = self.normal_change(hit, dp);
                let dwo = -dir.normalize_or(-wo) - wo;
                let ddn = dwo.dot(n) + wo.dot(dn);
                let dir = wi - dwo + 2.0 * (cos * dn + ddn * n);
                (hit.p + dp, if dir.is_finite() { dir } else { wi })
            };
            let (rx_origin, rx_dir) = mirror(dpdx, d.rx_dir);
            let (ry_origin, ry_dir) = mirror(dpdy, d.ry_dir);
            RayDifferential {
                rx_origin,
                rx_dir,
                ry_origin,
                ry_dir,
            }
        });
        (ray, mirrored)
    }

    /// The change of the world shading normal from `hit` to the point `dp` away on its tangent
    /// plane: exact for spheres and cylinder walls (whose normals follow the point), zero for
    /// flat shapes and meshes (flat per triangle; smooth meshes are treated as flat here).
    fn normal_change(&self, hit: &SurfaceHit, dp: Vec3A) -> Vec3A {
        let obj = &self.objects[hit.object];
        let q = hit.local.p + obj.object_from_world.transform_vector3a(dp);
        let local = match obj.shape {
            Shape::Sphere => q,
            Shape::Cylinder { .. } if hit.local.n.y.abs() < 0.5 => Vec3A::new(q.x, 0.0, q.z),
            _ => return Vec3A::ZERO,
        };
        let side = if hit.front_face { 1.0 } else { -1.0 };
        let n = (obj.normal_to_world(local.normalize_or(hit.local.n)) * side).normalize_or(hit.ns);
        let dn = n - hit.ns;
        if dn.is_finite() { dn } else { Vec3A::ZERO }
    }
}

/// The ray a mirror reflects the viewer's ray into, per lane: from the point `p` with
/// geometric normal `ng` and shading normal `ns`, seen from `wo`, the direction
/// `wi = 2 (ns . wo) ns - wo` (`ng` where that has no length) and the origin `offset` off the
/// surface on the side `wi` goes to. [`Scene::mirror_ray`] is its width-1 instance.
#[inline(always)]
pub(crate) fn mirror_lanes<S: Simd>(
    s: S,
    p: &V3<S>,
    ng: &V3<S>,
    ns: &V3<S>,
    wo: &V3<S>,
    offset: F<S>,
) -> (V3<S>, V3<S>) {
    let cos = ns.dot(s, wo);
    let wi = ns
        .scale(s, s.mul_f32s(s.splat_f32s(2.0), cos))
        .sub(s, wo)
        .normalize_or_lanes(s, ng);
    // Leave on the side the reflected ray goes to.
    let ahead = s.greater_than_or_equal_f32s(wi.dot(s, ng), s.splat_f32s(0.0));
    let side = s.select_f32s(ahead, s.splat_f32s(1.0), s.splat_f32s(-1.0));
    (p.add(s, &ng.scale(s, s.mul_f32s(offset, side))), wi)
}

/// The shape's own parameterisation, which [`Mapping::Uv`] falls back to.
#[must_use]
pub const fn natural_mapping(shape: &Shape) -> Mapping {
    match shape {
        Shape::Sphere | Shape::Mesh(_) => Mapping::Spherical,
        Shape::Cylinder { .. } => Mapping::Cylindrical,
        Shape::Plane | Shape::Rectangle | Shape::Disk => Mapping::Rectangular,
    }
}
