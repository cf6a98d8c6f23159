//! The window, headless: `egui_kittest` drives the real app and renders it with wgpu (Mesa's
//! lavapipe on a machine without a GPU). Small renders keep these quick.

use crate::gui_common::{WINDOW, harness, settle, small_earth};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use strum::VariantArray;
use texplore::gui::ExplorerApp;
use texplore::mapping::Mapping;
use texplore::names::Named;
use texplore::sampler::PixelSampler;
use texplore::scene::{LightKind, MaterialKind, ProjectionKind, ShapeKind, TextureKind};
use texplore::texture::{Filter, Lookup, View, Wrap};

/// Picks the cylindrical mapping in the texture's combo box, as a user would, and lets the
/// render finish.
fn choose_cylindrical_mapping(h: &mut Harness<'_, ExplorerApp>) {
    h.get_by_role_and_label(Role::ComboBox, "Mapping").click();
    h.run_steps(3);
    h.get_by_label("cylindrical").click();
    settle(h);
}

fn texture_mapping(app: &ExplorerApp) -> Option<Mapping> {
    app.desc()?.objects[0]
        .material
        .texture()
        .mapping()
        .and_then(texplore::scene::MappingDesc::builtin)
}

fn image_bytes(app: &ExplorerApp) -> Vec<u8> {
    app.image().expect("an image").rgba.clone()
}

#[test]
fn main_window_snapshot() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    // The status line holds timings, which differ from run to run.
    let status = h.get_by_label_contains("ms/pass").rect();
    h.mask(egui::Rect::from_min_max(
        egui::pos2(0.0, status.top() - 2.0),
        egui::pos2(WINDOW[0], WINDOW[1]),
    ));
    // Compared within kittest.toml's tolerance (threshold 1.5, at most 24 pixels): a lavapipe
    // or wgpu update passes, two swapped letters in one button (35 pixels) fail.
    h.snapshot("main_window");
}

#[test]
fn choosing_another_mapping_rerenders_and_changes_the_image() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    assert_eq!(texture_mapping(h.state()), Some(Mapping::Spherical));
    let before = image_bytes(h.state());
    choose_cylindrical_mapping(&mut h);
    assert_eq!(texture_mapping(h.state()), Some(Mapping::Cylindrical));
    let after = image_bytes(h.state());
    assert_eq!(before.len(), after.len());
    let differing = before
        .chunks(4)
        .zip(after.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    // The Earth covers about a third of the frame; the cylindrical map moves most of it.
    assert!(
        differing > 160 * 120 / 10,
        "only {differing} pixels changed"
    );
    assert!(h.state().is_dirty());
}

#[test]
fn opening_a_corrupt_image_shows_an_error_and_keeps_the_scene() {
    let dir = tempfile::tempdir().expect("temp dir");
    let corrupt = dir.path().join("corrupt.jpg");
    std::fs::write(&corrupt, b"\xFF\xD8\xFF\xE0 this is not a JPEG").expect("write");
    let mut h = harness(small_earth(dir.path()));
    let desc_before = h.state().desc().cloned();
    let image_before = image_bytes(h.state());

    let field = h.get_by_role_and_label(Role::TextInput, "image");
    field.focus();
    h.step();
    h.get_by_role_and_label(Role::TextInput, "image")
        .set_text_value_accesskit("corrupt.jpg");
    h.step();
    h.get_by_label("Load").click();
    settle(&mut h);

    let err = h.state().error().expect("an error is shown").to_owned();
    assert!(err.contains("corrupt.jpg"), "{err}");
    // The message is in the window, not only in the state.
    assert!(
        h.query_all_by_label_contains("corrupt.jpg")
            .next()
            .is_some()
    );
    assert_eq!(h.state().desc().cloned(), desc_before, "the scene stays");
    assert_eq!(image_bytes(h.state()), image_before, "the render stays");
}

#[test]
fn saving_then_reopening_a_screenshot_restores_the_preset() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    // An edit, so the screenshot holds something the preset file does not.
    choose_cylindrical_mapping(&mut h);
    let shown = image_bytes(h.state());
    let desc = h.state().desc().cloned().expect("scene");

    // File > Save screenshot..., type the path, Save.
    let png = dir.path().join("shot.png");
    h.get_by_label("File").click();
    h.run_steps(3);
    h.get_by_label("Save screenshot…").click();
    h.run_steps(3);
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&png.display().to_string());
    h.step();
    h.get_by_label("Save").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert!(png.exists());

    // A fresh window on the PNG: the same scene, the same image.
    let mut again = harness(png.clone());
    assert!(
        again.state().error().is_none(),
        "{:?}",
        again.state().error()
    );
    let restored = again.state().desc().cloned().expect("scene restored");
    assert_eq!(
        restored.objects[0].material.texture().mapping(),
        Some(&Mapping::Cylindrical.into())
    );
    assert_eq!(restored.camera, desc.camera);
    assert_eq!(restored.render, desc.render);
    assert_eq!(image_bytes(again.state()), shown);
    settle(&mut again);
}

