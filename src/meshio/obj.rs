//! Wavefront OBJ through `tobj` (polygons triangulated, one index per vertex), with the first
//! material that names a diffuse image (`map_Kd`).

use super::{MAX_MESH_FILE_BYTES, MAX_TRIANGLES, MAX_VERTICES};
use crate::error::{Error, Result};
use crate::geometry::{MeshData, MeshMaterial};
use crate::math::{Vec2, Vec3};
use std::cell::RefCell;
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

/// Reads an OBJ file and its material library.
///
/// # Errors
/// The file cannot be read or parsed (the message names the line where `tobj` stopped), or it
/// is too large.
pub fn read_obj(path: &Path) -> Result<MeshData> {
    let fail = |at: String, message: String| Error::Mesh {
        path: path.to_path_buf(),
        at,
        message,
    };
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    if meta.len() > MAX_MESH_FILE_BYTES {
        return Err(fail(
            "file".into(),
            format!(
                "{} bytes is more than texplore reads as OBJ ({MAX_MESH_FILE_BYTES})",
                meta.len()
            ),
        ));
    }
    check_face_indices(path).map_err(|(line, message)| fail(format!("line {line}"), message))?;
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let mut reader = LineCounter {
        inner: std::io::BufReader::new(file),
        lines: 0,
    };
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let mtl_dir: RefCell<Option<PathBuf>> = RefCell::new(None);
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..tobj::LoadOptions::default()
    };
    let (models, materials) = tobj::load_obj_buf(&mut reader, &options, |mtl| {
        let full = dir.join(mtl);
        *mtl_dir.borrow_mut() = full.parent().map(Path::to_path_buf);
        tobj::load_mtl(&full)
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
    data.faces = data.triangles.len();
    if has_uv && !data.positions.is_empty() {
        data.uv_names = Some(("vt".into(), "vt".into()));
    }
    match materials {
        Ok(mats) => {
            // The first material a model uses that has an image, else the first one used.
            let used = models.iter().filter_map(|m| m.mesh.material_id);
            let chosen = used
                .clone()
                .find(|&i| mats.get(i).is_some_and(|m| m.diffuse_texture.is_some()))
                .or_else(|| used.clone().next())
                .and_then(|i| mats.get(i));
            if let Some(m) = chosen {
                let mtl_dir = mtl_dir.borrow().clone().unwrap_or_else(|| dir.clone());
                data.material = Some(MeshMaterial {
                    name: m.name.clone(),
                    diffuse: m.diffuse,
                    diffuse_texture: m
                        .diffuse_texture
                        .as_deref()
                        .map(|t| mtl_dir.join(texture_file(t))),
                });
            }
        }
        Err(e) => {
            if mtl_dir.borrow().is_some() {
                data.material_problem = Some(format!("its material library cannot be read: {e}"));
            }
        }
    }
    Ok(data)
}

/// The file name of a `map_Kd` value, past any `-option value` pairs.
fn texture_file(value: &str) -> &str {
    let v = value.trim();
    if v.starts_with('-') {
        v.rsplit(char::is_whitespace).next().unwrap_or(v)
    } else {
        v
    }
}

/// Checks every face index of an OBJ against the vertices, texture coordinates and normals the
/// file defines, before `tobj` sees them: `tobj` 4 indexes its arrays with unchecked arithmetic
/// on the file's numbers (a huge `vt` index overflows, which panics in debug builds and reads a
/// wrong texel pair in release). Positive indices may refer to elements defined later in the
/// file (as `tobj` resolves them per object); relative (negative) ones count back from the line.
///
/// # Errors
/// The 1-based line and what is wrong.
fn check_face_indices(path: &Path) -> Result<(), (usize, String)> {
    use std::io::BufRead;
    const KINDS: [&str; 3] = ["vertex", "texture coordinate", "normal"];
    let file = std::fs::File::open(path).map_err(|e| (0, e.to_string()))?;
    let mut counts = [0i64; 3];
    // The largest positive index of each kind, and the line it is on.
    let mut largest = [(0i64, 0usize); 3];
    let mut line = Vec::new();
    let mut reader = std::io::BufReader::new(file);
    let mut number = 0usize;
    loop {
        line.clear();
        match reader.read_until(b'\n', &mut line) {
            Ok(0) => break,
            Ok(_) => number += 1,
            Err(e) => return Err((number + 1, e.to_string())),
        }
        let text = String::from_utf8_lossy(&line);
        let mut words = text.split_whitespace();
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
