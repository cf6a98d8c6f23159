//! The render kernel at its dispatched width (`--simd auto`: 16 rays a packet on AVX-512)
//! against its width-1 instance (`--simd scalar`): the same code, so every preset's film is the
//! same bit for bit, edge keys included, and renders stay deterministic for any thread count.

use std::path::{Path, PathBuf};
use texplore::render::{
    Film, SimdMode, kernel_width, render_blocking_with, render_pass_with, simd_level, thread_pool,
};
use texplore::sampler::PixelSampler;
use texplore::scene::{
    AdaptiveDesc, AssetCache, Scene, build_scene, list_presets, load_preset, parse_preset,
};
use texplore::snapshot::{MAX_BAD_FRACTION, MAX_MEAN_DIFF, compare};

fn presets() -> Vec<PathBuf> {
    list_presets(&Path::new(env!("CARGO_MANIFEST_DIR")).join("presets")).expect("presets/")
}

/// Adaptive sampling up to 6 samples: the film then also keeps edge keys and statistics.
const ADAPTIVE: AdaptiveDesc = AdaptiveDesc {
    max_spp: 6,
    threshold: 0.01,
};

/// A preset built at `width` x `height` and `spp`, adaptive up to 6 samples (2 past `spp`
/// when that is more).
fn scene_of(path: &Path, width: u32, height: u32, spp: u32, cache: &mut AssetCache) -> Scene {
    let mut desc = load_preset(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    desc.render.width = width;
    desc.render.height = height;
    desc.render.spp = spp;
    desc.render.adaptive = Some(AdaptiveDesc {
        max_spp: ADAPTIVE.max_spp.max(spp + 2),
        ..ADAPTIVE
    });
    build_scene(&desc, path, cache).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn render(scene: &Scene, mode: SimdMode, threads: usize) -> Film {
    thread_pool(threads)
        .expect("a pool")
        .install(|| render_blocking_with(scene, mode, |_| {}))
}

fn rgb8(scene: &Scene, film: &Film) -> Vec<u8> {
    film.to_display(scene.settings.exposure_scale).rgb()
}

/// Renders `scene` both ways and asserts the images agree within the snapshot tolerance;
/// returns the largest channel difference.
fn assert_paths_agree(name: &str, scene: &Scene) -> u8 {
    let packet = render(scene, SimdMode::Auto, 2);
    let scalar = render(scene, SimdMode::Scalar, 2);
    let c = compare(&rgb8(scene, &packet), &rgb8(scene, &scalar));
    assert!(
        c.passes(),
        "{name}: packet and scalar renders differ beyond the snapshot tolerance: {} of pixels \
         (at most {MAX_BAD_FRACTION}), mean {} (at most {MAX_MEAN_DIFF}), max {}",
        c.bad_fraction,
        c.mean_diff,
        c.max_diff
    );
    // The sample counts and edge keys (what adaptive sampling reads) agree too.
    assert_eq!(packet.keys(), scalar.keys(), "{name}: edge keys");
    c.max_diff
}

#[test]
fn every_preset_renders_the_same_at_every_width() {
    let mut cache = AssetCache::new();
    for path in presets() {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        // Small; 4 spp and adaptive passes exercise the sampler's two sets, and a width that
        // is not a multiple of the packet's.
        let scene = scene_of(&path, 51, 36, 4, &mut cache);
        assert_films_identical(&name, &scene, 6);
        assert_paths_agree(&name, &scene);
    }
}

#[test]
fn the_peer_scene_at_16_spp_renders_the_same_on_both_paths() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/peer-sphere.ron");
    let scene = scene_of(&path, 64, 48, 16, &mut AssetCache::new());
    let max = assert_paths_agree("peer-sphere", &scene);
    assert!(max <= 2, "largest channel difference {max}");
}

#[test]
fn the_kernel_width_is_reported() {
    assert_eq!(kernel_width(SimdMode::Scalar), 1);
    let w = kernel_width(SimdMode::Auto);
    assert!([1, 4, 8, 16].contains(&w), "{w} rays a packet");
    assert!(simd_level(SimdMode::Auto).ends_with(&format!("{w} rays a packet")));
    assert!(simd_level(SimdMode::Scalar).contains("1 ray a packet"));
}

#[test]
fn packet_renders_are_the_same_for_1_and_2_threads() {
    // The Earth, the checker plane under EWA and the peer sphere under the footprint filter
    // (whose summed-area table the first lookup builds, on whichever thread comes first).
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    let mut cache = AssetCache::new();
    let mut scenes: Vec<(String, Scene)> = ["earth", "checker-plane"]
        .iter()
        .map(|n| {
            let path = dir.join(format!("{n}.ron"));
            ((*n).to_owned(), scene_of(&path, 64, 48, 2, &mut cache))
        })
        .collect();
    let peer = std::fs::read_to_string(dir.join("peer-sphere.ron"))
        .expect("preset")
        .replace("filter: Bilinear", "filter: Footprint");
    let path = dir.join("peer-sphere.ron");
    let mut desc = parse_preset(&peer, &path).expect("the peer scene");
    (desc.render.width, desc.render.height, desc.render.spp) = (64, 48, 2);
    desc.render.adaptive = Some(ADAPTIVE);
    let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("builds");
    scenes.push(("peer-sphere footprint".to_owned(), scene));
    for (name, scene) in &scenes {
        let one = render(scene, SimdMode::Auto, 1);
        let two = render(scene, SimdMode::Auto, 2);
        assert!(one == two, "{name}: the film depends on the thread count");
    }
}

/// A scene whose packets mix hits of a sphere, hits of a mirror (a nested masked packet), and
/// misses; with every material term the kernel shades
/// (Matte's ka, kd and cd; Phong's ks, cs, exp and a constant glow ce; Emissive's ls and ce)
/// and every light kind with and without shadows (a directional light, a shadowing point light
/// across objects, a point light without shadows), a rotated and scaled plane under a (u, v)
/// transform, and a disk and rectangle.
#[test]
fn packets_with_hits_mirrors_and_misses_match_the_width_one_kernel() {
    let text = r"(
        version: 1,
        camera: (eye: (0.3, 1.2, 5), look_at: (0, 0, 0), projection: Pinhole(fov: 50)),
        render: (width: 61, height: 45, spp: 2, background: (0.1, 0.2, 0.3)),
        ambient: (ls: 0.25),
        lights: [
            Directional(direction: (1, 2, 1), ls: 2.0),
            Point(position: (-2, 3, 2), ls: 1.5, shadows: true),
            Point(position: (2.5, 0.5, 3), ls: 0.7, shadows: false),
            Directional(direction: (-1, 0.5, 2), ls: 0.4, shadows: false),
        ],
        objects: [
            (shape: Sphere, transform: (translate: (-0.8, 0, 0), scale: (0.7, 0.7, 0.7)),
             material: Phong(ka: 0.8, kd: 0.7, cd: Checker(mapping: Spherical), ks: 0.5,
                             cs: Constant((1, 0.8, 0.6)), exp: 20, ce: Constant((0.3, 0.1, 0.05)))),
            (shape: Sphere, transform: (translate: (0.9, 0.1, 0), scale: (0.6, 0.6, 0.6)),
             material: Reflective(cd: Constant((0.2, 0.2, 0.2)), kr: 0.8)),
            (shape: Plane, transform: (translate: (0, -0.8, 0), rotate: (0, 25, 0)),
             material: Matte(ka: 0.6, kd: 0.9, cd: Checker(mapping: Rectangular, uv: (scale: (4, 3), rotate: 30, offset: (0.25, 0))))),
            (shape: Disk, transform: (translate: (0, 0.2, -1.5), rotate: (80, 0, 0)),
             material: Emissive(ce: Constant((1, 0.5, 0.2)), ls: 1.5)),
            (shape: Rectangle, transform: (translate: (1.5, 0.5, -1), scale: (0.4, 1, 0.4), rotate: (70, -20, 0)),
             material: Matte(cd: UvGrid(mapping: Uv, filter: Bilinear))),
        ],
    )";
    let mut desc = parse_preset(text, Path::new("mixed.ron")).expect("the test scene parses");
    desc.render.adaptive = Some(ADAPTIVE);
    let scene = build_scene(&desc, Path::new("mixed.ron"), &mut AssetCache::new())
        .expect("the test scene builds");
    let packet = render(&scene, SimdMode::Auto, 2);
    let scalar = render(&scene, SimdMode::Scalar, 2);
    // The lanes follow the scalar formulas operation for operation: the films are identical.
    let (a, b) = (packet.pixels(), scalar.pixels());
    let worst = a
        .iter()
        .zip(b)
        .enumerate()
        .map(|(i, (p, q))| {
            let d = (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0_f32, f32::max);
            (d, i)
        })
        .fold((0.0_f32, 0), |m, x| if x.0 > m.0 { x } else { m });
    assert!(
        worst.0 <= 1e-5,
        "pixel ({}, {}) differs by {} (packet {:?}, scalar {:?})",
        worst.1 % 61,
        worst.1 / 61,
        worst.0,
        a[worst.1],
        b[worst.1]
    );
    assert_eq!(packet.keys(), scalar.keys());
    // The scene really mixes them: background, the mirror (scalar lanes) and shaded hits.
    let keys: std::collections::BTreeSet<u32> = scalar.keys().iter().map(|k| k & 0xffff).collect();
    assert!(
        keys.is_superset(&[0, 1, 2, 3].into()),
        "objects seen: {keys:?}"
    );
}

