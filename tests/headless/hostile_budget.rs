//! One budget for the whole scene (issue 26, section 2): every image a scene reads counts
//! against one texture budget, each file once whatever path spells it; the displaced meshes of
//! a scene share one triangle budget; a clip map's alpha channel goes through the same budget;
//! `lesson --list` checks scenes without decoding their images. Memory cases run the binary
//! under an address-space limit (`RLIMIT_AS`), as `memory.rs` does.
#![cfg(unix)]

use crate::memory::{BASELINE, MIB, grey_png, stderr, texplore_limited};
use std::path::Path;
use texplore::scene::{AssetCache, SceneDesc, build_scene};

/// A preset of one sphere with `object`'s material and maps, rendered at 8 x 8.
fn sphere(object: &str) -> String {
    format!(
        r#"(
    version: 1,
    camera: (eye: (0, 0, 3.6), projection: Pinhole(fov: 40)),
    render: (width: 8, height: 8, spp: 1),
    objects: [(name: "Ball", shape: Sphere, {object})],
)"#
    )
}

/// Renders `preset` (written to `dir/p.ron`) under `limit` bytes of address space.
fn render(dir: &Path, preset: &str, limit: u64) -> std::process::Output {
    std::fs::write(dir.join("p.ron"), preset).unwrap();
    texplore_limited(
        dir,
        &["render", "p.ron", "-o", "out.png", "--threads", "1"],
        limit,
    )
}

/// The bytes of every file in `dir`, by name, to check that a refusal changed none.
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| {
            let e = e.unwrap();
            e.file_type().unwrap().is_file().then(|| {
                (
                    e.file_name().to_string_lossy().into_owned(),
                    std::fs::read(e.path()).unwrap(),
                )
            })
        })
        .collect();
    v.sort();
    v
}

#[test]
fn two_bombs_in_one_material_are_refused_naming_the_second_field() {
    // Two files of 16384^2 grey texels (300 KB each): 1 GiB of sRGB texels each, each within
    // the budget alone; together they took 2.1 GB. The second is refused from its header.
    let dir = tempfile::tempdir().unwrap();
    grey_png(&dir.path().join("a.png"), 16384, 16384);
    std::fs::copy(dir.path().join("a.png"), dir.path().join("b.png")).unwrap();
    let preset = sphere(
        r#"material: Matte(cd: Image(path: "a.png", mapping: Spherical, filter: Nearest),
              kd: (texture: Image(path: "b.png", mapping: Spherical, filter: Nearest), channel: Red))"#,
    );
    std::fs::write(dir.path().join("p.ron"), &preset).unwrap();
    let before = contents(dir.path());
    let out = render(dir.path(), &preset, BASELINE + 1024 * MIB + 64 * MIB);
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{e}");
    assert!(
        e.contains(
            "p.ron: objects[0].material.kd.texture (object \"Ball\"): b.png: cannot load image: "
        ) && e.contains("16384 x 16384 texels need 1.0 GiB as sRGB")
            && e.contains("of the scene's 1.0 GiB texture budget (its other images take 1.0 GiB)"),
        "{e}"
    );
    assert!(!dir.path().join("out.png").exists());
    assert_eq!(contents(dir.path()), before, "a refusal changed a file");
    // The bump map and the colour: the same, naming the bump map's field.
    let preset = sphere(
        r#"material: Matte(cd: Image(path: "a.png", mapping: Spherical, filter: Nearest)),
           bump: (height: Image(path: "b.png", mapping: Spherical, filter: Nearest))"#,
    );
    let out = render(dir.path(), &preset, BASELINE + 1024 * MIB + 64 * MIB);
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{e}");
    assert!(
        e.contains("p.ron: objects[0].bump.height (object \"Ball\"): b.png: cannot load image: ")
            && e.contains("texture budget"),
        "{e}"
    );
}

