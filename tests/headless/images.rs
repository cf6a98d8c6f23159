//! Every supported image format loads with the right texels, and bad image files give one
//! clear error naming the file; what a render shows, saves and is measured on are the same bytes.

use crate::common::crc32;
use crate::common::{build_with, root, sized};
use std::fmt::Write as _;
use std::path::Path;
use texplore::Error;
use texplore::math::{DisplayImage, Rgb, quantize8, srgb_to_linear};
use texplore::render::render_blocking;
use texplore::report::metrics::EncodedImage;
use texplore::scene::{AssetCache, load_preset, save_render_png};
use texplore::texture::{ImageData, MipPyramid, Texels, load_image};

/// A 3 x 2 test pattern (row 0 on top): distinct colours so a flip or swap shows.
const PATTERN: [[u8; 3]; 6] = [
    [255, 0, 0],
    [0, 255, 0],
    [0, 0, 255],
    [255, 255, 0],
    [0, 255, 255],
    [128, 128, 128],
];

fn check_8bit(path: &Path) {
    let img = load_image(path, true).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((img.width(), img.height()), (3, 2));
    for (i, p) in PATTERN.iter().enumerate() {
        let c = img.texel_top(i as u32 % 3, i as u32 / 3);
        let expect = Rgb(
            srgb_to_linear(f32::from(p[0]) / 255.0),
            srgb_to_linear(f32::from(p[1]) / 255.0),
            srgb_to_linear(f32::from(p[2]) / 255.0),
        );
        let tol = if path.extension().unwrap() == "jpg" {
            0.08
        } else {
            1e-3
        };
        assert!(
            (c.0 - expect.0).abs() < tol
                && (c.1 - expect.1).abs() < tol
                && (c.2 - expect.2).abs() < tol,
            "{} texel {i}: {c:?} vs {expect:?}",
            path.display()
        );
    }
}

fn rgb8() -> image::RgbImage {
    image::RgbImage::from_fn(3, 2, |x, y| image::Rgb(PATTERN[(y * 3 + x) as usize]))
}

#[test]
fn png_tiff_ppm_load_exactly_and_jpeg_closely() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["png", "tif", "ppm"] {
        let p = dir.path().join(format!("t.{ext}"));
        rgb8().save(&p).unwrap();
        check_8bit(&p);
    }
    // JPEG is lossy and subsamples chroma: a larger flat-colour image keeps the colours.
    let big = image::RgbImage::from_fn(48, 32, |x, y| {
        image::Rgb(PATTERN[((y / 16) * 3 + x / 16) as usize])
    });
    let p = dir.path().join("t.jpg");
    image::DynamicImage::ImageRgb8(big)
        .to_rgb8()
        .save(&p)
        .unwrap();
    let img = load_image(&p, true).unwrap();
    assert_eq!((img.width(), img.height()), (48, 32));
    let c = img.texel_top(8, 8);
    assert!(c.0 > 0.8 && c.1 < 0.1 && c.2 < 0.1, "{c:?}");
}

/// An 8-bit image read raw (`srgb: false`, a mask or a data texture) keeps its bytes, 4 a
/// texel as sRGB ones do, and reads each as exactly `v / 255`; its coarser mip levels are the
/// exact averages of those values.
#[test]
fn a_raw_8_bit_image_keeps_its_bytes_and_reads_v_over_255() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("t.png");
    rgb8().save(&p).unwrap();
    let img = load_image(&p, false).unwrap();
    assert!(matches!(img.texels(), Texels::Unorm8(_)));
    assert_eq!(
        img.texels_bytes(),
        load_image(&p, true).unwrap().texels_bytes()
    );
    for (i, px) in PATTERN.iter().enumerate() {
        let c = img.texel_top(i as u32 % 3, i as u32 / 3);
        assert_eq!(c.to_array(), px.map(|v| f32::from(v) / 255.0), "texel {i}");
    }
    // The same values as linear floats (what raw 8-bit images were stored as before): the same
    // mip levels, bit for bit.
    let floats = ImageData::from_fn(3, 2, "floats", |c, r| img.texel_top(c, r));
    let (raw, floats) = (
        MipPyramid::build(std::sync::Arc::new(img)),
        MipPyramid::build(std::sync::Arc::new(floats)),
    );
    assert_eq!(raw.len(), floats.len());
    for l in 1..raw.len() {
        let (a, b) = (raw.level(l), floats.level(l));
        assert!(a.is_linear());
        for (c, r) in [(0, 0), (a.width() - 1, a.height() - 1)] {
            assert_eq!(a.texel(c, r), b.texel(c, r), "level {l}");
        }
    }
}

/// An 8-bit texture encoded back to sRGB bytes is the file's bytes.
#[test]
fn an_8_bit_texture_encodes_back_to_its_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("t.png");
    rgb8().save(&p).unwrap();
    let img = load_image(&p, true).unwrap();
    assert_eq!(img.to_srgb8(), PATTERN.concat());
}

