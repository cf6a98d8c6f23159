//! Antialiasing end to end: filters against high-sample references on the receding checker
//! plane and a zone plate, the spherical seam under trilinear filtering, screen-space
//! derivatives against finite differences of real hits, adaptive sampling, debug views.
//!
//! Errors are RMSE of display values in [0, 1] (sRGB-encoded, clipped) over every pixel and
//! channel, against references rendered with bilinear filtering, box pixels and 256 jittered
//! samples per pixel, at low resolution so each test runs in seconds.

use crate::common::{build_with, failure, render_on, root, sized, success, texplore};
use std::path::{Path, PathBuf};
use strum::VariantArray;
use texplore::mapping::MAX_FOOTPRINT;
use texplore::math::{Vec2, linear_to_srgb};
use texplore::render::Film;
use texplore::sampler::PixelSampler;
use texplore::scene::{
    AdaptiveDesc, AssetCache, Overrides, SceneDesc, build_scene, load_preset, parse_preset,
};
use texplore::texture::{Filter, ImageData, View, save_png};

fn preset(name: &str) -> PathBuf {
    root().join(format!("presets/{name}.ron"))
}

fn render_desc(desc: &SceneDesc, path: &Path, o: Overrides, threads: usize) -> Film {
    render_on(&build_with(desc, path, o, &mut AssetCache::new()), threads)
}

fn overrides(w: u32, h: u32, spp: u32, filter: Filter, sampler: PixelSampler) -> Overrides {
    Overrides {
        filter: Some(filter),
        sampler: Some(sampler),
        no_adaptive: true,
        ..sized(w, h, spp)
    }
}

fn display(film: &Film) -> Vec<f32> {
    film.to_linear()
        .iter()
        .flat_map(|c| c.to_array())
        .map(|v| linear_to_srgb(v.clamp(0.0, 1.0)))
        .collect()
}

/// RMSE on display values, as the report and the window's A/B split measure it.
fn rmse(a: &Film, b: &Film) -> f64 {
    use texplore::report::metrics::{EncodedImage, rmse};
    rmse(
        &EncodedImage::from_film(a, 1.0),
        &EncodedImage::from_film(b, 1.0),
    )
    .expect("same size")
}

/// RMSE of 1-spp nearest and 1-spp EWA renders against a 256-spp bilinear reference.
fn nearest_and_ewa_errors(desc: &SceneDesc, path: &Path, w: u32, h: u32) -> (f64, f64, f64) {
    let reference = render_desc(
        desc,
        path,
        overrides(w, h, 256, Filter::Bilinear, PixelSampler::Jittered),
        0,
    );
    let nearest = render_desc(
        desc,
        path,
        overrides(w, h, 1, Filter::Nearest, PixelSampler::Jittered),
        0,
    );
    let ewa = render_desc(
        desc,
        path,
        overrides(w, h, 1, Filter::Ewa, PixelSampler::Regular),
        0,
    );
    let trilinear = render_desc(
        desc,
        path,
        overrides(w, h, 1, Filter::Trilinear, PixelSampler::Regular),
        0,
    );
    (
        rmse(&nearest, &reference),
        rmse(&ewa, &reference),
        rmse(&trilinear, &reference),
    )
}

#[test]
fn receding_checker_plane_nearest_aliases_and_ewa_is_close_to_the_reference() {
    let path = preset("checker-plane");
    let desc = load_preset(&path).unwrap();
    let (nearest, ewa, trilinear) = nearest_and_ewa_errors(&desc, &path, 96, 72);
    eprintln!("checker plane: nearest {nearest:.4}, ewa {ewa:.4}, trilinear {trilinear:.4}");
    // Nearest at 1 spp draws moire toward the horizon; EWA at 1 spp is within 0.06 of the
    // reference (mostly the plane's near edge, which one sample per pixel cannot antialias).
    assert!(nearest > 0.1, "nearest {nearest}");
    assert!(ewa < 0.06, "ewa {ewa}");
    assert!(ewa < nearest * 0.5, "ewa {ewa} nearest {nearest}");
    // Trilinear is alias-free too, but blurs the distance: between the two.
    assert!(trilinear < nearest, "trilinear {trilinear}");
}

