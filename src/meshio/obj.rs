//! Wavefront OBJ through `tobj` (polygons triangulated, one index per vertex), with the first
//! material that names a diffuse image (`map_Kd`); the libraries through [`super::mtl`].

use super::mtl::{Libraries, MtlMaterial};
use super::{MAX_MESH_FILE_BYTES, MAX_TRIANGLES, MAX_VERTICES};
use crate::error::{Error, Result};
use crate::geometry::{MeshData, MeshMaterial};
use crate::math::{Vec2, Vec3};
use std::cell::RefCell;
use std::collections::HashSet;
use std::fmt::Write as _;
use std::io::{BufRead, Read};
use std::path::{Path, PathBuf};

/// Counts the lines consumed, so a `tobj` error can say where it stopped.
struct LineCounter<R> {
    inner: R,
    lines: usize,
}

impl<R: Read> Read for LineCounter<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.lines += buf[..n].iter().filter(|b| **b == b'\n').count();
        Ok(n)
    }
}

impl<R: BufRead> BufRead for LineCounter<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amt: usize) {
        if let Ok(buf) = self.inner.fill_buf() {
            let amt = amt.min(buf.len());
            self.lines += buf[..amt].iter().filter(|b| **b == b'\n').count();
        }
        self.inner.consume(amt);
    }
}

/// The OBJ text as `tobj` is given it, and the material libraries each `mtllib` line names.
struct Prepared {
    /// One output line per input line (a continued line's followers left blank), so line
    /// numbers stay those of the file; `mtllib` lines replaced by `mtllib K`, K indexing
    /// `libraries`; keywords separated from their argument by one space.
    text: String,
    /// The files of each `mtllib` line that names one not named before.
    libraries: Vec<Vec<PathBuf>>,
    /// Polylines (`l`) and points (`p`) left out.
    lines: usize,
    points: usize,
}

/// Reads the lines of `r` (at most `max_bytes`), joining backslash continuations; calls `f`
/// with each logical line and the count of physical lines it took. The bytes read.
pub(super) fn logical_lines(
    r: &mut impl BufRead,
    path: &Path,
    max_bytes: u64,
    mut f: impl FnMut(&str, usize) -> Result<()>,
) -> Result<u64> {
    let mut raw = Vec::new();
    let mut joined = String::new();
    let mut physical = 0usize;
    let mut total = 0u64;
    loop {
        raw.clear();
        let n = r
            .read_until(b'\n', &mut raw)
            .map_err(|e| Error::io(path, e))?;
        if n == 0 {
            break;
        }
        total += n as u64;
        if total > max_bytes {
            return Err(Error::invalid(
                path,
                format!(
                    "too large (larger than {})",
                    crate::input::human_bytes(max_bytes)
                ),
            ));
        }
        physical += 1;
        let text = String::from_utf8_lossy(&raw);
        let line = text.trim_end_matches(['\n', '\r']);
        let line = if physical == 1 && joined.is_empty() {
            line.strip_prefix('\u{feff}').unwrap_or(line)
        } else {
            line
        };
        if let Some(head) = line.trim_end().strip_suffix('\\') {
            joined.push_str(head);
            joined.push(' ');
            continue;
        }
        joined.push_str(line);
        f(&joined, physical)?;
        joined.clear();
        physical = 0;
    }
    if physical > 0 {
        f(&joined, physical)?;
    }
    Ok(total)
}

/// The first word of `line` and the rest, trimmed.
pub(super) fn keyword(line: &str) -> (&str, &str) {
    let line = line.trim_start();
    match line.find(char::is_whitespace) {
        Some(i) => (&line[..i], line[i..].trim()),
        None => (line, ""),
    }
}

/// The material name an empty `usemtl` becomes: no library defines it (names are kept from the
/// map [`read_obj`] hands `tobj`), so the faces after it have no material, as `usemtl` alone
/// means in the files that write it.
const NO_MATERIAL: &str = "\u{0}texplore: no material";

