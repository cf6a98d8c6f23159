//! The one writer behind every save (renders, probes, presets, screenshots, report files, the
//! reference cache, `snapshot update`): the user's files are never lost.
//!
//! [`write_atomically`] writes into a temporary file created exclusively, under a random name,
//! in the output's folder, syncs it and renames it over the output, so a reader (or a second
//! writer) sees the old file or the new one, never half of one. Before any byte is written it
//! refuses, with "cannot write FILE: reason":
//!
//! - an output that exists and is not a regular file (a directory, FIFO, device, socket);
//! - an output that is the same file as an input of the command (same device and inode,
//!   whatever the spelling: `./x/../x.ron`, a hard link, a symbolic link);
//! - a read-only output (no write permission bit), as `cp` without `-f` does;
//! - a dangling symbolic link, or a folder that does not exist.
//!
//! A symbolic link is followed, as `cp` does: its target is replaced and the link kept. An
//! existing file keeps its permission bits; a new one gets the usual `0666` less the umask. The
//! temporary file is removed on every failure.
//!
//! [`check_output`] runs the same checks plus the extension, without writing: commands call it
//! before any work, so a bad `-o` fails in milliseconds.
//!
//! [`write_own_file`] is the writer for files of texplore's own under predictable names (the
//! reference cache): there a symbolic link is never followed. Whatever link or special file a
//! name holds is replaced by the rename (the link's target is untouched); a directory is
//! refused.

use crate::error::{Error, Result};
use std::fs::{Metadata, Permissions};
#[cfg(not(target_arch = "wasm32"))]
use std::io::BufWriter;
use std::io::{self, Seek, Write};
use std::path::{Path, PathBuf};

/// A writer that can also seek (some image encoders, TIFF and EXR, seek back).
pub trait WriteSeek: Write + Seek {}

#[cfg(target_arch = "wasm32")]
mod saved;
#[cfg(target_arch = "wasm32")]
pub use saved::{SaveHook, set_save_hook};
impl<T: Write + Seek> WriteSeek for T {}

/// Where an output really goes: the path after following a symbolic link, and the existing
/// file's permissions (`None`: a new file).
#[derive(Debug)]
// A page only checks the name (`check_output`): it writes through no file.
#[cfg_attr(target_arch = "wasm32", allow(dead_code))]
struct Target {
    path: PathBuf,
    existing: Option<Permissions>,
}

/// "cannot write FILE: reason".
fn refuse(path: &Path, reason: impl Into<String>) -> Error {
    Error::Write {
        path: path.to_path_buf(),
        reason: reason.into(),
    }
}

/// An OS error as a short reason: "permission denied", "no space left on device", ...
fn io_reason(e: &io::Error) -> String {
    let s = e.to_string();
    // "Permission denied (os error 13)" -> "permission denied".
    let s = s.split(" (os error").next().unwrap_or(&s);
    let mut c = s.chars();
    c.next().map_or_else(String::new, |f| {
        f.to_lowercase().collect::<String>() + c.as_str()
    })
}

/// What a non-regular file is, for the refusal.
/// What a link leads to that has no name in the file system: a FIFO there is a pipe.
fn unnamed_kind(m: &Metadata) -> &'static str {
    match kind_name(m) {
        "a FIFO" => "a pipe",
        k => k,
    }
}

fn kind_name(m: &Metadata) -> &'static str {
    if m.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = m.file_type();
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "something else"
}

/// Whether two files' metadata describe the same file.
#[cfg(unix)]
fn same_file(a: &Metadata, _a_path: &Path, b: &Metadata, _b_path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    a.dev() == b.dev() && a.ino() == b.ino()
}

