//! Writing a mapping in the window (issue 28): pick `formula` in the mapping menu, type a
//! formula, see the image change; a mistake shows under the field and the image stays.

use crate::gui_common::{built, choose, desc, harness, image_bytes, settle, small_earth};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use texplore::gui::ExplorerApp;
use texplore::scene::MappingDesc;

/// Types `text` into the formula field labelled `label` and lets the render finish.
fn type_formula(h: &mut Harness<'_, ExplorerApp>, label: &str, text: &str) {
    h.get_by_role_and_label(Role::TextInput, label)
        .scroll_to_me();
    h.run_steps(3);
    h.get_by_role_and_label(Role::TextInput, label).focus();
    h.step();
    h.get_by_role_and_label(Role::TextInput, label)
        .set_text_value_accesskit(text);
    h.step();
    settle(h);
}

#[test]
fn typing_a_formula_changes_the_image_and_a_mistake_shows_under_the_field() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    let builtin = image_bytes(&h);

    choose(&mut h, "Mapping", "formula");
    let MappingDesc::Formula { u, v } = desc(&h).objects[0]
        .material
        .texture()
        .mapping()
        .cloned()
        .expect("a mapping")
    else {
        panic!("the mapping is a formula now");
    };
    assert_eq!(
        u, "fract(atan2(x, z) / tau)",
        "it starts from the spherical map's formulas"
    );
    assert!(v.starts_with("1 - acos("), "{v}");
    assert!(
        h.query_by_label_contains("finite differences").is_some(),
        "the derivative kind is shown"
    );
    let same = image_bytes(&h);
    let differing = builtin
        .iter()
        .zip(&same)
        .filter(|(a, b)| a.abs_diff(**b) > 2)
        .count();
    assert!(
        differing * 1000 <= builtin.len(),
        "the spherical formula renders the built-in Earth: {differing} bytes differ"
    );

    // A quarter turn: the continents move.
    type_formula(&mut h, "u =", "fract(atan2(x, z) / tau + 0.25)");
    let turned = image_bytes(&h);
    let moved = same
        .iter()
        .zip(&turned)
        .filter(|(a, b)| a.abs_diff(**b) > 16)
        .count();
    assert!(
        moved * 20 > same.len(),
        "the image changed: {moved} of {} bytes",
        same.len()
    );
    assert!(matches!(
        desc(&h).objects[0].material.texture().mapping(),
        Some(MappingDesc::Formula { u, .. }) if u == "fract(atan2(x, z) / tau + 0.25)"
    ));

    // A mistake: named under the field, the image stays as it was.
    type_formula(&mut h, "u =", "fract(atan2(x, z) / tau + w)");
    built(&mut h);
    assert!(
        h.query_by_label_contains("u: column 27: unknown name `w`")
            .is_some(),
        "the mistake is shown under the field"
    );
    assert_eq!(image_bytes(&h), turned, "the last good image stays");
}
