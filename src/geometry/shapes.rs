//! Ray intersection with the generic shapes, written to stay accurate far from the origin.

use super::LocalHit;
use super::mesh::{Mesh, Shading};
use crate::math::{Ray, Vec3A};
use std::sync::Arc;

/// A shape in its object space. Size, position and orientation come from the instance
/// transform, so the lecture's mappings see the generic object they were written for.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// The unit sphere at the origin.
    Sphere,
    /// The cylinder x^2 + z^2 = 1 with y in [-1, 1]; `capped` closes it with two disks.
    Cylinder {
        /// Close the ends with disks at y = -1 and y = 1.
        capped: bool,
    },
    /// The infinite plane y = 0, normal +y.
    Plane,
    /// The generic rectangle (x, z) in [-1, 1]^2 in the plane y = 0, normal +y.
    Rectangle,
    /// The unit disk x^2 + z^2 <= 1 in the plane y = 0, normal +y.
    Disk,
    /// A triangle mesh in its file's coordinates, shared by every instance of the file.
    Mesh(MeshShape),
}

/// A mesh instance's shape: the shared mesh (and its BVH) and how this instance shades it.
#[derive(Clone, Debug)]
pub struct MeshShape {
    /// The triangles and their BVH, loaded once per file and shared by its instances.
    pub mesh: Arc<Mesh>,
    /// Flat or smooth normals.
    pub shading: Shading,
}

impl PartialEq for MeshShape {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.mesh, &other.mesh) && self.shading == other.shading
    }
}

/// Part ids reported in [`LocalHit::part`] for the cylinder.
pub const CYLINDER_WALL: u32 = 0;
/// The cap at y = -1.
pub const CYLINDER_BOTTOM: u32 = 1;
/// The cap at y = +1.
pub const CYLINDER_TOP: u32 = 2;

/// The nearest hit of `ray` (in object space) with `shape` for t in (0, `t_max`).
#[must_use]
#[inline]
pub fn intersect_shape(shape: &Shape, ray: &Ray, t_max: f32) -> Option<LocalHit> {
    match shape {
        Shape::Sphere => sphere(ray, t_max),
        Shape::Cylinder { capped } => cylinder(ray, t_max, *capped),
        Shape::Plane => plane(ray, t_max, |_, _| true),
        Shape::Rectangle => plane(ray, t_max, |x, z| x.abs() <= 1.0 && z.abs() <= 1.0),
        Shape::Disk => plane(ray, t_max, |x, z| x * x + z * z <= 1.0),
        Shape::Mesh(m) => m.mesh.intersect_point(ray, t_max, m.shading),
    }
}

/// Whether `shape` lies on `ray` (in object space) within (0, `t_max`): shadow rays, which need
/// any hit, not the nearest.
#[must_use]
#[inline]
pub fn occluded_shape(shape: &Shape, ray: &Ray, t_max: f32) -> bool {
    match shape {
        Shape::Mesh(m) => m.mesh.occluded(ray, t_max),
        _ => intersect_shape(shape, ray, t_max).is_some(),
    }
}

fn hit(t: f32, p: Vec3A, n: Vec3A, part: u32) -> LocalHit {
    LocalHit {
        t,
        p,
        n,
        ns: n,
        uv: None,
        dpduv: None,
        part,
        prim: 0,
    }
}

/// Roots of a t^2 + 2 b' t + c = 0, the form sphere and cylinder share: `a = d.d`,
/// `half_b = o.d`, `c = o.o - 1`, and `perp2a = |o x d|^2`, which is `a` times the squared
/// distance from the centre (axis) to the ray's closest point. The discriminant is then
/// `a - perp2a`, exact where `b'^2 - a c` cancels catastrophically far from the surface (Ray
/// Tracing Gems ch. 7, with Lagrange's identity in place of a division). Returns the two roots
/// in increasing order.
#[inline]
fn stable_roots(a: f32, half_b: f32, c: f32, perp2a: f32) -> Option<(f32, f32)> {
    let disc = a - perp2a; // the discriminant / 4: half_b^2 - a c
    if disc < 0.0 || a <= 0.0 {
        return None;
    }
    let root = disc.sqrt();
    // q has the sign of -half_b so the sum never cancels.
    let q = if half_b > 0.0 {
        -half_b - root
    } else {
        -half_b + root
    };
    if q == 0.0 {
        // The ray starts on the surface and is tangent: a double root at 0.
        return Some((0.0, 0.0));
    }
    let (t0, t1) = (c / q, q / a);
    Some(if t0 < t1 { (t0, t1) } else { (t1, t0) })
}

