//! Displacement maps on meshes (`displace: (height, scale, subdivide)`): a flat height changes
//! nothing, a constant one moves every vertex by exactly `scale * height` along its normal, the
//! subdivided and displaced surface stays watertight across UV seams, the silhouette differs
//! from the bump map's exactly where the heights are large, and bad presets are refused with the
//! file, the object and the field named.

use crate::common::{build_with, failure, filtered, render_on, root, sized, texplore_in};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use strum::VariantArray;
use texplore::geometry::displace::{MAX_DISPLACED_TRIANGLES, displace, subdivide};
use texplore::geometry::{Mesh, MeshData, Shape};
use texplore::math::{Ray, Rgb, Vec2, Vec3, Vec3A};
use texplore::meshio::{PlyFormat, bumpy_sphere, torus, write_ply};
use texplore::scene::{
    AssetCache, BumpDesc, Overrides, Scene, build_scene, load_preset, parse_preset,
};
use texplore::texture::{Filter, save_png};

fn write_mesh(dir: &Path, name: &str, data: &MeshData) -> PathBuf {
    let path = dir.join(name);
    let mut f = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
    write_ply(&mut f, data, PlyFormat::BinaryLittleEndian).unwrap();
    drop(f);
    path
}

/// A unit sphere whose normals point exactly away from its centre.
fn round_sphere() -> MeshData {
    let mut d = bumpy_sphere(24, 12, 0.0);
    d.normals = d.positions.iter().map(|p| p.normalize()).collect();
    d
}

/// A 32 x 1 grey ramp: black at u = 0, white at u = 1 (so the two sides of a u seam differ
/// most).
fn write_ramp(dir: &Path) -> PathBuf {
    let rgb: Vec<u8> = (0..32u32).flat_map(|i| [(i * 255 / 31) as u8; 3]).collect();
    let path = dir.join("ramp.png");
    save_png(&path, 32, 1, &rgb, &[]).unwrap();
    path
}

/// A preset with one mesh object seen from above (+y), lit from above.
fn preset(mesh: &Path, extra: &str, spp: u32) -> String {
    format!(
        "(version: 1, camera: (eye: (0, 6, 0.001), projection: Pinhole(fov: 36)),
          render: (width: 64, height: 64, spp: {spp}, sampler: Regular),
          ambient: (ls: 0.2), lights: [Directional(direction: (0.3, 1, 0.2))],
          objects: [(shape: Mesh(path: {:?}, shading: Smooth),
                     material: Phong(cd: Constant((0.8, 0.6, 0.4)), ks: 0.4, exp: 20){extra})])",
        mesh.display().to_string()
    )
}

fn build(text: &str, at: &Path) -> texplore::Result<Scene> {
    let desc = parse_preset(text, at)?;
    build_scene(&desc, at, &mut AssetCache::new())
}

fn mesh_of(scene: &Scene, object: usize) -> &Mesh {
    match &scene.objects[object].shape {
        Shape::Mesh(m) => &m.mesh,
        other => panic!("not a mesh: {other:?}"),
    }
}

fn pixels(scene: &Scene) -> Vec<Rgb> {
    let film = render_on(scene, 2);
    assert!(film.is_finite());
    film.to_linear()
}

/// A constant height of 0 (or a scale of 0) is no displacement: the same image, bit for bit,
/// from the file's own mesh. An image that is black everywhere goes through subdivision (16
/// times the triangles) and still gives the same image, to rounding.
#[test]
fn a_flat_height_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write_mesh(dir.path(), "torus.ply", &torus(24, 12, 1.0, 0.4));
    let black: Vec<u8> = vec![0; 8 * 8 * 3];
    let black_png = dir.path().join("black.png");
    save_png(&black_png, 8, 8, &black, &[]).unwrap();
    let at = dir.path().join("p.ron");
    let plain = build(&preset(&mesh, "", 4), &at).unwrap();
    let reference = pixels(&plain);
    assert!(
        reference.iter().any(|c| c.luminance() > 0.05),
        "the torus is in view"
    );
    for exact in [
        ", displace: (height: Constant((0, 0, 0)), scale: 0.3, subdivide: 3)",
        ", displace: (height: Image(path: \"ramp.png\"), scale: 0, subdivide: 3)",
    ] {
        write_ramp(dir.path());
        let scene = build(&preset(&mesh, exact, 4), &at).unwrap();
        assert_eq!(mesh_of(&scene, 0).triangle_count(), 24 * 12 * 2, "{exact}");
        assert_eq!(pixels(&scene), reference, "{exact}");
    }
    let scene = build(
        &preset(
            &mesh,
            ", displace: (height: Image(path: \"black.png\", mapping: Uv), scale: 0.3, subdivide: 2)",
            4,
        ),
        &at,
    )
    .unwrap();
    assert_eq!(mesh_of(&scene, 0).triangle_count(), 24 * 12 * 2 * 16);
    // Inside a small triangle the shading normal interpolates the midpoints' renormalised
    // normals instead of the big triangle's three: a rounding-sized difference in the highlight.
    let flat = pixels(&scene);
    let diffs: Vec<f32> = flat
        .iter()
        .zip(&reference)
        .map(|(a, b)| {
            (a.0 - b.0)
                .abs()
                .max((a.1 - b.1).abs())
                .max((a.2 - b.2).abs())
        })
        .collect();
    let worst = diffs.iter().copied().fold(0.0f32, f32::max);
    let mean = diffs.iter().sum::<f32>() / diffs.len() as f32;
    assert!(
        worst < 1e-2 && mean < 2e-4,
        "largest difference {worst}, mean {mean}"
    );
}

