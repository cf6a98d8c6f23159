//! What the renderer did at one pixel (the window's inspector). The window's A/B split uses
//! the report's antialiasing [`Mode`](crate::report::Mode) and RMSE
//! ([`crate::report::metrics::rmse`]).
//!
//! Everything here is computed by the library; the GUI only displays it.

use crate::geometry::Shape;
use crate::mapping::explain_number;
use crate::mapping::{AnyMapping, Mapping, TexCoord, explain_mapping};
use crate::math::Vec3;
use crate::math::{Rgb, Vec2, Vec3A};
use crate::names::Named as _;
use crate::texture::{Filter, ImageData, Lookup, Texture, View, Wrap, explain_lookup};
use crate::{
    material::{Material, ParamValue},
    scene::Scene,
};
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

/// A mesh hit: the triangle's three vertices, their (u, v) and the barycentric weights that
/// interpolate them.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshPoint {
    /// The triangle's index in the file.
    pub triangle: u32,
    /// Its three vertices, in the file's coordinates.
    pub positions: [Vec3; 3],
    /// Their (u, v), when the mesh carries them.
    pub uvs: Option<[Vec2; 3]>,
    /// The hit's barycentric weights (w0, w1, w2), summing to 1: p = w0 p0 + w1 p1 + w2 p2.
    pub bary: Vec3,
    /// On a displaced mesh first how it was displaced (height texture, scale, subdivision
    /// levels, triangles), then the interpolation with its numbers (none without (u, v)).
    pub lines: Vec<String>,
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
    /// Its shape, in words ("Sphere", "mesh bunny.ply, triangle 812"; "mesh bunny.ply
    /// (displaced), triangle 812" on a displaced copy, whose [`MeshPoint::lines`] say how).
    pub shape: String,
    /// World-space hit point.
    pub world_point: Vec3A,
    /// Object-space hit point: the lecture's `local_hit_point`.
    pub local_point: Vec3A,
    /// The point the mapping reads: the local hit point, fitted into [-1, 1]^3 on a mesh.
    pub mapping_point: Vec3A,
    /// The kind of texture ("constant", "image", "checker").
    pub texture_kind: &'static str,
    /// The built-in mapping in effect (after `uv` falls back to the shape's natural one);
    /// `None` for a constant colour or a formula mapping.
    pub mapping: Option<Mapping>,
    /// The mapping's formula with this hit's numbers (a formula mapping's own formulas with
    /// the numbers substituted, and which derivatives it uses).
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
    /// The shaded radiance of the ray through the film position (linear, before exposure):
    /// the lit, textured colour, whatever debug view is on.
    pub radiance: Rgb,
    /// What the debug view in effect shows at this pixel instead (`None` in the shaded view).
    pub debug_value: Option<(View, Rgb)>,
    /// On a mesh: the triangle hit, its vertices' (u, v) and the barycentric weights.
    pub mesh: Option<MeshPoint>,
    /// The clip-mapped surfaces the ray passed through before it reached this one (alpha 0
    /// there: the ray continued, as the renderer's does), nearest first.
    pub passed: Vec<ClipPass>,
    /// This surface's clip-map alpha, if it has a clip map: below 1 the pixel blends it with
    /// what lies behind it (`alpha L_surface + (1 - alpha) L_behind`).
    pub alpha: Option<f32>,
    /// What this surface's bump or normal map does here, if it has one.
    pub perturbation: Option<PerturbationRead>,
    /// If this surface is a mirror: the ray it reflects and what that ray shows.
    pub mirror: Option<MirrorRead>,
}

