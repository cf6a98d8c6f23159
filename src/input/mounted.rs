//! The page's files (wasm32): a browser gives a page no file system, so the files texplore reads
//! there are *mounted*: put in memory under a path before anything reads them (the shipped
//! lessons, presets and assets, fetched from beside the page; a file the user dropped or chose;
//! a preset the user saved). [`open`](super::open_input) and [`list_dir`](super::list_dir)
//! read them; paths are compared after lexical normalisation (`presets/../assets/x.jpg` is
//! `assets/x.jpg`), since there are no links to resolve.
//!
//! A shipped file can also be *deferred*: listed (its path and size) but not downloaded until a
//! scene needs it ([`defer`], [`want`]); the page fetches what is wanted between frames
//! ([`take_wanted`], [`fetched`]), and work that reads those files waits for them
//! ([`is_ready`]).

use crate::error::{Error, Result};
use std::collections::BTreeMap;
use std::io::Cursor;
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

/// A mounted file: its bytes and a number that changes each time something is mounted there.
struct File {
    bytes: Arc<[u8]>,
    serial: u64,
}

/// Where a deferred file is.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Fetch {
    /// Not asked for yet.
    Idle,
    /// Asked for, not fetched yet.
    Wanted,
    /// Being fetched.
    Fetching,
    /// The fetch failed: why.
    Failed(String),
}

/// Every mounted file by its normalised path.
static FILES: Mutex<BTreeMap<PathBuf, File>> = Mutex::new(BTreeMap::new());
/// Shipped files not downloaded yet, with their sizes in bytes.
static DEFERRED: Mutex<BTreeMap<PathBuf, (u64, Fetch)>> = Mutex::new(BTreeMap::new());
static SERIAL: AtomicU64 = AtomicU64::new(1);

/// `path` with `.` dropped and `..` applied, relative (a leading `/` or `./` is dropped too).
#[must_use]
pub fn normalise(path: &Path) -> PathBuf {
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

fn files() -> std::sync::MutexGuard<'static, BTreeMap<PathBuf, File>> {
    FILES.lock().unwrap_or_else(PoisonError::into_inner)
}

fn deferred() -> std::sync::MutexGuard<'static, BTreeMap<PathBuf, (u64, Fetch)>> {
    DEFERRED.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Puts `bytes` at `path` (replacing what was there).
pub fn mount(path: &Path, bytes: impl Into<Arc<[u8]>>) {
    let p = normalise(path);
    deferred().remove(&p);
    let serial = SERIAL.fetch_add(1, Ordering::Relaxed);
    files().insert(
        p,
        File {
            bytes: bytes.into(),
            serial,
        },
    );
}

/// Lists `path` (`size` bytes) as a shipped file that is downloaded when a scene needs it.
pub fn defer(path: &Path, size: u64) {
    let p = normalise(path);
    if !files().contains_key(&p) {
        deferred().insert(p, (size, Fetch::Idle));
    }
}

/// Whether `path` is a deferred file not downloaded yet (nor failed).
#[must_use]
pub fn is_deferred(path: &Path) -> bool {
    deferred()
        .get(&normalise(path))
        .is_some_and(|(_, f)| !matches!(f, Fetch::Failed(_)))
}

/// Asks for the deferred files among `paths` (the others are ready or not shipped).
pub fn want(paths: &[PathBuf]) {
    let mut d = deferred();
    for p in paths {
        if let Some((_, f)) = d.get_mut(&normalise(p))
            && *f == Fetch::Idle
        {
            *f = Fetch::Wanted;
        }
    }
}

/// The files asked for and not being fetched yet, with their sizes; they are being fetched from
/// now on.
#[must_use]
pub fn take_wanted() -> Vec<(PathBuf, u64)> {
    let mut d = deferred();
    let mut out = Vec::new();
    for (p, (size, f)) in d.iter_mut() {
        if *f == Fetch::Wanted {
            *f = Fetch::Fetching;
            out.push((p.clone(), *size));
        }
    }
    out
}

/// The files being fetched or waiting to be, with their sizes.
#[must_use]
pub fn downloading() -> Vec<(PathBuf, u64)> {
    deferred()
        .iter()
        .filter(|(_, (_, f))| matches!(f, Fetch::Wanted | Fetch::Fetching))
        .map(|(p, (size, _))| (p.clone(), *size))
        .collect()
}

/// A deferred file's download ended: mounted, or why not (reading it then says why).
pub fn fetched(path: &Path, bytes: std::result::Result<Vec<u8>, String>) {
    match bytes {
        Ok(b) => mount(path, b),
        Err(why) => {
            if let Some((_, f)) = deferred().get_mut(&normalise(path)) {
                *f = Fetch::Failed(why);
            }
        }
    }
}

/// Whether reading `path` needs no download first: it is mounted, its download failed (the read
/// says why), or it is not a shipped file at all (the read says so).
#[must_use]
pub fn is_ready(path: &Path) -> bool {
    !is_deferred(path)
}

/// Whether a file is mounted at `path`.
#[must_use]
pub fn is_mounted(path: &Path) -> bool {
    files().contains_key(&normalise(path))
}

/// A number that changes whenever something is mounted at `path` (`None`: nothing is).
#[must_use]
pub fn stamp(path: &Path) -> Option<u64> {
    files().get(&normalise(path)).map(|f| f.serial)
}

/// Whether a file is mounted (or deferred) at `path` or in the folder `path`.
#[must_use]
pub fn exists(path: &Path) -> bool {
    let p = normalise(path);
    let in_it = |f: &PathBuf| *f == p || f.starts_with(&p);
    files().keys().any(in_it) || deferred().keys().any(in_it)
}

/// The mounted file at `path`, ready to read.
pub(super) fn open(path: &Path) -> Result<Cursor<Arc<[u8]>>> {
    let p = normalise(path);
    if let Some(f) = files().get(&p) {
        return Ok(Cursor::new(f.bytes.clone()));
    }
    let why = match deferred().get(&p) {
        Some((_, Fetch::Failed(why))) => format!("could not be downloaded: {why}"),
        Some(_) => "not downloaded yet (the page downloads a lesson's files when a scene needs them)".to_owned(),
        None => "no such file in the page (the page reads only the files beside it and those dropped on it)".to_owned(),
    };
    Err(Error::io(
        path,
        std::io::Error::new(std::io::ErrorKind::NotFound, why),
    ))
}

/// The files directly in `dir` (mounted or deferred), as `dir` joined with their names.
pub(super) fn list(dir: &Path) -> Result<Vec<PathBuf>> {
    let folder = normalise(dir);
    let mut names: Vec<PathBuf> = files().keys().cloned().collect();
    names.extend(deferred().keys().cloned());
    let mut v: Vec<PathBuf> = names
        .iter()
        .filter(|p| p.parent() == Some(folder.as_path()))
        .filter_map(|p| p.file_name().map(|n| dir.join(n)))
        .collect();
    v.sort();
    v.dedup();
    if v.is_empty() {
        return Err(Error::io(
            dir,
            std::io::Error::new(std::io::ErrorKind::NotFound, "no such folder in the page"),
        ));
    }
    Ok(v)
}
