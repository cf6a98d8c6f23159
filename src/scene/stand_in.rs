//! What a scene shows for a shipped file the page has not downloaded yet (wasm32: the page
//! fetches the lessons' images and meshes when a scene needs them, `input::want`): a grey
//! image, and a grey octahedron in the mesh's place. A build that stood a file in is followed by
//! one with the file once it is in (`gui::document`), and a lesson's check stands the files in
//! unread ([`AssetCache::checking`](super::AssetCache::checking)). Outside a page no file is
//! ever deferred, so nothing here is used.

use crate::error::Result;
use crate::geometry::{Mesh, MeshData, MeshMaterial};
use crate::math::{Rgb, Vec2, Vec3};
use crate::texture::ImageData;
use std::path::Path;

/// The grey a stand-in shows (linear; a normal map reads it as no tilt at all).
const GREY: f32 = 0.5;
/// The stand-in mesh's radius in the mesh's own units (the shipped meshes are a few units
/// across).
const RADIUS: f32 = 0.5;

/// The stand-in for the image at `path`: one grey texel.
#[must_use]
pub fn image(path: &Path) -> ImageData {
    let name = format!("{} (not downloaded yet)", path.display());
    ImageData::from_fn(1, 1, &name, |_, _| Rgb(GREY, GREY, GREY))
}

/// The stand-in for the mesh at `path`: an octahedron of [`RADIUS`] around the mesh's origin,
/// with (u, v) (longitude and latitude, as the sphere's) and a grey material of its own (a
/// `MeshMaterial` colour reads it).
///
/// # Errors
/// None in practice: the octahedron is a valid mesh.
pub fn mesh(path: &Path) -> Result<Mesh> {
    // Four corners around the equator, then the poles; each face's equator corners in turn.
    let corners = [
        Vec3::new(RADIUS, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -RADIUS),
        Vec3::new(-RADIUS, 0.0, 0.0),
        Vec3::new(0.0, 0.0, RADIUS),
        Vec3::new(0.0, RADIUS, 0.0),
        Vec3::new(0.0, -RADIUS, 0.0),
    ];
    let uvs = [
        Vec2::new(0.0, 0.5),
        Vec2::new(0.25, 0.5),
        Vec2::new(0.5, 0.5),
        Vec2::new(0.75, 0.5),
        Vec2::new(0.5, 1.0),
        Vec2::new(0.5, 0.0),
    ];
    let mut triangles = Vec::new();
    for i in 0..4u32 {
        let j = (i + 1) % 4;
        triangles.push([i, j, 4]);
        triangles.push([j, i, 5]);
    }
    let data = MeshData {
        positions: corners.to_vec(),
        uvs: uvs.to_vec(),
        normals: Vec::new(),
        faces: triangles.len(),
        triangles,
        format: "a stand-in (the file is not downloaded yet)".into(),
        uv_names: Some(("u".into(), "v".into())),
        material: Some(MeshMaterial {
            name: "stand-in".into(),
            diffuse: Some([GREY; 3]),
            diffuse_texture: None,
        }),
        material_problem: None,
    };
    Mesh::new(data, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stand_ins_are_grey_and_the_mesh_is_closed_and_mapped() {
        let img = image(Path::new("assets/x.jpg"));
        assert_eq!((img.width(), img.height()), (1, 1));
        assert!(img.name.contains("not downloaded yet"));
        let m = mesh(Path::new("assets/x.ply")).expect("an octahedron is a mesh");
        assert_eq!(m.triangle_count(), 8);
        assert!(m.has_uv());
        assert_eq!(m.material().and_then(|m| m.diffuse), Some([GREY; 3]));
    }
}
