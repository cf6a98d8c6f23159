//! The lane functions at every width against the width-1 instance (the scalar path) and
//! against std's own `f32` functions, bit for bit, on hard values.

use super::testing::{Walk, WidthCheck, at_every_width, bits, lane, lanes, load, load3};
use super::*;

struct Agree;

impl WidthCheck for Agree {
    fn check<S: Simd>(&mut self, s: S, name: &'static str) {
        let mut walk = Walk(11);
        for _ in 0..4000 {
            let (a, b) = (walk.lanes(), walk.lanes());
            let (va, vb) = (load::<S>(&a), load::<S>(&b));
            let got = [
                lanes::<S>(atan2(s, va, vb)),
                lanes::<S>(max(s, va, vb)),
                lanes::<S>(min(s, va, vb)),
                lanes::<S>(clamp(s, va, 0.0, 1.0)),
                lanes::<S>(copysign(s, va, vb)),
                lanes::<S>(neg(s, va)),
            ];
            for i in 0..S::F32_LANES {
                let want = [
                    crate::math::atan2(a[i], b[i]),
                    a[i].max(b[i]),
                    a[i].min(b[i]),
                    a[i].clamp(0.0, 1.0),
                    a[i].copysign(b[i]),
                    -a[i],
                ];
                for (k, w) in want.iter().enumerate() {
                    assert_eq!(
                        bits(got[k][i]),
                        bits(*w),
                        "{name}: function {k} of ({}, {})",
                        a[i],
                        b[i]
                    );
                }
            }
            let p = walk.v3();
            let v = load3::<S>(&p);
            let n = v.normalize_or(s, Vec3A::Y).to_arrays();
            let m = to_array::<S>(v.max_abs(s));
            let fin = mask_to_array(s, v.finite(s));
            for i in 0..S::F32_LANES {
                let q = lane(&p, i);
                let want = q.normalize_or(Vec3A::Y);
                assert_eq!(
                    [n[0][i], n[1][i], n[2][i]].map(bits),
                    want.to_array().map(bits),
                    "{name}: normalize {q:?}"
                );
                let ma = crate::math::max_abs(q);
                assert_eq!(bits(m[i]), bits(ma), "{name}: max_abs {q:?}");
                assert_eq!(fin[i], q.is_finite(), "{name}: finite {q:?}");
            }
            assert_eq!(
                any(s, s.less_than_f32s(va, vb)),
                (0..S::F32_LANES).any(|i| a[i] < b[i])
            );
        }
    }
}

#[test]
fn lane_functions_are_the_scalar_ones_at_every_width() {
    assert!(at_every_width(&mut Agree) >= 1);
}

#[test]
fn atan2_cases_libm_defines() {
    use std::f32::consts::{FRAC_PI_2, PI};
    let a = |y: f32, x: f32| atan2(pulp::Scalar, y, x);
    assert_eq!(a(0.0, -0.0).to_bits(), PI.to_bits());
    assert_eq!(a(-0.0, -0.0).to_bits(), (-PI).to_bits());
    assert_eq!(a(f32::INFINITY, f32::INFINITY), std::f32::consts::FRAC_PI_4);
    assert_eq!(a(1.0, 0.0), FRAC_PI_2);
    assert!(a(f32::NAN, 1.0).is_nan());
}
