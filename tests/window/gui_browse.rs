//! The window's files, headless: *Browse…* beside every path field (the system's dialog
//! replaced by a function that answers as a user would), the path dialog's keyboard focus and
//! Esc, the recent list, where a screenshot goes and the message saying so, the assets list
//! after *Save as*, and the description *Save as* offers to edit.

use crate::gui_common::{WINDOW, harness, harness_with, settle, small_earth};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use texplore::gui::{AppOptions, BrowseFor, Browser, ExplorerApp};
use texplore::names::Named;
use texplore::scene::{ShapeDesc, ShapeKind, TextureDesc, load_preset};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// What the replaced file dialog was asked: for what, starting where, suggesting which name.
type Asked = Arc<Mutex<Vec<(BrowseFor, PathBuf, String)>>>;

/// Options whose file dialog answers `answer(what)` and notes each question in the returned
/// list.
fn browsing(
    answer: impl Fn(BrowseFor) -> Option<PathBuf> + Send + Sync + 'static,
) -> (AppOptions, Asked) {
    let asked: Asked = Arc::default();
    let log = asked.clone();
    let browser = Browser::replaced_by(move |what, start, name| {
        log.lock()
            .expect("lock")
            .push((what, start.to_path_buf(), name.to_owned()));
        answer(what)
    });
    (
        AppOptions {
            browser,
            ..AppOptions::default()
        },
        asked,
    )
}

fn menu(h: &mut Harness<'_, ExplorerApp>, menu: &str, entry: &str) {
    h.get_by_label(menu).click();
    h.run_steps(3);
    h.get_by_label(entry).click();
    h.run_steps(3);
}

fn image_path(app: &ExplorerApp) -> Option<String> {
    match app.desc()?.objects[0].material.texture() {
        TextureDesc::Image { path, .. } => Some(path.clone()),
        _ => None,
    }
}

#[test]
fn browse_beside_the_image_field_loads_the_chosen_image() {
    let dir = tempfile::tempdir().expect("temp dir");
    let chosen = dir.path().join("pictures/checker_512.png");
    std::fs::create_dir_all(chosen.parent().expect("folder")).expect("folder");
    std::fs::copy(root().join("assets/checker_512.png"), &chosen).expect("copy");
    let answer = chosen.clone();
    let (options, asked) = browsing(move |_| Some(answer.clone()));
    let preset = small_earth(dir.path());
    let mut h = harness_with(preset, options);
    let before = h.state().image().expect("image").rgba.clone();

    h.get_by_label("Browse…").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(
        image_path(h.state()).as_deref(),
        Some("pictures/checker_512.png"),
        "the path, relative to the preset"
    );
    assert_eq!(
        h.get_by_role_and_label(Role::TextInput, "image")
            .value()
            .as_deref(),
        Some("pictures/checker_512.png")
    );
    assert_ne!(
        h.state().image().expect("image").rgba,
        before,
        "the checker renders"
    );
    let asked = asked.lock().expect("lock").clone();
    assert_eq!(asked.len(), 1);
    assert_eq!(asked[0].0, BrowseFor::Image);
    assert_eq!(asked[0].1, dir.path(), "it starts in the preset's folder");
}

#[test]
fn browse_beside_the_mesh_prompt_makes_the_shape_that_mesh() {
    let dir = tempfile::tempdir().expect("temp dir");
    let knot = dir.path().join("torus-knot.ply");
    std::fs::copy(root().join("assets/torus-knot.ply"), &knot).expect("copy");
    let answer = knot.clone();
    let (options, asked) = browsing(move |_| Some(answer.clone()));
    let mut h = harness_with(small_earth(dir.path()), options);
    h.get_by_role_and_label(Role::ComboBox, "Shape").click();
    h.run_steps(3);
    h.get_by_label(ShapeKind::Mesh.name()).click();
    h.run_steps(3);
    // The mesh prompt's Browse… (the image field has one too: the mesh's is the upper one).
    h.get_all_by_label("Browse…")
        .min_by(|a, b| a.rect().top().total_cmp(&b.rect().top()))
        .expect("a Browse… button")
        .click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert!(
        matches!(&h.state().desc().expect("scene").objects[0].shape,
            ShapeDesc::Mesh { path, .. } if path == "torus-knot.ply"),
        "{:?}",
        h.state().desc().map(|d| &d.objects[0].shape)
    );
    assert_eq!(asked.lock().expect("lock")[0].0, BrowseFor::Mesh);
}

