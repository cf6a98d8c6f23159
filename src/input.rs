//! Opening and reading input files: the one way every preset, image, mesh, material library and
//! texture is read.
//!
//! Only regular files are read. A FIFO, a device, a socket or a directory is refused after
//! opening (the check is on the opened file, so nothing can swap the path in between), and
//! opening itself cannot block: on unix the file is opened with `O_NONBLOCK`, which returns at
//! once for a FIFO with no writer and has no effect on reads of regular files. Every read into
//! memory is bounded by the bytes actually read (not by the size the metadata claims).

use crate::error::{Error, Result};
#[cfg(not(target_arch = "wasm32"))]
use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};

#[cfg(target_arch = "wasm32")]
mod mounted;
#[cfg(target_arch = "wasm32")]
pub use mounted::{
    defer, downloading, fetched, is_mounted, is_ready, mount, normalise, stamp, take_wanted, want,
};

/// Whether `path` is a shipped file the page has not downloaded yet (it downloads when a scene
/// needs it: `want`, in a page); never, outside a page.
#[must_use]
pub fn is_deferred(path: &Path) -> bool {
    #[cfg(target_arch = "wasm32")]
    return mounted::is_deferred(path);
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = path;
        false
    }
}

/// An opened input: a file; in a page (wasm32), a mounted file's bytes.
#[cfg(not(target_arch = "wasm32"))]
pub type Input = File;
/// An opened input: a file; in a page (wasm32), a mounted file's bytes ([`mount`]).
#[cfg(target_arch = "wasm32")]
pub type Input = std::io::Cursor<std::sync::Arc<[u8]>>;

/// The size of an opened input, when it is known.
#[must_use]
pub fn input_len(file: &Input) -> Option<u64> {
    #[cfg(not(target_arch = "wasm32"))]
    return file.metadata().map(|m| m.len()).ok();
    #[cfg(target_arch = "wasm32")]
    Some(file.get_ref().len() as u64)
}

/// Which file an opened input is, whatever path spelled it: its device and inode on unix, so
/// `x.png`, `./in/../x.png`, a hard link and a symbolic link to it are one file; elsewhere its
/// canonical path (in a page, the mounted path).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum FileId {
    /// Device and inode numbers.
    Inode(u64, u64),
    /// The canonical path (or the path itself, when it cannot be made canonical).
    Path(PathBuf),
}

/// The identity of the opened `file`, read from `path`.
#[must_use]
pub fn file_id(file: &Input, path: &Path) -> FileId {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let Ok(m) = file.metadata() {
            return FileId::Inode(m.dev(), m.ino());
        }
    }
    let _ = file;
    #[cfg(target_arch = "wasm32")]
    return FileId::Path(path.to_path_buf());
    #[cfg(not(target_arch = "wasm32"))]
    FileId::Path(std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()))
}

/// Whether a file or folder is at `path`; in a page, whether a file is mounted there or in that
/// folder (a page has no file system: `Path::exists` is always false there).
#[must_use]
pub fn exists(path: &Path) -> bool {
    #[cfg(target_arch = "wasm32")]
    return mounted::exists(path);
    #[cfg(not(target_arch = "wasm32"))]
    path.exists()
}

/// The entries of the folder `dir` (as `dir` joined with each name), in no particular order;
/// in a page, the files mounted in it.
///
/// # Errors
/// The folder cannot be read (`DIR: No such file or directory`).
pub fn list_dir(dir: &Path) -> Result<Vec<PathBuf>> {
    #[cfg(target_arch = "wasm32")]
    return mounted::list(dir);
    #[cfg(not(target_arch = "wasm32"))]
    Ok(std::fs::read_dir(dir)
        .map_err(|e| Error::io(dir, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect())
}

/// What kind of non-regular file `meta` describes, for the refusal message.
#[cfg(not(target_arch = "wasm32"))]
fn kind(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_symlink() {
        return "a symbolic link";
    }
    "not a plain file"
}

/// `bytes` as a person reads it: `16 MiB`, `2 GiB`, `1000 bytes`.
#[must_use]
pub fn human_bytes(bytes: u64) -> String {
    const UNITS: [(u64, &str); 3] = [(1 << 30, "GiB"), (1 << 20, "MiB"), (1 << 10, "KiB")];
    for (size, unit) in UNITS {
        if bytes >= size && bytes.is_multiple_of(size) {
            return format!("{} {unit}", bytes / size);
        }
    }
    format!("{bytes} bytes")
}

/// Opens `path` for reading if it is a regular file.
///
/// # Errors
/// The file cannot be opened (`FILE: No such file or directory`), or it is not a regular file
/// (`FILE: not a regular file (a FIFO)`).
pub fn open_input(path: &Path) -> Result<Input> {
    #[cfg(target_arch = "wasm32")]
    return mounted::open(path);
    #[cfg(not(target_arch = "wasm32"))]
    open_file(path)
}

#[cfg(not(target_arch = "wasm32"))]
fn open_file(path: &Path) -> Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // Opening a FIFO for reading waits for a writer unless O_NONBLOCK is set. A regular
        // file ignores the flag, so it can stay set for the reads that follow.
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(|e| Error::io(path, e))?;
    let meta = file.metadata().map_err(|e| Error::io(path, e))?;
    if !meta.is_file() {
        // An I/O error, so that callers which re-word value errors keep the file's name.
        let why = format!("not a regular file ({})", kind(&meta));
        return Err(Error::io(
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidInput, why),
        ));
    }
    Ok(file)
}

