//! Presets as text: parsing (with the line and column of an error), loading, pretty RON and
//! saving.

use super::PRESET_VERSION;
use super::SceneDesc;
use super::numbers::check_numbers;
use super::paths::asset_paths;
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Largest preset file read (a preset is a few kilobytes; anything huge is a mistake).
pub const MAX_PRESET_BYTES: u64 = 16 << 20;

/// Parses preset text; errors carry `path` and the line and column where parsing stopped.
///
/// # Errors
/// Malformed RON, unknown fields, wrong types, or an unsupported `version`.
pub fn parse_preset(text: &str, path: &Path) -> Result<SceneDesc> {
    // A byte-order mark is not RON; editors on Windows write one.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let desc: SceneDesc = ron::from_str(text).map_err(|e| Error::Preset {
        path: path.to_path_buf(),
        line: e.span.start.line,
        column: e.span.start.col,
        message: e.code.to_string(),
    })?;
    if desc.version != PRESET_VERSION {
        return Err(Error::invalid(
            path,
            format!(
                "version {} is not supported (this texplore reads version {PRESET_VERSION})",
                desc.version
            ),
        ));
    }
    Ok(desc)
}

/// Reads and parses a preset file (a regular file of at most 16 MiB, `MAX_PRESET_BYTES`).
///
/// # Errors
/// The file cannot be read, is not a regular file, is too large, or does not parse.
pub fn load_preset(path: &Path) -> Result<SceneDesc> {
    let text = crate::input::read_input_text(path, MAX_PRESET_BYTES)?;
    parse_preset(&text, path)
}

/// The preset as pretty RON.
#[must_use]
pub fn to_ron(desc: &SceneDesc) -> String {
    let config = ron::ser::PrettyConfig::new()
        .depth_limit(8)
        .struct_names(false);
    ron::ser::to_string_pretty(desc, config).unwrap_or_else(|e| format!("// cannot serialise: {e}"))
}

/// Writes a preset atomically through [`crate::output::write_atomically`] (a temporary file
/// beside it, renamed over it; never over a directory, device or read-only file, nor over one
/// of the preset's own images or meshes, whose paths are relative to `path`'s folder).
///
/// # Errors
/// A value is not a finite number ("FILE: not saved: ambient.color: NaN is not a number"), or
/// the file is refused or cannot be written: "cannot write FILE: reason".
pub fn save_preset(desc: &SceneDesc, path: &Path) -> Result<()> {
    check_numbers(desc)
        .map_err(|r| Error::invalid(path, format!("not saved: {}", desc.refusal_message(&r))))?;
    let folder = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let assets = asset_paths(desc, folder);
    let inputs: Vec<&Path> = assets.iter().map(PathBuf::as_path).collect();
    crate::output::write_bytes(path, &inputs, to_ron(desc).as_bytes())
}
