//! Texel lookups (both forms), wrap modes and bilinear filtering on small images.

use super::*;
use crate::math::srgb8_to_linear;
use strum::VariantArray;

/// A 4 x 2 image whose texel (column c, row-from-bottom r) has red = c and green = r.
fn ramp() -> ImageData {
    ImageData::from_fn(4, 2, "ramp", |c, row_top| {
        Rgb(c as f32, (1 - row_top) as f32, 0.0)
    })
}

#[test]
fn lecture_lookup_never_reaches_the_last_column_before_u_1() {
    // column = (int)((hres - 1) u) with hres = 4
    assert_eq!(Lookup::Lecture.index(0.0f32, 4), 0);
    assert_eq!(Lookup::Lecture.index(0.34f32, 4), 1);
    assert_eq!(Lookup::Lecture.index(0.99f32, 4), 2);
    assert_eq!(Lookup::Lecture.index(1.0f32, 4), 3);
    // Texel-centred: min(floor(u hres), hres - 1)
    assert_eq!(Lookup::Centred.index(0.0f32, 4), 0);
    assert_eq!(Lookup::Centred.index(0.2499f32, 4), 0);
    assert_eq!(Lookup::Centred.index(0.25f32, 4), 1);
    assert_eq!(Lookup::Centred.index(0.99f32, 4), 3);
    assert_eq!(Lookup::Centred.index(1.0f32, 4), 3);
    for n in [1, 2, 3, 1000] {
        for t in [0.0, 0.5, 1.0 - f32::EPSILON, 1.0] {
            assert!(Lookup::Centred.index(t, n) < n && Lookup::Lecture.index(t, n) < n);
        }
    }
}

#[test]
fn v_counts_from_the_bottom_of_the_image() {
    let img = ramp();
    let c = img.nearest(
        Vec2::new(0.1, 0.1),
        Lookup::Centred,
        Wrap::Repeat,
        Wrap::Repeat,
    );
    assert_eq!(c, Rgb(0.0, 0.0, 0.0));
    let c = img.nearest(
        Vec2::new(0.9, 0.9),
        Lookup::Centred,
        Wrap::Repeat,
        Wrap::Repeat,
    );
    assert_eq!(c, Rgb(3.0, 1.0, 0.0));
}

#[test]
fn wrap_modes() {
    assert_eq!(Wrap::Repeat.coord(1.25f32), Some(0.25));
    assert_eq!(Wrap::Repeat.coord(-0.25f32), Some(0.75));
    assert_eq!(Wrap::Repeat.coord(-1e-9f32), Some(0.0));
    assert_eq!(Wrap::Clamp.coord(1.5f32), Some(1.0));
    assert_eq!(Wrap::Mirror.coord(1.25f32), Some(0.75));
    assert_eq!(Wrap::Mirror.coord(-0.25f32), Some(0.25));
    assert_eq!(Wrap::Black.coord(1.5f32), None);
    assert_eq!(Wrap::Black.coord(0.5f32), Some(0.5));
    assert_eq!(Wrap::Repeat.index(-1, 4), Some(3));
    assert_eq!(Wrap::Clamp.index(-1, 4), Some(0));
    assert_eq!(Wrap::Mirror.index(-1, 4), Some(0));
    assert_eq!(Wrap::Mirror.index(4, 4), Some(3));
    assert_eq!(Wrap::Mirror.index(9, 4), Some(1));
    assert_eq!(Wrap::Black.index(4, 4), None);
    for &w in Wrap::VARIANTS {
        assert!(w.coord(f32::NAN).is_some_and(|t| (0.0..=1.0).contains(&t)));
        for i in [-9, -1, 0, 3, 4, 1000] {
            assert!(w.index(i, 4).is_none_or(|k| k < 4));
        }
    }
}

#[test]
fn bilinear_hits_texel_centres_and_blends_between() {
    let img = ramp();
    // Centre of column 1, row 0: u = 1.5 / 4, v = 0.5 / 2.
    let c = img.bilinear(Vec2::new(1.5 / 4.0, 0.25), Wrap::Clamp, Wrap::Clamp);
    assert!((c.0 - 1.0).abs() < 1e-6 && c.1.abs() < 1e-6);
    // Half-way between columns 1 and 2.
    let c = img.bilinear(Vec2::new(0.5, 0.25), Wrap::Clamp, Wrap::Clamp);
    assert!((c.0 - 1.5).abs() < 1e-6);
    // Across the u seam with repeat: half of column 3 and half of column 0.
    let c = img.bilinear(Vec2::new(0.0, 0.25), Wrap::Repeat, Wrap::Clamp);
    assert!((c.0 - 1.5).abs() < 1e-6);
    // Black outside.
    let c = img.bilinear(Vec2::new(-0.5, 0.25), Wrap::Black, Wrap::Black);
    assert_eq!(c, Rgb::BLACK);
}

