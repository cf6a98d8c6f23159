//! Reference images: rendered once at high spp, cached on disk as lossless linear float
//! OpenEXR files keyed by a hash of everything that changes them (the cache is the command
//! line's: a page has no cache folder), or made outside texplore ([`load_linear`]).

use super::ReportError;
use crate::math::Rgb;
use std::path::Path;

#[cfg(not(target_arch = "wasm32"))]
pub use cache::*;

/// The cache on disk.
#[cfg(not(target_arch = "wasm32"))]
mod cache {
    use super::{ReportError, check_radiance};
    use crate::math::Rgb;
    use crate::scene::{SceneDesc, SnapshotDesc, asset_paths, to_ron};
    use std::path::{Path, PathBuf};

    /// Bump when a renderer change alters images, so cached references are not reused.
    pub const REFERENCE_VERSION: &str = "texplore-reference-1";

    /// The cache key of a reference: the canonical text it is hashed from, and the hash.
    #[derive(Clone, Debug, PartialEq, Eq)]
    pub struct CacheKey {
        /// The preset (as canonical RON, with the reference's render settings), the version, and
        /// the path, length and FNV-1a 64 of every file the scene reads.
        pub text: String,
        /// FNV-1a 64 of `text`, in hex: the file name.
        pub hash: String,
    }

    /// 64-bit FNV-1a: stable across Rust versions and platforms (unlike `DefaultHasher`), so a
    /// key or checksum written by one build is read the same by the next.
    #[must_use]
    pub fn fnv1a64(bytes: &[u8]) -> u64 {
        let mut h = Fnv1a64::new();
        h.write(bytes);
        h.finish()
    }

    /// FNV-1a 64 fed in pieces (a file block by block).
    struct Fnv1a64(u64);

    impl Fnv1a64 {
        const fn new() -> Self {
            Self(0xcbf2_9ce4_8422_2325)
        }

        fn write(&mut self, bytes: &[u8]) {
            for b in bytes {
                self.0 ^= u64::from(*b);
                self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
            }
        }

        const fn finish(&self) -> u64 {
            self.0
        }
    }

    /// The key of `desc` (already carrying the reference's render settings) for the preset at
    /// `preset_path`. The description and snapshot settings do not change the image and are left
    /// out; every file the scene reads (images, meshes, an OBJ's `.mtl` libraries and their
    /// `map_Kd` images: [`crate::scene::asset_paths`]) is identified by its path, length and the
    /// FNV-1a 64 of its bytes, so editing any of them makes a new key.
    #[must_use]
    pub fn cache_key(desc: &SceneDesc, preset_path: &Path) -> CacheKey {
        let mut canonical = desc.clone();
        canonical.description.clear();
        canonical.snapshot = SnapshotDesc::default();
        let mut text = format!(
            "{REFERENCE_VERSION} texplore {}\n{}\n",
            env!("CARGO_PKG_VERSION"),
            to_ron(&canonical)
        );
        let base = preset_path.parent().unwrap_or(Path::new("."));
        for p in asset_paths(desc, base) {
            let abs = std::fs::canonicalize(&p).unwrap_or(p);
            let line = match file_fingerprint(&abs) {
                Ok((len, hash)) => format!("file {} {len} {hash:016x}\n", abs.display()),
                // The build that follows reports the file; the key only has to differ.
                Err(e) => format!("file {} unreadable: {e}\n", abs.display()),
            };
            text.push_str(&line);
        }
        let hash = format!("{:016x}", fnv1a64(text.as_bytes()));
        CacheKey { text, hash }
    }

    /// The length and FNV-1a 64 of a file's bytes, read in blocks through [`crate::input`].
    fn file_fingerprint(path: &Path) -> crate::Result<(u64, u64)> {
        use std::io::Read;
        let mut file = crate::input::open_input(path)?;
        let mut h = Fnv1a64::new();
        let mut len = 0u64;
        let mut buf = vec![0u8; 1 << 16];
        loop {
            let n = file.read(&mut buf).map_err(|e| crate::Error::io(path, e))?;
            if n == 0 {
                return Ok((len, h.finish()));
            }
            h.write(&buf[..n]);
            len += n as u64;
        }
    }

    /// The default cache directory: the platform's cache folder (from the `dirs` crate:
    /// `$XDG_CACHE_HOME` or `~/.cache` on Linux, `~/Library/Caches` on macOS, `%LOCALAPPDATA%` on
    /// Windows) + `texplore/references`, else `fallback`.
    #[must_use]
    pub fn default_cache_dir(fallback: &Path) -> PathBuf {
        dirs::cache_dir().map_or_else(
            || fallback.to_path_buf(),
            |d| d.join("texplore").join("references"),
        )
    }

    /// The files of one cached reference.
    #[derive(Clone, Debug)]
    pub struct CachedReference {
        /// The EXR holding linear RGB.
        pub exr: PathBuf,
        /// The key text beside it (checked on load, so a hash collision cannot return a wrong image).
        pub key_file: PathBuf,
    }