fn sphere(ray: &Ray, t_max: f32) -> Option<LocalHit> {
    let (o, d) = (ray.origin, ray.dir);
    let c = o.length_squared() - 1.0;
    let half_b = o.dot(d);
    // Outside and heading away: both roots are behind the origin (shadow rays leaving the
    // sphere, rays past it).
    if c > 0.0 && half_b >= 0.0 {
        return None;
    }
    let a = d.length_squared();
    let (t0, t1) = stable_roots(a, half_b, c, o.cross(d).length_squared())?;
    let t = if t0 > 0.0 { t0 } else { t1 };
    if !(t > 0.0 && t < t_max) {
        return None;
    }
    // Projecting back onto the unit sphere removes the error of o + t d far from the origin.
    let p = ray.at(t).normalize_or(Vec3A::Y);
    Some(hit(t, p, p, 0))
}

fn cylinder(ray: &Ray, t_max: f32, capped: bool) -> Option<LocalHit> {
    let (o, d) = (ray.origin, ray.dir);
    let mut best: Option<LocalHit> = None;
    let mut t_best = t_max;
    let (oxz, dxz) = (Vec3A::new(o.x, 0.0, o.z), Vec3A::new(d.x, 0.0, d.z));
    let a = dxz.length_squared();
    if a > 0.0 {
        let half_b = oxz.dot(dxz);
        let c = oxz.length_squared() - 1.0;
        let cross = o.z * d.x - o.x * d.z;
        if let Some((t0, t1)) = stable_roots(a, half_b, c, cross * cross) {
            for t in [t0, t1] {
                if t > 0.0 && t < t_best {
                    let p = ray.at(t);
                    if (-1.0..=1.0).contains(&p.y) {
                        let radial = Vec3A::new(p.x, 0.0, p.z).normalize_or(Vec3A::Z);
                        let p = Vec3A::new(radial.x, p.y, radial.z);
                        best = Some(hit(t, p, radial, CYLINDER_WALL));
                        t_best = t;
                        break;
                    }
                }
            }
        }
    }
    if capped && d.y != 0.0 {
        for (y, part) in [(-1.0_f32, CYLINDER_BOTTOM), (1.0, CYLINDER_TOP)] {
            let t = (y - o.y) / d.y;
            if t > 0.0 && t < t_best {
                let p = ray.at(t);
                if p.x * p.x + p.z * p.z <= 1.0 {
                    best = Some(hit(
                        t,
                        Vec3A::new(p.x, y, p.z),
                        Vec3A::new(0.0, y, 0.0),
                        part,
                    ));
                    t_best = t;
                }
            }
        }
    }
    best
}

