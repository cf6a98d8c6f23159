//! Wrap-free texel fetches (issue 25): the texel index of every wrap mode computed without an
//! integer division near the image, and every filter reading, bit for bit, what it read before.

use super::*;
use crate::math::Rgb;
use std::sync::Arc;
use strum::VariantArray;

/// [`Wrap::index`] as it was: one Euclidean remainder per texel.
fn index_by_remainder(wrap: Wrap, i: i64, n: u32) -> Option<u32> {
    let n64 = i64::from(n);
    match wrap {
        Wrap::Repeat => Some(i.rem_euclid(n64) as u32),
        Wrap::Clamp => Some(i.clamp(0, n64 - 1) as u32),
        Wrap::Mirror => {
            let m = i.rem_euclid(2 * n64);
            Some(if m >= n64 { 2 * n64 - 1 - m } else { m } as u32)
        }
        Wrap::Black => (0..n64).contains(&i).then_some(i as u32),
    }
}

#[test]
fn wrap_index_agrees_with_the_remainder_everywhere() {
    let sides = [1, 2, 3, 4, 5, 7, 8, 13, 2048, MAX_IMAGE_DIMENSION];
    for &wrap in Wrap::VARIANTS {
        for &n in &sides {
            let n64 = i64::from(n);
            // Every index within six periods of the image (the edges of a big image only),
            // and indices far away.
            let near: Vec<i64> = if n <= 13 {
                (-6 * n64 - 8..=6 * n64 + 8).collect()
            } else {
                (-3..=3)
                    .flat_map(|k| (-3..=3).map(move |d| k * n64 + d))
                    .collect()
            };
            let far = [
                i64::MIN / 4,
                -(1 << 40) - 3,
                -(1 << 33),
                1 << 33,
                (1 << 40) + 5,
                i64::MAX / 4,
            ];
            for &i in near.iter().chain(&far) {
                assert_eq!(
                    wrap.index(i, n),
                    index_by_remainder(wrap, i, n),
                    "{wrap} index {i} of {n}"
                );
            }
        }
    }
}

/// Coordinates along one axis: a dense grid over three periods, both sides of every texel
/// edge and centre of the small test images, and far away.
fn coords() -> Vec<f32> {
    let mut t: Vec<f32> = (-96..=144).map(|k| k as f32 / 48.0).collect();
    for k in -2..=3 {
        let k = k as f32;
        for e in [1e-7_f32, 1e-4, 0.01] {
            t.extend([k - e, k + e]);
        }
    }
    t.extend([
        -0.0,
        0.999_999_94,
        1.000_000_1,
        1000.3,
        -2000.7,
        8_388_607.5,
        -8_388_607.5,
        16_777_217.0,
        1e17,
        -1e17,
        3e38,
        -f32::MAX,
        f32::NAN,
        f32::INFINITY,
    ]);
    t
}

/// The images: one texel, one row, one column, odd sides, and a compact sRGB one.
fn images() -> Vec<Arc<ImageData>> {
    let f = |c: u32, r: u32| {
        Rgb(
            0.1 + c as f32 * 0.37,
            0.2 + r as f32 * 0.29,
            ((c * 7 + r * 3) % 5) as f32 / 4.0,
        )
    };
    let mut v: Vec<Arc<ImageData>> = [(1, 1), (1, 5), (5, 1), (3, 2), (16, 8)]
        .iter()
        .map(|&(w, h)| Arc::new(ImageData::from_fn(w, h, "grid", f)))
        .collect();
    let srgb = (0..6 * 3).map(|i| {
        [
            (i * 37 % 256) as u8,
            (i * 91 % 256) as u8,
            (i * 13 % 256) as u8,
            255,
        ]
    });
    v.push(Arc::new(ImageData::new(
        6,
        3,
        Texels::Srgb8(srgb.collect()),
        "srgb",
    )));
    v
}

/// FNV-1a over the bits of every filter's colour at every (u, v) of [`coords`] (a coarser grid
/// for the footprint filters), every image of [`images`], every pair of wraps and two
/// footprints, in that order.
fn every_filter_digest() -> (u64, usize) {
    let mut hash = 0xcbf2_9ce4_8422_2325_u64;
    let mut count = 0;
    let t = coords();
    let coarse: Vec<f32> = t.iter().copied().step_by(5).collect();
    let feet = [
        (Vec2::new(0.05, 0.01), Vec2::new(-0.01, 0.03)),
        (Vec2::new(0.9, 0.02), Vec2::new(0.0, 0.004)),
    ];
    for image in images() {
        let mip = Arc::new(MipPyramid::build(image.clone()));
        for &filter in Filter::VARIANTS {
            let grid = if filter.needs_footprint() {
                &coarse
            } else {
                &t
            };
            for &wu in Wrap::VARIANTS {
                for &wv in Wrap::VARIANTS {
                    for &(dx, dy) in &feet {
                        for &u in grid {
                            for &v in grid {
                                let uv = Vec2::new(u, v);
                                let c = match filter {
                                    Filter::Nearest => image.nearest(uv, Lookup::Centred, wu, wv),
                                    Filter::Bilinear => image.bilinear(uv, wu, wv),
                                    Filter::Bicubic => image.bicubic(uv, wu, wv),
                                    Filter::Trilinear => mip.trilinear(uv, dx, dy, wu, wv),
                                    Filter::Ewa => mip.ewa(uv, dx, dy, 8.0, wu, wv),
                                    // The tap grid (the filter's path without a table):
                                    // the summed-area table came after this digest.
                                    Filter::Footprint => footprint::supersampled(
                                        Some(&mip),
                                        &image,
                                        Wrap::reduce_uv(wu, wv, uv),
                                        dx,
                                        dy,
                                        wu,
                                        wv,
                                    ),
                                };
                                for x in c.to_array() {
                                    for b in x.to_bits().to_le_bytes() {
                                        hash = (hash ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
                                    }
                                }
                                count += 1;
                            }
                        }
                    }
                }
            }
        }
    }
    (hash, count)
}

/// Every filter under every pair of wraps gives, bit for bit, the colours the lookups gave
/// before the wrap-free fetches: the digest was recorded from the build before them (commit
/// 05894ee, `Wrap::index` by Euclidean remainder, `Wrap::reduce` by `f32::floor`). The
/// footprint filter is read through its tap grid, its only path then (its summed-area path is
/// checked against exact integrals in `summed/tests.rs` and `footprint.rs`).
#[test]
fn every_filter_reads_what_it_read_before_the_wrap_free_fetches() {
    let (hash, count) = every_filter_digest();
    assert_eq!(
        (hash, count),
        (0x3527_2360_2981_a093, 50_781_312),
        "digest {hash:#x} over {count} lookups"
    );
}
