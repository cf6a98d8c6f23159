//! Triangle meshes as a user meets them: the lecture's PLY renders with the (u, v) it implies,
//! every PLY encoding and spelling loads the same mesh, polygons triangulate, rays through
//! shared edges never slip through, and bad files name the file and the element.

use crate::common::{failure, parse_json, render_on, root, texplore};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use strum::VariantArray;
use texplore::geometry::{Mesh, MeshData, Shape};
use texplore::math::{Ray, Vec2, Vec3, Vec3A, srgb8_to_linear};
use texplore::meshio::{PlyFormat, load_mesh, read_ply_from, torus, write_ply};
use texplore::render::Film;
use texplore::scene::{AssetCache, Scene, build_scene, parse_preset};
use texplore::texture::save_png;

fn scene(text: &str, preset: &Path) -> texplore::Result<Scene> {
    let desc = parse_preset(text, preset)?;
    build_scene(&desc, preset, &mut AssetCache::new())
}

fn render(scene: &Scene) -> Film {
    render_on(scene, 2)
}

/// A 4 x 4 image whose texels all differ: (column, file row) -> colour bytes.
fn texel(col: u32, row: u32) -> [u8; 3] {
    [
        (30 + 60 * col) as u8,
        (30 + 60 * row) as u8,
        if (col + row).is_multiple_of(2) {
            200
        } else {
            40
        },
    ]
}

fn write_texture(dir: &Path) -> PathBuf {
    let mut rgb = Vec::new();
    for row in 0..4 {
        for col in 0..4 {
            rgb.extend_from_slice(&texel(col, row));
        }
    }
    let path = dir.join("tex4.png");
    save_png(&path, 4, 4, &rgb, &[]).unwrap();
    path
}

/// Seen from straight above with +x up and +z to the right, every pixel of the lecture's two
/// triangles shows the texel of u = (z + 1) / 2, v = (x + 1) / 2 (v = 0 at the image's bottom):
/// the photo stands upright, its top-left texel at the top-left corner.
#[test]
fn the_lectures_ply_renders_with_the_uv_it_implies() {
    let dir = tempfile::tempdir().unwrap();
    let tex = write_texture(dir.path());
    let ply = root().join("assets/two-triangles.ply");
    let text = format!(
        "(version: 1, camera: (eye: (0, 30, 0), up: (1, 0, 0), projection: Pinhole(fov: 4.5)),
          render: (width: 64, height: 64, spp: 1, sampler: Regular),
          objects: [(shape: Mesh(path: {:?}, shading: Flat),
                     material: Emissive(ce: Image(path: {:?}, mapping: Uv, filter: Nearest)))])",
        ply.display().to_string(),
        tex.display().to_string()
    );
    let preset = dir.path().join("p.ron");
    let scene = scene(&text, &preset).unwrap();
    let film = render(&scene).to_linear();
    let s = &scene.settings;
    let mut checked = 0;
    for y in 0..64u32 {
        for x in 0..64u32 {
            let pixel = y * 64 + x;
            let pos = Vec2::new(x as f32, y as f32) + s.sampler.sample(s.seed, pixel, 0, 1);
            let (ray, _) = scene.camera.ray(pos, 1.0).unwrap();
            let Some(hit) = scene.hit(&ray) else {
                continue;
            };
            let (u, v) = (f32::midpoint(hit.p.z, 1.0), f32::midpoint(hit.p.x, 1.0));
            let (fu, fv) = (u * 4.0, v * 4.0);
            // Skip pixels on texel borders.
            if (fu - fu.round()).abs() < 0.05 || (fv - fv.round()).abs() < 0.05 {
                continue;
            }
            let col = (fu as u32).min(3);
            let file_row = 3 - (fv as u32).min(3);
            let want = texel(col, file_row).map(srgb8_to_linear);
            let got = film[pixel as usize].to_array();
            for c in 0..3 {
                assert!(
                    (got[c] - want[c]).abs() < 1e-3,
                    "pixel ({x}, {y}) hit {:?} (u {u}, v {v}): got {got:?}, want texel ({col}, {file_row}) {want:?}",
                    hit.p
                );
            }
            checked += 1;
        }
    }
    assert!(checked > 2000, "only {checked} pixels checked");
    // Upright: the top-left of the picture is the file's top-left texel, the bottom-right the
    // file's bottom-right one.
    let near = |p: usize, t: [u8; 3]| {
        let got = film[p].to_array();
        (0..3).all(|c| (got[c] - srgb8_to_linear(t[c])).abs() < 1e-3)
    };
    let quad = |x: u32, y: u32| (y * 64 + x) as usize;
    let corners = (0..64)
        .find(|&k| {
            scene
                .hit(
                    &scene
                        .camera
                        .ray(Vec2::splat(k as f32 + 0.5), 1.0)
                        .unwrap()
                        .0,
                )
                .is_some()
        })
        .unwrap();
    let (lo, hi) = (corners + 3, 63 - corners - 3);
    assert!(near(quad(lo, lo), texel(0, 0)), "top-left");
    assert!(near(quad(hi, lo), texel(3, 0)), "top-right");
    assert!(near(quad(lo, hi), texel(0, 3)), "bottom-left");
    assert!(near(quad(hi, hi), texel(3, 3)), "bottom-right");
}