/// Clicks the path dialog's *Browse…* (the image field has one too, in the scene panel): the
/// one nearest the window's centre, where the modal sits.
fn dialog_browse(h: &mut Harness<'_, ExplorerApp>) {
    // A modal takes a few frames to size itself (the Open dialog's list) and settle.
    h.run_steps(5);
    let centre = egui::pos2(WINDOW[0] / 2.0, WINDOW[1] / 2.0);
    h.get_all_by_label("Browse…")
        .min_by(|a, b| {
            let d = |n: &egui_kittest::Node<'_>| n.rect().center().distance(centre);
            d(a).total_cmp(&d(b))
        })
        .expect("a Browse… button")
        .click();
    settle(h);
}

#[test]
fn browse_in_the_open_and_screenshot_dialogs_acts_on_the_chosen_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let preset = small_earth(dir.path());
    let shot = dir.path().join("chosen.png");
    let other = dir.path().join("other.ron");
    std::fs::copy(&preset, &other).expect("copy preset");
    let (shot2, other2) = (shot.clone(), other.clone());
    let (options, asked) = browsing(move |what| match what {
        BrowseFor::Screenshot => Some(shot2.clone()),
        BrowseFor::Scene => Some(other2.clone()),
        _ => None,
    });
    let mut h = harness_with(preset, options);

    menu(&mut h, "File", "Save screenshot…");
    dialog_browse(&mut h);
    assert!(shot.is_file(), "the screenshot went where the dialog said");
    let notice = h.state().notice().expect("a confirmation").to_owned();
    assert!(notice.contains("chosen.png"), "{notice}");
    assert!(
        h.query_all_by_label_contains("Screenshot saved to")
            .next()
            .is_some()
    );

    menu(&mut h, "File", "Open…");
    dialog_browse(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(h.state().path(), other);
    let asked: Vec<BrowseFor> = asked.lock().expect("lock").iter().map(|a| a.0).collect();
    assert_eq!(asked, [BrowseFor::Screenshot, BrowseFor::Scene]);
}

#[test]
fn the_path_dialog_takes_the_keyboard_and_esc_closes_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    menu(&mut h, "File", "Open…");
    h.run_steps(2);
    assert!(
        h.get_by_role_and_label(Role::TextInput, "Path")
            .is_focused(),
        "the path field has the keyboard"
    );
    h.key_press(egui::Key::Escape);
    h.run_steps(3);
    assert!(
        h.query_by_role_and_label(Role::TextInput, "Path").is_none(),
        "Esc closed the dialog"
    );
}

#[test]
fn the_recent_list_does_not_repeat_the_built_in_presets() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    menu(&mut h, "Presets", "checker");
    settle(&mut h);
    assert!(h.state().path().ends_with("presets/checker.ron"));
    menu(&mut h, "File", "Open…");
    // The built-in entry is "presets/checker.ron", the recent one its absolute path.
    let checker = h.query_all_by_label_contains("presets/checker.ron").count();
    assert_eq!(checker, 1, "checker.ron is listed once");
    let earth = h.query_all_by_label_contains("earth-small.ron").count();
    assert_eq!(earth, 1, "the recent file that is not built in is listed");
}

#[test]
fn a_screenshot_goes_beside_the_preset_by_default_and_the_window_says_where() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    menu(&mut h, "File", "Save screenshot…");
    let expected = dir.path().join("earth-small-shot.png");
    assert_eq!(
        h.get_by_role_and_label(Role::TextInput, "Path").value(),
        Some(expected.display().to_string())
    );
    h.get_by_label("Save").click();
    settle(&mut h);
    assert!(expected.is_file());
    let said = format!("Screenshot saved to {}", expected.display());
    assert!(
        h.query_all_by_label_contains(&said).next().is_some(),
        "the status line says '{said}'"
    );
    // The next default does not replace it.
    assert_eq!(
        texplore::gui::screenshot_default(h.state().path()),
        dir.path().join("earth-small-shot-2.png")
    );
    // A built-in preset's screenshot goes to the Pictures folder, not into presets/.
    let builtin = texplore::gui::screenshot_default(&root().join("presets/earth.ron"));
    assert!(!builtin.starts_with(root().join("presets")), "{builtin:?}");
}

