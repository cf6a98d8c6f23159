//! The hierarchy walked by a packet of rays at once: `S::F32_LANES` rays share one traversal,
//! each node's two child boxes are tested for every lane in SIMD, and a lane follows a subtree
//! only while it enters the box. One ray is the same code at width 1 (pulp's `Scalar`).
//!
//! **Order never changes a lane's answer.** A lane's leaves are those whose every ancestor box
//! it enters within (0, `t_max`) (the conservative slab test of Ize 2013: a box the ray touches
//! is never culled by rounding). That set depends on the lane alone. Boxes are then skipped once
//! a lane has a hit only when no primitive inside can be as near: the visitor's
//! [`Leaves::bound`] against the box's entry along the lane's *dominant axis* (the largest
//! direction component, the watertight test's kz). The triangle test's t lies within the
//! smallest and largest of its vertices' `(p[kz] - o[kz]) / d[kz]`, computed the same way as the
//! slab, so it is never below the entry of a box holding the triangle (rounding is monotone).
//! The entry along the other axes gives no such guarantee (a grazing triangle's t can round
//! below it), so it only decides which lanes enter a box. The packet's order of children (its
//! first lane's direction) thus changes the work, never the result.

use super::{Bvh, MAX_DEPTH, Node, ROBUST_FAR};
use crate::math::Vec3A;
use crate::math::lanes::{F, M, V3, any, mask_splat, mask_to_array, sign_negative, to_array};
use glam::BVec3A;
use pulp::Simd;

/// Which axis is each lane's dominant one: the largest |d| component, x before y before z on
/// ties (the watertight triangle test's kz). Returns the masks "is x" and "is y".
#[must_use]
#[inline(always)]
pub fn dominant_axis<S: Simd>(s: S, d: &V3<S>) -> (M<S>, M<S>) {
    let (ax, ay, az) = (s.abs_f32s(d.x), s.abs_f32s(d.y), s.abs_f32s(d.z));
    let x = s.and_m32s(
        s.greater_than_or_equal_f32s(ax, ay),
        s.greater_than_or_equal_f32s(ax, az),
    );
    let y = s.and_m32s(s.not_m32s(x), s.greater_than_or_equal_f32s(ay, az));
    (x, y)
}

/// `v`'s component along each lane's axis, the axis given as the masks "is x" and "is y".
#[must_use]
#[inline(always)]
pub fn pick<S: Simd>(s: S, is_x: M<S>, is_y: M<S>, v: &V3<S>) -> F<S> {
    s.select_f32s(is_x, v.x, s.select_f32s(is_y, v.y, v.z))
}

/// Whether any lane of `m` is set: [`crate::math::lanes::any`], but by a reduction where
/// pulp's mask is a vector register (AVX2, NEON), which pulp's `first_true_m32s` scans lane by
/// lane (a branch per lane on every box the walk tests).
#[must_use]
#[inline(always)]
pub fn any_lane<S: Simd>(s: S, m: M<S>) -> bool {
    if S::F32_LANES > 1 && size_of::<M<S>>() == size_of::<F<S>>() {
        let ones = s.select_f32s(m, s.splat_f32s(1.0), s.splat_f32s(0.0));
        s.reduce_max_f32s(ones) > 0.0
    } else {
        any(s, m)
    }
}

/// A packet of rays prepared for box tests.
#[derive(Clone, Copy, Debug)]
pub struct BoxRays<S: Simd> {
    o: V3<S>,
    /// 1 / d, or 0 on the axes in `free` (no 0 x inf NaN in a slab).
    inv: V3<S>,
    /// Per axis, the lanes whose direction has a negative inverse: their slab is entered at
    /// the box's max.
    neg: [M<S>; 3],
    /// The same signs when every active lane has them (a coherent packet): each box's near and
    /// far planes are then picked once for all lanes.
    octant: Option<[bool; 3]>,
    /// Per axis, the lanes running parallel to it (direction component exactly zero): tested
    /// by position instead (a ray lying in a box's face is inside it).
    parallel: [M<S>; 3],
    /// Per axis, the lanes it does not bound along t: the parallel ones, and those whose
    /// direction component is so small (subnormal) that its inverse overflows.
    free: [M<S>; 3],
    any_free: bool,
    /// Each lane's dominant axis ([`dominant_axis`]).
    kz: (M<S>, M<S>),
    /// Which child to visit first, per split axis: the packet's first active lane's direction.
    far_first: [bool; 3],
    /// At width 1, the same ray for [`OneRay::enters`].
    one: Option<OneRay>,
}