/// Every vertex of the subdivided sphere moves by exactly `scale * h` along its (interpolated)
/// normal, and through a preset the sphere's radius grows from 1 to 1 + scale * h: its box, and
/// where a ray along an axis meets it.
#[test]
fn a_constant_height_moves_every_vertex_by_scale_times_height() {
    let (mut d, parents) = subdivide(&round_sphere(), 2);
    assert_eq!(parents.len(), d.triangles.len());
    let before = d.clone();
    let heights = vec![0.8; d.positions.len()];
    let moved = displace(&mut d, &heights, 0.25);
    assert!((moved - 0.2).abs() < 1e-6, "{moved}");
    for v in 0..d.positions.len() {
        let expected = before.positions[v] + before.normals[v] * 0.2;
        assert!(
            (d.positions[v] - expected).length() < 1e-6,
            "vertex {v}: {} instead of {expected}",
            d.positions[v]
        );
    }

    let dir = tempfile::tempdir().unwrap();
    let mesh = write_mesh(dir.path(), "sphere.ply", &round_sphere());
    let at = dir.path().join("p.ron");
    let scene = build(
        &preset(
            &mesh,
            ", displace: (height: Constant((0.8, 0.8, 0.8)), scale: 0.25, subdivide: 1)",
            1,
        ),
        &at,
    )
    .unwrap();
    let m = mesh_of(&scene, 0);
    let b = m.bbox();
    for v in b.max.to_array() {
        assert!((v - 1.2).abs() < 1e-5, "{b:?}");
    }
    for v in b.min.to_array() {
        assert!((v + 1.2).abs() < 1e-5, "{b:?}");
    }
    // The vertex at (0, 0, 1) is now at z = 1.2.
    let hit = m
        .closest_hit(&Ray::new(Vec3A::new(0.0, 0.0, 5.0), Vec3A::NEG_Z), 10.0)
        .unwrap();
    assert!((5.0 - hit.t - 1.2).abs() < 1e-5, "{}", 5.0 - hit.t);
    // A negative scale pushes in.
    let scene = build(
        &preset(
            &mesh,
            ", displace: (height: Constant((0.8, 0.8, 0.8)), scale: -0.25, subdivide: 0)",
            1,
        ),
        &at,
    )
    .unwrap();
    assert!((mesh_of(&scene, 0).bbox().max.y - 0.8).abs() < 1e-5);
}

/// Position keys: bit patterns with -0 read as 0.
fn key(p: Vec3) -> [u32; 3] {
    (p + Vec3::ZERO).to_array().map(f32::to_bits)
}

/// An edge's ends and the normals of the faces that share it.
type Edge = (Vec3, Vec3, Vec<Vec3>);

/// Every edge, by its ends' positions, is shared by exactly two triangles (the surface is
/// closed, without cracks or T-junctions); returns each edge's ends and its two faces' normals.
fn closed_edges(triangles: &[[Vec3; 3]], name: &str) -> Vec<Edge> {
    let mut edges: HashMap<([u32; 3], [u32; 3]), Edge> = HashMap::new();
    for p in triangles {
        let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        for k in 0..3 {
            let (a, b) = (p[k], p[(k + 1) % 3]);
            let (ka, kb) = (key(a), key(b));
            let e = if ka < kb { (ka, kb) } else { (kb, ka) };
            edges.entry(e).or_insert((a, b, Vec::new())).2.push(n);
        }
    }
    let open = edges.values().filter(|e| e.2.len() != 2).count();
    assert_eq!(open, 0, "{name}: {open} of {} edges are open", edges.len());
    edges.into_values().collect()
}

