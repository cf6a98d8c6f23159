//! Undo and redo, the title's unsaved marker, the shortcuts list and what the window remembers
//! between runs, driven headless with `egui_kittest` as a user would (menus, keys, drags).

use crate::gui_common::{choose, desc, harness, image_bytes, settle, small_earth};
use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use std::collections::HashMap;
use texplore::gui::{AppOptions, ExplorerApp, Prefs};
use texplore::mapping::Mapping;
use texplore::names::Named;
use texplore::scene::{MaterialKind, ShapeKind, TextureDesc, TextureKind};
use texplore::texture::Filter;

/// The Edit menu's checkbox.
const CAMERA_RULE: &str = "Camera moves are unsaved changes";

fn press(h: &mut Harness<'_, ExplorerApp>, modifiers: Modifiers, key: Key) {
    h.key_press_modifiers(modifiers, key);
    settle(h);
}

fn undo_key(h: &mut Harness<'_, ExplorerApp>) {
    press(h, Modifiers::COMMAND, Key::Z);
}

/// Whether the Edit menu shows "Undo <what>" and "Redo <what>" (opened and closed again).
fn edit_menu_entries(h: &mut Harness<'_, ExplorerApp>) -> (bool, bool) {
    h.get_by_label("Edit").click();
    h.run_steps(3);
    let has = |h: &Harness<'_, ExplorerApp>, text: String| {
        h.query_all_by_label_contains(&text).next().is_some()
    };
    let undo = h.state().undo_label().map(|l| format!("Undo {l}"));
    let redo = h.state().redo_label().map(|l| format!("Redo {l}"));
    let shown = (
        undo.is_some_and(|t| has(h, t)),
        redo.is_some_and(|t| has(h, t)),
    );
    h.key_press(Key::Escape);
    h.run_steps(3);
    assert!(
        h.query_by_label(CAMERA_RULE).is_none(),
        "Esc closed the Edit menu"
    );
    shown
}

/// Makes `edit`, then checks that the Edit menu names it (`label`), that Ctrl+Z brings back
/// the scene and the image from before, Ctrl+Shift+Z the edited ones, and Ctrl+Z then Ctrl+Y
/// the same again. Leaves the edit done.
fn check_undo_redo(
    h: &mut Harness<'_, ExplorerApp>,
    label: &str,
    edit: impl FnOnce(&mut Harness<'_, ExplorerApp>),
) {
    let (before, image_before) = (desc(h), image_bytes(h));
    edit(h);
    let (after, image_after) = (desc(h), image_bytes(h));
    assert_ne!(after, before, "the edit '{label}' changed nothing");
    assert_eq!(h.state().undo_label(), Some(label));
    assert_eq!(
        edit_menu_entries(h),
        (true, false),
        "Edit menu: Undo {label}"
    );

    undo_key(h);
    assert_eq!(desc(h), before, "Ctrl+Z undoes {label}");
    assert_eq!(
        image_bytes(h),
        image_before,
        "the image from before {label}"
    );
    assert_eq!(h.state().redo_label(), Some(label));
    assert!(edit_menu_entries(h).1, "Edit menu: Redo {label}");

    press(h, Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    assert_eq!(desc(h), after, "Ctrl+Shift+Z redoes {label}");
    assert_eq!(image_bytes(h), image_after);

    undo_key(h);
    assert_eq!(desc(h), before);
    press(h, Modifiers::COMMAND, Key::Y);
    assert_eq!(desc(h), after, "Ctrl+Y redoes {label}");
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
}

#[test]
fn mapping_texture_and_filter_edits_undo_and_redo() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let start = desc(&h);
    check_undo_redo(&mut h, "mapping of Earth", |h| {
        choose(h, "Mapping", Mapping::Cylindrical.name());
    });
    check_undo_redo(&mut h, "filter of Earth", |h| {
        choose(h, "Filter", Filter::Bilinear.name());
    });
    check_undo_redo(&mut h, "texture of Earth", |h| {
        choose(h, "Texture", TextureKind::Checker.name());
    });
    // Three steps back is where the window started.
    for _ in 0..3 {
        undo_key(&mut h);
    }
    assert_eq!(desc(&h), start);
    assert!(!h.state().is_dirty());
    assert_eq!(h.state().undo_label(), None, "nothing more to undo");
}

#[test]
fn shape_and_material_edits_undo_and_redo() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    check_undo_redo(&mut h, "shape of Earth", |h| {
        choose(h, "Shape", ShapeKind::Cylinder.name());
    });
    check_undo_redo(&mut h, "material of Earth", |h| {
        choose(h, "Material", MaterialKind::Phong.name());
    });
}

