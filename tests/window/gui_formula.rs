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

    // A mistake: named under the field, which keeps it; the scene and the image stay as
    // they were.
    type_formula(&mut h, "u =", "fract(atan2(x, z) / tau + w)");
    built(&mut h);
    assert!(
        h.query_by_label_contains("u: column 27: unknown name `w`")
            .is_some(),
        "the mistake is shown, naming the field"
    );
    assert_eq!(
        h.get_by_role_and_label(Role::TextInput, "u =")
            .value()
            .as_deref(),
        Some("fract(atan2(x, z) / tau + w)"),
        "the field keeps what was typed"
    );
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_eq!(image_bytes(&h), turned, "the last good image stays");
}

/// Pixels of the RGBA image whose colour `test` accepts.
fn count(image: &[u8], test: impl Fn(u8, u8, u8) -> bool) -> usize {
    image
        .chunks_exact(4)
        .filter(|p| test(p[0], p[1], p[2]))
        .count()
}

#[test]
fn comparing_with_a_built_in_mapping_paints_the_difference_and_gives_the_hint() {
    use crate::gui_common::wait_for_label;
    use crate::gui_exercise::percent;
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    choose(&mut h, "Mapping", "formula");
    type_formula(&mut h, "v =", "acos(y) / pi");
    h.get_by_role_and_label(Role::CheckBox, "Compare with a built-in mapping")
        .click();
    settle(&mut h);
    assert_eq!(desc(&h).render.view, texplore::texture::View::Difference);
    // v upside down: green (|dv|) over most of the Earth, and the hint.
    let verdict = wait_for_label(&mut h, "of the visible surface agrees with spherical");
    assert!(percent(&verdict) < 60.0, "{verdict}");
    let hint = wait_for_label(&mut h, "hint: ");
    assert!(hint.contains("v is upside down"), "{hint}");
    let _ = h.get_by_label("agree within the tolerance");
    let image = image_bytes(&h);
    let green = count(&image, |r, g, _| g > 120 && r < 60);
    assert!(green * 10 > image.len() / 4, "{green} green pixels");

    // The right formula: agreement, no hint, the object dark blue.
    type_formula(&mut h, "v =", "1 - acos(y / sqrt(x*x + y*y + z*z)) / pi");
    let verdict = wait_for_label(&mut h, "of the visible surface agrees with spherical");
    let verdict = if percent(&verdict) < 99.0 {
        // The comparison of the scene before may still have been shown: wait for the new one.
        settle(&mut h);
        wait_for_label(&mut h, "of the visible surface agrees with spherical")
    } else {
        verdict
    };
    assert!(percent(&verdict) >= 99.0, "{verdict}");
    assert!(h.query_by_label_contains("hint: ").is_none());
    let image = image_bytes(&h);
    let agreeing = count(&image, |r, g, b| b > 60 && r < 20 && g < 50);
    assert!(
        agreeing * 10 > image.len() / 4,
        "{agreeing} dark blue pixels"
    );
    assert_eq!(count(&image, |r, g, _| g > 120 && r < 60), 0);
    let _ = h.get_by_label("NaN or infinity: at no hit of this render");

    // acos(2 y) is NaN beyond |y| = 1/2: counted next to the formula.
    type_formula(&mut h, "v =", "1 - acos(2 * y) / pi");
    let nan = wait_for_label(&mut h, "NaN or infinity: at ");
    let n: u64 = nan
        .trim_start_matches("NaN or infinity: at ")
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{nan}"));
    assert!(n > 0, "{nan}");
}

#[test]
fn the_tolerance_decides_what_agrees() {
    use crate::gui_common::wait_for_label;
    use crate::gui_exercise::percent;
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    choose(&mut h, "Mapping", "formula");
    // A quarter turn: |du| = 0.25, 512 texels of the 2048-wide Earth.
    type_formula(&mut h, "u =", "fract(atan2(x, z) / tau + 0.25)");
    h.get_by_role_and_label(Role::CheckBox, "Compare with a built-in mapping")
        .click();
    settle(&mut h);
    let verdict = wait_for_label(&mut h, "of the visible surface agrees with spherical");
    assert!(percent(&verdict) < 1.0, "{verdict}");
    let hint = wait_for_label(&mut h, "hint: ");
    assert!(hint.contains("quarter turn"), "{hint}");

    h.get_by_label("tolerance (texels)")
        .set_value_accesskit(600.0);
    settle(&mut h);
    assert_eq!(desc(&h).render.compare.tolerance, 600.0);
    let verdict = wait_for_label(&mut h, "within 600 texels");
    assert!(percent(&verdict) >= 99.0, "{verdict}");
    assert!(h.query_by_label_contains("hint: ").is_none());
}