/// The window's image, the PNG a render saves and the bytes the report measures are one
/// encoding of the film: exposure applied, clipped, sRGB.
#[test]
fn display_png_and_report_bytes_agree() {
    let path = root().join("presets/earth.ron");
    let desc = load_preset(&path).unwrap();
    let scene = build_with(&desc, &path, sized(48, 32, 2), &mut AssetCache::new());
    let film = render_blocking(&scene, |_| {});
    let linear = film.to_linear();
    for exposure in [scene.settings.exposure_scale, 8.0] {
        let shown = film.to_display(exposure);
        assert_eq!((shown.width, shown.height), (48, 32));
        assert!(shown.rgba.chunks_exact(4).all(|p| p[3] == 255));
        assert!(shown == DisplayImage::from_linear(48, 32, &linear, exposure));
        let measured = EncodedImage::from_linear(48, 32, &linear, exposure);
        assert!(measured.srgb8 == shown.rgb(), "exposure {exposure}");
        // The float values round to the bytes, give or take one for the display table's step.
        for (f, b) in measured.srgb.iter().zip(&measured.srgb8) {
            assert!(quantize8(*f).abs_diff(*b) <= 1, "{f} vs {b}");
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("e.png");
    let shown = film.to_display(scene.settings.exposure_scale);
    save_render_png(&png, &shown, &desc, root().join("presets").as_path()).unwrap();
    let saved = image::open(&png).unwrap().to_rgb8();
    assert_eq!(saved.dimensions(), (48, 32));
    assert!(saved.into_raw() == shown.rgb());
}

#[test]
fn ascii_ppm_p3_and_16_bit_p6() {
    let dir = tempfile::tempdir().unwrap();
    let p3 = dir.path().join("a.ppm");
    let mut text = String::from("P3\n# a comment\n3 2\n255\n");
    for p in PATTERN {
        let _ = writeln!(text, "{} {} {}", p[0], p[1], p[2]);
    }
    std::fs::write(&p3, text).unwrap();
    check_8bit(&p3);

    let p16 = dir.path().join("b.ppm");
    let mut bytes = b"P6\n2 1\n65535\n".to_vec();
    for v in [65535u16, 0, 0, 0, 32768, 65535] {
        bytes.extend_from_slice(&v.to_be_bytes());
    }
    std::fs::write(&p16, bytes).unwrap();
    let img = load_image(&p16, true).unwrap();
    assert!(img.is_linear());
    assert_eq!(img.texel_top(0, 0), Rgb(1.0, 0.0, 0.0));
    assert!((img.texel_top(1, 0).1 - srgb_to_linear(32768.0 / 65535.0)).abs() < 1e-5);
}

#[test]
fn hdr_and_exr_keep_values_above_one() {
    let dir = tempfile::tempdir().unwrap();
    let data = vec![8.0f32, 0.5, 0.25, 100.0, 1.0, 0.0];
    let img = image::Rgb32FImage::from_raw(2, 1, data).unwrap();
    for ext in ["hdr", "exr"] {
        let p = dir.path().join(format!("t.{ext}"));
        image::DynamicImage::ImageRgb32F(img.clone())
            .save(&p)
            .unwrap();
        let t = load_image(&p, true).unwrap();
        assert!(t.is_linear());
        let c = t.texel_top(1, 0);
        assert!(
            (c.0 - 100.0).abs() < 1.0 && (c.1 - 1.0).abs() < 0.02,
            "{ext}: {c:?}"
        );
        let c = t.texel_top(0, 0);
        assert!((c.0 - 8.0).abs() < 0.1, "{ext}: {c:?}");
    }
}

#[test]
fn shipped_assets_load() {
    let root = root().join("assets");
    for (name, w, h) in [
        ("earth_2048x1024.jpg", 2048, 1024),
        ("courtyard_1024x512.hdr", 1024, 512),
        ("courtyard_probe.hdr", 512, 512),
    ] {
        let img = load_image(&root.join(name), true).unwrap();
        assert_eq!((img.width(), img.height()), (w, h), "{name}");
    }
}

#[test]
fn corrupt_truncated_and_missing_files_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("good.png");
    rgb8().save(&good).unwrap();
    let bytes = std::fs::read(&good).unwrap();
    let truncated = dir.path().join("truncated.png");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    let garbage = dir.path().join("garbage.jpg");
    std::fs::write(&garbage, b"this is not a jpeg at all").unwrap();
    let empty = dir.path().join("empty.hdr");
    std::fs::write(&empty, b"").unwrap();
    for p in [&truncated, &garbage, &empty] {
        let e = load_image(p, true).unwrap_err();
        assert!(matches!(e, Error::Image { .. } | Error::Io { .. }));
        assert!(
            e.to_string()
                .contains(p.file_name().unwrap().to_str().unwrap()),
            "{e}"
        );
    }
    let e = load_image(&dir.path().join("missing.png"), true).unwrap_err();
    assert!(matches!(e, Error::Io { .. }) && e.to_string().contains("missing.png"));
}

#[test]
fn absurd_dimensions_are_refused_before_allocating() {
    // A valid PNG header claiming 100000 x 100000 pixels, with no data behind it.
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bomb.png");
    let mut png = vec![0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a];
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend_from_slice(&100_000u32.to_be_bytes());
    ihdr.extend_from_slice(&100_000u32.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    png.extend_from_slice(&13u32.to_be_bytes());
    png.extend_from_slice(&ihdr);
    png.extend_from_slice(&crc32(&ihdr).to_be_bytes());
    std::fs::write(&p, png).unwrap();
    let e = load_image(&p, true).unwrap_err().to_string();
    assert!(e.contains("bomb.png"), "{e}");
}
