//! Mesh files: a streaming PLY reader and writer of our own, OBJ through `tobj`, and procedural
//! models with real (u, v) and seams (for tests, benchmarks and the shipped assets).
//!
//! Every reader returns a [`MeshData`] (indexed triangles, optional per-vertex (u, v) and
//! normals); [`crate::geometry::Mesh::new`] turns it into a traceable mesh with its BVH.

mod generate;
mod mtl;
mod obj;
mod ply;

pub use generate::{bumpy_sphere, torus};
pub use mtl::{MAX_MESH_LIBRARIES, MAX_MESH_MTL_BYTES, MAX_MTL_BYTES};
pub use obj::{material_files, read_obj};
pub use ply::{MAX_HEADER_BYTES, PlyFormat, UV_NAMES, read_ply, read_ply_from, write_ply};

use crate::error::{Error, Result};
use crate::geometry::MeshData;
use std::path::Path;

/// Most vertices read from a file (2^25, about 1.6 GB of mesh and BVH at the largest).
pub const MAX_VERTICES: usize = 1 << 25;
/// Most triangles read from a file (after triangulation).
pub const MAX_TRIANGLES: usize = 1 << 25;
const _: () = assert!(MAX_TRIANGLES < crate::geometry::bvh::MAX_PRIMITIVES);
/// Most corners of one polygon (and items of any PLY list).
pub const MAX_POLYGON_CORNERS: usize = 1 << 12;
/// Largest OBJ file read (`tobj` reads the whole file into memory).
pub const MAX_MESH_FILE_BYTES: u64 = 2 << 30;

/// Reads a `.ply` or `.obj` file (by extension; a file starting with `ply` is read as PLY).
///
/// # Errors
/// An unknown format, or what the reader reports.
pub fn load_mesh(path: &Path) -> Result<MeshData> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("ply") => read_ply(path),
        Some("obj") => read_obj(path),
        _ => {
            let mut head = [0u8; 4];
            let mut file = crate::input::open_input(path)?;
            let n = std::io::Read::read(&mut file, &mut head).map_err(|e| Error::io(path, e))?;
            if n >= 3 && &head[..3] == b"ply" {
                read_ply(path)
            } else {
                Err(Error::Mesh {
                    path: path.to_path_buf(),
                    at: "file".into(),
                    message: "unknown mesh format (texplore reads .ply and .obj)".into(),
                })
            }
        }
    }
}
