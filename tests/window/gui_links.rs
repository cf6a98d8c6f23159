//! Links that open a scene, in the window (issue 36 §5): *File > Copy link to this scene* shows
//! a link that reads back as the same scene; *File > Open link…* opens a lesson link on the
//! lesson with its experiment in place and the Lessons panel on it, and refuses a damaged link
//! with its reason, the scene unchanged.

use crate::gui_common::{desc, harness, settle, small_earth};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use std::path::Path;
use texplore::gui::ExplorerApp;
use texplore::link::{LINK_PRESET, Link, parse};
use texplore::scene::{TextureDesc, parse_preset};

fn file_menu(h: &mut Harness<'_, ExplorerApp>, item: &str) {
    h.get_by_label("File").click();
    h.run_steps(3);
    h.get_by_label(item).click();
    h.run_steps(3);
}

fn open_link(h: &mut Harness<'_, ExplorerApp>, link: &str) {
    file_menu(h, "Open link…");
    h.get_by_role_and_label(Role::TextInput, "Link")
        .set_text_value_accesskit(link);
    h.step();
    h.get_by_label("Open").click();
    settle(h);
}

#[test]
fn copy_link_to_this_scene_shows_a_link_to_the_same_scene() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(small_earth(dir.path()));
    file_menu(&mut h, "Copy link to this scene");
    let link = h
        .get_by_role_and_label(Role::MultilineTextInput, "Link")
        .accesskit_node()
        .value()
        .unwrap_or_default();
    // On the desktop the link is its fragment: the teacher's page address goes before it.
    assert!(link.starts_with("#texplore1-s-"), "{link}");
    let Link::Scene(text) = parse(&link).unwrap() else {
        panic!("not a scene link: {link}")
    };
    let back = parse_preset(&text, Path::new(LINK_PRESET)).unwrap();
    let shown = desc(&h);
    assert_eq!(back.objects.len(), shown.objects.len());
    assert_eq!(back.render, shown.render);
    // The Earth's image is a copy in the test's folder with the shipped bytes: the link names
    // the shipped file.
    let TextureDesc::Image { path, .. } = back.objects[0].material.texture() else {
        panic!("{back:?}")
    };
    assert_eq!(path, "../assets/earth_2048x1024.jpg");
}

#[test]
fn open_link_opens_a_lesson_at_its_experiment_and_refuses_a_damaged_link() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(small_earth(dir.path()));
    let before = desc(&h);
    // Cut short: refused in the dialog, the scene unchanged.
    file_menu(&mut h, "Open link…");
    h.get_by_role_and_label(Role::TextInput, "Link")
        .set_text_value_accesskit("https://school.example/texplore/#texplore1-s-8VRNb9");
    h.step();
    h.get_by_label("Open").click();
    h.run_steps(3);
    assert!(
        h.query_by_label_contains("this link does not open a scene: it is damaged")
            .is_some(),
        "the reason shows"
    );
    assert_eq!(desc(&h), before);
    h.get_by_label("Cancel").click();
    h.run_steps(3);

    open_link(
        &mut h,
        "https://school.example/texplore/#texplore1-l-01-constant-vs-image~1",
    );
    settle(&mut h);
    let d = desc(&h);
    assert!(
        matches!(d.objects[0].material.texture(), TextureDesc::Constant(_)),
        "the first experiment, a constant blue, is in place: {:?}",
        d.objects[0].material.texture()
    );
    assert!(
        h.query_by_label("A constant blue, seen from the side")
            .is_some()
    );
    assert!(
        h.query_by_label_contains("A texture is a colour that varies")
            .is_some(),
        "the Lessons panel is on lesson 1"
    );
}