/// Reads all of an opened `file` (named `path` in errors), refusing it above `max_bytes`.
///
/// # Errors
/// A read fails, or the file holds more than `max_bytes` (`FILE: too large (larger than 16 MiB)`).
pub fn read_opened(file: Input, path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    let too_large = || {
        let why = format!("too large (larger than {})", human_bytes(max_bytes));
        Error::io(
            path,
            std::io::Error::new(std::io::ErrorKind::FileTooLarge, why),
        )
    };
    // A quick refusal when the size is known; the bound on the read below is what holds.
    if input_len(&file).is_some_and(|len| len > max_bytes) {
        return Err(too_large());
    }
    let mut bytes = Vec::new();
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large());
    }
    Ok(bytes)
}

/// Reads the regular file `path` into memory, refusing it above `max_bytes`.
///
/// # Errors
/// As [`open_input`] and [`read_opened`].
pub fn read_input(path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    read_opened(open_input(path)?, path, max_bytes)
}

/// [`read_input`] for files of texplore's own under a predictable name (the reference cache):
/// a symbolic link at `path` is refused, never followed (`O_NOFOLLOW` on Unix; elsewhere a link
/// seen before opening is refused), so a link planted there cannot make texplore read a file
/// of the user's, or `/dev/zero`, as its own.
///
/// # Errors
/// As [`read_input`], or `FILE: a symbolic link (not followed)`.
#[cfg(not(target_arch = "wasm32"))]
pub fn read_own_input(path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    let link = || {
        Error::io(
            path,
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "a symbolic link (not followed)",
            ),
        )
    };
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink()) {
        return Err(link());
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK | libc::O_NOFOLLOW);
    }
    let file = options.open(path).map_err(|e| {
        // A link planted between the check above and the open: ELOOP under O_NOFOLLOW.
        #[cfg(unix)]
        if e.raw_os_error() == Some(libc::ELOOP) {
            return link();
        }
        Error::io(path, e)
    })?;
    let meta = file.metadata().map_err(|e| Error::io(path, e))?;
    if !meta.is_file() {
        let why = format!("not a regular file ({})", kind(&meta));
        return Err(Error::io(
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidInput, why),
        ));
    }
    read_opened(file, path, max_bytes)
}

/// Reads the regular file `path` as UTF-8 text (a leading byte-order mark removed), refusing it
/// above `max_bytes`.
///
/// # Errors
/// As [`read_input`], or the bytes are not UTF-8 (the message gives the line).
pub fn read_input_text(path: &Path, max_bytes: u64) -> Result<String> {
    let bytes = read_input(path, max_bytes)?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let line = 1 + e.as_bytes()[..at].iter().filter(|b| **b == b'\n').count();
        Error::invalid(path, format!("line {line}: not UTF-8 text (byte {at})"))
    })?;
    Ok(match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_owned(),
        None => text,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_on_bytes_read() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f.txt");
        std::fs::write(&p, vec![b'a'; 100]).unwrap();
        assert_eq!(read_input(&p, 100).unwrap().len(), 100);
        let e = read_input(&p, 99).unwrap_err().to_string();
        assert!(
            e.ends_with("f.txt: too large (larger than 99 bytes)"),
            "{e}"
        );
    }

    #[test]
    fn directories_are_refused_with_their_kind() {
        let dir = tempfile::tempdir().unwrap();
        let e = open_input(dir.path()).unwrap_err().to_string();
        assert!(e.ends_with(": not a regular file (a directory)"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn devices_are_refused() {
        let e = read_input(Path::new("/dev/zero"), 16)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "/dev/zero: not a regular file (a character device)");
    }

    #[test]
    fn text_loses_its_byte_order_mark_and_names_bad_utf8() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("t.ron");
        std::fs::write(&p, b"\xef\xbb\xbf(a)").unwrap();
        assert_eq!(read_input_text(&p, 100).unwrap(), "(a)");
        std::fs::write(&p, b"ok\nbad \xff\n").unwrap();
        let e = read_input_text(&p, 100).unwrap_err().to_string();
        assert!(e.ends_with("t.ron: line 2: not UTF-8 text (byte 7)"), "{e}");
    }

    #[test]
    fn sizes_read_like_a_person_writes_them() {
        assert_eq!(human_bytes(16 << 20), "16 MiB");
        assert_eq!(human_bytes(2 << 30), "2 GiB");
        assert_eq!(human_bytes(1000), "1000 bytes");
    }
}
