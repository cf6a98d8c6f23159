//! The explicit kernels against their loop twins, bit for bit, at every width pulp can run
//! here: pulp's `Scalar` (1 lane, what a CPU without SIMD dispatch would take), AVX2's 4-lane
//! (`V3_128b`, the width of NEON and SSE), 8-lane (`V3`) and 16-lane (`V3_512b`, two registers)
//! forms, and AVX-512 (`V4`, 16 lanes) where the CPU has it; NEON on aarch64. A width that does
//! not divide the packet runs its leftover lanes through `Scalar`, which these cover too.

use super::super::{self as lanes, F, LANES, M, V3, splat};
use super::{W, flags, mask};
use crate::math::Vec3A;
use pulp::{Simd, WithSimd};

/// Hard lane values: zeros of both signs, infinities, NaN, subnormals, the extremes and the
/// values the kernels branch at.
const HARD: [f32; 16] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    3.0,
    -7.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    1e-30,
    -1e-40,
    f32::MAX,
    f32::MIN_POSITIVE,
    0.999_999_9,
    -2.5e-8,
];

/// A deterministic walk over [`HARD`] and a smooth sweep, for filling lanes.
struct Walk(u32);

impl Walk {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        let k = self.0 >> 8;
        if k.is_multiple_of(3) {
            (k as f32 * 1e-4).sin() * 2.5
        } else {
            HARD[(k % 16) as usize]
        }
    }

    fn lanes(&mut self) -> F {
        std::array::from_fn(|_| self.next())
    }

    fn v3(&mut self) -> V3 {
        V3 {
            x: self.lanes(),
            y: self.lanes(),
            z: self.lanes(),
        }
    }

    fn flags(&mut self) -> M {
        std::array::from_fn(|_| self.next() > 0.4)
    }
}

/// The lanes' bits, every NaN as one: Rust leaves a NaN's sign and payload to the compiler
/// (it may swap an addition's operands), and no NaN reaches the film (`finish` makes it black,
/// a NaN t is a miss).
fn bits(a: &F) -> [u32; LANES] {
    a.map(|x| {
        if x.is_nan() {
            f32::NAN.to_bits()
        } else {
            x.to_bits()
        }
    })
}

