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
//! - the window's remembered size below its minimum (800 x 500 points) or above 16384, or a
//!   position beyond what X11 can place (32767 pixels either way) is dropped: eframe opened
//!   a 70 x 30 window for a size of -1, and a window at (-1e6, 1e6) off every screen;
//! - texplore's stored arrangement of the panels is checked as the window checks it
//!   ([`check_stored`](super::layout_check::check_stored): no cycle, every tile present, a
//!   bounded depth, finite positive shares and sizes); a bad one is dropped, the file as it was
//!   kept beside it (`app.ron.refused-SECONDS`), the other entries kept.
//!
//! texplore's own entries are checked again when read ([`Prefs::load`](super::Prefs::load)
//! clamps the UI scale, [`Layout::restore`](super::layout::Layout::restore) checks the
//! arrangement: the page has no memory file, only its local storage).

use super::app::UI_SCALES;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The largest memory file read (a real one is a few kilobytes).
pub const MAX_BYTES: u64 = 4 << 20;

/// The largest coordinate or size (points) a remembered window geometry may hold.
const MAX_GEOMETRY: f64 = 1e6;

/// The smallest remembered window size (points): the window's own minimum.
pub const MIN_WINDOW: [f64; 2] = [800.0, 500.0];

/// The largest remembered window size (points).
const MAX_WINDOW: f64 = 16384.0;

/// The farthest a remembered window position (pixels) may be from the origin: X11 places
/// windows at 16-bit coordinates.
const MAX_POSITION: f64 = 32767.0;

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
    let mut notes = repair(&mut kv);
    if let Some(layout) = kv.get(super::Layout::KEY)
        && let Err(why) = super::layout_check::check_stored(layout)
    {
        kv.remove(super::Layout::KEY);
        let aside = keep_aside(path, &text)?;
        notes.push(format!(
            "the stored window layout was not used ({why}): the default layout is shown; \
             the file as it was is kept as {}",
            aside.display()
        ));
    }
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
        let why = match ron::from_str::<ron::Value>(window) {
            Ok(v) if !numbers_within(&v) => Some("not sane".to_owned()),
            Ok(v) => geometry_fault(&v),
            Err(_) => Some("unreadable".to_owned()),
        };
        if let Some(why) = why {
            kv.remove(WINDOW_KEY);
            notes.push(format!(
                "the window's remembered size or position was {why}: forgotten"
            ));
        }
    }
    notes
}

/// The field `name` of a RON struct or map.
fn field<'a>(v: &'a ron::Value, name: &str) -> Option<&'a ron::Value> {
    let ron::Value::Map(map) = v else {
        return None;
    };
    map.iter()
        .find(|(k, _)| matches!(k, ron::Value::String(s) if s == name))
        .map(|(_, v)| v)
}

/// The point `(x: X, y: Y)`, through an `Option` if there is one.
fn point(v: &ron::Value) -> Option<[f64; 2]> {
    let v = match v {
        ron::Value::Option(Some(inner)) => inner,
        v => v,
    };
    let n = |name| match field(v, name)? {
        ron::Value::Number(n) => Some((*n).into_f64()),
        _ => None,
    };
    Some([n("x")?, n("y")?])
}

/// What is wrong with eframe's remembered geometry (`normal_geometry`: `inner_size_points`
/// and `outer_position_pixels`), if anything: a size below the window's minimum or above
/// 16384, a position X11 cannot place.
fn geometry_fault(window: &ron::Value) -> Option<String> {
    let geometry = field(window, "normal_geometry")?;
    if let Some(size) = field(geometry, "inner_size_points").and_then(point)
        && (size[0] < MIN_WINDOW[0]
            || size[1] < MIN_WINDOW[1]
            || size.iter().any(|&s| s > MAX_WINDOW))
    {
        return Some(format!(
            "{} x {} points (the window is {} x {} to {MAX_WINDOW} x {MAX_WINDOW})",
            size[0], size[1], MIN_WINDOW[0], MIN_WINDOW[1]
        ));
    }
    if let Some(at) = field(geometry, "outer_position_pixels").and_then(point)
        && at.iter().any(|c| c.abs() > MAX_POSITION)
    {
        return Some(format!(
            "at ({}, {}), off any screen X11 can show",
            at[0], at[1]
        ));
    }
    None
}

/// Writes `text` (the memory file as it was) beside `path`, under a name not yet taken
/// (`app.ron.refused-SECONDS`, then `-2`, `-3`...); returns that name.
fn keep_aside(path: &Path, text: &str) -> crate::Result<PathBuf> {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let taken = |p: &Path| p.exists() || p.is_symlink();
    let aside = (1..=1000)
        .map(|k| {
            let suffix = if k == 1 {
                String::new()
            } else {
                format!("-{k}")
            };
            path.with_file_name(format!("{name}.refused-{secs}{suffix}"))
        })
        .find(|p| !taken(p))
        .ok_or_else(|| {
            crate::Error::invalid(path, "cannot keep it aside: 1000 refused copies are there")
        })?;
    crate::output::write_own_file(&aside, text.as_bytes())?;
    Ok(aside)
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
