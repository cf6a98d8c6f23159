//! The inspector against hand-worked values, the render and the presets.

use super::*;
use crate::scene::{AssetCache, SceneDesc, build_scene, load_preset};
use std::path::Path;

fn earth() -> (SceneDesc, std::path::PathBuf) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/earth.ron");
    let mut desc = load_preset(&path).expect("earth preset");
    desc.render.width = 64;
    desc.render.height = 48;
    (desc, path)
}

#[test]
fn inspecting_the_earth_centre_gives_the_spherical_map_and_both_texels() {
    let (desc, path) = earth();
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
    let i = scene
        .inspect(Vec2::new(32.0, 24.0))
        .expect("the Earth fills the centre");
    assert_eq!(i.mapping, Some(Mapping::Spherical));
    assert!((i.local_point.length() - 1.0).abs() < 1e-4);
    let tex = i.tex.expect("coordinates");
    let expect = Mapping::Spherical.map_point(i.local_point).uv;
    assert!((tex.uv - expect).length() < 1e-6);
    assert!(
        i.mapping_lines
            .iter()
            .any(|l| l.starts_with("theta = acos(y)"))
    );
    assert_eq!(i.texels.len(), 2);
    let read = i.image.as_ref().expect("image");
    let (w, h) = (read.image.width(), read.image.height());
    let centred = &i.texels[1];
    assert_eq!(centred.lookup, Lookup::Centred);
    assert_eq!(centred.column, ((tex.uv.x * w as f32) as u32).min(w - 1));
    assert_eq!(centred.file_row, h - 1 - centred.row_from_bottom);
    // 2048 texels around the Earth over ~40 pixels: tens of texels per pixel.
    let fp = i.footprint.expect("footprint");
    let (major, minor) = fp.axes_texels.expect("axes");
    assert!(major >= minor && minor > 1.0, "{major} {minor}");
    assert!(fp.mip_level.expect("mip") > 1.0);
    assert!(i.radiance.is_finite());
}

/// The inspection of every pixel centre of shipped preset `name` rendered at 80 x 60 (those
/// whose ray hits something).
fn every_pixel(name: &str) -> Vec<Inspection> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("presets/{name}.ron"));
    let mut desc = load_preset(&path).expect("preset");
    desc.render.width = 80;
    desc.render.height = 60;
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
    (0..60)
        .flat_map(|y| (0..80).map(move |x| Vec2::new(x as f32 + 0.5, y as f32 + 0.5)))
        .filter_map(|p| scene.inspect(p))
        .collect()
}

#[test]
fn over_a_hole_of_a_clip_map_the_inspector_reports_the_surface_behind_it() {
    let all = every_pixel("cutout");
    // Through a hole: the board is passed with alpha 0, and the floor is what shows, its
    // radiance the pixel's.
    let hole = all
        .iter()
        .find(|i| !i.passed.is_empty())
        .expect("a pixel over one of the board's holes");
    assert_eq!(hole.passed[0].object_name, "Board");
    assert_eq!(hole.passed[0].alpha, 0.0);
    assert_eq!(hole.object_name, "Floor");
    assert!(hole.alpha.is_none(), "the floor has no clip map");
    // On the board itself: solid, its alpha shown, nothing passed.
    let board = all
        .iter()
        .find(|i| i.object_name == "Board" && i.alpha == Some(1.0))
        .expect("a pixel on the board's solid part");
    assert!(board.passed.is_empty());
}

#[test]
fn a_mesh_hit_shows_its_vertices_uv_weights_and_the_interpolation() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/two-triangles.ron");
    let mut desc = load_preset(&path).expect("preset");
    desc.render.width = 80;
    desc.render.height = 60;
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
    let i = (20..60)
        .find_map(|x| scene.inspect(Vec2::new(x as f32 + 0.5, 30.5)))
        .expect("a triangle in the middle row");
    let m = i.mesh.as_ref().expect("a mesh hit");
    let uvs = m.uvs.expect("the PLY has (u, v)");
    assert!((m.bary.x + m.bary.y + m.bary.z - 1.0).abs() < 1e-5);
    assert!(m.bary.min_element() >= -1e-4, "{}", m.bary);
    let uv = uvs[0] * m.bary.x + uvs[1] * m.bary.y + uvs[2] * m.bary.z;
    let tex = i.tex.expect("coordinates");
    assert!((uv - tex.uv).length() < 1e-4, "{uv} {}", tex.uv);
    assert_eq!(m.lines.len(), 3);
    assert!(m.lines[1].starts_with("u = w0 u0 + w1 u1 + w2 u2 = "));
    assert!(
        m.lines[1].ends_with(&format!("= {}", explain_number(f64::from(uv.x)))),
        "{}",
        m.lines[1]
    );
}

