//! `texplore mesh-info`: what a mesh file holds, before loading it into a scene.

use crate::geometry::Mesh;
use crate::meshio::load_mesh;
use anyhow::Result;
use std::path::PathBuf;
use std::time::Instant;

/// `texplore mesh-info`.
#[derive(Debug, clap::Args)]
pub struct MeshInfoArgs {
    /// A .ply or .obj file.
    pub file: PathBuf,
    /// Print JSON (keys `vertices`, `triangles`, `has_uv`, `has_normals`, `bbox_min`,
    /// `bbox_max`, `degenerate`, ...).
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: &MeshInfoArgs) -> Result<()> {
    let t0 = Instant::now();
    let data = load_mesh(&a.file)?;
    let read = t0.elapsed();
    let faces = data.faces;
    let t0 = Instant::now();
    let mesh = Mesh::new(data, &a.file)?;
    let build = t0.elapsed();
    let b = mesh.bbox();
    let d = mesh.degenerate();
    let material = mesh.material();
    if a.json {
        let v = serde_json::json!({
            "file": a.file.display().to_string(),
            "format": mesh.format(),
            "vertices": mesh.vertex_count(),
            "faces": faces,
            "triangles": mesh.triangle_count(),
            "has_uv": mesh.has_uv(),
            "uv_names": mesh.uv_names().map(|(u, v)| [u, v]),
            "has_normals": mesh.has_file_normals(),
            "bbox_min": b.min.to_array(),
            "bbox_max": b.max.to_array(),
            "degenerate": d,
            "material": material.map(|m| m.name.clone()),
            "material_texture": material
                .and_then(|m| m.diffuse_texture.as_ref())
                .map(|p| p.display().to_string()),
            "material_problem": mesh.material_problem(),
            "bvh_nodes": mesh.bvh_nodes(),
            "bytes_per_triangle": mesh.bytes_per_triangle(),
            "read_ms": read.as_secs_f64() * 1e3,
            "bvh_build_ms": build.as_secs_f64() * 1e3,
        });
        println!("{}", serde_json::to_string_pretty(&v)?);
        return Ok(());
    }
    println!("{} ({})", a.file.display(), mesh.format());
    println!(
        "  vertices   {}\n  faces      {faces}\n  triangles  {}",
        mesh.vertex_count(),
        mesh.triangle_count()
    );
    match mesh.uv_names() {
        Some((u, v)) if mesh.has_uv() => println!("  uv         yes (from '{u}' '{v}')"),
        _ => println!(
            "  uv         no: choose a generated mapping (spherical, cylindrical, rectangular)"
        ),
    }
    println!(
        "  normals    {}",
        if mesh.has_file_normals() {
            "from the file"
        } else {
            "none (smooth shading uses area-weighted ones)"
        }
    );
    println!(
        "  bbox       ({}, {}, {}) to ({}, {}, {})",
        b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z
    );
    println!(
        "  degenerate {} zero-area, {} zero-uv-area triangles",
        d.zero_area, d.zero_uv_area
    );
    if let Some(m) = material {
        println!(
            "  material   '{}'{}",
            m.name,
            m.diffuse_texture
                .as_ref()
                .map(|p| format!(", map_Kd {}", p.display()))
                .unwrap_or_default()
        );
    }
    if let Some(p) = mesh.material_problem() {
        println!("  material   {p}");
    }
    println!(
        "  memory     {:.1} bytes per triangle (mesh + BVH of {} nodes)",
        mesh.bytes_per_triangle(),
        mesh.bvh_nodes()
    );
    println!(
        "  time       read {:.1} ms, BVH {:.1} ms",
        read.as_secs_f64() * 1e3,
        build.as_secs_f64() * 1e3
    );
    Ok(())
}