fn torus_scene(ply: &Path) -> String {
    format!(
        "(version: 1, camera: (eye: (0, 2, 2.6)), render: (width: 96, height: 72, spp: 2),
          lights: [Directional(direction: (1, 1, 1))],
          objects: [(shape: Mesh(path: {:?}, shading: Smooth),
                     material: Matte(cd: UvGrid(mapping: Uv, filter: Bilinear)))])",
        ply.display().to_string()
    )
}

/// The same mesh written as ascii, binary little-endian and binary big-endian renders to the
/// same image.
#[test]
fn ascii_and_binary_plys_give_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let data = torus(40, 16, 1.0, 0.4);
    let mut films = Vec::new();
    for &format in PlyFormat::VARIANTS {
        let path = dir.path().join(format!("torus-{format}.ply"));
        let mut f = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        write_ply(&mut f, &data, format).unwrap();
        drop(f);
        let loaded = load_mesh(&path).unwrap();
        assert_eq!(loaded.positions, data.positions, "{format}");
        assert_eq!(loaded.uvs, data.uvs, "{format}");
        assert_eq!(loaded.normals, data.normals, "{format}");
        assert_eq!(loaded.triangles, data.triangles, "{format}");
        let s = scene(&torus_scene(&path), &dir.path().join("p.ron")).unwrap();
        films.push(render(&s));
    }
    assert!(films[0] == films[1] && films[1] == films[2]);
    let lit = films[0]
        .to_linear()
        .iter()
        .filter(|c| c.max_channel() > 0.05)
        .count();
    assert!(lit > 96 * 72 / 5, "the torus is missing ({lit} lit pixels)");
}

fn ply(text: &str) -> texplore::Result<MeshData> {
    read_ply_from(&mut text.as_bytes(), Path::new("test.ply"))
}

/// Quads and pentagons become fans of triangles, all of them kept.
#[test]
fn polygons_are_triangulated() {
    let d = ply("ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n-0.5 0.5 0\n2 2 0\n4 0 1 2 3\n5 0 3 4 1 5\n")
        .unwrap();
    assert_eq!(d.faces, 2);
    assert_eq!(
        d.triangles,
        vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1], [0, 1, 5]]
    );
    // The quad's second triangle (the book's reader drops it) is hit.
    let m = Mesh::new(d, Path::new("test.ply")).unwrap();
    let down = Ray::new(Vec3A::new(0.25, 0.75, 1.0), Vec3A::new(0.0, 0.0, -1.0));
    assert!(m.closest_hit(&down, f32::INFINITY).is_some());
}

