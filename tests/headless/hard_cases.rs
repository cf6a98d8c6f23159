//! Numerical hard cases: the singular points and extreme magnitudes where the lecture's code (and
//! other renderers) produce NaN, divide by zero, lose precision or speckle with shadow acne.

use crate::common::{build_with, filtered, parse_json, root, sized, texplore};
use proptest::prelude::*;
use std::path::Path;
use strum::VariantArray;
use texplore::mapping::{MAX_FOOTPRINT, Mapping};
use texplore::math::{Ray, Rgb, Vec3A};
use texplore::render::render_blocking;
use texplore::scene::{
    AssetCache, Overrides, SceneDesc, build_scene, list_presets, load_preset, parse_preset,
};
use texplore::texture::{Filter, Lookup, Wrap};

/// Points where mappings are singular or numbers are extreme.
fn adversarial_points() -> Vec<Vec3A> {
    let one_up = f32::from_bits(1.0f32.to_bits() + 1);
    let one_down = f32::from_bits(1.0f32.to_bits() - 1);
    let tiny = f32::from_bits(1); // smallest subnormal
    let mut v = vec![
        Vec3A::new(0.0, 1.0, 0.0),
        Vec3A::new(0.0, -1.0, 0.0),
        Vec3A::new(-0.0, 1.0, -0.0),
        Vec3A::new(-0.0, -1.0, 0.0),
        Vec3A::new(0.0, 0.0, 1.0),
        Vec3A::new(0.0, 0.0, -1.0),
        Vec3A::new(-0.0, -0.0, -1.0),
        Vec3A::new(0.0, 0.0, 0.0),
        Vec3A::new(-0.0, -0.0, -0.0),
        Vec3A::new(0.0, one_up, 0.0),
        Vec3A::new(0.0, -one_up, 0.0),
        Vec3A::new(0.0, one_down, 0.0),
        Vec3A::new(0.0, 0.0, one_up),
        Vec3A::new(0.0, 0.0, -one_up),
        Vec3A::new(tiny, 0.0, 1.0),
        Vec3A::new(-tiny, 0.0, 1.0),
        Vec3A::new(-1e-7, 0.3, 0.95),
        Vec3A::new(1e-7, 0.3, 0.95),
        Vec3A::new(tiny, one_up, -tiny),
        Vec3A::new(1e30, 1e30, -1e30),
        Vec3A::new(3.4e38, -3.4e38, 3.4e38),
        Vec3A::new(tiny, tiny, tiny),
        Vec3A::new(1e-40, -2e-40, 3e-41),
        Vec3A::new(1.0 + 1e-6, 0.0, 0.0),
        Vec3A::new(0.0, 1e-3, 1.0 - 1e-6),
    ];
    // The seam from both sides at every latitude.
    for y in [-0.999, -0.5, 0.0, 0.5, 0.999] {
        let r = (1.0f32 - y * y).sqrt();
        v.push(Vec3A::new(-tiny, y, r));
        v.push(Vec3A::new(tiny, y, r));
        v.push(Vec3A::new(-1e-6, y, r));
    }
    v
}

fn check_mapping_at(m: Mapping, p: Vec3A) -> Result<(), String> {
    let dpdx = Vec3A::new(1e-3, -2e-3, 5e-4);
    let dpdy = Vec3A::new(-1e-3, 1e-3, 2e-3);
    let tc = m.map_with_differentials(p, dpdx, dpdy, None, Mapping::Spherical);
    if !(tc.uv.is_finite() && tc.duvdx.is_finite() && tc.duvdy.is_finite()) {
        return Err(format!("{m} at {p:?}: non-finite {tc:?}"));
    }
    if tc.duvdx.abs().max_element() > MAX_FOOTPRINT || tc.duvdy.abs().max_element() > MAX_FOOTPRINT
    {
        return Err(format!("{m} at {p:?}: unbounded footprint {tc:?}"));
    }
    // The rectangular map is unbounded by design (the wrap mode brings it into [0, 1]).
    let uv = if m == Mapping::Rectangular {
        let w = |t: f32| Wrap::Repeat.coord(t).unwrap();
        texplore::math::Vec2::new(w(tc.uv.x), w(tc.uv.y))
    } else {
        tc.uv
    };
    if !((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y)) {
        return Err(format!("{m} at {p:?}: (u, v) = {uv:?} outside [0, 1]"));
    }
    for (w, h) in [(1, 1), (1, 7), (2048, 1024), (3, 5), (65_535, 3)] {
        for &lookup in Lookup::VARIANTS {
            let (c, r) = (lookup.index(uv.x, w), lookup.index(uv.y, h));
            if c >= w || r >= h {
                return Err(format!("{m} at {p:?}: texel ({c}, {r}) outside {w}x{h}"));
            }
        }
    }
    Ok(())
}

