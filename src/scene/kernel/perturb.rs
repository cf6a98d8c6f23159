//! The kernel's bump and normal map stage: each lane's texture coordinates and the gradients of
//! u and v, the height or normal texture read for the whole packet in lanes
//! (`Bump::perturb_lanes`, `NormalMap::perturb_lanes`: an image's bilinear or trilinear filter
//! in lanes), each lane's tilted normal taken to world space (`Scene::tilted_to_world`).
//!
//! Where the map is an image under a built-in mapping of a generic shape (what
//! `Scene::filtered_in_lanes` serves), (u, v) and their gradients come from the mapping's own
//! lanes (`Mapping::map_lanes`) and need no per-lane record; otherwise (a mesh, the shape's own
//! (u, v), a formula) from each lane's texture context (`uv_gradients`). Either way the same
//! steps as `Scene::perturbed_normal_at` in the same order, so a lane's normal is the scalar
//! path's bit for bit.

use super::Diffs;
use super::nearest::Hits;
use super::shade::{PerLane, Resolved};
use crate::mapping::TexCoord;
use crate::material::{UvLanes, through_transform, uv_gradients};
use crate::math::Vec2;
use crate::math::Vec3A;
use crate::math::lanes::{MAX_LANES, V3, mask_to_array, to_array};
use crate::scene::Scene;
use crate::scene::trace::Perturbation;
use crate::texture::transformed;
use pulp::Simd;

impl Scene {
    /// Whether object `k`'s bump or normal map `p` is read without per-lane records.
    #[inline(always)]
    pub(super) fn perturbation_in_lanes(&self, k: usize, p: &Perturbation) -> bool {
        Self::filtered_in_lanes(&self.objects[k], p.texture()).is_some()
    }

    /// The shading normals `r.ns` of object `k`'s lanes in `on` tilted by its bump or normal
    /// map `p` (and the per-lane records' normals, where they were made, for the mirrors).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn perturb_lanes<S: Simd>(
        &self,
        s: S,
        k: usize,
        p: &Perturbation,
        hits: &Hits<S>,
        r: &mut Resolved<S>,
        mut per: Option<&mut PerLane>,
        diffs: Option<&Diffs>,
        on: &[bool; MAX_LANES],
    ) {
        let obj = &self.objects[k];
        let texture = p.texture();
        let (lp, ln, lns) = (hits.p.to_arrays(), hits.n.to_arrays(), hits.ns.to_arrays());
        let vec = |a: &[[f32; MAX_LANES]; 3], i: usize| Vec3A::new(a[0][i], a[1][i], a[2][i]);
        let mut at = UvLanes {
            tc: [TexCoord::default(); MAX_LANES],
            gu: [Vec3A::ZERO; MAX_LANES],
            gv: [Vec3A::ZERO; MAX_LANES],
            p: [Vec3A::ZERO; MAX_LANES],
            n: [Vec3A::Y; MAX_LANES],
        };
        // The lanes whose map has coordinates there.
        let mut have = [false; MAX_LANES];
        for i in 0..S::F32_LANES {
            if on[i] {
                // `Scene::perturbed_normal`: the object-space shading normal.
                let (n, ns) = (vec(&ln, i), vec(&lns, i));
                at.n[i] = if ns == n { n } else { ns };
            }
        }
        match (Self::filtered_in_lanes(obj, texture), per.as_deref()) {
            (Some((t, mapping)), _) => {
                // `uv_gradients` for a built-in mapping of the point: the mapping's lanes,
                // then per lane the footprint (`Scene::texture_context`), the coordinates
                // (`Mapping::map_with_differentials`, `Texture::tex_coord`) and the
                // gradients through the (u, v) transform.
                let m = mapping.map_lanes::<S, true>(s, &hits.p);
                let (u, v) = (to_array::<S>(m.u), to_array::<S>(m.v));
                let (gu, gv) = (m.grad_u.to_arrays(), m.grad_v.to_arrays());
                for i in 0..S::F32_LANES {
                    if !on[i] {
                        continue;
                    }
                    let (pi, ni) = (vec(&lp, i), vec(&ln, i));
                    let (dpdx, dpdy) = self.footprint_at(obj, diffs.map(|d| &d[i]), pi, ni);
                    let (gui, gvi) = (vec(&gu, i), vec(&gv, i));
                    let tc = TexCoord::from_gradients(Vec2::new(u[i], v[i]), gui, gvi, dpdx, dpdy);
                    at.tc[i] = transformed(tc, t.transform.as_ref());
                    (at.gu[i], at.gv[i]) = through_transform(texture, gui, gvi);
                    at.p[i] = pi;
                    have[i] = true;
                }
            }
            (None, Some(pl)) => {
                for i in 0..S::F32_LANES {
                    if on[i]
                        && let Some((tc, gu, gv)) = uv_gradients(texture, &pl.ctx[i])
                    {
                        (at.tc[i], at.gu[i], at.gv[i], at.p[i]) = (tc, gu, gv, pl.ctx[i].p);
                        have[i] = true;
                    }
                }
            }
            // Unreachable: a map read per lane makes the lanes' records.
            (None, None) => return,
        }
        let tilted = match p {
            Perturbation::Bump(b) => b.perturb_lanes(s, &at, &have),
            Perturbation::Normal(m) => m.perturb_lanes(s, &at, &have),
        };
        let (mut ns, wo) = (r.ns.to_arrays(), r.wo.to_arrays());
        let front = mask_to_array(s, r.front);
        for i in 0..S::F32_LANES {
            if !on[i] {
                continue;
            }
            let n =
                Self::tilted_to_world(obj, at.n[i], tilted[i], vec(&ns, i), vec(&wo, i), front[i]);
            (ns[0][i], ns[1][i], ns[2][i]) = (n.x, n.y, n.z);
            if let Some(pl) = per.as_deref_mut() {
                pl.hits[i].ns = n;
            }
        }
        r.ns = V3::from_arrays(&ns);
    }
}
