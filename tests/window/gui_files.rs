//! The window's file paths, headless (egui_kittest on the real app, as in `tests/window/gui.rs`): the
//! path fields show the scene's own paths after "Save as" and after opening a screenshot,
//! Shape -> Mesh asks for the file before it changes the shape, and switching a texture away
//! from Image and back keeps the image.

use crate::gui_common::{choose, harness, settle};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use std::path::{Path, PathBuf};
use texplore::gui::ExplorerApp;
use texplore::names::Named;
use texplore::scene::{
    SceneDesc, ShapeDesc, ShapeKind, TextureDesc, TextureKind, load_preset, save_preset,
};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The Earth preset at 96 x 72 and 2 spp, with object 0's texture the copy of `image` (from
/// assets/) put in `dir/assets/`, written as `dir/presets/<name>.ron`: the image path is
/// `../assets/<image>`, as in the built-in presets.
fn small_preset(dir: &Path, name: &str, image: &str) -> PathBuf {
    let mut desc = load_preset(&root().join("presets/earth.ron")).expect("earth preset");
    desc.render.width = 96;
    desc.render.height = 72;
    desc.render.spp = 2;
    std::fs::create_dir_all(dir.join("assets")).expect("assets dir");
    std::fs::create_dir_all(dir.join("presets")).expect("presets dir");
    std::fs::copy(
        root().join("assets").join(image),
        dir.join("assets").join(image),
    )
    .expect("copy image");
    if let TextureDesc::Image { path, .. } = desc.objects[0].material.texture_mut() {
        *path = format!("../assets/{image}");
    }
    let path = dir.join("presets").join(format!("{name}.ron"));
    save_preset(&desc, &path).expect("write preset");
    path
}

/// `desc` at 96 x 72 and 2 spp written as `dir/presets/<name>.ron`.
fn write_small(dir: &Path, name: &str, mut desc: SceneDesc) -> PathBuf {
    desc.render.width = 96;
    desc.render.height = 72;
    desc.render.spp = 2;
    std::fs::create_dir_all(dir.join("presets")).expect("presets dir");
    let path = dir.join("presets").join(format!("{name}.ron"));
    save_preset(&desc, &path).expect("write preset");
    path
}

/// Copies assets/torus-knot.ply to `dir/assets/` and returns the copy.
fn copy_knot(dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir.join("assets")).expect("assets dir");
    let to = dir.join("assets/torus-knot.ply");
    std::fs::copy(root().join("assets/torus-knot.ply"), &to).expect("copy mesh");
    to
}

/// What the text field labelled `label` shows.
fn field(h: &Harness<'_, ExplorerApp>, label: &str) -> String {
    h.get_by_role_and_label(Role::TextInput, label)
        .value()
        .unwrap_or_default()
}

fn has_field(h: &Harness<'_, ExplorerApp>, label: &str) -> bool {
    h.query_all_by_role_and_label(Role::TextInput, label)
        .next()
        .is_some()
}

/// File > Open..., type `path`, Open.
fn open(h: &mut Harness<'_, ExplorerApp>, path: &Path) {
    h.get_by_label("File").click();
    h.run_steps(3);
    h.get_by_label("Open…").click();
    h.run_steps(3);
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&path.display().to_string());
    h.step();
    h.get_by_label("Open").click();
    settle(h);
}

fn image_path(app: &ExplorerApp) -> Option<String> {
    match app.desc()?.objects[0].material.texture() {
        TextureDesc::Image { path, .. } => Some(path.clone()),
        _ => None,
    }
}

fn image_bytes(app: &ExplorerApp) -> Vec<u8> {
    app.image().expect("an image").rgba.clone()
}

#[test]
fn the_mesh_field_shows_the_rebased_path_after_save_as_into_another_folder() {
    let dir = tempfile::tempdir().expect("temp dir");
    copy_knot(dir.path());
    let mut desc = load_preset(&root().join("presets/earth.ron")).expect("earth preset");
    desc.objects[0].shape = ShapeDesc::Mesh {
        path: "../assets/torus-knot.ply".into(),
        shading: texplore::geometry::Shading::default(),
    };
    *desc.objects[0].material.texture_mut() = TextureKind::UvGrid.default_desc();
    let knot = write_small(dir.path(), "knot", desc);
    let mut h = harness(knot);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(field(&h, "mesh file"), "../assets/torus-knot.ply");

    // File > Save as..., a folder two levels down, Save.
    let deeper = dir.path().join("elsewhere/deeper");
    std::fs::create_dir_all(&deeper).expect("folder");
    let saved = deeper.join("knot.ron");
    h.get_by_label("File").click();
    h.run_steps(3);
    h.get_by_label("Save as…").click();
    h.run_steps(3);
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&saved.display().to_string());
    h.step();
    h.get_by_label("Save").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(h.state().path(), saved);

    // The field shows the path the saved preset holds, and that path loads from there.
    let ShapeDesc::Mesh { path, .. } = &h.state().desc().expect("scene").objects[0].shape else {
        panic!("the object is still a mesh");
    };
    let path = path.clone();
    assert_eq!(path, "../../assets/torus-knot.ply");
    assert_eq!(field(&h, "mesh file"), path);
    let on_disk = load_preset(&saved).expect("saved preset");
    assert!(matches!(&on_disk.objects[0].shape, ShapeDesc::Mesh { path: p, .. } if *p == path));
    h.get_by_label("Load").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert!(
        !h.state().is_dirty(),
        "Load on the shown path changes nothing"
    );
}

