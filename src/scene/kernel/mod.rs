//! The one render kernel: every stage of a ray's radiance written once over pulp's `Simd` and
//! run at every width it has. A packet is `S::F32_LANES` rays, one register per coordinate: 16
//! on AVX-512, 8 on AVX2, 4 on NEON, SSE2 and WebAssembly's simd128, and 1 under
//! [`pulp::Scalar`], which is the scalar path ([`Scene::trace_keyed`], the inspector, the
//! command line's single rays). No scene takes another path.
//!
//! The stages, in order ([`Scene::radiance_lanes`]):
//! 1. [`nearest`]: the nearest hit over the objects in preset order: the generic shapes'
//!    intersections in lanes (`geometry::lanes`), a mesh's BVH walked by the whole packet
//!    (`geometry::mesh::packet`).
//! 2. [`shade`], object by object for the lanes that hit it: the hit resolved in world space
//!    and faced toward the viewer, the texture's (u, v) by the mapping's own file
//!    (`Mapping::map_lanes`) and its texels (the lane-wise nearest lookup; an image filtered
//!    over the footprint by [`filtered`]: trilinear in lanes, EWA and the footprint filter per
//!    lane), the material's terms (`Material::terms`), a bump or normal map
//!    ([`perturb`]: the map's texels read for the packet in lanes), the debug views.
//! 3. [`light`]: each light's reflected radiance (`Terms::add_light`) past its shadow rays, and
//!    Phong's glow.
//! 4. Mirrors and clip maps: the lanes that reflect, or that see through a partly transparent
//!    surface, are traced again as a packet of their own (masked), one level deeper, and
//!    blended in.
//!
//! What stays per lane calls the one scalar definition there is of it: EWA and the footprint
//! filter's lookups, a texture on a mesh's own (u, v) filtered over the footprint
//! (`Texture::eval`), a student's formula, a textured coefficient, a bump or normal map's
//! slope and tilt, a shadow ray's any-hit walk, a mirror's ray differentials.
//! Each operation in lanes is one IEEE operation per lane in the scalar code's order, so a lane
//! gives the same bits at every width: renders are identical for `--simd scalar` and `auto`.

// Lane loops index several arrays by the lane, the form the vectoriser reads best.
#![allow(clippy::needless_range_loop)]

mod filtered;
mod light;
mod nearest;
mod perturb;
mod shade;
mod texels;

use super::Scene;
use crate::material::{C3, splat_rgb};
use crate::math::lanes::{F, M, MAX_LANES, V3, to_array};
use crate::math::{Ray, RayDifferential, Rgb};
use pulp::Simd;

/// A packet of rays in world space.
#[derive(Clone, Copy, Debug)]
pub struct Rays<S: Simd> {
    /// Origins.
    pub o: V3<S>,
    /// Directions (any non-zero length).
    pub d: V3<S>,
    /// Which lanes carry a ray.
    pub active: M<S>,
}

/// Each lane's ray differentials, where the scene's filters need footprints (the lanes'
/// order; inactive lanes hold anything).
pub type Diffs = [RayDifferential; MAX_LANES];

/// What a packet's rays see: radiance per lane and each lane's edge key (see
/// [`Scene::trace_keyed`]).
#[derive(Clone, Copy, Debug)]
pub struct Traced<S: Simd> {
    /// Linear radiance.
    pub rgb: C3<S>,
    /// Edge keys.
    pub keys: [u32; MAX_LANES],
}

impl Scene {
    /// Radiance and edge keys along a packet of camera rays: `Scene::radiance_lanes` at
    /// depth 0, black wherever it is not finite (what the film gets).
    #[must_use]
    #[inline(always)]
    pub fn trace_lanes<S: Simd>(&self, s: S, rays: &Rays<S>, diffs: Option<&Diffs>) -> Traced<S> {
        let mut t = self.radiance_lanes(s, rays, diffs, 0, 0);
        let fine = s.and_m32s(
            s.and_m32s(
                crate::math::lanes::finite(s, t.rgb[0]),
                crate::math::lanes::finite(s, t.rgb[1]),
            ),
            crate::math::lanes::finite(s, t.rgb[2]),
        );
        let zero = s.splat_f32s(0.0);
        for c in &mut t.rgb {
            *c = s.select_f32s(fine, *c, zero);
        }
        t
    }

