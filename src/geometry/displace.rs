//! Displacement maps, at load time on meshes: every triangle is split into four at its edge
//! midpoints (`levels` times), then every vertex moves along its interpolated normal by a
//! height, and the shading normals follow the moved surface.
//!
//! - **Watertight.** A midpoint is shared by the two triangles of its edge, so no T-junctions
//!   appear. Vertices that share a position but not their (u, v) or normal (a UV seam, a hard
//!   edge) are welded for the move: they all go along their mean normal by their mean height,
//!   so they stay one point and the surface does not crack there.
//! - **Normals.** The shading normal of a vertex is its interpolated normal turned by the
//!   rotation that takes the surface's normal there before the move to the one after (both
//!   area-weighted over the welded vertex), so a zero height leaves every normal as it was and
//!   hard edges stay hard.
//!
//! What texplore does not do: displace per pixel or per ray (no micropolygons, no adaptive
//! tessellation), or displace the analytic shapes (a bump map gives their look).

pub use super::mesh::Displacement;
use super::mesh::MeshData;
use crate::math::{Quat, Vec3};
use std::collections::HashMap;

/// Most triangles a displaced mesh may have after subdivision: 2^22 (4 M); building 3.8 M
/// took 0.75 GB at its peak (measured), so a preset cannot ask for gigabytes.
pub const MAX_DISPLACED_TRIANGLES: usize = 1 << 22;

/// The triangles `triangles` make after `levels` subdivisions (4^levels each), saturating.
#[must_use]
pub fn subdivided_triangle_count(triangles: usize, levels: u32) -> usize {
    triangles.saturating_mul(4usize.saturating_pow(levels))
}

/// `data` with every triangle split into four at its edge midpoints, `levels` times:
/// positions, (u, v) and normals interpolated at the midpoints (normals renormalised), each
/// midpoint shared by the triangles on both sides of its edge. Returns the mesh and, for each of
/// its triangles, the index of the triangle of `data` it lies in. Only the vertex arrays and
/// triangles are carried; `data` must be valid ([`MeshData::validate`]) and its normals, if
/// any, one per vertex.
#[must_use]
pub fn subdivide(data: &MeshData, levels: u32) -> (MeshData, Vec<u32>) {
    let mut out = MeshData {
        positions: data.positions.clone(),
        uvs: data.uvs.clone(),
        normals: data.normals.clone(),
        triangles: data.triangles.clone(),
        ..MeshData::default()
    };
    let mut parent: Vec<u32> = (0..data.triangles.len() as u32).collect();
    for _ in 0..levels {
        let (next, from) = split_once(&out);
        parent = from.iter().map(|&t| parent[t as usize]).collect();
        out = next;
    }
    (out, parent)
}

