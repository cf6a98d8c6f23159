//! Displacement maps at load: the object's mesh subdivided and displaced through the
//! [`AssetCache`], which keeps the latest displaced copies.

use super::super::assets::{AssetCache, DisplacedKey};
use super::super::texture::{param_texture, texture_words};
use super::super::trace::natural_mapping;
use super::maps::DisplaceDesc;
use crate::error::{Error, Result};
use crate::field::Refusal;
use crate::geometry::displace::{
    Displacement, MAX_DISPLACED_TRIANGLES, displace, subdivide, subdivided_triangle_count,
};
use crate::geometry::{Mesh, MeshShape, Shape};
use crate::math::Vec3A;
use crate::texture::{Texture, TextureContext};
use std::path::Path;
use std::sync::Arc;

/// `base` (read from `file`) subdivided and displaced as `d` says, through the cache (each
/// displacement of a file is made once; the file's own mesh stays shared and untouched).
/// Errors name their fields relative to `displace` (`subdivide`, `height.scale`); the caller
/// puts the object and `displace` in front.
pub(super) fn displaced_mesh(
    base: &Arc<Mesh>,
    file: &Path,
    d: &DisplaceDesc,
    dir: &Path,
    cache: &mut AssetCache,
) -> Result<Arc<Mesh>> {
    let invalid = |field: &str, m: String| Error::refused(dir, Refusal::new(field.into(), m));
    if !(d.scale.is_finite() && d.scale.abs() <= 1e6) {
        return Err(invalid(
            "scale",
            format!("{} is out of range (-1e6 to 1e6 mesh units)", d.scale),
        ));
    }
    let limit = MAX_DISPLACED_TRIANGLES;
    let triangles = subdivided_triangle_count(base.triangle_count(), d.subdivide);
    if triangles > limit {
        return Err(invalid(
            "subdivide",
            format!(
                "{} levels would make {} triangles of the {} in {} (each level makes \
             4 of every triangle); at most {limit} (4 M) are allowed: use fewer levels",
                d.subdivide,
                if triangles == usize::MAX {
                    "more than 2^64".to_owned()
                } else {
                    triangles.to_string()
                },
                base.triangle_count(),
                file.display()
            ),
        ));
    }
    let key: DisplacedKey = (file.to_path_buf(), dir.to_path_buf(), format!("{d:?}"));
    cache.count_displaced(&key, triangles).map_err(|m| {
        invalid(
            "subdivide",
            format!(
                "{} levels of the {} triangles in {} make {m}",
                d.subdivide,
                base.triangle_count(),
                file.display()
            ),
        )
    })?;
    if let Some(m) = cache.displaced(&key) {
        return Ok(m);
    }
    if !base.has_uv()
        && let Some(what) = d
            .height
            .mapping()
            .and_then(crate::scene::MappingDesc::reads_shape_uv)
    {
        return Err(Error::refused(
            dir,
            super::mesh::no_uv("height".into(), base, what),
        ));
    }
    let height = param_texture(&"height".into(), &d.height, dir, cache)?;
    let moves_nothing = match &height {
        Texture::Constant(c) => c.luminance() * d.scale == 0.0,
        _ => d.scale == 0.0,
    };
    if moves_nothing || cache.is_checking() {
        // A displacement that moves nothing is none: the file's mesh as it is, shared. A
        // checking cache checks the displacement without making it.
        return Ok(base.clone());
    }
    let (mut data, _) = subdivide(&base.to_data(), d.subdivide);
    let natural = natural_mapping(&Shape::Mesh(MeshShape {
        mesh: base.clone(),
        shading: crate::geometry::Shading::Smooth,
    }));
    let heights: Vec<Option<f32>> = {
        use rayon::prelude::*;
        let uvs = &data.uvs;
        data.positions
            .par_iter()
            .enumerate()
            .map(|(v, p)| {
                let (p, _) = base.to_mapping_frame((*p).into());
                let ctx = TextureContext {
                    p,
                    dpdx: Vec3A::ZERO,
                    dpdy: Vec3A::ZERO,
                    shape_uv: uvs.get(v).map(|uv| (*uv, None)),
                    natural,
                };
                Some(height.eval(&ctx).luminance()).filter(|h| h.is_finite())
            })
            .collect()
    };
    // Where a formula was NaN or infinite the texture gives magenta (counted by the texture),
    // as it does everywhere; a height still not finite moves nothing. Both are counted.
    let non_finite = heights.iter().filter(|h| h.is_none()).count()
        + usize::try_from(height.non_finite_count()).unwrap_or(usize::MAX);
    let heights: Vec<f32> = heights.into_iter().map(|h| h.unwrap_or(0.0)).collect();
    displace(&mut data, &heights, d.scale);
    if data.positions.iter().any(|p| !p.is_finite()) {
        let highest = heights.iter().fold(0.0f32, |m, h| m.max(h.abs()));
        return Err(invalid(
            "scale",
            format!(
                "{} times the height texture's values (up to {highest:e}) moves the surface \
             beyond the largest finite coordinate; use a smaller scale or height",
                d.scale
            ),
        ));
    }
    let what = Displacement {
        height: texture_words(&d.height),
        scale: d.scale,
        levels: d.subdivide,
        file_triangles: base.triangle_count(),
        triangles: data.triangles.len(),
        non_finite,
    };
    let mesh = Arc::new(Mesh::new(data, file)?.displaced_from(base, what));
    cache.keep_displaced(key, mesh.clone());
    Ok(mesh)
}
