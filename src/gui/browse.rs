//! The file chooser behind every *Browse…* button: the system's dialog, a test's stand-in, or,
//! where the system has none, the window's own path dialog (`files.rs` shows it).

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// What a *Browse…* button asks the file dialog for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BrowseFor {
    /// An image for the texture.
    Image,
    /// A PLY or OBJ mesh for the shape.
    Mesh,
    /// A preset or a texplore PNG to open.
    Scene,
    /// Where to save the preset.
    Preset,
    /// Where to save the screenshot.
    Screenshot,
}

/// A file chooser: what is asked for, the folder to start in, the file name to suggest;
/// `None` when the user cancels.
pub type BrowseFn = dyn Fn(BrowseFor, &Path, &str) -> Option<PathBuf> + Send + Sync;

/// The file chooser behind every *Browse…* button: the system's dialog (`rfd`: the XDG desktop
/// portal on Linux, the native panels on macOS and Windows), or, in tests, a function that
/// answers in its place.
///
/// Where the system has no dialog (no desktop portal: `rfd` then returns at once, as for a
/// cancel), the chooser notes why, and the window (`Files`) shows its own path dialog instead, saying so;
/// later *Browse…* clicks go straight to it.
#[derive(Clone, Default)]
pub struct Browser {
    replaced: Option<Arc<BrowseFn>>,
    /// Why the system's dialog is not used, once known; shared by every clone.
    missing: Arc<Mutex<Option<String>>>,
    /// A *Browse…* that found no system dialog: what it asked for and where, for the window (`Files`).
    fallback: Arc<Mutex<Option<(BrowseFor, PathBuf)>>>,
}

impl std::fmt::Debug for Browser {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.replaced.is_some() {
            "Browser(replaced)"
        } else {
            "Browser(native)"
        })
    }
}

/// A system dialog that answers faster than this did not open: nobody cancels a dialog in
/// under a quarter of a second.
#[cfg(not(target_arch = "wasm32"))]
const NO_DIALOG: std::time::Duration = std::time::Duration::from_millis(250);

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

impl Browser {
    /// A chooser that calls `f` instead of showing the system's dialog.
    #[must_use]
    pub fn replaced_by(
        f: impl Fn(BrowseFor, &Path, &str) -> Option<PathBuf> + Send + Sync + 'static,
    ) -> Self {
        Self {
            replaced: Some(Arc::new(f)),
            ..Self::default()
        }
    }

    /// A chooser on a system without a file dialog (`why` is what the window says): every
    /// *Browse…* opens the window's own path dialog.
    #[must_use]
    pub fn without_dialog(why: &str) -> Self {
        let b = Self::default();
        *lock(&b.missing) = Some(why.to_owned());
        b
    }

    /// Why the system's dialog is not used, if it is not.
    #[must_use]
    pub fn missing(&self) -> Option<String> {
        lock(&self.missing).clone()
    }

    /// The *Browse…* that fell back to the window's own dialog since the last call.
    pub(super) fn take_fallback(&self) -> Option<(BrowseFor, PathBuf)> {
        lock(&self.fallback).take()
    }

    /// Asks for a file: `start` is the folder shown first, `name` the suggested file name of a
    /// save. Blocks until the dialog closes. `None`: cancelled, or no system dialog (then the
    /// window's own path dialog opens, see [`Browser`]).
    #[must_use]
    pub fn pick(&self, what: BrowseFor, start: &Path, name: &str) -> Option<PathBuf> {
        if let Some(f) = &self.replaced {
            return f(what, start, name);
        }
        // The page's dialogs are asynchronous: what the user chooses arrives later, as a drop.
        #[cfg(target_arch = "wasm32")]
        {
            super::web::pick(what, start, name)
        }
        #[cfg(not(target_arch = "wasm32"))]
        {
            if self.missing().is_none() {
                let asked = web_time::Instant::now();
                let picked = native_pick(what, start, name);
                if picked.is_some() || asked.elapsed() >= NO_DIALOG {
                    return picked;
                }
                *lock(&self.missing) = Some(
                    "The system's file dialog did not open (no XDG desktop portal answered): \
                     type the path here instead."
                        .to_owned(),
                );
            }
            *lock(&self.fallback) = Some((what, start.to_path_buf()));
            None
        }
    }
}

/// The system's dialog (`rfd`).
#[cfg(not(target_arch = "wasm32"))]
fn native_pick(what: BrowseFor, start: &Path, name: &str) -> Option<PathBuf> {
    let start = std::path::absolute(start).unwrap_or_else(|_| start.to_path_buf());
    let d = rfd::FileDialog::new().set_directory(start);
    match what {
        BrowseFor::Image => d
            .set_title("Choose an image")
            .add_filter("Images", &IMAGE_EXTENSIONS)
            .pick_file(),
        BrowseFor::Mesh => d
            .set_title("Choose a mesh")
            .add_filter("Meshes (PLY, OBJ)", &["ply", "obj"])
            .pick_file(),
        BrowseFor::Scene => d
            .set_title("Open a preset or a texplore PNG")
            .add_filter("Presets and texplore PNGs", &["ron", "png"])
            .pick_file(),
        BrowseFor::Preset => d
            .set_title("Save the scene as a preset")
            .add_filter("Preset (.ron)", &["ron"])
            .set_file_name(name)
            .save_file(),
        BrowseFor::Screenshot => d
            .set_title("Save a screenshot")
            .add_filter("PNG", &["png"])
            .set_file_name(name)
            .save_file(),
    }
}

/// The image files texplore reads, by extension.
pub const IMAGE_EXTENSIONS: [&str; 9] = [
    "png", "jpg", "jpeg", "hdr", "exr", "tif", "tiff", "ppm", "pgm",
];
