//! A bounding volume hierarchy over primitives given by their boxes: binned SAH build (parallel
//! for large subtrees), flattened in depth-first order with the two children of each node in
//! one 64-byte cache line ([`Pair`]), and a traversal that visits the nearer child first and
//! never culls a box the ray touches (Ize 2013, "Robust BVH Ray Traversal"), so a watertight
//! triangle test stays watertight.

mod lanes;

pub use lanes::{BoxRays, Leaves, any_lane, dominant_axis, pick};

use crate::math::Vec3;

/// Most primitives in a leaf (below 16: the traversal stack packs a leaf's count in 4 bits).
pub const MAX_LEAF: usize = 8;
const _: () = assert!(MAX_LEAF < 16);
/// SAH bins per axis.
const BINS: usize = 16;
/// Cost of visiting a node, relative to one primitive test (0.5 and 1 measured the same on the
/// 1 M-triangle bench).
const TRAVERSAL_COST: f32 = 1.0;
/// Nodes with at most this many primitives become leaves without asking the SAH (small leaves
/// cost memory, a node per triangle, and save little time).
const MIN_SPLIT: usize = 3;
/// Nodes with more primitives than this are binned along their widest centroid axis only (the
/// SAH's choice among axes matters little for big nodes and binning one axis is 3 times faster).
const ONE_AXIS_ABOVE: usize = 1024;
/// Subtrees larger than this are built on two rayon tasks.
const PARALLEL_THRESHOLD: usize = 8192;
/// Beyond this depth splits are by count (object median), which bounds the depth for any input.
const SAH_DEPTH_LIMIT: u32 = 40;
/// Most primitives a hierarchy holds (meshes stop at [`crate::meshio::MAX_TRIANGLES`]): node
/// references then fit in 28 bits, with a leaf's count in the 4 above.
pub const MAX_PRIMITIVES: usize = 1 << 28;
/// Deepest tree the traversal stack holds: the SAH limit plus the median splits of
/// [`MAX_PRIMITIVES`] items.
pub const MAX_DEPTH: usize = SAH_DEPTH_LIMIT as usize + 28;
/// 1 + 2 gamma(3) in f32: widening the far distance by this keeps the slab test conservative
/// (a box a ray grazes is never culled by rounding).
const ROBUST_FAR: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest x, y and z inside (+infinity in [`Aabb::EMPTY`]).
    pub min: Vec3,
    /// Largest x, y and z inside (-infinity in [`Aabb::EMPTY`]).
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (grows from nothing).
    pub const EMPTY: Self = Self {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// The box around three points.
    #[must_use]
    #[inline]
    pub fn of_triangle(a: Vec3, b: Vec3, c: Vec3) -> Self {
        Self {
            min: a.min(b).min(c),
            max: a.max(b).max(c),
        }
    }

    /// The smallest box holding both.
    #[must_use]
    #[inline]
    pub fn union(self, o: Self) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// Half the surface area (enough for SAH ratios); 0 for the empty box.
    #[must_use]
    #[inline]
    pub fn half_area(self) -> f32 {
        let d = (self.max - self.min).max(Vec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    /// The midpoint of `min` and `max`: where the BVH build bins a primitive, and the centre of
    /// a mesh's mapping frame.
    #[must_use]
    #[inline]
    pub fn centre(self) -> Vec3 {
        (self.min + self.max) * 0.5
    }
}

/// A node as the build writes it, and a child entry in a [`Pair`]: 32 bytes, its box, and
/// `count` primitives `index .. index + count` (in the order [`Bvh::build`] returned) for a
/// leaf. For an interior node `count == 0`: in the build's depth-first list its first child
/// follows it and `index` is the second; in a [`Pair`] `index` is the pair holding its
/// children.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Node {
    min: [f32; 3],
    index: u32,
    max: [f32; 3],
    count: u16,
    axis: u16,
}

/// The two children of an interior node side by side in one 64-byte cache line: a traversal
/// step tests both boxes with one memory access (the boxes of a node's children, not its own,
/// are what the step needs).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct Pair([Node; 2]);

/// The hierarchy: the root's box, and a [`Pair`] per interior node in depth-first order (the
/// first child's pair right after its parent's).
#[derive(Clone, Debug)]
pub struct Bvh {
    root: Node,
    pairs: Vec<Pair>,
}

impl Default for Bvh {
    fn default() -> Self {
        Self {
            root: leaf(Aabb::EMPTY, 0, 0),
            pairs: Vec::new(),
        }
    }
}

#[derive(Clone, Copy)]
struct Prim {
    bounds: Aabb,
    centre: Vec3,
    index: u32,
}

/// The component along `axis` (0, 1, 2) as a plain function, chosen once per node rather than
/// indexed per primitive.
fn component(axis: usize) -> fn(Vec3) -> f32 {
    match axis {
        0 => |v| v.x,
        1 => |v| v.y,
        _ => |v| v.z,
    }
}

impl Bvh {
    /// Builds over `bounds` (one box per primitive). Returns the hierarchy and the primitive
    /// order its leaves refer to: leaf ranges index into `order`, so callers reorder their
    /// primitives by it.
    ///
    /// # Panics
    /// With 2^28 primitives or more (a leaf's first index has 28 bits); meshes are refused long
    /// before that by their loaders' limits.
    #[must_use]
    pub fn build(bounds: &[Aabb]) -> (Self, Vec<u32>) {
        let mut prims: Vec<Prim> = bounds
            .iter()
            .enumerate()
            .map(|(i, b)| Prim {
                bounds: *b,
                centre: b.centre(),
                index: i as u32,
            })
            .collect();
        assert!(
            bounds.len() < MAX_PRIMITIVES,
            "a BVH holds fewer than 2^28 primitives"
        );
        let mut nodes = Vec::with_capacity(2 * bounds.len() / 3 + 1);
        if prims.is_empty() {
            return (Self::default(), Vec::new());
        }
        build_node(&mut prims, 0, 0, &mut nodes);
        let order = prims.iter().map(|p| p.index).collect();
        (Self::from_depth_first(&nodes), order)
    }

    /// Pairs up the children of the build's depth-first node list.
    fn from_depth_first(nodes: &[Node]) -> Self {
        // The pair of interior node i is its rank among the interior nodes.
        let mut pair_of = vec![0u32; nodes.len()];
        let mut interior = 0u32;
        for (i, n) in nodes.iter().enumerate() {
            if n.count == 0 {
                pair_of[i] = interior;
                interior += 1;
            }
        }
        let entry = |i: usize| {
            let n = nodes[i];
            if n.count == 0 {
                Node {
                    index: pair_of[i],
                    ..n
                }
            } else {
                n
            }
        };
        let mut pairs = Vec::with_capacity(interior as usize);
        pairs.extend(
            nodes
                .iter()
                .enumerate()
                .filter(|(_, n)| n.count == 0)
                .map(|(i, n)| Pair([entry(i + 1), entry(n.index as usize)])),
        );
        Self {
            root: entry(0),
            pairs,
        }
    }

    /// Number of nodes (the root and every child).
    #[must_use]
    pub fn node_count(&self) -> usize {
        if self.root.count == 0 && self.pairs.is_empty() {
            0
        } else {
            1 + 2 * self.pairs.len()
        }
    }

    /// Heap bytes held.
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        self.pairs.capacity() * std::mem::size_of::<Pair>()
    }

    /// The box around everything (empty for an empty hierarchy).
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        Aabb {
            min: Vec3::from_array(self.root.min),
            max: Vec3::from_array(self.root.max),
        }
    }
}

