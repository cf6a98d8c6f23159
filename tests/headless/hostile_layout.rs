//! The window's stored layout and geometry as a hostile user leaves them (issue 38 §1 and §3):
//! a container listing itself, its parent or the root, 40,000 nested one-child columns, shares
//! of NaN, 0 or infinity, an exact width or height of NaN or -1, a root or a child that does
//! not exist; a window size of -1, 0 or 70 x 30 and a position of (-1e6, 1e6). Each used to
//! abort every start (a stack overflow in egui_tiles) or open a blank or unusable window.
//! Checked before eframe reads the file: the layout is dropped (the file as it was kept
//! beside it, the other entries kept byte for byte), the geometry forgotten; and checked again
//! when the window reads it (the page has no file), falling back to the default arrangement
//! with a note.

use crate::layouts::{bad_layouts, ron_of};
use std::collections::HashMap;
use std::path::Path;
use texplore::gui::{Guarded, Layout, default_tree, guard_storage};

/// eframe's storage in memory (what the page's local storage holds).
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
fn a_bad_stored_layout_is_refused_when_read_and_the_default_taken_saying_why() {
    for (name, words, text) in bad_layouts() {
        let storage = Memory(HashMap::from([(Layout::KEY.to_owned(), text)]));
        let (layout, why) = Layout::restore(Some(&storage));
        let why = why.unwrap_or_else(|| panic!("{name}: accepted"));
        assert!(
            why.contains("stored window layout was not used"),
            "{name}: {why}"
        );
        assert!(why.contains(words), "{name}: {why}");
        assert_eq!(
            ron_of(&layout.tree).len(),
            ron_of(&default_tree()).len(),
            "{name}: the default arrangement"
        );
    }
    // A good one is kept without a word.
    let storage = Memory(HashMap::from([(
        Layout::KEY.to_owned(),
        ron_of(&default_tree()),
    )]));
    assert_eq!(Layout::restore(Some(&storage)).1, None);
}

/// The entries of `dir` whose name starts with `app.ron.refused-`.
fn refused(dir: &Path) -> Vec<std::path::PathBuf> {
    std::fs::read_dir(dir)
        .expect("read dir")
        .map(|e| e.expect("entry").path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("app.ron.refused-"))
        })
        .collect()
}

#[test]
fn a_bad_stored_layout_is_dropped_from_the_file_which_is_kept_aside_and_the_rest_kept() {
    let prefs = "(last_scene: None, camera_is_unsaved: true, ui_scale: 1.5)".to_owned();
    for (name, _, layout) in bad_layouts() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("app.ron");
        let kv = HashMap::from([
            ("texplore-prefs".to_owned(), prefs.clone()),
            (Layout::KEY.to_owned(), layout),
        ]);
        std::fs::write(&path, ron::to_string(&kv).expect("ron")).expect("write");
        let before = std::fs::read(&path).expect("read");
        match guard_storage(&path).expect("guarded") {
            Guarded::Repaired(notes) => assert!(
                notes
                    .iter()
                    .any(|n| n.contains("window layout was not used")
                        && n.contains("app.ron.refused-")),
                "{name}: {notes:?}"
            ),
            other => panic!("{name}: {other:?}"),
        }
        let kv: HashMap<String, String> =
            ron::from_str(&std::fs::read_to_string(&path).expect("read")).expect("eframe's");
        assert!(!kv.contains_key(Layout::KEY), "{name}: dropped");
        assert_eq!(kv["texplore-prefs"], prefs, "{name}: the rest kept");
        let aside = refused(dir.path());
        assert_eq!(aside.len(), 1, "{name}");
        assert_eq!(std::fs::read(&aside[0]).expect("read"), before, "{name}");
        assert_eq!(
            guard_storage(&path).expect("guarded"),
            Guarded::Fine,
            "said once"
        );
    }
}

#[test]
fn a_window_size_below_the_minimum_or_a_position_off_every_screen_is_forgotten() {
    let geometry = |size: (f64, f64), at: (f64, f64)| {
        format!(
            "(normal_geometry: (outer_position_pixels: Some((x: {}, y: {})), scale_factor: 1.0, \
             inner_size_points: (x: {}, y: {})), fullscreen: false, maximized: false)",
            at.0, at.1, size.0, size.1
        )
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("app.ron");
    let write = |window: &str| {
        let kv = HashMap::from([("window".to_owned(), window.to_owned())]);
        std::fs::write(&path, ron::to_string(&kv).expect("ron")).expect("write");
    };
    let good = geometry((1440.0, 900.0), (10.0, 20.0));
    write(&good);
    assert_eq!(
        guard_storage(&path).expect("guarded"),
        Guarded::Fine,
        "{good}"
    );
    for (size, at) in [
        ((-1.0, -1.0), (10.0, 20.0)),
        ((0.0, 0.0), (10.0, 20.0)),
        ((70.0, 30.0), (10.0, 20.0)),
        ((1440.0, 900.0), (-1e6, 1e6)),
        ((1440.0, 900.0), (40_000.0, 0.0)),
        ((1e5, 900.0), (0.0, 0.0)),
    ] {
        let window = geometry(size, at);
        write(&window);
        match guard_storage(&path).expect("guarded") {
            Guarded::Repaired(notes) => {
                assert!(notes[0].contains("forgotten"), "{window}: {notes:?}");
            }
            other => panic!("{window}: {other:?}"),
        }
        let kv: HashMap<String, String> =
            ron::from_str(&std::fs::read_to_string(&path).expect("read")).expect("eframe's");
        assert!(!kv.contains_key("window"), "{window}");
    }
}