/// Reads the OBJ (at most [`MAX_MESH_FILE_BYTES`]) into the form `tobj` parses: continuations
/// joined, tabs after `usemtl` and `mtllib` accepted, every library of a `mtllib` line kept
/// (each file once, however many lines name it), polylines (`l`) and points (`p`) dropped (they
/// are not surfaces: `tobj` would read a 3-point line as a triangle), an empty `usemtl` read as
/// no material, and vertex colours (`v x y z r g b`) dropped (texplore does not use them, and
/// `tobj` refuses a file where only some vertices have one).
fn prepare(path: &Path, dir: &Path) -> Result<Prepared> {
    let file = crate::input::open_input(path)?;
    if crate::input::input_len(&file).is_some_and(|len| len > MAX_MESH_FILE_BYTES) {
        return Err(Error::invalid(
            path,
            format!(
                "too large (larger than {}, the most texplore reads as OBJ)",
                crate::input::human_bytes(MAX_MESH_FILE_BYTES)
            ),
        ));
    }
    let mut reader = std::io::BufReader::new(file.take(MAX_MESH_FILE_BYTES + 1));
    // A UTF-16 file reads as text with a NUL between letters, so nothing would parse.
    let head = reader.fill_buf().map_err(|e| Error::io(path, e))?;
    if head.starts_with(&[0xFE, 0xFF]) || head.starts_with(&[0xFF, 0xFE]) {
        return Err(Error::invalid(
            path,
            "the file is UTF-16 text (save it as UTF-8): UTF-16 OBJ is not supported",
        ));
    }
    let mut out = Prepared {
        text: String::new(),
        libraries: Vec::new(),
        lines: 0,
        points: 0,
    };
    // Every library name seen so far: a name repeated (on one line or many) is read once.
    let mut named = HashSet::new();
    logical_lines(&mut reader, path, MAX_MESH_FILE_BYTES, |line, physical| {
        let (word, rest) = keyword(line);
        match word {
            "mtllib" => {
                // A name with spaces if that file exists, else one library per word.
                let whole = dir.join(rest);
                let files: Vec<PathBuf> = if rest.contains(char::is_whitespace) && whole.is_file() {
                    vec![whole]
                } else {
                    rest.split_whitespace().map(|w| dir.join(w)).collect()
                };
                let files: Vec<PathBuf> = files
                    .into_iter()
                    .filter(|f| named.insert(f.clone()))
                    .collect();
                if files.is_empty() {
                    out.text.push('\n');
                } else {
                    let _ = writeln!(out.text, "mtllib {}", out.libraries.len());
                    out.libraries.push(files);
                }
            }
            "usemtl" if rest.is_empty() => {
                let _ = writeln!(out.text, "usemtl {NO_MATERIAL}");
            }
            "usemtl" | "o" | "g" => {
                let _ = writeln!(out.text, "{word} {rest}");
            }
            "l" | "p" => {
                out.text.push('\n');
                *if word == "l" {
                    &mut out.lines
                } else {
                    &mut out.points
                } += 1;
            }
            // `v x y z w` keeps its weight; `v x y z r g b [a]` loses its colour.
            "v" if rest.split_whitespace().count() >= 5 => {
                let xyz: Vec<&str> = rest.split_whitespace().take(3).collect();
                let _ = writeln!(out.text, "v {}", xyz.join(" "));
            }
            // `vt u` is valid OBJ (v defaults to 0); tobj wants two numbers.
            "vt" if rest.split_whitespace().count() == 1 => {
                let _ = writeln!(out.text, "vt {rest} 0");
            }
            _ => {
                out.text.push_str(line);
                out.text.push('\n');
            }
        }
        for _ in 1..physical {
            out.text.push('\n');
        }
        Ok(())
    })?;
    drop_missing_kinds(&mut out.text);
    Ok(out)
}