fn bounds_of(prims: &[Prim]) -> (Aabb, Aabb) {
    let mut b = Aabb::EMPTY;
    let mut c = Aabb::EMPTY;
    for p in prims {
        b = b.union(p.bounds);
        c.min = c.min.min(p.centre);
        c.max = c.max.max(p.centre);
    }
    (b, c)
}

fn leaf(bounds: Aabb, first: usize, count: usize) -> Node {
    Node {
        min: bounds.min.to_array(),
        index: first as u32,
        max: bounds.max.to_array(),
        count: count as u16,
        axis: 0,
    }
}

/// Builds the subtree of `prims` (which start at `first` in the global order) into `out`, with
/// node indices relative to `out[0]`.
fn build_node(prims: &mut [Prim], first: usize, depth: u32, out: &mut Vec<Node>) {
    let (bounds, centres) = if prims.len() > PARALLEL_THRESHOLD * 8 {
        let (a, b) = prims.split_at(prims.len() / 2);
        let ((ba, ca), (bb, cb)) = rayon::join(|| bounds_of(a), || bounds_of(b));
        (ba.union(bb), ca.union(cb))
    } else {
        bounds_of(prims)
    };
    let n = prims.len();
    if n <= MIN_SPLIT {
        out.push(leaf(bounds, first, n));
        return;
    }
    let Some((axis, mid)) = choose_split(prims, bounds, centres, depth) else {
        out.push(leaf(bounds, first, n));
        return;
    };
    let me = out.len();
    out.push(Node {
        min: bounds.min.to_array(),
        index: 0,
        max: bounds.max.to_array(),
        count: 0,
        axis: axis as u16,
    });
    let (left, right) = prims.split_at_mut(mid);
    if n > PARALLEL_THRESHOLD {
        let (mut l, mut r) = (Vec::new(), Vec::new());
        rayon::join(
            || build_node(left, first, depth + 1, &mut l),
            || build_node(right, first + mid, depth + 1, &mut r),
        );
        append(out, l);
        out[me].index = out.len() as u32;
        append(out, r);
    } else {
        build_node(left, first, depth + 1, out);
        out[me].index = out.len() as u32;
        build_node(right, first + mid, depth + 1, out);
    }
}

