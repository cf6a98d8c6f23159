//! Every preset loads, builds and renders without NaN; renders are deterministic whatever the
//! thread count; a bad preset names the file and the position where parsing stopped.

use crate::common::{build_with, render_on, root, sized};
use std::path::{Path, PathBuf};
use texplore::Error;
use texplore::render::Film;
use texplore::scene::{AssetCache, build_scene, list_presets, load_preset, parse_preset};

fn presets() -> Vec<PathBuf> {
    list_presets(&root().join("presets")).unwrap()
}

fn render(path: &Path, w: u32, h: u32, spp: u32, threads: usize) -> Film {
    let desc = load_preset(path).unwrap();
    let scene = build_with(&desc, path, sized(w, h, spp), &mut AssetCache::new());
    render_on(&scene, threads)
}

#[test]
fn every_preset_renders_finite_and_not_black() {
    for p in presets() {
        let film = render(&p, 64, 48, 2, 0);
        assert!(film.is_finite(), "{} has NaN or Inf", p.display());
        let lit = film
            .to_linear()
            .iter()
            .filter(|c| c.max_channel() > 0.01)
            .count();
        assert!(
            lit > 64 * 48 / 10,
            "{} is almost black ({lit} lit pixels)",
            p.display()
        );
    }
}

#[test]
fn one_and_two_threads_give_the_same_image() {
    for name in ["earth", "checker", "light-probe"] {
        let p = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("presets/{name}.ron"));
        let a = render(&p, 96, 64, 3, 1);
        let b = render(&p, 96, 64, 3, 2);
        assert!(a == b, "{name}: 1- and 2-thread renders differ");
    }
}

#[test]
fn a_typo_names_the_file_line_and_field() {
    let text = "(\n    version: 1,\n    camera: (eye: (0, 0, 5)),\n    objects: [\n        (shape: Sphere, material: Matte(kdd: 0.5, cd: Constant((1, 1, 1)))),\n    ],\n)\n";
    let err = parse_preset(text, Path::new("presets/typo.ron")).unwrap_err();
    let msg = err.to_string();
    assert!(matches!(err, Error::Preset { line: 5, .. }), "{msg}");
    assert!(msg.starts_with("presets/typo.ron:5:"), "{msg}");
    assert!(msg.contains("kdd"), "{msg}");
}

#[test]
fn wrong_types_and_versions_are_refused() {
    let wrong = "(version: 1, camera: (eye: \"here\"), objects: [])";
    assert!(matches!(
        parse_preset(wrong, Path::new("w.ron")),
        Err(Error::Preset { line: 1, .. })
    ));
    let future = "(version: 99, camera: (eye: (0, 0, 5)), objects: [])";
    let e = parse_preset(future, Path::new("f.ron"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("version 99"), "{e}");
}

#[test]
fn absurd_values_are_refused_with_the_field_named() {
    let base = "(version: 1, camera: (eye: (0, 0, 5)), render: RENDER, objects: [(shape: Sphere, transform: TRANSFORM, material: Matte(cd: Constant((1, 1, 1))))])";
    let cases = [
        ("(spp: 0)", "()", "render.spp"),
        ("(width: 1000000000)", "()", "resolution"),
        ("()", "(scale: (0, 1, 1))", "scale"),
        ("()", "(scale: (-1, 1, 1))", ""),
        ("(exposure: 1e30)", "()", "exposure"),
    ];
    for (render, transform, needle) in cases {
        let text = base
            .replace("RENDER", render)
            .replace("TRANSFORM", transform);
        let desc = parse_preset(&text, Path::new("bad.ron")).unwrap();
        let result = build_scene(&desc, Path::new("bad.ron"), &mut AssetCache::new());
        if needle.is_empty() {
            // A negative scale mirrors the object: allowed.
            result.unwrap_or_else(|e| panic!("transform {transform} (a mirror) must build: {e}"));
            continue;
        }
        let e = result.unwrap_err().to_string();
        assert!(
            e.starts_with("bad.ron: ") && e.contains(needle),
            "{render} {transform}: {e}"
        );
    }
}

#[test]
fn a_missing_image_names_the_file() {
    let text = "(version: 1, camera: (eye: (0, 0, 5)), objects: [(shape: Sphere, material: Matte(cd: Image(path: \"nope.png\")))])";
    let desc = parse_preset(text, Path::new("dir/p.ron")).unwrap();
    let e = build_scene(&desc, Path::new("dir/p.ron"), &mut AssetCache::new())
        .unwrap_err()
        .to_string();
    assert!(e.contains("nope.png"), "{e}");
}

#[test]
fn presets_round_trip_through_ron() {
    for p in presets() {
        let desc = load_preset(&p).unwrap();
        let text = texplore::scene::to_ron(&desc);
        let back = parse_preset(&text, &p).unwrap();
        assert_eq!(desc, back, "{}", p.display());
    }
}

/// Saves go through a temporary file and a rename: the result is complete, nothing is left
/// beside it, and a save that fails leaves the file the user had untouched.
#[test]
fn saves_are_atomic_and_a_failed_save_keeps_the_old_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mine.ron");
    let desc = load_preset(&presets()[0]).unwrap();
    texplore::scene::save_preset(&desc, &path).unwrap();
    let first = std::fs::read_to_string(&path).unwrap();
    assert_eq!(parse_preset(&first, &path).unwrap(), desc);
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.file_name())
        .filter(|n| n != "mine.ron")
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    // The save is refused (the file is read-only): the file is kept, nothing is left beside it.
    let mut perms = std::fs::metadata(&path).unwrap().permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(&path, perms).unwrap();
    let mut other = desc.clone();
    other.render.spp += 1;
    let e = texplore::scene::save_preset(&other, &path).unwrap_err();
    assert!(
        e.to_string().starts_with("cannot write ") && e.to_string().contains("mine.ron"),
        "{e}"
    );
    assert_eq!(std::fs::read_to_string(&path).unwrap(), first);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    // A preset file of absurd size is refused before it is read.
    let huge = dir.path().join("huge.ron");
    let f = std::fs::File::create(&huge).unwrap();
    f.set_len(1 << 30).unwrap();
    let e = load_preset(&huge).unwrap_err().to_string();
    assert!(e.contains("huge.ron") && e.contains("too large"), "{e}");
}