#[test]
fn after_save_as_the_assets_list_is_the_new_folders() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let elsewhere = dir.path().join("elsewhere");
    std::fs::create_dir_all(elsewhere.join("assets")).expect("folder");
    std::fs::copy(
        root().join("assets/chelsea_451x300.png"),
        elsewhere.join("assets/only_here.png"),
    )
    .expect("copy");
    // The list is read once before the move.
    h.get_by_role_and_label(Role::ComboBox, "from assets/")
        .click();
    h.run_steps(3);
    assert!(h.query_by_label("only_here.png").is_none());
    h.get_by_role_and_label(Role::ComboBox, "from assets/")
        .click();
    h.run_steps(3);

    menu(&mut h, "File", "Save as…");
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&elsewhere.join("moved.ron").display().to_string());
    h.step();
    h.get_by_label("Save").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    h.get_by_role_and_label(Role::ComboBox, "from assets/")
        .click();
    h.run_steps(3);
    assert!(
        h.query_by_label("only_here.png").is_some(),
        "the new folder's assets, without Rescan"
    );
}

#[test]
fn save_as_offers_to_edit_the_description() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let old = h.state().desc().expect("scene").description.clone();
    menu(&mut h, "File", "Save as…");
    let field = "Description (shown in the Presets menu)";
    assert_eq!(
        h.get_by_role_and_label(Role::MultilineTextInput, field)
            .value(),
        Some(old),
        "it starts as the preset's"
    );
    h.get_by_role_and_label(Role::MultilineTextInput, field)
        .set_text_value_accesskit("A smaller Earth for the tests");
    h.step();
    let saved = dir.path().join("renamed.ron");
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&saved.display().to_string());
    h.step();
    h.get_by_label("Save").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    let on_disk = load_preset(&saved).expect("saved");
    assert_eq!(on_disk.description, "A smaller Earth for the tests");
    assert!(!h.state().is_dirty());
}

#[test]
fn without_a_system_dialog_browse_opens_the_windows_own_path_dialog_and_says_why() {
    let dir = tempfile::tempdir().expect("temp dir");
    let chosen = dir.path().join("pictures/checker_512.png");
    std::fs::create_dir_all(chosen.parent().expect("folder")).expect("folder");
    std::fs::copy(root().join("assets/checker_512.png"), &chosen).expect("copy");
    let why = "No desktop portal here: type the path instead.";
    let options = AppOptions {
        browser: Browser::without_dialog(why),
        ..AppOptions::default()
    };
    let mut h = harness_with(small_earth(dir.path()), options);
    h.get_by_label("Browse…").click();
    h.run_steps(3);
    let _ = h.get_by_label("Choose an image for the selected object");
    let _ = h.get_by_label(why);
    // The shipped images are offered.
    let _ = h.get_by_label_contains("earth_2048x1024.jpg");
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&chosen.display().to_string());
    h.step();
    h.get_by_label("Use").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(
        image_path(h.state()).as_deref(),
        Some("pictures/checker_512.png")
    );
    // The Open dialog says it too, and its Browse… lists the folder typed instead: a folder
    // clicked opens, a file clicked goes into the field.
    let other = dir.path().join("scenes/other.ron");
    std::fs::create_dir_all(other.parent().expect("folder")).expect("folder");
    std::fs::copy(dir.path().join("earth-small.ron"), &other).expect("copy");
    std::fs::copy(
        dir.path().join("earth_2048x1024.jpg"),
        dir.path().join("scenes/earth_2048x1024.jpg"),
    )
    .expect("copy");
    menu(&mut h, "File", "Open…");
    let _ = h.get_by_label("Open a preset or a texplore PNG");
    let _ = h.get_by_label(why);
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&format!("{}/", dir.path().display()));
    h.step();
    dialog_browse(&mut h);
    h.get_by_label(&format!("scenes{}", std::path::MAIN_SEPARATOR))
        .click();
    h.run_steps(3);
    h.get_by_label("other.ron").click();
    h.run_steps(3);
    let typed = h
        .get_by_role_and_label(Role::TextInput, "Path")
        .accesskit_node()
        .value();
    assert_eq!(typed.as_deref(), Some(other.display().to_string().as_str()));
    h.get_by_label("Open").click();
    h.run_steps(3);
    // The image chosen above is an unsaved change.
    h.get_by_label("Discard changes").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(h.state().path(), other);
}