#[test]
fn a_mesh_under_a_generated_mapping_shows_the_fit_into_the_unit_cube() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/two-triangles.ron");
    let mut desc = load_preset(&path).expect("preset");
    desc.render.width = 80;
    desc.render.height = 60;
    for o in &mut desc.objects {
        if let crate::scene::TextureDesc::Image { mapping, .. } = o.material.texture_mut() {
            *mapping = Mapping::Rectangular.into();
        }
    }
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
    let i = (20..60)
        .find_map(|x| scene.inspect(Vec2::new(x as f32 + 0.5, 30.5)))
        .expect("a hit");
    assert!(i.mapping_lines[0].starts_with("fit the model into [-1, 1]^3"));
    // The worked u is the u the texel comes from.
    let u = i.tex.expect("coordinates").uv.x;
    let line = i
        .mapping_lines
        .iter()
        .find(|l| l.starts_with("u = (z + 1) / 2"))
        .expect("the rectangular map's u");
    assert!(
        line.ends_with(&format!("= {}", explain_number(f64::from(u)))),
        "{line} but u = {u}"
    );
}

#[test]
fn under_a_debug_view_the_shaded_radiance_and_the_view_value_are_apart() {
    let (mut desc, path) = earth();
    desc.render.view = View::Uv;
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
    let i = scene.inspect(Vec2::new(32.0, 24.0)).expect("hit");
    let (view, value) = i.debug_value.expect("a debug value");
    assert_eq!(view, View::Uv);
    let w = i.wrapped_uv.expect("uv");
    // The uv view's red is u and green v (as displayed: sRGB-encoded); the radiance is the
    // lit Earth, not that.
    let lin = crate::math::srgb_to_linear;
    assert!((value.0 - lin(w.x)).abs() < 1e-3 && (value.1 - lin(w.y)).abs() < 1e-3);
    let (shaded_desc, _) = earth();
    let shaded = build_scene(&shaded_desc, &path, &mut AssetCache::new()).expect("build");
    let s = shaded.inspect(Vec2::new(32.0, 24.0)).expect("hit");
    assert!(s.debug_value.is_none());
    assert_eq!(i.radiance, s.radiance);
    assert_ne!(i.radiance, value);
}

#[test]
fn hints_name_a_3_2_photo_on_the_sphere_and_the_lecture_lookups_last_column() {
    let (mut desc, path) = earth();
    if let crate::scene::TextureDesc::Image {
        path: image,
        lookup,
        ..
    } = desc.objects[0].material.texture_mut()
    {
        "../assets/coffee_600x400.png".clone_into(image);
        *lookup = Lookup::Lecture;
    }
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
    let hints = mapping_hints(&scene, 0);
    assert_eq!(hints.len(), 2, "{hints:?}");
    assert!(
        hints[0].starts_with("this image is 3:2 (600 x 400)"),
        "{}",
        hints[0]
    );
    assert!(hints[0].ends_with("1.33 times too wide)"), "{}", hints[0]);
    assert!(
        hints[1].contains("reaches column 599 only at u = 1"),
        "{}",
        hints[1]
    );
    // The Earth as shipped: 2:1 and the centred lookup, nothing to say.
    let (desc, path) = earth();
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
    assert!(mapping_hints(&scene, 0).is_empty());
}