/// Texture coordinates under every spelling in use load to the same (u, v); comments,
/// `obj_info`, extra properties and elements are skipped.
#[test]
fn uv_spellings_and_extra_properties() {
    for (u, v) in [
        ("u", "v"),
        ("s", "t"),
        ("texture_u", "texture_v"),
        ("texture_s", "texture_t"),
    ] {
        let text = format!(
            "ply\nformat ascii 1.0\ncomment made by hand\nobj_info nothing\nelement vertex 3\nproperty float x\nproperty float y\nproperty uchar red\nproperty float z\nproperty float {u}\nproperty double {v}\nelement edge 1\nproperty int vertex1\nproperty int vertex2\nelement face 1\nproperty uchar flags\nproperty list uchar uint vertex_index\nproperty list uchar float other\nend_header\n0 0 255 0 0.25 0.5\n1 0 0 0 0.75 0.5\n0 1 7 0 0.25 1\n0 1\n9 3 0 1 2 2 0.5 0.5\n"
        );
        let d = ply(&text).unwrap_or_else(|e| panic!("{u} {v}: {e}"));
        assert_eq!(
            d.uvs,
            vec![
                Vec2::new(0.25, 0.5),
                Vec2::new(0.75, 0.5),
                Vec2::new(0.25, 1.0)
            ]
        );
        assert_eq!(d.positions[2], Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(d.triangles, vec![[0, 1, 2]]);
        assert_eq!(d.uv_names, Some((u.to_string(), v.to_string())));
    }
}

/// Bad files: one error naming the file, the position and the element.
#[test]
fn bad_plys_name_the_file_and_element() {
    let head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
    let verts = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
    let cases = [
        (format!("{head}{verts}3 0 1 2\n3 0 2 9\n"), &["line 15 (face 1)", "vertex index 9 is out of range (4 vertices)"][..]),
        (format!("{head}{verts}3 0 1 2\n3 0 -2 3\n"), &["face 1", "negative"]),
        (format!("{head}{verts}3 0 1 2\n"), &["face 1", "ends early"]),
        (format!("{head}{verts}3 0 1 2\n3 0 2\n"), &["face 1", "ends early"]),
        (format!("{head}0 0 0\n1 nan 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"), &["line 11 (vertex 1)", "not finite"]),
        (format!("{head}0 0 0\n1 x 0\n"), &["vertex 1", "expected a number, found 'x'"]),
        (head.replace("vertex 4", "vertex 4000000000"), &["header line 3", "4000000000 vertices is more than"]),
        (format!("{head}{verts}3 0 1 2\n2 0 2\n"), &["face 1", "at least 3"]),
        (format!("{}{verts}3 0 1 2\n200000 0 2\n", head.replace("list uchar", "list uint")), &["face 1", "200000 items"]),
        // A count beyond the header's `uchar`: refused, not read as a 300-gon.
        (format!("{head}{verts}3 0 1 2\n300 0 1 2\n"), &["face 1", "300 does not fit the header's uchar (0 to 255)"]),
        (format!("{}{verts}3 0 1 2\n3 0 1 70000\n", head.replace("uchar int", "uchar ushort")), &["face 1", "70000 does not fit the header's ushort"]),
        ("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n".to_string(), &["header line 3", "no 'z'"]),
        ("PLY\n".to_string(), &["header line 1", "not a PLY"]),
        ("ply\nformat ascii 1.0\nelement vertex 1\nproperty quaternion x\n".to_string(), &["header line 4", "quaternion"]),
    ];
    for (text, needles) in cases {
        let e = ply(&text)
            .err()
            .unwrap_or_else(|| panic!("accepted:\n{text}"))
            .to_string();
        assert!(e.starts_with("test.ply: "), "{e}");
        for n in needles {
            assert!(e.contains(n), "'{n}' not in: {e}");
        }
    }
    // Binary: a truncated file names the byte and the element.
    let data = torus(8, 4, 1.0, 0.4);
    for format in [PlyFormat::BinaryLittleEndian, PlyFormat::BinaryBigEndian] {
        let mut bytes = Vec::new();
        write_ply(&mut bytes, &data, format).unwrap();
        bytes.truncate(bytes.len() - 7);
        let e = read_ply_from(&mut bytes.as_slice(), Path::new("cut.ply"))
            .unwrap_err()
            .to_string();
        let last = data.triangles.len() - 1;
        assert!(
            e.starts_with("cut.ply: byte ")
                && e.contains(&format!("(face {last})"))
                && e.contains("ends early"),
            "{e}"
        );
    }
}

/// Binary PLYs with every scalar type, in both byte orders, read the values written; a file cut
/// inside a value names the byte where that value starts.
#[test]
fn binary_plys_read_every_scalar_type_in_both_byte_orders() {
    let header = |order: &str| {
        format!(
            "ply\nformat binary_{order}_endian 1.0\nelement vertex 3\nproperty double x\nproperty float y\nproperty short z\nproperty uchar u\nproperty char v\nproperty ushort a\nproperty int b\nproperty uint c\nelement face 1\nproperty list ushort int vertex_indices\nend_header\n"
        )
    };
    let vertices: [(f64, f32, i16, u8, i8); 3] = [
        (1.5, -2.25, -300, 200, -5),
        (-1e10, 3.0e-3, 32767, 0, 127),
        (0.125, 7.0, -32768, 255, -128),
    ];
    for big in [false, true] {
        let mut bytes = header(if big { "big" } else { "little" }).into_bytes();
        let header_len = bytes.len();
        macro_rules! put {
            ($v:expr) => {
                if big {
                    bytes.extend_from_slice(&$v.to_be_bytes())
                } else {
                    bytes.extend_from_slice(&$v.to_le_bytes())
                }
            };
        }
        for (x, y, z, u, v) in vertices {
            put!(x);
            put!(y);
            put!(z);
            put!(u);
            put!(v);
            put!(60_000u16);
            put!(-70_000i32);
            put!(3_000_000_000u32);
        }
        put!(3u16);
        for i in [2i32, 0, 1] {
            put!(i);
        }
        let m = read_ply_from(&mut bytes.as_slice(), Path::new("t.ply")).unwrap();
        let order = if big { "big" } else { "little" };
        assert_eq!(m.format, format!("ply binary_{order}_endian"));
        let expect: Vec<Vec3> = vertices
            .iter()
            .map(|&(x, y, z, _, _)| Vec3::new(x as f32, y, f32::from(z)))
            .collect();
        assert_eq!(m.positions, expect, "{order}");
        let uvs: Vec<Vec2> = vertices
            .iter()
            .map(|&(.., u, v)| Vec2::new(f32::from(u), f32::from(v)))
            .collect();
        assert_eq!(m.uvs, uvs, "{order}");
        assert_eq!(m.triangles, vec![[2, 0, 1]]);
        // Cut two bytes into the first vertex's y: the error names the byte where y starts.
        let cut = &bytes[..header_len + 8 + 2];
        let e = read_ply_from(&mut &cut[..], Path::new("t.ply"))
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            format!(
                "t.ply: byte {} (vertex 0): the file ends early (truncated?)",
                header_len + 8
            )
        );
    }
}