#[test]
fn every_mapping_is_defined_at_every_adversarial_point() {
    for &m in Mapping::VARIANTS {
        for p in adversarial_points() {
            check_mapping_at(m, p).unwrap();
            check_mapping_at(m, -p).unwrap();
            check_mapping_at(m, Vec3A::new(p.z, p.x, p.y)).unwrap();
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Any finite point, of any magnitude and sign, near or far from the unit surface.
    #[test]
    fn mappings_never_produce_nan_or_out_of_range(
        x in prop::num::f32::NORMAL | prop::num::f32::SUBNORMAL | prop::num::f32::ZERO,
        y in prop::num::f32::NORMAL | prop::num::f32::SUBNORMAL | prop::num::f32::ZERO,
        z in prop::num::f32::NORMAL | prop::num::f32::SUBNORMAL | prop::num::f32::ZERO,
    ) {
        for &m in Mapping::VARIANTS {
            check_mapping_at(m, Vec3A::new(x, y, z)).map_err(TestCaseError::fail)?;
        }
    }

    /// Points on the unit sphere (where the lecture's formulas live), including the poles.
    #[test]
    fn mappings_on_the_unit_sphere(theta in 0.0f32..=std::f32::consts::PI, phi in -7.0f32..7.0) {
        let p = Vec3A::new(theta.sin() * phi.sin(), theta.cos(), theta.sin() * phi.cos());
        for &m in Mapping::VARIANTS {
            check_mapping_at(m, p).map_err(TestCaseError::fail)?;
        }
    }
}

fn scene_from(text: &str) -> texplore::scene::Scene {
    let desc = parse_preset(text, Path::new("hard.ron")).unwrap();
    build_scene(&desc, Path::new("hard.ron"), &mut AssetCache::new()).unwrap()
}

/// A 1e6 sphere seen from inside (the light probe's environment) and from 1e4 away: every ray
/// hits, hit points lie on the sphere within 1e-5 relative error.
#[test]
fn huge_sphere_from_inside_and_from_outside() {
    let scene = scene_from(
        "(version: 1, camera: (eye: (0, 0, 0), look_at: (0, 0, -1)), objects: [(shape: Sphere, transform: (scale: (1e6, 1e6, 1e6)), material: Emissive(ce: Constant((1, 1, 1))))])",
    );
    let mut rng = texplore::math::SampleRng::new(9, 0, 0);
    for _ in 0..20_000 {
        let d = Vec3A::new(
            rng.next_f32() - 0.5,
            rng.next_f32() - 0.5,
            rng.next_f32() - 0.5,
        );
        let Some(d) = d.try_normalize() else { continue };
        // From inside, near the centre and off-centre.
        for origin in [
            Vec3A::ZERO,
            Vec3A::new(3.0, -2.0, 1.0),
            Vec3A::new(1e5, 0.0, -2e5),
        ] {
            let hit = scene
                .hit(&Ray::new(origin, d))
                .expect("a ray from inside always hits");
            let r = f64::from(hit.p.length());
            assert!((r - 1e6).abs() / 1e6 < 1e-5, "from {origin:?}: |p| = {r}");
        }
    }
    // From 1e4 outside the surface, rays toward the sphere: hit the near side.
    let eye = Vec3A::new(0.0, 0.0, 1e6 + 1e4);
    for i in 0..2000 {
        let a = (i as f32 / 2000.0 - 0.5) * 2.0; // across the visible disc
        let target = Vec3A::new(a * 9e5, 0.3 * a * 4e5, 0.0);
        let ray = Ray::new(eye, target - eye);
        if let Some(hit) = scene.hit(&ray) {
            let r = f64::from(hit.p.length());
            assert!((r - 1e6).abs() / 1e6 < 1e-5, "|p| = {r}");
            assert!(hit.p.z > 0.0, "hit the far side: {:?}", hit.p);
        } else {
            panic!("ray {i} toward the sphere missed");
        }
    }
}

/// A render from inside the huge emissive sphere has no holes (every pixel hit, no black ring)
/// and no NaN.
#[test]
fn huge_environment_sphere_renders_without_holes() {
    let scene = scene_from(
        "(version: 1, camera: (eye: (0.5, 0.1, 0.2), look_at: (0, 0, -1), projection: Spherical(h_fov: 360, v_fov: 180)), render: (width: 128, height: 64, spp: 1), objects: [(shape: Sphere, transform: (scale: (1e6, 1e6, 1e6)), material: Emissive(ce: Checker(mapping: Spherical, squares: (16, 8), colors: ((1, 0.5, 0.2), (0.2, 0.5, 1)))))])",
    );
    let film = render_blocking(&scene, |_| {});
    assert!(film.is_finite());
    assert!(
        film.to_linear().iter().all(|c| c.max_channel() > 0.15),
        "a pixel missed the environment"
    );
}

/// Grazing rays: tangent to the sphere, along the plane, along the cylinder wall. Hits or
/// misses, but never NaN, and hits lie on the surface.
#[test]
fn grazing_rays_are_clean() {
    let scene = scene_from(
        "(version: 1, camera: (eye: (0, 0, 5)), objects: [
            (shape: Sphere, material: Matte(cd: Constant((1, 1, 1)))),
            (shape: Plane, transform: (translate: (0, -1, 0)), material: Matte(cd: Constant((1, 1, 1)))),
            (shape: Cylinder(capped: true), transform: (translate: (4, 0, 0)), material: Matte(cd: Constant((1, 1, 1)))),
        ])",
    );
    let mut rng = texplore::math::SampleRng::new(3, 0, 0);
    for _ in 0..20_000 {
        let e = (rng.next_f32() - 0.5) * 1e-4;
        let rays = [
            // Tangent to the unit sphere at x = 1.
            Ray::new(
                Vec3A::new(1.0 + e, rng.next_f32() * 0.01, 5.0),
                Vec3A::new(0.0, 0.0, -1.0),
            ),
            // Along the plane y = -1, slightly above or below.
            Ray::new(
                Vec3A::new(-5.0, -1.0 + e, rng.next_f32()),
                Vec3A::new(1.0, e * 1e-3, 0.1),
            ),
            // Along the cylinder wall x = 5 (cylinder centred at x = 4).
            Ray::new(Vec3A::new(5.0 + e, -3.0, 0.0), Vec3A::new(0.0, 1.0, e)),
        ];
        for ray in rays {
            if let Some(hit) = scene.hit(&ray) {
                assert!(
                    hit.p.is_finite() && hit.ng.is_finite() && hit.ns.is_finite(),
                    "{ray:?} -> {hit:?}"
                );
                let c = scene.trace(&ray, None);
                assert!(c.is_finite());
            }
        }
    }
}

