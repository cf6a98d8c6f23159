//! The window in front of a class: the image keeps at least 60% of the width with the side
//! panels open, presentation mode (F5) gives it the window with the lesson's captions over it,
//! the UI scale keys work, and the render follows the image pane's size.

use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use std::path::Path;
use texplore::gui::{AppOptions, ExplorerApp};
use texplore::lesson::{Lesson, load_dir};
use texplore::scene::load_preset;

/// Lesson 2 (the texel lookup), its scene a 640x480 rectangle.
pub fn lesson_two() -> Lesson {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let loaded = load_dir(&dir).expect("the shipped lessons");
    loaded
        .lessons
        .into_iter()
        .find(|l| l.name.starts_with("02"))
        .expect("lesson 2")
}

/// The app started on lesson 2 in a `size` window, the render following the image pane as in
/// the real window when `follow`.
fn start(size: [f32; 2], follow: bool) -> Harness<'static, ExplorerApp> {
    let lesson = lesson_two();
    let mut h = Harness::builder().with_size(size).build_eframe(move |_cc| {
        ExplorerApp::with_options(
            lesson.preset.clone(),
            AppOptions {
                lesson: Some(lesson),
                follow_viewport: follow,
                ..AppOptions::default()
            },
        )
    });
    crate::gui_common::built(&mut h);
    h
}

/// The image pane's space for the image, and the image drawn in it.
fn image_rects(h: &mut Harness<'_, ExplorerApp>) -> (egui::Rect, egui::Rect) {
    crate::gui_common::settle(h);
    let pane = h.state().image_space().expect("the image pane was drawn");
    let image = h
        .get_by_role_and_label(Role::Image, "Rendered image")
        .rect();
    (pane, image)
}

#[test]
fn the_image_keeps_60_percent_of_the_width_with_the_lessons_and_the_inspector_open() {
    for size in [[1280.0, 720.0], [1920.0, 1080.0]] {
        let mut h = start(size, false);
        // A lesson starts with the inspector closed; I opens it (as a tab beside the lesson).
        h.key_press(Key::I);
        h.run_steps(3);
        assert!(
            h.query_by_role_and_label(Role::Button, "Inspector")
                .is_some()
        );
        assert!(h.query_by_role_and_label(Role::Button, "Lessons").is_some());
        assert!(h.query_by_role_and_label(Role::Button, "Scene").is_some());
        let (pane, image) = image_rects(&mut h);
        assert!(
            pane.width() >= 0.6 * size[0],
            "at {size:?} the image pane is {} wide",
            pane.width()
        );
        // The image fills the pane one way (its aspect fixes the other).
        assert!(
            (image.width() - pane.width()).abs() < 2.0
                || (image.height() - pane.height()).abs() < 2.0,
            "image {image:?} in pane {pane:?}"
        );
        // The texture panel opens as one more tab: the image keeps its width.
        h.get_by_role_and_label(Role::Button, "View").click();
        h.run_steps(2);
        h.get_by_label("Texture panel").click();
        h.run_steps(3);
        h.key_press(Key::Escape);
        h.run_steps(3);
        let (after, _) = image_rects(&mut h);
        assert!(
            (after.width() - pane.width()).abs() < 1.0,
            "{after:?} vs {pane:?}"
        );
    }
}

#[test]
fn presentation_mode_gives_the_image_the_window_with_the_lessons_captions() {
    let mut h = start([1280.0, 720.0], false);
    h.get_by_label("The lecture's lookup").click();
    crate::gui_common::built(&mut h);
    h.key_press(Key::F5);
    h.run_steps(3);
    assert!(h.state().presenting());
    // The panels are gone but for the strip's buttons.
    assert!(h.query_by_role_and_label(Role::Button, "Lessons").is_none());
    assert!(
        h.query_by_label("Lesson").is_some(),
        "the strip's Lessons button"
    );
    let (pane, _) = image_rects(&mut h);
    assert!(pane.width() >= 0.9 * 1280.0, "{pane:?}");
    // The experiment and what to look for, and the question, over the image.
    let look_for = h
        .query_all_by_label_contains("The lecture's lookup\nLook for: The yellow column")
        .count();
    assert_eq!(look_for, 1, "the Look for caption");
    let question = lesson_two().question;
    assert!(
        h.query_by_label(&question).is_some(),
        "the question caption"
    );
    // The inspector is one key away, and F5 brings the panels back.
    h.key_press(Key::I);
    h.run_steps(3);
    assert!(
        h.query_by_role_and_label(Role::Button, "Inspector")
            .is_some()
    );
    h.key_press(Key::I);
    h.key_press(Key::F5);
    h.run_steps(3);
    assert!(!h.state().presenting());
    assert!(h.query_by_role_and_label(Role::Button, "Lessons").is_some());
    assert!(
        h.query_by_role_and_label(Role::Button, "Inspector")
            .is_none()
    );
}

#[test]
fn the_ui_scale_keys_step_reset_and_are_kept() {
    let mut h = start([1280.0, 720.0], false);
    for _ in 0..3 {
        h.key_press_modifiers(Modifiers::COMMAND, Key::Equals);
        h.run_steps(2);
    }
    assert!((h.state().prefs().ui_scale - 1.3).abs() < 1e-4);
    assert!((h.ctx.zoom_factor() - 1.3).abs() < 1e-4);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Minus);
    h.run_steps(2);
    assert!((h.state().prefs().ui_scale - 1.2).abs() < 1e-4);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Num0);
    h.run_steps(2);
    assert!((h.ctx.zoom_factor() - 1.0).abs() < 1e-4);
}

