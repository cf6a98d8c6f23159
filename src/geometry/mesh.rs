//! Triangle meshes: the lecture's `FlatUVMeshTriangle` and `SmoothUVMeshTriangle` as one
//! [`Mesh`] with a [`Shading`] per instance. (u, v), normals and the hit point are interpolated
//! by barycentrics in one place ([`Mesh::surface`]); the ray/triangle test is watertight (Woop,
//! Benthin and Wald 2013), so rays through shared edges and vertices never slip between
//! triangles; a [`Bvh`] finds the candidates.

mod displacement;
mod packet;
mod surface;

pub use displacement::Displacement;
pub use packet::TriangleHits;
pub use surface::MeshSurface;

use super::LocalHit;
use super::bvh::{Aabb, Bvh};
use crate::error::{Error, Result};
use crate::math::lanes::{MAX_LANES, V3};
use crate::math::{Ray, Vec2, Vec3, Vec3A};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// How a mesh's shading normal is found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[derive(Serialize, Deserialize)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum Shading {
    /// The lecture's `FlatUVMeshTriangle`: each triangle's own normal (facets show).
    #[strum(message = "One normal per triangle: facets show.")]
    Flat,
    /// The lecture's `SmoothUVMeshTriangle`: vertex normals (the file's, else area-weighted
    /// averages of the adjacent triangles') interpolated by barycentrics.
    #[default]
    #[strum(message = "Vertex normals interpolated across each triangle: smooth.")]
    Smooth,
}

impl crate::names::Named for Shading {
    const WHAT: &'static str = "shading";
}

/// The material a mesh file names (an OBJ's .mtl): its diffuse colour and image.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshMaterial {
    /// The material's name.
    pub name: String,
    /// `Kd`, linear RGB.
    pub diffuse: Option<[f32; 3]>,
    /// `map_Kd`, resolved against the mesh file's folder.
    pub diffuse_texture: Option<PathBuf>,
}

/// A mesh as a file holds it, before acceleration: indexed triangles (polygons already
/// triangulated) with optional per-vertex (u, v) and normals.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// Vertex positions in the file's coordinates (the object space); `triangles` index them.
    pub positions: Vec<Vec3>,
    /// Per-vertex (u, v); empty when the file has none.
    pub uvs: Vec<Vec2>,
    /// Per-vertex normals; empty when the file has none.
    pub normals: Vec<Vec3>,
    /// Triangles as vertex indices, counter-clockwise seen from the outside.
    pub triangles: Vec<[u32; 3]>,
    /// Faces in the file (polygons count once, before triangulation).
    pub faces: usize,
    /// The file's format, for messages (`ply ascii`, `ply binary_little_endian`, `obj`).
    pub format: String,
    /// The property names the (u, v) were read from (`u v`, `s t`, ...), if any.
    pub uv_names: Option<(String, String)>,
    /// The material the file names, if any.
    pub material: Option<MeshMaterial>,
    /// Why the material could not be read, if it could not (a missing .mtl).
    pub material_problem: Option<String>,
}

/// Counts of triangles that cannot be shaded normally.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Degenerate {
    /// Triangles with (numerically) zero area: rays never hit them.
    pub zero_area: usize,
    /// Triangles whose (u, v) span zero area: their texture derivatives are taken as zero.
    pub zero_uv_area: usize,
}

/// Whether the triangle (a, b, c) has zero area relative to its size in f32.
#[must_use]
pub fn is_zero_area(a: Vec3, b: Vec3, c: Vec3) -> bool {
    let (e1, e2) = (b - a, c - a);
    let longest = e1
        .length_squared()
        .max(e2.length_squared())
        .max((c - b).length_squared());
    e1.cross(e2).length() <= 1e-7 * longest || longest == 0.0
}

/// Whether the (u, v) triangle spans zero area.
#[must_use]
pub fn is_zero_uv_area(a: Vec2, b: Vec2, c: Vec2) -> bool {
    let (e1, e2) = (b - a, c - a);
    let longest = e1
        .length_squared()
        .max(e2.length_squared())
        .max((c - b).length_squared());
    e1.perp_dot(e2).abs() <= 1e-7 * longest || longest == 0.0
}

impl MeshData {
    /// The bounding box of the vertices (empty for no vertices).
    #[must_use]
    pub fn bbox(&self) -> Aabb {
        self.positions.iter().fold(Aabb::EMPTY, |b, p| Aabb {
            min: b.min.min(*p),
            max: b.max.max(*p),
        })
    }

