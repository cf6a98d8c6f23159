//! `texplore snapshot`: renders every preset at its snapshot settings and compares it with the
//! golden image in `screenshots/`.
//!
//! Tolerance: renders are deterministic, so a match is normally exact; to absorb last-bit
//! differences between machines a pixel counts as different when a channel differs by more than
//! [`PIXEL_TOLERANCE`] (of 255), and the check fails when more than [`MAX_BAD_FRACTION`] of the
//! pixels differ or the mean absolute difference exceeds [`MAX_MEAN_DIFF`].

use crate::error::{Error, Result};
use crate::render::render_blocking;
use crate::scene::SimdMode;
use crate::scene::{AssetCache, SceneDesc, build_scene, load_preset};
use crate::texture::save_png;
use std::path::{Path, PathBuf};

/// Largest per-channel difference (0-255) that still counts as the same pixel.
pub const PIXEL_TOLERANCE: u8 = 2;
/// Largest fraction of differing pixels that still passes.
pub const MAX_BAD_FRACTION: f64 = 0.001;
/// Largest mean absolute channel difference (0-255) that still passes.
pub const MAX_MEAN_DIFF: f64 = 0.25;

/// The outcome for one preset.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// Within tolerance.
    Match(Comparison),
    /// Outside tolerance; the new render and a diff image were written.
    Mismatch {
        /// The numbers.
        comparison: Comparison,
        /// The new render.
        new: PathBuf,
        /// The amplified difference.
        diff: PathBuf,
    },
    /// No golden image yet (or its size changed); the new render was written there.
    Missing {
        /// The new render.
        new: PathBuf,
    },
    /// Golden rewritten (`snapshot update`).
    Updated,
}

/// How two 8-bit RGB images differ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// Largest channel difference.
    pub max_diff: u8,
    /// Mean absolute channel difference.
    pub mean_diff: f64,
    /// Fraction of pixels with a channel differing by more than [`PIXEL_TOLERANCE`].
    pub bad_fraction: f64,
}

impl Comparison {
    /// Whether this is within the stated tolerance.
    #[must_use]
    pub fn passes(&self) -> bool {
        self.bad_fraction <= MAX_BAD_FRACTION && self.mean_diff <= MAX_MEAN_DIFF
    }
}

/// Compares two RGB8 buffers of the same size.
#[must_use]
pub fn compare(a: &[u8], b: &[u8]) -> Comparison {
    let mut max_diff = 0u8;
    let mut sum = 0u64;
    let mut bad = 0usize;
    for (pa, pb) in a.chunks_exact(3).zip(b.chunks_exact(3)) {
        let d = (0..3).map(|i| pa[i].abs_diff(pb[i])).max().unwrap_or(0);
        sum += (0..3)
            .map(|i| u64::from(pa[i].abs_diff(pb[i])))
            .sum::<u64>();
        max_diff = max_diff.max(d);
        bad += usize::from(d > PIXEL_TOLERANCE);
    }
    let n = (a.len() / 3).max(1);
    Comparison {
        max_diff,
        mean_diff: sum as f64 / (n * 3) as f64,
        bad_fraction: bad as f64 / n as f64,
    }
}

/// Renders a preset at its snapshot settings, its primary rays on the path `simd` chooses;
/// returns (width, height, RGB8).
///
/// # Errors
/// The preset or its assets cannot be loaded.
pub fn render_snapshot(
    desc: &SceneDesc,
    preset_path: &Path,
    cache: &mut AssetCache,
    simd: SimdMode,
) -> Result<(u32, u32, Vec<u8>)> {
    let mut desc = desc.clone();
    desc.render.width = desc.snapshot.width;
    desc.render.height = desc.snapshot.height;
    desc.render.spp = desc.snapshot.spp;
    let mut scene = build_scene(&desc, preset_path, cache)?;
    scene.settings.simd = simd;
    let film = render_blocking(&scene, |_| {});
    let img = film.to_display(scene.settings.exposure_scale);
    Ok((img.width, img.height, img.rgb()))
}

/// Checks (or with `update`, rewrites) the golden image of one preset.
///
/// # Errors
/// The preset cannot be rendered or an image cannot be read or written.
pub fn check_preset(
    preset: &Path,
    screenshots: &Path,
    update: bool,
    cache: &mut AssetCache,
    simd: SimdMode,
) -> Result<Outcome> {
    let name = preset
        .file_stem()
        .map_or_else(|| "preset".into(), |s| s.to_string_lossy().into_owned());
    let desc = load_preset(preset)?;
    let (w, h, rgb) = render_snapshot(&desc, preset, cache, simd)?;
    let golden = screenshots.join(format!("{name}.png"));
    let new = screenshots.join(format!("{name}.new.png"));
    let diff = screenshots.join(format!("{name}.diff.png"));
    std::fs::create_dir_all(screenshots).map_err(|e| Error::io(screenshots, e))?;
    if update {
        save_png(&golden, w, h, &rgb, &[])?;
        let _ = std::fs::remove_file(&new);
        let _ = std::fs::remove_file(&diff);
        return Ok(Outcome::Updated);
    }
    let old = match read_golden(&golden)? {
        Some(img) if img.width() == w && img.height() == h => img.into_raw(),
        _ => {
            save_png(&new, w, h, &rgb, &[])?;
            return Ok(Outcome::Missing { new });
        }
    };
    let comparison = compare(&old, &rgb);
    if comparison.passes() {
        let _ = std::fs::remove_file(&new);
        let _ = std::fs::remove_file(&diff);
        return Ok(Outcome::Match(comparison));
    }
    save_png(&new, w, h, &rgb, &[])?;
    let amplified: Vec<u8> = old
        .iter()
        .zip(&rgb)
        .map(|(a, b)| a.abs_diff(*b).saturating_mul(8))
        .collect();
    save_png(&diff, w, h, &amplified, &[])?;
    Ok(Outcome::Mismatch {
        comparison,
        new,
        diff,
    })
}

/// The golden image at `path` as 8-bit RGB, read through [`crate::input`] (a regular file of at
/// most [`crate::texture::MAX_IMAGE_BYTES`]); `None` when there is none yet.
///
/// # Errors
/// The path is not a regular file, or the file is not a readable image.
fn read_golden(path: &Path) -> Result<Option<image::RgbImage>> {
    let bytes = match crate::input::read_input(path, crate::texture::MAX_IMAGE_BYTES) {
        Ok(b) => b,
        Err(Error::Io { io, .. }) if io.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(e),
    };
    let img =
        image::load_from_memory_with_format(&bytes, image::ImageFormat::Png).map_err(|e| {
            Error::Image {
                path: path.to_path_buf(),
                message: format!("the golden image cannot be read: {e}"),
            }
        })?;
    Ok(Some(img.to_rgb8()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comparison_counts_and_tolerates() {
        let a = vec![10u8; 3 * 1000];
        let mut b = a.clone();
        assert!(compare(&a, &b).passes());
        b[0] = 12; // within tolerance
        let c = compare(&a, &b);
        assert_eq!(c.max_diff, 2);
        assert!(c.passes());
        b[3] = 40; // one bad pixel in 1000: exactly at the limit
        assert!(compare(&a, &b).passes());
        b[6] = 40; // two: over
        let c = compare(&a, &b);
        assert!(!c.passes() && (c.bad_fraction - 0.002).abs() < 1e-12);
    }
}