#[test]
fn the_render_follows_the_image_panes_size() {
    let mut h = start([1280.0, 720.0], true);
    let deadline = std::time::Instant::now() + std::time::Duration::from_mins(2);
    loop {
        crate::gui_common::settle(&mut h);
        let (pane, _) = image_rects(&mut h);
        let ppp = h.ctx.pixels_per_point();
        // 4:3 fitted into the pane, in pixels.
        let fit = (pane.width() / 4.0).min(pane.height() / 3.0) * ppp;
        let want = ((4.0 * fit).round() as u32, (3.0 * fit).round() as u32);
        let image = h.state().image().expect("an image");
        if (image.width, image.height) == want {
            assert!(
                want.0 > 640,
                "larger than the preset's 640x480 at 1280x720: {want:?}"
            );
            break;
        }
        assert!(
            std::time::Instant::now() < deadline,
            "the render is {}x{}, the pane wants {want:?}",
            image.width,
            image.height
        );
        std::thread::sleep(std::time::Duration::from_millis(100));
        h.step();
    }
}

/// Scrolls the widget labelled `label` (of `role`) into view, waits for it to stop moving,
/// clicks it and lets the scene it asks for build.
fn press(h: &mut Harness<'_, ExplorerApp>, role: Role, label: &str) {
    // The pointer leaves the last button first: its tooltip would cover the next one.
    if let Some(image) = h.state().image_space() {
        h.hover_at(image.center());
        h.run_steps(2);
    }
    h.get_by_role_and_label(role, label).scroll_to_me();
    // Scrolling starts a frame later and animates: click once the widget has held still for
    // a few frames.
    let mut last = None;
    let mut still = 0;
    for _ in 0..120 {
        h.step();
        let r = h.get_by_role_and_label(role, label).rect();
        still = if last == Some(r) { still + 1 } else { 0 };
        if still >= 4 {
            break;
        }
        last = Some(r);
    }
    h.get_by_role_and_label(role, label).click();
    crate::gui_common::built(h);
}

/// The image pane's width as a share of the window's.
fn image_share(h: &Harness<'_, ExplorerApp>, width: f32) -> f32 {
    h.state().image_space().expect("the image pane").width() / width
}

#[test]
fn every_lesson_in_presentation_mode_keeps_the_image_wide_and_captions_each_experiment() {
    const W: f32 = 1280.0;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let lessons = load_dir(&dir).expect("the shipped lessons").lessons;
    let shipped = crate::gui_lessons_class::shipped_files();
    let first = lessons[0].clone();
    let mut h = Harness::builder()
        .with_size([W, 720.0])
        .build_eframe(move |_cc| {
            ExplorerApp::with_options(
                first.preset.clone(),
                AppOptions {
                    lesson: Some(first),
                    ..AppOptions::default()
                },
            )
        });
    crate::gui_common::built(&mut h);
    h.key_press(Key::F5);
    h.run_steps(3);
    assert!(h.state().presenting());
    assert!(image_share(&h, W) > 0.9, "the image alone");
    // The lesson beside the image, from the strip.
    press(&mut h, Role::Button, "Lesson");
    for (i, lesson) in lessons.iter().enumerate() {
        let base = load_preset(&lesson.preset).expect("the lesson's preset");
        assert_eq!(h.state().desc(), Some(&base), "{}", lesson.name);
        for (k, x) in lesson.experiments.iter().enumerate() {
            press(&mut h, Role::Button, &x.label);
            let want = lesson.scene(k, &base).expect("the experiment's scene");
            assert!(
                h.state().desc() == Some(&want),
                "{}: {} did not apply (error {:?}, button at {:?}, lessons pane {:?})",
                lesson.name,
                x.label,
                h.state().error(),
                h.get_by_role_and_label(Role::Button, &x.label).rect(),
                h.get_by_role_and_label(Role::Button, "Lessons").rect(),
            );
            let caption = format!("{}\nLook for: {}", x.label, x.look_for);
            assert_eq!(
                h.query_all_by_label(&caption).count(),
                1,
                "{}: the caption of {}",
                lesson.name,
                x.label
            );
            let share = image_share(&h, W);
            assert!(
                share >= 0.6,
                "{}: the image is {share} of the width",
                lesson.name
            );
            // Edit > Undo takes the experiment and its caption away: back to the lesson's
            // scene, where the experiment (even one built on another) was pressed from.
            h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
            crate::gui_common::built(&mut h);
            assert_eq!(
                h.state().desc(),
                Some(&base),
                "{}: undo {}",
                lesson.name,
                x.label
            );
            assert_eq!(h.query_all_by_label(&caption).count(), 0, "{}", lesson.name);
        }
        assert!(h.state().presenting(), "{}", lesson.name);
        if i + 1 < lessons.len() {
            press(&mut h, Role::Button, "Next lesson");
        }
    }
    assert!(
        crate::gui_lessons_class::shipped_files() == shipped,
        "a shipped file changed on disk during the walk"
    );
}
