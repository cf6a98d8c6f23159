//! The explorer window (eframe + wgpu). The only module that knows egui exists: it edits a
//! [`SceneDesc`](crate::scene::SceneDesc), rebuilds the scene, shows the render job's film, and
//! displays what [`crate::inspect`] computes. One file per panel.

mod app;
mod command;
mod compare;
mod document;
mod files;
mod help;
mod history;
mod inspector;
mod lessons;
mod live;
mod overlay;
mod scene_panel;
mod texture_panel;
mod viewer;
mod viewport;
#[cfg(target_arch = "wasm32")]
pub mod web;
mod widgets;

pub use app::{AppOptions, ExplorerApp, Prefs};
pub use files::{BrowseFor, Browser, config_dir, screenshot_default};
pub use viewport::HINT as VIEW_HINT;

#[cfg(not(target_arch = "wasm32"))]
use std::path::PathBuf;

/// The preset the window opens on.
pub const DEFAULT_PRESET: &str = "presets/earth.ron";

/// Opens the window on `open` (a preset or a texplore PNG), else on the scene open when it was
/// last closed, else on the Earth. eframe keeps the window's size, the panels' widths and
/// [`Prefs`] between runs (in its storage folder, `~/.local/share/texplore` on Linux).
///
/// # Errors
/// The window cannot be created (no display, no GPU adapter).
#[cfg(not(target_arch = "wasm32"))]
pub fn run(open: Option<PathBuf>) -> anyhow::Result<()> {
    run_app(open, None)
}

/// Opens the window on `lesson`: its preset, with the Lessons panel open on it.
///
/// # Errors
/// The window cannot be created (no display, no GPU adapter).
#[cfg(not(target_arch = "wasm32"))]
pub fn run_lesson(lesson: crate::lesson::Lesson) -> anyhow::Result<()> {
    run_app(Some(lesson.preset.clone()), Some(lesson))
}

#[cfg(not(target_arch = "wasm32"))]
fn run_app(open: Option<PathBuf>, lesson: Option<crate::lesson::Lesson>) -> anyhow::Result<()> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("texplore")
            .with_inner_size([1440.0, 900.0])
            .with_min_inner_size([800.0, 500.0])
            .with_drag_and_drop(true),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    let app_options = AppOptions {
        recent_file: config_dir().map(|d| d.join("recent.ron")),
        lesson,
        browser: Browser::default(),
    };
    eframe::run_native(
        "texplore",
        options,
        Box::new(move |cc| {
            Ok(Box::new(ExplorerApp::restore(
                cc.storage,
                open,
                app_options,
            )))
        }),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the window: {e}"))
}
