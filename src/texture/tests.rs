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
    assert_eq!(Lookup::Lecture.index(0.0, 4), 0);
    assert_eq!(Lookup::Lecture.index(0.34, 4), 1);
    assert_eq!(Lookup::Lecture.index(0.99, 4), 2);
    assert_eq!(Lookup::Lecture.index(1.0, 4), 3);
    // Texel-centred: min(floor(u hres), hres - 1)
    assert_eq!(Lookup::Centred.index(0.0, 4), 0);
    assert_eq!(Lookup::Centred.index(0.2499, 4), 0);
    assert_eq!(Lookup::Centred.index(0.25, 4), 1);
    assert_eq!(Lookup::Centred.index(0.99, 4), 3);
    assert_eq!(Lookup::Centred.index(1.0, 4), 3);
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
    assert_eq!(Wrap::Repeat.coord(1.25), Some(0.25));
    assert_eq!(Wrap::Repeat.coord(-0.25), Some(0.75));
    assert_eq!(Wrap::Repeat.coord(-1e-9), Some(0.0));
    assert_eq!(Wrap::Clamp.coord(1.5), Some(1.0));
    assert_eq!(Wrap::Mirror.coord(1.25), Some(0.75));
    assert_eq!(Wrap::Mirror.coord(-0.25), Some(0.25));
    assert_eq!(Wrap::Black.coord(1.5), None);
    assert_eq!(Wrap::Black.coord(0.5), Some(0.5));
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
        mapping: Mapping::Spherical,
        filter: Filter::Bilinear,
        lookup: Lookup::Centred,
        wrap: Wrap::Black,
        scale: 1.0,
        mip: None,
        max_anisotropy: DEFAULT_MAX_ANISOTROPY,
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
