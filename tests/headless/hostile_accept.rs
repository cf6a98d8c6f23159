//! Hostile input, round three (issue 38 §3): what was accepted that should not have been, and
//! messages that named the wrong thing. Exercise targets checked as a preset's checker is;
//! a lesson's edit into a field left at its default; displacement over huge but finite
//! (u, v); `report` options refused before any work; `-o /dev/stdout` into a pipe named as a
//! pipe; formulas that give NaN or infinity warned in every field; `mesh_u` on a mesh without
//! (u, v) refused as `Uv` is; control characters in a formula escaped in the error.

use crate::common::{root, texplore};
use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::{Duration, Instant};
use texplore::geometry::MeshData;
use texplore::lesson::load_lesson;
use texplore::math::{Vec2, Vec3};
use texplore::meshio::{PlyFormat, torus, write_ply};
use texplore::scene::{AssetCache, build_scene, load_preset, parse_preset};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8")
}

/// A lesson on the rectangle preset with `body` (experiments and exercises), in `dir`.
fn lesson(dir: &Path, body: &str) -> PathBuf {
    let preset = root().join("presets/rectangle.ron");
    let text = format!(
        "title = \"Hostile\"\npreset = {:?}\ntext = \"x\"\n\n{body}\n[question]\nask = \"a\"\nanswer = \"b\"\n",
        preset.display().to_string()
    );
    let file = dir.join("hostile.toml");
    std::fs::write(&file, text).expect("write lesson");
    file
}

#[test]
fn an_exercise_target_is_checked_as_a_presets_checker_naming_the_field() {
    let dir = tempfile::tempdir().expect("temp dir");
    let grey = "0.9 - 0.8 * 2 * fract((floor(8 * u) + floor(8 * v)) / 2)";
    let colours = "((0.9, 0.9, 0.9), (0.1, 0.1, 0.1))";
    for (squares, colors, want) in [
        (
            "(0, 0)",
            colours,
            "`target.squares`: (0.0, 0.0) must be positive and at most 1e6",
        ),
        (
            "(NaN, NaN)",
            colours,
            "`target.squares`: (NaN, NaN) must be positive",
        ),
        (
            "(inf, 8)",
            colours,
            "`target.squares`: (inf, 8.0) must be positive",
        ),
        (
            "(1e30, 1e30)",
            colours,
            "`target.squares`: (1e30, 1e30) must be positive and at most 1e6",
        ),
        (
            "(-8, 8)",
            colours,
            "`target.squares`: (-8.0, 8.0) must be positive",
        ),
        (
            "(8, 8)",
            "((NaN, 0.9, 0.9), (0.1, 0.1, 0.1))",
            "`target.colors`: NaN must be finite and not negative",
        ),
        (
            "(8, 8)",
            "((0.9, 0.9, 0.9), (-1, 0.1, 0.1))",
            "`target.colors`: -1 must be finite and not negative",
        ),
    ] {
        let file = lesson(
            dir.path(),
            &format!(
                "[[exercise]]\ntask = \"t\"\ntarget = \"Checker(squares: {squares}, colors: {colors})\"\n\
                 start = {{ grey = \"0\" }}\nsolution = {{ grey = \"{grey}\" }}\n"
            ),
        );
        let e = load_lesson(&file).expect_err(squares).to_string();
        assert!(e.contains("hostile.toml:"), "{e}");
        assert!(e.contains(want), "{squares} {colors}: want {want:?} in {e}");
        assert!(!e.contains("does not solve it"), "{e}");
    }
}