#[test]
fn a_clip_map_bomb_is_refused_from_its_header() {
    // A grey+alpha PNG of 16384^2 (550 KB): its alpha channel as linear texels would take
    // 3 GiB. It used to be decoded whole and abort on a 3 GiB allocation (11 GB peak).
    let dir = tempfile::tempdir().unwrap();
    grey_alpha_png(&dir.path().join("ga.png"), 16384, 16384);
    let out = render(
        dir.path(),
        &sphere(
            r#"material: Matte(cd: Constant((0.5, 0.5, 0.5))),
               alpha: (texture: Image(path: "ga.png", mapping: Spherical, filter: Nearest), channel: Alpha)"#,
        ),
        BASELINE,
    );
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{e}");
    assert!(
        e.contains("p.ron: objects[0].alpha.texture (object \"Ball\"): ga.png: cannot load image: 16384 x 16384 texels need 3.0 GiB as a linear alpha channel")
            && e.contains("above the 1.0 GiB texture budget"),
        "{e}"
    );
    // A clip map within the budget counts against the scene with the colour: 2048^2 of alpha
    // (48 MiB) and a 16384^2 colour (1 GiB) do not fit together.
    grey_alpha_png(&dir.path().join("small.png"), 2048, 2048);
    grey_png(&dir.path().join("big.png"), 16384, 16384);
    let out = render(
        dir.path(),
        &sphere(
            r#"material: Matte(cd: Image(path: "big.png", mapping: Spherical, filter: Nearest)),
               alpha: (texture: Image(path: "small.png", mapping: Spherical, filter: Nearest), channel: Alpha)"#,
        ),
        BASELINE + 1024 * MIB + 64 * MIB,
    );
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{e}");
    assert!(
        e.contains("objects[0].alpha.texture (object \"Ball\"): small.png: ")
            && e.contains("2048 x 2048 texels need 48.0 MiB as a linear alpha channel"),
        "{e}"
    );
    // Alone, the small clip map renders, and reads its alpha (64 / 255 in every texel here).
    let out = render(
        dir.path(),
        &sphere(
            r#"material: Matte(cd: Constant((0.5, 0.5, 0.5))),
               alpha: (texture: Image(path: "small.png", mapping: Spherical, filter: Nearest), channel: Alpha)"#,
        ),
        BASELINE + 256 * MIB,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let alpha = texplore::texture::load_alpha(&dir.path().join("small.png")).unwrap();
    assert_eq!((alpha.width(), alpha.height()), (2048, 2048));
    assert!((alpha.texel_top(100, 200).0 - 64.0 / 255.0).abs() < 1e-6);
    // A file without alpha is still refused as having none.
    let e = texplore::texture::load_alpha(&dir.path().join("big.png"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("big.png") && e.contains("has no alpha channel"),
        "{e}"
    );
}

/// Writes a `width` x `height` grey+alpha PNG: grey 128, alpha 64 everywhere.
fn grey_alpha_png(path: &Path, width: u32, height: u32) {
    use std::io::Write;
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    let mut enc = png::Encoder::new(file, width, height);
    enc.set_color(png::ColorType::GrayscaleAlpha);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Fastest);
    let mut writer = enc.write_header().unwrap();
    let mut stream = writer.stream_writer().unwrap();
    let row: Vec<u8> = [128u8, 64].repeat(width as usize);
    for _ in 0..height {
        stream.write_all(&row).unwrap();
    }
    stream.finish().unwrap();
}

#[test]
fn one_file_under_many_spellings_is_decoded_once() {
    // The Earth under 200 spellings of its path (`in/earth.jpg`, `in/./earth.jpg`,
    // `in/../in/earth.jpg`, ..., a symbolic and a hard link): one file, decoded once. It was
    // decoded 200 times (1.66 GB, 4.9 s).
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in");
    std::fs::create_dir(&input).unwrap();
    std::fs::copy(
        crate::common::root().join("assets/earth_2048x1024.jpg"),
        input.join("earth.jpg"),
    )
    .unwrap();
    std::os::unix::fs::symlink("earth.jpg", input.join("link.jpg")).unwrap();
    std::fs::hard_link(input.join("earth.jpg"), input.join("hard.jpg")).unwrap();
    let mut spellings: Vec<String> = (0..196)
        .map(|i| match i % 3 {
            0 => format!("in/{}earth.jpg", "./".repeat(i)),
            1 => format!("in/{}../in/earth.jpg", "./".repeat(i)),
            _ => format!("{}/in/earth.jpg", dir.path().display()),
        })
        .collect();
    spellings.extend(
        [
            "in/link.jpg",
            "in/hard.jpg",
            "./in/link.jpg",
            "in/../in/hard.jpg",
        ]
        .map(String::from),
    );
    let objects: Vec<String> = spellings
        .iter()
        .enumerate()
        .map(|(i, p)| {
            format!(
                r#"(shape: Sphere, transform: (translate: ({}, 0, 0)), material: Matte(cd: Image(path: "{p}", mapping: Spherical)))"#,
                3 * i
            )
        })
        .collect();
    let preset = format!(
        "(version: 1, camera: (eye: (0, 0, 3.6)), render: (width: 8, height: 8, spp: 1), objects: [{}])",
        objects.join(", ")
    );
    let desc: SceneDesc = ron::from_str(&preset).unwrap();
    let mut cache = AssetCache::new();
    build_scene(&desc, &dir.path().join("p.ron"), &mut cache).unwrap();
    assert_eq!(cache.image_count(), 1, "one file, one decode");
    // Read as linear too, it is a second image (another storage), not a 201st.
    let mut linear = desc.clone();
    if let texplore::scene::MaterialDesc::Matte { cd, .. } = &mut linear.objects[5].material
        && let texplore::scene::TextureDesc::Image { srgb, .. } = cd
    {
        *srgb = false;
    } else {
        panic!("a Matte with an image");
    }
    build_scene(&linear, &dir.path().join("p.ron"), &mut cache).unwrap();
    assert_eq!(cache.image_count(), 2);
    // The command line under 8 MiB of texels more than the program: 200 copies would take
    // 1.6 GB.
    let out = render(dir.path(), &preset, BASELINE + 64 * MIB);
    assert!(out.status.success(), "{}", stderr(&out));
}

/// A preset of `n` torus knots (6144 triangles each), each displaced `levels` levels with its
/// own scale (`scale` times 1 to n) by the gravel image at `image_scale`.
fn knots_with(n: usize, levels: u32, scale: f32, image_scale: f32) -> SceneDesc {
    let knot = crate::common::root().join("assets/torus-knot.ply");
    let gravel = crate::common::root().join("assets/gravel_gray_512.png");
    let objects: Vec<String> = (0..n)
        .map(|i| {
            format!(
                r#"(name: "Knot {i}", shape: Mesh(path: "{}"), material: Matte(cd: Constant((0.5, 0.5, 0.5))),
                   displace: (height: Image(path: "{}", mapping: Uv, scale: {image_scale:e}), scale: {:e}, subdivide: {levels}))"#,
                knot.display(),
                gravel.display(),
                scale * (i + 1) as f32
            )
        })
        .collect();
    ron::from_str(&format!(
        "(version: 1, camera: (eye: (0, 0, 6)), render: (width: 8, height: 8, spp: 1), objects: [{}])",
        objects.join(", ")
    ))
    .unwrap()
}

