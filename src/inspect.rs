//! What the renderer did at one pixel (the window's inspector). The window's A/B split uses
//! the report's antialiasing [`Mode`](crate::report::Mode) and RMSE
//! ([`crate::report::metrics::rmse`]).
//!
//! Everything here is computed by the library; the GUI only displays it.

use crate::geometry::Shape;
use crate::mapping::{Mapping, TexCoord, explain_mapping};
use crate::math::{Rgb, Vec2, Vec3A};
use crate::names::Named as _;
use crate::texture::{Filter, ImageData, Lookup, Texture, Wrap, explain_lookup};
use crate::{material::ParamValue, scene::Scene};
use std::sync::Arc;
use strum::VariantArray;

/// The texel one lookup picks for the inspected (u, v).
#[derive(Clone, Debug, PartialEq)]
pub struct TexelPick {
    /// Which lookup.
    pub lookup: Lookup,
    /// Column, from the left.
    pub column: u32,
    /// Row counted from the bottom (as v is).
    pub row_from_bottom: u32,
    /// Row counted from the top of the file.
    pub file_row: u32,
    /// The formula lines with the numbers substituted.
    pub lines: Vec<String>,
}

/// The pixel's footprint in texture space: the ellipse spanned by d(u,v)/dx and d(u,v)/dy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    /// Change of (u, v) to the pixel on the right.
    pub duvdx: Vec2,
    /// Change of (u, v) to the pixel below.
    pub duvdy: Vec2,
    /// The two axes' lengths in texels (longest first), when an image is read.
    pub axes_texels: Option<(f32, f32)>,
    /// The mip level an isotropic (trilinear) filter reads: log2 of the longest axis in texels,
    /// at least 0.
    pub mip_level: Option<f32>,
}

/// The image a texture reads, with how it is read.
#[derive(Clone, Debug)]
pub struct ImageRead {
    /// The texels.
    pub image: Arc<ImageData>,
    /// The filter in use.
    pub filter: Filter,
    /// The lookup the nearest filter uses.
    pub lookup: Lookup,
    /// The wrap modes actually applied along u and v.
    pub wraps: (Wrap, Wrap),
}

