//! Ray intersection with the generic shapes, written to stay accurate far from the origin: the
//! width-1 instances of the lanes in [`super::lanes`], and meshes through their BVH.

use super::LocalHit;
use super::lanes::{self, Flat, ShapeHits};
use super::mesh::{Mesh, Shading};
use crate::math::Ray;
use crate::math::lanes::V3;
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
        Shape::Plane => flat(ray, t_max, Flat::Plane),
        Shape::Rectangle => flat(ray, t_max, Flat::Rectangle),
        Shape::Disk => flat(ray, t_max, Flat::Disk),
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

/// The width-1 instance of a generic shape's lanes ([`super::lanes`]) as a [`LocalHit`].
#[inline(always)]
fn one(h: ShapeHits<pulp::Scalar>) -> Option<LocalHit> {
    h.hit.then(|| LocalHit {
        t: h.t,
        p: h.p.vec(),
        n: h.n.vec(),
        ns: h.n.vec(),
        uv: None,
        dpduv: None,
        part: h.part,
        prim: 0,
    })
}

/// The ray's origin and direction at width 1.
#[inline(always)]
fn lanes_of(ray: &Ray) -> (V3<pulp::Scalar>, V3<pulp::Scalar>) {
    (V3::one(ray.origin), V3::one(ray.dir))
}

fn sphere(ray: &Ray, t_max: f32) -> Option<LocalHit> {
    let (o, d) = lanes_of(ray);
    one(lanes::sphere(pulp::Scalar, &o, &d, t_max))
}

fn cylinder(ray: &Ray, t_max: f32, capped: bool) -> Option<LocalHit> {
    let (o, d) = lanes_of(ray);
    one(lanes::cylinder(pulp::Scalar, &o, &d, t_max, capped))
}

fn flat(ray: &Ray, t_max: f32, flat: Flat) -> Option<LocalHit> {
    let (o, d) = lanes_of(ray);
    one(lanes::flat(pulp::Scalar, &o, &d, t_max, flat))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec3A;

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
        assert!((flat(&r, f32::INFINITY, Flat::Plane).unwrap().t - 2.0).abs() < 1e-6);
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