/// Whether two files' metadata describe the same file (by canonical path where inodes are not
/// available).
#[cfg(not(unix))]
fn same_file(_a: &Metadata, a_path: &Path, _b: &Metadata, b_path: &Path) -> bool {
    match (std::fs::canonicalize(a_path), std::fs::canonicalize(b_path)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// Whether the writer follows a symbolic link at the output (a user's `-o`) or replaces the
/// link itself (texplore's own files).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Links {
    Follow,
    Replace,
}

/// The target of a file of texplore's own: `path` itself, never a link's target. A directory
/// is refused (the rename could not replace it); a link or any other special file is replaced.
#[cfg(not(target_arch = "wasm32"))]
fn resolve_own(path: &Path) -> Result<Target> {
    if path.as_os_str().is_empty() {
        return Err(refuse(path, "the file name is empty"));
    }
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => Err(refuse(path, "it is a folder, not a regular file")),
        Ok(m) if m.is_file() => Ok(Target {
            path: path.to_path_buf(),
            existing: Some(m.permissions()),
        }),
        Ok(_) => Ok(Target {
            path: path.to_path_buf(),
            existing: None,
        }),
        Err(e) if e.kind() == io::ErrorKind::NotFound => match std::fs::metadata(folder(path)) {
            Ok(d) if d.is_dir() => Ok(Target {
                path: path.to_path_buf(),
                existing: None,
            }),
            _ => Err(refuse(
                path,
                format!("the folder {} does not exist", folder(path).display()),
            )),
        },
        Err(e) => Err(refuse(path, io_reason(&e))),
    }
}

/// Follows a symbolic link and runs every check that needs no writing.
fn resolve(path: &Path, inputs: &[&Path]) -> Result<Target> {
    if path.as_os_str().is_empty() {
        return Err(refuse(path, "the file name is empty"));
    }
    let link = match std::fs::symlink_metadata(path) {
        Ok(m) => Some(m),
        Err(e) if e.kind() == io::ErrorKind::NotFound => None,
        Err(e) => return Err(refuse(path, io_reason(&e))),
    };
    let target = match &link {
        Some(m) if m.file_type().is_symlink() => std::fs::canonicalize(path).map_err(|e| {
            if e.kind() != io::ErrorKind::NotFound {
                return refuse(path, io_reason(&e));
            }
            match std::fs::metadata(path) {
                // The link leads to something without a name in the file system: `-o
                // /dev/stdout` into a pipe is /proc/self/fd/1, a link to `pipe:[N]`.
                Ok(m) => refuse(
                    path,
                    format!(
                        "it leads to {}{}, not a regular file",
                        unnamed_kind(&m),
                        std::fs::read_link(path)
                            .map(|t| format!(" ({})", t.display()))
                            .unwrap_or_default()
                    ),
                ),
                Err(_) => refuse(
                    path,
                    "it is a symbolic link to a file that does not exist (not writing through it)",
                ),
            }
        })?,
        _ => path.to_path_buf(),
    };
    let meta = match &link {
        Some(m) if !m.file_type().is_symlink() => Some(m.clone()),
        Some(_) => Some(std::fs::metadata(&target).map_err(|e| refuse(path, io_reason(&e)))?),
        None => None,
    };
    let Some(meta) = meta else {
        // A new file: its folder must exist.
        let dir = folder(&target);
        return match std::fs::metadata(dir) {
            Ok(d) if d.is_dir() => Ok(Target {
                path: target,
                existing: None,
            }),
            Ok(_) => Err(refuse(path, format!("{} is not a folder", dir.display()))),
            Err(e) if e.kind() == io::ErrorKind::NotFound => Err(refuse(
                path,
                format!("the folder {} does not exist", dir.display()),
            )),
            Err(e) => Err(refuse(path, io_reason(&e))),
        };
    };
    if !meta.is_file() {
        let what = kind_name(&meta);
        let reason = if target == path {
            format!("it is {what}, not a regular file")
        } else {
            format!(
                "it is a symbolic link to {what} ({}), not a regular file",
                target.display()
            )
        };
        return Err(refuse(path, reason));
    }
    for input in inputs {
        if let Ok(im) = std::fs::metadata(input)
            && same_file(&meta, &target, &im, input)
        {
            return Err(refuse(
                path,
                format!(
                    "it is the input {} (an output never replaces an input)",
                    input.display()
                ),
            ));
        }
    }
    if meta.permissions().readonly() {
        return Err(refuse(path, "permission denied (the file is read-only)"));
    }
    Ok(Target {
        path: target,
        existing: Some(meta.permissions()),
    })
}