fn render_preset_text(text: &str, scale: f32) -> Vec<Rgb> {
    // Scale every coordinate of the scene (camera, objects, lights) by `scale`.
    let mut desc: SceneDesc = parse_preset(text, Path::new("s.ron")).unwrap();
    desc.camera.eye *= scale;
    desc.camera.look_at *= scale;
    for o in &mut desc.objects {
        o.transform.translate *= scale;
        o.transform.scale *= scale;
    }
    for l in &mut desc.lights {
        if let texplore::scene::LightDesc::Point { position, .. } = l {
            *position *= scale;
        }
    }
    let scene = build_scene(&desc, Path::new("s.ron"), &mut AssetCache::new()).unwrap();
    render_blocking(&scene, |_| {}).to_linear()
}

const SHADOWED_SCENE: &str = "(version: 1,
    camera: (eye: (0, 2.5, 6), look_at: (0, 0.5, 0), projection: Pinhole(fov: 45)),
    render: (width: 96, height: 72, spp: 2),
    ambient: (ls: 0.2),
    lights: [Directional(direction: (0.4, 1, 0.3), ls: 2), Point(position: (-2, 3, 2), ls: 1)],
    objects: [
        (shape: Plane, material: Matte(cd: Checker(mapping: Rectangular, squares: (2, 2)))),
        (shape: Sphere, transform: (translate: (0, 1, 0)), material: Phong(cd: Checker(mapping: Spherical, squares: (8, 4)))),
        (shape: Cylinder(capped: true), transform: (translate: (1.8, 0.5, -0.5), scale: (0.4, 0.5, 0.4)), material: Matte(cd: Constant((0.8, 0.6, 0.3)))),
    ])";