/// Face corners that name a texture coordinate or a normal in a file that defines none of them
/// (`f 1//5` without any `vn`) lose that index: there is nothing it could mean, and lenient
/// readers (trimesh, Blender) ignore it. A file that defines some but names one past them is
/// still refused by [`check_face_indices`].
fn drop_missing_kinds(text: &mut String) {
    let defines = |kind: &str| {
        text.lines()
            .any(|l| l.split_whitespace().next() == Some(kind))
    };
    let (has_vt, has_vn) = (defines("vt"), defines("vn"));
    if has_vt && has_vn {
        return;
    }
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let mut words = line.split_whitespace();
        if words.next() != Some("f") {
            out.push_str(line);
            out.push('\n');
            continue;
        }
        out.push('f');
        for corner in words {
            let mut parts: Vec<&str> = corner.split('/').collect();
            if !has_vt && parts.len() > 1 {
                parts[1] = "";
            }
            if !has_vn && parts.len() > 2 {
                parts.truncate(2);
            }
            while parts.len() > 1 && parts.last() == Some(&"") {
                parts.pop();
            }
            out.push(' ');
            out.push_str(&parts.join("/"));
        }
        out.push('\n');
    }
    *text = out;
}

/// Reads an OBJ file and its material libraries.
///
/// # Errors
/// The file is not a regular file, cannot be read or parsed (the message names the line where
/// parsing stopped), or is too large. A material library that cannot be read or parsed is not
/// an error here: the mesh keeps its geometry and [`MeshData::material_problem`] names the
/// library, the line and the problem.
pub fn read_obj(path: &Path) -> Result<MeshData> {
    let fail = |at: String, message: String| Error::Mesh {
        path: path.to_path_buf(),
        at,
        message,
    };
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let prepared = prepare(path, &dir)?;
    check_face_indices(&prepared.text)
        .map_err(|(line, message)| fail(format!("line {line}"), message))?;
    let mut reader = LineCounter {
        inner: prepared.text.as_bytes(),
        lines: 0,
    };
    // Every material of every library, in the order tobj numbers them; each library read once.
    let parsed: RefCell<Vec<MtlMaterial>> = RefCell::new(Vec::new());
    let libraries = RefCell::new(Libraries::new());
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, |line| {
        let files = line
            .to_str()
            .and_then(|k| k.parse::<usize>().ok())
            .and_then(|k| prepared.libraries.get(k))
            .map_or(&[][..], Vec::as_slice);
        let mut mats = Vec::new();
        let mut names = std::collections::HashMap::new();
        for file in files {
            for m in libraries.borrow_mut().read(file) {
                if m.name != NO_MATERIAL {
                    names.insert(m.name.clone(), mats.len());
                }
                mats.push(tobj::Material {
                    name: m.name.clone(),
                    ..tobj::Material::default()
                });
                parsed.borrow_mut().push(m);
            }
        }
        Ok((mats, names.into_iter().collect()))
    })
    .map_err(|e| fail(format!("line {}", reader.lines), e.to_string()))?;

    let mut data = MeshData {
        format: "obj".into(),
        ..MeshData::default()
    };
    let has_uv = models.iter().all(|m| {
        !m.mesh.texcoords.is_empty() && m.mesh.texcoords.len() / 2 == m.mesh.positions.len() / 3
    });
    let has_normals = models
        .iter()
        .all(|m| !m.mesh.normals.is_empty() && m.mesh.normals.len() == m.mesh.positions.len());
    for m in &models {
        let base = data.positions.len();
        let mesh = &m.mesh;
        if base + mesh.positions.len() / 3 > MAX_VERTICES {
            return Err(fail(
                format!("object '{}'", m.name),
                format!("more than {MAX_VERTICES} vertices"),
            ));
        }
        data.positions.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        if has_uv {
            data.uvs.extend(
                mesh.texcoords
                    .chunks_exact(2)
                    .map(|t| Vec2::new(t[0], t[1])),
            );
        }
        if has_normals {
            data.normals.extend(
                mesh.normals
                    .chunks_exact(3)
                    .map(|n| Vec3::new(n[0], n[1], n[2])),
            );
        }
        for t in mesh.indices.chunks_exact(3) {
            data.triangles
                .push([t[0] + base as u32, t[1] + base as u32, t[2] + base as u32]);
        }
        if data.triangles.len() > MAX_TRIANGLES {
            return Err(fail(
                format!("object '{}'", m.name),
                format!("more than {MAX_TRIANGLES} triangles"),
            ));
        }
    }
    if data.triangles.is_empty() && prepared.lines + prepared.points > 0 {
        return Err(fail(
            "faces".into(),
            format!(
                "no triangles: the file has only polylines ({} `l`) and points ({} `p`), \
                 which are not surfaces",
                prepared.lines, prepared.points
            ),
        ));
    }
    data.faces = data.triangles.len();
    if has_uv && !data.positions.is_empty() {
        data.uv_names = Some(("vt".into(), "vt".into()));
    }
    let mats = parsed.into_inner();
    // The first material a model uses that has an image, else the first one used.
    let used = models.iter().filter_map(|m| m.mesh.material_id);
    let chosen = used
        .clone()
        .find(|&i| mats.get(i).is_some_and(|m| m.texture.is_some()))
        .or_else(|| used.clone().next())
        .and_then(|i| mats.get(i));
    if let Some(m) = chosen {
        data.material = Some(MeshMaterial {
            name: m.name.clone(),
            diffuse: m.diffuse,
            diffuse_texture: m.texture.clone(),
        });
    }
    data.material_problem = libraries.into_inner().problem;
    Ok(data)
}

