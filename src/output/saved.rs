//! Saving in a page (wasm32): a browser gives a page no folder to write to, so the bytes of a
//! save go to the hook the page installed ([`set_save_hook`]): the window's web entry point
//! offers them as a download and keeps them readable under the same path.

use crate::error::{Error, Result};
use std::io::{self, Cursor};
use std::path::Path;
use std::sync::OnceLock;

/// What receives a save: the path asked for and the bytes.
pub type SaveHook = dyn Fn(&Path, Vec<u8>) -> io::Result<()> + Send + Sync;

static HOOK: OnceLock<Box<SaveHook>> = OnceLock::new();

/// Installs the hook every save goes to (once; later calls are ignored).
pub fn set_save_hook(hook: impl Fn(&Path, Vec<u8>) -> io::Result<()> + Send + Sync + 'static) {
    let _ = HOOK.set(Box::new(hook));
}

/// The bytes `write` produces, handed to the hook.
pub(super) fn write<F>(path: &Path, write: F) -> Result<()>
where
    F: FnOnce(&mut dyn super::WriteSeek) -> io::Result<()>,
{
    let refuse = |e: io::Error| Error::io(path, e);
    let mut out = Cursor::new(Vec::new());
    write(&mut out).map_err(refuse)?;
    let hook = HOOK.get().ok_or_else(|| {
        refuse(io::Error::new(
            io::ErrorKind::Unsupported,
            "this page cannot save files",
        ))
    })?;
    hook(path, out.into_inner()).map_err(refuse)
}