/// `1 / x` per lane, 0 where `x` is 0 (parallel) or so small that the inverse overflows
/// (free); and those two masks.
#[inline(always)]
fn inverse<S: Simd>(s: S, x: F<S>) -> (F<S>, M<S>, M<S>) {
    let zero = s.splat_f32s(0.0);
    let i = s.div_f32s(s.splat_f32s(1.0), x);
    let par = s.equal_f32s(x, zero);
    // Below 2^-128 or so the inverse overflows: the axis then bounds nothing (clamping it
    // would cull boxes the ray reaches).
    let free = s.and_m32s(
        s.not_m32s(par),
        s.not_m32s(s.less_than_f32s(s.abs_f32s(i), s.splat_f32s(f32::INFINITY))),
    );
    (s.select_f32s(s.or_m32s(par, free), zero, i), par, free)
}

impl<S: Simd> BoxRays<S> {
    /// Prepares `o + t d` per lane; `active` picks the lane whose direction orders children.
    #[must_use]
    #[inline(always)]
    pub fn new(s: S, o: &V3<S>, d: &V3<S>, active: M<S>) -> Self {
        let (ix, px, fx) = inverse(s, d.x);
        let (iy, py, fy) = inverse(s, d.y);
        let (iz, pz, fz) = inverse(s, d.z);
        let inv = V3 {
            x: ix,
            y: iy,
            z: iz,
        };
        let neg = [
            sign_negative(s, ix),
            sign_negative(s, iy),
            sign_negative(s, iz),
        ];
        let parallel = [px, py, pz];
        let free = [s.or_m32s(px, fx), s.or_m32s(py, fy), s.or_m32s(pz, fz)];
        let first = mask_to_array(s, active)[..S::F32_LANES]
            .iter()
            .position(|a| *a)
            .unwrap_or(0);
        let lane = |v: F<S>| to_array::<S>(v)[first];
        let far_first = [lane(d.x) < 0.0, lane(d.y) < 0.0, lane(d.z) < 0.0];
        let any_free = any_lane(
            s,
            s.and_m32s(active, s.or_m32s(free[0], s.or_m32s(free[1], free[2]))),
        );
        let shared = |m: M<S>| {
            let (yes, no) = (s.and_m32s(active, m), s.and_m32s(active, s.not_m32s(m)));
            match (any_lane(s, yes), any_lane(s, no)) {
                (true, true) => None,
                (all, _) => Some(all),
            }
        };
        let octant = match (shared(neg[0]), shared(neg[1]), shared(neg[2])) {
            (Some(x), Some(y), Some(z)) => Some([x, y, z]),
            _ => None,
        };
        let kz = dominant_axis(s, d);
        let one = S::IS_SCALAR.then(|| {
            let v = |a: &V3<S>| Vec3A::new(lane(a.x), lane(a.y), lane(a.z));
            let flag = |m: M<S>| mask_to_array(s, m)[0];
            let b = |m: &[M<S>; 3]| BVec3A::new(flag(m[0]), flag(m[1]), flag(m[2]));
            OneRay {
                o: v(o),
                inv: v(&inv),
                neg: b(&neg),
                parallel: b(&parallel),
                free: b(&free),
                any_free,
                kz: if flag(kz.0) {
                    0
                } else if flag(kz.1) {
                    1
                } else {
                    2
                },
            }
        });
        Self {
            o: *o,
            inv,
            neg,
            octant,
            parallel,
            free,
            any_free,
            kz,
            far_first,
            one,
        }
    }

    /// The slab of `n` along `axis` for the lanes' origins `o` and inverse directions `inv`:
    /// the t where each lane enters it and where it leaves. (A method, not a closure: closures
    /// are compiled outside the dispatched instruction set and call each SIMD operation.)
    #[inline(always)]
    fn slab(&self, s: S, n: &Node, axis: usize, o: F<S>, inv: F<S>) -> (F<S>, F<S>) {
        let (lo, hi) = (n.min[axis], n.max[axis]);
        let (near, far) = if let Some(neg) = self.octant {
            let (a, b) = if neg[axis] { (hi, lo) } else { (lo, hi) };
            (s.splat_f32s(a), s.splat_f32s(b))
        } else {
            let (lo, hi) = (s.splat_f32s(lo), s.splat_f32s(hi));
            let neg = self.neg[axis];
            (s.select_f32s(neg, hi, lo), s.select_f32s(neg, lo, hi))
        };
        (
            s.mul_f32s(s.sub_f32s(near, o), inv),
            s.mul_f32s(s.sub_f32s(far, o), inv),
        )
    }