/// The error building a scene whose one object is `(name: "Ball", OBJECT)`, with the preset
/// at `dir/p.ron`.
fn build_error(dir: &Path, object: &str) -> String {
    let text =
        format!("(version: 1, camera: (eye: (0, 0, 3.6)), objects: [(name: \"Ball\", {object})])");
    let preset = dir.join("p.ron");
    let desc = parse_preset(&text, &preset).expect("parses");
    match build_scene(&desc, &preset, &mut AssetCache::new()) {
        Ok(_) => panic!("{text} built"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_missing_or_empty_asset_path_names_the_preset_the_object_and_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let p = d.join("p.ron").display().to_string();
    // Empty: it used to read the preset's folder ("/tmp/x/: not a regular file (a directory)").
    let e = build_error(d, r#"shape: Sphere, material: Matte(cd: Image(path: ""))"#);
    assert_eq!(
        e,
        format!("{p}: objects[0].material.cd.path (object \"Ball\"): is empty: name an image file")
    );
    let e = build_error(
        d,
        r#"shape: Mesh(path: ""), material: Matte(cd: Constant((1, 1, 1)))"#,
    );
    assert!(
        e.starts_with(&format!(
            "{p}: objects[0].shape.path (object \"Ball\"): is empty: name a PLY or OBJ file"
        )),
        "{e}"
    );
    let e = build_error(
        d,
        r#"shape: Sphere, material: Matte(cd: Constant((1, 1, 1))), alpha: (texture: Image(path: ""), channel: Alpha)"#,
    );
    assert!(
        e.starts_with(&format!(
            "{p}: objects[0].alpha.texture.path (object \"Ball\"): is empty"
        )),
        "{e}"
    );
    // Missing: the preset and the field first, then the file's own error.
    let e = build_error(
        d,
        r#"shape: Sphere, material: Phong(cd: Constant((1, 1, 1)), ks: Image(path: "gone.png"))"#,
    );
    assert!(
        e.starts_with(&format!("{p}: objects[0].material.ks (object \"Ball\"): "))
            && e.contains("gone.png"),
        "{e}"
    );
    let e = build_error(
        d,
        r#"shape: Sphere, material: Matte(cd: Image(path: "gone.png"))"#,
    );
    assert!(
        e.starts_with(&format!("{p}: objects[0].material.cd (object \"Ball\"): "))
            && e.contains("gone.png: No such file"),
        "{e}"
    );
    let e = build_error(
        d,
        r#"shape: Sphere, material: Matte(cd: Constant((1, 1, 1))), bump: (height: Image(path: "gone.png"))"#,
    );
    assert!(
        e.starts_with(&format!("{p}: objects[0].bump.height (object \"Ball\"): "))
            && e.contains("gone.png: No such file"),
        "{e}"
    );
    let e = build_error(
        d,
        r#"shape: Mesh(path: "gone.ply"), material: Matte(cd: Constant((1, 1, 1)))"#,
    );
    assert!(
        e.starts_with(&format!("{p}: objects[0].shape (object \"Ball\"): "))
            && e.contains("gone.ply"),
        "{e}"
    );
}
