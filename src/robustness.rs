//! Harnesses that feed arbitrary bytes to every parser a user's file reaches, shared by the
//! cargo-fuzz targets in `fuzz/` and the bounded fuzz test in `tests/fuzz.rs`.
//!
//! Each harness returns the library's result for the input and panics only when an invariant a
//! user relies on is broken: a parser panicked, an error does not name the file, a loaded image
//! exceeds the decode limits or holds a non-finite texel, or a scene that built renders NaN. A
//! panic here is a finding; an `Err` is the correct answer to bad input.

use crate::error::{Error, Result};
use crate::render::render_blocking;
use crate::scene::{AssetCache, Overrides, apply_overrides, build_scene, parse_preset};
use crate::texture::{ImageData, MAX_IMAGE_DIMENSION, load_image};
use std::path::Path;

/// Largest render a fuzzed preset is rendered at: enough to reach every shape, texture and
/// mapping of the scene, small enough for thousands of executions a second.
const FUZZ_RENDER: (u32, u32) = (8, 6);

/// Panics unless `e`'s message names `path` (the promise every error of texplore keeps).
fn assert_names(e: &Error, path: &Path) {
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let msg = e.to_string();
    assert!(
        msg.contains(&name),
        "the error does not name the file {name}: {msg}"
    );
    assert!(!msg.contains('\n') || msg.len() < 4096, "unbounded message");
}

/// Parses `data` as a preset at `preset_path` (asset paths resolve beside it, through `cache`),
/// builds it, and renders it at 8x6, 1 spp.
///
/// # Errors
/// What the parser or the scene build refused, naming `preset_path`.
///
/// # Panics
/// When an invariant breaks (see the module docs): that is a bug in texplore.
pub fn preset_bytes(data: &[u8], preset_path: &Path, cache: &mut AssetCache) -> Result<()> {
    let text = String::from_utf8_lossy(data);
    let result = parse_preset(&text, preset_path).and_then(|mut desc| {
        apply_overrides(
            &mut desc,
            Overrides {
                width: Some(FUZZ_RENDER.0),
                height: Some(FUZZ_RENDER.1),
                spp: Some(1),
                ..Overrides::default()
            },
        );
        let scene = build_scene(&desc, preset_path, cache)?;
        let film = render_blocking(&scene, |_| {});
        assert!(film.is_finite(), "a preset that built rendered NaN or Inf");
        Ok(())
    });
    if let Err(e) = &result {
        // Asset errors name the asset, not the preset; everything else names the preset.
        if !matches!(e, Error::Image { .. } | Error::Io { .. }) {
            assert_names(e, preset_path);
        }
    }
    result
}

/// Writes `data` to `path` and loads it as an image the way a preset's texture is loaded.
///
/// # Errors
/// The decoder's refusal, naming `path`.
///
/// # Panics
/// When an invariant breaks (see the module docs), or `path` cannot be written.
pub fn image_bytes(data: &[u8], path: &Path) -> Result<ImageData> {
    std::fs::write(path, data).expect("the fuzz harness cannot write its scratch file");
    match load_image(path, true) {
        Ok(img) => {
            assert!(img.width() >= 1 && img.height() >= 1);
            assert!(img.width() <= MAX_IMAGE_DIMENSION && img.height() <= MAX_IMAGE_DIMENSION);
            for y in 0..img.height() {
                for x in 0..img.width() {
                    assert!(img.texel_top(x, y).is_finite(), "non-finite texel");
                }
            }
            Ok(img)
        }
        Err(e) => {
            assert_names(&e, path);
            Err(e)
        }
    }
}

/// Writes `data` to `path` (a `.png`) and reads the preset a texplore screenshot carries, the
/// way opening or dropping a PNG on the window does.
///
/// # Errors
/// Not a PNG, no preset inside, or a preset that does not parse, naming `path`.
///
/// # Panics
/// When an invariant breaks (see the module docs), or `path` cannot be written.
pub fn screenshot_bytes(data: &[u8], path: &Path) -> Result<crate::scene::SceneDesc> {
    std::fs::write(path, data).expect("the fuzz harness cannot write its scratch file");
    let result = crate::scene::read_preset_or_png(path);
    if let Err(e) = &result {
        assert_names(e, path);
    }
    result
}