/// Presses the primary button at `from`, moves to `to` in `steps` frames and releases it.
fn drag(h: &mut Harness<'_, ExplorerApp>, from: egui::Pos2, to: egui::Pos2, steps: usize) {
    h.hover_at(from);
    h.run_steps(2);
    h.drag_at(from);
    h.step();
    for i in 1..=steps {
        h.hover_at(from + (to - from) * (i as f32 / steps as f32));
        h.step();
    }
    h.drop_at(to);
    settle(h);
}

#[test]
fn an_orbit_drag_is_one_step_and_so_is_a_run_of_wheel_clicks() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let home = desc(&h).camera;
    let centre = h.get_by_label("Rendered image").rect().center();
    check_undo_redo(&mut h, "camera", |h| {
        drag(h, centre, centre + egui::vec2(80.0, 20.0), 8);
    });
    let orbited = desc(&h).camera;
    assert_ne!(orbited.eye, home.eye);

    // Five wheel clicks, one per frame: one step.
    h.hover_at(centre);
    h.step();
    for _ in 0..5 {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Line,
            delta: egui::vec2(0.0, 1.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Wheel,
            modifiers: Modifiers::NONE,
        });
        h.step();
    }
    // egui's smooth scrolling spreads the clicks over more frames: wait until the camera stops.
    let mut still = 0;
    let mut eye = desc(&h).camera.eye;
    for _ in 0..2000 {
        h.step();
        let e = desc(&h).camera.eye;
        still = if e == eye { still + 1 } else { 0 };
        eye = e;
        if still == 10 {
            break;
        }
    }
    assert_eq!(still, 10, "the zoom never settled");
    settle(&mut h);
    let zoomed = desc(&h).camera;
    assert!(
        zoomed.eye.distance(zoomed.look_at) < orbited.eye.distance(orbited.look_at) * 0.9,
        "the wheel zoomed in"
    );
    undo_key(&mut h);
    assert_eq!(desc(&h).camera, orbited, "one Ctrl+Z undoes the whole zoom");
    undo_key(&mut h);
    assert_eq!(desc(&h).camera, home, "the next undoes the whole orbit");
    // A camera move alone is not an unsaved change (the README says so).
    press(&mut h, Modifiers::COMMAND, Key::Y);
    assert!(!h.state().is_dirty());
    assert!(!h.state().title().contains('•'), "{}", h.state().title());
}

#[test]
fn undo_brings_a_removed_object_back_and_selects_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    check_undo_redo(&mut h, "add object", |h| {
        h.get_by_label("Duplicate").click();
        settle(h);
    });
    assert_eq!(desc(&h).objects.len(), 2);
    // Select the Earth (object 0) and remove it.
    h.get_by_label("0: Earth").click();
    settle(&mut h);
    let two = desc(&h);
    check_undo_redo(&mut h, "remove Earth", |h| {
        // The objects' Remove (the topmost; each light has one too).
        h.get_all_by_label("Remove")
            .min_by(|a, b| a.rect().top().total_cmp(&b.rect().top()))
            .expect("a Remove button")
            .click();
        settle(h);
    });
    assert_eq!(desc(&h).objects.len(), 1);
    undo_key(&mut h);
    assert_eq!(desc(&h), two, "the Earth is back, first in the list");
    assert!(
        h.query_by_label("0: Earth").is_some(),
        "the list shows it again"
    );
    assert_eq!(h.state().selected_object(), 0, "and the panel edits it");
}