/// The same scene scaled by 1e-3 and 1e3 renders the same (within a small tolerance): the
/// shadow offset and the intersection tolerances scale with the scene.
#[test]
fn scaled_scenes_render_the_same() {
    let base = render_preset_text(SHADOWED_SCENE, 1.0);
    for s in [1e-3, 1e3] {
        let scaled = render_preset_text(SHADOWED_SCENE, s);
        let differing = base
            .iter()
            .zip(&scaled)
            .filter(|(a, b)| (a.0 - b.0).abs() + (a.1 - b.1).abs() + (a.2 - b.2).abs() > 0.02)
            .count();
        assert!(
            differing <= base.len() / 200,
            "scale {s}: {differing} of {} pixels differ",
            base.len()
        );
    }
}

/// No shadow acne: with nothing between a surface and its lights, turning shadows on changes
/// nothing. A scene of single convex objects, one at a time, checked pixel by pixel.
#[test]
fn no_shadow_acne_on_lit_spheres_planes_and_cylinders() {
    for shape in [
        "Sphere",
        "Plane",
        "Cylinder(capped: true)",
        "Rectangle",
        "Disk",
    ] {
        for scale in [1e-3, 1.0, 1e3] {
            let text = |shadows: bool| {
                format!(
                    "(version: 1, camera: (eye: (0.3, 3, 4), look_at: (0, 0, 0), projection: Pinhole(fov: 50)), render: (width: 64, height: 48, spp: 1),
                     lights: [Directional(direction: (0.3, 1, 0.5), ls: 2, shadows: {shadows}), Directional(direction: (-1, 0.2, 0.1), ls: 1, shadows: {shadows})],
                     objects: [(shape: {shape}, transform: (rotate: (10, 20, 0)), material: Matte(cd: Constant((1, 1, 1))))])"
                )
            };
            let lit = render_preset_text(&text(false), scale);
            let shadowed = render_preset_text(&text(true), scale);
            for (i, (a, b)) in lit.iter().zip(&shadowed).enumerate() {
                // A convex object cannot shadow itself where the light reaches it: the pixels
                // must be identical (a speckle here is acne).
                if shape == "Cylinder(capped: true)" {
                    assert!(
                        (a.0 - b.0).abs() < 1e-6,
                        "{shape} x{scale}: acne at pixel {i}: {a:?} vs {b:?}"
                    );
                } else {
                    assert!(
                        a == b,
                        "{shape} x{scale}: acne at pixel {i}: {a:?} vs {b:?}"
                    );
                }
            }
        }
    }
}

/// HDR texels far above 1 shade to finite values; exposure brings them into range.
#[test]
fn hdr_values_far_above_one() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bright.hdr");
    let img = image::Rgb32FImage::from_fn(8, 4, |x, _| {
        image::Rgb([1e4 * (x as f32 + 1.0), 1.0, 65_000.0])
    });
    image::DynamicImage::ImageRgb32F(img).save(&p).unwrap();
    let text = format!(
        "(version: 1, camera: (eye: (0, 0, 3)), render: (width: 32, height: 32, spp: 2, exposure: -16), objects: [(shape: Sphere, material: Emissive(ce: Image(path: \"{}\", filter: Bilinear)))])",
        p.display()
    );
    let desc = parse_preset(&text, Path::new("/h.ron")).unwrap();
    let scene = build_scene(&desc, Path::new("/h.ron"), &mut AssetCache::new()).unwrap();
    let film = render_blocking(&scene, |_| {});
    assert!(film.is_finite());
    let display = film.to_display(scene.settings.exposure_scale);
    assert!(
        display.rgba.chunks(4).any(|p| p[0] > 0 && p[0] < 255),
        "exposure did not bring HDR values into range"
    );
}

/// No NaN or Inf reaches the film: every preset, in every filter and every sampler.
#[test]
fn every_preset_in_every_mode_renders_finite() {
    let presets = list_presets(&root().join("presets")).unwrap();
    let mut cache = AssetCache::new();
    for p in &presets {
        let desc = load_preset(p).unwrap();
        for &filter in Filter::VARIANTS {
            for &sampler in texplore::sampler::PixelSampler::VARIANTS {
                let o = Overrides {
                    filter: Some(filter),
                    sampler: Some(sampler),
                    ..sized(24, 16, 2)
                };
                let scene = build_with(&desc, p, o, &mut cache);
                let film = render_blocking(&scene, |_| {});
                assert!(film.is_finite(), "{} with {filter}/{sampler}", p.display());
            }
        }
    }
}