#[test]
fn one_by_one_and_one_by_n_images() {
    let one = ImageData::from_fn(1, 1, "1x1", |_, _| Rgb(0.5, 0.25, 1.0));
    for uv in [Vec2::ZERO, Vec2::ONE, Vec2::new(7.3, -2.1)] {
        for &l in Lookup::VARIANTS {
            assert_eq!(
                one.nearest(uv, l, Wrap::Repeat, Wrap::Mirror),
                Rgb(0.5, 0.25, 1.0)
            );
        }
        assert_eq!(
            one.bilinear(uv, Wrap::Repeat, Wrap::Clamp),
            Rgb(0.5, 0.25, 1.0)
        );
    }
    let strip = ImageData::from_fn(1, 5, "1x5", |_, r| Rgb::grey(r as f32));
    let c = strip.nearest(
        Vec2::new(0.3, 0.99),
        Lookup::Centred,
        Wrap::Clamp,
        Wrap::Clamp,
    );
    assert_eq!(c, Rgb::grey(0.0)); // top of the image is file row 0
}

#[test]
fn srgb8_storage_decodes_to_linear() {
    let img = ImageData::new(1, 1, Texels::Srgb8(vec![[255, 128, 0, 255]]), "px");
    let c = img.texel(0, 0);
    assert_eq!(c, Rgb(1.0, srgb8_to_linear(128), 0.0));
    assert!((c.1 - 0.2158).abs() < 1e-3);
}

#[test]
fn periodic_mappings_override_the_wrap_on_u() {
    let tex = ImageTexture {
        image: std::sync::Arc::new(ramp()),
        mapping: Mapping::Spherical.into(),
        filter: Filter::Bilinear,
        lookup: Lookup::Centred,
        wrap: Wrap::Black,
        scale: 1.0,
        mip: None,
        max_anisotropy: DEFAULT_MAX_ANISOTROPY,
        transform: None,
    };
    assert_eq!(tex.wraps(), (Wrap::Repeat, Wrap::Clamp));
}

#[test]
fn uv_grid_labels_its_corners() {
    let img = uv_grid_image(256);
    assert_eq!((img.width(), img.height()), (256, 256));
    // Bottom-left cell is reddish-dark, top-right brighter in both red and green.
    let bl = img.texel(16, 16);
    let tr = img.texel(256 - 16, 256 - 16);
    assert!(tr.0 > bl.0 && tr.1 > bl.1, "{bl:?} {tr:?}");
    // The u = 0 edge is the bold red frame.
    let edge = img.texel(0, 128);
    assert!(edge.0 > 0.5 && edge.1 < 0.1);
}

#[test]
fn the_square_is_closed_under_every_wrap() {
    // u = 0 and u = 1 are inside: no mode moves them, and 1 reaches the last texel.
    for &w in Wrap::VARIANTS {
        assert_eq!(w.coord(0.0f32), Some(0.0), "{w}");
        assert_eq!(w.coord(1.0f32), Some(1.0), "{w}");
        assert_eq!(w.coord(1.0f64), Some(1.0), "{w}");
        assert_eq!(w.coord(0.5f32), Some(0.5), "{w}");
    }
    // Just outside, each mode does its own thing.
    let above = f32::from_bits(1.0f32.to_bits() + 1);
    assert_eq!(Wrap::Repeat.coord(above), Some(above - 1.0));
    assert_eq!(Wrap::Clamp.coord(above), Some(1.0));
    assert_eq!(Wrap::Mirror.coord(above), Some(2.0 - above));
    assert_eq!(Wrap::Black.coord(above), None);
    // Whole numbers outside: repeat starts the next tile at 0, mirror turns at 1.
    assert_eq!(Wrap::Repeat.coord(2.0f32), Some(0.0));
    assert_eq!(Wrap::Repeat.coord(-1.0f32), Some(0.0));
    assert_eq!(Wrap::Mirror.coord(2.0f32), Some(0.0));
    assert_eq!(Wrap::Mirror.coord(3.0f32), Some(1.0));
    assert_eq!(Wrap::Mirror.coord(-1.0f32), Some(1.0));
    // The nearest lookup at u = v = 1 reads the top-right texel under both lookups and every
    // mode (it read the first column and the bottom row under repeat).
    let img = ramp();
    for &w in Wrap::VARIANTS {
        for &lookup in Lookup::VARIANTS {
            assert_eq!(
                img.nearest(Vec2::ONE, lookup, w, w),
                Rgb(3.0, 1.0, 0.0),
                "{w} {lookup}"
            );
            assert_eq!(
                img.nearest(Vec2::ZERO, lookup, w, w),
                Rgb(0.0, 0.0, 0.0),
                "{w} {lookup}"
            );
        }
    }
}