/// Rays at points along every edge, from directions that see both faces of the edge from the
/// front, all hit (a crack would let one through).
fn rays_never_slip_through(m: &Mesh, edges: &[Edge], name: &str) {
    let mut rays = 0;
    for (a, b, normals) in edges {
        let mean = (normals[0] + normals[1]).normalize_or_zero();
        if normals.iter().any(|n| n.dot(mean) < 0.3) {
            continue;
        }
        for f in [0.5, 0.25, 0.875] {
            let target = *a + (*b - *a) * f;
            let from = target + mean * 2.0;
            let hit = m.closest_hit(&Ray::new(from.into(), (target - from).into()), 1.5);
            assert!(
                hit.is_some_and(|h| h.t <= 1.0 + 1e-4),
                "{name}: a ray from {from} to {target} slipped through"
            );
            rays += 1;
        }
    }
    assert!(rays > 1000, "{name}: {rays} rays");
}

/// The torus has seams in u and v (vertices copied with other (u, v)); heights taken from u
/// differ most across the u seam (0 on one side, 1 on the other), yet the subdivided and
/// displaced torus is closed and no ray slips through, in the library and through a preset.
#[test]
fn subdivision_and_displacement_stay_watertight_across_uv_seams() {
    let base = torus(24, 12, 1.0, 0.4);
    let (mut d, _) = subdivide(&base, 2);
    let heights: Vec<f32> = d.uvs.iter().map(|uv| uv.x).collect();
    // The seam copies really are asked to go to different heights.
    let mut at_seam: HashMap<[u32; 3], Vec<f32>> = HashMap::new();
    for (p, h) in d.positions.iter().zip(&heights) {
        at_seam.entry(key(*p)).or_default().push(*h);
    }
    let split = at_seam
        .values()
        .filter(|h| h.iter().any(|x| (x - h[0]).abs() > 0.5))
        .count();
    assert!(split >= 48, "{split} seam vertices with differing heights");
    displace(&mut d, &heights, 0.3);
    let tris: Vec<[Vec3; 3]> = d
        .triangles
        .iter()
        .map(|t| t.map(|k| d.positions[k as usize]))
        .collect();
    let edges = closed_edges(&tris, "library torus");
    let m = Mesh::new(d, Path::new("torus")).unwrap();
    rays_never_slip_through(&m, &edges, "library torus");

    let dir = tempfile::tempdir().unwrap();
    let mesh = write_mesh(dir.path(), "torus.ply", &base);
    write_ramp(dir.path());
    let scene = build(
        &preset(
            &mesh,
            ", displace: (height: Image(path: \"ramp.png\", mapping: Uv, filter: Bilinear), scale: 0.3, subdivide: 2)",
            1,
        ),
        &dir.path().join("p.ron"),
    )
    .unwrap();
    let m = mesh_of(&scene, 0);
    let tris: Vec<[Vec3; 3]> = (0..m.triangle_count() as u32)
        .map(|t| m.triangle_vertices(t).unwrap().0)
        .collect();
    let edges = closed_edges(&tris, "preset torus");
    rays_never_slip_through(m, &edges, "preset torus");
}

/// Seen from above, a torus displaced by a height that is 1 where 1/4 <= u < 3/4 and 0 elsewhere
/// covers the same pixels as the bump-mapped one where the heights are 0 and more pixels where
/// they are 1: the bump map leaves the outline, the displacement moves it.
#[test]
fn the_silhouette_differs_from_the_bump_maps_where_the_heights_are_large() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write_mesh(dir.path(), "torus.ply", &torus(48, 16, 1.0, 0.35));
    // 4 x 1: black, white, white, black (so both sides of the u seam are black).
    save_png(
        &dir.path().join("half.png"),
        4,
        1,
        &[0, 0, 0, 255, 255, 255, 255, 255, 255, 0, 0, 0],
        &[],
    )
    .unwrap();
    let height = "Image(path: \"half.png\", mapping: Uv, filter: Nearest)";
    let at = dir.path().join("p.ron");
    let bumped = build(
        &preset(&mesh, &format!(", bump: (height: {height}, scale: 0.2)"), 1),
        &at,
    )
    .unwrap();
    let displaced = build(
        &preset(
            &mesh,
            &format!(", displace: (height: {height}, scale: 0.2, subdivide: 2)"),
            1,
        ),
        &at,
    )
    .unwrap();
    let (mut only_displaced, mut both) = (0, 0);
    for y in 0..64 {
        for x in 0..64 {
            let pos = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let (ray, _) = bumped.camera.ray(pos, 1.0).unwrap();
            match (bumped.hit(&ray), displaced.hit(&ray)) {
                (Some(_), Some(_)) => both += 1,
                (None, Some(h)) => {
                    only_displaced += 1;
                    let u = h.local.uv.unwrap().x;
                    // Up to one small triangle (1/192 of u) beyond the white texels.
                    assert!(
                        (0.24..0.76).contains(&u),
                        "pixel ({x}, {y}) grew where u = {u}"
                    );
                }
                (Some(h), None) => {
                    panic!("pixel ({x}, {y}) at u = {} lost", h.local.uv.unwrap().x);
                }
                (None, None) => {}
            }
        }
    }
    assert!(both > 500, "{both}");
    assert!(only_displaced > 40, "{only_displaced} pixels grew");
}