/// Rays aimed at shared edges and vertices of closed meshes never slip through: the watertight
/// test sees a shared edge identically from both triangles. Each ray comes from a direction
/// that sees every triangle around its target from the front (so the target is no silhouette
/// point and a miss could only be a crack).
#[test]
fn rays_through_shared_edges_and_vertices_never_miss() {
    use std::collections::HashMap;
    for (name, data) in [
        ("torus", torus(48, 20, 1.0, 0.35)),
        ("sphere", texplore::meshio::bumpy_sphere(64, 32, 0.05)),
    ] {
        // Faces around each edge and each vertex, by position (seams duplicate indices).
        type Key = [u32; 3];
        let m = Mesh::new(data.clone(), Path::new(name)).unwrap();
        let key = |p: Vec3| (p + Vec3::ZERO).to_array().map(f32::to_bits); // -0 is 0
        // Edge (by its ends' positions) -> its ends and the normals of the faces around it.
        let mut edges: HashMap<(Key, Key), (Vec3, Vec3, Vec<Vec3>)> = HashMap::new();
        let mut verts: HashMap<[u32; 3], (Vec3, Vec<Vec3>)> = HashMap::new();
        for t in &data.triangles {
            let p = t.map(|i| data.positions[i as usize]);
            let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
            if n == Vec3::ZERO {
                continue;
            }
            for k in 0..3 {
                let (a, b) = (p[k], p[(k + 1) % 3]);
                let (ka, kb) = (key(a), key(b));
                let e = if ka < kb { (ka, kb) } else { (kb, ka) };
                edges.entry(e).or_insert((a, b, Vec::new())).2.push(n);
                verts.entry(ka).or_insert((a, Vec::new())).1.push(n);
            }
        }
        let mut rng = texplore::math::SampleRng::new(5, 0, 0);
        let mut rays = 0;
        let mut check = |target: Vec3, normals: &[Vec3]| {
            let mean: Vec3 = normals.iter().copied().sum::<Vec3>().normalize();
            for _ in 0..4 {
                let jitter = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5;
                let d = (mean + jitter * 0.6).normalize();
                if normals.iter().any(|n| n.dot(d) < 0.05) {
                    continue;
                }
                let from = target + d * 3.0;
                let hit = m.closest_hit(&Ray::new(from.into(), (target - from).into()), 1.5);
                assert!(
                    hit.is_some_and(|h| h.t <= 1.0 + 1e-4),
                    "{name}: a ray from {from} to {target} slipped through"
                );
                rays += 1;
            }
        };
        for (a, b, normals) in edges.values() {
            assert_eq!(normals.len(), 2, "{name} is not closed");
            for f in [0.5, 0.3125, 0.875] {
                check(*a + (*b - *a) * f, normals);
            }
        }
        for (v, normals) in verts.values() {
            check(*v, normals);
        }
        assert!(rays > 10_000, "{name}: {rays} rays");
    }
    // Rays exactly through the lecture's shared diagonal (x = z), straight down and slanted.
    let m = Mesh::new(
        load_mesh(&root().join("assets/two-triangles.ply")).unwrap(),
        Path::new("two"),
    )
    .unwrap();
    for k in -63..64 {
        let x = k as f32 / 64.0;
        for dir in [
            Vec3A::new(0.0, -1.0, 0.0),
            Vec3A::new(0.3, -1.0, 0.3),
            Vec3A::new(-0.2, -1.0, -0.2),
        ] {
            let from = Vec3A::new(x, 0.0, x) - dir * 4.0;
            assert!(
                m.closest_hit(&Ray::new(from, dir), 10.0).is_some(),
                "diagonal at {x}"
            );
        }
    }
}