#[test]
fn wrap_and_lookup_agree_in_f32_and_f64() {
    // One formula for both types: on f32 inputs, the f64 run gives the same texel except where
    // f32 rounding of the product moves it across a texel boundary.
    let mut rng = crate::math::SampleRng::new(17, 2, 3);
    let mut differ = 0;
    for i in 0..200_000 {
        let t = match i % 4 {
            0 => rng.next_f32() * 6.0 - 3.0,
            1 => rng.next_f32(),
            2 => (rng.next_f32() * 8.0).round() - 4.0, // whole numbers: the closed ends
            _ => 1.0 - rng.next_f32() * 1e-6,
        };
        for &w in Wrap::VARIANTS {
            let (a, b) = (w.coord(t), w.coord(f64::from(t)));
            assert_eq!(a.is_some(), b.is_some(), "{w} {t}");
            let (Some(a), Some(b)) = (a, b) else { continue };
            assert!((f64::from(a) - b).abs() <= 1e-6, "{w} {t}: {a} {b}");
            for n in [1, 4, 1023, 2048] {
                for &lookup in Lookup::VARIANTS {
                    let (i32_, i64_) = (lookup.index(a, n), lookup.index(b, n));
                    assert!(i32_.abs_diff(i64_) <= 1, "{w} {lookup} {t} {n}");
                    differ += usize::from(i32_ != i64_);
                }
            }
        }
    }
    // Rounding at a boundary is rare.
    assert!(differ < 200, "{differ} lookups differ");
}

#[test]
fn explained_lookup_shows_the_renderers_texel() {
    // The example: u = 1 on a 1024-wide image is column 1023 under the lecture's formula.
    let lines = explain_lookup(1.0f64, 0.5, 1024, 512, Lookup::Lecture);
    assert_eq!(
        lines[0],
        "column = (int)((hres - 1) u) = (int)(1023 x 1.0000) = 1023"
    );
    assert_eq!(
        lines[1],
        "row = (int)((vres - 1) v) = (int)(511 x 0.5000) = 255"
    );
    let lines = explain_lookup(1.0f32, 1.0, 1024, 512, Lookup::Centred);
    assert_eq!(
        lines[0],
        "column = min(floor(u hres), hres - 1) = min(floor(1.0000 x 1024), 1023) = 1023"
    );
    // Just below 1, four decimals would say 1.0000 and hide why the column is 1022.
    let below = 1.0 - 1e-9;
    let lines = explain_lookup(below, 0.0, 1024, 512, Lookup::Lecture);
    assert_eq!(
        lines[0],
        "column = (int)((hres - 1) u) = (int)(1023 x 0.999999999) = 1022"
    );
    // The wrap only speaks for coordinates outside.
    let (w, lines) = explain_wrap(1.0f64, 0.0, (Wrap::Repeat, Wrap::Repeat));
    assert_eq!((w, lines.len()), (Some((1.0, 0.0)), 0));
    let (w, lines) = explain_wrap(1.25f64, -0.25, (Wrap::Repeat, Wrap::Mirror));
    assert_eq!(w, Some((0.25, 0.25)));
    assert_eq!(
        lines,
        [
            "u = 1.2500 is outside [0, 1]: repeat brings it to u = 0.2500",
            "v = -0.2500 is outside [0, 1]: mirror brings it to v = 0.2500"
        ]
    );
    let (w, lines) = explain_wrap(1.5f32, 0.5, (Wrap::Black, Wrap::Black));
    assert_eq!(w, None);
    assert_eq!(
        lines,
        ["u = 1.5000 is outside [0, 1]: black reads black there (no texel)"]
    );
}

