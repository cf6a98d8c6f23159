//! The explorer window (eframe + wgpu). The only module that knows egui exists: it edits a
//! [`SceneDesc`](crate::scene::SceneDesc), rebuilds the scene, and shows the render job's film.

mod app;

pub use app::ExplorerApp;

use std::path::PathBuf;

/// The preset the window opens on.
pub const DEFAULT_PRESET: &str = "presets/earth.ron";

/// Opens the window on `open` (a preset or a texplore PNG) or on the Earth.
///
/// # Errors
/// The window cannot be created (no display, no GPU adapter).
pub fn run(open: Option<PathBuf>) -> anyhow::Result<()> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("texplore")
            .with_inner_size([1280.0, 820.0])
            .with_min_inner_size([640.0, 420.0])
            .with_drag_and_drop(true),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    let path = open.unwrap_or_else(|| PathBuf::from(DEFAULT_PRESET));
    eframe::run_native(
        "texplore",
        options,
        Box::new(move |_cc| Ok(Box::new(ExplorerApp::open(path)))),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the window: {e}"))
}