#[test]
fn zone_plate_nearest_aliases_and_ewa_is_close_to_the_reference() {
    // A 512 x 512 zone plate (cos of the squared radius, frequency rising to the corners) on a
    // rectangle filling a 64 x 64 view: each pixel covers 8 x 8 texels.
    let dir = tempfile::tempdir().unwrap();
    let n = 512u32;
    let img = ImageData::from_fn(n, n, "zone", |x, y| {
        let (dx, dy) = (x as f32 - n as f32 / 2.0, y as f32 - n as f32 / 2.0);
        let k = std::f32::consts::PI / n as f32;
        texplore::math::Rgb::grey(0.5 + 0.5 * (k * (dx * dx + dy * dy)).cos())
    });
    let png = dir.path().join("zone.png");
    save_png(&png, n, n, &img.to_srgb8(), &[]).unwrap();
    let path = dir.path().join("zone.ron");
    let text = r#"(
        version: 1,
        camera: (eye: (0, 3, 0), look_at: (0, 0, 0), up: (0, 0, -1), projection: Pinhole(fov: 36.87)),
        render: (width: 64, height: 64),
        ambient: (ls: 1),
        objects: [(shape: Rectangle, material: Emissive(ce: Image(path: "zone.png", mapping: Rectangular, wrap: Clamp)))],
    )"#;
    let desc = parse_preset(text, &path).unwrap();
    let (nearest, ewa, trilinear) = nearest_and_ewa_errors(&desc, &path, 64, 64);
    eprintln!("zone plate: nearest {nearest:.4}, ewa {ewa:.4}, trilinear {trilinear:.4}");
    assert!(nearest > 0.15, "nearest {nearest}");
    assert!(ewa < 0.05, "ewa {ewa}");
    assert!(trilinear < 0.05, "trilinear {trilinear}");
}

/// Renders the Earth with the spherical seam running down the middle column (no rotation: the
/// seam is the meridian at local +z, facing the camera), 65 pixels wide so it crosses the
/// centre of column 32.
fn earth_facing_seam(filter: Filter, view: View) -> (Film, u32) {
    let path = preset("earth");
    let mut desc = load_preset(&path).unwrap();
    desc.objects[0].transform.rotate = texplore::math::Vec3::ZERO;
    desc.render.view = view;
    desc.lights.clear();
    let w = 65;
    let film = render_desc(
        &desc,
        &path,
        overrides(w, 49, 1, filter, PixelSampler::Regular),
        0,
    );
    (film, w)
}

#[test]
fn trilinear_draws_no_line_at_the_spherical_seam() {
    for filter in [Filter::Trilinear, Filter::Ewa] {
        let (film, w) = earth_facing_seam(filter, View::Shaded);
        let px = display(&film);
        let h = px.len() / 3 / w as usize;
        // How much column c differs from the mean of its neighbours, over the sphere's rows.
        let bump = |c: usize| -> f64 {
            let mut s = 0.0;
            for y in 12..h - 12 {
                for ch in 0..3 {
                    let at = |x: usize| f64::from(px[(y * w as usize + x) * 3 + ch]);
                    s += (at(c) - 0.5 * (at(c - 1) + at(c + 1))).abs();
                }
            }
            s
        };
        let seam = bump(32);
        let others: Vec<f64> = (26..39).filter(|c| *c != 32).map(bump).collect();
        let typical = others.iter().sum::<f64>() / others.len() as f64;
        eprintln!("{filter}: seam column {seam:.3}, neighbouring columns {typical:.3}");
        assert!(
            seam < 2.0 * typical,
            "{filter}: the seam column stands out ({seam} vs {typical})"
        );
    }
}

#[test]
fn seam_view_marks_the_seam_column_and_uv_view_shows_u() {
    let (film, w) = earth_facing_seam(Filter::Bilinear, View::Seams);
    let lin = film.to_linear();
    let magenta = |c: texplore::math::Rgb| c.0 > 0.5 && c.1 < 0.1 && c.2 > 0.5;
    assert!(
        magenta(lin[24 * w as usize + 32]),
        "{:?}",
        lin[24 * w as usize + 32]
    );
    assert!(!magenta(lin[24 * w as usize + 24]));
    // Rotated 90 degrees about y, the point facing the camera is local -x: u = 0.75, v = 0.5.
    let path = preset("earth");
    let mut desc = load_preset(&path).unwrap();
    desc.objects[0].transform.rotate = texplore::math::Vec3::new(0.0, 90.0, 0.0);
    desc.render.view = View::Uv;
    let film = render_desc(
        &desc,
        &path,
        overrides(65, 49, 1, Filter::Bilinear, PixelSampler::Regular),
        0,
    );
    let c = film.to_linear()[24 * 65 + 32];
    let (u, v) = (linear_to_srgb(c.0), linear_to_srgb(c.1));
    assert!((u - 0.75).abs() < 0.01 && (v - 0.5).abs() < 0.01, "{u} {v}");
}

