//! The Lessons panel on the real app (egui_kittest, as in `tests/window/gui.rs`): started on a lesson
//! as `texplore lesson` starts it, every lesson opens its preset, every experiment button puts
//! the lesson's edit into the scene and Undo takes it back, Show answer reveals the answer, and
//! Next lesson walks the lecture in order; a lesson file dropped into the folder appears after
//! Rescan.

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use std::path::Path;
use texplore::gui::{AppOptions, ExplorerApp};
use texplore::lesson::{Lesson, edit::value_at, load_dir};
use texplore::scene::load_preset;

pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The app started on `lesson`, tall enough that the panel's buttons are all on screen.
pub fn start(lesson: Lesson) -> Harness<'static, ExplorerApp> {
    let mut h = Harness::builder()
        .with_size([1280.0, 1500.0])
        .build_eframe(move |_cc| {
            ExplorerApp::with_options(
                lesson.preset.clone(),
                AppOptions {
                    lesson: Some(lesson),
                    ..AppOptions::default()
                },
            )
        });
    crate::gui_common::built(&mut h);
    h
}

/// Clicks the widget labelled `label` and lets the app react.
pub fn press(h: &mut Harness<'_, ExplorerApp>, label: &str) {
    h.get_by_label(label).scroll_to_me();
    // Scrolling animates: click once the widget has stopped moving.
    let mut last = None;
    for _ in 0..60 {
        h.step();
        let r = h.get_by_label(label).rect();
        if last == Some(r) {
            break;
        }
        last = Some(r);
    }
    h.get_by_label(label).click();
    // The scene an experiment or a lesson's preset makes builds off the UI thread.
    crate::gui_common::built(h);
}

#[test]
fn every_lesson_opens_and_every_experiment_applies_and_undoes() {
    let loaded = load_dir(&root().join("lessons")).unwrap();
    assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
    let lessons = loaded.lessons;
    let shipped = crate::gui_lessons_class::shipped_files();
    let mut h = start(lessons[0].clone());
    for (i, lesson) in lessons.iter().enumerate() {
        let base = load_preset(&lesson.preset).unwrap();
        assert_eq!(h.state().path(), lesson.preset, "{}", lesson.name);
        assert_eq!(h.state().desc(), Some(&base), "{}", lesson.name);
        // The panel shows this lesson: its heading and its question.
        let _ = h.get_by_label(&lesson.title);
        let _ = h.get_by_label(&lesson.question);
        let last = lesson.experiments.len() - 1;
        for (k, x) in lesson.experiments.iter().enumerate() {
            press(&mut h, &x.label);
            // Each experiment applies to the lesson's scene (or the one it builds on).
            let expected = lesson.scene(k, &base).unwrap();
            let desc = h.state().desc().cloned().unwrap();
            assert_ne!(desc, base, "{}: {}", lesson.name, x.label);
            assert_eq!(desc, expected, "{}: {}", lesson.name, x.label);
            for e in &x.edits {
                let mut want = x
                    .after
                    .map_or_else(|| base.clone(), |a| lesson.scene(a, &base).unwrap());
                want = texplore::lesson::edit::set_path(&want, &e.path, &e.value).unwrap();
                assert_eq!(
                    value_at(&desc, &e.path),
                    value_at(&want, &e.path),
                    "{}: {} sets {}",
                    lesson.name,
                    x.label,
                    e.path
                );
            }
            assert!(h.state().error().is_none(), "{:?}", h.state().error());
            if k < last || i + 1 == lessons.len() {
                press(&mut h, "Undo");
                let back = x
                    .after
                    .map_or_else(|| base.clone(), |a| lesson.scene(a, &base).unwrap());
                assert_eq!(
                    h.state().desc(),
                    Some(&back),
                    "{}: undo {}",
                    lesson.name,
                    x.label
                );
                // Back to the lesson's scene (an experiment that builds on another goes back
                // to that one's, a change of the scene still).
                assert_eq!(h.state().is_dirty(), x.after.is_some(), "{}", lesson.name);
            }
        }
        assert!(
            h.query_by_label(&lesson.answer).is_none(),
            "{}",
            lesson.name
        );
        press(&mut h, "Show answer");
        let _ = h.get_by_label(&lesson.answer);
        if i + 1 < lessons.len() {
            // The last experiment is still applied: the lesson's own edits open the next
            // lesson without the unsaved-changes prompt.
            assert!(h.state().is_dirty());
            press(&mut h, "Next lesson");
            assert!(h.query_by_label("Unsaved changes").is_none());
        }
    }
    // And back.
    press(&mut h, "Previous lesson");
    assert_eq!(h.state().path(), lessons[lessons.len() - 2].preset);
    assert!(
        crate::gui_lessons_class::shipped_files() == shipped,
        "a shipped file changed on disk during the walk"
    );
}

#[test]
fn a_dropped_lesson_appears_after_rescan_and_a_learners_edit_is_guarded() {
    let dir = tempfile::tempdir().unwrap();
    let presets = format!("{}/presets/", root().display());
    let text = std::fs::read_to_string(root().join("lessons/05-cylindrical-mapping.toml"))
        .unwrap()
        .replace("../presets/", &presets);
    std::fs::write(dir.path().join("01-first.toml"), &text).unwrap();
    let first = texplore::lesson::load_lesson(&dir.path().join("01-first.toml")).unwrap();
    let mut h = start(first);
    // One lesson: no Next.
    assert!(h.get_by_label("Next lesson").accesskit_node().is_disabled());
    let second = std::fs::read_to_string(root().join("lessons/06-spherical-mapping.toml"))
        .unwrap()
        .replace("../presets/", &presets)
        .replace("Spherical mapping: why 2:1", "Dropped in: why 2:1");
    std::fs::write(dir.path().join("02-dropped.toml"), second).unwrap();
    press(&mut h, "Rescan lessons");
    press(&mut h, "Next lesson");
    let _ = h.get_by_label("Dropped in: why 2:1, what happens at the poles");
    assert!(h.state().path().ends_with("presets/earth.ron"));
    // The learner's own change (an orbit in the viewport) is guarded by the unsaved-changes
    // prompt: Cancel stays, Discard changes goes back.
    press(&mut h, "The 3:2 cat photo");
    let image = h.get_by_label(IMAGE).rect();
    let before = h.state().desc().cloned().unwrap();
    drag(
        &mut h,
        image.center(),
        image.center() + egui::vec2(60.0, 10.0),
    );
    assert_ne!(
        h.state().desc().unwrap().camera,
        before.camera,
        "the drag orbits"
    );
    press(&mut h, "Previous lesson");
    let _ = h.get_by_label("Unsaved changes");
    press(&mut h, "Cancel");
    assert!(h.state().path().ends_with("presets/earth.ron"));
    press(&mut h, "Previous lesson");
    press(&mut h, "Discard changes");
    assert!(h.state().path().ends_with("presets/cylinder.ron"));
    let _ = h.get_by_label("Cylindrical mapping: φ, the seam and tiling");
}

/// The viewport's image, as the accessibility tree names it.
pub const IMAGE: &str = "Rendered image";

/// Presses the primary button at `from`, moves to `to` in a few steps and releases it there.
pub fn drag(h: &mut Harness<'_, ExplorerApp>, from: egui::Pos2, to: egui::Pos2) {
    h.hover_at(from);
    h.run_steps(3);
    h.drag_at(from);
    h.step();
    for i in 1..=5 {
        h.hover_at(from + (to - from) * (i as f32 / 5.0));
        h.step();
    }
    h.drop_at(to);
    h.run_steps(2);
}