/// `texplore mesh-info --json` reports what the file holds.
#[test]
fn mesh_info_json() {
    let v = parse_json(&texplore(&[
        "mesh-info",
        "assets/two-triangles.ply",
        "--json",
    ]));
    assert_eq!(v["vertices"], 4);
    assert_eq!(v["triangles"], 2);
    assert_eq!(v["has_uv"], true);
    assert_eq!(v["has_normals"], false);
    assert_eq!(v["bbox_min"], serde_json::json!([-1.0, -1.0, -1.0]));
    assert_eq!(v["bbox_max"], serde_json::json!([1.0, 0.0, 1.0]));
    assert_eq!(v["degenerate"], 0);
    assert_eq!(v["degenerate_uv"], 0);
    // A bad file: one line naming it.
    let e = failure(&texplore(&["mesh-info", "presets/earth.ron"]));
    assert!(
        e.contains("presets/earth.ron") && e.contains(".ply and .obj"),
        "{e}"
    );
}

/// A mesh without (u, v): the `Uv` mapping is refused with the reason and the way out; a
/// generated mapping renders.
#[test]
fn a_mesh_without_uv_takes_a_generated_mapping() {
    let dir = tempfile::tempdir().unwrap();
    let mut data = torus(24, 12, 1.0, 0.4);
    data.uvs.clear();
    let path = dir.path().join("plain.ply");
    let mut f = std::fs::File::create(&path).unwrap();
    write_ply(&mut f, &data, PlyFormat::BinaryLittleEndian).unwrap();
    drop(f);
    let preset = dir.path().join("p.ron");
    let e = scene(&torus_scene(&path), &preset).unwrap_err().to_string();
    assert!(
        e.contains("plain.ply has no texture coordinates for the Uv mapping to read; choose a generated mapping (spherical, cylindrical, rectangular)"),
        "{e}"
    );
    // The maps read (u, v) too: a clip, bump or normal map under `Uv` is refused the same way,
    // naming its field.
    let generated = torus_scene(&path).replace("UvGrid(mapping: Uv", "UvGrid(mapping: Spherical");
    for (map, field) in [
        (
            "alpha: (texture: Image(path: \"../alpha.png\", mapping: Uv), channel: Alpha)",
            "alpha.texture",
        ),
        (
            "bump: (height: Image(path: \"h.png\", mapping: Uv), scale: 0.01)",
            "bump.height",
        ),
        (
            "normal: (map: Image(path: \"n.png\", mapping: Uv))",
            "normal.map",
        ),
    ] {
        let text = generated.replace(
            "filter: Bilinear)))",
            &format!("filter: Bilinear)), {map})"),
        );
        let e = scene(&text, &preset).unwrap_err().to_string();
        assert!(
            e.contains(&format!("objects[0].{field}: "))
                && e.contains("plain.ply has no texture coordinates"),
            "{map}: {e}"
        );
    }
    // A checker under the spherical map of the fitted model: both colours cover the torus.
    let text = torus_scene(&path).replace(
        "Matte(cd: UvGrid(mapping: Uv, filter: Bilinear))",
        "Emissive(ce: Checker(mapping: Spherical, squares: (8, 4), colors: ((1, 0, 0), (0, 0, 1))))",
    );
    let film = render(&scene(&text, &preset).unwrap()).to_linear();
    let count = |want: [f32; 3]| {
        film.iter()
            .filter(|c| (0..3).all(|k| (c.to_array()[k] - want[k]).abs() < 0.01))
            .count()
    };
    let (red, blue) = (count([1.0, 0.0, 0.0]), count([0.0, 0.0, 1.0]));
    assert!(red > 400 && blue > 400, "red {red}, blue {blue}");
}

