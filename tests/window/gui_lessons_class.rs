//! The Lessons panel in front of a class (issue 24): experiments are independent (lesson 2's
//! second lookup after the first shows its own change, yellow included), *Edit → Undo* and the
//! panel agree on what is applied, shipped files and lesson scenes are saved only under another
//! name (no shipped file changes on disk), the text is Markdown (lesson 8's list is a list),
//! and the panel scrolls back to the top and keeps its width from one lesson to the next.

use crate::gui_common::{settle, undo};
use crate::gui_lessons::{IMAGE, drag, press, root, start};
use egui::accesskit::{Role, Toggled};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use std::path::PathBuf;
use texplore::gui::ExplorerApp;
use texplore::lesson::{Lesson, find, load_dir};
use texplore::scene::load_preset;

fn lessons() -> Vec<Lesson> {
    let loaded = load_dir(&root().join("lessons")).unwrap();
    assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
    loaded.lessons
}

/// Every shipped file on disk, with its bytes: the source tree's `presets/` and `lessons/`, and
/// the copy of the store the window opens from.
pub fn shipped_files() -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let copy = texplore::shipped::root().unwrap().to_path_buf();
    for dir in [
        root().join("presets"),
        root().join("lessons"),
        copy.join("presets"),
        copy.join("lessons"),
    ] {
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            let bytes = std::fs::read(&p).unwrap();
            out.push((p, bytes));
        }
    }
    out.sort();
    out
}

/// Whether the experiment button `label` shows as applied.
fn applied(h: &Harness<'_, ExplorerApp>, label: &str) -> bool {
    h.get_by_role_and_label(Role::Button, label)
        .accesskit_node()
        .toggled()
        == Some(Toggled::True)
}

/// How many panel *Undo* buttons there are (one per applied experiment).
fn undo_buttons(h: &Harness<'_, ExplorerApp>) -> usize {
    h.query_all_by_label("Undo").count()
}

/// Pixels of the image that are the texel image's yellow (the last column).
fn yellow(h: &Harness<'_, ExplorerApp>) -> usize {
    h.state()
        .image()
        .expect("an image")
        .rgba
        .chunks(4)
        .filter(|p| p[0] > 150 && p[1] > 120 && p[2] < 80)
        .count()
}

#[test]
fn lesson_2s_second_lookup_shows_its_own_change_and_undo_agrees() {
    let all = lessons();
    let lesson = find(&all, "texel-coordinates").unwrap().clone();
    let base = load_preset(&lesson.preset).unwrap();
    let lecture = "Fly to the right edge (lecture's lookup)";
    let centred = "Fly to the right edge (centred lookup)";
    let k = |label: &str| {
        lesson
            .experiments
            .iter()
            .position(|x| x.label == label)
            .unwrap()
    };
    let mut h = start(lesson.clone());
    press(&mut h, lecture);
    settle(&mut h);
    assert_eq!(
        h.state().desc(),
        Some(&lesson.scene(k(lecture), &base).unwrap())
    );
    assert!(applied(&h, lecture) && !applied(&h, centred));
    assert_eq!(
        yellow(&h),
        0,
        "the lecture's lookup never reads the last column"
    );
    // The second after the first: the lesson's scene with its own edits (the centred lookup),
    // not the first's lookup with the second's camera.
    press(&mut h, centred);
    settle(&mut h);
    let second = lesson.scene(k(centred), &base).unwrap();
    assert_eq!(h.state().desc(), Some(&second));
    assert_eq!(
        second.objects[0].material.texture(),
        base.objects[0].material.texture()
    );
    assert!(applied(&h, centred) && !applied(&h, lecture));
    assert_eq!(undo_buttons(&h), 1);
    let seen = yellow(&h);
    assert!(
        seen > h.state().image().unwrap().rgba.len() / 4 / 10,
        "the centred lookup shows the yellow column up to the edge: {seen} pixels"
    );
    // Edit > Undo: back to the first experiment's scene, and the panel says so.
    undo(&mut h);
    assert_eq!(
        h.state().desc(),
        Some(&lesson.scene(k(lecture), &base).unwrap())
    );
    assert!(applied(&h, lecture) && !applied(&h, centred));
    // Again: the lesson's scene, nothing applied, no Undo in the panel.
    undo(&mut h);
    assert_eq!(h.state().desc(), Some(&base));
    for x in &lesson.experiments {
        assert!(!applied(&h, &x.label), "{}", x.label);
    }
    assert_eq!(undo_buttons(&h), 0);
    // Redo brings the applied state back with the scene.
    h.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::Z,
    );
    settle(&mut h);
    assert_eq!(
        h.state().desc(),
        Some(&lesson.scene(k(lecture), &base).unwrap())
    );
    assert!(applied(&h, lecture));
    // The panel's Undo: the lesson's scene too.
    press(&mut h, "Undo");
    assert_eq!(h.state().desc(), Some(&base));
    assert!(!applied(&h, lecture));
}