/// The folder a file goes into (`.` for a bare name).
fn folder(path: &Path) -> &Path {
    path.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// The extension of `path`, lower case (`""` when there is none).
#[must_use]
pub fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Checks, without writing anything, that `path` could be written by [`write_atomically`]
/// (see the module documentation) and that its extension is one of `allowed_exts` (lower case,
/// without the dot; an empty list allows any).
///
/// # Errors
/// "cannot write FILE: reason" when the output would be refused.
pub fn check_output(path: &Path, allowed_exts: &[&str], inputs: &[&Path]) -> Result<()> {
    // What the path is (a directory, a FIFO, an input) says more than its extension.
    resolve(path, inputs)?;
    check_extension(path, allowed_exts)
}

/// Checks only the extension (see [`check_output`]).
///
/// # Errors
/// "cannot write FILE: reason" for an extension not in `allowed_exts`.
pub fn check_extension(path: &Path, allowed_exts: &[&str]) -> Result<()> {
    if allowed_exts.is_empty() {
        return Ok(());
    }
    let ext = extension(path);
    if allowed_exts.contains(&ext.as_str()) {
        return Ok(());
    }
    let list = allowed_exts
        .iter()
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ");
    let what = if ext.is_empty() {
        "the file name has no extension".to_string()
    } else {
        format!("unknown extension '.{ext}'")
    };
    Err(refuse(path, format!("{what} (use {list})")))
}

/// Writes `path` atomically with the bytes `write` produces (see the module documentation):
/// nothing is written when `path` is refused, and on any failure the temporary file is removed
/// and the old file, if any, is left as it was.
///
/// # Errors
/// "cannot write FILE: reason": the output is refused, `write` failed, or the OS refused the
/// temporary file, the sync or the rename.
pub fn write_atomically<F>(path: &Path, inputs: &[&Path], write: F) -> Result<()>
where
    F: FnOnce(&mut dyn WriteSeek) -> io::Result<()>,
{
    write_with(path, inputs, Links::Follow, write)
}

/// Writes a file of texplore's own under a predictable name (the reference cache) atomically,
/// as [`write_atomically`] does, but never through a symbolic link: a link (or FIFO, socket,
/// device) at `path` is replaced by the new file, its target left untouched.
///
/// # Errors
/// "cannot write FILE: reason": `path` is a folder, its folder does not exist, or the OS
/// refused the temporary file, the sync or the rename.
pub fn write_own_file(path: &Path, bytes: &[u8]) -> Result<()> {
    write_with(path, &[], Links::Replace, |w| w.write_all(bytes))
}

/// In a page there are no files to protect: every save goes to the page's hook (a download).
#[cfg(target_arch = "wasm32")]
fn write_with<F>(path: &Path, _inputs: &[&Path], _links: Links, write: F) -> Result<()>
where
    F: FnOnce(&mut dyn WriteSeek) -> io::Result<()>,
{
    saved::write(path, write)
}

#[cfg(not(target_arch = "wasm32"))]
fn write_with<F>(path: &Path, inputs: &[&Path], links: Links, write: F) -> Result<()>
where
    F: FnOnce(&mut dyn WriteSeek) -> io::Result<()>,
{
    let target = match links {
        Links::Follow => resolve(path, inputs)?,
        Links::Replace => resolve_own(path)?,
    };
    let dir = folder(&target.path);
    let name = target
        .path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let prefix = format!(".{name}.");
    // `.NAME.<12 random characters>.tmp`, created with O_EXCL: never a name a user's file or a
    // planted symlink can already hold (a clash is retried with new characters).
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).rand_bytes(12).suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // A new file gets what `File::create` would give (0666 less the umask), not 0600.
        builder.permissions(Permissions::from_mode(0o666));
    }
    let mut tmp = builder
        .tempfile_in(dir)
        .map_err(|e| refuse(path, io_reason(&e)))?;
    // From here on, dropping `tmp` on an early return removes the temporary file.
    {
        let mut w = BufWriter::new(tmp.as_file_mut());
        write(&mut w).map_err(|e| refuse(path, io_reason(&e)))?;
        w.flush().map_err(|e| refuse(path, io_reason(&e)))?;
    }
    if let Some(perms) = target.existing {
        std::fs::set_permissions(tmp.path(), perms).map_err(|e| refuse(path, io_reason(&e)))?;
    }
    tmp.as_file()
        .sync_all()
        .map_err(|e| refuse(path, io_reason(&e)))?;
    tmp.persist(&target.path)
        .map_err(|e| refuse(path, io_reason(&e.error)))?;
    // Make the rename itself durable (best effort: not every system can sync a folder).
    #[cfg(unix)]
    if let Ok(d) = std::fs::File::open(dir) {
        let _ = d.sync_all();
    }
    Ok(())
}

