//! Meshes in presets: the material a mesh file names, and the check that `Uv` is only asked of
//! meshes that carry (u, v).

use super::super::material::MaterialDesc;
use super::super::texture::TextureDesc;
use crate::field::{FieldPath, Refusal};
use crate::geometry::Mesh;
use std::borrow::Cow;

/// The material with a [`TextureDesc::MeshMaterial`] replaced by what the mesh file names: its
/// `map_Kd` image, else its `Kd` colour.
///
/// # Errors
/// The refusal of the material's colour texture (`cd`; the caller puts the object and
/// `material` in front) when the mesh names no material.
pub(super) fn resolve_mesh_material<'a>(
    m: &'a MaterialDesc,
    mesh: Option<&Mesh>,
) -> Result<Cow<'a, MaterialDesc>, Refusal> {
    let refused = |message: String| Refusal::new(m.kind().colour_name().into(), message);
    let TextureDesc::MeshMaterial {
        mapping,
        filter,
        lookup,
        wrap,
        max_anisotropy,
        uv,
    } = m.texture()
    else {
        return Ok(Cow::Borrowed(m));
    };
    let Some(mesh) = mesh else {
        return Err(refused(
            "MeshMaterial: only a Mesh shape names a material".into(),
        ));
    };
    let file = mesh.path().display();
    let material = mesh.material().ok_or_else(|| {
        refused(match mesh.material_problem() {
            Some(p) => format!("MeshMaterial: {file}: {p}"),
            None => {
                format!("MeshMaterial: {file} names no material (no .mtl with Kd or map_Kd)")
            }
        })
    })?;
    let texture = match (&material.diffuse_texture, material.diffuse) {
        (Some(image), _) => TextureDesc::Image {
            // Absolute: the preset's folder must not be prefixed again.
            path: std::path::absolute(image)
                .unwrap_or_else(|_| image.clone())
                .to_string_lossy()
                .into_owned(),
            mapping: mapping.clone(),
            filter: *filter,
            lookup: *lookup,
            wrap: *wrap,
            scale: 1.0,
            srgb: true,
            max_anisotropy: *max_anisotropy,
            uv: *uv,
        },
        (None, Some(kd)) => TextureDesc::Constant(crate::math::Rgb::from_array(kd)),
        (None, None) => {
            return Err(refused(format!(
                "MeshMaterial: material '{}' of {file} has neither map_Kd nor Kd",
                material.name
            )));
        }
    };
    let mut m = m.clone();
    *m.texture_mut() = texture;
    Ok(Cow::Owned(m))
}

/// Refuses the `Uv` mapping, or formulas reading mesh_u and mesh_v, on a mesh without texture
/// coordinates, saying what to do instead.
pub(super) fn check_uv_mapping(m: &MaterialDesc, mesh: &Mesh) -> Result<(), Refusal> {
    if mesh.has_uv() {
        return Ok(());
    }
    match m
        .textures()
        .into_iter()
        .find_map(|(name, t)| Some((name, t.mapping()?.reads_shape_uv()?)))
    {
        Some((name, what)) => Err(no_uv(name.into(), mesh, what)),
        None => Ok(()),
    }
}

/// `field`'s mapping (`what`: the Uv mapping, or formulas) reads the (u, v) `mesh` does not
/// have.
pub(super) fn no_uv(field: FieldPath, mesh: &Mesh, what: &str) -> Refusal {
    Refusal::new(
        field,
        format!(
            "{} has no texture coordinates for {what} to read; choose a generated mapping \
             (spherical, cylindrical, rectangular)",
            mesh.path().display()
        ),
    )
}
