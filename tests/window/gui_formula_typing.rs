//! Typing a formula in the Scene panel key by key (issue 37 §1): the field keeps every key,
//! valid or not; each prefix's mistake shows under its field with the checker's column and a
//! caret; the scene keeps the last valid formulas until the typing is valid again, and the
//! typing in one field is one undo step.

use crate::gui_common::{choose, desc, harness, image_bytes, settle, small_earth, undo};
use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use texplore::gui::ExplorerApp;
use texplore::mapping::FormulaError;
use texplore::mapping::formula::{Expr, MAPPING_VARS, TEXTURE_VARS};
use texplore::scene::{MappingDesc, TextureDesc};

/// The lecture's u of the spherical map, the formula typed.
const TYPED: &str = "fract(atan2(x, z) / tau)";

/// What the field labelled `label` shows.
fn field(h: &Harness<'_, ExplorerApp>, label: &str) -> String {
    h.get_by_role_and_label(Role::TextInput, label)
        .value()
        .unwrap_or_default()
}

/// Puts the keyboard in the field labelled `label` and selects its text.
fn enter_field(h: &mut Harness<'_, ExplorerApp>, label: &str) {
    h.get_by_role_and_label(Role::TextInput, label)
        .scroll_to_me();
    h.run_steps(3);
    h.get_by_role_and_label(Role::TextInput, label).focus();
    h.step();
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    h.step();
    assert!(
        h.get_by_role_and_label(Role::TextInput, label).is_focused(),
        "{label} has the keyboard"
    );
}

/// Whether `error` is shown, as a label and with its caret line, and no other mistake of the
/// same field (`field: column ...`) is.
fn assert_shown(h: &Harness<'_, ExplorerApp>, name: &str, error: Option<&FormulaError>, at: &str) {
    let shown: Vec<String> = h
        .query_all_by_label_contains(&format!("{name}: "))
        .filter_map(|n| {
            let node = n.accesskit_node();
            node.value().or_else(|| node.label())
        })
        .filter(|l| l.starts_with(&format!("{name}: ")))
        .collect();
    match error {
        Some(e) => {
            assert_eq!(shown, vec![e.to_string()], "typed `{at}`");
            if let Some(pointer) = e.pointer() {
                assert!(
                    h.query_by_label(&pointer).is_some(),
                    "typed `{at}`: the caret line\n{pointer}"
                );
            }
        }
        None => assert!(shown.is_empty(), "typed `{at}`: no mistake, yet {shown:?}"),
    }
}

/// The mapping's formulas in the scene.
fn mapping(h: &Harness<'_, ExplorerApp>) -> (String, String) {
    match desc(h).objects[0].material.texture().mapping() {
        Some(MappingDesc::Formula { u, v }) => (u.clone(), v.clone()),
        other => panic!("a formula mapping, not {other:?}"),
    }
}

/// A formula field: its label, its name in the checker's messages and the checker's inputs.
struct Field<'a> {
    label: &'a str,
    name: &'a str,
    vars: &'a [&'a str],
    /// Whether a valid prefix goes into the scene (false: the field's group still lacks
    /// another field, so the scene keeps `before`).
    applies: bool,
}

/// Types `text` one key at a time into the selected field `f`: after each key the field holds
/// the prefix, the prefix's mistake (as the checker finds it) is shown under it, and `scene`
/// (the formula the scene holds) is the last valid prefix, or `before` while none was. Returns
/// how many prefixes were refused.
fn type_keys(
    h: &mut Harness<'_, ExplorerApp>,
    f: &Field<'_>,
    text: &str,
    before: &str,
    scene: impl Fn(&Harness<'_, ExplorerApp>) -> String,
) -> usize {
    let Field {
        label,
        name,
        vars,
        applies,
    } = *f;
    let mut last_valid = before.to_owned();
    let mut refused = 0;
    for (end, c) in text.char_indices() {
        let prefix = &text[..end + c.len_utf8()];
        h.get_by_role_and_label(Role::TextInput, label)
            .type_text(&c.to_string());
        h.run_steps(2);
        assert_eq!(field(h, label), prefix, "the field keeps every key");
        let error = Expr::compile(name, prefix, vars).err();
        assert_shown(h, name, error.as_ref(), prefix);
        if error.is_some() {
            refused += 1;
        } else if applies {
            prefix.clone_into(&mut last_valid);
        }
        assert_eq!(
            scene(h),
            last_valid,
            "typed `{prefix}`: the scene holds the last valid formula"
        );
    }
    refused
}

/// Takes the keyboard out of the text field (Escape), lets the scene build and render.
fn leave_field(h: &mut Harness<'_, ExplorerApp>) {
    h.key_press(Key::Escape);
    settle(h);
}

/// The mapping's field `name` (`u` or `v`).
fn mapping_field(name: &str) -> Field<'_> {
    Field {
        label: if name == "u" { "u =" } else { "v =" },
        name,
        vars: &MAPPING_VARS,
        applies: true,
    }
}

