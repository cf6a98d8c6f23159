use super::*;
use crate::math::Vec2;
use std::sync::Arc;

/// A texture with no period: a hard checker, smooth waves and a ramp.
fn busy(w: u32, h: u32) -> ImageData {
    ImageData::from_fn(w, h, "busy", |c, r| {
        let (x, y) = (c as f32, r as f32);
        let check = if (c / 3 + r / 2) % 2 == 0 { 0.8 } else { 0.1 };
        Rgb(
            check,
            0.5 + 0.4 * (x * 0.7).sin() * (y * 0.3).cos(),
            x / w as f32,
        )
    })
}

/// The largest difference between two colours' channels.
fn diff(a: Rgb, b: Rgb) -> f32 {
    let (a, b) = (a.to_array(), b.to_array());
    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f32::max)
}

const WRAPS: [Wrap; 4] = [Wrap::Repeat, Wrap::Mirror, Wrap::Clamp, Wrap::Black];

/// The integral of the tent (bilinear's weight for one texel) from -infinity to `s`.
fn tent_cdf(s: f64) -> f64 {
    if s <= -1.0 {
        0.0
    } else if s <= 0.0 {
        0.5 * (1.0 + s) * (1.0 + s)
    } else if s <= 1.0 {
        1.0 - 0.5 * (1.0 - s) * (1.0 - s)
    } else {
        1.0
    }
}

/// The box integral of the bilinear image the slow way: every texel near the box, weighted by
/// the integral of its tent over the box, its index wrapped by `Wrap::index` as the bilinear
/// lookup wraps it.
fn brute_box(img: &ImageData, x: (f64, f64), y: (f64, f64), wu: Wrap, wv: Wrap) -> [f64; 3] {
    let mut s = [0.0; 3];
    for j in y.0.floor() as i64 - 2..y.1.ceil() as i64 + 2 {
        let centre = j as f64 + 0.5;
        let oy = tent_cdf(y.1 - centre) - tent_cdf(y.0 - centre);
        for i in x.0.floor() as i64 - 2..x.1.ceil() as i64 + 2 {
            let centre = i as f64 + 0.5;
            let ox = tent_cdf(x.1 - centre) - tent_cdf(x.0 - centre);
            let (Some(c), Some(r)) = (wu.index(i, img.width()), wv.index(j, img.height())) else {
                continue;
            };
            let t = img.texel(c, r).to_array();
            for k in 0..3 {
                s[k] += ox * oy * f64::from(t[k]);
            }
        }
    }
    s
}

/// The tables of `img` (level 0 first) under its own plan.
fn tables(img: ImageData) -> (MipPyramid, SummedArea) {
    let mip = MipPyramid::build(Arc::new(img));
    let t = SummedArea::for_pyramid(&mip, mip.table_plan()).unwrap();
    (mip, t)
}

/// The boxes every box test reads: inside, across every edge, far outside, thin, the whole image.
const BOXES: [((f64, f64), (f64, f64)); 7] = [
    ((0.0, 13.0), (0.0, 7.0)),
    ((2.25, 5.5), (1.75, 6.125)),
    ((3.0, 4.0), (2.0, 3.0)),
    ((-4.3, 2.2), (0.5, 3.5)),
    ((11.6, 29.9), (-9.1, 1.3)),
    ((-40.7, -3.2), (5.5, 22.4)),
    ((6.1, 6.1), (1.0, 2.0)),
];