    /// Counts the degenerate triangles.
    #[must_use]
    pub fn degenerate(&self) -> Degenerate {
        let mut d = Degenerate::default();
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| i as usize);
            let (Some(pa), Some(pb), Some(pc)) = (
                self.positions.get(a),
                self.positions.get(b),
                self.positions.get(c),
            ) else {
                continue;
            };
            d.zero_area += usize::from(is_zero_area(*pa, *pb, *pc));
            if !self.uvs.is_empty() {
                d.zero_uv_area +=
                    usize::from(is_zero_uv_area(self.uvs[a], self.uvs[b], self.uvs[c]));
            }
        }
        d
    }

    /// Checks what [`Mesh::new`] relies on: indices in range, finite values, matching lengths.
    ///
    /// # Errors
    /// Names `path` and the first bad triangle or vertex.
    pub fn validate(&self, path: &Path) -> Result<()> {
        let n = self.positions.len();
        let bad = |at: String, message: String| Error::Mesh {
            path: path.to_path_buf(),
            at,
            message,
        };
        if !self.uvs.is_empty() && self.uvs.len() != n {
            return Err(bad(
                "vertices".into(),
                format!("{} (u, v) pairs for {n} vertices", self.uvs.len()),
            ));
        }
        if !self.normals.is_empty() && self.normals.len() != n {
            return Err(bad(
                "vertices".into(),
                format!("{} normals for {n} vertices", self.normals.len()),
            ));
        }
        if let Some(i) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(bad(format!("vertex {i}"), "position is not finite".into()));
        }
        if let Some(i) = self.uvs.iter().position(|p| !p.is_finite()) {
            return Err(bad(format!("vertex {i}"), "(u, v) is not finite".into()));
        }
        if let Some(i) = self.normals.iter().position(|p| !p.is_finite()) {
            return Err(bad(format!("vertex {i}"), "normal is not finite".into()));
        }
        for (i, t) in self.triangles.iter().enumerate() {
            if let Some(k) = t.iter().find(|k| **k as usize >= n) {
                return Err(bad(
                    format!("triangle {i}"),
                    format!("vertex index {k} is out of range ({n} vertices)"),
                ));
            }
        }
        Ok(())
    }
}

/// A mesh ready to trace: vertex arrays, triangles in BVH order and the BVH. Shared by every
/// instance of the same file (through an `Arc`).
pub struct Mesh {
    path: PathBuf,
    positions: Vec<Vec3>,
    uvs: Vec<Vec2>,
    /// The file's normals, or area-weighted vertex normals (zero where undefined).
    normals: Vec<Vec3>,
    file_normals: bool,
    /// Triangles in the BVH's leaf order.
    triangles: Vec<[u32; 3]>,
    /// Each triangle's index in the file, for the inspector.
    file_index: Vec<u32>,
    bvh: Bvh,
    bbox: Aabb,
    /// Generated mappings see the model fitted into the generic [-1, 1]^3 box.
    map_centre: Vec3A,
    map_scale: f32,
    faces: usize,
    format: String,
    uv_names: Option<(String, String)>,
    material: Option<MeshMaterial>,
    material_problem: Option<String>,
    degenerate: Degenerate,
    /// How the mesh was displaced, when it is a displaced copy of a file's mesh.
    displacement: Option<Displacement>,
}

impl std::fmt::Debug for Mesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Mesh")
            .field("path", &self.path)
            .field("vertices", &self.positions.len())
            .field("triangles", &self.triangles.len())
            .field("has_uv", &self.has_uv())
            .finish_non_exhaustive()
    }
}

/// The nearest triangle hit: index (BVH order), ray parameter and barycentrics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Triangle index in BVH order.
    pub triangle: u32,
    /// Ray parameter of the hit: the point is `origin + t * dir` (a distance only if `dir` is
    /// unit length).
    pub t: f32,
    /// Barycentric weights of the triangle's three vertices.
    pub bary: Vec3,
}