    /// Radiance and edge keys along a packet of rays that have been mirrored `depth` times and
    /// passed `layer` clip-mapped surfaces: the kernel's stages (see the module documentation).
    #[must_use]
    #[inline(always)]
    pub(crate) fn radiance_lanes<S: Simd>(
        &self,
        s: S,
        rays: &Rays<S>,
        diffs: Option<&Diffs>,
        depth: u32,
        layer: u32,
    ) -> Traced<S> {
        let hits = self.nearest_lanes(s, rays);
        let mut out = Traced {
            rgb: splat_rgb(s, self.settings.background),
            keys: [0; MAX_LANES],
        };
        if !crate::math::lanes::any(s, hits.hit) {
            return out;
        }
        // Each object the packet hit, once, in the order the lanes meet them.
        let mut seen = [u32::MAX; MAX_LANES];
        let mut n_seen = 0;
        for i in 0..S::F32_LANES {
            let k = hits.object[i];
            if k != u32::MAX && !seen[..n_seen].contains(&k) {
                seen[n_seen] = k;
                n_seen += 1;
            }
        }
        for &k in &seen[..n_seen] {
            let mine = hits.of_object(s, k);
            let (l, keys) =
                self.shade_object(s, k as usize, rays, &hits, mine, diffs, depth, layer);
            for c in 0..3 {
                out.rgb[c] = s.select_f32s(mine, l[c], out.rgb[c]);
            }
            let on = crate::math::lanes::mask_to_array(s, mine);
            for i in 0..S::F32_LANES {
                if on[i] {
                    out.keys[i] = keys[i];
                }
            }
        }
        out
    }

    /// [`Scene::radiance_lanes`] for a packet traced again (a mirror's reflections, what lies
    /// behind a clip map): a call of its own, entered through `s`'s `#[target_feature]` entry
    /// so the nested packet runs at the dispatched width (a recursive call cannot be inlined).
    #[inline(never)]
    pub(crate) fn radiance_nested<S: Simd>(
        &self,
        s: S,
        rays: &Rays<S>,
        diffs: Option<&Diffs>,
        depth: u32,
        layer: u32,
    ) -> Traced<S> {
        /// The packet as per-lane buffers: pulp's `WithSimd` hands `with_simd` a token of its
        /// own type parameter (the same type as `s`, which the compiler cannot see).
        struct Nested<'a> {
            scene: &'a Scene,
            o: [[f32; MAX_LANES]; 3],
            d: [[f32; MAX_LANES]; 3],
            active: [bool; MAX_LANES],
            diffs: Option<&'a Diffs>,
            depth: u32,
            layer: u32,
        }
        impl pulp::WithSimd for Nested<'_> {
            type Output = ([[f32; MAX_LANES]; 3], [u32; MAX_LANES]);
            #[inline(always)]
            fn with_simd<S: Simd>(self, s: S) -> Self::Output {
                let rays = Rays {
                    o: V3::from_arrays(&self.o),
                    d: V3::from_arrays(&self.d),
                    active: crate::math::lanes::mask_from_array(s, &self.active),
                };
                let t = self
                    .scene
                    .radiance_lanes(s, &rays, self.diffs, self.depth, self.layer);
                (crate::math::lanes::map3(t.rgb, to_array::<S>), t.keys)
            }
        }
        let (rgb, keys) = s.vectorize(Nested {
            scene: self,
            o: rays.o.to_arrays(),
            d: rays.d.to_arrays(),
            active: crate::math::lanes::mask_to_array(s, rays.active),
            diffs,
            depth,
            layer,
        });
        Traced {
            rgb: crate::math::lanes::map3(rgb, |c| crate::math::lanes::from_array::<S>(&c)),
            keys,
        }
    }

    /// Radiance and edge key along one ray (the kernel at width 1): see
    /// [`Scene::trace_keyed`].
    #[must_use]
    #[inline]
    pub(crate) fn radiance_one(
        &self,
        ray: &Ray,
        diff: Option<&RayDifferential>,
        depth: u32,
        finish: bool,
    ) -> (Rgb, u32) {
        let s = pulp::Scalar;
        let rays = Rays {
            o: V3::one(ray.origin),
            d: V3::one(ray.dir),
            active: true,
        };
        let diffs = diff.map(|d| [*d; MAX_LANES]);
        let t = if finish {
            self.trace_lanes(s, &rays, diffs.as_ref())
        } else {
            self.radiance_lanes(s, &rays, diffs.as_ref(), depth, 0)
        };
        (Rgb(t.rgb[0], t.rgb[1], t.rgb[2]), t.keys[0])
    }
}

/// The lanes of a register as an array, for per-lane work.
#[inline(always)]
pub(super) fn lanes<S: Simd>(v: F<S>) -> [f32; MAX_LANES] {
    to_array::<S>(v)
}