fn plane(ray: &Ray, t_max: f32, inside: impl Fn(f32, f32) -> bool) -> Option<LocalHit> {
    if ray.dir.y == 0.0 {
        return None;
    }
    let t = -ray.origin.y / ray.dir.y;
    if !(t > 0.0 && t < t_max) {
        return None;
    }
    let p = ray.at(t);
    if !inside(p.x, p.z) {
        return None;
    }
    Some(hit(t, Vec3A::new(p.x, 0.0, p.z), Vec3A::Y, 0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
        Ray::new(Vec3A::from(o), Vec3A::from(d))
    }

    #[test]
    fn sphere_from_outside_inside_tangent_behind() {
        let h = sphere(&ray([0.0, 0.0, 5.0], [0.0, 0.0, -1.0]), f32::INFINITY).unwrap();
        assert!((h.t - 4.0).abs() < 1e-6);
        assert_eq!(h.p, Vec3A::Z);
        // From inside the nearest positive root is the far wall.
        let h = sphere(&ray([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), f32::INFINITY).unwrap();
        assert!((h.t - 1.0).abs() < 1e-6);
        assert!((h.n - Vec3A::X).length() < 1e-6);
        // Tangent: grazes x = 1.
        let h = sphere(&ray([1.0, 0.0, 5.0], [0.0, 0.0, -1.0]), f32::INFINITY).unwrap();
        assert!((h.p - Vec3A::X).length() < 1e-3);
        // Just outside: miss.
        assert!(sphere(&ray([1.0001, 0.0, 5.0], [0.0, 0.0, -1.0]), f32::INFINITY).is_none());
        // Behind the origin: miss.
        assert!(sphere(&ray([0.0, 0.0, 5.0], [0.0, 0.0, 1.0]), f32::INFINITY).is_none());
        // t_max excludes the hit.
        assert!(sphere(&ray([0.0, 0.0, 5.0], [0.0, 0.0, -1.0]), 3.9).is_none());
    }

    #[test]
    fn huge_sphere_stays_accurate() {
        // A 1e6 sphere seen from 1e4 outside, in object space (scaled to unit).
        let s = 1e6_f32;
        let o = Vec3A::new(0.3, 0.2, (s + 1e4) / s);
        let d = Vec3A::new(0.0, 0.0, -1.0) / s;
        let h = sphere(&Ray::new(o, d), f32::INFINITY).unwrap();
        let world = h.p * s;
        let expected_z = (1.0_f64 - 0.13).sqrt() * 1e6;
        assert!(
            ((f64::from(world.z) - expected_z) / expected_z).abs() < 1e-5,
            "{world:?}"
        );
        let expected_t = (1e6 + 1e4) - expected_z;
        assert!(
            ((f64::from(h.t) - expected_t) / expected_t).abs() < 1e-4,
            "{}",
            h.t
        );
    }

    #[test]
    fn cylinder_wall_and_caps() {
        let h = cylinder(
            &ray([0.0, 0.5, 5.0], [0.0, 0.0, -1.0]),
            f32::INFINITY,
            false,
        )
        .unwrap();
        assert!((h.t - 4.0).abs() < 1e-6 && h.part == CYLINDER_WALL);
        // Above the open cylinder looking down: misses without caps, hits the top cap with.
        let r = ray([0.2, 5.0, 0.0], [0.0, -1.0, 0.0]);
        assert!(cylinder(&r, f32::INFINITY, false).is_none());
        let h = cylinder(&r, f32::INFINITY, true).unwrap();
        assert_eq!(h.part, CYLINDER_TOP);
        assert!((h.t - 4.0).abs() < 1e-6);
        // Through the open end into the inside wall.
        let h = cylinder(
            &ray([0.0, 1.5, 0.0], [0.5, -1.0, 0.0]),
            f32::INFINITY,
            false,
        )
        .unwrap();
        assert!((h.p.x - 1.0).abs() < 1e-6 && (h.p.y + 0.5).abs() < 1e-6);
    }

    #[test]
    fn planes_rectangles_disks() {
        let r = ray([0.5, 2.0, 0.5], [0.0, -1.0, 0.0]);
        assert!((plane(&r, f32::INFINITY, |_, _| true).unwrap().t - 2.0).abs() < 1e-6);
        assert!(intersect_shape(&Shape::Rectangle, &r, f32::INFINITY).is_some());
        assert!(intersect_shape(&Shape::Disk, &r, f32::INFINITY).is_some());
        let r = ray([0.9, 2.0, 0.9], [0.0, -1.0, 0.0]);
        assert!(intersect_shape(&Shape::Rectangle, &r, f32::INFINITY).is_some());
        assert!(intersect_shape(&Shape::Disk, &r, f32::INFINITY).is_none());
        // Parallel and grazing rays miss without NaN.
        assert!(
            intersect_shape(&Shape::Plane, &ray([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]), 1e30).is_none()
        );
        assert!(
            intersect_shape(&Shape::Plane, &ray([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), 1e30).is_none()
        );
    }
}