/// Renders an emissive sphere textured with `img` (saved as PNG) under every filter and wrap
/// mode; returns (filter, wrap, linear pixels) with the background black.
fn render_image_sphere(img: &image::RgbImage, mapping: &str) -> Vec<(Filter, Wrap, Vec<Rgb>)> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.png");
    img.save(&path).unwrap();
    let mut out = Vec::new();
    let mut cache = AssetCache::new();
    for &wrap in Wrap::VARIANTS {
        let text = format!(
            "(version: 1, camera: (eye: (0.3, 0.6, 3)), render: (width: 40, height: 30, spp: 1),
              objects: [(shape: Sphere, transform: (scale: (1, 1, 1)), material: Emissive(ce: Image(path: \"t.png\", mapping: {mapping}, wrap: {wrap:?})))])"
        );
        let preset = dir.path().join("p.ron");
        let desc = parse_preset(&text, &preset).unwrap();
        for &filter in Filter::VARIANTS {
            let scene = build_with(&desc, &preset, filtered(filter), &mut cache);
            let film = render_blocking(&scene, |_| {});
            assert!(film.is_finite(), "{filter}/{wrap}");
            out.push((filter, wrap, film.to_linear()));
        }
    }
    out
}

/// A 1x1 texture is one colour everywhere, under every filter and every wrap that stays inside
/// the image (Black may fade toward the border, where filters reach outside).
#[test]
fn one_by_one_texture_is_its_colour_under_every_filter() {
    let img = image::RgbImage::from_pixel(1, 1, image::Rgb([200, 100, 50]));
    let want = Rgb(
        texplore::math::srgb8_to_linear(200),
        texplore::math::srgb8_to_linear(100),
        texplore::math::srgb8_to_linear(50),
    );
    for mapping in ["Spherical", "Rectangular", "LightProbe"] {
        for (filter, wrap, pixels) in render_image_sphere(&img, mapping) {
            let hit: Vec<&Rgb> = pixels.iter().filter(|c| c.max_channel() > 0.0).collect();
            assert!(
                hit.len() > 200,
                "{mapping} {filter}/{wrap}: sphere not seen"
            );
            if wrap == Wrap::Black {
                assert!(
                    hit.iter().all(|c| c.0 <= want.0 + 1e-5),
                    "{mapping} {filter}/{wrap}: brighter than the texel"
                );
                continue;
            }
            for c in hit {
                let d = (c.0 - want.0)
                    .abs()
                    .max((c.1 - want.1).abs())
                    .max((c.2 - want.2).abs());
                assert!(d < 1e-4, "{mapping} {filter}/{wrap}: {c:?} != {want:?}");
            }
        }
    }
}

/// 1xN, Nx1 and odd non-power-of-two sizes: every filter and wrap stays finite, inside the
/// texels' range (up to a bicubic's overshoot) and sees both ends of a ramp.
#[test]
fn thin_and_odd_sized_textures_under_every_filter() {
    for (w, h) in [(1, 7), (9, 1), (3, 5), (257, 3)] {
        let img = image::RgbImage::from_fn(w, h, |x, y| {
            let t = (x + y) as f32 / (w + h - 2).max(1) as f32;
            image::Rgb([(255.0 * t) as u8, 40, (255.0 * (1.0 - t)) as u8])
        });
        for (filter, wrap, pixels) in render_image_sphere(&img, "Spherical") {
            let reds: Vec<f32> = pixels.iter().filter(|c| c.1 > 0.0).map(|c| c.0).collect();
            assert!(reds.len() > 200, "{w}x{h} {filter}/{wrap}");
            let (lo, hi) = reds
                .iter()
                .fold((f32::MAX, f32::MIN), |(a, b), &r| (a.min(r), b.max(r)));
            assert!(
                lo >= -0.05 && hi <= 1.1,
                "{w}x{h} {filter}/{wrap}: red in [{lo}, {hi}]"
            );
            if wrap != Wrap::Black {
                assert!(
                    hi - lo > 0.3,
                    "{w}x{h} {filter}/{wrap}: the ramp is not visible ({lo}..{hi})"
                );
            }
        }
    }
}

/// OBJ face indices that point at nothing are refused with the file and the line, before the
/// OBJ library indexes its arrays with them (a huge index once overflowed inside `tobj`).
#[test]
fn obj_face_indices_out_of_range_name_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/9223372036854775807 2/1 3/1\n",
            "line 5",
            "texture coordinate",
        ),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "line 4", "vertex"),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
            "line 4",
            "start at 1",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//-2 2//1 3//1\n",
            "line 5",
            "normal",
        ),
    ];
    for (i, (text, line, what)) in cases.iter().enumerate() {
        let p = dir.path().join(format!("bad{i}.obj"));
        std::fs::write(&p, text).unwrap();
        let e = texplore::meshio::load_mesh(&p).unwrap_err().to_string();
        assert!(
            e.contains(&format!("bad{i}.obj")) && e.contains(line) && e.contains(what),
            "{e}"
        );
    }
    // Relative indices and indices of elements defined later in the file are fine.
    let p = dir.path().join("good.obj");
    std::fs::write(
        &p,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nf 1 2 4\nv 1 1 0\n",
    )
    .unwrap();
    let m = texplore::meshio::load_mesh(&p).unwrap();
    assert_eq!(m.triangles.len(), 2);
}

