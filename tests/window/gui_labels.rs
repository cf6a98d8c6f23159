//! Labels, menus and hints of the window, headless: the Presets menu in the lecture's order
//! with descriptions, the texture's brightness multiplier, max anisotropy only for EWA, the
//! debug views' colour key, the camera's field of view kept across projections, the edge-on
//! hint, and panels that keep their width.

use crate::gui_common::{choose, harness, settle, small_earth};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use texplore::gui::ExplorerApp;
use texplore::names::Named;
use texplore::scene::{LECTURE_ORDER, ProjectionDesc, ProjectionKind, ShapeDesc};
use texplore::texture::{Filter, View};

#[test]
fn the_presets_menu_follows_the_lecture_and_shows_each_description() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    h.get_by_label("Presets").click();
    h.run_steps(3);
    let tops: Vec<f32> = LECTURE_ORDER
        .iter()
        .map(|name| h.get_by_role_and_label(Role::Button, name).rect().top())
        .collect();
    assert!(
        tops.windows(2).all(|w| w[0] < w[1]),
        "the menu lists {LECTURE_ORDER:?} top to bottom: {tops:?}"
    );
    for description in [
        "The Blue Marble under the spherical map: the lecture's Earth",
        "A photo on the generic rectangle under the rectangular map",
        "Checkers on a receding plane and on a sphere: aliasing at the horizon",
    ] {
        assert!(
            h.query_by_label(description).is_some(),
            "the menu shows '{description}'"
        );
    }
}

#[test]
fn the_texture_scale_is_a_brightness_multiplier_and_anisotropy_shows_only_for_ewa() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    assert_eq!(
        h.query_all_by_label("scale").count(),
        1,
        "only the transform's scale is called scale"
    );
    assert!(h.query_by_label("brightness multiplier").is_some());
    assert!(h.query_by_label("max anisotropy").is_none(), "nearest");
    choose(&mut h, "Filter", Filter::Trilinear.name());
    assert!(h.query_by_label("max anisotropy").is_none(), "trilinear");
    choose(&mut h, "Filter", Filter::Ewa.name());
    assert!(h.query_by_label("max anisotropy").is_some(), "EWA");
}

#[test]
fn the_from_assets_list_holds_only_the_presets_assets() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    // The Earth image lies beside the preset, not in an assets/ folder: the list is empty and
    // says the file is elsewhere (the working directory's assets/ are not the preset's).
    let combo = h.get_by_role_and_label(Role::ComboBox, "from assets/");
    assert_eq!(combo.value().as_deref(), Some("(a file elsewhere)"));
    combo.click();
    h.run_steps(3);
    assert!(
        h.query_by_label("checker_512.png").is_none(),
        "the working directory's assets are not listed"
    );
}

#[test]
fn each_debug_view_draws_its_colour_key_in_the_viewport() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    assert!(
        h.query_by_label("red: u").is_none(),
        "no key on the shaded image"
    );
    for (view, entries) in [
        (View::Uv, &["red: u", "green: v"][..]),
        (
            View::MipLevel,
            &["level magnified", "level 0", "level 5+"][..],
        ),
        (View::Seams, &["seam: u wraps", "pole", "tile edge"][..]),
    ] {
        choose(&mut h, "View", view.name());
        let image = h.get_by_label("Rendered image").rect();
        for entry in entries {
            let key = h.get_by_label(entry).rect();
            assert!(
                image.contains_rect(key),
                "'{entry}' is drawn on the image ({key:?} in {image:?})"
            );
        }
    }
}

#[test]
fn pinhole_fisheye_pinhole_gives_the_presets_field_of_view_back() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let projection =
        |h: &Harness<'_, ExplorerApp>| h.state().desc().expect("scene").camera.projection;
    assert_eq!(projection(&h), ProjectionDesc::Pinhole { fov: 40.0 });
    choose(&mut h, "Camera", ProjectionKind::Fisheye.name());
    assert!(matches!(projection(&h), ProjectionDesc::Fisheye { .. }));
    choose(&mut h, "Camera", ProjectionKind::Pinhole.name());
    assert_eq!(projection(&h), ProjectionDesc::Pinhole { fov: 40.0 });
}

#[test]
fn a_rectangle_turned_edge_on_says_why_nothing_renders() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    // The lecture's rectangle lies in y = 0; the camera looks along -z from (0, 0, 3.6): as it
    // comes, the eye is in its plane.
    h.state_mut().edit_scene(|d| {
        d.objects[0].shape = ShapeDesc::Rectangle;
        d.objects[0].transform.rotate = texplore::math::Vec3::ZERO;
    });
    settle(&mut h);
    let hint = "Earth is edge-on to the camera";
    assert!(
        h.query_all_by_label_contains(hint).next().is_some(),
        "the viewport says why"
    );
    // Turned to face the camera, it renders and the hint goes.
    h.state_mut()
        .edit_scene(|d| d.objects[0].transform.rotate = texplore::math::Vec3::new(90.0, 0.0, 0.0));
    settle(&mut h);
    assert!(h.query_all_by_label_contains(hint).next().is_none());
}

#[test]
fn panels_keep_their_width_when_their_content_grows() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let image = h.get_by_label("Rendered image").rect();
    // Wide numbers (a preset far from the origin) and a long image path.
    h.state_mut().edit_scene(|d| {
        d.objects[0].transform.translate = texplore::math::Vec3::new(123_456.78, -98_765.43, 1e5);
        d.camera.eye = texplore::math::Vec3::new(123_456.78, -98_765.43, 1e5 + 3.6);
        d.camera.look_at = d.objects[0].transform.translate;
    });
    settle(&mut h);
    let after = h.get_by_label("Rendered image").rect();
    assert_eq!(after.left(), image.left(), "the viewport did not move");
    assert_eq!(after.width(), image.width());
    // Hovering the image fills the inspector: the viewport stays put.
    h.hover_at(after.center());
    h.run_steps(4);
    assert_eq!(h.get_by_label("Rendered image").rect(), after);
    // The hint line is whole: it ends before the inspector begins.
    let hint = h.get_by_label(texplore::gui::VIEW_HINT).rect();
    // The inspector's tab: the pane's left edge.
    let inspector = h
        .get_by_role_and_label(egui::accesskit::Role::Button, "Inspector")
        .rect();
    assert!(
        hint.right() <= inspector.left(),
        "the hint {hint:?} runs under the inspector {inspector:?}"
    );
}