#[test]
fn looking_down_at_a_pole_every_filter_and_view_is_finite() {
    let path = preset("earth");
    let mut desc = load_preset(&path).unwrap();
    desc.camera.eye = texplore::math::Vec3::new(0.0, 3.0, 0.0);
    desc.camera.up = texplore::math::Vec3::Z;
    desc.objects[0].transform.rotate = texplore::math::Vec3::ZERO;
    for &filter in Filter::VARIANTS {
        for &view in View::VARIANTS {
            desc.render.view = view;
            let film = render_desc(
                &desc,
                &path,
                overrides(33, 33, 1, filter, PixelSampler::Regular),
                0,
            );
            assert!(film.is_finite(), "{filter} {view}");
            // The pole pixel is the polar cap's colour, not black.
            assert!(
                film.to_linear()[16 * 33 + 16].max_channel() > 0.0,
                "{filter} {view}"
            );
        }
    }
}

#[test]
fn screen_space_derivatives_match_finite_differences_of_real_hits() {
    // For the sphere, the cylinder and the plane, d(u, v)/dx from the ray differentials agrees
    // within 5% with the (u, v) of the real hits one pixel right and one pixel down, away from
    // seams, clamped footprints and grazing views.
    for (name, mapping_check) in [("earth", 0), ("cylinder", 1), ("checker-plane", 2)] {
        let path = preset(name);
        let o = Overrides {
            width: Some(200),
            height: Some(150),
            filter: Some(Filter::Ewa),
            ..Overrides::default()
        };
        let scene = build_with(
            &load_preset(&path).unwrap(),
            &path,
            o,
            &mut AssetCache::new(),
        );
        assert!(scene.needs_differentials());
        let mut checked = 0;
        for y in (10..140).step_by(7) {
            for x in (10..190).step_by(7) {
                let pos = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                let Some((ray, diff)) = scene.camera.ray(pos, 1.0) else {
                    continue;
                };
                let Some(hit) = scene.hit(&ray) else { continue };
                // Near the silhouette a one-pixel offset ray meets the tangent plane far from
                // the surface (first-order only, as in pbrt): compare where the view is not
                // grazing.
                // (A plane is its own tangent plane: exact at any angle.)
                if name != "checker-plane" && hit.ng.dot(ray.dir.normalize()).abs() < 0.5 {
                    continue;
                }
                let obj = &scene.objects[hit.object];
                let Some(mapping) = scene.materials[obj.material].texture().mapping() else {
                    continue;
                };
                let tc = scene.texture_context(&hit, Some(&diff)).tex_coord(mapping);
                let at = |p: Vec2| {
                    let (r, _) = scene.camera.ray(p, 1.0)?;
                    let h = scene.hit(&r)?;
                    // The same surface: same object and part, facing the same way (the open
                    // cylinder shows its inside next to its outside).
                    let same = h.object == hit.object
                        && h.local.part == hit.local.part
                        && h.ng.dot(hit.ng) > 0.9
                        && (h.p - hit.p).length() < 0.2;
                    same.then(|| scene.texture_context(&h, None).tex_coord(mapping).uv)
                };
                // The differentials are the offsets to the neighbouring pixels' hits (one pixel
                // right, one down): compare with the (u, v) found there.
                let (Some(r), Some(d)) =
                    (at(pos + Vec2::new(1.0, 0.0)), at(pos + Vec2::new(0.0, 1.0)))
                else {
                    continue;
                };
                let (fdx, fdy) = (r - tc.uv, d - tc.uv);
                // Skip the seam (u jumps by ~1) and footprints clamped to MAX_FOOTPRINT.
                if fdx.abs().max(fdy.abs()).max_element() > 0.25
                    || tc.duvdx.abs().max(tc.duvdy.abs()).max_element() >= MAX_FOOTPRINT
                {
                    continue;
                }
                let scale = fdx.abs().max(fdy.abs()).max_element().max(1e-4);
                let err = (fdx - tc.duvdx)
                    .abs()
                    .max((fdy - tc.duvdy).abs())
                    .max_element();
                assert!(
                    err < 0.05 * scale,
                    "{name} ({mapping_check}) at ({x}, {y}): analytic {:?} {:?}, finite {fdx:?} {fdy:?}",
                    tc.duvdx,
                    tc.duvdy
                );
                checked += 1;
            }
        }
        assert!(checked > 50, "{name}: only {checked} pixels checked");
    }
}

