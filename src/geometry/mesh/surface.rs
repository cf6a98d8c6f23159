//! The surface at a packet's triangle hits, lane-wise: the point, the geometric and shading
//! normals and (u, v), interpolated by barycentrics. Each lane's triangle is its own, so its
//! vertex data is gathered per lane (one load per lane and value); the arithmetic runs on the
//! lanes together. [`Mesh::surface`] is the width-1 instance.

use super::{Mesh, Shading, TriangleHits};
use crate::math::lanes::{F, MAX_LANES, V3, finite, from_array, mask_to_array};
use crate::math::{Vec2, Vec3, Vec3A};
use pulp::Simd;

/// The surface at each lane's hit ([`Mesh::surface_lanes`]), in object space. Lanes without a
/// hit hold finite values of no meaning.
#[derive(Clone, Copy, Debug)]
pub struct MeshSurface<S: Simd> {
    /// The hit point, interpolated from the triangle's corners by the barycentrics (so on the
    /// triangle, not `o + t d`).
    pub p: V3<S>,
    /// The geometric normal, unit length; with smooth shading turned to the side the shading
    /// normal is on (the outside is where the vertex normals point, whatever the winding).
    pub n: V3<S>,
    /// The shading normal: `n` for flat shading, the vertex normals interpolated and
    /// normalised for smooth shading (`n` where they cancel).
    pub ns: V3<S>,
    /// u per lane, interpolated from the vertices' (0 when the mesh has no (u, v)).
    pub u: F<S>,
    /// v per lane.
    pub v: F<S>,
    /// Whether the mesh has (u, v) (else `u` and `v` are 0).
    pub has_uv: bool,
    /// Each lane's triangle's index in the file ([`crate::geometry::LocalHit::part`]).
    pub part: [u32; MAX_LANES],
}

/// `w0 a + w1 b + w2 c` per lane, summed as glam's `a * w0 + b * w1 + c * w2`.
#[inline(always)]
fn blend<S: Simd>(s: S, w: &V3<S>, a: F<S>, b: F<S>, c: F<S>) -> F<S> {
    s.add_f32s(
        s.add_f32s(s.mul_f32s(a, w.x), s.mul_f32s(b, w.y)),
        s.mul_f32s(c, w.z),
    )
}

/// Unit length per lane, or `fallback` where the reciprocal length is not finite or not above
/// 0 (glam's `Vec3::normalize_or`, with a fallback per lane).
#[inline(always)]
fn normalize_or<S: Simd>(s: S, v: &V3<S>, fallback: &V3<S>) -> V3<S> {
    let rcp = s.div_f32s(s.splat_f32s(1.0), s.sqrt_f32s(v.dot(s, v)));
    let ok = s.and_m32s(finite(s, rcp), s.greater_than_f32s(rcp, s.splat_f32s(0.0)));
    V3::select(s, ok, &v.scale(s, rcp), fallback)
}

impl Mesh {
    /// The vertices' `values` of each lane's triangle, gathered into lane buffers.
    #[inline(always)]
    fn gather<T: Copy, const N: usize>(
        &self,
        lanes: usize,
        triangle: &[u32; MAX_LANES],
        values: &[T],
        array: impl Fn(T) -> [f32; N],
    ) -> [[[f32; MAX_LANES]; N]; 3] {
        let mut out = [[[0.0; MAX_LANES]; N]; 3];
        for (i, &t) in triangle[..lanes].iter().enumerate() {
            for (corner, &k) in self.triangles[t as usize].iter().enumerate() {
                let v = array(values[k as usize]);
                for axis in 0..N {
                    out[corner][axis][i] = v[axis];
                }
            }
        }
        out
    }

    /// The surface at each lane's hit of `hits` (from [`Mesh::closest_hit_lanes`]): point,
    /// normals and (u, v), each lane the same bits as [`Mesh::surface`] gives it alone. The
    /// vertex data is gathered per lane; the interpolation runs on the lanes together.
    #[must_use]
    #[inline(always)]
    pub fn surface_lanes<S: Simd>(
        &self,
        s: S,
        hits: &TriangleHits<S>,
        shading: Shading,
    ) -> MeshSurface<S> {
        let lanes = S::F32_LANES;
        let hit = mask_to_array(s, hits.hit);
        // Lanes without a hit read triangle 0 (every mesh has one): finite, meaningless.
        let triangle: [u32; MAX_LANES] =
            crate::math::lanes::each_lane(|i| if hit[i] { hits.triangle[i] } else { 0 });
        let w = &hits.bary;
        let pc = self.gather(lanes, &triangle, &self.positions, |v: Vec3| v.to_array());
        let (p0, p1, p2) = (
            V3::<S>::from_arrays(&pc[0]),
            V3::<S>::from_arrays(&pc[1]),
            V3::<S>::from_arrays(&pc[2]),
        );
        let p = V3 {
            x: blend(s, w, p0.x, p1.x, p2.x),
            y: blend(s, w, p0.y, p1.y, p2.y),
            z: blend(s, w, p0.z, p1.z, p2.z),
        };
        let up = V3::splat(s, Vec3A::Y);
        let mut n = normalize_or(s, &p1.sub(s, &p0).cross(s, &p2.sub(s, &p0)), &up);
        let ns = match shading {
            Shading::Flat => n,
            Shading::Smooth => {
                let nc = self.gather(lanes, &triangle, &self.normals, |v: Vec3| v.to_array());
                let (n0, n1, n2) = (
                    V3::<S>::from_arrays(&nc[0]),
                    V3::<S>::from_arrays(&nc[1]),
                    V3::<S>::from_arrays(&nc[2]),
                );
                let blended = V3 {
                    x: blend(s, w, n0.x, n1.x, n2.x),
                    y: blend(s, w, n0.y, n1.y, n2.y),
                    z: blend(s, w, n0.z, n1.z, n2.z),
                };
                let ns = normalize_or(s, &blended, &n);
                let behind = s.less_than_f32s(ns.dot(s, &n), s.splat_f32s(0.0));
                n = V3::select(s, behind, &n.neg(s), &n);
                ns
            }
        };
        let has_uv = !self.uvs.is_empty();
        let (u, v) = if has_uv {
            let tc = self.gather(lanes, &triangle, &self.uvs, |v: Vec2| v.to_array());
            (
                blend(
                    s,
                    w,
                    from_array::<S>(&tc[0][0]),
                    from_array::<S>(&tc[1][0]),
                    from_array::<S>(&tc[2][0]),
                ),
                blend(
                    s,
                    w,
                    from_array::<S>(&tc[0][1]),
                    from_array::<S>(&tc[1][1]),
                    from_array::<S>(&tc[2][1]),
                ),
            )
        } else {
            (s.splat_f32s(0.0), s.splat_f32s(0.0))
        };
        MeshSurface {
            p,
            n,
            ns,
            u,
            v,
            has_uv,
            part: triangle.map(|t| self.file_index.get(t as usize).copied().unwrap_or(0)),
        }
    }
}
