//! The explorer window (eframe + wgpu). The only module that knows egui exists: it edits a
//! [`SceneDesc`](crate::scene::SceneDesc), rebuilds the scene, shows the render job's film, and
//! displays what [`crate::inspect`] computes. One file per panel.

mod app;
mod compare;
mod files;
mod inspector;
mod lessons;
mod live;
mod overlay;
mod scene_panel;
mod texture_panel;
mod viewport;
mod widgets;

pub use app::{AppOptions, ExplorerApp};
pub use files::config_dir;

use std::path::PathBuf;

/// The preset the window opens on.
pub const DEFAULT_PRESET: &str = "presets/earth.ron";

/// Opens the window on `open` (a preset or a texplore PNG) or on the Earth.
///
/// # Errors
/// The window cannot be created (no display, no GPU adapter).
pub fn run(open: Option<PathBuf>) -> anyhow::Result<()> {
    let path = open.unwrap_or_else(|| PathBuf::from(DEFAULT_PRESET));
    run_app(path, None)
}

/// Opens the window on `lesson`: its preset, with the Lessons panel open on it.
///
/// # Errors
/// The window cannot be created (no display, no GPU adapter).
pub fn run_lesson(lesson: crate::lesson::Lesson) -> anyhow::Result<()> {
    run_app(lesson.preset.clone(), Some(lesson))
}

fn run_app(path: PathBuf, lesson: Option<crate::lesson::Lesson>) -> anyhow::Result<()> {
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
    };
    eframe::run_native(
        "texplore",
        options,
        Box::new(move |_cc| Ok(Box::new(ExplorerApp::with_options(path, app_options)))),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the window: {e}"))
}