    /// Which of `lanes` enter `n`'s box within (0, `t_max`) (conservatively), and each lane's
    /// entry along its dominant axis (meaningful in the lanes that enter).
    #[must_use]
    #[inline(always)]
    pub(super) fn enters(&self, s: S, n: &Node, t_max: F<S>, lanes: M<S>) -> (M<S>, F<S>) {
        if let Some(one) = &self.one {
            let (m, entry) = one.enters(n, to_array::<S>(t_max)[0]);
            return (s.and_m32s(lanes, mask_splat(s, m)), s.splat_f32s(entry));
        }
        let (nx, fx) = self.slab(s, n, 0, self.o.x, self.inv.x);
        let (ny, fy) = self.slab(s, n, 1, self.o.y, self.inv.y);
        let (nz, fz) = self.slab(s, n, 2, self.o.z, self.inv.z);
        let entry = pick(
            s,
            self.kz.0,
            self.kz.1,
            &V3 {
                x: nx,
                y: ny,
                z: nz,
            },
        );
        let (mut near, mut far) = ([nx, ny, nz], [fx, fy, fz]);
        let mut lanes = lanes;
        if self.any_free {
            // A free axis constrains nothing along t; on a parallel one the origin must lie in
            // the slab.
            let o = [self.o.x, self.o.y, self.o.z];
            for axis in 0..3 {
                let (par, free) = (self.parallel[axis], self.free[axis]);
                let (lo, hi) = (s.splat_f32s(n.min[axis]), s.splat_f32s(n.max[axis]));
                let outside = s.or_m32s(
                    s.less_than_f32s(o[axis], lo),
                    s.greater_than_f32s(o[axis], hi),
                );
                lanes = s.and_m32s(lanes, s.not_m32s(s.and_m32s(par, outside)));
                near[axis] = s.select_f32s(free, s.splat_f32s(f32::NEG_INFINITY), near[axis]);
                far[axis] = s.select_f32s(free, s.splat_f32s(f32::INFINITY), far[axis]);
            }
        }
        // `a > b ? a : b` and `a < b ? a : b`: no NaN reaches here in an active lane (finite
        // inverses and origins).
        let t_near = mx(
            s,
            mx(s, near[0], near[1]),
            mx(s, near[2], s.splat_f32s(0.0)),
        );
        let t_far = s.mul_f32s(
            mn(s, mn(s, far[0], far[1]), mn(s, far[2], t_max)),
            s.splat_f32s(ROBUST_FAR),
        );
        (
            s.and_m32s(lanes, s.less_than_or_equal_f32s(t_near, t_far)),
            entry,
        )
    }
}

/// One ray's box test (width 1): the packet's slab arithmetic, operation for operation, with x,
/// y and z in one SSE register instead of three scalar passes (what the scalar path always
/// did). Each coordinate is the same IEEE operations on the same values, so the answers are
/// the lanes' bits (the walk's tests compare every width against width 1).
#[derive(Clone, Copy, Debug)]
struct OneRay {
    o: Vec3A,
    inv: Vec3A,
    neg: BVec3A,
    parallel: BVec3A,
    free: BVec3A,
    any_free: bool,
    kz: usize,
}

impl OneRay {
    #[inline(always)]
    fn enters(&self, n: &Node, t_max: f32) -> (bool, f32) {
        let (lo, hi) = (Vec3A::from_array(n.min), Vec3A::from_array(n.max));
        let mut near = (Vec3A::select(self.neg, hi, lo) - self.o) * self.inv;
        let mut far = (Vec3A::select(self.neg, lo, hi) - self.o) * self.inv;
        let entry = near[self.kz];
        if self.any_free {
            let outside = self.o.cmplt(lo) | self.o.cmpgt(hi);
            if (self.parallel & outside).any() {
                return (false, entry);
            }
            near = Vec3A::select(self.free, Vec3A::NEG_INFINITY, near);
            far = Vec3A::select(self.free, Vec3A::INFINITY, far);
        }
        let mx = |a: f32, b: f32| if a > b { a } else { b };
        let mn = |a: f32, b: f32| if a < b { a } else { b };
        let t_near = mx(mx(near.x, near.y), mx(near.z, 0.0));
        let t_far = mn(mn(far.x, far.y), mn(far.z, t_max)) * ROBUST_FAR;
        (t_near <= t_far, entry)
    }
}