/// A bump or normal map at one hit: the value read, the (u, v) frame it is read in, and the
/// shading normal it gives against the geometric one.
#[derive(Clone, Debug, PartialEq)]
pub struct PerturbationRead {
    /// "bump map" or "normal map".
    pub kind: &'static str,
    /// The value read, worked: `height 0.53 x scale 0.02 = 0.0106` (object units) or
    /// `texel (0.52, 0.48, 0.98) -> tangent-space normal (0.03, -0.05, 1.00)`.
    pub value: String,
    /// The surface's dp/du and dp/dv (object space) the map is read in: `None` where the
    /// mapping has no slope (a pole, a triangle without a (u, v) layout).
    pub frame: Option<(Vec3A, Vec3A)>,
    /// The geometric normal (world space, toward the viewer).
    pub geometric: Vec3A,
    /// The shading normal the map gives (world space).
    pub shading: Vec3A,
    /// The angle between them, in degrees.
    pub tilt_degrees: f32,
}

/// A clip-mapped surface a ray went through: where its clip map's alpha is 0 the surface is a
/// hole, and the ray continues behind it.
#[derive(Clone, Debug, PartialEq)]
pub struct ClipPass {
    /// The object's name.
    pub object_name: String,
    /// Where the ray met it (world space).
    pub world_point: Vec3A,
    /// Its clip map's alpha there (0: a hole).
    pub alpha: f32,
}

impl Scene {
    /// The first surface `ray` shows: through the holes of clip maps (alpha 0), as the
    /// renderer goes. Returns the ray that reaches it, the hit, the surfaces passed and the hit's
    /// own clip-map alpha (if it has a clip map).
    fn through_holes(
        &self,
        mut ray: crate::math::Ray,
        diff: &crate::math::RayDifferential,
    ) -> Option<(
        crate::math::Ray,
        crate::scene::SurfaceHit,
        Vec<ClipPass>,
        Option<f32>,
    )> {
        let mut passed = Vec::new();
        loop {
            let hit = self.hit(&ray)?;
            let Some(clip) = self.surfaces[hit.object]
                .clip
                .as_ref()
                .filter(|_| self.has_clips())
            else {
                return Some((ray, hit, passed, None));
            };
            let a = clip
                .eval(&self.texture_context(&hit, Some(diff)))
                .clamp(0.0, 1.0);
            if a > 0.0 || passed.len() + 1 >= crate::scene::MAX_CLIP_LAYERS as usize {
                return Some((ray, hit, passed, Some(a)));
            }
            passed.push(ClipPass {
                object_name: self.objects[hit.object].name.clone(),
                world_point: hit.p,
                alpha: a,
            });
            let origin = hit.p + ray.dir.normalize_or_zero() * self.offset_at(&hit);
            ray = crate::math::Ray::new(origin, ray.dir);
        }
    }

    /// What the renderer does for the ray through film position `pixel` (pixels, (0, 0) the
    /// top-left corner; add 0.5 for a pixel's centre), or `None` where it hits nothing.
    #[must_use]
    pub fn inspect(&self, pixel: Vec2) -> Option<Inspection> {
        let (ray, diff) = self.camera.ray(pixel, 1.0)?;
        self.inspect_ray(pixel, ray, &diff, 0)
    }

