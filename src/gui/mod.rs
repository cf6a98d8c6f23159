//! The explorer window (eframe + wgpu). The only module that knows egui exists: it edits a
//! [`SceneDesc`](crate::scene::SceneDesc), rebuilds the scene, shows the render job's film, and
//! displays what [`crate::inspect`] computes. One file per panel.

mod app;
mod browse;
mod command;
mod compare;
mod document;
mod files;
mod help;
mod history;
mod inspector;
mod layout;
mod layout_check;
mod lessons;
mod links;
mod live;
mod overlay;
mod panes;
mod resolution;
mod scene_notices;
mod scene_panel;
#[cfg(not(target_arch = "wasm32"))]
mod storage;
mod texture_panel;
mod viewer;
mod viewport;
#[cfg(target_arch = "wasm32")]
pub mod web;
mod widgets;

pub use app::{AppOptions, ExplorerApp, Prefs};
pub use files::{BrowseFor, Browser, config_dir, screenshot_default};
pub use layout::{Layout, Pane, default_tree};
pub use layout_check::{MAX_DEPTH as MAX_LAYOUT_DEPTH, check_stored as check_stored_layout};
#[cfg(not(target_arch = "wasm32"))]
pub use storage::{Guarded, app_ron, guard as guard_storage};
pub use viewport::HINT as VIEW_HINT;

#[cfg(not(target_arch = "wasm32"))]
use std::path::PathBuf;

/// The preset the window opens on (in the shipped presets, [`default_preset`]).
pub const DEFAULT_PRESET: &str = "presets/earth.ron";

/// [`DEFAULT_PRESET`] in the copy of the shipped files, so the window opens on the Earth
/// wherever it is started (in the working folder if the copy cannot be made; in the page, where
/// the shipped files are mounted at their own paths, as it is).
#[must_use]
pub fn default_preset() -> std::path::PathBuf {
    #[cfg(target_arch = "wasm32")]
    return std::path::PathBuf::from(DEFAULT_PRESET);
    #[cfg(not(target_arch = "wasm32"))]
    crate::shipped::root().map_or_else(
        |_| PathBuf::from(DEFAULT_PRESET),
        |r| r.join(DEFAULT_PRESET),
    )
}

/// Opens the window on `open` (a preset or a texplore PNG), else on the scene open when it was
/// last closed, else on the Earth. eframe keeps the window's size, the panels' widths and
/// [`Prefs`] between runs (in its storage folder, `~/.local/share/texplore` on Linux).
///
/// # Errors
/// The window cannot be created (no display, no GPU adapter).
#[cfg(not(target_arch = "wasm32"))]
pub fn run(open: Option<PathBuf>, simd: crate::scene::SimdMode) -> anyhow::Result<()> {
    run_app(open, None, None, simd)
}

/// Opens the window on `lesson`: its preset, with the Lessons panel open on it.
///
/// # Errors
/// The window cannot be created (no display, no GPU adapter).
#[cfg(not(target_arch = "wasm32"))]
pub fn run_lesson(
    lesson: crate::lesson::Lesson,
    simd: crate::scene::SimdMode,
) -> anyhow::Result<()> {
    run_lesson_at(lesson, None, simd)
}

/// Opens the window on `lesson` (as [`run_lesson`]) with its experiment `experiment` (0-based)
/// in place, as a link to it does.
///
/// # Errors
/// The window cannot be created (no display, no GPU adapter).
#[cfg(not(target_arch = "wasm32"))]
pub fn run_lesson_at(
    lesson: crate::lesson::Lesson,
    experiment: Option<usize>,
    simd: crate::scene::SimdMode,
) -> anyhow::Result<()> {
    run_app(Some(lesson.preset.clone()), Some(lesson), experiment, simd)
}

#[cfg(not(target_arch = "wasm32"))]
fn run_app(
    open: Option<PathBuf>,
    lesson: Option<crate::lesson::Lesson>,
    experiment: Option<usize>,
    simd: crate::scene::SimdMode,
) -> anyhow::Result<()> {
    // The window's memory is checked before eframe reads it (see `storage`); what was done is
    // said on stderr and, once, in the window's status line.
    let memory = app_ron();
    let mut startup_notes = Vec::new();
    if let Some(path) = &memory {
        match guard_storage(path)? {
            Guarded::Fine => {}
            Guarded::Repaired(notes) => {
                for note in notes {
                    eprintln!("warning: {}: {note}", path.display());
                    startup_notes.push(format!("{}: {note}", path.display()));
                }
            }
            Guarded::MovedAside(to, why) => {
                let note = format!(
                    "{}: {why}; moved aside to {} and starting afresh",
                    path.display(),
                    to.display()
                );
                eprintln!("warning: {note}");
                startup_notes.push(note);
            }
        }
    }
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("texplore")
            .with_inner_size([1440.0, 900.0])
            .with_min_inner_size([800.0, 500.0])
            .with_drag_and_drop(true),
        renderer: eframe::Renderer::Wgpu,
        persistence_path: memory,
        ..Default::default()
    };
    let app_options = AppOptions {
        recent_file: config_dir().map(|d| d.join("recent.ron")),
        lesson,
        browser: Browser::default(),
        follow_viewport: true,
        simd,
        startup_notes,
    };
    eframe::run_native(
        "texplore",
        options,
        Box::new(move |cc| {
            let mut app = ExplorerApp::restore(cc.storage, open, app_options);
            app.lessons.then_experiment(experiment);
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the window: {e}"))
}