/// The displaced preset's knots: the bumped one's outline is the smooth tube's, the displaced
/// one covers more (its gravel stands out), and its shadow on the floor differs too.
#[test]
fn the_displaced_preset_shows_outline_and_shadow() {
    let path = root().join("presets/displaced.ron");
    let desc = load_preset(&path).unwrap();
    let scene = build_with(&desc, &path, sized(160, 120, 1), &mut AssetCache::new());
    let name = |i: usize| scene.objects[i].name.clone();
    assert_eq!(
        (name(1).as_str(), name(2).as_str()),
        ("Bumped knot", "Displaced knot")
    );
    let base = 6144;
    assert_eq!(mesh_of(&scene, 1).triangle_count(), base);
    assert_eq!(mesh_of(&scene, 2).triangle_count(), base * 64);
    // Pixels of each knot: the displaced one is bigger than the bumped one.
    let mut count = [0usize; 3];
    for y in 0..120 {
        for x in 0..160 {
            let (ray, _) = scene
                .camera
                .ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), 1.0)
                .unwrap();
            if let Some(h) = scene.hit(&ray) {
                count[h.object] += 1;
            }
        }
    }
    assert!(count[2] as f32 > 1.1 * count[1] as f32, "{count:?}");
    // The same knot bump-mapped in the displaced one's place: the floor in its shadow (a ray
    // toward the sun meets the knot) is a part of the displaced knot's shadow, which is bigger.
    let mut twin = desc.clone();
    let d = twin.objects[2].displace.take().unwrap();
    twin.objects[2].bump = Some(BumpDesc {
        height: d.height,
        scale: d.scale,
    });
    let twin = build_with(&twin, &path, sized(160, 120, 1), &mut AssetCache::new());
    let to_sun = Vec3A::new(-0.5, 1.0, 0.45).normalize();
    let shadowed = |scene: &Scene, ray: &Ray| {
        let h = scene.hit(ray).filter(|h| h.object == 0)?;
        let up = Ray::new(h.p + Vec3A::Y * 1e-3, to_sun);
        Some(scene.hit(&up).is_some_and(|b| b.object == 2))
    };
    let (mut both, mut only_displaced, mut only_bumped) = (0, 0, 0);
    for y in 0..120 {
        for x in 0..160 {
            let (ray, _) = scene
                .camera
                .ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), 1.0)
                .unwrap();
            // Floor points both cameras see (the thicker knot hides a little more floor).
            match (shadowed(&scene, &ray), shadowed(&twin, &ray)) {
                (Some(true), Some(true)) => both += 1,
                (Some(true), Some(false)) => only_displaced += 1,
                (Some(false), Some(true)) => only_bumped += 1,
                _ => {}
            }
        }
    }
    assert!(both > 200, "{both}");
    assert!(
        only_displaced > 30 && only_bumped <= 2,
        "displaced only {only_displaced}, bumped only {only_bumped}"
    );
    let inspected = (0..120)
        .flat_map(|y| (0..160).map(move |x| Vec2::new(x as f32 + 0.5, y as f32 + 0.5)))
        .filter_map(|p| scene.inspect(p))
        .find(|i| i.object == 2)
        .expect("the displaced knot is in view");
    assert!(
        inspected
            .shape
            .starts_with("mesh torus-knot.ply (displaced), triangle "),
        "{}",
        inspected.shape
    );
    let lines = &inspected.mesh.as_ref().unwrap().lines;
    assert_eq!(
        lines[..3],
        [
            "displaced at load by gravel_gray_512.png,",
            "scale 0.15, 3 subdivision levels:",
            "393216 triangles from the file's 6144"
        ]
    );
    assert!(lines[3].starts_with("weights: "), "{lines:?}");
}