#[test]
fn a_box_integrates_the_bilinear_image_for_every_wrap_inside_and_out() {
    // Texels quantized to 2^-16 of the unit: a box's integral is within 2^-17 a texel of area
    // of the exact one, plus f32 rounding.
    let (_, t) = tables(busy(13, 7));
    let img = busy(13, 7);
    for wu in WRAPS {
        for wv in WRAPS {
            for (x, y) in BOXES {
                let got = t.box_sum(0, x, y, wu, wv);
                let want = brute_box(&img, x, y, wu, wv);
                let area = (x.1 - x.0 + 3.0) * (y.1 - y.0 + 3.0);
                for k in 0..3 {
                    assert!(
                        (f64::from(got[k]) - want[k]).abs() < area * 1e-5 + 1e-6 * want[k].abs(),
                        "{wu} {wv} {x:?} {y:?}: {got:?} against {want:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn every_level_has_its_table() {
    // Level 1 of a 26 x 14 image is 13 x 7: its table integrates that level's bilinear image.
    let (mip, t) = tables(busy(26, 14));
    assert_eq!(t.first_level(), 0);
    for l in 0..mip.len() {
        let img = mip.level(l);
        let (w, h) = (f64::from(img.width()), f64::from(img.height()));
        for (x, y) in [
            ((0.0, w), (0.0, h)),
            ((0.3 * w, 0.8 * w), (-0.4 * h, 0.9 * h)),
        ] {
            let got = t.box_sum(l, x, y, Wrap::Repeat, Wrap::Clamp);
            let want = brute_box(img, x, y, Wrap::Repeat, Wrap::Clamp);
            for k in 0..3 {
                assert!(
                    (f64::from(got[k]) - want[k]).abs() < 1e-3 + 1e-5 * want[k].abs(),
                    "level {l} {x:?} {y:?}: {got:?} against {want:?}"
                );
            }
        }
    }
}

#[test]
fn wrapping_sums_stay_exact_however_large_the_corners() {
    // A 2048 x 1024 white image: the corners' sums reach 2^21 texels, 2^37 in steps of 2^-16,
    // wrapping round an i32 32 times. A box anywhere still averages to 1 exactly (to f32).
    let (_, t) = tables(ImageData::from_fn(2048, 1024, "white", |_, _| {
        Rgb::grey(1.0)
    }));
    for (c, hw) in [
        ((2000.3, 1000.7), (3.0, 2.5)),
        ((1024.0, 512.0), (90.0, 2.0)),
        ((1.5, 1.5), (0.5, 0.25)),
        ((2047.9, 3.0), (5.0, 5.0)),
    ] {
        let m = t.box_mean(0, c, hw, Wrap::Repeat, Wrap::Repeat);
        assert!((m.0 - 1.0).abs() < 1e-6, "{c:?} {hw:?}: {m:?}");
    }
}

#[test]
fn a_tiny_box_is_the_bilinear_lookup_everywhere() {
    // The mean of the bilinear image over a box 1/100 of a texel wide, centred at p, is the
    // bilinear lookup at p to within the kink at a texel centre, edges and wraps included.
    let img = busy(9, 5);
    let (_, t) = tables(busy(9, 5));
    for wu in WRAPS {
        for wv in WRAPS {
            for k in 0..400 {
                let uv = Vec2::new(
                    (k as f32 * 0.618_034).fract() * 1.2 - 0.1,
                    (k as f32 * 0.414_214).fract() * 1.2 - 0.1,
                );
                let uv = Wrap::reduce_uv(wu, wv, uv);
                let c = (f64::from(uv.x) * 9.0, f64::from(uv.y) * 5.0);
                let got = t.box_mean(0, c, (0.005, 0.005), wu, wv);
                let want = img.bilinear(uv, wu, wv);
                assert!(
                    diff(got, want) < 5e-3,
                    "{wu} {wv} at {uv:?}: {got:?} against {want:?}"
                );
            }
        }
    }
}

#[test]
fn a_large_image_sums_from_its_first_level_within_the_cap() {
    // 4096 x 2048 is twice the cap: its tables start at level 1 (2048 x 1024).
    let img = ImageData::from_fn(4096, 2048, "big", |c, r| Rgb::grey(((c + r) % 2) as f32));
    let (mip, t) = tables(img);
    assert_eq!(t.first_level(), 1);
    // Level 1 averages the checker of single texels to a flat half grey.
    let m = t.box_mean(1, (100.0, 100.0), (3.0, 3.0), Wrap::Repeat, Wrap::Repeat);
    assert!((m.0 - 0.5).abs() < 1e-6, "{m:?}");
    // 12 bytes a corner (texels within [0, 1]), every level from 2048 x 1024 down: what the
    // plan reserves.
    assert_eq!(
        t.bytes() as u64,
        mip.table_plan().table_bytes(4096, 2048),
        "the plan's bytes"
    );
    assert!(t.bytes() >= 2049 * 1025 * 12 && t.bytes() < 2049 * 1025 * 12 * 4 / 3 + 65536);
}

#[test]
fn hdr_texels_are_summed_in_64_bits_and_a_huge_one_refuses_the_table() {
    // Texels up to 1000: i64 sums, as many fractional bits as 1000 leaves (37).
    let hdr = busy(13, 7);
    let hdr = ImageData::from_fn(13, 7, "hdr", |c, r| hdr.texel_top(c, r) * 1000.0);
    let plan = TablePlan::for_image(&hdr);
    assert_eq!(plan, TablePlan::Wide { bits: 37 });
    assert_eq!(plan.bytes_per_corner(), 24);
    let (_, t) = tables(hdr.clone());
    for (x, y) in BOXES {
        let got = t.box_sum(0, x, y, Wrap::Mirror, Wrap::Repeat);
        let want = brute_box(&hdr, x, y, Wrap::Mirror, Wrap::Repeat);
        for k in 0..3 {
            assert!(
                (f64::from(got[k]) - want[k]).abs() < 1e-5 * (1.0 + want[k].abs()),
                "{x:?} {y:?}: {got:?} against {want:?}"
            );
        }
    }
    // One texel of 1e16 (the f64 sums cancelled there): no table, and why.
    let huge = ImageData::from_fn(64, 64, "huge", |c, r| {
        Rgb::grey(if (c, r) == (0, 63) { 1e16 } else { 0.5 })
    });
    let TablePlan::Refused(why) = TablePlan::for_image(&huge) else {
        panic!("a texel of 1e16 planned a table");
    };
    assert!(why.contains("1.000e16"), "{why}");
    assert_eq!(TablePlan::for_image(&huge).table_bytes(64, 64), 0);
    let mip = MipPyramid::build(Arc::new(huge));
    assert!(mip.build_summed_area().is_err() && mip.summed_area().is_none());
    assert_eq!(mip.summed_area_refusal(), Some(why.as_str()));
}