#[test]
fn a_lesson_edit_reaches_a_field_left_at_its_default() {
    let dir = tempfile::tempdir().expect("temp dir");
    let file = lesson(
        dir.path(),
        "[[experiment]]\nlabel = \"Tolerant\"\nlook_for = \"x\"\nset = { \"render.compare.tolerance\" = 3, \"render.view\" = \"Difference\" }\n",
    );
    let l = load_lesson(&file).expect("the lesson loads");
    let base = load_preset(&l.preset).expect("the preset");
    let d = l.scene(0, &base).expect("the experiment applies");
    assert_eq!(d.render.compare.tolerance, 3.0);
    let o = texplore(&["lesson", "--list", "--dir", s(dir.path())]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A name the format does not have is still refused, naming where.
    let file = lesson(
        dir.path(),
        "[[experiment]]\nlabel = \"Typo\"\nlook_for = \"x\"\nset = { \"render.compare.tolerence\" = 3 }\n",
    );
    let e = load_lesson(&file).expect_err("a typo").to_string();
    assert!(
        e.contains("`render.compare` has no field `tolerence` (it has with, tolerance)"),
        "{e}"
    );
}

/// A quad in the y = 0 plane whose (u, v) are `uv` at its corners, as a binary PLY in `dir`.
fn quad(dir: &Path, uv: f32) -> PathBuf {
    let data = MeshData {
        positions: vec![
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(-1.0, 0.0, 1.0),
        ],
        uvs: vec![
            Vec2::new(-uv, -uv),
            Vec2::new(uv, -uv),
            Vec2::new(uv, uv),
            Vec2::new(-uv, uv),
        ],
        normals: vec![Vec3::Y; 4],
        triangles: vec![[0, 2, 1], [0, 3, 2]],
        ..MeshData::default()
    };
    let path = dir.join("huge-uv.ply");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&path).expect("create"));
    write_ply(&mut f, &data, PlyFormat::BinaryLittleEndian).expect("write ply");
    path
}

fn mesh_preset(mesh: &Path, material: &str, extra: &str) -> String {
    format!(
        "(version: 1, camera: (eye: (0, 4, 0.001), projection: Pinhole(fov: 50)),
          render: (width: 16, height: 16, spp: 1),
          ambient: (ls: 0.3), lights: [Directional(direction: (0.3, 1, 0.2))],
          objects: [(name: \"Mesh\", shape: Mesh(path: {:?}, shading: Smooth),
                     material: {material}{extra})])",
        s(mesh)
    )
}

#[test]
fn a_mesh_with_huge_but_finite_uv_is_displaced() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mesh = quad(dir.path(), 3e38);
    let text = mesh_preset(
        &mesh,
        "Matte(cd: Constant((0.8, 0.6, 0.4)))",
        ", displace: (height: Constant((1, 1, 1)), scale: 0.1, subdivide: 2)",
    );
    let at = dir.path().join("p.ron");
    let desc = parse_preset(&text, &at).expect("parses");
    let scene = build_scene(&desc, &at, &mut AssetCache::new())
        .unwrap_or_else(|e| panic!("the four finite vertices displace: {e}"));
    let film = crate::common::render_on(&scene, 1);
    assert!(film.is_finite());
}