/// A subdivision past the triangle limit is refused before any work, naming the preset, the
/// object, the field and the limit; so are a generic shape, a huge scale and typos.
#[test]
fn bad_displacements_are_refused_with_the_field_named() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = root().join("assets/torus-knot.ply");
    let at = dir.path().join("hostile.ron");
    for (extra, expected) in [
        (
            ", displace: (height: Constant((1, 1, 1)), subdivide: 6)",
            format!(
                "hostile.ron: objects[0].displace.subdivide: 6 levels would make 25165824 triangles of the 6144 in {}",
                mesh.display()
            ),
        ),
        (
            ", displace: (height: Constant((1, 1, 1)), subdivide: 4294967295)",
            "subdivide: 4294967295 levels would make more than 2^64 triangles".into(),
        ),
        (
            ", displace: (height: Constant((1, 1, 1)), scale: 1e9)",
            "objects[0].displace.scale: 1000000000 is out of range".into(),
        ),
        (
            ", displace: (height: Image(path: \"missing.png\"))",
            "missing.png".into(),
        ),
    ] {
        let e = build(&preset(&mesh, extra, 1), &at)
            .unwrap_err()
            .to_string();
        assert!(e.contains(&expected), "{e}\nexpected: {expected}");
        assert!(
            e.contains("hostile.ron") || e.contains("missing.png"),
            "{e}"
        );
    }
    let e = build(
        &preset(
            &mesh,
            ", displace: (height: Constant((1, 1, 1)), subdivide: 6)",
            1,
        ),
        &at,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains(&format!("at most {MAX_DISPLACED_TRIANGLES} (4 M)")),
        "{e}"
    );

    // The command line says the same and exits with an error.
    let text = preset(
        &mesh,
        ", displace: (height: Constant((1, 1, 1)), subdivide: 9)",
        1,
    );
    std::fs::write(&at, text).unwrap();
    let out = texplore_in(dir.path(), &["render", "hostile.ron", "-o", "out.png"]);
    let e = failure(&out);
    assert!(
        e.contains("hostile.ron") && e.contains("displace.subdivide: 9 levels"),
        "{e}"
    );
    assert!(!dir.path().join("out.png").exists());

    // A generic shape: use a mesh, or a bump map.
    let sphere = "(version: 1, camera: (eye: (0, 0, 4)), objects: [(name: \"Ball\", shape: Sphere,
        material: Matte(cd: Constant((1, 1, 1))), displace: (height: Constant((1, 1, 1))))])";
    let e = build(sphere, &at).unwrap_err().to_string();
    assert!(
        e.contains("objects[0].displace (object \"Ball\"): a displacement map needs a Mesh shape")
            && e.contains("bump map"),
        "{e}"
    );
    // A mesh without (u, v) cannot be displaced through them.
    let mut no_uv = round_sphere();
    no_uv.uvs.clear();
    let plain = write_mesh(dir.path(), "plain.ply", &no_uv);
    write_ramp(dir.path());
    let e = build(
        &preset(
            &plain,
            ", displace: (height: Image(path: \"ramp.png\", mapping: Uv))",
            1,
        ),
        &at,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("displace.height: ") && e.contains("has no texture coordinates"),
        "{e}"
    );

    // Typos name the field.
    for (extra, field) in [
        (
            ", displace: (height: Constant((1, 1, 1)), scael: 0.1)",
            "scael",
        ),
        (
            ", displace: (height: Constant((1, 1, 1)), subdivisions: 2)",
            "subdivisions",
        ),
        (", displce: (height: Constant((1, 1, 1)))", "displce"),
    ] {
        let e = parse_preset(&preset(&mesh, extra, 1), &at)
            .unwrap_err()
            .to_string();
        assert!(e.contains("hostile.ron") && e.contains(field), "{e}");
    }
    let e = parse_preset(
        &preset(
            &mesh,
            ", displace: (height: Constant((1, 1, 1)), scael: 0.1)",
            1,
        ),
        &at,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("subdivide"),
        "the expected fields are listed: {e}"
    );
}

/// The displaced preset renders finite and not black under every texture filter (the height
/// is read through each at zero footprint).
#[test]
fn renders_are_finite_in_every_filter() {
    let path = root().join("presets/displaced.ron");
    let desc = load_preset(&path).unwrap();
    let mut cache = AssetCache::new();
    for &f in Filter::VARIANTS {
        let o = Overrides {
            width: Some(48),
            height: Some(36),
            spp: Some(1),
            ..filtered(f)
        };
        let scene = build_with(&desc, &path, o, &mut cache);
        let film = render_on(&scene, 2);
        assert!(film.is_finite(), "{f:?}");
        let px = film.to_linear();
        assert!(px.iter().any(|c| c.luminance() > 0.05), "{f:?} is black");
    }
}
