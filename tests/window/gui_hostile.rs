//! The window on hostile input (issue 38 §1 and §3): a preset whose formulas overflowed the
//! stack (12 operands of `/` killed the window) opens, renders and shows each formula in the
//! Scene panel; a stored layout that aborted every start (a container listing itself, 40,000
//! nested columns) or left the window blank (shares of NaN, a width of -1, a root that does
//! not exist) gives way to the default layout, with the image shown and a note saying why.

use crate::formulas::{chain, fill};
use crate::gui_common::{WINDOW, desc, select, settle, small_earth};
use crate::layouts::bad_layouts;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use std::collections::HashMap;
use texplore::gui::{AppOptions, ExplorerApp, Layout};
use texplore::scene::{MappingDesc, load_preset, save_preset};

#[test]
fn a_preset_of_formulas_that_overflowed_the_stack_opens_and_shows_each() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = small_earth(dir.path());
    let mut d = load_preset(&path).expect("preset");
    let base = d.objects[0].clone();
    let formulas = [
        ("twelve", chain("/", 12)),
        ("twenty", chain("+", 20)),
        ("products", chain("*", 20)),
        ("longest", fill("x", "+", "x")),
        (
            "nested",
            fill(
                &format!("{}x{}", "x/(".repeat(32), ")".repeat(32)),
                "^",
                "x",
            ),
        ),
        ("minus", "-".repeat(4095) + "x"),
    ];
    d.objects = formulas
        .iter()
        .enumerate()
        .map(|(i, (name, u))| {
            let mut o = base.clone();
            o.name = (*name).to_owned();
            o.transform.translate[0] = i as f32 * 2.5 - 6.0;
            o.material.texture_mut().set_mapping(MappingDesc::Formula {
                u: u.clone(),
                v: "y".into(),
            });
            o
        })
        .collect();
    save_preset(&d, &path).expect("write preset");
    let mut h = Harness::builder()
        .with_size(WINDOW)
        .build_eframe(move |_cc| ExplorerApp::with_options(path, AppOptions::default()));
    settle(&mut h);
    assert!(h.state().image().is_some(), "the scene rendered");
    assert_eq!(desc(&h).objects.len(), formulas.len());
    for (i, (name, _)) in formulas.iter().enumerate() {
        select(&mut h, &format!("{i}: {name}"));
        assert!(
            h.query_by_label_contains("derivatives: symbolic").is_some(),
            "{name}: the Scene panel checked the formula and says how it is differentiated"
        );
    }
}

/// eframe's storage in memory, holding only a layout.
#[derive(Default)]
struct Memory(HashMap<String, String>);

impl eframe::Storage for Memory {
    fn get_string(&self, key: &str) -> Option<String> {
        self.0.get(key).cloned()
    }
    fn set_string(&mut self, key: &str, value: String) {
        self.0.insert(key.to_owned(), value);
    }
    fn remove_string(&mut self, key: &str) {
        self.0.remove(key);
    }
    fn flush(&mut self) {}
}

#[test]
fn a_stored_layout_that_aborted_or_blanked_the_window_gives_way_to_the_default() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = small_earth(dir.path());
    for (name, words, layout) in bad_layouts() {
        let storage = Memory(HashMap::from([(Layout::KEY.to_owned(), layout)]));
        let open = path.clone();
        let mut h = Harness::builder()
            .with_size(WINDOW)
            .build_eframe(move |_cc| {
                ExplorerApp::restore(Some(&storage), Some(open), AppOptions::default())
            });
        settle(&mut h);
        let notice = h.state().notice().unwrap_or_default().to_owned();
        assert!(
            notice.contains("stored window layout was not used") && notice.contains(words),
            "{name}: {notice}"
        );
        let image = h
            .get_by_role_and_label(Role::Image, "Rendered image")
            .rect();
        assert!(
            image.width() > WINDOW[0] * 0.5 && image.height() > 100.0,
            "{name}: the image is shown ({image:?})"
        );
        assert!(
            h.query_by_label_contains("Scene").is_some(),
            "{name}: the panels are shown"
        );
    }
}