#[test]
fn a_mapping_formula_typed_key_by_key_keeps_every_key_and_applies_once_valid() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    // From the rectangular map: its formulas are not the one typed.
    choose(&mut h, "Mapping", "rectangular");
    choose(&mut h, "Mapping", "formula");
    let (u0, v0) = mapping(&h);
    assert_eq!((u0.as_str(), v0.as_str()), ("(z + 1) / 2", "(x + 1) / 2"));
    let start = image_bytes(&h);

    enter_field(&mut h, "u =");
    let refused = type_keys(&mut h, &mapping_field("u"), TYPED, &u0, |h| mapping(h).0);
    assert_eq!(
        refused,
        TYPED.len() - 1,
        "no prefix but the whole is a formula"
    );
    leave_field(&mut h);
    assert_eq!(mapping(&h), (TYPED.to_owned(), v0.clone()), "applied");
    assert_eq!(field(&h, "u ="), TYPED);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    let turned = image_bytes(&h);
    assert_ne!(turned, start, "the image follows the new u");

    // The typing was one step: one undo takes it all back, one redo brings it again.
    assert_eq!(h.state().undo_label(), Some("mapping of Earth"));
    undo(&mut h);
    assert_eq!(mapping(&h), (u0.clone(), v0.clone()));
    assert_eq!(
        field(&h, "u ="),
        u0,
        "the field shows the scene's formula again"
    );
    assert_eq!(image_bytes(&h), start);
    assert_eq!(
        h.state().undo_label(),
        Some("mapping of Earth"),
        "the step before: the menu's formula"
    );
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    settle(&mut h);
    assert_eq!(mapping(&h).0, TYPED);

    // The same into v: a second field, a second step.
    enter_field(&mut h, "v =");
    type_keys(&mut h, &mapping_field("v"), TYPED, &v0, |h| mapping(h).1);
    leave_field(&mut h);
    assert_eq!(mapping(&h), (TYPED.to_owned(), TYPED.to_owned()));
    undo(&mut h);
    assert_eq!(mapping(&h), (TYPED.to_owned(), v0), "v alone goes back");
}

#[test]
fn a_formula_with_valid_prefixes_is_one_undo_step() {
    // Step 4 of issue 37's report: `y`, then ` *` (wrong), then ` 0.5`; `y * 0.55` has two
    // valid prefixes after `y`, each applied, and all of it is one step.
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    choose(&mut h, "Mapping", "formula");
    let (u0, v0) = mapping(&h);
    enter_field(&mut h, "v =");
    let refused = type_keys(&mut h, &mapping_field("v"), "y * 0.55", &v0, |h| {
        mapping(h).1
    });
    assert!(refused >= 2, "`y *` and `y * ` are refused: {refused}");
    leave_field(&mut h);
    assert_eq!(mapping(&h).1, "y * 0.55");
    undo(&mut h);
    assert_eq!(
        mapping(&h),
        (u0, v0),
        "one undo takes the whole typing back"
    );
}

/// The colour texture's formulas (grey, r, g, b) in the scene.
fn colours(h: &Harness<'_, ExplorerApp>) -> [String; 4] {
    match desc(h).objects[0].material.texture() {
        TextureDesc::Formula { grey, r, g, b, .. } => {
            [grey.clone(), r.clone(), g.clone(), b.clone()]
        }
        other => panic!("a formula texture, not {other:?}"),
    }
}

#[test]
fn colour_formulas_typed_key_by_key_apply_as_grey_alone_or_three_channels() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    choose(&mut h, "Texture", "Formula");
    let [grey0, ..] = colours(&h);
    assert!(!grey0.is_empty());

    // grey: the lecture's u as a grey ramp round the Earth.
    enter_field(&mut h, "grey =");
    let grey = Field {
        label: "grey =",
        name: "grey",
        vars: &TEXTURE_VARS,
        applies: true,
    };
    type_keys(&mut h, &grey, TYPED, &grey0, |h| colours(h)[0].clone());
    leave_field(&mut h);
    assert_eq!(colours(&h)[0], TYPED);
    let ramp = image_bytes(&h);
    undo(&mut h);
    assert_eq!(colours(&h)[0], grey0, "one step");
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    settle(&mut h);

    // Per channel: grey emptied first; until r, g and b are all written the scene keeps grey,
    // and the group says what is missing.
    enter_field(&mut h, "grey =");
    h.key_press(Key::Backspace);
    h.run_steps(2);
    assert_eq!(field(&h, "grey ="), "");
    assert!(
        h.query_by_label("r, g, b missing: write grey alone, or r, g and b")
            .is_some()
    );
    assert_eq!(colours(&h)[0], TYPED, "the scene keeps the last valid grey");
    enter_field(&mut h, "r =");
    // The scene's r stays empty: g and b are missing, so nothing applies yet.
    let red = Field {
        label: "r =",
        name: "r",
        vars: &TEXTURE_VARS,
        applies: false,
    };
    type_keys(&mut h, &red, TYPED, "", |h| colours(h)[1].clone());
    assert!(
        h.query_by_label("g, b missing: write grey alone, or r, g and b")
            .is_some()
    );
    assert_eq!(
        colours(&h),
        [
            TYPED.to_owned(),
            String::new(),
            String::new(),
            String::new()
        ]
    );
    enter_field(&mut h, "g =");
    h.get_by_role_and_label(Role::TextInput, "g =")
        .type_text("v");
    h.run_steps(2);
    enter_field(&mut h, "b =");
    h.get_by_role_and_label(Role::TextInput, "b =")
        .type_text("0.5");
    h.run_steps(2);
    leave_field(&mut h);
    assert_eq!(
        colours(&h),
        [
            String::new(),
            TYPED.to_owned(),
            "v".to_owned(),
            "0.5".to_owned()
        ],
        "the three channels apply together, grey emptied with them"
    );
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    assert_ne!(image_bytes(&h), ramp, "red, green and blue, not grey");
}
