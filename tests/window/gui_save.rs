//! Saving and the shipped files (issue 37 §4): a save into texplore's copy of the shipped
//! files, a new name there included, is refused at the *Save* button, saying why, and a name in
//! the user's folder is offered.

use crate::gui_common::{harness, small_earth};
use egui::accesskit::Role;
use egui_kittest::kittest::{NodeT as _, Queryable as _};

#[test]
fn a_save_into_the_shipped_files_folder_is_refused_at_the_button_and_your_folder_offered() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(small_earth(dir.path()));
    h.get_by_label("File").click();
    h.run_steps(3);
    h.get_by_label("Save as…").click();
    h.run_steps(3);
    let root = texplore::shipped::root().expect("the shipped copy");
    let target = root.join("pr");
    h.get_by_role_and_label(Role::TextInput, "Path")
        .set_text_value_accesskit(&target.display().to_string());
    h.run_steps(3);
    let _ = h.get_by_label_contains("own copy of its shipped files");
    assert!(h.get_by_label("Save").accesskit_node().is_disabled());
    h.get_by_label("Save").click();
    h.run_steps(3);
    assert!(
        !target.exists(),
        "nothing written into the shipped files' folder"
    );
    // The user's folder, offered: it goes into the field and Save is enabled.
    h.get_by_label_contains("Save in your folder: ").click();
    h.run_steps(3);
    let offered = h
        .get_by_role_and_label(Role::TextInput, "Path")
        .accesskit_node()
        .value()
        .expect("the path");
    let offered = std::path::Path::new(&offered);
    assert!(!offered.starts_with(root), "{}", offered.display());
    assert_eq!(
        offered.extension().and_then(|e| e.to_str()),
        Some("ron"),
        "{}",
        offered.display()
    );
    assert!(!h.get_by_label("Save").accesskit_node().is_disabled());
    assert!(
        h.query_by_label_contains("own copy of its shipped files")
            .is_none()
    );
}
