//! Measuring outside texplore (issue 15): the linear EXR / HDR a render writes, a report judged
//! against an external linear reference, and the peer scene (`presets/peer-sphere.ron`) whose
//! error falls as the samples per pixel grow, for every count.

use crate::common::{build_with, failure, render_on, root, success, texplore};
use std::path::Path;
use texplore::math::{Rgb, linear_to_srgb, quantize8};
use texplore::sampler::PixelSampler;
use texplore::scene::{AssetCache, Overrides, load_preset};

const PEER: &str = "presets/peer-sphere.ron";

fn render(args: &[&str], out: &Path) {
    let mut all = vec![
        "render",
        PEER,
        "-q",
        "--threads",
        "2",
        "-o",
        out.to_str().unwrap(),
    ];
    all.extend_from_slice(args);
    success(&texplore(&all));
}

fn rgb32(path: &Path) -> image::Rgb32FImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb32f()
}

fn rmse(a: &[f32], b: &[f32]) -> f64 {
    assert_eq!(a.len(), b.len());
    let s: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| (f64::from(*x) - f64::from(*y)).powi(2))
        .sum();
    (s / a.len() as f64).sqrt()
}

#[test]
fn render_writes_the_linear_image_as_exr_and_hdr() {
    let dir = tempfile::tempdir().unwrap();
    let size = ["--width", "64", "--height", "48", "--spp", "4"];
    let (png, exr, hdr) = (
        dir.path().join("p.png"),
        dir.path().join("p.exr"),
        dir.path().join("p.hdr"),
    );
    for out in [&png, &exr, &hdr] {
        render(&size, out);
    }
    let exr = rgb32(&exr);
    assert_eq!(exr.dimensions(), (64, 48));
    // The EXR holds the radiance itself: sRGB-encoded and rounded it is the PNG's bytes
    // (the peer scene's exposure is 0), and the texture's raw values stay below 1.
    let bytes: Vec<u8> = exr
        .as_raw()
        .iter()
        .map(|v| quantize8(linear_to_srgb(*v)))
        .collect();
    assert_eq!(bytes, image::open(&png).unwrap().to_rgb8().into_raw());
    let max = exr.as_raw().iter().copied().fold(0.0f32, f32::max);
    assert!(max > 0.3 && max <= 1.0, "{max}");
    // Black background at the corner, texture at the centre.
    assert_eq!(exr.get_pixel(0, 0).0, [0.0; 3]);
    assert!(exr.get_pixel(32, 24).0.iter().all(|c| *c > 0.0));
    // RGBE: 8 mantissa bits against each pixel's largest channel.
    let hdr = rgb32(&hdr);
    for (a, b) in hdr.pixels().zip(exr.pixels()) {
        let top = b.0.iter().copied().fold(0.0f32, f32::max);
        for k in 0..3 {
            assert!(
                (a.0[k] - b.0[k]).abs() <= top / 128.0 + 1e-6,
                "{a:?} vs {b:?}"
            );
        }
    }
}

#[test]
fn report_judges_against_an_external_reference_in_linear_units() {
    let dir = tempfile::tempdir().unwrap();
    let size = ["--width", "48", "--height", "36"];
    let reference = dir.path().join("ref.exr");
    render(&[&size[..], &["--spp", "64"]].concat(), &reference);
    // What the report's bilinear/jittered 1-spp render is: the same settings, the same seed.
    let test = dir.path().join("test.exr");
    render(
        &[
            &size[..],
            &[
                "--spp",
                "1",
                "--filter",
                "bilinear",
                "--sampler",
                "jittered",
            ],
        ]
        .concat(),
        &test,
    );
    let out = dir.path().join("rep");
    success(&texplore(&[
        "report",
        PEER,
        "--reference",
        reference.to_str().unwrap(),
        "--modes",
        "bilinear/jittered",
        "--spp",
        "1",
        "--width",
        "48",
        "--height",
        "36",
        "--repeat",
        "1",
        "--quiet",
        "-o",
        out.to_str().unwrap(),
    ]));
    let mut csv = csv::Reader::from_path(out.join("report.csv")).unwrap();
    let header = csv.headers().unwrap().clone();
    let row = csv.records().next().unwrap().unwrap();
    let col = |name: &str| {
        let i = header.iter().position(|h| h == name).unwrap();
        row[i].parse::<f64>().unwrap()
    };
    let want = rmse(rgb32(&reference).as_raw(), rgb32(&test).as_raw());
    assert!(want > 0.005, "{want}");
    assert!(
        (col("rmse_linear") - want).abs() < 2e-7,
        "{} vs {want}",
        col("rmse_linear")
    );
    // The display-encoded RMSE is another number (the sRGB curve in between).
    assert!(
        (col("rmse") - want).abs() > 1e-3,
        "{} vs {want}",
        col("rmse")
    );
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("RMSE linear") && md.contains("ref.exr"), "{md}");
}

