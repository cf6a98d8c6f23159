//! The inspector at a mirror: the reflected ray, the bounce it is, and what it shows.

use super::Inspection;
use crate::mapping::explain_number;
use crate::math::{Rgb, Vec2, Vec3A};
use crate::scene::{Scene, SurfaceHit};
use crate::texture::TextureContext;

/// A mirror at an inspected hit: the reflected ray, the bounce it is, and what it shows there,
/// inspected as a pixel is (its texel read through the mirrored ray differentials).
#[derive(Clone, Debug)]
pub struct MirrorRead {
    /// The bounce the reflected ray is: 1 for the first mirror the camera ray meets.
    pub depth: u32,
    /// The scene's reflection depth: the most bounces a ray takes. A mirror met at a deeper
    /// bounce adds nothing.
    pub limit: u32,
    /// `kr cr` here: what multiplies the radiance along the reflected ray.
    pub weight: Rgb,
    /// The normal it reflects about (world space; the shading normal, after a bump or normal
    /// map).
    pub normal: Vec3A,
    /// Unit vector toward the viewer, v.
    pub view: Vec3A,
    /// The reflected direction, r = 2 (n . v) n - v.
    pub direction: Vec3A,
    /// The reflection worked with this hit's numbers.
    pub lines: Vec<String>,
    /// Radiance along the reflected ray (the background's when it hits nothing; black when
    /// the depth limit stops it).
    pub radiance: Rgb,
    /// What the reflected ray hits, inspected; `None` for the background, or when the depth
    /// limit stops the ray.
    pub seen: Option<Box<Inspection>>,
}

impl MirrorRead {
    /// Whether the reflected ray is traced: false past the scene's reflection depth.
    #[must_use]
    pub const fn followed(&self) -> bool {
        self.depth <= self.limit
    }

    /// What the mirror adds to the pixel: `kr cr` times the radiance along the reflected ray.
    #[must_use]
    pub fn added(&self) -> Rgb {
        self.weight * self.radiance
    }
}

impl Scene {
    /// The mirror at `hit`, reached after `depth` bounces: its reflected ray and what the ray
    /// shows, or `None` if the surface does not mirror here (`kr cr` black).
    pub(super) fn mirror_read(
        &self,
        pixel: Vec2,
        hit: &SurfaceHit,
        ctx: &TextureContext,
        diff: &crate::math::RayDifferential,
        depth: u32,
    ) -> Option<MirrorRead> {
        let material = &self.materials[self.objects[hit.object].material];
        if !material.is_lit() {
            return None;
        }
        let weight = material.shade_point(ctx, self.ambient).mirror?;
        let normal = self.perturbed_normal_at(hit, ctx).unwrap_or(hit.ns);
        let bent = SurfaceHit { ns: normal, ..*hit };
        let (ray, mirrored) = self.mirror_ray(&bent, Some(diff), self.offset_at(hit));
        let limit = self.settings.reflection_depth;
        let followed = depth < limit;
        let (radiance, seen) = match mirrored {
            Some(d) if followed => (
                self.trace_at_depth(&ray, self.needs_differentials().then_some(&d), depth + 1),
                self.inspect_ray(pixel, ray, &d, depth + 1).map(Box::new),
            ),
            _ => (Rgb::BLACK, None),
        };
        let v3 = |v: Vec3A| format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z);
        let cos = normal.dot(hit.wo);
        let mut lines = vec![
            format!("n = {}, v = {} (toward the viewer)", v3(normal), v3(hit.wo)),
            format!(
                "r = 2 (n . v) n - v = 2 x {} x n - v = {}",
                explain_number(f64::from(cos)),
                v3(ray.dir)
            ),
            format!(
                "v and r both make {:.1}° with n: the angle of incidence is the angle of \
                 reflection",
                cos.clamp(-1.0, 1.0).acos().to_degrees()
            ),
        ];
        if !followed {
            lines.push(format!(
                "bounce {} is past the reflection depth {limit}: the ray is not traced, and \
                 this mirror adds nothing",
                depth + 1
            ));
        }
        Some(MirrorRead {
            depth: depth + 1,
            limit,
            weight,
            normal,
            view: hit.wo,
            direction: ray.dir,
            lines,
            radiance,
            seen,
        })
    }
}