fn earth_like(dir: &Path, material: &str, extra: &str) -> PathBuf {
    let text = format!(
        "(version: 1, camera: (eye: (0, 0, 4)),
          render: (width: 24, height: 16, spp: 1),
          ambient: (ls: 0.3), lights: [Directional(direction: (0.3, 1, 0.2))],
          objects: [(name: \"Ball\", shape: Sphere, material: {material}{extra})])"
    );
    let path = dir.join("nan.ron");
    std::fs::write(&path, text).expect("write preset");
    path
}

#[test]
fn formulas_that_give_nan_are_warned_in_every_field() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("out.png");
    let nan = "Formula(grey: \"ln(x - 5)\")";
    let mapping = "Checker(mapping: Formula(u: \"sqrt(y - 5)\", v: \"y\"))";
    for (material, extra, field) in [
        (
            format!("Phong(cd: Constant((0.5, 0.5, 0.5)), ks: {nan})"),
            String::new(),
            "objects[0].material.ks (object \"Ball\"): its formula was NaN or infinite at ",
        ),
        (
            format!("Phong(cd: Constant((0.5, 0.5, 0.5)), exp: {mapping})"),
            String::new(),
            "objects[0].material.exp (object \"Ball\"): its formula was NaN or infinite at ",
        ),
        (
            "Matte(cd: Constant((0.5, 0.5, 0.5)))".to_owned(),
            format!(", bump: (height: {nan}, scale: 0.1)"),
            "objects[0].bump.height (object \"Ball\"): its formula was NaN or infinite at ",
        ),
        (
            format!("Matte(cd: {nan})"),
            String::new(),
            "objects[0].material.cd (object \"Ball\"): its formula was NaN or infinite at ",
        ),
    ] {
        let p = earth_like(dir.path(), &material, &extra);
        let o = texplore(&["render", s(&p), "-o", s(&out)]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(stderr(&o).contains(field), "{field} in {}", stderr(&o));
    }
    // Displacement: counted as the mesh is displaced at load.
    let mut ring = torus(16, 8, 1.0, 0.4);
    ring.uvs.clear();
    let mesh = dir.path().join("torus.ply");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&mesh).expect("create"));
    write_ply(&mut f, &ring, PlyFormat::BinaryLittleEndian).expect("write ply");
    drop(f);
    let p = dir.path().join("displaced.ron");
    let text = mesh_preset(
        &mesh,
        "Matte(cd: Constant((0.5, 0.5, 0.5)))",
        &format!(", displace: (height: {nan}, scale: 0.1, subdivide: 1)"),
    );
    std::fs::write(&p, text).expect("write");
    let o = texplore(&["render", s(&p), "-o", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "objects[0].displace.height (object \"Mesh\"): its formula was NaN or infinite at "
        ) && stderr(&o).contains("vertices, read there as magenta's value"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_formula_reading_mesh_uv_on_a_mesh_without_them_is_refused_as_uv_is() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut ring = torus(16, 8, 1.0, 0.4);
    ring.uvs.clear();
    let mesh = dir.path().join("plain.ply");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&mesh).expect("create"));
    write_ply(&mut f, &ring, PlyFormat::BinaryLittleEndian).expect("write ply");
    drop(f);
    let checker = |u: &str| format!("Checker(mapping: Formula(u: \"{u}\", v: \"y\"))");
    for (material, extra, field) in [
        (
            format!("Matte(cd: {})", checker("mesh_u")),
            String::new(),
            "objects[0].material.cd",
        ),
        (
            format!(
                "Phong(cd: Constant((1, 1, 1)), ks: {})",
                checker("mesh_v * 2")
            ),
            String::new(),
            "objects[0].material.ks",
        ),
        (
            "Matte(cd: Constant((1, 1, 1)))".to_owned(),
            format!(", bump: (height: {}, scale: 0.1)", checker("x + mesh_u")),
            "objects[0].bump.height",
        ),
        (
            "Matte(cd: Constant((1, 1, 1)))".to_owned(),
            format!(", displace: (height: {}, scale: 0.1)", checker("mesh_u")),
            "objects[0].displace.height",
        ),
    ] {
        let p = dir.path().join("p.ron");
        std::fs::write(&p, mesh_preset(&mesh, &material, &extra)).expect("write");
        let o = texplore(&["render", s(&p), "-o", s(&dir.path().join("o.png"))]);
        assert!(!o.status.success(), "{material}{extra}: rendered");
        let e = stderr(&o);
        assert!(
            e.contains(field)
                && e.contains("plain.ply has no texture coordinates for its formula's mesh_u and mesh_v to read"),
            "{field}: {e}"
        );
    }
    // A formula that does not read them is fine there.
    let p = dir.path().join("p.ron");
    std::fs::write(
        &p,
        mesh_preset(&mesh, &format!("Matte(cd: {})", checker("x")), ""),
    )
    .expect("write");
    let o = texplore(&["render", s(&p), "-o", s(&dir.path().join("o.png"))]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_control_character_in_a_formula_is_escaped_in_the_error() {
    let dir = tempfile::tempdir().expect("temp dir");
    for (raw, shown) in [
        ("\u{0}", "`\\0`"),
        ("\u{1b}", "`\\u{1b}`"),
        ("\u{7}", "`\\u{7}`"),
    ] {
        let p = earth_like(
            dir.path(),
            &format!("Matte(cd: Checker(mapping: Formula(u: \"x + {raw}[2J\", v: \"y\")))"),
            "",
        );
        let o = texplore(&["render", s(&p), "-o", s(&dir.path().join("o.png"))]);
        assert!(!o.status.success());
        let e = stderr(&o);
        assert!(
            e.contains(&format!("unexpected character {shown}")),
            "{e:?}"
        );
        assert!(!e.contains(raw), "the raw character is not echoed: {e:?}");
    }
}

#[test]
fn report_refuses_a_reference_file_with_reference_settings_before_any_work() {
    let dir = tempfile::tempdir().expect("temp dir");
    let exr = dir.path().join("ref.exr");
    std::fs::write(&exr, b"not read").expect("write");
    let out = dir.path().join("out");
    for extra in [
        ["--reference-spp", "8"],
        ["--reference-filter", "ewa"],
        ["--reference-sampler", "random"],
    ] {
        let mut args = vec![
            "report",
            "presets/earth.ron",
            "-o",
            s(&out),
            "--reference",
            s(&exr),
        ];
        args.extend(extra);
        let o = texplore(&args);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("cannot be used with") && stderr(&o).contains(extra[0]),
            "{}",
            stderr(&o)
        );
    }
}

#[test]
fn report_refuses_a_cache_under_a_file_or_at_a_dangling_link_before_any_render() {
    let dir = tempfile::tempdir().expect("temp dir");
    let file = dir.path().join("p.ron");
    std::fs::write(&file, b"(x)").expect("write");
    let dangling = dir.path().join("cache-link");
    std::os::unix::fs::symlink(dir.path().join("nowhere"), &dangling).expect("symlink");
    let out = dir.path().join("out");
    for (cache, want) in [
        (file.join("sub"), "p.ron is not a folder".to_owned()),
        (file.join("sub/deeper"), "p.ron is not a folder".to_owned()),
        (
            dangling.clone(),
            format!(
                "it is a symbolic link to {}, which does not exist",
                s(&dir.path().join("nowhere"))
            ),
        ),
        (
            dangling.join("sub"),
            "cache-link is a symbolic link to".to_owned(),
        ),
    ] {
        let start = Instant::now();
        let o = texplore(&[
            "report",
            "presets/earth.ron",
            "-o",
            s(&out),
            "--cache",
            s(&cache),
            "--modes",
            "nearest/jittered",
            "--spp",
            "1",
            "--reference-spp",
            "64",
            "--width",
            "32",
            "--height",
            "16",
        ]);
        assert!(!o.status.success(), "{}", cache.display());
        let e = stderr(&o);
        assert!(
            e.contains("cannot use the reference cache") && e.contains(&want),
            "{}: {e}",
            cache.display()
        );
        assert!(
            !e.contains("reference rendered"),
            "refused before rendering: {e}"
        );
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "{:?}",
            start.elapsed()
        );
    }
}

#[test]
fn an_output_that_is_a_pipe_is_named_a_pipe() {
    let dir = tempfile::tempdir().expect("temp dir");
    let p = earth_like(dir.path(), "Matte(cd: Constant((0.5, 0.5, 0.5)))", "");
    // `output()` gives the child a pipe for its stdout.
    let o = texplore(&["render", s(&p), "-o", "/dev/stdout"]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("it leads to a pipe"), "{e}");
    assert!(!e.contains("does not exist"), "{e}");
}