    impl CachedReference {
        /// The files for `key` in `dir`.
        #[must_use]
        pub fn new(dir: &Path, key: &CacheKey) -> Self {
            Self {
                exr: dir.join(format!("{}.exr", key.hash)),
                key_file: dir.join(format!("{}.key.txt", key.hash)),
            }
        }

        /// The cached image if present and of the expected size, for exactly this key, and with
        /// the EXR's bytes matching the checksum stored in the key file; `Ok(None)` when nothing
        /// is cached for this key. Another report may be storing the same reference meanwhile:
        /// every file is replaced whole, and a key and EXR from two different writes fail the
        /// checksum, so the caller renders the reference again rather than fail.
        ///
        /// # Errors
        /// Why a cached reference for this key cannot be used: "FILE: checksum mismatch (stored
        /// ..., read ...)", a truncated or unreadable EXR, a wrong size. The caller renders the
        /// reference again (and stores it over the damaged one).
        pub fn load(
            &self,
            key: &CacheKey,
            width: u32,
            height: u32,
        ) -> Result<Option<Vec<Rgb>>, String> {
            let max_key = key.text.len() as u64 + 256;
            // The cache's names are predictable: a link planted at one is refused, not followed.
            let stored = match crate::input::read_own_input(&self.key_file, max_key) {
                Ok(bytes) => String::from_utf8(bytes)
                    .map_err(|_| format!("{}: not UTF-8 text", self.key_file.display()))?,
                Err(crate::Error::Io { io, .. }) if io.kind() == std::io::ErrorKind::NotFound => {
                    return Ok(None);
                }
                Err(e) => return Err(e.to_string()),
            };
            let Some((text, checksum)) = split_key_file(&stored) else {
                return Err(format!(
                    "{}: no EXR checksum line (written by an older texplore?)",
                    self.key_file.display()
                ));
            };
            if text != key.text {
                // A hash collision, or a key of another format: not this reference.
                return Ok(None);
            }
            let max_exr = 4096 + 16 * u64::from(width) * u64::from(height);
            let bytes =
                crate::input::read_own_input(&self.exr, max_exr).map_err(|e| e.to_string())?;
            let (len, hash) = (bytes.len() as u64, fnv1a64(&bytes));
            if (len, hash) != checksum {
                return Err(format!(
                    "{}: checksum mismatch (the key file says {} bytes with FNV-1a {:016x}, the file \
                     has {len} bytes with {hash:016x})",
                    self.exr.display(),
                    checksum.0,
                    checksum.1
                ));
            }
            let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::OpenExr)
                .map_err(|e| format!("{}: {e}", self.exr.display()))?
                .to_rgb32f();
            if img.dimensions() != (width, height) {
                return Err(format!(
                    "{}: {}x{} pixels, not the {width}x{height} asked for",
                    self.exr.display(),
                    img.width(),
                    img.height()
                ));
            }
            // Checked as `--reference` checks its file: a matching checksum says only that the
            // bytes are the ones stored.
            check_radiance(&img).map_err(|why| format!("{}: {why}", self.exr.display()))?;
            Ok(Some(img.pixels().map(|p| Rgb::from_array(p.0)).collect()))
        }

        /// Stores an image atomically through [`crate::output::write_own_file`] (a symbolic link
        /// planted at a cache name is replaced, never written through): the EXR first, then the key
        /// with the EXR's length and checksum on its last line.
        ///
        /// # Errors
        /// The directory or files cannot be written.
        pub fn store(
            &self,
            key: &CacheKey,
            width: u32,
            height: u32,
            pixels: &[Rgb],
        ) -> Result<(), ReportError> {
            let dir = self.exr.parent().unwrap_or(Path::new("."));
            std::fs::create_dir_all(dir).map_err(|e| ReportError::io(dir, e))?;
            let data: Vec<f32> = pixels.iter().flat_map(|c| c.to_array()).collect();
            let img = image::Rgb32FImage::from_raw(width, height, data)
                .ok_or_else(|| ReportError::io(&self.exr, std::io::Error::other("image size")))?;
            let mut exr = std::io::Cursor::new(Vec::new());
            image::DynamicImage::ImageRgb32F(img)
                .write_to(&mut exr, image::ImageFormat::OpenExr)
                .map_err(|e| ReportError::io(&self.exr, std::io::Error::other(e)))?;
            let exr = exr.into_inner();
            crate::output::write_own_file(&self.exr, &exr)?;
            // The key last: a reference is only used once its key matches and the EXR's bytes
            // match the checksum.
            let key_file = format!(
                "{}\n{CHECKSUM_PREFIX}{} {:016x}\n",
                key.text,
                exr.len(),
                fnv1a64(&exr)
            );
            crate::output::write_own_file(&self.key_file, key_file.as_bytes())?;
            Ok(())
        }
    }

    /// The last line of a key file, after the key text and a newline: `exr LENGTH FNV1A64-HEX`.
    const CHECKSUM_PREFIX: &str = "exr ";

    /// A key file's key text and the EXR length and checksum on its last line.
    fn split_key_file(stored: &str) -> Option<(&str, (u64, u64))> {
        let body = stored.strip_suffix('\n')?;
        let at = body.rfind('\n')?;
        let (text, last) = (&body[..at], &body[at + 1..]);
        let (len, hash) = last.strip_prefix(CHECKSUM_PREFIX)?.split_once(' ')?;
        Some((
            text,
            (len.parse().ok()?, u64::from_str_radix(hash, 16).ok()?),
        ))
    }
}

