//! The window's memory file (eframe's `app.ron`: the window's size, egui's memory, texplore's
//! [`Prefs`](super::Prefs) and [`Layout`](super::layout::Layout)), checked before eframe reads it.
//!
//! eframe reads that file whole, from any kind of file, and trusts what it holds: a FIFO there
//! hangs the window before it opens, a link to `/dev/zero` reads gigabytes, and a remembered
//! UI zoom of 0, NaN or 1e30 panics in winit at every start. So the window first reads it as
//! every other input is read ([`crate::input::read_own_input`]: a regular file, not through a
//! link, bounded in bytes) and checks what eframe would take from it:
//!
//! - a file that is not a regular file, is too large or is not eframe's format is moved aside
//!   (renamed, never deleted: `app.ron.refused-SECONDS`) and the window starts afresh;
//! - egui's memory with a zoom outside [`UI_SCALES`](super::app::UI_SCALES), or unreadable, is
//!   repaired (the zoom back to 1) or dropped; the window's remembered geometry with a
//!   non-finite or absurd number is dropped (the window opens at its default size).
//!
//! texplore's own entries are checked when read ([`Prefs::load`](super::Prefs::load) clamps the
//! UI scale, [`Layout::restore`](super::layout::Layout::restore) wants every pane once).

use super::app::UI_SCALES;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The largest memory file read (a real one is a few kilobytes).
pub const MAX_BYTES: u64 = 4 << 20;

/// The largest coordinate or size (points) a remembered window geometry may hold.
const MAX_GEOMETRY: f64 = 1e6;

/// eframe's key for egui's memory.
const EGUI_KEY: &str = "egui";
/// eframe's key for the window's geometry.
const WINDOW_KEY: &str = "window";

/// Where eframe keeps the window's memory (`~/.local/share/texplore/app.ron` on Linux).
#[must_use]
pub fn app_ron() -> Option<PathBuf> {
    eframe::storage_dir("texplore").map(|d| d.join("app.ron"))
}

/// What [`guard`] did to the memory file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Guarded {
    /// Nothing to do (no file, or a good one).
    Fine,
    /// Entries repaired or dropped, each with why; the file was rewritten.
    Repaired(Vec<String>),
    /// The file was moved aside to the path given, for the reason given.
    MovedAside(PathBuf, String),
}

/// Checks the memory file at `path` before eframe reads it (see the module's documentation).
///
/// # Errors
/// The file had to be moved aside and could not be, or the repaired file could not be written:
/// the window must not open on it.
pub fn guard(path: &Path) -> crate::Result<Guarded> {
    let meta = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Guarded::Fine),
        Err(e) => return Err(crate::Error::io(path, e)),
    };
    if meta.file_type().is_symlink() {
        return move_aside(path, "a symbolic link".to_owned());
    }
    if !meta.is_file() {
        return move_aside(path, "not a regular file".to_owned());
    }
    if meta.len() > MAX_BYTES {
        return move_aside(path, format!("{} bytes, more than {MAX_BYTES}", meta.len()));
    }
    let text = match crate::input::read_own_input(path, MAX_BYTES)
        .map_err(|e| e.to_string())
        .and_then(|b| String::from_utf8(b).map_err(|_| "not UTF-8 text".to_owned()))
    {
        Ok(t) => t,
        Err(e) => return move_aside(path, e),
    };
    let mut kv: HashMap<String, String> = match ron::from_str(&text) {
        Ok(kv) => kv,
        Err(e) => return move_aside(path, format!("not eframe's format: {e}")),
    };
    let notes = repair(&mut kv);
    if notes.is_empty() {
        return Ok(Guarded::Fine);
    }
    let out = ron::ser::to_string_pretty(&kv, ron::ser::PrettyConfig::default())
        .map_err(|e| crate::Error::invalid(path, e.to_string()))?;
    crate::output::write_own_file(path, out.as_bytes())?;
    Ok(Guarded::Repaired(notes))
}

/// Repairs or drops what eframe would choke on; returns what was done.
fn repair(kv: &mut HashMap<String, String>) -> Vec<String> {
    let mut notes = Vec::new();
    if let Some(memory) = kv.get(EGUI_KEY) {
        if let Ok(mut m) = ron::from_str::<egui::Memory>(memory) {
            let zoom = m.options.zoom_factor;
            if !(zoom.is_finite() && UI_SCALES.contains(&zoom)) {
                m.options.zoom_factor = 1.0;
                if let Ok(s) = ron::to_string(&m) {
                    kv.insert(EGUI_KEY.to_owned(), s);
                    notes.push(format!("the remembered UI zoom {zoom} is now 1"));
                } else {
                    kv.remove(EGUI_KEY);
                    notes.push(format!("the remembered UI zoom {zoom}: forgotten"));
                }
            }
        } else {
            kv.remove(EGUI_KEY);
            notes.push("egui's memory was unreadable: forgotten".to_owned());
        }
    }
    if let Some(window) = kv.get(WINDOW_KEY) {
        let sane = ron::from_str::<ron::Value>(window).is_ok_and(|v| numbers_within(&v));
        if !sane {
            kv.remove(WINDOW_KEY);
            notes.push(
                "the window's remembered size or position was not sane: forgotten".to_owned(),
            );
        }
    }
    notes
}

/// Whether every number in `v` is finite and at most [`MAX_GEOMETRY`] in size.
fn numbers_within(v: &ron::Value) -> bool {
    match v {
        ron::Value::Number(n) => {
            let x = (*n).into_f64();
            x.is_finite() && x.abs() <= MAX_GEOMETRY
        }
        ron::Value::Seq(items) => items.iter().all(numbers_within),
        ron::Value::Map(map) => map
            .iter()
            .all(|(k, v)| numbers_within(k) && numbers_within(v)),
        ron::Value::Option(Some(inner)) => numbers_within(inner),
        _ => true,
    }
}

/// Renames `path` aside (the link itself, not its target) so eframe starts afresh.
fn move_aside(path: &Path, why: String) -> crate::Result<Guarded> {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(format!(".refused-{secs}"));
    let aside = path.with_file_name(name);
    if aside.exists() || aside.is_symlink() {
        return Err(crate::Error::invalid(
            path,
            format!("{why}; cannot move it aside: {} exists", aside.display()),
        ));
    }
    std::fs::rename(path, &aside)
        .map_err(|e| crate::Error::invalid(path, format!("{why}; cannot move it aside: {e}")))?;
    Ok(Guarded::MovedAside(aside, why))
}