/// What a walk does at the leaves: tests primitives for some lanes and says how far each lane
/// still looks.
pub trait Leaves<S: Simd> {
    /// Tests primitives `first .. first + count` (the order [`Bvh::build`] returned) for the
    /// rays of `lanes`.
    fn leaf(&mut self, s: S, first: u32, count: u32, lanes: M<S>);
    /// Per lane, the farthest t a primitive can have and still matter (the nearest hit so far,
    /// or `t_max`): boxes whose entry along the lane's dominant axis lies beyond it are skipped.
    /// It must only shrink during a walk.
    fn bound(&self, s: S) -> F<S>;
    /// The lanes still looking (shadow rays stop at their first hit); the walk ends when none
    /// are.
    fn searching(&self, s: S) -> M<S>;
}

/// A subtree waiting on the walk's stack: its node and each lane's entry along its dominant
/// axis, NaN in the lanes that do not enter it (NaN <= bound is false).
#[derive(Clone, Copy)]
struct Waiting<S: Simd> {
    node: (u32, u16, u16),
    entry: F<S>,
}

impl Bvh {
    /// Walks the leaves the packet's rays may hit within (0, `t_max`) per lane, for the lanes
    /// of `active`, handing each leaf to `visit` with the lanes that reach it. The subtree a
    /// lane reaches, and so its answer, does not depend on the other lanes (see the module).
    #[inline(always)]
    pub fn walk<S: Simd>(
        &self,
        s: S,
        rays: &BoxRays<S>,
        t_max: F<S>,
        active: M<S>,
        visit: &mut impl Leaves<S>,
    ) {
        if self.root.count == 0 && self.pairs.is_empty() {
            return;
        }
        let (root, _) = rays.enters(s, &self.root, t_max, active);
        if !any_lane(s, root) {
            return;
        }
        let nan = s.splat_f32s(f32::NAN);
        let mut stack = [Waiting::<S> {
            node: (0, 0, 0),
            entry: nan,
        }; MAX_DEPTH + 1];
        let mut top = 0usize;
        let key = |n: &Node| (n.index, n.count, n.axis);
        let (mut node, mut lanes) = (key(&self.root), root);
        loop {
            let (index, count, axis) = node;
            if count > 0 {
                visit.leaf(s, index, u32::from(count), lanes);
                if !any_lane(s, visit.searching(s)) {
                    return;
                }
            } else {
                let [a, b] = &self.pairs[index as usize].0;
                let bound = visit.bound(s);
                let (ma, ea) = rays.enters(s, a, t_max, lanes);
                let (mb, eb) = rays.enters(s, b, t_max, lanes);
                let ma = s.and_m32s(ma, s.less_than_or_equal_f32s(ea, bound));
                let mb = s.and_m32s(mb, s.less_than_or_equal_f32s(eb, bound));
                match (any_lane(s, ma), any_lane(s, mb)) {
                    (true, true) => {
                        // The far child waits with its lanes' entries.
                        let ((near, mn), (far, mf, ef)) = if rays.far_first[axis as usize] {
                            ((b, mb), (a, ma, ea))
                        } else {
                            ((a, ma), (b, mb, eb))
                        };
                        stack[top] = Waiting {
                            node: key(far),
                            entry: s.select_f32s(mf, ef, nan),
                        };
                        top += 1;
                        (node, lanes) = (key(near), mn);
                        continue;
                    }
                    (true, false) => {
                        (node, lanes) = (key(a), ma);
                        continue;
                    }
                    (false, true) => {
                        (node, lanes) = (key(b), mb);
                        continue;
                    }
                    (false, false) => {}
                }
            }
            // The next waiting subtree some lane still enters before its bound.
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let w = stack[top];
                let m = s.and_m32s(
                    visit.searching(s),
                    s.less_than_or_equal_f32s(w.entry, visit.bound(s)),
                );
                if any_lane(s, m) {
                    (node, lanes) = (w.node, m);
                    break;
                }
            }
        }
    }
}

/// `a > b ? a : b` per lane (no NaN reaches the box test in an active lane: finite inverses and
/// origins).
#[inline(always)]
fn mx<S: Simd>(s: S, a: F<S>, b: F<S>) -> F<S> {
    s.select_f32s(s.greater_than_f32s(a, b), a, b)
}

/// `a < b ? a : b` per lane.
#[inline(always)]
fn mn<S: Simd>(s: S, a: F<S>, b: F<S>) -> F<S> {
    s.select_f32s(s.less_than_f32s(a, b), a, b)
}