/// Instances of one file share the mesh (and its BVH); shadow rays see meshes.
#[test]
fn instances_share_and_meshes_cast_shadows() {
    let ply = root().join("assets/two-triangles.ply");
    let text = format!(
        "(version: 1, camera: (eye: (0, 5, 0.1)), lights: [Directional(direction: (0, 1, 0))],
          objects: [
            (shape: Mesh(path: {p:?}, shading: Flat), transform: (translate: (0, 1, 0)), material: Matte(cd: Constant((1, 1, 1)))),
            (shape: Mesh(path: {p:?}, shading: Smooth), transform: (translate: (0, 2, 0)), material: Matte(cd: Constant((1, 1, 1)))),
            (shape: Plane, transform: (translate: (0, -3, 0)), material: Matte(cd: Constant((1, 1, 1)))),
          ])",
        p = ply.display().to_string()
    );
    let s = scene(&text, Path::new("p.ron")).unwrap();
    let (Shape::Mesh(a), Shape::Mesh(b)) = (&s.objects[0].shape, &s.objects[1].shape) else {
        panic!("not meshes");
    };
    assert!(Arc::ptr_eq(&a.mesh, &b.mesh));
    let up = Vec3A::new(0.0, 1.0, 0.0);
    assert!(s.occluded(&Ray::new(Vec3A::new(0.2, -2.9, 0.3), up), f32::INFINITY));
    assert!(!s.occluded(&Ray::new(Vec3A::new(1.5, -2.9, 0.3), up), f32::INFINITY));
    assert!(!s.occluded(&Ray::new(Vec3A::new(0.2, -2.9, 0.3), up), 2.0));
}

/// An OBJ with a .mtl: `map_Kd` becomes the texture of `MeshMaterial`; a broken face names the
/// line.
#[test]
fn obj_with_material_and_errors() {
    let dir = tempfile::tempdir().unwrap();
    let tex = write_texture(dir.path());
    std::fs::write(
        dir.path().join("quad.mtl"),
        format!(
            "newmtl paper\nKd 0.8 0.8 0.8\nmap_Kd {}\n",
            tex.file_name().unwrap().to_string_lossy()
        ),
    )
    .unwrap();
    let obj = dir.path().join("quad.obj");
    std::fs::write(
        &obj,
        "mtllib quad.mtl\nv -1 0 -1\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl paper\nf 1/1 2/2 3/3 4/4\n",
    )
    .unwrap();
    let d = load_mesh(&obj).unwrap();
    assert_eq!(d.triangles.len(), 2);
    assert_eq!(d.uvs.len(), 4);
    let m = d.material.unwrap();
    assert_eq!(m.diffuse_texture.as_deref(), Some(tex.as_path()));
    let text = format!(
        "(version: 1, camera: (eye: (0, 30, 0), up: (1, 0, 0), projection: Pinhole(fov: 4.5)),
          render: (width: 32, height: 32, spp: 1, sampler: Regular),
          objects: [(shape: Mesh(path: {:?}), material: Emissive(ce: MeshMaterial(filter: Nearest)))])",
        obj.display().to_string()
    );
    let s = scene(&text, &dir.path().join("p.ron")).unwrap();
    let film = render(&s).to_linear();
    // Top-left: the file's top-left texel.
    let got = film[5 * 32 + 5].to_array();
    let want = texel(0, 0).map(srgb8_to_linear);
    assert!(
        (0..3).all(|c| (got[c] - want[c]).abs() < 1e-3),
        "{got:?} {want:?}"
    );

    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n").unwrap();
    let e = load_mesh(&obj).unwrap_err().to_string();
    assert!(e.contains("quad.obj: line 5"), "{e}");
    // MeshMaterial on a file without a material says so.
    let e = scene(
        &text.replace("quad.obj", "../nope.obj"),
        &dir.path().join("p.ron"),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("nope.obj"), "{e}");
}

