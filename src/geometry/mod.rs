//! Shapes in the lecture's generic form, instances that place them, and the hit record.
//!
//! Every analytic shape lives in its own object space in the generic form the lecture's mappings
//! assume (unit sphere at the origin; cylinder of radius 1 with y in [-1, 1]; rectangle and disk
//! in the y = 0 plane); an [`Object`] moves it into the world with a `world_from_object`
//! transform. Meshes keep the coordinates of their file.

pub mod bvh;
pub mod displace;
pub mod lanes;
pub mod mesh;
mod shapes;

pub use mesh::{Mesh, MeshData, MeshMaterial, Shading};
pub use shapes::{MeshShape, Shape, intersect_shape, occluded_shape};

use crate::math::{Affine3A, Mat3A, Ray, Vec2, Vec3A};

/// What a ray hit in an object's own space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalHit {
    /// Ray parameter (the same in object and world space: directions are not renormalised).
    pub t: f32,
    /// Hit point in object space: the lecture's `local_hit_point`.
    pub p: Vec3A,
    /// Geometric normal in object space, unit length, on the outside of the shape.
    pub n: Vec3A,
    /// Shading normal in object space (equal to `n` except on smooth meshes).
    pub ns: Vec3A,
    /// Texture coordinates carried by the shape itself (mesh vertices), if any.
    pub uv: Option<Vec2>,
    /// For meshes: dp/du and dp/dv of the triangle, for UV derivatives. [`Mesh::intersect`]
    /// fills it; the renderer's [`intersect_shape`] leaves it `None` and
    /// `Scene::texture_context` computes it ([`Mesh::uv_derivatives`]) only when a footprint
    /// filter needs it.
    pub dpduv: Option<(Vec3A, Vec3A)>,
    /// Which part was hit (triangle index in the file, cylinder wall or cap), for the inspector.
    pub part: u32,
    /// The primitive hit in the shape's own order (for meshes the triangle's index in BVH
    /// order, which [`Mesh::uv_derivatives`] takes; 0 for the analytic shapes).
    pub prim: u32,
}

/// A placed shape: transform, material index, and whether it blocks shadow rays.
#[derive(Clone, Debug)]
pub struct Object {
    /// The shape in its object space.
    pub shape: Shape,
    /// Object space to world space.
    pub world_from_object: Affine3A,
    /// World space to object space.
    pub object_from_world: Affine3A,
    /// Inverse transpose of the linear part, for normals. When the transform is a similarity
    /// (rotation, uniform scale, translation) it is divided by its scale, so it is orthonormal
    /// and unit normals stay unit without renormalising.
    pub normal_to_world: Mat3A,
    /// True when `normal_to_world` is orthonormal (see there).
    pub normal_orthonormal: bool,
    /// True when the transform is the identity (skips two matrix products per ray).
    pub identity: bool,
    /// Index into the scene's materials.
    pub material: usize,
    /// Whether this object blocks shadow rays (an environment sphere must not).
    pub casts_shadows: bool,
    /// A name for the inspector and error messages.
    pub name: String,
}

impl Object {
    /// Places `shape` with the given transform.
    #[must_use]
    pub fn new(shape: Shape, world_from_object: Affine3A, material: usize, name: String) -> Self {
        let object_from_world = world_from_object.inverse();
        let mut normal_to_world = world_from_object.matrix3.inverse().transpose();
        let normal_orthonormal = match similarity_scale(normal_to_world) {
            Some(s) => {
                normal_to_world *= 1.0 / s;
                true
            }
            None => false,
        };
        let identity = world_from_object == Affine3A::IDENTITY;
        Self {
            shape,
            world_from_object,
            object_from_world,
            normal_to_world,
            normal_orthonormal,
            identity,
            material,
            casts_shadows: true,
            name,
        }
    }