/// Appends a subtree built with indices relative to its own start.
fn append(out: &mut Vec<Node>, sub: Vec<Node>) {
    let base = out.len() as u32;
    out.extend(sub.into_iter().map(|mut n| {
        if n.count == 0 {
            n.index += base;
        }
        n
    }));
}

/// The split axis and the count of primitives that go left (after partitioning `prims`), or
/// `None` when a leaf is cheaper and small enough.
fn choose_split(
    prims: &mut [Prim],
    bounds: Aabb,
    centres: Aabb,
    depth: u32,
) -> Option<(usize, usize)> {
    let n = prims.len();
    let extent = centres.max - centres.min;
    let widest = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    if extent[widest] <= 0.0 || depth >= SAH_DEPTH_LIMIT {
        // All centres coincide (or the tree is deep): split by count so the depth stays bounded.
        if n <= MAX_LEAF {
            return None;
        }
        let mid = n / 2;
        prims.select_nth_unstable_by(mid, |a, b| a.centre[widest].total_cmp(&b.centre[widest]));
        return Some((widest, mid));
    }

    // Bin the centres along every axis with a non-zero extent.
    let mut best: Option<(f32, usize, usize)> = None; // cost, axis, bins on the left
    let mut counts = [[0u32; BINS]; 3];
    let mut boxes = [[Aabb::EMPTY; BINS]; 3];
    let scale = Vec3::select(
        extent.cmpgt(Vec3::ZERO),
        Vec3::splat(BINS as f32 * (1.0 - f32::EPSILON)) / extent,
        Vec3::ZERO,
    );
    let axes = if n > ONE_AXIS_ABOVE {
        widest..widest + 1
    } else {
        0..3
    };
    if axes.len() == 1 {
        let (min, s) = (centres.min[widest], scale[widest]);
        let get = component(widest);
        let (counts, boxes) = (&mut counts[widest], &mut boxes[widest]);
        for p in prims.iter() {
            let i = (((get(p.centre) - min) * s) as usize).min(BINS - 1);
            counts[i] += 1;
            boxes[i] = boxes[i].union(p.bounds);
        }
    } else {
        for p in prims.iter() {
            let b = ((p.centre - centres.min) * scale)
                .as_uvec3()
                .min(glam::UVec3::splat(BINS as u32 - 1));
            for axis in 0..3 {
                let i = b[axis] as usize;
                counts[axis][i] += 1;
                boxes[axis][i] = boxes[axis][i].union(p.bounds);
            }
        }
    }
    for axis in axes {
        if extent[axis] <= 0.0 {
            continue;
        }
        // Sweep from the right, then from the left.
        let mut right_area = [0.0f32; BINS];
        let mut acc = Aabb::EMPTY;
        for i in (1..BINS).rev() {
            acc = acc.union(boxes[axis][i]);
            right_area[i] = acc.half_area();
        }
        let mut acc = Aabb::EMPTY;
        let mut left_count = 0u32;
        for i in 0..BINS - 1 {
            acc = acc.union(boxes[axis][i]);
            left_count += counts[axis][i];
            let right_count = n as u32 - left_count;
            if left_count == 0 || right_count == 0 {
                continue;
            }
            let cost = acc.half_area() * left_count as f32 + right_area[i + 1] * right_count as f32;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, i + 1));
            }
        }
    }
    let area = bounds.half_area();
    let leaf_cost = n as f32;
    let (cost, axis, split_bin) = best?;
    let split_cost = if area > 0.0 {
        TRAVERSAL_COST + cost / area
    } else {
        f32::INFINITY
    };
    if split_cost >= leaf_cost && n <= MAX_LEAF {
        return None;
    }
    let min = centres.min[axis];
    let s = scale[axis];
    let get = component(axis);
    let goes_left = |p: &Prim| {
        let b = (((get(p.centre) - min) * s) as usize).min(BINS - 1);
        b < split_bin
    };
    let mid = partition(prims, goes_left);
    if mid == 0 || mid == n {
        let mid = n / 2;
        prims.select_nth_unstable_by(mid, |a, b| a.centre[axis].total_cmp(&b.centre[axis]));
        return Some((axis, mid));
    }
    Some((axis, mid))
}