#[test]
fn the_diagram_angles_are_the_formulas_angles() {
    let p = Vec3A::new(0.5, 0.5_f32.sqrt(), -0.5);
    let a = mapping_angles(Mapping::Spherical, p);
    assert!((a.phi.unwrap() - 0.75 * std::f64::consts::PI).abs() < 1e-6);
    assert!((a.theta.unwrap() - std::f64::consts::FRAC_PI_4).abs() < 1e-6);
    let q = Vec3A::new(0.0, 1.0, 0.0);
    let probe = mapping_angles(Mapping::LightProbe, q);
    assert!((probe.alpha.unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-6);
    assert!((probe.beta.unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-6);
    assert!((probe.r.unwrap() - 0.5).abs() < 1e-6);
    let pano = mapping_angles(Mapping::Panoramic, Vec3A::new(0.0, 0.0, -1.0));
    assert!(pano.alpha.unwrap().abs() < 1e-6, "panoramic looks along -z");
    assert_eq!(
        mapping_angles(Mapping::Rectangular, p),
        MappingAngles::default()
    );
}

#[test]
fn missing_the_scene_inspects_nothing() {
    let (desc, path) = earth();
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
    assert!(scene.inspect(Vec2::new(0.5, 0.5)).is_none());
}

#[test]
fn a_bump_or_normal_map_shows_its_value_its_frame_and_the_tilted_normal() {
    let all = every_pixel("bumps");
    for kind in ["bump map", "normal map"] {
        let reads: Vec<&PerturbationRead> = all
            .iter()
            .filter_map(|i| i.perturbation.as_ref())
            .filter(|p| p.kind == kind)
            .collect();
        assert!(!reads.is_empty(), "a pixel on the {kind}");
        for p in &reads {
            assert!((p.shading.length() - 1.0).abs() < 1e-4, "{p:?}");
            assert!((p.geometric.length() - 1.0).abs() < 1e-4, "{p:?}");
            assert!((0.0..90.0).contains(&p.tilt_degrees), "{p:?}");
        }
        // Somewhere the map tilts the normal, in a (u, v) frame.
        let tilted = reads
            .iter()
            .find(|p| p.tilt_degrees > 1.0)
            .unwrap_or_else(|| panic!("the {kind} tilts the normal somewhere"));
        assert!(tilted.frame.is_some(), "{tilted:?}");
        let prefix = if kind == "bump map" {
            "height "
        } else {
            "texel ("
        };
        assert!(tilted.value.starts_with(prefix), "{}", tilted.value);
    }
}

/// The light-probe scene at 80 x 60 with reflection depth `depth`.
fn light_probe(depth: u32) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/light-probe.ron");
    let mut desc = load_preset(&path).expect("preset");
    desc.render.width = 80;
    desc.render.height = 60;
    desc.render.reflection_depth = depth;
    build_scene(&desc, &path, &mut AssetCache::new()).expect("build")
}

#[test]
fn at_a_mirror_the_inspector_follows_the_reflected_ray_to_the_texel_it_reads() {
    let scene = light_probe(4);
    let pixels =
        (0..60).flat_map(|y| (0..80).map(move |x| Vec2::new(x as f32 + 0.5, y as f32 + 0.5)));
    let on_mirror: Vec<Inspection> = pixels
        .filter_map(|p| scene.inspect(p))
        .filter(|i| i.object_name == "Mirror ball")
        .collect();
    assert!(
        on_mirror.len() > 50,
        "{} pixels on the mirror ball",
        on_mirror.len()
    );
    for i in &on_mirror {
        let m = i.mirror.as_ref().expect("the mirror ball mirrors");
        assert_eq!((m.depth, m.limit), (1, 4));
        assert!(m.followed());
        // r = 2 (n . v) n - v: the angle of incidence equals the angle of reflection.
        let cos_in = m.normal.dot(m.view);
        let cos_out = m.normal.dot(m.direction);
        assert!((cos_in - cos_out).abs() < 1e-4, "{cos_in} {cos_out}");
        assert!((m.direction - (2.0 * cos_in * m.normal - m.view)).length() < 1e-4);
        // kr 0.95, cr white, and no other term: the pixel is exactly what the mirror adds.
        assert!((m.weight.0 - 0.95).abs() < 1e-6);
        let added = m.added();
        assert!(
            (added.0 - i.radiance.0).abs() <= 1e-4 * (1.0 + i.radiance.0),
            "mirror adds {added:?}, pixel is {:?}",
            i.radiance
        );
        // The ray goes on to the environment or a ball, whose texel the inspector reads
        // through the mirrored differentials.
        let seen = m.seen.as_ref().expect("the room surrounds everything");
        if seen.texture_kind != "constant" {
            assert!(
                seen.tex.is_some() && seen.footprint.is_some(),
                "{}",
                seen.object_name
            );
        }
        assert!(m.lines.iter().any(|l| l.starts_with("r = 2 (n . v) n - v")));
    }
    // The convex mirror shrinks the room: a pixel's footprint in the probe is larger seen in
    // the mirror than seen directly.
    let direct = scene
        .inspect(Vec2::new(2.5, 2.5))
        .filter(|i| i.object_name == "Environment")
        .and_then(|i| i.footprint?.axes_texels)
        .expect("the room in the corner");
    let mirrored = on_mirror
        .iter()
        .filter_map(|i| i.mirror.as_ref()?.seen.as_ref())
        .filter(|s| s.object_name == "Environment")
        .filter_map(|s| s.footprint?.axes_texels)
        .map(|(a, _)| a)
        .fold(0.0_f32, f32::max);
    assert!(mirrored > 2.0 * direct.0, "{mirrored} vs {}", direct.0);
}

#[test]
fn past_the_reflection_depth_a_mirror_is_not_followed() {
    let scene = light_probe(0);
    let i = (0..60)
        .flat_map(|y| (0..80).map(move |x| Vec2::new(x as f32 + 0.5, y as f32 + 0.5)))
        .filter_map(|p| scene.inspect(p))
        .find(|i| i.object_name == "Mirror ball")
        .expect("the mirror ball is in view");
    let m = i.mirror.expect("still a mirror");
    assert_eq!((m.depth, m.limit), (1, 0));
    assert!(!m.followed());
    assert!(m.seen.is_none());
    assert_eq!(m.radiance, Rgb::BLACK);
    assert!(
        m.lines
            .iter()
            .any(|l| l.contains("past the reflection depth 0"))
    );
}

#[test]
fn a_mirror_seen_in_a_mirror_is_the_second_bounce() {
    let scene = light_probe(4);
    let second = (0..60)
        .flat_map(|y| (0..80).map(move |x| Vec2::new(x as f32 + 0.5, y as f32 + 0.5)))
        .filter_map(|p| scene.inspect(p))
        .find_map(|i| i.mirror?.seen?.mirror)
        .expect("a ball mirrors the other somewhere");
    assert_eq!(second.depth, 2);
    // A matte surface mirrors nothing.
    let matte = scene.inspect(Vec2::new(40.5, 30.5)).expect("the ball");
    assert_eq!(matte.object_name, "Ball");
    assert!(matte.mirror.is_none());
}

#[test]
fn under_the_difference_view_the_formula_is_worked_beside_the_builtin_mapping() {
    let (mut desc, path) = earth();
    desc.objects[0]
        .material
        .texture_mut()
        .set_mapping(crate::scene::MappingDesc::Formula {
            u: "fract(atan2(x, z) / tau)".into(),
            v: "acos(y) / pi".into(),
        });
    desc.render.view = View::Difference;
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
    // Above the Earth's centre, away from the equator where the flip changes nothing.
    let i = scene.inspect(Vec2::new(32.0, 12.0)).expect("hit");
    let lines = i.mapping_lines.join("\n");
    assert!(lines.contains("v = acos(y) / pi = acos("), "{lines}");
    assert!(
        lines.contains("compared with the spherical mapping:"),
        "{lines}"
    );
    assert!(lines.contains("  v = 1 - theta / pi = "), "{lines}");
    assert!(lines.contains(": beyond the tolerance"), "{lines}");
    assert_eq!(i.debug_value.map(|(v, _)| v), Some(View::Difference));
}

#[test]
fn a_hall_of_mirrors_is_followed_to_the_reflection_depth_and_no_further() {
    // Two mirror planes facing each other, the camera between them looking along them: every
    // ray bounces until the depth runs out.
    let text = r"(
        version: 1,
        camera: (eye: (0, 1, 0), look_at: (0, 0.2, -1), projection: Pinhole(fov: 30)),
        render: (width: 8, height: 6, spp: 1, reflection_depth: 64),
        objects: [
            (shape: Plane, material: Reflective(cd: Constant((0, 0, 0)), ka: 0, kd: 0, ks: 0, kr: 0.9)),
            (shape: Plane, transform: (translate: (0, 2, 0), rotate: (180, 0, 0)),
             material: Reflective(cd: Constant((0, 0, 0)), ka: 0, kd: 0, ks: 0, kr: 0.9)),
        ],
    )";
    let path = Path::new("/hall.ron");
    let desc = crate::scene::parse_preset(text, path).expect("parses");
    let scene = build_scene(&desc, path, &mut AssetCache::new()).expect("build");
    let i = scene.inspect(Vec2::new(4.0, 3.0)).expect("a mirror");
    let mut m = i.mirror.as_ref().expect("mirrors");
    let mut bounces = 1;
    while let Some(next) = m.seen.as_ref().and_then(|s| s.mirror.as_ref()) {
        assert_eq!(next.depth, m.depth + 1);
        m = next;
        bounces += 1;
    }
    // Bounces 1 to 64 are traced; the 65th mirror is met but not followed.
    assert_eq!(bounces, 65);
    assert_eq!(m.depth, 65);
    assert!(!m.followed());
    assert!(m.seen.is_none());
    // Mirrors all the way down and nothing else: the pixel is black, as the renderer makes it.
    assert_eq!(i.radiance, Rgb::BLACK);
    assert_eq!(
        scene.trace(
            &scene.camera.ray(Vec2::new(4.0, 3.0), 1.0).expect("ray").0,
            None
        ),
        Rgb::BLACK
    );
}
