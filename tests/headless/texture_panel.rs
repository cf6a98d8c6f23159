//! The mapping made visible, without a window (`texplore::coverage`): the visible region, the
//! reverse lookup and the iso-lines, each checked against what `Scene::inspect` reports pixel
//! by pixel.

use crate::common::{build_with, root};
use std::collections::BTreeSet;
use std::sync::atomic::AtomicBool;
use texplore::coverage::{
    FieldError, ISO_POLE, ISO_SEAM, ISO_U, ISO_V, TexelMask, UvField, iso_lines, pixels_reading,
    visible_region,
};
use texplore::math::Vec2;
use texplore::scene::{AssetCache, Overrides, Scene, TransformDesc, load_preset};
use texplore::texture::Filter;

fn scene(preset: &str, width: u32, height: u32, filter: Option<Filter>) -> Scene {
    let path = root().join("presets").join(preset);
    let desc = load_preset(&path).expect("preset");
    let o = Overrides {
        width: Some(width),
        height: Some(height),
        filter,
        ..Overrides::default()
    };
    build_with(&desc, &path, o, &mut AssetCache::new())
}

fn field(scene: &Scene) -> UvField {
    UvField::compute(scene, &AtomicBool::new(false)).expect("field")
}

fn centre(x: u32, y: u32) -> Vec2 {
    Vec2::new(x as f32 + 0.5, y as f32 + 0.5)
}

/// The texel the in-use lookup picks at pixel (x, y), by the inspector.
fn inspected_texel(scene: &Scene, x: u32, y: u32) -> Option<(u32, u32)> {
    let i = scene.inspect(centre(x, y))?;
    let read = i.image.as_ref()?;
    let pick = i.texels.iter().find(|t| t.lookup == read.lookup)?;
    Some((pick.column, pick.row_from_bottom))
}

#[test]
fn reverse_lookup_under_nearest_is_the_pixels_whose_inspected_texel_is_chosen() {
    // The photo on the rectangle, magnified: many pixels read each texel.
    let scene = scene("rectangle.ron", 96, 72, Some(Filter::Nearest));
    let field = field(&scene);
    let (w, h) = (96, 72);
    let chosen = inspected_texel(&scene, 48, 36).expect("the photo fills the centre");
    let img = &scene.inspect(centre(48, 36)).unwrap().image.unwrap().image;
    let mut mask = TexelMask::new(img.width(), img.height());
    mask.insert(chosen.0, chosen.1);
    let got = pixels_reading(&scene, &field, 0, &mask);
    let mut expected = 0;
    for y in 0..h {
        for x in 0..w {
            let reads = inspected_texel(&scene, x, y) == Some(chosen);
            expected += usize::from(reads);
            assert_eq!(got.contains(x, y), reads, "pixel ({x}, {y})");
        }
    }
    assert!(expected >= 1, "the centre pixel reads its own texel");
    assert_eq!(got.count(), expected);
}

#[test]
fn reverse_lookup_of_a_brushed_block_under_bilinear_covers_the_four_taps() {
    let scene = scene("earth.ron", 64, 48, Some(Filter::Bilinear));
    let field = field(&scene);
    let i = scene
        .inspect(centre(32, 24))
        .expect("the Earth fills the centre");
    let img = i.image.as_ref().unwrap().image.clone();
    let (tw, th) = (img.width(), img.height());
    let uv = i.wrapped_uv.unwrap();
    // A 40 x 20 block of texels around the centre pixel's (u, v).
    let (c0, r0) = (
        (uv.x * tw as f32) as u32 - 20,
        (uv.y * th as f32) as u32 - 10,
    );
    let mut mask = TexelMask::new(tw, th);
    for r in r0..r0 + 20 {
        for c in c0..c0 + 40 {
            mask.insert(c, r);
        }
    }
    let got = pixels_reading(&scene, &field, 0, &mask);
    assert!(got.contains(32, 24));
    for y in 0..48 {
        for x in 0..64 {
            // Bilinear's taps from the inspector's (u, v): texel centres at (i + 0.5) / w.
            let reads = scene
                .inspect(centre(x, y))
                .and_then(|i| i.tex)
                .is_some_and(|t| {
                    let fx = (t.uv.x * tw as f32 - 0.5).floor() as i64;
                    let fy = (t.uv.y * th as f32 - 0.5).floor() as i64;
                    [(0, 0), (1, 0), (0, 1), (1, 1)].iter().any(|(di, dj)| {
                        let c = (fx + di).rem_euclid(i64::from(tw)) as u32;
                        let r = (fy + dj).clamp(0, i64::from(th) - 1) as u32;
                        mask.contains(c, r)
                    })
                });
            assert_eq!(got.contains(x, y), reads, "pixel ({x}, {y})");
        }
    }
}