/// Clicks the objects' Remove (the topmost; each light has one too).
fn remove_selected_object(h: &mut Harness<'_, ExplorerApp>) {
    h.get_all_by_label("Remove")
        .min_by(|a, b| a.rect().top().total_cmp(&b.rect().top()))
        .expect("a Remove button")
        .click();
    settle(h);
}

#[test]
fn what_an_editor_remembers_about_an_object_follows_it_through_remove_and_undo() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let image = desc(&h).objects[0].material.texture().clone();
    assert!(matches!(image, TextureDesc::Image { .. }), "{image:?}");
    // Switched to a checker, the Earth remembers its image...
    choose(&mut h, "Texture", TextureKind::Checker.name());
    h.get_by_label("Duplicate").click();
    settle(&mut h);
    h.get_by_label("0: Earth").click();
    settle(&mut h);
    // ...through its removal and the undo that brings it back (kept under the object's id,
    // not its index).
    remove_selected_object(&mut h);
    assert_eq!(desc(&h).objects.len(), 1);
    undo_key(&mut h);
    assert_eq!(desc(&h).objects.len(), 2);
    assert_eq!(h.state().selected_object(), 0);
    choose(&mut h, "Texture", TextureKind::Image.name());
    assert_eq!(
        desc(&h).objects[0].material.texture(),
        &image,
        "the Earth's own image comes back"
    );
}

#[test]
fn the_title_marks_unsaved_changes_and_a_camera_move_counts_only_when_asked() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    assert_eq!(h.state().title(), "earth-small.ron — texplore");
    choose(&mut h, "Mapping", Mapping::Rectangular.name());
    assert_eq!(h.state().title(), "• earth-small.ron — texplore");
    undo_key(&mut h);
    assert_eq!(
        h.state().title(),
        "earth-small.ron — texplore",
        "undone: saved again"
    );

    let centre = h.get_by_label("Rendered image").rect().center();
    drag(&mut h, centre, centre + egui::vec2(60.0, 0.0), 4);
    assert!(
        !h.state().is_dirty(),
        "an orbit alone is not unsaved by default"
    );
    h.get_by_label("Edit").click();
    h.run_steps(3);
    h.get_by_role_and_label(Role::CheckBox, CAMERA_RULE).click();
    h.run_steps(3);
    assert!(h.state().is_dirty(), "now it is");
    assert_eq!(h.state().title(), "• earth-small.ron — texplore");
}

#[test]
fn edit_scene_is_one_undo_step_like_a_panel_edit() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let before = desc(&h);
    h.state_mut().edit_scene(|d| d.render.exposure = 1.5);
    settle(&mut h);
    assert_eq!(desc(&h).render.exposure, 1.5);
    assert_eq!(h.state().undo_label(), Some("render settings"));
    undo_key(&mut h);
    assert_eq!(desc(&h), before);
}

#[test]
fn the_shortcuts_window_lists_the_keys_the_window_answers() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    h.get_by_label("Help").click();
    h.run_steps(3);
    h.get_by_label_contains("Keyboard shortcuts").click();
    h.run_steps(3);
    for text in [
        "Ctrl+Z",
        "Ctrl+Shift+Z",
        "Ctrl+Y",
        "Ctrl+S",
        "Ctrl+O",
        "F1",
        "Undo the last change of the scene",
        "Orbit the camera around the point looked at",
    ] {
        assert!(
            h.query_all_by_label(text).next().is_some(),
            "the list shows '{text}'"
        );
    }
    // F1 closes it again.
    press(&mut h, Modifiers::NONE, Key::F1);
    assert!(h.query_by_label("Ctrl+Shift+Z").is_none());
}

/// eframe's storage, in memory: the tests never touch the user's.
#[derive(Default)]
struct MemoryStorage(HashMap<String, String>);