    /// The nearest hit in (0, `t_max`) of a world-space ray, in object space.
    #[must_use]
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<LocalHit> {
        if self.identity {
            intersect_shape(&self.shape, ray, t_max)
        } else {
            intersect_shape(
                &self.shape,
                &ray.transformed(&self.object_from_world),
                t_max,
            )
        }
    }

    /// Whether this object lies on a world-space ray within (0, `t_max`) (shadow rays).
    #[must_use]
    #[inline]
    pub fn occludes(&self, ray: &Ray, t_max: f32) -> bool {
        if self.identity {
            occluded_shape(&self.shape, ray, t_max)
        } else {
            occluded_shape(
                &self.shape,
                &ray.transformed(&self.object_from_world),
                t_max,
            )
        }
    }

    /// A point from object to world space.
    #[must_use]
    #[inline]
    pub fn point_to_world(&self, p: Vec3A) -> Vec3A {
        if self.identity {
            p
        } else {
            self.world_from_object.transform_point3a(p)
        }
    }

    /// A normal from object to world space, renormalised.
    #[must_use]
    #[inline]
    pub fn normal_to_world(&self, n: Vec3A) -> Vec3A {
        if self.identity {
            n
        } else if self.normal_orthonormal {
            self.normal_to_world * n
        } else {
            (self.normal_to_world * n).normalize_or(Vec3A::Y)
        }
    }
}

/// The scale `s` when `m` is `s` times a rotation (or reflection): its columns orthogonal and
/// of one length, to 16 f32 ulps. Unit normals through `m / s` then stay unit within the
/// rounding of a normalisation.
fn similarity_scale(m: Mat3A) -> Option<f32> {
    let g = m.transpose() * m; // the Gram matrix: s^2 I for a similarity
    let s2 = g.x_axis.x;
    if !(s2 > 0.0 && s2.is_finite()) {
        return None;
    }
    let tol = 16.0 * f32::EPSILON * s2;
    let diag_ok = (g.y_axis.y - s2).abs() <= tol && (g.z_axis.z - s2).abs() <= tol;
    let off_ok = g.x_axis.y.abs() <= tol && g.x_axis.z.abs() <= tol && g.y_axis.z.abs() <= tol;
    (diag_ok && off_ok).then(|| s2.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Quat, Vec3};

    fn object(m: Affine3A) -> Object {
        Object::new(Shape::Sphere, m, 0, String::new())
    }

    #[test]
    fn similarity_normals_stay_unit_without_renormalising() {
        let rot = Quat::from_euler(glam::EulerRot::YXZ, 2.8, 0.4, 0.41);
        for scale in [1.0_f32, 1e-3, 3.7, 1e6] {
            let o = object(Affine3A::from_scale_rotation_translation(
                Vec3::splat(scale),
                rot,
                Vec3::new(1.0, -2.0, 3.0),
            ));
            assert!(o.normal_orthonormal, "scale {scale}");
            for n in [Vec3A::X, Vec3A::Y, Vec3A::Z, Vec3A::new(0.6, 0.0, -0.8)] {
                let w = o.normal_to_world(n);
                let exact = (o.world_from_object.matrix3.inverse().transpose() * n).normalize();
                assert!((w.length() - 1.0).abs() < 4.0 * f32::EPSILON, "{w}");
                assert!((w - exact).length() < 1e-6, "{w} vs {exact}");
            }
        }
    }

    #[test]
    fn non_uniform_scale_renormalises() {
        let o = object(Affine3A::from_scale(Vec3::new(1.0, 2.0, 1.0)));
        assert!(!o.normal_orthonormal);
        // The sphere stretched along y: the normal at 45 degrees tilts toward x.
        let w = o.normal_to_world(Vec3A::new(1.0, 1.0, 0.0).normalize());
        assert!((w.length() - 1.0).abs() < 1e-6);
        assert!((w - Vec3A::new(2.0, 1.0, 0.0).normalize()).length() < 1e-6);
    }
}