/// A mesh hit in a render carries no dp/du, dp/dv (they cost 4% of a pass); a footprint filter
/// gets them when it builds its texture context, equal to the eager ones, and the (u, v)
/// derivatives they give match the (u, v) of the neighbouring pixels' hits.
#[test]
fn mesh_uv_derivatives_come_when_a_footprint_filter_asks_and_match_neighbouring_hits() {
    use texplore::mapping::Mapping;
    let preset = root().join("presets/derivatives.ron");
    let text = r#"(
        version: 1,
        camera: (eye: (-3.2, 5.2, 0), look_at: (0, -0.5, 0), projection: Pinhole(fov: 33)),
        render: (width: 400, height: 300, spp: 1),
        objects: [(
            shape: Mesh(path: "../assets/two-triangles.ply", shading: Flat),
            material: Matte(cd: Image(path: "../assets/chelsea_451x300.png", mapping: Uv, filter: Ewa)),
        )],
    )"#;
    let scene = scene(text, &preset).unwrap();
    assert!(scene.needs_differentials());
    let mut checked = 0;
    for (x, y) in [
        (200.0, 150.0),
        (170.0, 120.0),
        (240.0, 180.0),
        (150.0, 170.0),
    ] {
        let pos = Vec2::new(x + 0.5, y + 0.5);
        let (ray, diff) = scene.camera.ray(pos, 1.0).unwrap();
        let hit = scene
            .hit(&ray)
            .expect("the centre of the view is on the mesh");
        assert!(hit.local.dpduv.is_none(), "the render path left them out");
        let Shape::Mesh(m) = &scene.objects[hit.object].shape else {
            panic!("not the mesh")
        };
        // The object has no transform: the world ray is the object ray.
        let eager = m.mesh.intersect(&ray, f32::INFINITY, m.shading).unwrap();
        assert!(eager.dpduv.is_some());
        assert_eq!(m.mesh.uv_derivatives(hit.local.prim), eager.dpduv);
        let tc = scene
            .texture_context(&hit, Some(&diff))
            .tex_coord(&Mapping::Uv.into());
        let uv_at = |p: Vec2| {
            let h = scene.hit(&scene.camera.primary_ray(p).unwrap())?;
            (h.local.prim == hit.local.prim).then_some(h.local.uv.unwrap())
        };
        let uv = hit.local.uv.unwrap();
        for (step, d) in [(Vec2::X, tc.duvdx), (Vec2::Y, tc.duvdy)] {
            // Centred differences on the same triangle: (u, v) is linear there, so only the
            // perspective's curvature separates them from the derivative.
            let (Some(a), Some(b)) = (uv_at(pos + step), uv_at(pos - step)) else {
                continue;
            };
            let exact = (a - b) * 0.5;
            assert!(exact.length() > 1e-4, "the footprint is not empty");
            assert!(
                (d - exact).length() < 0.02 * exact.length(),
                "pixel ({x}, {y}): d(u, v) {d} against neighbours {exact} (uv {uv})"
            );
            checked += 1;
        }
    }
    assert!(checked >= 6, "only {checked} derivatives compared");
}
