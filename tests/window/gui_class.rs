//! The window read from the back of a class (issue 37 §3): presentation mode's panel text at
//! least 20 px high at 1280x720, its captions beside the image and never over its lower third,
//! the render resized at once after F5; a click on a pixel shows the inspector with the answer
//! first.

use crate::gui_common::{built, settle};
use crate::gui_layout::lesson_two;
use egui::Key;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use texplore::gui::{AppOptions, ExplorerApp};

/// The app on lesson 2 in a 1280x720 window, the render at the preset's resolution (the
/// default: only presentation mode makes it follow the image).
fn classroom() -> Harness<'static, ExplorerApp> {
    let lesson = lesson_two();
    let mut h = Harness::builder()
        .with_size([1280.0, 720.0])
        .build_eframe(move |_cc| {
            ExplorerApp::with_options(
                lesson.preset.clone(),
                AppOptions {
                    lesson: Some(lesson),
                    ..AppOptions::default()
                },
            )
        });
    built(&mut h);
    h
}

#[test]
fn presentation_mode_text_is_20_px_and_the_captions_leave_the_image_uncovered() {
    let mut h = classroom();
    let normal = h.get_by_role_and_label(Role::Button, "Next lesson").rect();
    h.get_by_label("The lecture's lookup").click();
    built(&mut h);
    h.key_press(Key::F5);
    settle(&mut h);
    assert!(h.state().presenting());
    let image = h.state().image_rect().expect("the image drawn");
    assert!(image.width() >= 0.6 * 1280.0, "{image:?}");
    let look_for = h
        .get_by_label_contains("The lecture's lookup\nLook for: The yellow column")
        .rect();
    let question = h.get_by_label(&lesson_two().question).rect();
    for caption in [look_for, question] {
        // A 4:3 scene on a 16:9 window: the captions in the column beside the image.
        assert!(
            !caption.intersects(image.shrink(0.5)),
            "{caption:?} over {image:?}"
        );
        assert!(
            caption.right() <= 1280.0 && caption.bottom() <= 720.0,
            "{caption:?}"
        );
    }
    // The lesson beside the image, from the strip: its text at least 20 px high (one line of
    // a button is its text's row and a pixel of padding either side).
    h.get_by_label("Lesson").click();
    h.run_steps(4);
    let next = h.get_by_role_and_label(Role::Button, "Next lesson").rect();
    assert!(
        next.height() >= 22.0 && normal.height() < 22.0,
        "Next lesson is {} px high presenting, {} px otherwise",
        next.height(),
        normal.height()
    );
    let image = h.state().image_rect().expect("the image drawn");
    let lower_third = egui::Rect::from_min_max(
        egui::pos2(image.left(), image.top() + image.height() * 2.0 / 3.0),
        image.max,
    );
    let look_for = h
        .get_by_label_contains("The lecture's lookup\nLook for: The yellow column")
        .rect();
    assert!(
        !look_for.intersects(lower_third.shrink(0.5)),
        "{look_for:?} covers the lower third {lower_third:?}"
    );
}

#[test]
fn after_f5_the_render_takes_the_images_size_without_the_pointer_moving() {
    let mut h = classroom();
    settle(&mut h);
    let before = h.state().image().expect("an image");
    assert_eq!(
        (before.width, before.height),
        (640, 480),
        "the preset's size"
    );
    h.key_press(Key::F5);
    // No pointer moves from here on: only frames and the render.
    let deadline = std::time::Instant::now() + std::time::Duration::from_mins(2);
    loop {
        settle(&mut h);
        let image = h.state().image_rect().expect("the image drawn");
        let ppp = h.ctx.pixels_per_point();
        let want = (
            (image.width() * ppp).round() as u32,
            (image.height() * ppp).round() as u32,
        );
        let got = h.state().image().expect("an image");
        if (got.width.abs_diff(want.0), got.height.abs_diff(want.1)) <= (1, 1) {
            assert!(
                want.0 > 640,
                "presentation at 1280x720 renders larger: {want:?}"
            );
            break;
        }
        assert!(
            std::time::Instant::now() < deadline,
            "the render is {}x{}, the image {want:?}",
            got.width,
            got.height
        );
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
}

#[test]
fn a_click_on_a_pixel_shows_the_inspector_with_the_texel_first() {
    let mut h = classroom();
    settle(&mut h);
    assert!(
        h.query_by_role_and_label(Role::Button, "Inspector")
            .is_none(),
        "a lesson starts without the inspector"
    );
    // A click at the image's centre.
    h.get_by_role_and_label(Role::Image, "Rendered image")
        .click();
    h.run_steps(4);
    let _ = h.get_by_role_and_label(Role::Button, "Inspector");
    let texel = h.get_by_label_contains("Texel: column").rect();
    let working = h.get_by_label("The working, step by step:").rect();
    assert!(
        texel.bottom() <= working.top(),
        "{texel:?} then {working:?}"
    );
    // In view at 720 rows, without scrolling.
    assert!(texel.top() >= 0.0 && texel.bottom() <= 720.0, "{texel:?}");
    let inspection = h.state().inspection().expect("the pinned pixel");
    let read = inspection.image.as_ref().expect("lesson 2 reads an image");
    let pick = inspection
        .texels
        .iter()
        .find(|p| p.lookup == read.lookup)
        .expect("the lookup's texel");
    let _ = h.get_by_label(&format!(
        "Texel: column {}, row {} from the bottom of {}",
        pick.column, pick.row_from_bottom, read.image.name
    ));
}