/// Every explicit kernel against its loop twin at `S`'s width.
struct Agree(&'static str);

impl WithSimd for Agree {
    type Output = usize;

    #[inline(always)]
    fn with_simd<S: Simd>(self, s: S) -> usize {
        let name = self.0;
        let mut walk = Walk(7);
        let mut checked = 0;
        for round in 0..3000 {
            // The sphere: rays from anywhere along anything, t_max at and about the hits.
            let (mut o, mut d) = (walk.v3(), walk.v3());
            if round % 2 == 0 {
                // Mostly towards the sphere, so that hits are common.
                for i in 0..LANES {
                    o.z[i] += 2.0;
                    d.z[i] = -1.0;
                }
            }
            let t_max: F = std::array::from_fn(|i| {
                [f32::INFINITY, 1.5, 2.0, 0.0, f32::NAN, 1.0][(round + i) % 6]
            });
            let (tw, hw) = super::sphere(s, &o, &d, &t_max);
            let (tl, hl) = lanes::sphere(&o, &d, &t_max);
            assert_eq!(flags(hw), hl, "{name}: sphere hits from {o:?} along {d:?}");
            assert_eq!(
                bits(&tw),
                bits(&tl),
                "{name}: sphere t from {o:?} along {d:?}"
            );

            // atan2 on hard pairs, both ways round.
            let (y, x) = (walk.lanes(), walk.lanes());
            assert_eq!(
                bits(&super::atan2(s, &y, &x)),
                bits(&lanes::atan2(&y, &x)),
                "{name}: atan2({y:?}, {x:?})"
            );
            assert_eq!(
                bits(&super::atan2(s, &x, &y)),
                bits(&lanes::atan2(&x, &y)),
                "{name}: atan2({x:?}, {y:?})"
            );

            // The spherical map at hard points.
            let p = walk.v3();
            let (wu, wv) = super::spherical(s, &p);
            let (lu, lv) = lanes::spherical(&p);
            assert_eq!(
                (bits(&wu), bits(&wv)),
                (bits(&lu), bits(&lv)),
                "{name}: {p:?}"
            );

            // One light's term, with hard terms and any masks.
            let (reach, has_spec) = (walk.flags(), walk.flags());
            let (pw, n) = (walk.lanes(), walk.lanes());
            let diffuse = [walk.lanes(), walk.lanes(), walk.lanes()];
            let spec = [walk.lanes(), walk.lanes(), walk.lanes()];
            let li = [walk.next(), walk.next(), walk.next()];
            let (mut lw, mut litw) = ([walk.lanes(), walk.lanes(), walk.lanes()], walk.lanes());
            let (mut ll, mut litl) = (lw, litw);
            super::add_light(
                s, &reach, &has_spec, &pw, &diffuse, &spec, li, &n, &mut lw, &mut litw,
            );
            lanes::add_light(
                &reach, &has_spec, &pw, &diffuse, &spec, li, &n, &mut ll, &mut litl,
            );
            assert_eq!(lw.map(|c| bits(&c)), ll.map(|c| bits(&c)), "{name}: light");
            assert_eq!(bits(&litw), bits(&litl), "{name}: lit");

            // The selects, on the sphere's mask and on any flags.
            let m: W = if round % 2 == 0 { hw } else { mask(&reach) };
            let want = flags(m);
            let (a, b) = (walk.v3(), walk.v3());
            let got = super::select_v3(s, m, &a, &b);
            let ids = super::select_u32(s, m, &[7; LANES], &bits(&b.x));
            for i in 0..LANES {
                let pick = if want[i] { a.lane(i) } else { b.lane(i) };
                assert_eq!(
                    got.lane(i).to_array().map(f32::to_bits),
                    pick.to_array().map(f32::to_bits)
                );
                let id = if want[i] { 7 } else { b.x[i].to_bits() };
                assert_eq!(ids[i], id, "{name}: select_u32 lane {i}");
            }
            assert_eq!(super::any(m), want.contains(&true));
            checked += 1;
        }
        // The seam and the poles of the spherical map, lane by lane.
        let seam = [
            Vec3A::new(-0.0, 0.0, -1.0),
            Vec3A::new(-1e-8, 0.0, -1.0),
            Vec3A::new(1e-8, 0.0, -1.0),
            Vec3A::new(0.0, 1.0, 0.0),
            Vec3A::new(-0.0, -1.0, -0.0),
            Vec3A::ZERO,
            Vec3A::new(3e38, -3e38, 1.0),
            Vec3A::new(-f32::MIN_POSITIVE, 0.5, 0.0),
        ];
        let mut p = V3::splat(Vec3A::ZERO);
        for i in 0..LANES {
            p.set_lane(i, seam[i % seam.len()] * if i < 8 { 1.0 } else { -1.0 });
        }
        let (wu, wv) = super::spherical(s, &p);
        let (lu, lv) = lanes::spherical(&p);
        assert_eq!(
            (bits(&wu), bits(&wv)),
            (bits(&lu), bits(&lv)),
            "{name}: seam"
        );
        let _ = splat(0.0);
        checked
    }
}

/// Runs [`Agree`] through `s`'s `#[target_feature]` entry, as the packet path runs.
fn agree<S: Simd>(s: S, name: &'static str) {
    assert_eq!(s.vectorize(Agree(name)), 3000, "{name}");
}

#[test]
fn explicit_kernels_match_the_lane_loops_bit_for_bit_at_every_width_here() {
    // pulp's `Scalar`: one lane per step, everywhere.
    agree(pulp::Scalar, "Scalar (1 lane)");
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    {
        use pulp::x86::{V3, V3_128b, V3_512b, V4};
        if let Some(v3) = V3::try_new() {
            agree(V3_128b(v3), "AVX2 at 4 lanes (the NEON and SSE width)");
            agree(v3, "AVX2 (8 lanes)");
            agree(V3_512b(v3), "AVX2 as 16 lanes (two registers)");
        }
        if let Some(v4) = V4::try_new() {
            agree(v4, "AVX-512 (16 lanes)");
        }
    }
    #[cfg(target_arch = "aarch64")]
    if let Some(neon) = pulp::aarch64::Neon::try_new() {
        agree(neon, "NEON (4 lanes)");
    }
}

#[test]
fn the_packet_arch_is_at_most_a_packet_wide() {
    struct Lanes;
    impl WithSimd for Lanes {
        type Output = usize;
        fn with_simd<S: Simd>(self, _s: S) -> usize {
            S::F32_LANES
        }
    }
    let w = crate::render::packet::arch().dispatch(Lanes);
    assert!(
        LANES.is_multiple_of(w),
        "{w} lanes per instruction, {LANES} per packet"
    );
    assert!(crate::render::simd_level().contains(", "));
}
