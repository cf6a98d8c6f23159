//! The kernel's direct light: the ambient term, then each light that reaches the point past
//! its shadow ray (`Terms::add_light`), then Phong's glow where direct light fades.

use super::shade::Resolved;
use crate::geometry::Shape;
use crate::material::{C3, GLOW_FADE, Light, Terms};
use crate::math::lanes::{
    F, M, MAX_LANES, V3, clamp, finite, from_array, mask_from_array, mask_to_array, to_array,
};
use crate::math::{Ray, Vec3A};
use crate::scene::Scene;
use pulp::Simd;

/// The direction to `light` from each lane's point `p`, the distance (infinite for a
/// directional light), its radiance and whether it casts shadows (`Light::incident`).
#[inline(always)]
fn incident<S: Simd>(s: S, light: &Light, p: &V3<S>) -> (V3<S>, F<S>, crate::math::Rgb, bool) {
    match *light {
        Light::Directional {
            to_light,
            radiance,
            shadows,
        } => (
            V3::splat(s, to_light),
            s.splat_f32s(f32::INFINITY),
            radiance,
            shadows,
        ),
        Light::Point {
            position,
            radiance,
            shadows,
        } => {
            let d = V3::splat(s, position).sub(s, p);
            let dist = s.sqrt_f32s(d.dot(s, &d));
            let away = s.greater_than_f32s(dist, s.splat_f32s(0.0));
            let wi = V3::select(s, away, &d.div(s, dist), &V3::splat(s, Vec3A::Y));
            (wi, dist, radiance, shadows)
        }
    }
}

impl Scene {
    /// The radiance object `k`'s lanes `on` reflect from the scene's lights with the
    /// material's `terms` at the resolved hits `r` (normals facing the viewer), shadow rays
    /// leaving `offset` off the surface; a blocked light sets its bit in the lanes' `keys`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn direct_lanes<S: Simd>(
        &self,
        s: S,
        k: usize,
        terms: &Terms<S>,
        r: &Resolved<S>,
        on: M<S>,
        offset: F<S>,
        keys: &mut [u32; MAX_LANES],
    ) -> C3<S> {
        let obj = &self.objects[k];
        let zero = s.splat_f32s(0.0);
        let mut l = terms.base;
        // A shadow ray leaves the surface on the side it was hit from. A flat shape cannot be
        // met again that way, nor a closed convex one hit from outside: skip the object
        // itself. An open cylinder, a mesh, or a sphere seen from inside can shadow itself.
        let self_shadows: [bool; MAX_LANES] = match obj.shape {
            Shape::Plane | Shape::Rectangle | Shape::Disk => [false; MAX_LANES],
            Shape::Sphere | Shape::Cylinder { capped: true } => {
                let front = mask_to_array(s, r.front);
                crate::math::lanes::each_lane(|i| !front[i])
            }
            Shape::Cylinder { capped: false } | Shape::Mesh(_) => [true; MAX_LANES],
        };
        let mut lit = zero;
        for (li, light) in self.lights.iter().enumerate() {
            let (wi, dist, radiance, shadows) = incident(s, light, &r.p);
            let ndotwi = r.ns.dot(s, &wi);
            let below = s.or_m32s(
                s.less_than_or_equal_f32s(ndotwi, zero),
                s.less_than_or_equal_f32s(r.ng.dot(s, &wi), zero),
            );
            let mut reach = s.and_m32s(on, s.not_m32s(below));
            let mut share = None;
            if shadows && crate::math::lanes::any(s, reach) && !self.has_clips {
                // The packet's shadow rays traced together (`Scene::occluded_lanes`).
                let rays = super::Rays {
                    o: r.p.at(s, offset, &r.ng),
                    d: wi,
                    active: reach,
                };
                let t_max = s.select_f32s(
                    finite(s, dist),
                    s.sub_f32s(dist, offset),
                    s.splat_f32s(f32::INFINITY),
                );
                let skip =
                    crate::math::lanes::each_lane(|i| if self_shadows[i] { usize::MAX } else { k });
                let blocked = self.occluded_lanes(s, &rays, t_max, &skip);
                let flags = mask_to_array(s, blocked);
                for (i, key) in keys.iter_mut().enumerate().take(S::F32_LANES) {
                    if flags[i] {
                        *key |= (1 << (16 + li.min(14))) as u32;
                    }
                }
                reach = s.and_m32s(reach, s.not_m32s(blocked));
            } else if shadows && crate::math::lanes::any(s, reach) {
                // Clip maps let part of the light through: each lane's transmittance.
                let mut flags = mask_to_array(s, reach);
                let (pa, nga, offs) = (r.p.to_arrays(), r.ng.to_arrays(), to_array::<S>(offset));
                let (wa, da) = (wi.to_arrays(), to_array::<S>(dist));
                let mut tr = [1.0_f32; MAX_LANES];
                for i in 0..S::F32_LANES {
                    if !flags[i] {
                        continue;
                    }
                    let v = |a: &[[f32; MAX_LANES]; 3]| Vec3A::new(a[0][i], a[1][i], a[2][i]);
                    let origin = v(&pa) + v(&nga) * offs[i];
                    let t_max = if da[i].is_finite() {
                        da[i] - offs[i]
                    } else {
                        f32::INFINITY
                    };
                    let skip = if self_shadows[i] { usize::MAX } else { k };
                    let ray = Ray::new(origin, v(&wa));
                    tr[i] = self.transmittance(&ray, t_max, skip);
                    let blocked = tr[i] <= 0.0;
                    if blocked {
                        keys[i] |= (1 << (16 + li.min(14))) as u32;
                        flags[i] = false;
                    }
                }
                reach = mask_from_array(s, &flags);
                share = Some(from_array::<S>(&tr));
            }
            terms.add_light(
                s, reach, &r.ns, &r.wo, &wi, radiance, ndotwi, share, &mut l, &mut lit,
            );
        }
        if let Some((glow, glows)) = terms.glow {
            // The glow's weight: 1 in the dark, fading linearly to 0 at GLOW_FADE.
            let w = clamp(
                s,
                s.sub_f32s(s.splat_f32s(1.0), s.div_f32s(lit, s.splat_f32s(GLOW_FADE))),
                0.0,
                1.0,
            );
            let glows = s.and_m32s(on, glows);
            for c in 0..3 {
                let add = s.add_f32s(l[c], s.mul_f32s(glow[c], w));
                l[c] = s.select_f32s(glows, add, l[c]);
            }
        }
        l
    }
}
