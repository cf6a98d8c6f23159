//! Reference images: rendered once at high spp, cached on disk as lossless linear float
//! OpenEXR files keyed by a hash of everything that changes them.

use super::ReportError;
use crate::math::Rgb;
use crate::scene::{SceneDesc, SnapshotDesc, TextureDesc, to_ron};
use std::path::{Path, PathBuf};

/// Bump when a renderer change alters images, so cached references are not reused.
pub const REFERENCE_VERSION: &str = "texplore-reference-1";

/// The cache key of a reference: the canonical text it is hashed from, and the hash.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CacheKey {
    /// The preset (as canonical RON, with the reference's render settings), the version and
    /// the size and modification time of every asset file.
    pub text: String,
    /// FNV-1a 64 of `text`, in hex: the file name.
    pub hash: String,
}

/// 64-bit FNV-1a: stable across Rust versions and platforms (unlike `DefaultHasher`).
#[must_use]
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// The key of `desc` (already carrying the reference's render settings) for the preset at
/// `preset_path`. The description and snapshot settings do not change the image and are left
/// out; asset files are identified by path, size and modification time.
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
    for obj in &desc.objects {
        if let TextureDesc::Image { path, .. } = obj.material.texture() {
            let p = base.join(path);
            let abs = std::fs::canonicalize(&p).unwrap_or(p);
            let (len, mtime) = std::fs::metadata(&abs).map_or((0, 0), |m| {
                let mtime = m
                    .modified()
                    .ok()
                    .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
                    .map_or(0, |d| d.as_nanos());
                (m.len(), mtime)
            });
            text.push_str(&format!("asset {} {len} {mtime}\n", abs.display()));
        }
    }
    let hash = format!("{:016x}", fnv1a64(text.as_bytes()));
    CacheKey { text, hash }
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

    /// The cached image if present, complete, of the expected size and for exactly this key.
    #[must_use]
    pub fn load(&self, key: &CacheKey, width: u32, height: u32) -> Option<Vec<Rgb>> {
        let stored = std::fs::read_to_string(&self.key_file).ok()?;
        if stored != key.text {
            return None;
        }
        let img = image::open(&self.exr).ok()?.to_rgb32f();
        if img.dimensions() != (width, height) {
            return None;
        }
        Some(img.pixels().map(|p| Rgb::from_array(p.0)).collect())
    }

    /// Stores an image atomically through [`crate::output::write_atomically`] (EXR first, key
    /// last).
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
        crate::output::write_atomically(&self.exr, &[], |out| {
            image::DynamicImage::ImageRgb32F(img)
                .write_to(out, image::ImageFormat::OpenExr)
                .map_err(std::io::Error::other)
        })?;
        // The key last: a reference is only used once its key matches.
        crate::output::write_bytes(&self.key_file, &[], key.text.as_bytes())?;
        Ok(())
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
        assert!(c.load(&key, 2, 1).is_none());
        c.store(&key, 2, 1, &px).unwrap();
        assert_eq!(c.load(&key, 2, 1).unwrap(), px);
        assert!(
            c.load(&key, 1, 2).is_none(),
            "wrong size must not be reused"
        );
        let other = CacheKey {
            text: "k2".into(),
            hash: "00ff".into(),
        };
        assert!(
            c.load(&other, 2, 1).is_none(),
            "a collision must not be reused"
        );
    }
}