/// [`write_atomically`] for bytes already in memory.
///
/// # Errors
/// As [`write_atomically`].
pub fn write_bytes(path: &Path, inputs: &[&Path], bytes: &[u8]) -> Result<()> {
    write_atomically(path, inputs, |w| w.write_all(bytes))
}

/// The extensions [`write_linear_image`] writes: OpenEXR (32-bit float RGB) and Radiance HDR
/// (RGBE, 8-bit mantissas with a shared exponent).
pub const LINEAR_EXTS: &[&str] = &["exr", "hdr"];

/// Writes linear RGB floats (3 per pixel, row-major from the top-left pixel) as OpenEXR
/// (`.exr`, 32-bit float, lossless) or Radiance HDR (`.hdr`), chosen by the extension, through
/// [`write_atomically`].
///
/// # Errors
/// "cannot write FILE: reason": an extension not in [`LINEAR_EXTS`], `rgb` not holding
/// `3 * width * height` values, a negative or non-finite value (neither format stores one
/// faithfully), or any refusal of [`write_atomically`].
pub fn write_linear_image(
    path: &Path,
    inputs: &[&Path],
    width: u32,
    height: u32,
    rgb: &[f32],
) -> Result<()> {
    check_extension(path, LINEAR_EXTS)?;
    if rgb.len() != width as usize * height as usize * 3 {
        return Err(refuse(
            path,
            format!(
                "{} values for a {width}x{height} RGB image (needs {})",
                rgb.len(),
                width as usize * height as usize * 3
            ),
        ));
    }
    if let Some(i) = rgb.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
        return Err(refuse(
            path,
            format!(
                "pixel ({}, {}) has the value {} (radiance must be finite and not negative)",
                (i / 3) % width.max(1) as usize,
                (i / 3) / width.max(1) as usize,
                rgb[i]
            ),
        ));
    }
    let img = image::Rgb32FImage::from_raw(width, height, rgb.to_vec())
        .ok_or_else(|| refuse(path, "image size"))?;
    let format = if extension(path) == "exr" {
        image::ImageFormat::OpenExr
    } else {
        image::ImageFormat::Hdr
    };
    write_atomically(path, inputs, |w| {
        image::DynamicImage::ImageRgb32F(img)
            .write_to(w, format)
            .map_err(io::Error::other)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_images_round_trip_through_exr_exactly_and_hdr_closely() {
        let dir = tempfile::tempdir().unwrap();
        // 3 x 2, distinct values, one above 1 (radiance is not clipped).
        let rgb: Vec<f32> = (0..18).map(|i| i as f32 * 0.37 + 0.01).collect();
        for ext in LINEAR_EXTS {
            let p = dir.path().join(format!("lin.{ext}"));
            write_linear_image(&p, &[], 3, 2, &rgb).unwrap();
            let back = image::open(&p).unwrap().to_rgb32f();
            assert_eq!(back.dimensions(), (3, 2));
            for (a, b) in back.as_raw().iter().zip(&rgb) {
                // RGBE keeps 8 mantissa bits per channel against the pixel's largest.
                let tol = if *ext == "exr" {
                    0.0
                } else {
                    0.03 * b.max(1.0)
                };
                assert!((a - b).abs() <= tol, "{ext}: {a} vs {b}");
            }
        }
        assert_eq!(names(dir.path()), ["lin.exr", "lin.hdr"]);
    }

    #[test]
    fn linear_images_refuse_other_extensions_and_bad_values_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.png");
        let e = write_linear_image(&p, &[], 1, 1, &[0.0; 3]).unwrap_err();
        assert!(
            e.to_string().contains("out.png") && e.to_string().contains(".exr, .hdr"),
            "{e}"
        );
        let p = dir.path().join("out.exr");
        let e = write_linear_image(&p, &[], 2, 1, &[0.0, 0.0, 0.0, 0.1, f32::NAN, 0.0])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("out.exr") && e.contains("pixel (1, 0)") && e.contains("NaN"),
            "{e}"
        );
        let e = write_linear_image(&p, &[], 2, 2, &[0.0; 3])
            .unwrap_err()
            .to_string();
        assert!(e.contains("3 values for a 2x2"), "{e}");
        assert!(names(dir.path()).is_empty());
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn writes_replaces_and_leaves_nothing_beside() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("a.txt");
        write_bytes(&out, &[], b"one").unwrap();
        write_bytes(&out, &[], b"two").unwrap();
        assert_eq!(std::fs::read(&out).unwrap(), b"two");
        assert_eq!(names(dir.path()), ["a.txt"]);
    }

    #[test]
    fn a_failed_write_keeps_the_old_file_and_removes_the_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("a.txt");
        write_bytes(&out, &[], b"kept").unwrap();
        let e = write_atomically(&out, &[], |w| {
            w.write_all(b"half")?;
            Err(io::Error::other("encoder gave up"))
        })
        .unwrap_err()
        .to_string();
        assert_eq!(
            e,
            format!("cannot write {}: encoder gave up", out.display())
        );
        assert_eq!(std::fs::read(&out).unwrap(), b"kept");
        assert_eq!(names(dir.path()), ["a.txt"]);
    }

    #[test]
    fn refuses_a_directory_a_missing_folder_and_an_input() {
        let dir = tempfile::tempdir().unwrap();
        let e = write_bytes(dir.path(), &[], b"x").unwrap_err().to_string();
        assert!(
            e.starts_with("cannot write ") && e.contains("a directory"),
            "{e}"
        );
        let missing = dir.path().join("nope").join("a.txt");
        let e = write_bytes(&missing, &[], b"x").unwrap_err().to_string();
        assert!(e.contains("does not exist"), "{e}");
        let input = dir.path().join("in.ron");
        std::fs::write(&input, "keep").unwrap();
        let other_spelling = dir.path().join(".").join("in.ron");
        let e = write_bytes(&other_spelling, &[&input], b"x")
            .unwrap_err()
            .to_string();
        assert!(e.contains("is the input"), "{e}");
        assert_eq!(std::fs::read(&input).unwrap(), b"keep");
        assert_eq!(names(dir.path()), ["in.ron"]);
    }

    #[test]
    fn extensions_are_checked_case_insensitively() {
        check_extension(Path::new("a.PNG"), &["png"]).unwrap();
        let e = check_extension(Path::new("noext"), &["png", "exr"])
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "cannot write noext: the file name has no extension (use .png, .exr)"
        );
        let e = check_extension(Path::new("a.gif"), &["png"])
            .unwrap_err()
            .to_string();
        assert_eq!(e, "cannot write a.gif: unknown extension '.gif' (use .png)");
    }

    #[cfg(unix)]
    #[test]
    fn own_files_replace_a_link_and_never_write_through_it() {
        let dir = tempfile::tempdir().unwrap();
        let users = dir.path().join("users.txt");
        std::fs::write(&users, "the user's").unwrap();
        let own = dir.path().join("cache.exr");
        std::os::unix::fs::symlink(&users, &own).unwrap();
        write_own_file(&own, b"texplore's").unwrap();
        assert_eq!(std::fs::read(&users).unwrap(), b"the user's");
        assert!(std::fs::symlink_metadata(&own).unwrap().is_file());
        assert_eq!(std::fs::read(&own).unwrap(), b"texplore's");
        // A dangling link is replaced too; a folder is refused and left alone.
        let dangling = dir.path().join("key.txt");
        std::os::unix::fs::symlink(dir.path().join("nowhere"), &dangling).unwrap();
        write_own_file(&dangling, b"k").unwrap();
        assert!(!dir.path().join("nowhere").exists());
        let folder = dir.path().join("sub.exr");
        std::fs::create_dir(&folder).unwrap();
        let e = write_own_file(&folder, b"x").unwrap_err().to_string();
        assert!(e.contains("a folder"), "{e}");
        assert!(folder.is_dir());
        assert_eq!(
            names(dir.path()),
            ["cache.exr", "key.txt", "sub.exr", "users.txt"]
        );
    }

    #[cfg(unix)]
    #[test]
    fn keeps_the_mode_and_follows_a_symlink() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let real = dir.path().join("real.txt");
        std::fs::write(&real, "old").unwrap();
        std::fs::set_permissions(&real, Permissions::from_mode(0o640)).unwrap();
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_bytes(&link, &[], b"new").unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
        let mode = std::fs::metadata(&real).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o640);
        std::fs::set_permissions(&real, Permissions::from_mode(0o444)).unwrap();
        let e = write_bytes(&real, &[], b"x").unwrap_err().to_string();
        assert!(
            e.ends_with("permission denied (the file is read-only)"),
            "{e}"
        );
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
    }
}