impl Mesh {
    /// Builds the BVH and vertex normals of `data` (read from `path`, which names it in
    /// messages).
    ///
    /// # Errors
    /// Indices out of range or non-finite values (see [`MeshData::validate`]), or no triangles.
    pub fn new(data: MeshData, path: &Path) -> Result<Self> {
        data.validate(path)?;
        if data.triangles.is_empty() {
            return Err(Error::Mesh {
                path: path.to_path_buf(),
                at: "faces".into(),
                message: "the mesh has no triangles".into(),
            });
        }
        let degenerate = data.degenerate();
        let bbox = data.bbox();
        let MeshData {
            positions,
            uvs,
            normals,
            triangles,
            faces,
            format,
            uv_names,
            material,
            material_problem,
        } = data;
        let file_normals = !normals.is_empty();
        let normals = if file_normals {
            normals.iter().map(|n| n.normalize_or_zero()).collect()
        } else {
            area_weighted_normals(&positions, &triangles)
        };
        let bounds: Vec<Aabb> = triangles
            .iter()
            .map(|t| {
                Aabb::of_triangle(
                    positions[t[0] as usize],
                    positions[t[1] as usize],
                    positions[t[2] as usize],
                )
            })
            .collect();
        let (bvh, order) = Bvh::build(&bounds);
        drop(bounds);
        let triangles: Vec<[u32; 3]> = order.iter().map(|&i| triangles[i as usize]).collect();
        let (positions, uvs, normals, triangles) =
            renumber_vertices(&positions, uvs, &normals, triangles);
        let half = ((bbox.max - bbox.min) * 0.5).max_element();
        Ok(Self {
            path: path.to_path_buf(),
            positions,
            uvs,
            normals,
            file_normals,
            triangles,
            file_index: order,
            bvh,
            bbox,
            map_centre: bbox.centre().into(),
            map_scale: if half > 0.0 && half.is_finite() {
                1.0 / half
            } else {
                1.0
            },
            faces,
            format,
            uv_names,
            material,
            material_problem,
            degenerate,
            displacement: None,
        })
    }

    /// The vertex arrays (vertex normals always: the file's or the area-weighted ones) and the
    /// triangles (in BVH order), as [`MeshData`] without the file's facts: what a displaced copy
    /// starts from.
    #[must_use]
    pub fn to_data(&self) -> MeshData {
        MeshData {
            positions: self.positions.clone(),
            uvs: self.uvs.clone(),
            normals: self.normals.clone(),
            triangles: self.triangles.clone(),
            faces: self.triangles.len(),
            ..MeshData::default()
        }
    }

    /// This mesh, built from a subdivided and displaced copy of `base`, with `base`'s file,
    /// format, material and mapping frame (so generated mappings read the same texels at the
    /// same surface points as on `base`), and `what` saying how it was displaced.
    #[must_use]
    pub fn displaced_from(mut self, base: &Self, what: Displacement) -> Self {
        self.path.clone_from(&base.path);
        self.file_normals = base.file_normals;
        self.map_centre = base.map_centre;
        self.map_scale = base.map_scale;
        self.faces = base.faces;
        self.format.clone_from(&base.format);
        self.uv_names.clone_from(&base.uv_names);
        self.material.clone_from(&base.material);
        self.material_problem.clone_from(&base.material_problem);
        self.displacement = Some(what);
        self
    }

    /// How the mesh was displaced (height texture, scale, subdivision levels), when it was.
    #[must_use]
    pub const fn displacement(&self) -> Option<&Displacement> {
        self.displacement.as_ref()
    }

    /// The file it was read from.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Number of vertices.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Faces in the file (before triangulation).
    #[must_use]
    pub fn face_count(&self) -> usize {
        self.faces
    }

    /// The file's format.
    #[must_use]
    pub fn format(&self) -> &str {
        &self.format
    }

    /// Whether the vertices carry (u, v).
    #[must_use]
    pub fn has_uv(&self) -> bool {
        !self.uvs.is_empty()
    }

    /// The property names the (u, v) came from.
    #[must_use]
    pub fn uv_names(&self) -> Option<&(String, String)> {
        self.uv_names.as_ref()
    }

    /// Whether the file carried vertex normals (else smooth shading uses area-weighted ones).
    #[must_use]
    pub fn has_file_normals(&self) -> bool {
        self.file_normals
    }

    /// The bounding box in the file's coordinates.
    #[must_use]
    pub fn bbox(&self) -> Aabb {
        self.bbox
    }

    /// Degenerate triangle counts.
    #[must_use]
    pub fn degenerate(&self) -> Degenerate {
        self.degenerate
    }

    /// The material the file names.
    #[must_use]
    pub fn material(&self) -> Option<&MeshMaterial> {
        self.material.as_ref()
    }

    /// Why the file's material could not be read.
    #[must_use]
    pub fn material_problem(&self) -> Option<&str> {
        self.material_problem.as_deref()
    }

    /// Nodes in the BVH.
    #[must_use]
    pub fn bvh_nodes(&self) -> usize {
        self.bvh.node_count()
    }