fn knots(n: usize, levels: u32) -> SceneDesc {
    knots_with(n, levels, 0.01, 1.0)
}

#[test]
fn the_displaced_meshes_of_a_scene_share_one_triangle_budget() {
    // Eight knots of 1.57 M triangles each (within the 4 M cap of one object): 12.6 M together,
    // 2.5 GB and 44 s before. The third crosses the scene's 4 M and is named.
    let dir = tempfile::tempdir().unwrap();
    let desc = knots(8, 4);
    let Err(e) = build_scene(&desc, &dir.path().join("p.ron"), &mut AssetCache::new()) else {
        panic!("eight displaced knots are accepted");
    };
    let e = e.to_string();
    assert!(
        e.contains("p.ron: objects[2].displace.subdivide (object \"Knot 2\"): 4 levels of the 6144 triangles in ")
            && e.contains("make 1572864 triangles, and the scene's other displaced meshes hold 3145728: 4718592 in all, above the 4194304 (4 M) a scene may hold"),
        "{e}"
    );
    // One displacement shared by several objects is one mesh, counted once.
    let mut shared = knots(1, 4);
    for _ in 0..3 {
        shared.objects.push(shared.objects[0].clone());
    }
    build_scene(&shared, &dir.path().join("p.ron"), &mut AssetCache::new())
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_displacement_that_overflows_names_its_scale_not_the_mesh_file() {
    let dir = tempfile::tempdir().unwrap();
    // Heights up to 1e38 (the image's scale) times 1e6: beyond f32. It was blamed on the file,
    // "torus-knot.ply: vertex 0: position is not finite".
    let desc = knots_with(1, 1, 1e6, 1e38);
    let Err(e) = build_scene(&desc, &dir.path().join("p.ron"), &mut AssetCache::new()) else {
        panic!("an overflowing displacement is accepted");
    };
    let e = e.to_string();
    assert!(
        e.starts_with(&format!(
            "{}: objects[0].displace.scale (object \"Knot 0\"): 1000000 times the height texture's values",
            dir.path().join("p.ron").display()
        )) && e.contains("beyond the largest finite coordinate"),
        "{e}"
    );
    assert!(
        !e.contains("torus-knot.ply") && !e.contains("vertex"),
        "{e}"
    );
}

#[test]
fn lesson_list_checks_experiments_without_decoding_their_images() {
    // Three experiments, each pointing the Earth's colour at a different 16384^2 file (1 GiB of
    // texels each): listing kept all three (3.7 GB). Now it reads their headers only.
    let dir = tempfile::tempdir().unwrap();
    let lessons = dir.path().join("lessons");
    std::fs::create_dir(&lessons).unwrap();
    grey_png(&lessons.join("a.png"), 16384, 16384);
    for name in ["b.png", "c.png"] {
        std::fs::copy(lessons.join("a.png"), lessons.join(name)).unwrap();
    }
    std::fs::copy(
        crate::common::root().join("assets/earth_2048x1024.jpg"),
        lessons.join("earth.jpg"),
    )
    .unwrap();
    std::fs::write(
        lessons.join("p.ron"),
        r#"(version: 1, camera: (eye: (0, 0, 3.6)), objects: [(shape: Sphere, material: Matte(cd: Image(path: "earth.jpg", mapping: Spherical)))])"#,
    )
    .unwrap();
    let experiments: Vec<String> = ["a", "b", "c"]
        .iter()
        .map(|x| {
            format!(
                "[[experiment]]\nlabel = \"{x}\"\nlook_for = \"grey\"\nset = {{ \"objects[0].material.cd.path\" = '\"{x}.png\"' }}\n\n"
            )
        })
        .collect();
    let experiments = experiments.concat();
    std::fs::write(
        lessons.join("01-bombs.toml"),
        format!(
            "title = \"Three bombs\"\npreset = \"p.ron\"\ntext = \"t\"\n\n{experiments}[question]\nask = \"q\"\nanswer = \"a\"\n"
        ),
    )
    .unwrap();
    let before = contents(&lessons);
    let out = texplore_limited(
        dir.path(),
        &["lesson", "--list", "--dir", "lessons"],
        BASELINE + 256 * MIB,
    );
    let (o, e) = (String::from_utf8_lossy(&out.stdout), stderr(&out));
    assert!(out.status.success(), "{o}{e}");
    assert!(
        o.starts_with("01-bombs") && o.contains("Three bombs"),
        "{o}{e}"
    );
    assert_eq!(contents(&lessons), before);
    // An experiment whose scene is above the budget is still refused, from the headers: the
    // colour and a kd of two of the files.
    let two = "[[experiment]]\nlabel = \"two\"\nlook_for = \"x\"\nset = { \"objects[0].material.cd.path\" = '\"a.png\"', \"objects[0].material.kd\" = '(texture: Image(path: \"b.png\", mapping: Spherical), channel: Red)' }\n\n";
    std::fs::write(
        lessons.join("02-over.toml"),
        format!(
            "title = \"Over\"\npreset = \"p.ron\"\ntext = \"t\"\n\n{two}[question]\nask = \"q\"\nanswer = \"a\"\n"
        ),
    )
    .unwrap();
    let out = texplore_limited(
        dir.path(),
        &["lesson", "--list", "--dir", "lessons"],
        BASELINE + 256 * MIB,
    );
    let (o, e) = (String::from_utf8_lossy(&out.stdout), stderr(&out));
    assert!(o.starts_with("01-bombs"), "{o}{e}");
    assert!(
        e.contains("02-over.toml")
            && e.contains("objects[0].material.kd.texture: lessons/b.png")
            && e.contains("texture budget"),
        "{e}"
    );
}

#[test]
fn lesson_list_counts_displacements_without_subdividing() {
    // Five experiments displacing the torus knot at 4 levels (1.57 M triangles, about 290 MB
    // each while built, four kept): listing took 1.8 GB and 21 s. Now each is counted, not made.
    let dir = tempfile::tempdir().unwrap();
    let lessons = dir.path().join("lessons");
    std::fs::create_dir(&lessons).unwrap();
    let desc = knots(1, 1);
    std::fs::write(lessons.join("knot.ron"), texplore::scene::to_ron(&desc)).unwrap();
    let experiments: Vec<String> = (1..=5)
        .map(|i| {
            format!(
                "[[experiment]]\nlabel = \"level 4, scale {i}\"\nlook_for = \"lumps\"\nset = {{ \"objects[0].displace.subdivide\" = \"4\", \"objects[0].displace.scale\" = \"0.0{i}5\" }}\n\n"
            )
        })
        .collect();
    // A sixth adds a second knot of 4 levels: 3.1 M triangles, within the scene's 4 M; a
    // seventh a third, above it, which is refused from the counts alone.
    let second = ron::to_string(&desc.objects[0])
        .unwrap()
        .replace("subdivide:1", "subdivide:4");
    let add = |label: &str, objects: usize| {
        format!(
            "[[experiment]]\nlabel = \"{label}\"\nlook_for = \"x\"\nset = {{ \"objects\" = '[{}]' }}\n\n",
            vec![second.clone(); objects]
                .iter()
                .enumerate()
                .map(|(i, o)| o.replace("scale:0.01", &format!("scale:0.0{}", i + 1)))
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    let ok = format!("{}{}", experiments.concat(), add("two knots", 2));
    let lesson = |body: &str| {
        format!(
            "title = \"Knots\"\npreset = \"knot.ron\"\ntext = \"t\"\n\n{body}[question]\nask = \"q\"\nanswer = \"a\"\n"
        )
    };
    std::fs::write(lessons.join("01-knots.toml"), lesson(&ok)).unwrap();
    std::fs::write(
        lessons.join("02-three.toml"),
        lesson(&add("three knots", 3)),
    )
    .unwrap();
    let out = texplore_limited(
        dir.path(),
        &["lesson", "--list", "--dir", "lessons"],
        BASELINE + 256 * MIB,
    );
    let (o, e) = (String::from_utf8_lossy(&out.stdout), stderr(&out));
    assert!(o.starts_with("01-knots") && o.contains("Knots"), "{o}{e}");
    assert!(
        e.contains("02-three.toml")
            && e.contains("objects[2].displace.subdivide (object \"Knot 0\"): 4 levels")
            && e.contains("4718592 in all"),
        "{o}{e}"
    );
}

#[test]
fn a_command_going_through_scenes_does_not_keep_every_image_it_met() {
    // `snapshot update` of three presets, each reading its own 16384^2 file (1 GiB of texels),
    // through one cache: it kept all three (3 GiB). Now the cache keeps, beside a scene's own
    // images, no more than the scene budget of others.
    let dir = tempfile::tempdir().unwrap();
    let presets = dir.path().join("presets");
    std::fs::create_dir(&presets).unwrap();
    grey_png(&presets.join("a.png"), 16384, 16384);
    for x in ["a", "b", "c"] {
        if x != "a" {
            std::fs::copy(presets.join("a.png"), presets.join(format!("{x}.png"))).unwrap();
        }
        let preset = sphere(&format!(
            r#"material: Matte(cd: Image(path: "{x}.png", mapping: Spherical, filter: Nearest))"#
        ))
        .replace(
            "render:",
            "snapshot: (width: 8, height: 8, spp: 1), render:",
        );
        std::fs::write(presets.join(format!("{x}.ron")), preset).unwrap();
    }
    let out = texplore_limited(
        dir.path(),
        &[
            "snapshot",
            "update",
            "--presets",
            "presets",
            "--screenshots",
            "shots",
        ],
        BASELINE + 2048 * MIB + 128 * MIB,
    );
    let (o, e) = (String::from_utf8_lossy(&out.stdout), stderr(&out));
    assert!(out.status.success(), "{o}{e}");
    for x in ["a", "b", "c"] {
        assert!(dir.path().join(format!("shots/{x}.png")).is_file(), "{o}");
    }
}