/// Everything the renderer did at one film position.
#[derive(Clone, Debug)]
pub struct Inspection {
    /// Film position inspected (pixels, (0, 0) the top-left corner).
    pub pixel: Vec2,
    /// Index of the object hit.
    pub object: usize,
    /// Its name.
    pub object_name: String,
    /// Its shape, in words ("Sphere", "mesh bunny.ply, triangle 812").
    pub shape: String,
    /// World-space hit point.
    pub world_point: Vec3A,
    /// Object-space hit point: the lecture's `local_hit_point`.
    pub local_point: Vec3A,
    /// The kind of texture ("constant", "image", "checker").
    pub texture_kind: &'static str,
    /// The mapping in effect (after `uv` falls back to the shape's natural one); `None` for a
    /// constant colour.
    pub mapping: Option<Mapping>,
    /// The mapping's formula with this hit's numbers.
    pub mapping_lines: Vec<String>,
    /// Texture coordinates and their screen-space derivatives.
    pub tex: Option<TexCoord>,
    /// (u, v) after the wrap modes, as the lookup uses them (`None` outside under `black`).
    pub wrapped_uv: Option<Vec2>,
    /// The image read, if any.
    pub image: Option<ImageRead>,
    /// The texel each lookup picks (both, to compare the lecture's with the centred one).
    pub texels: Vec<TexelPick>,
    /// The pixel's footprint in texture space.
    pub footprint: Option<Footprint>,
    /// The texture's colour here (linear, before lighting).
    pub texture_colour: Rgb,
    /// Every other material parameter that is a texture (`ks`, `cs`, ...), by preset name,
    /// with its value here; constants are not listed.
    pub parameters: Vec<(&'static str, ParamValue)>,
    /// The radiance of the ray through the film position (linear, before exposure).
    pub radiance: Rgb,
}

impl Scene {
    /// What the renderer does for the ray through film position `pixel` (pixels, (0, 0) the
    /// top-left corner; add 0.5 for a pixel's centre), or `None` where it hits nothing.
    #[must_use]
    pub fn inspect(&self, pixel: Vec2) -> Option<Inspection> {
        let (ray, diff) = self.camera.ray(pixel, 1.0)?;
        let hit = self.hit(&ray)?;
        let obj = &self.objects[hit.object];
        // Differentials always, even when no filter needs them: the footprint is worth showing.
        let d = if obj.identity {
            diff
        } else {
            diff.transformed(&obj.object_from_world)
        };
        let (dpdx, dpdy) = d.footprint_on_plane(hit.local.p, hit.local.n);
        let ctx = self.texture_context_at(&hit, dpdx, dpdy);
        let material = &self.materials[obj.material];
        let texture = material.texture();
        let (kind, mapping, image) = match texture {
            Texture::Constant(_) => ("constant", None, None),
            Texture::Checker(c) => ("checker", Some(c.mapping), None),
            Texture::Image(t) => (
                "image",
                Some(t.mapping),
                Some(ImageRead {
                    image: t.image.clone(),
                    filter: t.filter,
                    lookup: t.lookup,
                    wraps: t.wraps(),
                }),
            ),
        };
        // `uv` without coordinates of the shape's own means its natural mapping.
        let effective = mapping.map(|m| match (m, ctx.shape_uv) {
            (Mapping::Uv, None) => ctx.natural,
            (m, _) => m,
        });
        let tex = texture.tex_coord(&ctx);
        let mapping_lines = match (effective, mapping) {
            (Some(Mapping::Uv), _) => vec!["(u, v) carried by the shape's vertices".to_owned()],
            (Some(e), Some(m)) => {
                let mut lines = explain_mapping(e, hit.local.p);
                if m != e {
                    lines.insert(
                        0,
                        format!(
                            "uv: this shape carries no (u, v), so its natural {} map is used",
                            e.name()
                        ),
                    );
                }
                lines
            }
            _ => Vec::new(),
        };
        let wraps = image
            .as_ref()
            .map_or((Wrap::Repeat, Wrap::Repeat), |i| i.wraps);
        let wrapped_uv =
            tex.and_then(|t| Some(Vec2::new(wraps.0.coord(t.uv.x)?, wraps.1.coord(t.uv.y)?)));
        let texels = match (&image, wrapped_uv) {
            (Some(read), Some(uv)) => {
                let (w, h) = (read.image.width(), read.image.height());
                Lookup::VARIANTS
                    .iter()
                    .map(|&lookup| {
                        let column = lookup.index(uv.x, w);
                        let row_from_bottom = lookup.index(uv.y, h);
                        TexelPick {
                            lookup,
                            column,
                            row_from_bottom,
                            file_row: h - 1 - row_from_bottom,
                            lines: explain_lookup(uv.x, uv.y, w, h, lookup),
                        }
                    })
                    .collect()
            }
            _ => Vec::new(),
        };
        let footprint = tex.map(|t| {
            let size = image
                .as_ref()
                .map(|i| Vec2::new(i.image.width() as f32, i.image.height() as f32));
            let axes_texels = size.map(|s| {
                let (a, b) = ((t.duvdx * s).length(), (t.duvdy * s).length());
                (a.max(b), a.min(b))
            });
            Footprint {
                duvdx: t.duvdx,
                duvdy: t.duvdy,
                axes_texels,
                mip_level: axes_texels.map(|(a, _)| a.max(1.0).log2()),
            }
        });
        let texture_colour = texture.eval(&ctx);
        let parameters = material.textured_values(&ctx);
        let radiance = self.trace(&ray, self.needs_differentials.then_some(&diff));
        Some(Inspection {
            pixel,
            object: hit.object,
            object_name: obj.name.clone(),
            shape: shape_label(&obj.shape, hit.local.part),
            world_point: hit.p,
            local_point: hit.local.p,
            texture_kind: kind,
            mapping: effective,
            mapping_lines,
            tex,
            wrapped_uv,
            image,
            texels,
            footprint,
            texture_colour,
            parameters,
            radiance,
        })
    }
}

/// A shape in words, with the triangle hit for meshes.
fn shape_label(shape: &Shape, part: u32) -> String {
    match shape {
        Shape::Sphere => "Sphere".into(),
        Shape::Cylinder { .. } => "Cylinder".into(),
        Shape::Plane => "Plane".into(),
        Shape::Rectangle => "Rectangle".into(),
        Shape::Disk => "Disk".into(),
        Shape::Mesh(m) => format!(
            "mesh {}, triangle {part} of {}",
            m.mesh
                .path()
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
            m.mesh.triangle_count()
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{AssetCache, SceneDesc, build_scene, load_preset};
    use std::path::Path;

    fn earth() -> (SceneDesc, std::path::PathBuf) {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/earth.ron");
        let mut desc = load_preset(&path).expect("earth preset");
        desc.render.width = 64;
        desc.render.height = 48;
        (desc, path)
    }

    #[test]
    fn inspecting_the_earth_centre_gives_the_spherical_map_and_both_texels() {
        let (desc, path) = earth();
        let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
        let i = scene
            .inspect(Vec2::new(32.0, 24.0))
            .expect("the Earth fills the centre");
        assert_eq!(i.mapping, Some(Mapping::Spherical));
        assert!((i.local_point.length() - 1.0).abs() < 1e-4);
        let tex = i.tex.expect("coordinates");
        let expect = Mapping::Spherical.map_point(i.local_point).uv;
        assert!((tex.uv - expect).length() < 1e-6);
        assert!(
            i.mapping_lines
                .iter()
                .any(|l| l.starts_with("theta = acos(y)"))
        );
        assert_eq!(i.texels.len(), 2);
        let read = i.image.as_ref().expect("image");
        let (w, h) = (read.image.width(), read.image.height());
        let centred = &i.texels[1];
        assert_eq!(centred.lookup, Lookup::Centred);
        assert_eq!(centred.column, ((tex.uv.x * w as f32) as u32).min(w - 1));
        assert_eq!(centred.file_row, h - 1 - centred.row_from_bottom);
        // 2048 texels around the Earth over ~40 pixels: tens of texels per pixel.
        let fp = i.footprint.expect("footprint");
        let (major, minor) = fp.axes_texels.expect("axes");
        assert!(major >= minor && minor > 1.0, "{major} {minor}");
        assert!(fp.mip_level.expect("mip") > 1.0);
        assert!(i.radiance.is_finite());
    }

    #[test]
    fn missing_the_scene_inspects_nothing() {
        let (desc, path) = earth();
        let scene = build_scene(&desc, &path, &mut AssetCache::new()).expect("build");
        assert!(scene.inspect(Vec2::new(0.5, 0.5)).is_none());
    }
}