/// The films of passes `0..passes` on both paths, bit for bit: the lane-wise sampler (its
/// first set and, past `spp` without adaptive sampling, the one-sample second set) and the
/// lane-wise nearest lookup give the scalar numbers exactly.
fn assert_films_identical(name: &str, scene: &Scene, passes: u32) {
    let s = &scene.settings;
    let mut films = [SimdMode::Auto, SimdMode::Scalar].map(|mode| {
        let mut film = Film::new(s.width, s.height);
        for k in 0..passes {
            render_pass_with(scene, &mut film, k, None, mode, &|| false).expect("not cancelled");
        }
        film
    });
    let [packet, scalar] = &mut films;
    for (i, (p, q)) in packet.pixels().iter().zip(scalar.pixels()).enumerate() {
        assert!(
            p.map(f32::to_bits) == q.map(f32::to_bits),
            "{name}: pixel ({}, {}) is {p:?} in packets, {q:?} at width 1",
            i as u32 % s.width,
            i as u32 / s.width
        );
    }
}

#[test]
fn nearest_image_lookups_and_lane_samplers_are_bit_identical_to_the_scalar_path() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    let mut cache = AssetCache::new();
    // The Earth (sRGB texels, repeat in u, clamp in v), the four texels under the centred and
    // the lecture's lookup (clamp), the coffee rectangle (clamp), and an HDR image's linear
    // texels read nearest on a sphere, tiled past [0, 1] by a (u, v) transform (repeat).
    let mut cases: Vec<(String, String, PathBuf)> = ["earth", "texels", "rectangle"]
        .iter()
        .map(|n| {
            let path = dir.join(format!("{n}.ron"));
            let text = std::fs::read_to_string(&path).expect("preset");
            ((*n).to_owned(), text, path)
        })
        .collect();
    let texels = cases[1].1.replace("lookup: Centred", "lookup: Lecture");
    assert_ne!(texels, cases[1].1, "texels.ron names its lookup");
    cases.push(("texels-lecture".into(), texels, dir.join("texels.ron")));
    cases.push((
        "hdr-nearest".into(),
        r#"(
            version: 1,
            camera: (eye: (0, 0.4, 3.2), look_at: (0, 0, 0), projection: Pinhole(fov: 45)),
            render: (width: 64, height: 48, spp: 1),
            ambient: (ls: 0.5),
            lights: [Directional(direction: (1, 1, 1), ls: 2.0)],
            objects: [
                (shape: Sphere, material: Matte(cd: Image(path: "../assets/courtyard_probe.hdr",
                    mapping: Spherical, filter: Nearest, uv: (scale: (3, 2), offset: (-0.4, 0.3))))),
            ],
        )"#
        .into(),
        dir.join("hdr-nearest.ron"),
    ));
    for (name, text, path) in &cases {
        let mut desc = parse_preset(text, path).unwrap_or_else(|e| panic!("{name}: {e}"));
        desc.render.width = 67; // not a multiple of the packet width
        desc.render.height = 41;
        desc.render.adaptive = None;
        for sampler in [
            PixelSampler::Jittered,
            PixelSampler::Random,
            PixelSampler::Regular,
        ] {
            desc.render.sampler = sampler;
            desc.render.spp = 1;
            let scene = build_scene(&desc, path, &mut cache).unwrap_or_else(|e| panic!("{e}"));
            // Pass 0 from the first set, passes 1 and 2 from the second.
            assert_films_identical(&format!("{name} {sampler} 1 spp"), &scene, 3);
        }
        // More samples than the lane-wise sampler takes (jittered cells): per lane, the same.
        desc.render.sampler = PixelSampler::Jittered;
        desc.render.spp = 3;
        let scene = build_scene(&desc, path, &mut cache).unwrap_or_else(|e| panic!("{e}"));
        assert_films_identical(&format!("{name} jittered 3 spp"), &scene, 3);
    }
}