/// The light-probe preset (a mirror ball, a glossy ball, a matte ball in a courtyard) at
/// 160 x 120 and 1 spp, written to `dir` with its texture path made absolute.
fn small_light_probe(dir: &std::path::Path) -> std::path::PathBuf {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut desc =
        texplore::scene::load_preset(&root.join("presets/light-probe.ron")).expect("preset");
    desc.render.width = 160;
    desc.render.height = 120;
    desc.render.spp = 1;
    if let texplore::scene::TextureDesc::Image { path, .. } = desc.objects[0].material.texture_mut()
    {
        *path = root
            .join("assets/courtyard_probe.hdr")
            .display()
            .to_string();
    }
    let path = dir.join("probe-small.ron");
    texplore::scene::save_preset(&desc, &path).expect("write preset");
    path
}

#[test]
fn hovering_a_mirror_follows_its_reflected_ray() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = small_light_probe(dir.path());
    let desc = texplore::scene::load_preset(&path).expect("preset");
    let scene = texplore::scene::build_scene(&desc, &path, &mut texplore::scene::AssetCache::new())
        .expect("build");
    let mut h = harness(path);
    // A film pixel on the mirror ball, found as the inspector finds it.
    let (w, hh) = (scene.settings.width, scene.settings.height);
    let film = (0..hh)
        .flat_map(|y| {
            (0..w).map(move |x| texplore::math::Vec2::new(x as f32 + 0.5, y as f32 + 0.5))
        })
        .find(|&p| {
            scene
                .inspect(p)
                .is_some_and(|i| i.object_name == "Mirror ball")
        })
        .expect("the mirror ball is in view");
    let image = h.get_by_label("Rendered image").rect();
    let at = image.min
        + egui::vec2(
            film.x / w as f32 * image.width(),
            film.y / hh as f32 * image.height(),
        );
    h.hover_at(at);
    h.run_steps(3);
    let i = h.state().inspection().expect("an inspection");
    assert_eq!(i.object_name, "Mirror ball");
    // The reflection worked, drawn and followed: what the ray hits and the texel it reads.
    assert!(
        h.query_all_by_label_contains("Mirror: bounce 1 (the reflection depth allows 4)")
            .next()
            .is_some()
    );
    assert!(
        h.query_all_by_label_contains("r = 2 (n . v) n - v")
            .next()
            .is_some()
    );
    assert!(
        h.query_all_by_label_contains("make equal angles")
            .next()
            .is_some()
    );
    assert!(h.query_by_label("r hits").is_some());
    assert!(h.query_by_label("the mirror adds").is_some());
}

#[test]
fn hovering_the_earth_explains_the_pixel() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    // The viewport's centre is the image's centre: the Earth.
    let centre = h.get_by_label("Reset view").rect();
    let viewport_centre = egui::pos2(
        (centre.left() + WINDOW[0] - 360.0) / 2.0,
        (centre.bottom() + WINDOW[1] - 30.0) / 2.0,
    );
    h.hover_at(viewport_centre);
    h.step();
    h.step();
    let i = h.state().inspection().expect("an inspection");
    assert_eq!(i.mapping, Some(Mapping::Spherical));
    assert_eq!(i.texels.len(), 2);
    assert!(
        h.query_all_by_label_contains("theta = acos(y)")
            .next()
            .is_some()
    );
    assert!(
        h.query_all_by_label_contains("centred lookup")
            .next()
            .is_some()
    );
}

#[test]
fn unsaved_changes_are_asked_about_before_another_preset_opens() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    choose_cylindrical_mapping(&mut h);
    let here = h.state().path().to_path_buf();
    let open_checker = |h: &mut Harness<'_, ExplorerApp>| {
        h.get_by_label("Presets").click();
        h.run_steps(3);
        h.get_by_label("checker").click();
        h.run_steps(3);
    };

    open_checker(&mut h);
    assert!(
        h.query_all_by_label_contains("not saved").next().is_some(),
        "the prompt shows"
    );
    assert_eq!(h.state().path(), here, "nothing opens before the answer");
    h.get_by_label("Cancel").click();
    settle(&mut h);
    assert_eq!(h.state().path(), here);
    assert_eq!(
        texture_mapping(h.state()),
        Some(Mapping::Cylindrical),
        "the edit stays"
    );

    open_checker(&mut h);
    h.get_by_label("Discard changes").click();
    settle(&mut h);
    assert!(
        h.state().path().ends_with("presets/checker.ron"),
        "{:?}",
        h.state().path()
    );
    assert!(!h.state().is_dirty());
}