#[test]
fn reverse_lookup_under_ewa_covers_the_pixels_whose_footprint_holds_the_texel() {
    let scene = scene("earth.ron", 48, 36, Some(Filter::Ewa));
    let field = field(&scene);
    let i = scene.inspect(centre(24, 18)).expect("hit");
    let img = i.image.as_ref().unwrap().image.clone();
    let uv = i.wrapped_uv.unwrap();
    let (c, r) = (
        (uv.x * img.width() as f32) as u32,
        (uv.y * img.height() as f32) as u32,
    );
    let mut mask = TexelMask::new(img.width(), img.height());
    mask.insert(c, r);
    let got = pixels_reading(&scene, &field, 0, &mask);
    assert!(
        got.contains(24, 18),
        "the pixel reads the texel under its centre"
    );
    // Every pixel that reads it has the texel within its footprint parallelogram's bounding box
    // (by the inspector's derivatives, in texels, plus the bilinear taps).
    for y in 0..36 {
        for x in 0..48 {
            if !got.contains(x, y) {
                continue;
            }
            let t = scene.inspect(centre(x, y)).unwrap().tex.unwrap();
            let s = Vec2::new(img.width() as f32, img.height() as f32);
            let at = t.uv * s;
            let half = ((t.duvdx * s).abs() + (t.duvdy * s).abs()) * 0.5 + Vec2::splat(2.0);
            let mut dx = (c as f32 + 0.5 - at.x).abs();
            dx = dx.min(s.x - dx);
            assert!(
                dx <= half.x && (r as f32 + 0.5 - at.y).abs() <= half.y,
                "pixel ({x}, {y}) reads texel ({c}, {r}) far outside its footprint"
            );
        }
    }
}

#[test]
fn the_visible_region_is_the_union_of_the_texels_the_pixels_read() {
    let scene = scene("earth.ron", 64, 48, Some(Filter::Nearest));
    let field = field(&scene);
    let region = visible_region(&scene, &field, 0).expect("the Earth reads an image");
    let mut read = BTreeSet::new();
    for y in 0..48 {
        for x in 0..64 {
            if let Some(t) = inspected_texel(&scene, x, y) {
                read.insert(t);
            }
        }
    }
    assert_eq!(region.count(), read.len());
    for &(c, r) in &read {
        assert!(
            region.contains(c, r),
            "texel ({c}, {r}) read but not in the region"
        );
    }
    // Under bilinear each pixel reads 4 texels: the region grows, and holds the nearest one's.
    let bilinear = self::scene("earth.ron", 64, 48, Some(Filter::Bilinear));
    let wide = visible_region(&bilinear, &self::field(&bilinear), 0).unwrap();
    assert!(wide.count() > region.count());
    // The centred texel is one of bilinear's four taps.
    assert!(read.iter().all(|&(c, r)| wide.contains(c, r)));
    // One side of the Earth: far from the whole texture, more than a few texels.
    let total = (region.width * region.height) as usize;
    assert!(region.count() > 500 && region.count() < total / 10);
}

#[test]
fn under_a_footprint_filter_the_visible_region_spans_the_footprints() {
    // Far away the Earth's footprints are tens of texels: mip filters read far more texels
    // than the nearest filter's one per pixel.
    let nearest = scene("earth.ron", 32, 24, Some(Filter::Nearest));
    let trilinear = scene("earth.ron", 32, 24, Some(Filter::Trilinear));
    let a = visible_region(&nearest, &field(&nearest), 0)
        .unwrap()
        .count();
    let b = visible_region(&trilinear, &field(&trilinear), 0)
        .unwrap()
        .count();
    assert!(b > 20 * a, "nearest {a} texels, trilinear {b}");
}