#[test]
fn footprint_filters_on_the_packet_path_are_bit_identical_to_the_scalar_path() {
    // Textures filtered over the pixel's footprint read it per lane from the lane's ray
    // differentials: the peer sphere under each footprint filter, a matte sphere turned and
    // scaled (object space differs from world space) and a tiled plane at a grazing angle,
    // at 1 spp (its second set per lane, non-square cells past it) and 4 spp.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    let mut cache = AssetCache::new();
    let peer = std::fs::read_to_string(dir.join("peer-sphere.ron")).expect("preset");
    let mut cases = Vec::new();
    for filter in ["Footprint", "Ewa", "Trilinear"] {
        let text = peer.replace("filter: Bilinear", &format!("filter: {filter}"));
        assert_ne!(text, peer, "peer-sphere.ron names its filter");
        cases.push((format!("peer-sphere {filter}"), text));
    }
    cases.push((
        "turned matte sphere and tiled plane".to_owned(),
        r#"(
            version: 1,
            camera: (eye: (0, 1.2, 4), look_at: (0, 0, 0), projection: Pinhole(fov: 50)),
            render: (width: 64, height: 48, spp: 1),
            ambient: (ls: 0.4),
            lights: [Point(position: (2, 3, 3), ls: 3.0, shadows: true)],
            objects: [
                (shape: Sphere, transform: (rotate: (20, 50, 0), scale: (0.8, 0.8, 0.8)),
                    material: Matte(cd: Image(path: "../assets/earth_2048x1024.jpg",
                        mapping: Spherical, filter: Footprint))),
                (shape: Plane, transform: (translate: (0, -1, 0)),
                    material: Matte(cd: Image(path: "../assets/checker_512.png",
                        mapping: Rectangular, filter: Footprint, wrap: Mirror,
                        uv: (scale: (6, 6), offset: (0.3, -0.2))))),
            ],
        )"#
        .to_owned(),
    ));
    for (name, text) in &cases {
        let path = dir.join("footprint-case.ron");
        let mut desc = parse_preset(text, &path).unwrap_or_else(|e| panic!("{name}: {e}"));
        desc.render.width = 67; // not a multiple of the packet width
        desc.render.height = 41;
        desc.render.adaptive = None;
        for (sampler, spp) in [
            (PixelSampler::Regular, 1),
            (PixelSampler::Jittered, 1),
            (PixelSampler::Regular, 4),
        ] {
            desc.render.sampler = sampler;
            desc.render.spp = spp;
            let scene = build_scene(&desc, &path, &mut cache).unwrap_or_else(|e| panic!("{e}"));
            assert_films_identical(&format!("{name} {sampler} {spp} spp"), &scene, spp + 2);
        }
        // Adaptive sampling reads the edge keys, whose bit 31 says "filtered over the footprint".
        desc.render.spp = 1;
        desc.render.adaptive = Some(ADAPTIVE);
        let scene = build_scene(&desc, &path, &mut cache).unwrap_or_else(|e| panic!("{e}"));
        assert_paths_agree(name, &scene);
    }
}