#[test]
fn the_image_field_shows_the_opened_scenes_image_after_a_screenshot_and_other_presets() {
    let dir = tempfile::tempdir().expect("temp dir");
    let earth = small_preset(dir.path(), "earth", "earth_2048x1024.jpg");
    let mut h = harness(earth);
    assert_eq!(field(&h, "image"), "../assets/earth_2048x1024.jpg");

    // A screenshot in another folder holds the scene with paths relative to itself.
    let shots = dir.path().join("shots/deeper");
    std::fs::create_dir_all(&shots).expect("folder");
    let png = shots.join("shot.png");
    h.state().save_screenshot(&png).expect("screenshot");
    open(&mut h, &png);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(h.state().path(), png);
    assert_eq!(
        image_path(h.state()).as_deref(),
        Some("../../assets/earth_2048x1024.jpg")
    );
    assert_eq!(field(&h, "image"), "../../assets/earth_2048x1024.jpg");

    // Half-typed text is about the scene it was typed in: five other presets each show their
    // own image (or no image field at all).
    h.get_by_role_and_label(Role::TextInput, "image")
        .set_text_value_accesskit("typo-never-loaded.png");
    h.step();
    let mut checker = load_preset(&root().join("presets/earth.ron")).expect("earth preset");
    *checker.objects[0].material.texture_mut() = TextureKind::Checker.default_desc();
    let others = [
        small_preset(dir.path(), "cat", "chelsea_451x300.png"),
        small_preset(dir.path(), "coffee", "coffee_600x400.png"),
        write_small(dir.path(), "checker", checker),
        small_preset(dir.path(), "grid", "checker_512.png"),
        small_preset(dir.path(), "label", "soup-can-label.png"),
    ];
    for p in &others {
        open(&mut h, p);
        assert!(h.state().error().is_none(), "{:?}", h.state().error());
        assert_eq!(h.state().path(), p.as_path());
        match image_path(h.state()) {
            Some(image) => assert_eq!(field(&h, "image"), image, "{}", p.display()),
            None => assert!(!has_field(&h, "image"), "{}", p.display()),
        }
    }
}

#[test]
fn choosing_mesh_asks_for_the_file_and_keeps_the_shape_until_one_loads() {
    let dir = tempfile::tempdir().expect("temp dir");
    let knot = copy_knot(dir.path());
    let mut desc = load_preset(&root().join("presets/earth.ron")).expect("earth preset");
    *desc.objects[0].material.texture_mut() = TextureKind::Checker.default_desc();
    let preset = write_small(dir.path(), "sphere", desc);
    let mut h = harness(preset);
    let before = h.state().desc().cloned().expect("scene");
    let shown = image_bytes(h.state());
    assert!(matches!(before.objects[0].shape, ShapeDesc::Sphere));

    // Shape -> Mesh: a question, the sphere still there and still rendered.
    choose(&mut h, "Shape", ShapeKind::Mesh.name());
    assert!(
        h.query_all_by_label_contains("Which mesh?")
            .next()
            .is_some(),
        "the panel asks for the file"
    );
    assert_eq!(h.state().desc(), Some(&before));
    assert_eq!(image_bytes(h.state()), shown);
    assert_eq!(field(&h, "mesh file"), "");

    // A file that is not there: the message names it, the sphere stays, the question stays.
    h.get_by_role_and_label(Role::TextInput, "mesh file")
        .set_text_value_accesskit("../assets/no-such-mesh.ply");
    h.step();
    h.get_by_label("Load").click();
    settle(&mut h);
    let err = h.state().error().expect("an error").to_owned();
    assert!(err.contains("no-such-mesh.ply"), "{err}");
    assert_eq!(h.state().desc(), Some(&before));
    assert_eq!(image_bytes(h.state()), shown);
    assert!(
        h.query_all_by_label_contains("Which mesh?")
            .next()
            .is_some()
    );

    // Cancel: the sphere, no question.
    h.get_by_label("Cancel").click();
    settle(&mut h);
    assert!(
        h.query_all_by_label_contains("Which mesh?")
            .next()
            .is_none()
    );
    assert_eq!(h.state().desc(), Some(&before));
    assert!(!has_field(&h, "mesh file"));

    // Again, with the knot: now the object is that mesh and the image changes.
    choose(&mut h, "Shape", ShapeKind::Mesh.name());
    h.get_by_role_and_label(Role::TextInput, "mesh file")
        .set_text_value_accesskit("../assets/torus-knot.ply");
    h.step();
    h.get_by_label("Load").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert!(knot.exists());
    assert!(matches!(
        &h.state().desc().expect("scene").objects[0].shape,
        ShapeDesc::Mesh { path, .. } if path == "../assets/torus-knot.ply"
    ));
    assert!(
        h.query_all_by_label_contains("Which mesh?")
            .next()
            .is_none()
    );
    assert_eq!(field(&h, "mesh file"), "../assets/torus-knot.ply");
    assert_ne!(image_bytes(h.state()), shown);
}

#[test]
fn image_to_constant_and_back_keeps_the_chosen_image() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = small_preset(dir.path(), "cat", "chelsea_451x300.png");
    let mut h = harness(preset);
    // Settings of the image's own that a fresh image texture would not have.
    choose(&mut h, "Wrap", texplore::texture::Wrap::Mirror.name());
    let image = h.state().desc().expect("scene").objects[0]
        .material
        .texture()
        .clone();
    let shown = image_bytes(h.state());

    choose(&mut h, "Texture", TextureKind::Constant.name());
    assert!(!has_field(&h, "image"));
    assert_ne!(image_bytes(h.state()), shown);

    choose(&mut h, "Texture", TextureKind::Image.name());
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(
        h.state().desc().expect("scene").objects[0]
            .material
            .texture(),
        &image,
        "the same file, wrap, filter and mapping"
    );
    assert_eq!(field(&h, "image"), "../assets/chelsea_451x300.png");
    assert_eq!(image_bytes(h.state()), shown);
}
