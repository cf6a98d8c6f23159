//! The page's files (wasm32): a browser gives a page no file system, so the files texplore reads
//! there are *mounted*: put in memory under a path before anything reads them (the shipped
//! lessons, presets and assets, fetched from beside the page; a file the user dropped or chose;
//! a preset the user saved). [`open`](super::open_input) and [`list_dir`](super::list_dir)
//! read them; paths are compared after lexical normalisation (`presets/../assets/x.jpg` is
//! `assets/x.jpg`), since there are no links to resolve.

use crate::error::{Error, Result};
use std::collections::BTreeMap;
use std::io::Cursor;
use std::path::{Component, Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

/// Every mounted file by its normalised path.
static FILES: Mutex<BTreeMap<PathBuf, Arc<[u8]>>> = Mutex::new(BTreeMap::new());

/// `path` with `.` dropped and `..` applied, relative (a leading `/` or `./` is dropped too).
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::Normal(part) => out.push(part),
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir | Component::RootDir | Component::Prefix(_) => {}
        }
    }
    out
}

/// Puts `bytes` at `path` (replacing what was there).
pub fn mount(path: &Path, bytes: impl Into<Arc<[u8]>>) {
    let mut files = FILES.lock().unwrap_or_else(PoisonError::into_inner);
    files.insert(normalise(path), bytes.into());
}

/// Whether a file is mounted at `path`.
#[must_use]
pub fn is_mounted(path: &Path) -> bool {
    let files = FILES.lock().unwrap_or_else(PoisonError::into_inner);
    files.contains_key(&normalise(path))
}

/// Whether a file is mounted at `path` or in the folder `path`.
#[must_use]
pub fn exists(path: &Path) -> bool {
    let files = FILES.lock().unwrap_or_else(PoisonError::into_inner);
    let p = normalise(path);
    files.contains_key(&p) || files.keys().any(|f| f.starts_with(&p))
}

/// The mounted file at `path`, ready to read.
pub(super) fn open(path: &Path) -> Result<Cursor<Arc<[u8]>>> {
    let files = FILES.lock().unwrap_or_else(PoisonError::into_inner);
    files.get(&normalise(path)).map_or_else(
        || {
            Err(Error::io(
                path,
                std::io::Error::new(
                    std::io::ErrorKind::NotFound,
                    "no such file in the page (the page reads only the files beside it and those dropped on it)",
                ),
            ))
        },
        |bytes| Ok(Cursor::new(bytes.clone())),
    )
}

/// The mounted files directly in `dir`, as `dir` joined with their names.
pub(super) fn list(dir: &Path) -> Result<Vec<PathBuf>> {
    let files = FILES.lock().unwrap_or_else(PoisonError::into_inner);
    let folder = normalise(dir);
    let v: Vec<PathBuf> = files
        .keys()
        .filter(|p| p.parent() == Some(folder.as_path()))
        .filter_map(|p| p.file_name().map(|n| dir.join(n)))
        .collect();
    if v.is_empty() {
        return Err(Error::io(
            dir,
            std::io::Error::new(std::io::ErrorKind::NotFound, "no such folder in the page"),
        ));
    }
    Ok(v)
}
