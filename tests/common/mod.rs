//! Helpers the headless tests share (`tests/headless/`): running the binary, and scenes built
//! from a preset with overrides; `tests/headless/main.rs` declares the module once.

// Each test module uses a subset of these.
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};
use texplore::render::{Film, render_blocking};
use texplore::scene::{AssetCache, Overrides, Scene, SceneDesc, apply_overrides, build_scene};
use texplore::texture::Filter;

/// The crate's root (where `presets/` and `assets/` are).
#[must_use]
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `texplore` with `args` from the crate's root.
#[must_use]
pub fn texplore(args: &[&str]) -> Output {
    texplore_in(root(), args)
}

/// Runs `texplore` with `args` from `dir`.
#[must_use]
pub fn texplore_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_texplore"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run texplore {args:?}: {e}"))
}

/// Checks that a run succeeded (showing its stderr if not) and returns its stdout as text.
pub fn success(out: &Output) -> String {
    assert!(
        out.status.success(),
        "texplore failed ({}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Checks that a run failed (showing its stdout if not) and returns its stderr as text.
#[must_use]
pub fn failure(out: &Output) -> String {
    assert!(
        !out.status.success(),
        "texplore succeeded where it should fail: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs `texplore` with `args` from the crate's root, checks success, and parses its stdout as
/// JSON.
#[must_use]
pub fn texplore_json(args: &[&str]) -> serde_json::Value {
    parse_json(&texplore(args))
}

/// A successful run's stdout as JSON.
#[must_use]
pub fn parse_json(out: &Output) -> serde_json::Value {
    let text = success(out);
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("stdout is not JSON ({e}): {text}"))
}

/// Overrides of the image size and the samples per pixel (the rest from the preset).
#[must_use]
pub fn sized(width: u32, height: u32, spp: u32) -> Overrides {
    Overrides {
        width: Some(width),
        height: Some(height),
        spp: Some(spp),
        ..Overrides::default()
    }
}

/// Overrides of every image texture's filter only.
#[must_use]
pub fn filtered(filter: Filter) -> Overrides {
    Overrides {
        filter: Some(filter),
        ..Overrides::default()
    }
}

/// `desc` with `overrides` applied, built; asset paths resolve next to `preset` (which also
/// names the scene in errors).
#[must_use]
pub fn build_with(
    desc: &SceneDesc,
    preset: &Path,
    overrides: Overrides,
    cache: &mut AssetCache,
) -> Scene {
    let mut desc = desc.clone();
    apply_overrides(&mut desc, overrides);
    build_scene(&desc, preset, cache).unwrap_or_else(|e| panic!("{e}"))
}

/// Renders `scene` to completion on `threads` threads.
#[must_use]
pub fn render_on(scene: &Scene, threads: usize) -> Film {
    let pool = texplore::render::thread_pool(threads).unwrap_or_else(|e| panic!("{e}"));
    pool.install(|| render_blocking(scene, |_| {}))
}

/// `texplore report` on `presets` at 16x12, one mode, 1 spp, a 4-spp reference, cached in
/// `cache` (`None`: `--no-cache`).
pub fn tiny_report(presets: &[&Path], out: &Path, cache: Option<&Path>) -> Output {
    let mut args = vec!["report".to_string()];
    args.extend(presets.iter().map(|p| p.to_str().unwrap().to_string()));
    for a in [
        "--modes",
        "nearest/jittered",
        "--spp",
        "1",
        "--reference-spp",
        "4",
        "--width",
        "16",
        "--height",
        "12",
        "--repeat",
        "1",
        "--time-budget",
        "0",
        "--threads",
        "1",
        "-o",
        out.to_str().unwrap(),
    ] {
        args.push(a.into());
    }
    match cache {
        Some(c) => args.extend(["--cache".into(), c.to_str().unwrap().into()]),
        None => args.push("--no-cache".into()),
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    texplore(&args)
}

/// The CRC-32 of a PNG chunk's type and data (bit by bit: a test needs no table), for every
/// test that writes a PNG by hand.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}