#[test]
fn opening_a_preset_with_a_missing_image_keeps_the_scene() {
    let dir = tempfile::tempdir().expect("temp dir");
    let here = small_earth(dir.path());
    let text = std::fs::read_to_string(&here).expect("read");
    let broken = dir.path().join("broken.ron");
    std::fs::write(&broken, text.replace("earth_2048x1024.jpg", "missing.jpg")).expect("write");
    let mut h = harness(here.clone());
    let desc_before = h.state().desc().cloned();
    let image_before = image_bytes(h.state());

    // File > Open..., type the path, Open.
    h.get_by_label("File").click();
    h.run_steps(3);
    h.get_by_label("Open…").click();
    h.run_steps(3);
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&broken.display().to_string());
    h.step();
    h.get_by_label("Open").click();
    settle(&mut h);

    let err = h.state().error().expect("an error is shown").to_owned();
    assert!(err.contains("missing.jpg"), "{err}");
    assert_eq!(h.state().path(), here);
    assert_eq!(h.state().desc().cloned(), desc_before);
    assert_eq!(image_bytes(h.state()), image_before);
}

#[test]
fn the_uv_debug_view_shows_u_in_red_and_v_in_green() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = small_earth(dir.path());
    let mut h = harness(path.clone());
    h.get_by_role_and_label(Role::ComboBox, "View").click();
    h.run_steps(3);
    h.get_by_label("uv").click();
    settle(&mut h);
    let desc = h.state().desc().cloned().expect("scene");
    assert_eq!(desc.render.view.name(), "uv");

    // The pixel at the centre of the Earth against the library's own (u, v) there.
    let scene = texplore::scene::build_scene(&desc, &path, &mut texplore::scene::AssetCache::new())
        .expect("build");
    let (x, y) = (80u32, 60u32);
    let i = scene
        .inspect(texplore::math::Vec2::new(x as f32 + 0.5, y as f32 + 0.5))
        .expect("the Earth is at the centre");
    let uv = i.wrapped_uv.expect("uv");
    let image = h.state().image().expect("image");
    let px = &image.rgba[((y * image.width + x) * 4) as usize..][..2];
    let (r, g) = (f32::from(px[0]) / 255.0, f32::from(px[1]) / 255.0);
    assert!(
        (r - uv.x).abs() < 0.02 && (g - uv.y).abs() < 0.02,
        "pixel ({r}, {g}) against (u, v) = {uv}"
    );
}

/// Opens the combo box `label`, checks that it offers an entry for every variant the library
/// names (each name shows once more while the menu is open), and closes it again.
fn assert_menu_offers_every<T: Named>(h: &mut Harness<'_, ExplorerApp>, label: &str) {
    let count = |h: &Harness<'_, ExplorerApp>, name: &str| h.query_all_by_label(name).count();
    // The lower menus of the scene panel are scrolled out of sight at first.
    h.get_by_role_and_label(Role::ComboBox, label)
        .scroll_to_me();
    h.run_steps(3);
    let before: Vec<usize> = T::VARIANTS.iter().map(|v| count(h, v.name())).collect();
    h.get_by_role_and_label(Role::ComboBox, label).click();
    h.run_steps(3);
    for (v, before) in T::VARIANTS.iter().zip(before) {
        assert_eq!(
            count(h, v.name()),
            before + 1,
            "the {label} menu should offer '{}' once",
            v.name()
        );
    }
    h.get_by_role_and_label(Role::ComboBox, label).click();
    h.run_steps(3);
}

#[test]
fn every_menu_offers_every_variant_the_library_names() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    assert_menu_offers_every::<ShapeKind>(&mut h, "Shape");
    assert_menu_offers_every::<MaterialKind>(&mut h, "Material");
    assert_menu_offers_every::<TextureKind>(&mut h, "Texture");
    assert_menu_offers_every::<Mapping>(&mut h, "Mapping");
    assert_menu_offers_every::<Filter>(&mut h, "Filter");
    assert_menu_offers_every::<Lookup>(&mut h, "Lookup");
    assert_menu_offers_every::<Wrap>(&mut h, "Wrap");
    assert_menu_offers_every::<PixelSampler>(&mut h, "Sampler");
    assert_menu_offers_every::<ProjectionKind>(&mut h, "Camera");
    assert_menu_offers_every::<View>(&mut h, "View");
    for &kind in LightKind::VARIANTS {
        let button = format!("Add {}", kind.name());
        assert!(h.query_by_label(&button).is_some(), "no '{button}' button");
    }
}

#[test]
fn picking_a_texture_kind_gives_its_defaults_and_keeps_the_mapping() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    h.get_by_role_and_label(Role::ComboBox, "Texture").click();
    h.run_steps(3);
    h.get_by_label(TextureKind::Checker.name()).click();
    settle(&mut h);
    let texture = h.state().desc().expect("scene").objects[0]
        .material
        .texture()
        .clone();
    let mut expected = TextureKind::Checker.default_desc();
    expected.set_mapping(Mapping::Spherical.into());
    assert_eq!(texture, expected);
    // The checker's own settings replace the image's.
    assert!(h.query_by_label("squares along u").is_some());
    assert!(h.query_by_label("Lookup").is_none());
}
