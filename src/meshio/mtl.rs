//! Wavefront material libraries (`.mtl`): our own parser of what texplore uses (`newmtl`, `Kd`,
//! `map_Kd`), and [`Libraries`], which reads each library of a mesh once and all of them
//! together under one byte budget, however often the OBJ names them.

use super::obj::{keyword, logical_lines};
use crate::error::{Error, Result};
use crate::input::FileId;
use std::collections::HashSet;
use std::io::Read;
use std::path::{Path, PathBuf};

/// Largest `.mtl` file read.
pub const MAX_MTL_BYTES: u64 = 16 << 20;
/// Most bytes of material libraries one mesh reads, all its libraries together: an OBJ naming
/// a large library 20,000 times reads it once, and naming 20,000 large libraries stops here.
pub const MAX_MESH_MTL_BYTES: u64 = 64 << 20;
/// Most material libraries one mesh reads (each one opened costs a look-up of the file system).
pub const MAX_MESH_LIBRARIES: usize = 256;

/// The material libraries one mesh reads: each file once (known by its identity, so `m.mtl`
/// and `./m.mtl` are one), all of them within [`MAX_MESH_MTL_BYTES`] and [`MAX_MESH_LIBRARIES`].
/// A library that cannot be read is not an error: the first problem is kept for
/// `MeshData::material_problem`, and the mesh keeps its geometry.
#[derive(Debug)]
pub(super) struct Libraries {
    read: HashSet<FileId>,
    opened: usize,
    bytes_left: u64,
    /// The first problem met, naming the library (and the line).
    pub(super) problem: Option<String>,
}

impl Libraries {
    pub(super) fn new() -> Self {
        Self {
            read: HashSet::new(),
            opened: 0,
            bytes_left: MAX_MESH_MTL_BYTES,
            problem: None,
        }
    }

    fn note(&mut self, problem: String) {
        self.problem.get_or_insert(problem);
    }

    /// The materials of the library at `path`: empty when this mesh read it already, when it
    /// cannot be read or parsed, or when the mesh's budget is spent (the problem noted).
    pub(super) fn read(&mut self, path: &Path) -> Vec<MtlMaterial> {
        if self.opened >= MAX_MESH_LIBRARIES {
            self.note(format!(
                "material library {}: not read (the mesh names more than \
                 {MAX_MESH_LIBRARIES} libraries, the most texplore reads)",
                path.display()
            ));
            return Vec::new();
        }
        self.opened += 1;
        let file = match crate::input::open_input(path) {
            Ok(f) => f,
            Err(e) => {
                self.note(format!("material library {e}"));
                return Vec::new();
            }
        };
        if !self.read.insert(crate::input::file_id(&file, path)) {
            // The same file under another name: read once.
            self.opened -= 1;
            return Vec::new();
        }
        let len = crate::input::input_len(&file);
        let max = MAX_MTL_BYTES.min(self.bytes_left);
        if len.is_some_and(|n| n > max) || max == 0 {
            self.note(Self::too_large(path, max));
            self.bytes_left = 0;
            return Vec::new();
        }
        match parse_mtl(file, path, max) {
            Ok((list, bytes)) => {
                self.bytes_left -= bytes.min(self.bytes_left);
                list
            }
            Err(e) if e.to_string().contains("too large") => {
                self.note(Self::too_large(path, max));
                self.bytes_left = 0;
                Vec::new()
            }
            Err(e) => {
                self.note(format!("material library {e}"));
                Vec::new()
            }
        }
    }

    /// Why the library at `path` is not read past `max` bytes.
    fn too_large(path: &Path, max: u64) -> String {
        if max == MAX_MTL_BYTES {
            format!(
                "material library {}: too large (larger than {}, the most texplore reads \
                 of one library)",
                path.display(),
                crate::input::human_bytes(MAX_MTL_BYTES)
            )
        } else {
            format!(
                "material library {}: not read (the mesh's libraries together are larger than \
                 {}, the most texplore reads for one mesh)",
                path.display(),
                crate::input::human_bytes(MAX_MESH_MTL_BYTES)
            )
        }
    }
}

/// A material as texplore uses it: its name, `Kd` and the file `map_Kd` names (resolved against
/// the library's folder).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct MtlMaterial {
    pub(super) name: String,
    pub(super) diffuse: Option<[f32; 3]>,
    pub(super) texture: Option<PathBuf>,
}