#[test]
fn a_reference_of_another_size_or_kind_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let reference = dir.path().join("small.exr");
    render(
        &["--width", "20", "--height", "10", "--spp", "1"],
        &reference,
    );
    let out = dir.path().join("rep");
    let run = |reference: &Path, presets: &[&str]| {
        let mut args = vec!["report"];
        args.extend_from_slice(presets);
        args.extend_from_slice(&[
            "--reference",
            reference.to_str().unwrap(),
            "--modes",
            "bilinear/jittered",
            "--spp",
            "1",
            "--width",
            "30",
            "--height",
            "20",
            "--quiet",
            "-o",
            out.to_str().unwrap(),
        ]);
        failure(&texplore(&args))
    };
    let e = run(&reference, &[PEER]);
    assert!(
        e.contains("small.exr") && e.contains("20x10 pixels, but the render is 30x20"),
        "{e}"
    );
    let png = dir.path().join("r.png");
    std::fs::write(&png, b"not an image").unwrap();
    let e = run(&png, &[PEER]);
    assert!(e.contains("r.png") && e.contains(".exr or .hdr"), "{e}");
    let e = run(&reference, &[PEER, "presets/earth.ron"]);
    assert!(e.contains("exactly one preset"), "{e}");
    let broken = dir.path().join("broken.exr");
    std::fs::write(&broken, b"v/1\x01 not really").unwrap();
    let e = run(&broken, &[PEER]);
    assert!(
        e.contains("broken.exr") && e.contains("not a readable image"),
        "{e}"
    );
}

#[test]
fn the_peer_scene_error_falls_with_the_sample_count() {
    // At 80x60 a pixel covers ~25 texels of the peer texture: a pattern that leaves part of
    // each pixel unsampled (32 = a 6x6 grid less 4 cells) was 5x worse than 30 or 36.
    let path = root().join(PEER);
    let desc = load_preset(&path).unwrap();
    let mut cache = AssetCache::new();
    let at = |spp: u32, sampler: PixelSampler, seed: u32, cache: &mut AssetCache| {
        let o = Overrides {
            width: Some(80),
            height: Some(60),
            spp: Some(spp),
            sampler: Some(sampler),
            seed: Some(seed),
            ..Overrides::default()
        };
        render_on(&build_with(&desc, &path, o, cache), 2).to_linear()
    };
    let reference = at(1024, PixelSampler::Jittered, 99, &mut cache);
    let flat = |v: &[Rgb]| v.iter().flat_map(|c| c.to_array()).collect::<Vec<f32>>();
    let reference = flat(&reference);
    for sampler in [
        PixelSampler::Regular,
        PixelSampler::Jittered,
        PixelSampler::MultiJittered,
    ] {
        let e: Vec<f64> = [27, 30, 32, 36]
            .iter()
            .map(|&n| rmse(&flat(&at(n, sampler, 1, &mut cache)), &reference))
            .collect();
        // Monotone within noise: each count at most 10 % above the one before it, and 36 below
        // 27 by more than the noise.
        for w in e.windows(2) {
            assert!(
                w[1] <= w[0] * 1.1,
                "{sampler:?}: RMSE at 27, 30, 32, 36 spp: {e:?}"
            );
        }
        assert!(e[3] < e[0] * 0.95, "{sampler:?}: {e:?}");
    }
}
