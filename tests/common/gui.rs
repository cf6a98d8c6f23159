//! Helpers the window's tests share (`tests/window/`): a small Earth preset, the harness that
//! opens the real app on it, and waiting for its render. Kept out of `common/mod.rs`, so the
//! headless tests do not build the window; `tests/window/main.rs` declares the module once.

// Each test module uses a subset of these.
#![allow(dead_code)]

use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use texplore::gui::{AppOptions, ExplorerApp};
use texplore::scene::{SceneDesc, TextureDesc, load_preset, save_preset};

/// The window size every test opens: tall enough that the scene panel, above the inspector in
/// the panels' column, shows its editors without scrolling (as it did at full height).
pub const WINDOW: [f32; 2] = [1280.0, 1400.0];

/// The Earth preset at 160 x 120 and 4 spp, written to `dir` with a copy of its texture (so
/// the paths the window shows are the same on every machine).
pub fn small_earth(dir: &Path) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut desc = load_preset(&root.join("presets/earth.ron")).expect("earth preset");
    desc.render.width = 160;
    desc.render.height = 120;
    desc.render.spp = 4;
    let texture = "earth_2048x1024.jpg";
    std::fs::copy(root.join("assets").join(texture), dir.join(texture)).expect("copy texture");
    if let TextureDesc::Image { path, .. } = desc.objects[0].material.texture_mut() {
        texture.clone_into(path);
    }
    let path = dir.join("earth-small.ron");
    save_preset(&desc, &path).expect("write preset");
    path
}

/// The app on the preset at `path`, in a [`WINDOW`]-sized harness, with its first render done.
pub fn harness(path: PathBuf) -> Harness<'static, ExplorerApp> {
    harness_with(path, AppOptions::default())
}

/// [`harness`] with `options` (a replaced file dialog, say).
pub fn harness_with(path: PathBuf, options: AppOptions) -> Harness<'static, ExplorerApp> {
    let mut h = Harness::builder()
        .with_size(WINDOW)
        .build_eframe(move |_cc| ExplorerApp::with_options(path, options));
    settle(&mut h);
    h
}

/// Lets the scene build land and the render finish (within two minutes, or the test fails) and
/// the UI catch up with its last image. Scenes build off the UI thread: a frame takes in a
/// build that ended, so the window is stepped while one runs.
pub fn settle(h: &mut Harness<'_, ExplorerApp>) {
    let deadline = std::time::Duration::from_mins(2);
    let start = std::time::Instant::now();
    for _ in 0..3 {
        h.step();
        while h.state().building() {
            assert!(start.elapsed() < deadline, "the scene build ends");
            h.state().wait_for_render(deadline).expect("the build ends");
            h.step();
        }
        h.state()
            .wait_for_render(deadline)
            .expect("the render ends");
    }
    h.step();
    h.step();
}

/// Lets the scene build running (if any) land, without waiting for its render: for tests that
/// look at the description, the file or the panels rather than the image.
pub fn built(h: &mut Harness<'_, ExplorerApp>) {
    let deadline = std::time::Duration::from_mins(2);
    let start = std::time::Instant::now();
    h.run_steps(3);
    while h.state().building() {
        assert!(start.elapsed() < deadline, "the scene build ends");
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
    }
    h.run_steps(2);
}

/// The scene the window holds.
pub fn desc(h: &Harness<'_, ExplorerApp>) -> SceneDesc {
    h.state().desc().cloned().expect("a scene")
}

/// The window's current image, RGBA bytes.
pub fn image_bytes(h: &Harness<'_, ExplorerApp>) -> Vec<u8> {
    h.state().image().expect("an image").rgba.clone()
}

/// Picks `item` in the combo box labelled `combo` (scrolled into view first: the lower menus
/// of the scene panel start out of sight), then lets the render finish.
pub fn choose(h: &mut Harness<'_, ExplorerApp>, combo: &str, item: &str) {
    h.get_by_role_and_label(Role::ComboBox, combo)
        .scroll_to_me();
    h.run_steps(3);
    h.get_by_role_and_label(Role::ComboBox, combo).click();
    h.run_steps(3);
    h.get_by_label(item).click();
    settle(h);
}

/// Selects the object labelled `object` in the scene panel's list.
pub fn select(h: &mut Harness<'_, ExplorerApp>, object: &str) {
    h.get_by_label(object).scroll_to_me();
    h.run_steps(3);
    h.get_by_label(object).click();
    settle(h);
}

/// Ctrl+Z.
pub fn undo(h: &mut Harness<'_, ExplorerApp>) {
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(h);
}

/// Steps until a label containing `text` shows (one minute at most); returns its text.
pub fn wait_for_label(h: &mut Harness<'_, ExplorerApp>, text: &str) -> String {
    let started = Instant::now();
    loop {
        h.step();
        if let Some(n) = h.query_by_label_contains(text) {
            let node = n.accesskit_node();
            return node.value().or_else(|| node.label()).unwrap_or_default();
        }
        assert!(
            started.elapsed() < Duration::from_mins(1),
            "no label with '{text}' appeared"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}
