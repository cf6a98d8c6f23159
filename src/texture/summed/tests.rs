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

#[test]
fn a_box_integrates_the_bilinear_image_for_every_wrap_inside_and_out() {
    let img = busy(13, 7);
    let t = SummedArea::build(&img, 0).unwrap();
    let boxes = [
        ((0.0, 13.0), (0.0, 7.0)),
        ((2.25, 5.5), (1.75, 6.125)),
        ((3.0, 4.0), (2.0, 3.0)),
        ((-4.3, 2.2), (0.5, 3.5)),
        ((11.6, 29.9), (-9.1, 1.3)),
        ((-40.7, -3.2), (5.5, 22.4)),
        ((6.1, 6.1), (1.0, 2.0)),
    ];
    for wu in WRAPS {
        for wv in WRAPS {
            for (x, y) in boxes {
                let got = t.box_sum(x.0, x.1, y.0, y.1, wu, wv);
                let want = brute_box(&img, x, y, wu, wv);
                for k in 0..3 {
                    assert!(
                        (got[k] - want[k]).abs() < 1e-9 * (1.0 + want[k].abs()),
                        "{wu} {wv} {x:?} {y:?}: {got:?} against {want:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_tiny_box_is_the_bilinear_lookup_everywhere() {
    // The mean of the bilinear image over a box 1/100 of a texel wide, centred at p, is the
    // bilinear lookup at p to within the kink at a texel centre, edges and wraps included.
    let img = busy(9, 5);
    let t = SummedArea::build(&img, 0).unwrap();
    for wu in WRAPS {
        for wv in WRAPS {
            for k in 0..400 {
                let uv = Vec2::new(
                    (k as f32 * 0.618_034).fract() * 1.2 - 0.1,
                    (k as f32 * 0.414_214).fract() * 1.2 - 0.1,
                );
                let uv = Wrap::reduce_uv(wu, wv, uv);
                let (cx, cy) = (f64::from(uv.x) * 9.0, f64::from(uv.y) * 5.0);
                let got = t.box_mean(cx, cy, 0.005, 0.005, wu, wv);
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
fn a_large_image_sums_its_first_level_within_the_cap() {
    // 4096 x 2048 is twice the cap: its table sums level 1 (2048 x 1024).
    let img = Arc::new(ImageData::from_fn(4096, 2048, "big", |c, r| {
        Rgb::grey(((c + r) % 2) as f32)
    }));
    let mip = MipPyramid::build(img);
    let t = SummedArea::for_pyramid(&mip).unwrap();
    assert_eq!((t.level(), t.width(), t.height()), (1, 2048, 1024));
    // Level 1 averages the checker of single texels to a flat half grey.
    let m = t.box_mean(100.0, 100.0, 3.0, 3.0, Wrap::Repeat, Wrap::Repeat);
    assert!((m.0 - 0.5).abs() < 1e-6, "{m:?}");
    assert!(t.bytes() >= 2049 * 1025 * 24);
}