/// One level of [`subdivide`]: each triangle (a, b, c) becomes (a, ab, ca), (ab, b, bc),
/// (ca, bc, c) and (ab, bc, ca), keeping its winding.
fn split_once(d: &MeshData) -> (MeshData, Vec<u32>) {
    let n = d.positions.len();
    let edges = d.triangles.len() * 3 / 2 + 1;
    let mut out = MeshData {
        positions: Vec::with_capacity(n + edges),
        uvs: Vec::with_capacity(if d.uvs.is_empty() { 0 } else { n + edges }),
        normals: Vec::with_capacity(if d.normals.is_empty() { 0 } else { n + edges }),
        triangles: Vec::with_capacity(d.triangles.len() * 4),
        ..MeshData::default()
    };
    out.positions.extend_from_slice(&d.positions);
    out.uvs.extend_from_slice(&d.uvs);
    out.normals.extend_from_slice(&d.normals);
    let mut parent = Vec::with_capacity(d.triangles.len() * 4);
    let mut midpoints: HashMap<u64, u32> = HashMap::with_capacity(edges);
    let mut mid = |out: &mut MeshData, i: u32, j: u32| -> u32 {
        let key = (u64::from(i.min(j)) << 32) | u64::from(i.max(j));
        *midpoints.entry(key).or_insert_with(|| {
            let (a, b) = (i as usize, j as usize);
            let k = out.positions.len() as u32;
            // Sums are commutative in IEEE arithmetic: the two copies of an edge on a seam
            // get bit-identical midpoints. Halved before the sum (exact, so the same bits as
            // halving the sum), so values past half the largest float, which a file may hold,
            // do not overflow: (u, v) of 3e38 gave midpoints of infinity.
            out.positions
                .push(d.positions[a] * 0.5 + d.positions[b] * 0.5);
            if !d.uvs.is_empty() {
                out.uvs.push(d.uvs[a] * 0.5 + d.uvs[b] * 0.5);
            }
            if !d.normals.is_empty() {
                out.normals
                    .push((d.normals[a] + d.normals[b]).normalize_or_zero());
            }
            k
        })
    };
    for (t, &[a, b, c]) in d.triangles.iter().enumerate() {
        let ab = mid(&mut out, a, b);
        let bc = mid(&mut out, b, c);
        let ca = mid(&mut out, c, a);
        out.triangles
            .extend_from_slice(&[[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        parent.extend_from_slice(&[t as u32; 4]);
    }
    (out, parent)
}

/// Groups the vertices that share a position (bit for bit, -0 as 0): each vertex's group index,
/// and the number of groups.
#[must_use]
pub fn weld_by_position(positions: &[Vec3]) -> (Vec<u32>, usize) {
    let mut groups: HashMap<[u32; 3], u32> = HashMap::with_capacity(positions.len());
    let group = positions
        .iter()
        .map(|p| {
            let key = (*p + Vec3::ZERO).to_array().map(f32::to_bits);
            let next = groups.len() as u32;
            *groups.entry(key).or_insert(next)
        })
        .collect();
    (group, groups.len())
}

/// Moves every vertex of `data` along its normal by `scale * heights[v]` (welded: vertices at
/// one position move together, along their mean normal by their mean height), then turns the
/// normals with the surface (see the module's notes). Returns the largest distance a vertex
/// moved. `data` needs one normal and one height per vertex; vertices whose mean normal is
/// undefined (opposite normals at one point) stay where they are.
///
/// # Panics
/// If `heights` or `data.normals` does not hold one value per vertex.
pub fn displace(data: &mut MeshData, heights: &[f32], scale: f32) -> f32 {
    let n = data.positions.len();
    assert!(heights.len() == n && data.normals.len() == n);
    let (group, groups) = weld_by_position(&data.positions);
    let mut dir = vec![Vec3::ZERO; groups];
    let mut height = vec![(0.0f64, 0u32); groups];
    for v in 0..n {
        let g = group[v] as usize;
        dir[g] += data.normals[v];
        height[g].0 += f64::from(heights[v]);
        height[g].1 += 1;
    }
    let before = welded_normals(&data.positions, &data.triangles, &group, groups);
    let mut moved = 0.0f32;
    // Every copy of a welded vertex gets the same offset, so the copies stay one point.
    let offset: Vec<Vec3> = dir
        .iter()
        .zip(&height)
        .map(|(d, &(sum, count))| {
            let h = if count == 1 {
                sum as f32
            } else {
                (sum / f64::from(count)) as f32
            };
            d.normalize_or_zero() * (scale * h)
        })
        .collect();
    for (p, g) in data.positions.iter_mut().zip(&group) {
        let o = offset[*g as usize];
        moved = moved.max(o.length());
        *p += o;
    }
    let after = welded_normals(&data.positions, &data.triangles, &group, groups);
    for (v, normal) in data.normals.iter_mut().enumerate() {
        let g = group[v] as usize;
        *normal = turned(*normal, before[g], after[g]);
    }
    moved
}

/// `n` turned by the rotation taking `from` to `to` (unit or zero); `n` itself where the two
/// are equal or either is undefined, `to` where `n` is.
fn turned(n: Vec3, from: Vec3, to: Vec3) -> Vec3 {
    if from == to || from == Vec3::ZERO || to == Vec3::ZERO {
        return if n == Vec3::ZERO { to } else { n };
    }
    if n == Vec3::ZERO {
        return to;
    }
    let r = (Quat::from_rotation_arc(from, to) * n).normalize_or(to);
    if r.is_finite() { r } else { to }
}

/// Area-weighted normals per welded vertex: each triangle adds its cross product to the
/// groups of its corners; unit, or zero where undefined.
fn welded_normals(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    group: &[u32],
    groups: usize,
) -> Vec<Vec3> {
    let mut acc = vec![Vec3::ZERO; groups];
    for t in triangles {
        let [a, b, c] = t.map(|k| k as usize);
        let n = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
        if n.is_finite() {
            for k in [a, b, c] {
                acc[group[k] as usize] += n;
            }
        }
    }
    for n in &mut acc {
        *n = n.normalize_or_zero();
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec2;

    /// A unit square in y = 0 as two triangles, (u, v) = (x, z).
    fn square() -> MeshData {
        MeshData {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 1.0),
                Vec3::new(0.0, 0.0, 1.0),
            ],
            uvs: vec![
                Vec2::new(0.0, 0.0),
                Vec2::new(1.0, 0.0),
                Vec2::new(1.0, 1.0),
                Vec2::new(0.0, 1.0),
            ],
            normals: vec![Vec3::Y; 4],
            triangles: vec![[0, 2, 1], [0, 3, 2]],
            ..MeshData::default()
        }
    }

    #[test]
    fn each_level_quadruples_the_triangles_and_shares_the_midpoints() {
        let (d, parent) = subdivide(&square(), 2);
        assert_eq!(d.triangles.len(), 32);
        assert_eq!(subdivided_triangle_count(2, 2), 32);
        // A 4 x 4 grid of quads has 5 x 5 vertices: every midpoint is shared.
        assert_eq!(d.positions.len(), 25);
        assert_eq!((d.uvs.len(), d.normals.len()), (25, 25));
        for (p, uv) in d.positions.iter().zip(&d.uvs) {
            assert_eq!(Vec2::new(p.x, p.z), *uv);
        }
        assert_eq!(parent.iter().filter(|&&t| t == 0).count(), 16);
        // The winding is kept: every small triangle faces +y as its parent does.
        for t in &d.triangles {
            let p = t.map(|k| d.positions[k as usize]);
            assert!((p[1] - p[0]).cross(p[2] - p[0]).y > 0.0);
        }
        assert_eq!(subdivided_triangle_count(usize::MAX / 2, 3), usize::MAX);
    }

    #[test]
    fn a_zero_height_moves_nothing_and_keeps_every_normal() {
        let (mut d, _) = subdivide(&square(), 1);
        let before = d.clone();
        let zero = vec![0.0; d.positions.len()];
        let moved = displace(&mut d, &zero, 0.5);
        assert_eq!(moved, 0.0);
        assert_eq!(d, before);
    }

    #[test]
    fn a_raised_centre_tilts_the_normals_around_it() {
        let (mut d, _) = subdivide(&square(), 1);
        let centre = d
            .positions
            .iter()
            .position(|p| *p == Vec3::new(0.5, 0.0, 0.5))
            .unwrap();
        let mut h = vec![0.0; d.positions.len()];
        h[centre] = 1.0;
        let moved = displace(&mut d, &h, 0.25);
        assert_eq!(moved, 0.25);
        assert_eq!(d.positions[centre], Vec3::new(0.5, 0.25, 0.5));
        let edge = d
            .positions
            .iter()
            .position(|p| *p == Vec3::new(0.5, 0.0, 0.0))
            .unwrap();
        // The edge midpoint's surface now slopes up toward the centre: its normal leans away.
        assert!(d.normals[edge].z < -0.1, "{}", d.normals[edge]);
        assert!((d.normals[centre] - Vec3::Y).length() < 1e-6);
        assert!(d.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
    }
}