/// What `texplore mesh-info --json FILE` prints (the command must succeed).
fn mesh_info_json(file: &Path) -> serde_json::Value {
    parse_json(&texplore(&[
        "mesh-info",
        "--json",
        file.to_str().expect("a UTF-8 temporary path"),
    ]))
}

/// Degenerate triangles: collinear corners, a repeated corner, corners at one point, and
/// zero (u, v) area. They load, `mesh-info` counts them, and a render of them under every
/// filter (the footprint of a zero-UV-area triangle has no derivatives) stays finite.
#[test]
fn degenerate_triangles_load_count_and_render_finite() {
    let dir = tempfile::tempdir().unwrap();
    let ply = dir.path().join("degenerate.ply");
    std::fs::write(
        &ply,
        "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement face 5\nproperty list uchar int vertex_indices\nend_header\n\
         -1 0 -1 0 0\n1 0 -1 1 0\n1 0 1 1 1\n0 0 0 0.5 0.5\n2 0 2 1 1\n-1 0 1 0.3 0.3\n-1 0 1 0.3 0.3\n\
         3 0 1 2\n3 0 3 4\n3 0 0 1\n3 5 6 5\n3 1 2 5\n",
    )
    .unwrap();
    // Faces: a good one; collinear (0, 3, 4); a repeated corner; all corners at one point
    // (5, 6 duplicate vertices); and (1, 2, 5), of positive area and positive (u, v) area.
    let v = mesh_info_json(&ply);
    assert_eq!(v["triangles"], 5);
    assert_eq!(v["degenerate"], 3, "{v}");
    // A triangle whose (u, v) are collinear: add one by giving three corners the same (u, v).
    let flat_uv = dir.path().join("flat_uv.ply");
    std::fs::write(
        &flat_uv,
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n-1 0 -1 0.5 0.5\n1 0 -1 0.5 0.5\n0 0 1 0.5 0.5\n3 0 1 2\n",
    )
    .unwrap();
    let v = mesh_info_json(&flat_uv);
    assert_eq!(
        (v["degenerate"].as_u64(), v["degenerate_uv"].as_u64()),
        (Some(0), Some(1)),
        "{v}"
    );
    // Both render finite under every filter, seen from above through the UV grid.
    for (file, lit) in [("degenerate.ply", 1), ("flat_uv.ply", 1)] {
        for &filter in Filter::VARIANTS {
            let text = format!(
                "(version: 1, camera: (eye: (0.1, 4, 0.2), look_at: (0, 0, 0)), render: (width: 32, height: 32, spp: 2),
                  lights: [Directional(direction: (0.2, 1, 0.1), ls: 1, shadows: true)],
                  objects: [(shape: Mesh(path: \"{file}\"), material: Matte(cd: UvGrid(mapping: Uv)))])"
            );
            let preset = dir.path().join("m.ron");
            let desc = parse_preset(&text, &preset).unwrap();
            let scene = build_with(&desc, &preset, filtered(filter), &mut AssetCache::new());
            let film = render_blocking(&scene, |_| {});
            assert!(film.is_finite(), "{file} {filter}");
            let seen = film
                .to_linear()
                .iter()
                .filter(|c| c.max_channel() > 0.0)
                .count();
            assert!(seen >= lit, "{file} {filter}: nothing rendered");
        }
    }
}
