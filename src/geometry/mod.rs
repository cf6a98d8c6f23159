//! Shapes in the lecture's generic form, instances that place them, and the hit record.
//!
//! Every analytic shape lives in its own object space in the generic form the lecture's mappings
//! assume (unit sphere at the origin; cylinder of radius 1 with y in [-1, 1]; rectangle and disk
//! in the y = 0 plane); an [`Object`] moves it into the world with a `world_from_object`
//! transform. Meshes keep the coordinates of their file.

pub mod bvh;
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
    /// For meshes: dp/du and dp/dv of the triangle, for UV derivatives.
    pub dpduv: Option<(Vec3A, Vec3A)>,
    /// Which part was hit (triangle index, cylinder wall or cap), for the inspector.
    pub part: u32,
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
    /// Inverse transpose of the linear part, for normals.
    pub normal_to_world: Mat3A,
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
        let normal_to_world = world_from_object.matrix3.inverse().transpose();
        let identity = world_from_object == Affine3A::IDENTITY;
        Self {
            shape,
            world_from_object,
            object_from_world,
            normal_to_world,
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
        } else {
            (self.normal_to_world * n).normalize_or(Vec3A::Y)
        }
    }
}