#[test]
fn interpolating_filters_at_the_closed_ends_take_the_neighbour_from_the_wrap() {
    // u = 1 is halfway between the last texel centre (3.5 / 4) and the one beyond the edge,
    // which the wrap supplies: the same value as at u = 0 under repeat (continuous across the
    // tile seam), the edge texel under clamp and mirror, half black under black.
    let img = ramp();
    let at = |u: f32, w: Wrap| img.bilinear(Vec2::new(u, 0.25), w, Wrap::Clamp);
    assert_eq!(at(1.0, Wrap::Repeat), at(0.0, Wrap::Repeat));
    assert_eq!(at(1.0, Wrap::Repeat), Rgb(1.5, 0.0, 0.0));
    assert_eq!(at(1.0, Wrap::Clamp), Rgb(3.0, 0.0, 0.0));
    assert_eq!(at(1.0, Wrap::Mirror), Rgb(3.0, 0.0, 0.0));
    assert_eq!(at(1.0, Wrap::Black), Rgb(1.5, 0.0, 0.0));
    assert_eq!(at(0.0, Wrap::Black), Rgb(0.0, 0.0, 0.0));
    let cubic = |u: f32, w: Wrap| img.bicubic(Vec2::new(u, 0.25), w, Wrap::Clamp);
    assert_eq!(cubic(1.0, Wrap::Repeat), cubic(0.0, Wrap::Repeat));
}

/// Issue 26: a (u, v) of any finite size reads a valid texel under every filter and wrap (a
/// 1e17 offset used to overflow the texel arithmetic and index past the image), and under
/// `Repeat` and `Mirror` it reads exactly the texels of its place in the tile.
#[test]
fn huge_coordinates_wrap_exactly_under_every_filter() {
    // 16 x 8, so the mip pyramid has levels and the tiles are partly filled.
    let img = ImageData::from_fn(16, 8, "busy", |c, r| {
        Rgb(
            c as f32 / 15.0,
            r as f32 / 7.0,
            ((c * 7 + r * 3) % 5) as f32 / 4.0,
        )
    });
    let image = std::sync::Arc::new(img);
    let mip = std::sync::Arc::new(MipPyramid::build(image.clone()));
    let _ = mip.build_summed_area();
    let d = (Vec2::new(0.05, 0.01), Vec2::new(-0.01, 0.03));
    let huge = [
        1e16_f32,
        2e16,
        1e17,
        -1e17,
        1e20,
        3e38,
        f32::MAX,
        -f32::MAX,
        16_777_217.0,
    ];
    for &filter in Filter::VARIANTS {
        for &wrap in Wrap::VARIANTS {
            let tex = ImageTexture {
                image: image.clone(),
                mapping: Mapping::Rectangular.into(),
                filter,
                lookup: Lookup::Centred,
                wrap,
                scale: 1.0,
                mip: filter.needs_mip().then(|| mip.clone()),
                max_anisotropy: DEFAULT_MAX_ANISOTROPY,
                transform: None,
            };
            for &u in &huge {
                for v in [0.3, u] {
                    let tc = TexCoord {
                        uv: Vec2::new(u, v),
                        duvdx: d.0,
                        duvdy: d.1,
                    };
                    let c = tex.sample(tc);
                    assert!(
                        c.0.is_finite() && c.1.is_finite() && c.2.is_finite(),
                        "{filter} {wrap} at ({u}, {v}): {c:?}"
                    );
                    // Where the coordinate lies in the tile, worked out here: every f32 this
                    // large is a whole, even number, so under `Repeat` and `Mirror` it is
                    // exactly 0; under `Clamp` and `Black` it is far outside, as 2 or -1
                    // already is for this footprint.
                    let place = |t: f32| match wrap {
                        _ if t == 0.3 => t,
                        Wrap::Repeat | Wrap::Mirror => 0.0,
                        Wrap::Clamp | Wrap::Black => {
                            if t > 0.0 {
                                2.0
                            } else {
                                -1.0
                            }
                        }
                    };
                    let expected = tex.sample(TexCoord {
                        uv: Vec2::new(place(u), place(v)),
                        ..tc
                    });
                    assert_eq!(c, expected, "{filter} {wrap} at ({u}, {v})");
                }
            }
        }
    }
    // Reduction keeps [0, 1] as it is and moves by whole periods outside.
    assert_eq!(Wrap::Repeat.reduce(1.0), 1.0);
    assert_eq!(Wrap::Repeat.reduce(3.25), 0.25);
    assert_eq!(Wrap::Repeat.reduce(-0.75), 0.25);
    assert_eq!(Wrap::Mirror.reduce(3.25), 1.25);
    assert_eq!(Wrap::Clamp.reduce(-1e30), -Wrap::REDUCED_MARGIN);
    assert_eq!(Wrap::Black.reduce(1e30), 1.0 + Wrap::REDUCED_MARGIN);
}
