//! The shipped files: the lessons (`lessons/`), presets (`presets/`) and assets (`assets/`)
//! built into the binary, so a lesson opens wherever texplore is run from.
//!
//! Two layers, kept apart on purpose: the store ([`files`], [`get`]) is the embedded bytes
//! and nothing else (no file system: a browser build reads it as it is); [`root`] copies the
//! store once per process into a folder of its own under the user's cache folder ([`copy_folder`]), because
//! everything that loads a preset, an image or a mesh takes a path. The copy is checked file by
//! file on every start (a file that differs is written again, atomically) and its files are
//! made read-only, so a save in the window cannot land there.

use crate::error::{Error, Result};
use include_dir::Dir;
use std::path::{Path, PathBuf};

#[cfg(not(target_arch = "wasm32"))]
static LESSONS: Dir<'static> = include_dir::include_dir!("$CARGO_MANIFEST_DIR/lessons");
#[cfg(not(target_arch = "wasm32"))]
static PRESETS: Dir<'static> = include_dir::include_dir!("$CARGO_MANIFEST_DIR/presets");
#[cfg(not(target_arch = "wasm32"))]
static ASSETS: Dir<'static> = include_dir::include_dir!("$CARGO_MANIFEST_DIR/assets");

// The page fetches the shipped files from beside itself and mounts them (`gui::web`): built in
// as well, they would be 7.7 MB of its download for nothing. Its store is empty.
#[cfg(target_arch = "wasm32")]
static LESSONS: Dir<'static> = Dir::new("", &[]);
#[cfg(target_arch = "wasm32")]
static PRESETS: Dir<'static> = Dir::new("", &[]);
#[cfg(target_arch = "wasm32")]
static ASSETS: Dir<'static> = Dir::new("", &[]);

/// The shipped folders, as they are named in the source tree and in the copy.
pub const FOLDERS: [&str; 3] = ["lessons", "presets", "assets"];

fn folder(name: &str) -> Option<&'static Dir<'static>> {
    match name {
        "lessons" => Some(&LESSONS),
        "presets" => Some(&PRESETS),
        "assets" => Some(&ASSETS),
        _ => None,
    }
}

fn walk(dir: &'static Dir<'static>, prefix: &str, out: &mut Vec<(String, &'static [u8])>) {
    for f in dir.files() {
        out.push((
            format!("{prefix}/{}", f.path().to_string_lossy().replace('\\', "/")),
            f.contents(),
        ));
    }
    for d in dir.dirs() {
        walk(d, prefix, out);
    }
}

/// Every shipped file: its path in the store (`presets/earth.ron`, always with `/`) and its
/// bytes, sorted by path.
#[must_use]
pub fn files() -> Vec<(String, &'static [u8])> {
    let mut out = Vec::new();
    for name in FOLDERS {
        if let Some(d) = folder(name) {
            walk(d, name, &mut out);
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// The bytes of the shipped file at `path` (`presets/earth.ron`), if there is one.
#[must_use]
pub fn get(path: &str) -> Option<&'static [u8]> {
    let (top, rest) = path.split_once('/')?;
    folder(top)?.get_file(rest).map(include_dir::File::contents)
}

/// Where the copy goes: `texplore/shipped` in the user's cache folder (`~/.cache` on Linux,
/// `~/Library/Caches` on macOS, `%LOCALAPPDATA%` on Windows), else in the system's temporary
/// folder. The name stays the same from one version to the next, so a preset the user saved
/// elsewhere that names a shipped image keeps finding it (each start puts back what is missing
/// or changed).
#[must_use]
pub fn copy_folder() -> PathBuf {
    dirs::cache_dir()
        .unwrap_or_else(std::env::temp_dir)
        .join("texplore")
        .join("shipped")
}

/// Makes `dir` hold exactly the store's bytes for each shipped file (files of its own beside
/// them are left alone), each written atomically and left read-only.
///
/// # Errors
/// A folder cannot be made or a file cannot be written (naming it).
pub fn copy_to(dir: &Path) -> Result<()> {
    for (rel, bytes) in files() {
        let path = dir.join(&rel);
        if same(&path, bytes) {
            continue;
        }
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        }
        // A changed copy of ours: writable again so it can be replaced.
        if let Ok(meta) = std::fs::symlink_metadata(&path)
            && meta.is_file()
        {
            let mut perms = meta.permissions();
            #[allow(clippy::permissions_set_readonly_false)]
            perms.set_readonly(false);
            let _ = std::fs::set_permissions(&path, perms);
        }
        let written = crate::output::write_own_file(&path, bytes);
        // Another texplore starting at the same moment may have written it first.
        if let Err(e) = written
            && !same(&path, bytes)
        {
            return Err(e);
        }
        if let Ok(meta) = std::fs::metadata(&path) {
            let mut perms = meta.permissions();
            perms.set_readonly(true);
            let _ = std::fs::set_permissions(&path, perms);
        }
    }
    Ok(())
}

/// Whether the regular file at `path` holds exactly `bytes` (read through [`crate::input`],
/// bounded by their length).
fn same(path: &Path, bytes: &[u8]) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file() && m.len() == bytes.len() as u64)
        && crate::input::read_input(path, bytes.len() as u64 + 1).is_ok_and(|b| b == bytes)
}