/// Reads a reference made outside texplore: a linear OpenEXR or Radiance HDR file of
/// `width` x `height` pixels (the render's size), as it is (no exposure, no curve).
///
/// # Errors
/// [`ReportError::Invalid`] naming the file: it cannot be read, is not an EXR or HDR image, has
/// another size, or holds a negative or non-finite value.
pub fn load_linear(path: &Path, width: u32, height: u32) -> Result<Vec<Rgb>, ReportError> {
    let bad = |why: String| ReportError::Invalid(format!("{}: {why}", path.display()));
    let format = match crate::output::extension(path).as_str() {
        "exr" => image::ImageFormat::OpenExr,
        "hdr" => image::ImageFormat::Hdr,
        other => {
            return Err(bad(format!(
                "a reference is a linear .exr or .hdr image, not '.{other}'"
            )));
        }
    };
    // Room for an uncompressed float image of the render's size and some headers.
    let max = (1 << 20) + 16 * u64::from(width) * u64::from(height);
    let bytes =
        crate::input::read_input(path, max).map_err(|e| ReportError::Invalid(e.to_string()))?;
    let img = image::load_from_memory_with_format(&bytes, format)
        .map_err(|e| bad(format!("not a readable image ({e})")))?
        .to_rgb32f();
    if img.dimensions() != (width, height) {
        return Err(bad(format!(
            "{}x{} pixels, but the render is {width}x{height} (give the reference's size with \
             --width and --height)",
            img.width(),
            img.height()
        )));
    }
    check_radiance(&img).map_err(bad)?;
    Ok(img.pixels().map(|p| Rgb::from_array(p.0)).collect())
}

/// Every value of a reference is a radiance: finite and not negative.
///
/// # Errors
/// "pixel (x, y) holds VALUE, not a radiance" for the first that is not.
fn check_radiance(img: &image::Rgb32FImage) -> Result<(), String> {
    let width = img.width() as usize;
    match img
        .as_raw()
        .iter()
        .enumerate()
        .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
    {
        Some((i, v)) => Err(format!(
            "pixel ({}, {}) holds {v}, not a radiance",
            (i / 3) % width,
            (i / 3) / width
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_matches_published_vectors() {
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn exr_round_trip_is_lossless_and_checks_the_key() {
        let dir = tempfile::tempdir().unwrap();
        let key = CacheKey {
            text: "k1".into(),
            hash: "00ff".into(),
        };
        let px = vec![Rgb(0.1, 2.5, 1e-4), Rgb(0.0, 0.333_333, 7.0)];
        let c = CachedReference::new(dir.path(), &key);
        assert_eq!(c.load(&key, 2, 1), Ok(None));
        c.store(&key, 2, 1, &px).unwrap();
        assert_eq!(c.load(&key, 2, 1).unwrap(), Some(px));
        assert!(
            c.load(&key, 1, 2).unwrap_err().contains("not the 1x2"),
            "wrong size must not be reused"
        );
        let other = CacheKey {
            text: "k2".into(),
            hash: "00ff".into(),
        };
        assert_eq!(
            c.load(&other, 2, 1),
            Ok(None),
            "a collision must not be reused"
        );
    }

    #[test]
    fn a_flipped_bit_in_the_exr_is_refused_by_its_checksum() {
        let dir = tempfile::tempdir().unwrap();
        let key = CacheKey {
            text: "key\nlines\n".into(),
            hash: "0abc".into(),
        };
        let c = CachedReference::new(dir.path(), &key);
        c.store(&key, 1, 1, &[Rgb(0.5, 0.25, 1.0)]).unwrap();
        let mut bytes = std::fs::read(&c.exr).unwrap();
        let last = bytes.len() - 1;
        bytes[last] ^= 0x10;
        std::fs::write(&c.exr, &bytes).unwrap();
        let e = c.load(&key, 1, 1).unwrap_err();
        assert!(e.contains("0abc.exr: checksum mismatch"), "{e}");
        std::fs::remove_file(&c.exr).unwrap();
        let e = c.load(&key, 1, 1).unwrap_err();
        assert!(e.contains("0abc.exr") && e.contains("No such file"), "{e}");
    }
}