/// Moves the elements for which `left` holds to the front; returns how many there are.
fn partition(v: &mut [Prim], left: impl Fn(&Prim) -> bool) -> usize {
    let mut i = 0;
    let mut j = v.len();
    loop {
        while i < j && left(&v[i]) {
            i += 1;
        }
        while i < j && !left(&v[j - 1]) {
            j -= 1;
        }
        if i >= j {
            return i;
        }
        v.swap(i, j - 1);
        i += 1;
        j -= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{SampleRng, Vec3A};

    fn random_boxes(n: usize, seed: u32) -> Vec<Aabb> {
        let mut rng = SampleRng::new(seed, 0, 0);
        (0..n)
            .map(|_| {
                let c = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 10.0;
                let h = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 0.2;
                Aabb {
                    min: c - h,
                    max: c + h,
                }
            })
            .collect()
    }

    /// Every primitive appears once in the order, every leaf range is in bounds, and every
    /// node's box holds its children's.
    #[test]
    fn build_is_a_partition_with_nested_boxes() {
        for n in [1, 2, 3, 9, 100, 20_000] {
            let boxes = random_boxes(n, 7);
            let (bvh, order) = Bvh::build(&boxes);
            let mut seen = order.clone();
            seen.sort_unstable();
            assert_eq!(seen, (0..n as u32).collect::<Vec<_>>());
            // Walk the pairs from the root: every child box inside its parent's, every leaf
            // range in bounds and holding its primitives' boxes.
            let mut covered = 0usize;
            let mut todo = vec![(bvh.root, None::<Node>)];
            while let Some((node, parent)) = todo.pop() {
                let inside = |outer: &Node, b: &Aabb| {
                    Vec3::from_array(outer.min).cmple(b.min).all()
                        && Vec3::from_array(outer.max).cmpge(b.max).all()
                };
                if let Some(parent) = parent {
                    let b = Aabb {
                        min: Vec3::from_array(node.min),
                        max: Vec3::from_array(node.max),
                    };
                    assert!(inside(&parent, &b));
                }
                if node.count > 0 {
                    assert!(node.count as usize <= MAX_LEAF.max(2));
                    for k in node.index..node.index + u32::from(node.count) {
                        assert!(inside(&node, &boxes[order[k as usize] as usize]));
                    }
                    covered += node.count as usize;
                } else {
                    let [a, b] = bvh.pairs[node.index as usize].0;
                    todo.push((a, Some(node)));
                    todo.push((b, Some(node)));
                }
            }
            assert_eq!(covered, n);
            assert_eq!(bvh.node_count(), 1 + 2 * bvh.pairs.len());
        }
    }

    /// Identical centres (a degenerate input) still build a shallow tree with small leaves.
    #[test]
    fn coincident_primitives_split_by_count() {
        let b = Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        };
        let (bvh, order) = Bvh::build(&vec![b; 1000]);
        assert_eq!(order.len(), 1000);
        let leaves = bvh.pairs.iter().flat_map(|p| p.0).filter(|n| n.count > 0);
        assert!(leaves.clone().all(|n| n.count as usize <= MAX_LEAF));
        assert_eq!(leaves.map(|n| n.count as usize).sum::<usize>(), 1000);
    }

    /// Counts the leaves a walk reaches.
    struct Reached(u32);

    impl Leaves<pulp::Scalar> for Reached {
        fn leaf(&mut self, _: pulp::Scalar, _: u32, _: u32, lanes: bool) {
            self.0 += u32::from(lanes);
        }
        fn bound(&self, _: pulp::Scalar) -> f32 {
            f32::INFINITY
        }
        fn searching(&self, _: pulp::Scalar) -> bool {
            true
        }
    }

    /// A ray along a box's face (zero thickness box, axis-parallel ray) is not culled.
    #[test]
    fn flat_boxes_and_axis_parallel_rays_are_not_culled() {
        use crate::math::lanes::V3;
        let flat = Aabb {
            min: Vec3::new(-1.0, 0.0, -1.0),
            max: Vec3::new(1.0, 0.0, 1.0),
        };
        let (bvh, _) = Bvh::build(&[flat]);
        let s = pulp::Scalar;
        let reaches = |x: f32, z: f32| {
            let (o, d) = (V3::one(Vec3A::new(x, 2.0, z)), V3::one(Vec3A::NEG_Y));
            let mut r = Reached(0);
            bvh.walk(
                s,
                &BoxRays::new(s, &o, &d, true),
                f32::INFINITY,
                true,
                &mut r,
            );
            r.0 > 0
        };
        assert!(reaches(0.3, 0.7));
        assert!(reaches(1.0, 1.0));
        assert!(!reaches(1.001, 1.0));
    }
}