/// The material libraries (`mtllib`) an OBJ file names and the images (`map_Kd`) those
/// libraries name, resolved as [`read_obj`] resolves them: every file besides the OBJ itself
/// that loading it reads, each once. Unreadable files are listed but not followed (an OBJ that
/// cannot be read lists nothing, a library that cannot be parsed lists no images); libraries
/// past the mesh's limits ([`super::MAX_MESH_LIBRARIES`], [`super::MAX_MESH_MTL_BYTES`]) are listed, not read.
#[must_use]
pub fn material_files(path: &Path) -> Vec<PathBuf> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let Ok(prepared) = prepare(path, dir) else {
        return Vec::new();
    };
    let mut libraries = Libraries::new();
    let mut out = Vec::new();
    let mut listed = HashSet::new();
    for library in prepared.libraries.into_iter().flatten() {
        let images: Vec<PathBuf> = libraries
            .read(&library)
            .into_iter()
            .filter_map(|m| m.texture)
            .collect();
        for file in std::iter::once(library).chain(images) {
            if listed.insert(file.clone()) {
                out.push(file);
            }
        }
    }
    out
}

/// Checks every face index of an OBJ against the vertices, texture coordinates and normals the
/// file defines, before `tobj` sees them: `tobj` 4 indexes its arrays with unchecked arithmetic
/// on the file's numbers (a huge `vt` index overflows, which panics in debug builds and reads a
/// wrong texel pair in release). Positive indices may refer to elements defined later in the
/// file (as `tobj` resolves them per object); relative (negative) ones count back from the line.
///
/// # Errors
/// The 1-based line and what is wrong.
fn check_face_indices(text: &str) -> Result<(), (usize, String)> {
    const KINDS: [&str; 3] = ["vertex", "texture coordinate", "normal"];
    let mut counts = [0i64; 3];
    // The largest positive index of each kind, and the line it is on.
    let mut largest = [(0i64, 0usize); 3];
    for (index, line) in text.lines().enumerate() {
        let number = index + 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            Some("f") => {
                for corner in words {
                    for (kind, part) in corner.split('/').enumerate().take(3) {
                        if part.is_empty() {
                            continue;
                        }
                        // Not a number: left to tobj, which refuses it with its own message.
                        let Ok(i) = part.parse::<i64>() else { continue };
                        let bad = |why: &str| {
                            Err((
                                number,
                                format!(
                                    "face index {i}: {why} {} ({} defined so far)",
                                    KINDS[kind], counts[kind]
                                ),
                            ))
                        };
                        if i == 0 {
                            return bad("OBJ indices start at 1; there is no");
                        }
                        if i < 0 && -i > counts[kind] {
                            return bad("counts back past the first");
                        }
                        if i > largest[kind].0 {
                            largest[kind] = (i, number);
                        }
                    }
                }
            }
            _ => {}
        }
    }
    for kind in 0..3 {
        let (i, at) = largest[kind];
        if i > counts[kind] {
            return Err((
                at,
                format!(
                    "face index {i} refers to a {} that does not exist (the file has {})",
                    KINDS[kind], counts[kind]
                ),
            ));
        }
    }
    Ok(())
}