#[test]
fn adaptive_sampling_is_deterministic_refines_edges_and_beats_uniform_at_equal_cost() {
    let path = preset("checker");
    let desc = load_preset(&path).unwrap();
    let adaptive = |threads| {
        render_desc(
            &desc,
            &path,
            Overrides {
                adaptive: Some(AdaptiveDesc {
                    max_spp: 16,
                    threshold: 0.01,
                }),
                no_adaptive: false,
                ..overrides(80, 60, 1, Filter::Ewa, PixelSampler::Regular)
            },
            threads,
        )
    };
    let (a1, a2) = (adaptive(1), adaptive(2));
    assert!(a1 == a2, "1- and 2-thread adaptive renders differ");
    let reference = render_desc(
        &desc,
        &path,
        overrides(80, 60, 256, Filter::Nearest, PixelSampler::Jittered),
        0,
    );
    let spp = a1.total_samples() / (80.0 * 60.0);
    let uniform = render_desc(
        &desc,
        &path,
        overrides(
            80,
            60,
            spp.ceil() as u32,
            Filter::Ewa,
            PixelSampler::Jittered,
        ),
        0,
    );
    let (ea, eu) = (rmse(&a1, &reference), rmse(&uniform, &reference));
    eprintln!(
        "adaptive: {spp:.2} spp, RMSE {ea:.4}; uniform {} spp: {eu:.4}",
        spp.ceil()
    );
    // Extra samples went to edges only: far fewer than 16 per pixel on average, and some
    // pixels (the sky, the plane's filtered interior) kept a single sample.
    assert!(spp < 6.0, "{spp}");
    assert!(a1.pixels().iter().any(|p| p[3] == 1.0));
    assert!(a1.pixels().iter().any(|p| p[3] == 16.0));
    assert!(ea < eu, "adaptive {ea} vs uniform {eu}");
}

#[test]
fn render_command_takes_the_antialiasing_options() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ewa.png");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "render",
            "presets/checker-plane.ron",
            "--width",
            "32",
            "--height",
            "24",
            "--spp",
            "1",
            "-q",
        ];
        args.extend_from_slice(extra);
        texplore(&args)
    };
    let o = run(&[
        "--filter",
        "ewa",
        "--max-aniso",
        "16",
        "--pixel-filter",
        "tent",
        "--adaptive",
        "4,0.02",
        "--view",
        "mip-level",
        "-o",
        out.to_str().unwrap(),
    ]);
    success(&o);
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (32, 24));
    // The preset saved in the PNG carries the options.
    let desc = texplore::scene::read_preset_or_png(&out).unwrap();
    assert_eq!(desc.render.view, View::MipLevel);
    assert_eq!(
        desc.render.adaptive,
        Some(AdaptiveDesc {
            max_spp: 4,
            threshold: 0.02
        })
    );
    // Bad values are refused with the option named.
    for (bad, named) in [
        (["--adaptive", "lots"], "MAX_SPP"),
        (["--max-aniso", "0.5"], "max_anisotropy"),
        (["--view", "depth"], "texel-grid"),
    ] {
        let e = failure(&run(&[bad[0], bad[1], "-o", out.to_str().unwrap()]));
        assert!(e.contains(named), "{bad:?}: {e}");
    }
}

#[test]
fn mip_pyramids_are_built_only_for_mip_filters_and_once_per_image() {
    let path = preset("checker-plane");
    let mut desc = load_preset(&path).unwrap();
    let mut cache = AssetCache::new();
    for filter in [Filter::Nearest, Filter::Bilinear, Filter::Bicubic] {
        desc.objects[0].material.texture_mut().set_filter(filter);
        build_scene(&desc, &path, &mut cache).unwrap();
    }
    assert_eq!(cache.mip_count(), 0);
    for filter in [Filter::Ewa, Filter::Trilinear, Filter::Ewa] {
        desc.objects[0].material.texture_mut().set_filter(filter);
        build_scene(&desc, &path, &mut cache).unwrap();
    }
    assert_eq!(cache.mip_count(), 1);
}

#[test]
fn presets_name_ewa_plainly_and_refuse_bad_anisotropy() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/x.ron");
    let text = |extra: &str| {
        format!(
            r#"(
            version: 1,
            camera: (eye: (0, 0, 3)),
            objects: [(shape: Sphere, material: Matte(cd: Image(path: "../assets/earth_2048x1024.jpg", filter: Ewa{extra})))],
        )"#
        )
    };
    let desc = parse_preset(&text(""), &path).unwrap();
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).unwrap();
    assert!(scene.needs_differentials());
    let desc = parse_preset(&text(", max_anisotropy: 16"), &path).unwrap();
    build_scene(&desc, &path, &mut AssetCache::new()).expect("max_anisotropy 16 is accepted");
    let desc = parse_preset(&text(", max_anisotropy: 0"), &path).unwrap();
    let e = build_scene(&desc, &path, &mut AssetCache::new())
        .unwrap_err()
        .to_string();
    assert!(e.contains("max_anisotropy") && e.contains("x.ron"), "{e}");
    // Adaptive settings are checked too.
    let mut desc = parse_preset(&text(""), &path).unwrap();
    desc.render.spp = 8;
    desc.render.adaptive = Some(AdaptiveDesc {
        max_spp: 4,
        threshold: 0.01,
    });
    let e = build_scene(&desc, &path, &mut AssetCache::new())
        .unwrap_err()
        .to_string();
    assert!(e.contains("render.adaptive.max_spp"), "{e}");
}