    /// Heap bytes held by the mesh and its BVH.
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        self.positions.capacity() * size_of::<Vec3>()
            + self.uvs.capacity() * size_of::<Vec2>()
            + self.normals.capacity() * size_of::<Vec3>()
            + self.triangles.capacity() * size_of::<[u32; 3]>()
            + self.file_index.capacity() * size_of::<u32>()
            + self.bvh.heap_bytes()
    }

    /// Heap bytes per triangle.
    #[must_use]
    pub fn bytes_per_triangle(&self) -> f64 {
        self.heap_bytes() as f64 / self.triangles.len().max(1) as f64
    }

    /// An object-space point in the frame generated mappings use: the model's bounding box
    /// centred on the origin and scaled uniformly so its largest side spans [-1, 1] (the
    /// generic objects' size). Returns the point and the scale applied to offsets.
    #[must_use]
    #[inline]
    pub fn to_mapping_frame(&self, p: Vec3A) -> (Vec3A, f32) {
        ((p - self.map_centre) * self.map_scale, self.map_scale)
    }

    /// The centre and scale of the frame generated mappings see ([`Mesh::to_mapping_frame`]:
    /// `(p - centre) * scale`), for the inspector's worked formula.
    #[must_use]
    pub fn mapping_frame(&self) -> (Vec3A, f32) {
        (self.map_centre, self.map_scale)
    }

    /// Triangle `triangle`'s (BVH order, as [`LocalHit::prim`]) vertex positions and their
    /// (u, v) when the mesh has them, for the inspector.
    #[must_use]
    pub fn triangle_vertices(&self, triangle: u32) -> Option<([Vec3; 3], Option<[Vec2; 3]>)> {
        let t = self.triangles.get(triangle as usize)?.map(|k| k as usize);
        let uv = (!self.uvs.is_empty()).then(|| t.map(|k| self.uvs[k]));
        Some((t.map(|k| self.positions[k]), uv))
    }

    /// Every triangle's (u, v) corners (none without (u, v)): the mesh's UV layout.
    pub fn uv_triangles(&self) -> impl Iterator<Item = [Vec2; 3]> + '_ {
        let uvs = &self.uvs;
        self.triangles
            .iter()
            .filter(move |_| !uvs.is_empty())
            .map(move |t| t.map(|k| uvs[k as usize]))
    }

    /// The nearest triangle hit in (0, `t_max`) of an object-space ray: the width-1 instance of
    /// [`Mesh::closest_hit_lanes`] (equal t go to the lower triangle index).
    #[must_use]
    #[inline]
    pub fn closest_hit(&self, ray: &Ray, t_max: f32) -> Option<TriangleHit> {
        let s = pulp::Scalar;
        let (o, d) = (V3::one(ray.origin), V3::one(ray.dir));
        let h = self.closest_hit_lanes(s, &o, &d, t_max, true);
        h.hit.then(|| TriangleHit {
            triangle: h.triangle[0],
            t: h.t,
            bary: Vec3::new(h.bary.x, h.bary.y, h.bary.z),
        })
    }

    /// Whether any triangle lies on the object-space ray within (0, `t_max`) (shadow rays):
    /// the width-1 instance of [`Mesh::occluded_lanes`].
    #[must_use]
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let s = pulp::Scalar;
        let (o, d) = (V3::one(ray.origin), V3::one(ray.dir));
        self.occluded_lanes(s, &o, &d, t_max, true)
    }

    /// The nearest hit as a [`LocalHit`], with dp/du and dp/dv.
    #[must_use]
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32, shading: Shading) -> Option<LocalHit> {
        let h = self.closest_hit(ray, t_max)?;
        Some(self.surface(h, shading))
    }

    /// [`Mesh::intersect`] without dp/du and dp/dv (`dpduv` left `None`): what a render needs
    /// unless a footprint filter asks for them ([`Mesh::uv_derivatives`]); they were 4% of a
    /// pass over a 1 M-triangle mesh.
    #[must_use]
    #[inline]
    pub fn intersect_point(&self, ray: &Ray, t_max: f32, shading: Shading) -> Option<LocalHit> {
        let h = self.closest_hit(ray, t_max)?;
        Some(self.surface_point(h, shading))
    }

    /// Everything shading needs at a triangle hit, interpolated by its barycentrics: the point
    /// (reprojected onto the triangle), the normals, (u, v) and dp/du, dp/dv. The one place the
    /// flat and smooth triangles share, as the lecture's base `MeshTriangle`.
    #[must_use]
    pub fn surface(&self, hit: TriangleHit, shading: Shading) -> LocalHit {
        LocalHit {
            dpduv: self.uv_derivatives(hit.triangle),
            ..self.surface_point(hit, shading)
        }
    }

    /// dp/du and dp/dv of triangle `triangle` (BVH order, as [`LocalHit::prim`]), or `None`
    /// without (u, v) or where the (u, v) triangle has zero area.
    #[must_use]
    pub fn uv_derivatives(&self, triangle: u32) -> Option<(Vec3A, Vec3A)> {
        if self.uvs.is_empty() {
            return None;
        }
        let [a, b, c] = self.triangles.get(triangle as usize)?.map(|k| k as usize);
        let (p0, p1, p2) = (self.positions[a], self.positions[b], self.positions[c]);
        dp_duv(p0, p1, p2, self.uvs[a], self.uvs[b], self.uvs[c])
    }

    /// [`Mesh::surface`] without dp/du and dp/dv: the width-1 instance of
    /// [`Mesh::surface_lanes`].
    #[must_use]
    pub fn surface_point(&self, hit: TriangleHit, shading: Shading) -> LocalHit {
        let mut triangle = [0; MAX_LANES];
        triangle[0] = hit.triangle;
        let hits = TriangleHits::<pulp::Scalar> {
            t: hit.t,
            hit: true,
            triangle,
            bary: V3::one(hit.bary.into()),
        };
        let m = self.surface_lanes(pulp::Scalar, &hits, shading);
        LocalHit {
            t: hit.t,
            p: m.p.vec(),
            n: m.n.vec(),
            ns: m.ns.vec(),
            uv: m.has_uv.then(|| Vec2::new(m.u, m.v)),
            dpduv: None,
            part: m.part[0],
            prim: hit.triangle,
        }
    }
}