/// Parses the opened material library `file` (read from `path`), at most `max_bytes` of it:
/// its materials and the bytes read.
///
/// # Errors
/// The file cannot be read or is larger than `max_bytes`, or a statement texplore uses is
/// malformed: the error names the library and the line.
fn parse_mtl(
    file: crate::input::Input,
    path: &Path,
    max_bytes: u64,
) -> Result<(Vec<MtlMaterial>, u64)> {
    let mut reader = std::io::BufReader::new(file.take(max_bytes + 1));
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut materials: Vec<MtlMaterial> = Vec::new();
    let mut number = 0usize;
    let bytes = logical_lines(&mut reader, path, max_bytes, |line, physical| {
        number += physical;
        let fail = |message: String| Error::Mesh {
            path: path.to_path_buf(),
            at: format!("line {}", number + 1 - physical),
            message,
        };
        let (word, rest) = keyword(line);
        match word {
            "newmtl" if rest.is_empty() => Err(fail("'newmtl' names no material".into())),
            "newmtl" => {
                materials.push(MtlMaterial {
                    name: rest.to_owned(),
                    diffuse: None,
                    texture: None,
                });
                Ok(())
            }
            "Kd" => {
                let kd = parse_color(rest).map_err(|m| fail(format!("Kd: {m}")))?;
                if let (Some(m), Some(kd)) = (materials.last_mut(), kd) {
                    m.diffuse = Some(kd);
                }
                Ok(())
            }
            "map_Kd" => {
                let file = texture_file(rest).map_err(|m| fail(format!("map_Kd: {m}")))?;
                if let Some(m) = materials.last_mut() {
                    m.texture = Some(dir.join(file));
                }
                Ok(())
            }
            // What texplore does not use is not checked.
            _ => Ok(()),
        }
    })?;
    Ok((materials, bytes))
}

/// An MTL colour: `r [g b]` (one number is grey), `xyz x [y z]` (taken as RGB), or `spectral
/// file [factor]` (not supported: `None`).
fn parse_color(rest: &str) -> std::result::Result<Option<[f32; 3]>, String> {
    let mut words: Vec<&str> = rest.split_whitespace().collect();
    match words.first() {
        Some(&"spectral") => return Ok(None),
        Some(&"xyz") => {
            words.remove(0);
        }
        _ => {}
    }
    let numbers = words
        .iter()
        .map(|w| {
            w.parse::<f32>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("'{w}' is not a number"))
        })
        .collect::<std::result::Result<Vec<f32>, String>>()?;
    match numbers[..] {
        [g] => Ok(Some([g; 3])),
        [r, g, b] => Ok(Some([r, g, b])),
        _ => Err(format!(
            "expected 1 or 3 numbers (r [g b]), found {}",
            numbers.len()
        )),
    }
}

/// The file name of a `map_Kd` value, past its options (`-s 2 2 1`, `-bm 1`, `-clamp on`, ...);
/// the rest of the line is the name, spaces included.
fn texture_file(value: &str) -> std::result::Result<&str, String> {
    let mut rest = value.trim();
    while rest.starts_with('-') {
        let (option, after) = keyword(rest);
        // (arguments required, at most, numeric)
        let (min, max, numeric) = match option {
            "-o" | "-s" | "-t" => (1, 3, true),
            "-mm" => (2, 2, true),
            "-bm" | "-boost" | "-texres" => (1, 1, true),
            "-blendu" | "-blendv" | "-cc" | "-clamp" | "-imfchan" | "-type" => (1, 1, false),
            _ => return Err(format!("unknown option '{option}'")),
        };
        rest = after;
        for k in 0..max {
            let (word, after) = keyword(rest);
            let ok =
                !word.is_empty() && (!numeric || word.parse::<f32>().is_ok_and(f32::is_finite));
            if !ok {
                if k < min {
                    return Err(format!(
                        "option '{option}' needs {min} {}",
                        if numeric { "numbers" } else { "values" }
                    ));
                }
                break;
            }
            rest = after;
        }
    }
    if rest.is_empty() {
        return Err("no file name".into());
    }
    Ok(rest)
}