/// The copy of the store (made or checked on the first call of the process, see
/// [`copy_folder`]): `lessons/`, `presets/` and `assets/` side by side, as in the source tree.
/// In a page, the relative root under which the page mounted the files beside it (`gui::web`):
/// a page has no folder to copy into.
///
/// # Errors
/// The copy could not be made (the message names the file).
pub fn root() -> std::result::Result<&'static Path, String> {
    #[cfg(target_arch = "wasm32")]
    return Ok(Path::new(""));
    #[cfg(not(target_arch = "wasm32"))]
    {
        static ROOT: std::sync::OnceLock<std::result::Result<PathBuf, String>> =
            std::sync::OnceLock::new();
        ROOT.get_or_init(|| {
            let dir = copy_folder();
            copy_to(&dir).map_err(|e| format!("the shipped lessons and presets: {e}"))?;
            Ok(dir)
        })
        .as_ref()
        .map(PathBuf::as_path)
        .map_err(Clone::clone)
    }
}

/// The shipped lessons' folder in the copy.
///
/// # Errors
/// As [`root`].
pub fn lessons_dir() -> std::result::Result<PathBuf, String> {
    root().map(|r| r.join("lessons"))
}

/// The shipped presets' folder in the copy.
///
/// # Errors
/// As [`root`].
pub fn presets_dir() -> std::result::Result<PathBuf, String> {
    root().map(|r| r.join("presets"))
}

/// Whether `path` is a shipped preset or lesson: a file in the copy, or a file in a folder named
/// `presets` or `lessons` whose bytes are the shipped file's of that name (the source tree's
/// own `presets/earth.ron`). The window saves such a file only under another name.
#[must_use]
pub fn is_shipped(path: &Path) -> bool {
    let canonical = |p: &Path| std::fs::canonicalize(p).ok();
    if let (Ok(root), Some(file)) = (root(), canonical(path))
        && canonical(root).is_some_and(|r| file.starts_with(r))
    {
        return true;
    }
    let (Some(name), Some(parent)) = (
        path.file_name().and_then(|n| n.to_str()),
        path.parent()
            .and_then(Path::file_name)
            .and_then(|n| n.to_str()),
    ) else {
        return false;
    };
    if !matches!(parent, "presets" | "lessons") {
        return false;
    }
    get(&format!("{parent}/{name}")).is_some_and(|bytes| same(path, bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_store_holds_the_source_trees_files() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let all = files();
        for name in FOLDERS {
            let on_disk = std::fs::read_dir(root.join(name)).unwrap().count();
            let stored = all
                .iter()
                .filter(|(p, _)| p.starts_with(&format!("{name}/")))
                .count();
            assert!(
                stored >= on_disk && on_disk > 0,
                "{name}: {stored} vs {on_disk}"
            );
        }
        assert_eq!(
            get("presets/earth.ron").unwrap(),
            std::fs::read(root.join("presets/earth.ron")).unwrap()
        );
        assert!(get("presets/mars.ron").is_none() && get("nowhere").is_none());
    }

    #[test]
    fn a_copy_is_repaired_and_read_only() {
        let dir = tempfile::tempdir().unwrap();
        copy_to(dir.path()).unwrap();
        let earth = dir.path().join("presets/earth.ron");
        assert_eq!(
            std::fs::read(&earth).unwrap(),
            get("presets/earth.ron").unwrap()
        );
        assert!(std::fs::metadata(&earth).unwrap().permissions().readonly());
        // A changed file is written again; a file of the user's beside it stays.
        let mut perms = std::fs::metadata(&earth).unwrap().permissions();
        #[allow(clippy::permissions_set_readonly_false)]
        perms.set_readonly(false);
        std::fs::set_permissions(&earth, perms).unwrap();
        std::fs::write(&earth, "changed").unwrap();
        std::fs::write(dir.path().join("presets/mine.ron"), "mine").unwrap();
        copy_to(dir.path()).unwrap();
        assert_eq!(
            std::fs::read(&earth).unwrap(),
            get("presets/earth.ron").unwrap()
        );
        assert_eq!(
            std::fs::read_to_string(dir.path().join("presets/mine.ron")).unwrap(),
            "mine"
        );
    }

    #[test]
    fn shipped_files_are_recognised_by_their_bytes() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        assert!(is_shipped(&root.join("presets/light-probe.ron")));
        assert!(is_shipped(&root.join("lessons/07-light-probes.toml")));
        let dir = tempfile::tempdir().unwrap();
        let presets = dir.path().join("presets");
        std::fs::create_dir(&presets).unwrap();
        let edited = presets.join("earth.ron");
        std::fs::write(&edited, "(changed)").unwrap();
        assert!(!is_shipped(&edited), "a user's own edit of the name");
        std::fs::write(&edited, get("presets/earth.ron").unwrap()).unwrap();
        assert!(is_shipped(&edited));
        assert!(!is_shipped(&dir.path().join("earth.ron")));
    }
}