impl eframe::Storage for MemoryStorage {
    fn get_string(&self, key: &str) -> Option<String> {
        self.0.get(key).cloned()
    }
    fn set_string(&mut self, key: &str, value: String) {
        self.0.insert(key.to_owned(), value);
    }
    fn remove_string(&mut self, key: &str) {
        self.0.remove(key);
    }
    fn flush(&mut self) {}
}

#[test]
fn the_window_reopens_the_last_scene_and_the_camera_rule() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = small_earth(dir.path());
    let mut storage = MemoryStorage::default();
    {
        let mut h = harness(path.clone());
        h.get_by_label("Edit").click();
        h.run_steps(3);
        h.get_by_role_and_label(Role::CheckBox, CAMERA_RULE).click();
        h.run_steps(3);
        eframe::App::save(h.state_mut(), &mut storage);
    }
    let prefs = Prefs::load(Some(&storage));
    assert_eq!(
        prefs.last_scene.as_deref(),
        Some(std::path::absolute(&path).expect("absolute").as_path())
    );
    assert!(prefs.camera_is_unsaved);

    let app = ExplorerApp::restore(Some(&storage), None, AppOptions::default());
    assert_eq!(app.path(), std::path::absolute(&path).expect("absolute"));
    assert!(app.error().is_none(), "{:?}", app.error());
    app.wait_for_render(std::time::Duration::from_mins(2))
        .expect("the render ends");
    // A file given on the command line wins; a kept scene that is gone falls back.
    let other = ExplorerApp::restore(Some(&storage), Some(path.clone()), AppOptions::default());
    assert_eq!(other.path(), path);
    std::fs::remove_file(&path).expect("remove");
    let gone = ExplorerApp::restore(Some(&storage), None, AppOptions::default());
    assert!(
        gone.path().ends_with(texplore::gui::DEFAULT_PRESET),
        "{:?}",
        gone.path()
    );
}

#[test]
fn a_render_job_calls_its_publish_hook_for_each_image_and_at_once_for_one_already_there() {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use texplore::render::{Generation, RenderJob, RenderOptions};
    let dir = tempfile::tempdir().expect("temp dir");
    let path = small_earth(dir.path());
    let desc = texplore::scene::load_preset(&path).expect("preset");
    let scene = texplore::scene::build_scene(&desc, &path, &mut texplore::scene::AssetCache::new())
        .expect("build");
    let generation = Generation::new();
    let job = RenderJob::start(
        std::sync::Arc::new(scene),
        RenderOptions::default(),
        &generation,
    )
    .expect("start");
    let (tx, rx) = std::sync::mpsc::channel();
    let calls = std::sync::Arc::new(AtomicUsize::new(0));
    let counted = calls.clone();
    job.on_publish(move || {
        counted.fetch_add(1, Ordering::SeqCst);
        let _ = tx.send(());
    });
    rx.recv_timeout(std::time::Duration::from_mins(2))
        .expect("the hook is called for the first image");
    assert!(
        job.image().is_some(),
        "an image is there when the hook runs"
    );
    let progress = job.wait();
    assert!(progress.finished);
    // 3 previews and 4 passes at 4 spp; the hook may have been set after some of them (then
    // it runs once at once for those).
    let n = calls.load(Ordering::SeqCst);
    assert!((1..=7).contains(&n), "{n} calls");

    // Set on a finished job: called at once, once.
    let job = RenderJob::start(
        std::sync::Arc::new(
            texplore::scene::build_scene(&desc, &path, &mut texplore::scene::AssetCache::new())
                .expect("build"),
        ),
        RenderOptions::default(),
        &generation,
    )
    .expect("start");
    let started = std::time::Instant::now();
    while !job.progress().finished {
        assert!(
            started.elapsed() < std::time::Duration::from_mins(2),
            "the render never finished"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let once = std::sync::Arc::new(AtomicUsize::new(0));
    let c = once.clone();
    job.on_publish(move || {
        c.fetch_add(1, Ordering::SeqCst);
    });
    assert_eq!(once.load(Ordering::SeqCst), 1);
}