    /// What the renderer does along `ray` (with differentials `diff`) for the pixel at `pixel`,
    /// after `depth` mirror bounces.
    pub(super) fn inspect_ray(
        &self,
        pixel: Vec2,
        ray: crate::math::Ray,
        diff: &crate::math::RayDifferential,
        depth: u32,
    ) -> Option<Inspection> {
        let (ray, hit, passed, alpha) = self.through_holes(ray, diff)?;
        let obj = &self.objects[hit.object];
        // Differentials always, even when no filter needs them: the footprint is worth showing.
        let d = if obj.identity {
            *diff
        } else {
            diff.transformed(&obj.object_from_world)
        };
        let (dpdx, dpdy) = d.footprint_on_plane(hit.local.p, hit.local.n);
        let ctx = self.texture_context_at(&hit, dpdx, dpdy);
        let material = &self.materials[obj.material];
        let texture = material.texture();
        let (kind, mapping, image) = texture_parts(texture);
        // `uv` without coordinates of the shape's own means its natural mapping.
        let effective = mapping
            .and_then(AnyMapping::builtin)
            .map(|m| match (m, ctx.shape_uv) {
                (Mapping::Uv, None) => ctx.natural,
                (m, _) => m,
            });
        let formula = match mapping {
            Some(AnyMapping::Formula(f)) => Some(f),
            _ => None,
        };
        let tex = texture.tex_coord(&ctx);
        // A mesh under a generated mapping: the model is fitted into [-1, 1]^3 first.
        let generated = formula.is_some() || effective.is_some_and(|e| e != Mapping::Uv);
        let fit_lines = match &obj.shape {
            Shape::Mesh(m) if generated => {
                let (c, s) = m.mesh.mapping_frame();
                let v3 = |v: Vec3A| {
                    format!(
                        "({}, {}, {})",
                        explain_number(f64::from(v.x)),
                        explain_number(f64::from(v.y)),
                        explain_number(f64::from(v.z))
                    )
                };
                vec![
                    format!(
                        "fit the model into [-1, 1]^3: p = (p_file - centre) x scale = ({} - {}) x {}",
                        v3(hit.local.p),
                        v3(c),
                        explain_number(f64::from(s))
                    ),
                    format!("p = {}", v3(ctx.p)),
                ]
            }
            _ => Vec::new(),
        };
        let mapping_lines = match (effective, mapping.and_then(AnyMapping::builtin)) {
            _ if let Some(f) = formula => {
                let mut lines = fit_lines;
                lines.extend(formula_lines(f, &ctx));
                if self.settings.view == View::Difference {
                    let tol = texture.texel_size() * f64::from(self.settings.compare.tolerance);
                    lines.extend(compare_lines(f, self.settings.compare.with, &ctx, tol));
                }
                lines
            }
            (Some(Mapping::Uv), _) => vec!["(u, v) carried by the shape's vertices".to_owned()],
            (Some(e), Some(m)) => {
                // The point the mapping reads: for meshes, the fitted one.
                let mut lines = fit_lines;
                lines.extend(explain_mapping(e, ctx.p));
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
        let (radiance, debug_value) = self.radiance_and_view(&ray, diff, depth);
        let mesh = match &obj.shape {
            Shape::Mesh(m) => mesh_point(&m.mesh, hit.local.prim, hit.local.part, hit.local.p),
            _ => None,
        };
        Some(Inspection {
            pixel,
            object: hit.object,
            object_name: obj.name.clone(),
            shape: shape_label(&obj.shape, hit.local.part),
            world_point: hit.p,
            local_point: hit.local.p,
            mapping_point: ctx.p,
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
            debug_value,
            mesh,
            passed,
            alpha,
            perturbation: self.perturbation_read(&hit, &ctx),
            mirror: self.mirror_read(pixel, &hit, &ctx, diff, depth),
        })
    }

    /// The shaded radiance along `ray` and, under a debug view, the view's value separately:
    /// there the film shows the view's colour, not the light. `depth` counts the mirror bounces
    /// `ray` has taken.
    fn radiance_and_view(
        &self,
        ray: &crate::math::Ray,
        diff: &crate::math::RayDifferential,
        depth: u32,
    ) -> (Rgb, Option<(View, Rgb)>) {
        let diff = self.needs_differentials().then_some(diff);
        let shown = self.trace_at_depth(ray, diff, depth);
        if self.settings.view == View::Shaded {
            (shown, None)
        } else {
            let mut shaded = self.clone();
            shaded.settings.view = View::Shaded;
            (
                shaded.trace_at_depth(ray, diff, depth),
                Some((self.settings.view, shown)),
            )
        }
    }

    /// What the bump or normal map of `hit`'s object does there (`None` without one).
    fn perturbation_read(
        &self,
        hit: &crate::scene::SurfaceHit,
        ctx: &crate::texture::TextureContext,
    ) -> Option<PerturbationRead> {
        use crate::scene::Perturbation;
        let perturbation = self.surfaces[hit.object].perturbation.as_ref()?;
        let (kind, texture, shading) = match perturbation {
            Perturbation::Bump(b) => ("bump map", &b.height, self.bumped_normal(hit, b, ctx)),
            Perturbation::Normal(m) => ("normal map", &m.map, self.normal_mapped(hit, m, ctx)),
        };
        let gradients = crate::material::uv_gradients(texture, ctx);
        let read = gradients.map_or_else(
            || texture.eval(ctx),
            |(tc, _, _)| texture.eval_tex_coord(tc, ctx.p),
        );
        let value = match perturbation {
            Perturbation::Bump(b) => {
                let h = read.luminance();
                format!(
                    "height {} x scale {} = {}",
                    explain_number(f64::from(h)),
                    explain_number(f64::from(b.scale)),
                    explain_number(f64::from(h * b.scale))
                )
            }
            Perturbation::Normal(_) => {
                let t = crate::material::decode_normal(read);
                format!(
                    "texel ({:.3}, {:.3}, {:.3}) -> tangent-space normal ({:.3}, {:.3}, {:.3})",
                    read.0, read.1, read.2, t.x, t.y, t.z
                )
            }
        };
        let frame = gradients
            .map(|(_, gu, gv)| crate::material::dual_basis(gu, gv))
            .filter(|(a, b)| a.is_finite() && b.is_finite() && a.cross(*b) != Vec3A::ZERO);
        let tilt = hit.ng.dot(shading).clamp(-1.0, 1.0).acos().to_degrees();
        Some(PerturbationRead {
            kind,
            value,
            frame,
            geometric: hit.ng,
            shading,
            tilt_degrees: tilt,
        })
    }
}

/// A texture's kind in a word, its mapping and the image it reads (if any).
fn texture_parts(texture: &Texture) -> (&'static str, Option<&AnyMapping>, Option<ImageRead>) {
    match texture {
        Texture::Constant(_) => ("constant", None, None),
        Texture::Checker(c) => ("checker", Some(&c.mapping), None),
        Texture::Formula(f) => ("formula", Some(&f.mapping), None),
        Texture::Image(t) => (
            "image",
            Some(&t.mapping),
            Some(ImageRead {
                image: t.image.clone(),
                filter: t.filter,
                lookup: t.lookup,
                wraps: t.wraps(),
            }),
        ),
    }
}

/// What a formula mapping reads at the hit of `ctx`: the point, then the shape's own (u, v) as
/// mesh_u, mesh_v.
fn formula_inputs(ctx: &crate::texture::TextureContext) -> [f64; 5] {
    let own = Mapping::Uv.map_with_differentials(
        ctx.p,
        Vec3A::ZERO,
        Vec3A::ZERO,
        ctx.shape_uv,
        ctx.natural,
    );
    crate::mapping::formula::inputs_of(ctx.p.as_dvec3(), own.uv.as_dvec2())
}

/// A formula mapping's worked formulas at the hit of `ctx`: each with the point's numbers (and
/// the shape's own (u, v) as mesh_u, mesh_v) substituted, and which derivatives it uses.
fn formula_lines(
    f: &crate::mapping::FormulaMapping,
    ctx: &crate::texture::TextureContext,
) -> Vec<String> {
    let inputs = formula_inputs(ctx);
    let mut lines = Vec::new();
    if f.reads_mesh() {
        lines.push(format!(
            "mesh_u = {}, mesh_v = {} (the shape's own (u, v))",
            explain_number(inputs[3]),
            explain_number(inputs[4])
        ));
    }
    lines.extend(f.explain(&inputs).0);
    lines
}

/// Under the `Difference` view: the built-in mapping `with` worked at the same point, and how
/// far the formula's (u, v) is from it against the tolerance `tol` (in (u, v)).
fn compare_lines(
    f: &crate::mapping::FormulaMapping,
    with: Mapping,
    ctx: &crate::texture::TextureContext,
    tol: glam::DVec2,
) -> Vec<String> {
    let got = f.eval(&formula_inputs(ctx));
    let want = crate::mapping::map_uv_f64(with, ctx.p.as_dvec3());
    let d = crate::mapping::formula::compare::difference(with, got, want);
    let mut lines = vec![format!("compared with the {} mapping:", with.name())];
    lines.extend(
        explain_mapping(with, ctx.p)
            .into_iter()
            .map(|l| format!("  {l}")),
    );
    let verdict = if d.x <= tol.x && d.y <= tol.y {
        "within the tolerance: they agree here"
    } else {
        "beyond the tolerance"
    };
    lines.push(format!(
        "  |du| = {}, |dv| = {} ({:.2} and {:.2} times the tolerance): {verdict}",
        explain_number(d.x),
        explain_number(d.y),
        d.x / tol.x.max(f64::MIN_POSITIVE),
        d.y / tol.y.max(f64::MIN_POSITIVE),
    ));
    lines
}

/// Where a learner goes wrong with object `object`'s image texture, in words: an image whose
/// aspect does not suit its mapping, the light probe's z flip and its panoramic variant, the
/// lecture lookup's missing last column. Empty when the object reads no image.
#[must_use]
pub fn mapping_hints(scene: &Scene, object: usize) -> Vec<String> {
    let Some(Texture::Image(t)) = scene
        .objects
        .get(object)
        .and_then(|o| scene.materials.get(o.material))
        .map(Material::texture)
    else {
        return Vec::new();
    };
    let (w, h) = (t.image.width(), t.image.height());
    let aspect = f64::from(w) / f64::from(h);
    let ratio = ratio_words(w, h);
    let mut hints = Vec::new();
    match t.mapping.builtin() {
        Some(Mapping::Spherical) if (aspect - 2.0).abs() > 0.02 => hints.push(format!(
            "this image is {ratio} ({w} x {h}), but the spherical map spreads its width over \
             360 degrees of longitude and its height over 180 of latitude: only a 2:1 image \
             keeps its shapes (its shapes come out {:.2} times {})",
            2.0 / aspect,
            if aspect < 2.0 {
                "too wide"
            } else {
                "too narrow"
            }
        )),
        Some(Mapping::LightProbe) => hints.push(
            "the light probe looks along +z: alpha = acos(z) is 0 at the image centre. A \
             probe made for a panorama looks along -z; its variant `panoramic` flips z (alpha \
             = acos(-z)), so the centre of the image lands behind the viewer"
                .to_owned(),
        ),
        Some(Mapping::Panoramic) => hints.push(
            "panoramic: the light probe with z flipped (alpha = acos(-z)): the image centre \
             is the direction -z. Switch to `light-probe` to see the lecture's +z convention"
                .to_owned(),
        ),
        _ => {}
    }
    if matches!(
        t.mapping.builtin(),
        Some(Mapping::LightProbe | Mapping::Panoramic | Mapping::MirrorBall)
    ) && (aspect - 1.0).abs() > 0.02
    {
        hints.push(format!(
            "a light probe is a disc in a square image; this one is {ratio} ({w} x {h}), so \
             the disc is squeezed into an ellipse"
        ));
    }
    if t.mapping.builtin() == Some(Mapping::Rectangular) && (aspect - 1.0).abs() > 0.02 {
        hints.push(format!(
            "the rectangular map puts the whole {ratio} image on the square [-1, 1]^2: its \
             aspect is kept only if the object is scaled {ratio} too"
        ));
    }
    if t.filter == Filter::Nearest && t.lookup == Lookup::Lecture {
        hints.push(format!(
            "the lecture's lookup (int)((hres - 1) u) reaches column {} only at u = 1 exactly \
             (and row {} only at v = 1): the last column and row are almost never read, and \
             every other texel is stretched by hres / (hres - 1). The centred lookup \
             min(floor(u hres), hres - 1) reads every texel alike",
            w - 1,
            h - 1
        ));
    }
    hints
}

/// "3:2" for 600 x 400, "2:1", or "1.47:1" when no small ratio fits.
fn ratio_words(w: u32, h: u32) -> String {
    for d in 1..=10_u32 {
        let n = f64::from(w) * f64::from(d) / f64::from(h);
        if (n - n.round()).abs() < 0.02 * n.max(1.0) && n.round() >= 1.0 {
            return format!("{}:{d}", n.round());
        }
    }
    format!("{:.2}:1", f64::from(w) / f64::from(h))
}

/// The triangle `prim` (BVH order; `part` in the file) of `mesh` hit at `p`: its vertices,
/// their (u, v) and the barycentric weights of `p`, with the interpolation worked.
fn mesh_point(mesh: &crate::geometry::Mesh, prim: u32, part: u32, p: Vec3A) -> Option<MeshPoint> {
    let (positions, uvs) = mesh.triangle_vertices(prim)?;
    let bary = barycentric(positions, Vec3::from(p));
    let n = |x: f32| explain_number(f64::from(x));
    let displaced = mesh
        .displacement()
        .map(crate::geometry::displace::Displacement::lines)
        .unwrap_or_default();
    let interpolation = uvs.map_or_else(Vec::new, |t| {
        let uv = t[0] * bary.x + t[1] * bary.y + t[2] * bary.z;
        vec![
            format!(
                "weights: w0 = {}, w1 = {}, w2 = {} (w0 + w1 + w2 = 1)",
                n(bary.x),
                n(bary.y),
                n(bary.z)
            ),
            format!(
                "u = w0 u0 + w1 u1 + w2 u2 = {} x {} + {} x {} + {} x {} = {}",
                n(bary.x),
                n(t[0].x),
                n(bary.y),
                n(t[1].x),
                n(bary.z),
                n(t[2].x),
                n(uv.x)
            ),
            format!(
                "v = w0 v0 + w1 v1 + w2 v2 = {} x {} + {} x {} + {} x {} = {}",
                n(bary.x),
                n(t[0].y),
                n(bary.y),
                n(t[1].y),
                n(bary.z),
                n(t[2].y),
                n(uv.y)
            ),
        ]
    });
    let lines = displaced.into_iter().chain(interpolation).collect();
    Some(MeshPoint {
        triangle: part,
        positions,
        uvs,
        bary,
        lines,
    })
}

/// The barycentric weights of `p` (on the triangle's plane) in triangle `t`, from the areas of
/// the sub-triangles (in f64: the weights of a point near a vertex keep their digits).
#[must_use]
pub fn barycentric(t: [Vec3; 3], p: Vec3) -> Vec3 {
    let [a, b, c] = t.map(|v| v.as_dvec3());
    let p = p.as_dvec3();
    let n = (b - a).cross(c - a);
    let nn = n.length_squared();
    if nn <= 0.0 || !nn.is_finite() {
        return Vec3::new(1.0, 0.0, 0.0);
    }
    let w1 = (p - a).cross(c - a).dot(n) / nn;
    let w2 = (b - a).cross(p - a).dot(n) / nn;
    Vec3::new((1.0 - w1 - w2) as f32, w1 as f32, w2 as f32)
}

/// A shape in words, with the triangle hit for meshes (and whether the mesh was displaced).
fn shape_label(shape: &Shape, part: u32) -> String {
    match shape {
        Shape::Sphere => "Sphere".into(),
        Shape::Cylinder { .. } => "Cylinder".into(),
        Shape::Plane => "Plane".into(),
        Shape::Rectangle => "Rectangle".into(),
        Shape::Disk => "Disk".into(),
        Shape::Mesh(m) => format!(
            "mesh {}{}, triangle {part} of {}",
            m.mesh
                .path()
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
            // A displaced copy says so (how, in the mesh lines): its triangles are the
            // subdivided ones.
            if m.mesh.displacement().is_some() {
                " (displaced)"
            } else {
                ""
            },
            m.mesh.triangle_count()
        ),
    }
}

mod angles;
mod mirror;
#[cfg(test)]
mod tests;

pub use angles::{MappingAngles, mapping_angles};
pub use mirror::MirrorRead;