#[test]
fn shipped_scenes_are_saved_only_under_another_name() {
    let before = shipped_files();
    let all = lessons();
    let lesson = find(&all, "light-probes").unwrap().clone();
    assert!(lesson.preset.ends_with("presets/light-probe.ron"));
    let mut h = start(lesson.clone());
    press(&mut h, &lesson.experiments[0].label);
    assert!(h.state().is_dirty());
    // Ctrl+S on a shipped preset: Save as, saying why, never the replace prompt.
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.run_steps(3);
    let _ = h.get_by_label(
        "light-probe.ron ships with texplore and is read-only: save your scene under another name",
    );
    assert!(h.query_by_label("Replace the file?").is_none());
    // Typing the shipped file itself is refused, the dialog stays.
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&lesson.preset.display().to_string());
    h.step();
    h.get_by_label("Save").click();
    h.run_steps(3);
    assert!(h.query_by_label("Replace the file?").is_none());
    let _ = h.get_by_role_and_label(Role::TextInput, "Path");
    h.key_press(egui::Key::Escape);
    h.run_steps(3);
    // The dialog's closing resizes the viewport, which restarts the render: the image shows
    // once its first preview lands.
    crate::gui_common::settle(&mut h);
    // A learner's own change, then the next lesson: the prompt offers Save as, not Save.
    let image = h.get_by_label(IMAGE).rect();
    drag(
        &mut h,
        image.center(),
        image.center() + egui::vec2(60.0, 10.0),
    );
    press(&mut h, "Next lesson");
    let _ = h.get_by_label("Unsaved changes");
    assert!(h.query_by_label("Save and continue").is_none());
    press(&mut h, "Save as… and continue");
    let dir = tempfile::tempdir().unwrap();
    let mine = dir.path().join("my-probe.ron");
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&mine.display().to_string());
    h.step();
    h.get_by_label("Save").click();
    settle(&mut h);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    // Saved there, and the next lesson opened.
    let saved = load_preset(&mine).unwrap();
    assert_ne!(saved.camera, load_preset(&lesson.preset).unwrap().camera);
    assert_eq!(
        h.state().path(),
        all[all.iter().position(|l| l.name == lesson.name).unwrap() + 1].preset
    );
    assert_eq!(shipped_files(), before, "a shipped file changed on disk");
}

#[test]
fn lesson_text_is_markdown_and_the_panel_keeps_its_width_and_scrolls_to_the_top() {
    let all = lessons();
    let aliasing = find(&all, "aliasing").unwrap().clone();
    let mut h = start(all[0].clone());
    let left = h.get_by_label("Rescan lessons").rect().left();
    for l in all.iter().skip(1) {
        // Scrolled down to the question, then the next lesson: its title is back at the top.
        h.get_by_label("Show answer").scroll_to_me();
        h.run_steps(10);
        press(&mut h, "Next lesson");
        h.run_steps(5);
        assert_eq!(h.state().path(), l.preset);
        let title = h.get_by_label(&l.title).rect();
        let top = h.get_by_label("Next lesson").rect().bottom();
        assert!(
            title.top() > top && title.top() < top + 60.0,
            "{}: the title is at {} (the buttons end at {top})",
            l.name,
            title.top()
        );
        assert_eq!(
            h.get_by_label("Rescan lessons").rect().left(),
            left,
            "{}: the panel's width changed",
            l.name
        );
        if l.name == aliasing.name {
            // Each item of the list is its own line, not one run-on paragraph.
            let a = h.get_by_label_contains("a pixel covers many texels").rect();
            let b = h
                .get_by_label_contains("a pixel covers a fraction of a texel")
                .rect();
            assert!(b.top() > a.top(), "{a:?} {b:?}");
        }
    }
}