#[test]
fn iso_lines_sit_where_inspect_says_u_or_v_crosses_an_eighth() {
    let scene = scene("earth.ron", 64, 48, None);
    let field = field(&scene);
    let iso = iso_lines(&field, 8);
    let uv = |x: u32, y: u32| {
        scene
            .inspect(centre(x, y))
            .and_then(|i| i.tex)
            .map(|t| t.uv)
    };
    let cell = |t: f32| (t * 8.0).floor();
    let (mut u_lines, mut v_lines, mut seams) = (0, 0, 0);
    for y in 0..47 {
        for x in 0..63 {
            let Some(a) = uv(x, y) else {
                assert_eq!(iso.at(x, y), 0, "background pixel ({x}, {y}) marked");
                continue;
            };
            let (mut u, mut v, mut seam) = (false, false, false);
            for b in [uv(x + 1, y), uv(x, y + 1)].into_iter().flatten() {
                if (a.x - b.x).abs() > 0.5 {
                    seam = true;
                } else if cell(a.x) != cell(b.x) {
                    u = true;
                }
                v |= cell(a.y) != cell(b.y);
            }
            let f = iso.at(x, y);
            assert_eq!(f & ISO_U != 0, u, "u line at ({x}, {y}): {a}");
            assert_eq!(f & ISO_V != 0, v, "v line at ({x}, {y}): {a}");
            assert_eq!(f & ISO_SEAM != 0, seam, "seam at ({x}, {y})");
            u_lines += usize::from(u);
            v_lines += usize::from(v);
            seams += usize::from(seam);
        }
    }
    // Half the globe shows: about four meridians and most of the seven parallels.
    assert!(u_lines > 40 && v_lines > 40, "{u_lines} {v_lines}");
    assert!(
        seams == 0 || seams > 5,
        "the seam is a line, not a dot: {seams}"
    );
    let texts: BTreeSet<&str> = iso.labels.iter().map(|l| l.text.as_str()).collect();
    assert!(texts.contains("v = 1/2"), "{texts:?}");
    for l in &iso.labels {
        let f = iso.at(l.pixel.0, l.pixel.1);
        assert!(f & if l.is_u { ISO_U } else { ISO_V } != 0, "{l:?}");
    }
}

#[test]
fn the_north_pole_is_marked_where_the_spherical_map_reaches_v_1() {
    // The Earth seen from above its north pole.
    let path = root().join("presets/earth.ron");
    let mut desc = load_preset(&path).unwrap();
    desc.camera.eye = [0.0, 3.6, 0.01].into();
    desc.objects[0].transform = TransformDesc::default();
    let scene = build_with(
        &desc,
        &path,
        crate::common::sized(41, 41, 1),
        &mut AssetCache::new(),
    );
    let iso = iso_lines(&field(&scene), 8);
    assert!(iso.at(20, 20) & ISO_POLE != 0, "the pole at the centre");
    assert_eq!(iso.at(5, 20) & ISO_POLE, 0, "not the rim");
    // One pole marker, at the centre, for the overlay's ring; the seam runs from it.
    assert_eq!(iso.poles.len(), 1, "{:?}", iso.poles);
    let (px, py) = iso.poles[0];
    assert!(
        (px - 20.5).abs() < 1.5 && (py - 20.5).abs() < 1.5,
        "{px}, {py}"
    );
    assert!(!iso.seam.is_empty());
    assert!(iso.seam.iter().all(|&(x, y)| iso.at(x, y) & ISO_SEAM != 0));
    let v = scene.inspect(centre(20, 20)).unwrap().tex.unwrap().uv.y;
    assert!(v > 0.97, "{v}");
}

#[test]
fn a_cancelled_pass_returns_no_field() {
    let scene = scene("earth.ron", 64, 48, None);
    let r = UvField::compute(&scene, &AtomicBool::new(true));
    assert!(matches!(r, Err(FieldError::Cancelled)));
}