/// dp/du and dp/dv of a triangle (pbrt's solve), or `None` where the (u, v) triangle has zero
/// area: the texture's derivatives are then zero (the finest level), never NaN.
fn dp_duv(p0: Vec3, p1: Vec3, p2: Vec3, t0: Vec2, t1: Vec2, t2: Vec2) -> Option<(Vec3A, Vec3A)> {
    if is_zero_uv_area(t0, t1, t2) {
        return None;
    }
    let (d02, d12) = (t0 - t2, t1 - t2);
    let (dp02, dp12) = (p0 - p2, p1 - p2);
    let det = d02.x * d12.y - d02.y * d12.x;
    let inv = 1.0 / det;
    let dpdu = (dp02 * d12.y - dp12 * d02.y) * inv;
    let dpdv = (dp12 * d02.x - dp02 * d12.x) * inv;
    (dpdu.is_finite() && dpdv.is_finite()).then(|| (dpdu.into(), dpdv.into()))
}

/// Renumbers the vertices in the order the (BVH-ordered) triangles first use them, so the
/// vertices of a leaf, and of nearby leaves, sit together in memory. Unused vertices go last.
fn renumber_vertices(
    positions: &[Vec3],
    uvs: Vec<Vec2>,
    normals: &[Vec3],
    mut triangles: Vec<[u32; 3]>,
) -> (Vec<Vec3>, Vec<Vec2>, Vec<Vec3>, Vec<[u32; 3]>) {
    const UNSEEN: u32 = u32::MAX;
    let mut new_index = vec![UNSEEN; positions.len()];
    let mut old_of_new = Vec::with_capacity(positions.len());
    for t in &mut triangles {
        for k in t.iter_mut() {
            let slot = &mut new_index[*k as usize];
            if *slot == UNSEEN {
                *slot = old_of_new.len() as u32;
                old_of_new.push(*k);
            }
            *k = *slot;
        }
    }
    for (old, slot) in new_index.iter().enumerate() {
        if *slot == UNSEEN {
            old_of_new.push(old as u32);
        }
    }
    let pick = |i: &u32| *i as usize;
    let positions = old_of_new.iter().map(|i| positions[pick(i)]).collect();
    let uvs = if uvs.is_empty() {
        uvs
    } else {
        old_of_new.iter().map(|i| uvs[pick(i)]).collect()
    };
    let normals = old_of_new.iter().map(|i| normals[pick(i)]).collect();
    (positions, uvs, normals, triangles)
}

/// Area-weighted vertex normals: each triangle adds its unnormalised cross product (twice its
/// area times its normal) to its corners.
fn area_weighted_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut acc = vec![Vec3::ZERO; positions.len()];
    for t in triangles {
        let [a, b, c] = t.map(|k| k as usize);
        let n = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
        if n.is_finite() {
            acc[a] += n;
            acc[b] += n;
            acc[c] += n;
        }
    }
    for n in &mut acc {
        *n = n.normalize_or_zero();
    }
    acc
}

#[cfg(test)]
mod tests;
