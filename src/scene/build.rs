//! Reading, validating and writing presets, and building the runtime [`Scene`] from one.

use super::desc::{
    AdaptiveDesc, CameraDesc, ColorDesc, DisplaceDesc, LightDesc, MaterialDesc, PRESET_VERSION,
    ParamRef, ProjectionDesc, RenderDesc, ScalarDesc, SceneDesc, TextureDesc, TransformDesc,
};
use super::{RenderSettings, Scene};
use crate::camera::{Camera, Projection};
use crate::error::{Error, Result};
use crate::geometry::displace::{
    Displacement, MAX_DISPLACED_TRIANGLES, displace, subdivide, subdivided_triangle_count,
};
use crate::geometry::{Mesh, MeshShape, Object, Shape};
use crate::mapping::{Mapping, UvAffine, UvTransform};
use crate::material::{Bump, Colour, Light, Material, NormalMap, Scalar, ScalarTexture};
use crate::math::{Affine3A, Quat, Vec3, Vec3A};
use crate::sampler::{PixelFilter, PixelSampler};
use crate::texture::{
    Channel, Checker, Filter, ImageData, ImageTexture, Lookup, MAX_ANISOTROPY_LIMIT, MipPyramid,
    Texture, TextureContext, View, load_alpha, load_image, uv_grid_image,
};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Largest accepted width or height of a render.
pub const MAX_RESOLUTION: u32 = 16_384;
/// Largest accepted samples per pixel.
pub const MAX_SPP: u32 = 1 << 20;
/// Largest preset file read (a preset is a few kilobytes; anything huge is a mistake).
pub const MAX_PRESET_BYTES: u64 = 16 << 20;
/// Side of the generated UV test grid image.
pub const UV_GRID_SIZE: u32 = 1024;

/// Parses preset text; errors carry `path` and the line and column where parsing stopped.
///
/// # Errors
/// Malformed RON, unknown fields, wrong types, or an unsupported `version`.
pub fn parse_preset(text: &str, path: &Path) -> Result<SceneDesc> {
    // A byte-order mark is not RON; editors on Windows write one.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let desc: SceneDesc = ron::from_str(text).map_err(|e| Error::Preset {
        path: path.to_path_buf(),
        line: e.span.start.line,
        column: e.span.start.col,
        message: e.code.to_string(),
    })?;
    if desc.version != PRESET_VERSION {
        return Err(Error::invalid(
            path,
            format!(
                "version {} is not supported (this texplore reads version {PRESET_VERSION})",
                desc.version
            ),
        ));
    }
    Ok(desc)
}

/// Reads and parses a preset file (a regular file of at most 16 MiB, `MAX_PRESET_BYTES`).
///
/// # Errors
/// The file cannot be read, is not a regular file, is too large, or does not parse.
pub fn load_preset(path: &Path) -> Result<SceneDesc> {
    let text = crate::input::read_input_text(path, MAX_PRESET_BYTES)?;
    parse_preset(&text, path)
}

/// The preset as pretty RON.
#[must_use]
pub fn to_ron(desc: &SceneDesc) -> String {
    let config = ron::ser::PrettyConfig::new()
        .depth_limit(8)
        .struct_names(false);
    ron::ser::to_string_pretty(desc, config).unwrap_or_else(|e| format!("// cannot serialise: {e}"))
}

/// Writes a preset atomically through [`crate::output::write_atomically`] (a temporary file
/// beside it, renamed over it; never over a directory, device or read-only file, nor over one
/// of the preset's own images or meshes, whose paths are relative to `path`'s folder).
///
/// # Errors
/// A value is not a finite number ("FILE: not saved: ambient.color: NaN is not a number"), or
/// the file is refused or cannot be written: "cannot write FILE: reason".
pub fn save_preset(desc: &SceneDesc, path: &Path) -> Result<()> {
    check_numbers(desc).map_err(|m| Error::invalid(path, format!("not saved: {m}")))?;
    let folder = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let assets = super::files::asset_paths(desc, folder);
    let inputs: Vec<&Path> = assets.iter().map(PathBuf::as_path).collect();
    crate::output::write_bytes(path, &inputs, to_ron(desc).as_bytes())
}

/// Refuses a preset holding a NaN or an infinity anywhere (every `f32`, point and colour),
/// naming the field: `ambient.color: NaN is not a number`,
/// `objects[2].material.cd.scale: inf is not finite`. Ranges are checked by [`build_scene`];
/// this check needs no files, so it also guards every preset written out (a saved preset or
/// the one a PNG carries never holds a value that does not read back).
///
/// # Errors
/// The first field that is not a finite number.
pub fn check_numbers(desc: &SceneDesc) -> std::result::Result<(), String> {
    let mut n = Numbers(None);
    let c = &desc.camera;
    n.check(|| "camera.eye".into(), &c.eye.to_array());
    n.check(|| "camera.look_at".into(), &c.look_at.to_array());
    n.check(|| "camera.up".into(), &c.up.to_array());
    match c.projection {
        ProjectionDesc::Pinhole { fov } | ProjectionDesc::Fisheye { fov } => {
            n.check(|| "camera.fov".into(), &[fov]);
        }
        ProjectionDesc::Spherical { h_fov, v_fov } => {
            n.check(|| "camera.h_fov".into(), &[h_fov]);
            n.check(|| "camera.v_fov".into(), &[v_fov]);
        }
        ProjectionDesc::Orthographic { height } => {
            n.check(|| "camera.height".into(), &[height]);
        }
    }
    let r = &desc.render;
    n.check(|| "render.exposure".into(), &[r.exposure]);
    n.check(|| "render.background".into(), &r.background.to_array());
    if let Some(a) = r.adaptive {
        n.check(|| "render.adaptive.threshold".into(), &[a.threshold]);
    }
    n.check(|| "ambient.ls".into(), &[desc.ambient.ls]);
    n.check(|| "ambient.color".into(), &desc.ambient.color.to_array());
    for (i, l) in desc.lights.iter().enumerate() {
        let (point, point_name, ls, color) = match *l {
            LightDesc::Directional {
                direction,
                ls,
                color,
                ..
            } => (direction, "direction", ls, color),
            LightDesc::Point {
                position,
                ls,
                color,
                ..
            } => (position, "position", ls, color),
        };
        n.check(|| format!("lights[{i}].{point_name}"), &point.to_array());
        n.check(|| format!("lights[{i}].ls"), &[ls]);
        n.check(|| format!("lights[{i}].color"), &color.to_array());
    }
    for (i, o) in desc.objects.iter().enumerate() {
        n.object(&format!("objects[{i}]"), o);
    }
    n.0.map_or(Ok(()), Err)
}

/// The first non-finite number [`check_numbers`] met, as its message.
struct Numbers(Option<String>);

impl Numbers {
    /// Notes the first of `values` that is not finite, unless one was noted before; `what`
    /// names the field.
    fn check(&mut self, what: impl FnOnce() -> String, values: &[f32]) {
        if self.0.is_none()
            && let Some(v) = values.iter().find(|v| !v.is_finite())
        {
            self.0 = Some(format!("{}: {}", what(), not_finite(*v)));
        }
    }

    /// Every number of one object: its transform, material and texture.
    fn object(&mut self, at: &str, o: &super::ObjectDesc) {
        let t = &o.transform;
        self.check(
            || format!("{at}.transform.translate"),
            &t.translate.to_array(),
        );
        self.check(|| format!("{at}.transform.rotate"), &t.rotate.to_array());
        self.check(|| format!("{at}.transform.scale"), &t.scale.to_array());
        for (name, p) in o.material.params() {
            match p {
                ParamRef::Scalar(ScalarDesc::Value(v)) => {
                    self.check(|| format!("{at}.material.{name}"), &[*v]);
                }
                ParamRef::Color(ColorDesc::Value(c)) => {
                    self.check(|| format!("{at}.material.{name}"), &c.to_array());
                }
                _ => {}
            }
        }
        for (name, t) in o.material.textures() {
            self.texture(&format!("{at}.material.{name}"), t);
        }
        match &o.alpha {
            Some(ScalarDesc::Value(v)) => self.check(|| format!("{at}.alpha"), &[*v]),
            Some(a) => {
                if let Some(t) = a.texture() {
                    self.texture(&format!("{at}.alpha"), t);
                }
            }
            None => {}
        }
        if let Some(b) = &o.bump {
            self.check(|| format!("{at}.bump.scale"), &[b.scale]);
            self.texture(&format!("{at}.bump.height"), &b.height);
        }
        if let Some(n) = &o.normal {
            self.check(|| format!("{at}.normal.strength"), &[n.strength]);
            self.texture(&format!("{at}.normal.map"), &n.map);
        }
        if let Some(d) = &o.displace {
            self.check(|| format!("{at}.displace.scale"), &[d.scale]);
            self.texture(&format!("{at}.displace.height"), &d.height);
        }
    }

    /// Every number of one texture; `tex` names it.
    fn texture(&mut self, tex: &str, t: &TextureDesc) {
        if let Some(uv) = t.uv_transform() {
            self.check(|| format!("{tex}.uv.scale"), &uv.scale.to_array());
            self.check(|| format!("{tex}.uv.rotate"), &[uv.rotate]);
            self.check(|| format!("{tex}.uv.offset"), &uv.offset.to_array());
        }
        match t {
            TextureDesc::Constant(c) => self.check(|| tex.to_owned(), &c.to_array()),
            TextureDesc::Image {
                scale,
                max_anisotropy,
                ..
            } => {
                self.check(|| format!("{tex}.scale"), &[*scale]);
                self.check(|| format!("{tex}.max_anisotropy"), &[*max_anisotropy]);
            }
            TextureDesc::Checker {
                squares, colors, ..
            } => {
                self.check(|| format!("{tex}.squares"), &[squares.0, squares.1]);
                self.check(
                    || format!("{tex}.colors"),
                    &[colors.0.to_array(), colors.1.to_array()].concat(),
                );
            }
            TextureDesc::MeshMaterial { max_anisotropy, .. }
            | TextureDesc::UvGrid { max_anisotropy, .. } => {
                self.check(|| format!("{tex}.max_anisotropy"), &[*max_anisotropy]);
            }
        }
    }
}

/// Why a non-finite number is refused.
fn not_finite(v: f32) -> String {
    if v.is_nan() {
        "NaN is not a number".into()
    } else {
        format!("{v} is not finite")
    }
}

/// Decoded images shared between builds, so an edit in the GUI does not decode the Earth again.
#[derive(Debug, Default)]
pub struct AssetCache {
    images: HashMap<(PathBuf, bool), Arc<ImageData>>,
    alphas: HashMap<PathBuf, Arc<ImageData>>,
    uv_grid: Option<Arc<ImageData>>,
    meshes: HashMap<PathBuf, Arc<Mesh>>,
    /// Mip pyramids, built on first use by a mip filter and keyed by their base image (the
    /// cache holds every base image, so an `Arc` pointer stays a unique key).
    mips: Vec<(Arc<ImageData>, Arc<MipPyramid>)>,
    /// The latest displaced meshes (at most [`DISPLACED_KEPT`]), by mesh file, the folder the
    /// height texture's path is relative to, and the displacement.
    displaced: Vec<(DisplacedKey, Arc<Mesh>)>,
}

/// What a displaced mesh is made from: the mesh file, the preset's folder and the displacement.
type DisplacedKey = (PathBuf, PathBuf, DisplaceDesc);

/// How many displaced meshes the cache keeps (the latest), so editing a displacement in the
/// window does not pile up copies.
pub const DISPLACED_KEPT: usize = 4;

impl AssetCache {
    /// An empty cache.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The image at `path`, decoded once.
    ///
    /// # Errors
    /// See [`load_image`].
    pub fn image(&mut self, path: &Path, srgb: bool) -> Result<Arc<ImageData>> {
        let key = (path.to_path_buf(), srgb);
        if let Some(img) = self.images.get(&key) {
            return Ok(img.clone());
        }
        let img = Arc::new(load_image(path, srgb)?);
        self.images.insert(key, img.clone());
        Ok(img)
    }

    /// The alpha channel of the image at `path` as a grey image, decoded once.
    ///
    /// # Errors
    /// See [`load_alpha`].
    pub fn alpha(&mut self, path: &Path) -> Result<Arc<ImageData>> {
        if let Some(img) = self.alphas.get(path) {
            return Ok(img.clone());
        }
        let img = Arc::new(load_alpha(path)?);
        self.alphas.insert(path.to_path_buf(), img.clone());
        Ok(img)
    }

    /// The mesh at `path`, read and its BVH built once (every instance shares it).
    ///
    /// # Errors
    /// See [`crate::meshio::load_mesh`] and [`Mesh::new`].
    pub fn mesh(&mut self, path: &Path) -> Result<Arc<Mesh>> {
        if let Some(m) = self.meshes.get(path) {
            return Ok(m.clone());
        }
        let mesh = Arc::new(Mesh::new(crate::meshio::load_mesh(path)?, path)?);
        self.meshes.insert(path.to_path_buf(), mesh.clone());
        Ok(mesh)
    }

    /// Makes `mesh` what presets naming `path` get (a generated mesh, for benchmarks).
    pub fn insert_mesh(&mut self, path: &Path, mesh: Arc<Mesh>) {
        self.meshes.insert(path.to_path_buf(), mesh);
    }

    /// The displaced mesh made for `key`, if one is kept.
    fn displaced(&self, key: &DisplacedKey) -> Option<Arc<Mesh>> {
        self.displaced
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, m)| m.clone())
    }

    /// Keeps `mesh` as the displaced mesh of `key`, forgetting the oldest beyond
    /// [`DISPLACED_KEPT`].
    fn keep_displaced(&mut self, key: DisplacedKey, mesh: Arc<Mesh>) {
        if self.displaced.len() >= DISPLACED_KEPT {
            self.displaced.remove(0);
        }
        self.displaced.push((key, mesh));
    }

    /// The generated UV test grid.
    pub fn uv_grid(&mut self) -> Arc<ImageData> {
        self.uv_grid
            .get_or_insert_with(|| Arc::new(uv_grid_image(UV_GRID_SIZE)))
            .clone()
    }

    /// The mip pyramid of `image`, built once.
    pub fn mip(&mut self, image: &Arc<ImageData>) -> Arc<MipPyramid> {
        if let Some((_, m)) = self.mips.iter().find(|(i, _)| Arc::ptr_eq(i, image)) {
            return m.clone();
        }
        let m = Arc::new(MipPyramid::build(image.clone()));
        self.mips.push((image.clone(), m.clone()));
        m
    }

    /// How many mip pyramids have been built (each at most once).
    #[must_use]
    pub fn mip_count(&self) -> usize {
        self.mips.len()
    }
}

/// Resolution and samples for one render, possibly overriding the preset's.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Width in pixels.
    pub width: Option<u32>,
    /// Height in pixels.
    pub height: Option<u32>,
    /// Samples per pixel.
    pub spp: Option<u32>,
    /// Seed.
    pub seed: Option<u32>,
    /// Texture filter for every image texture.
    pub filter: Option<Filter>,
    /// Pixel sampler.
    pub sampler: Option<PixelSampler>,
    /// EWA's largest anisotropy for every image texture.
    pub max_anisotropy: Option<f32>,
    /// Pixel reconstruction filter.
    pub pixel_filter: Option<PixelFilter>,
    /// Adaptive sampling on (`Some`); the preset's setting otherwise.
    pub adaptive: Option<AdaptiveDesc>,
    /// Turns adaptive sampling off whatever the preset says.
    pub no_adaptive: bool,
    /// Debug view.
    pub view: Option<View>,
}

/// Builds the runtime scene. `preset_path` names the file in errors; asset paths are resolved
/// relative to its directory.
///
/// # Errors
/// An out-of-range value (naming the field) or an asset that cannot be loaded.
pub fn build_scene(desc: &SceneDesc, preset_path: &Path, cache: &mut AssetCache) -> Result<Scene> {
    let base = preset_path.parent().unwrap_or(Path::new("."));
    let bad = |msg: String| Error::invalid(preset_path, msg);
    check_numbers(desc).map_err(bad)?;
    let settings = render_settings(&desc.render).map_err(bad)?;
    let camera = camera(&desc.camera, settings.width, settings.height).map_err(bad)?;
    finite_non_negative("ambient.ls", &[desc.ambient.ls]).map_err(bad)?;
    finite_non_negative("ambient.color", &desc.ambient.color.to_array()).map_err(bad)?;
    let ambient = desc.ambient.color * desc.ambient.ls;

    let mut lights = Vec::with_capacity(desc.lights.len());
    for (i, l) in desc.lights.iter().enumerate() {
        lights.push(light(l).map_err(|m| bad(format!("lights[{i}]: {m}")))?);
    }

    let mut objects = Vec::with_capacity(desc.objects.len());
    let mut materials = Vec::with_capacity(desc.objects.len());
    let mut needs_differentials = false;
    let mut clips = Vec::with_capacity(desc.objects.len());
    let mut bumps = Vec::with_capacity(desc.objects.len());
    let mut normal_maps = Vec::with_capacity(desc.objects.len());
    for (i, o) in desc.objects.iter().enumerate() {
        let what = if o.name.is_empty() {
            format!("objects[{i}]")
        } else {
            format!("objects[{i}] ({})", o.name)
        };
        let transform =
            transform(&o.transform).map_err(|m| bad(format!("{what}.transform: {m}")))?;
        let shape = match (&o.shape, &o.displace) {
            (super::ShapeDesc::Mesh { path, shading }, displace) => {
                let file = base.join(path);
                let mut mesh = cache.mesh(&file)?;
                if let Some(d) = displace {
                    mesh = displaced_mesh(&mesh, &file, d, base, cache).map_err(|e| match e {
                        Error::Invalid { message, .. } => bad(format!("{what}.displace.{message}")),
                        other => other,
                    })?;
                }
                Shape::Mesh(MeshShape {
                    mesh,
                    shading: *shading,
                })
            }
            (generic, Some(_)) => {
                return Err(bad(format!(
                    "{what}.displace: a displacement map needs a Mesh shape, and {} is a generic \
                     shape; use a mesh (which is subdivided and displaced at load), or a bump map \
                     (bump: ...) for the look without moving the surface",
                    generic.kind()
                )));
            }
            (generic, None) => generic
                .generic()
                .ok_or_else(|| bad(format!("{what}.shape: {generic:?} is not a generic shape")))?,
        };
        let mesh = match &shape {
            Shape::Mesh(m) => Some(&*m.mesh),
            _ => None,
        };
        let material_desc = super::mesh::resolve_mesh_material(&o.material, mesh)
            .map_err(|m| bad(format!("{what}.material: {m}")))?;
        if let Some(mesh) = mesh {
            super::mesh::check_uv_mapping(&material_desc, mesh)
                .map_err(|m| bad(format!("{what}.material: {m}")))?;
        }
        let material = material(&material_desc, base, cache).map_err(|e| match e {
            Error::Invalid { message, .. } => bad(format!("{what}.material: {message}")),
            other => other,
        })?;
        needs_differentials |= material.needs_differentials() || settings.view.needs_footprint();
        let name = match (&o.shape, o.name.is_empty()) {
            (_, false) => o.name.clone(),
            (super::ShapeDesc::Mesh { path, .. }, true) => format!("{path} {i}"),
            (s, true) => format!("{s:?} {i}"),
        };
        let clip = match &o.alpha {
            None => None,
            Some(a) => match scalar("alpha", a, base, cache).map_err(|e| match e {
                Error::Invalid { message, .. } => bad(format!("{what}.{message}")),
                other => other,
            })? {
                // Solid everywhere: no clip map at all.
                Scalar::Const(v) if v >= 1.0 => None,
                s => Some(s),
            },
        };
        needs_differentials |= clip.as_ref().is_some_and(Scalar::needs_differentials);
        clips.push(clip);
        let bump = match &o.bump {
            None => None,
            Some(b) => {
                if !b.scale.is_finite() {
                    return Err(bad(format!("{what}.bump.scale: {} is not finite", b.scale)));
                }
                let height =
                    param_texture("bump.height", &b.height, base, cache).map_err(|e| match e {
                        Error::Invalid { message, .. } => bad(format!("{what}.{message}")),
                        other => other,
                    })?;
                match height {
                    // A constant height has no slope: no bump map at all.
                    Texture::Constant(_) => None,
                    height => Some(Bump {
                        height,
                        scale: b.scale,
                    }),
                }
            }
        };
        needs_differentials |= bump
            .as_ref()
            .is_some_and(|b| b.height.needs_differentials());
        bumps.push(bump);
        let normal_map = match &o.normal {
            None => None,
            Some(_) if o.bump.is_some() => {
                return Err(bad(format!(
                    "{what}: has both a bump map and a normal map; an object has one or the other"
                )));
            }
            Some(n) => Some(normal_map(n, base, cache).map_err(|e| match e {
                Error::Invalid { message, .. } => bad(format!("{what}.{message}")),
                other => other,
            })?),
        };
        needs_differentials |= normal_map
            .as_ref()
            .is_some_and(|n| n.map.needs_differentials());
        normal_maps.push(normal_map);
        let mut obj = Object::new(shape, transform, materials.len(), name);
        obj.casts_shadows = o.casts_shadows.unwrap_or(material.is_lit());
        materials.push(material);
        objects.push(obj);
    }
    let has_clips = clips.iter().any(Option::is_some);
    let has_perturbations =
        bumps.iter().any(Option::is_some) || normal_maps.iter().any(Option::is_some);
    Ok(Scene {
        objects,
        materials,
        lights,
        ambient,
        camera,
        settings,
        needs_differentials,
        clips,
        has_clips,
        bumps,
        normal_maps,
        has_perturbations,
    })
}

/// `base` (read from `file`) subdivided and displaced as `d` says, through the cache (each
/// displacement of a file is made once; the file's own mesh stays shared and untouched).
/// Messages start with the field (`subdivide: ...`, `height.Image.scale: ...`); the caller
/// prefixes the object and `displace`.
fn displaced_mesh(
    base: &Arc<Mesh>,
    file: &Path,
    d: &DisplaceDesc,
    dir: &Path,
    cache: &mut AssetCache,
) -> Result<Arc<Mesh>> {
    let invalid = |m: String| Error::invalid(dir, m);
    if !(d.scale.is_finite() && d.scale.abs() <= 1e6) {
        return Err(invalid(format!(
            "scale: {} is out of range (-1e6 to 1e6 mesh units)",
            d.scale
        )));
    }
    let limit = MAX_DISPLACED_TRIANGLES;
    let triangles = subdivided_triangle_count(base.triangle_count(), d.subdivide);
    if triangles > limit {
        return Err(invalid(format!(
            "subdivide: {} levels would make {} triangles of the {} in {} (each level makes \
             4 of every triangle); at most {limit} (4 M) are allowed: use fewer levels",
            d.subdivide,
            if triangles == usize::MAX {
                "more than 2^64".to_owned()
            } else {
                triangles.to_string()
            },
            base.triangle_count(),
            file.display()
        )));
    }
    let key = (file.to_path_buf(), dir.to_path_buf(), d.clone());
    if let Some(m) = cache.displaced(&key) {
        return Ok(m);
    }
    if !base.has_uv()
        && let Some(Mapping::Uv) = d.height.mapping()
    {
        return Err(invalid(format!(
            "height: {} has no texture coordinates; choose a generated mapping (spherical, \
             cylindrical, rectangular)",
            file.display()
        )));
    }
    let height = param_texture("height", &d.height, dir, cache)?;
    let moves_nothing = match &height {
        Texture::Constant(c) => c.luminance() * d.scale == 0.0,
        _ => d.scale == 0.0,
    };
    if moves_nothing {
        // A displacement that moves nothing is none: the file's mesh as it is, shared.
        return Ok(base.clone());
    }
    let (mut data, _) = subdivide(&base.to_data(), d.subdivide);
    let natural = super::natural_mapping(&Shape::Mesh(MeshShape {
        mesh: base.clone(),
        shading: crate::geometry::Shading::Smooth,
    }));
    let heights: Vec<f32> = {
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
                let h = height.eval(&ctx).luminance();
                if h.is_finite() { h } else { 0.0 }
            })
            .collect()
    };
    displace(&mut data, &heights, d.scale);
    let what = Displacement {
        height: texture_words(&d.height),
        scale: d.scale,
        levels: d.subdivide,
        file_triangles: base.triangle_count(),
        triangles: data.triangles.len(),
    };
    let mesh = Arc::new(Mesh::new(data, file)?.displaced_from(base, what));
    cache.keep_displaced(key, mesh.clone());
    Ok(mesh)
}

/// A texture in a few words, for the inspector: an image's file name, else its kind.
fn texture_words(t: &TextureDesc) -> String {
    match t {
        TextureDesc::Image { path, .. } => Path::new(path)
            .file_name()
            .map_or_else(|| path.clone(), |n| n.to_string_lossy().into_owned()),
        TextureDesc::Constant(c) => format!("a constant {:?}", c.to_array()),
        other => format!("a {} texture", other.kind()),
    }
}

/// A normal map: its texture read raw (normals are not colours), never a constant (which has
/// no mapping, so no tangent frame).
fn normal_map(n: &super::NormalMapDesc, base: &Path, cache: &mut AssetCache) -> Result<NormalMap> {
    if !n.strength.is_finite() {
        return Err(Error::invalid(
            base,
            format!("normal.strength: {} is not finite", n.strength),
        ));
    }
    let mut raw = n.map.clone();
    if let TextureDesc::Image { srgb, .. } = &mut raw {
        *srgb = false;
    }
    match param_texture("normal.map", &raw, base, cache)? {
        Texture::Constant(_) => Err(Error::invalid(
            base,
            "normal.map: a constant has no (u, v) mapping, so no tangent frame; use an image",
        )),
        map => Ok(NormalMap {
            map,
            strength: n.strength,
        }),
    }
}

fn render_settings(r: &RenderDesc) -> std::result::Result<RenderSettings, String> {
    if !(1..=MAX_RESOLUTION).contains(&r.width) || !(1..=MAX_RESOLUTION).contains(&r.height) {
        return Err(format!(
            "render: resolution {}x{} is out of range (1 to {MAX_RESOLUTION} per side)",
            r.width, r.height
        ));
    }
    if !(1..=MAX_SPP).contains(&r.spp) {
        return Err(format!(
            "render.spp: {} is out of range (1 to {MAX_SPP})",
            r.spp
        ));
    }
    if !r.exposure.is_finite() || r.exposure.abs() > 64.0 {
        return Err(format!(
            "render.exposure: {} stops is out of range (-64 to 64)",
            r.exposure
        ));
    }
    finite_non_negative("render.background", &r.background.to_array())?;
    if let Some(a) = r.adaptive {
        if !(r.spp..=MAX_SPP).contains(&a.max_spp) {
            return Err(format!(
                "render.adaptive.max_spp: {} is out of range ({} = render.spp to {MAX_SPP})",
                a.max_spp, r.spp
            ));
        }
        if !(a.threshold.is_finite() && a.threshold > 0.0 && a.threshold <= 1.0) {
            return Err(format!(
                "render.adaptive.threshold: {} is out of range (0, 1]",
                a.threshold
            ));
        }
    }
    if r.reflection_depth > super::desc::MAX_REFLECTION_DEPTH {
        return Err(format!(
            "render.reflection_depth: {} is out of range (0 to {})",
            r.reflection_depth,
            super::desc::MAX_REFLECTION_DEPTH
        ));
    }
    Ok(RenderSettings {
        width: r.width,
        height: r.height,
        spp: r.spp,
        seed: r.seed,
        sampler: r.sampler,
        exposure_scale: r.exposure.exp2(),
        background: r.background,
        pixel_filter: r.pixel_filter,
        adaptive: r.adaptive,
        view: r.view,
        reflection_depth: r.reflection_depth,
    })
}

fn finite_vec(what: &str, v: Vec3) -> std::result::Result<Vec3A, String> {
    if v.is_finite() {
        Ok(v.into())
    } else {
        Err(format!("{what}: {v} is not finite"))
    }
}

fn finite_non_negative(what: &str, values: &[f32]) -> std::result::Result<(), String> {
    match values.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
        Some(v) => Err(format!("{what}: {v} must be finite and not negative")),
        None => Ok(()),
    }
}

fn camera(c: &CameraDesc, width: u32, height: u32) -> std::result::Result<Camera, String> {
    let eye = finite_vec("camera.eye", c.eye)?;
    let look_at = finite_vec("camera.look_at", c.look_at)?;
    let up = finite_vec("camera.up", c.up)?;
    if (eye - look_at).length_squared() == 0.0 {
        return Err("camera: eye and look_at are the same point".into());
    }
    if up.length_squared() == 0.0 {
        return Err("camera.up: must not be zero".into());
    }
    let in_range = |what: &str, v: f32, max: f32| {
        if v > 0.0 && v <= max {
            Ok(v.to_radians())
        } else {
            Err(format!(
                "camera.{what}: {v} degrees is out of range (0, {max}]"
            ))
        }
    };
    let projection = match c.projection {
        ProjectionDesc::Pinhole { fov } => {
            let fov_y = in_range("fov", fov, 179.0)?;
            Projection::Pinhole { fov_y }
        }
        ProjectionDesc::Fisheye { fov } => Projection::Fisheye {
            psi_max: in_range("fov", fov, 360.0)? * 0.5,
        },
        ProjectionDesc::Spherical { h_fov, v_fov } => Projection::Spherical {
            lambda_max: in_range("h_fov", h_fov, 360.0)? * 0.5,
            psi_max: in_range("v_fov", v_fov, 180.0)? * 0.5,
        },
        ProjectionDesc::Orthographic { height } => {
            if !(height > 0.0 && height <= 1e9) {
                return Err(format!(
                    "camera.height: {height} is out of range (0, 1e9] world units"
                ));
            }
            Projection::Orthographic { height }
        }
    };
    Ok(Camera::new(eye, look_at, up, projection, width, height))
}

fn light(l: &LightDesc) -> std::result::Result<Light, String> {
    Ok(match *l {
        LightDesc::Directional {
            direction,
            ls,
            color,
            shadows,
        } => {
            let d = finite_vec("direction", direction)?;
            let to_light = d.try_normalize().ok_or("direction: must not be zero")?;
            finite_non_negative("ls", &[ls])?;
            finite_non_negative("color", &color.to_array())?;
            Light::Directional {
                to_light,
                radiance: color * ls,
                shadows,
            }
        }
        LightDesc::Point {
            position,
            ls,
            color,
            shadows,
        } => {
            finite_non_negative("ls", &[ls])?;
            finite_non_negative("color", &color.to_array())?;
            Light::Point {
                position: finite_vec("position", position)?,
                radiance: color * ls,
                shadows,
            }
        }
    })
}

fn transform(t: &TransformDesc) -> std::result::Result<Affine3A, String> {
    let translate = finite_vec("translate", t.translate)?;
    let rotate = finite_vec("rotate", t.rotate)?;
    let scale = finite_vec("scale", t.scale)?;
    if scale.abs().min_element() < 1e-30 || scale.abs().max_element() > 1e30 {
        return Err(format!(
            "scale: {} must be non-zero and below 1e30 on every axis",
            t.scale
        ));
    }
    let r = Quat::from_rotation_z(rotate.z.to_radians())
        * Quat::from_rotation_y(rotate.y.to_radians())
        * Quat::from_rotation_x(rotate.x.to_radians());
    Ok(Affine3A::from_scale_rotation_translation(
        scale.into(),
        r,
        translate.into(),
    ))
}

fn material(m: &MaterialDesc, base: &Path, cache: &mut AssetCache) -> Result<Material> {
    Ok(match m {
        MaterialDesc::Matte { ka, kd, cd } => Material::Matte {
            ka: scalar("ka", ka, base, cache)?,
            kd: scalar("kd", kd, base, cache)?,
            cd: texture(cd, base, cache)?,
        },
        MaterialDesc::Phong {
            ka,
            kd,
            cd,
            ks,
            cs,
            exp,
            ce,
        } => Material::Phong {
            ka: scalar("ka", ka, base, cache)?,
            kd: scalar("kd", kd, base, cache)?,
            cd: texture(cd, base, cache)?,
            ks: scalar("ks", ks, base, cache)?,
            cs: colour("cs", cs, base, cache)?,
            exp: scalar("exp", exp, base, cache)?,
            ce: colour("ce", ce, base, cache)?,
        },
        MaterialDesc::Reflective {
            ka,
            kd,
            cd,
            ks,
            cs,
            exp,
            kr,
            cr,
        } => Material::Reflective {
            ka: scalar("ka", ka, base, cache)?,
            kd: scalar("kd", kd, base, cache)?,
            cd: texture(cd, base, cache)?,
            ks: scalar("ks", ks, base, cache)?,
            cs: colour("cs", cs, base, cache)?,
            exp: scalar("exp", exp, base, cache)?,
            kr: scalar("kr", kr, base, cache)?,
            cr: colour("cr", cr, base, cache)?,
        },
        MaterialDesc::Emissive { ls, ce } => Material::Emissive {
            ls: scalar("ls", ls, base, cache)?,
            ce: texture(ce, base, cache)?,
        },
    })
}

/// A texture of parameter `what`, its messages prefixed with the parameter's name
/// (`ks.Image.scale: ...`).
fn param_texture(
    what: &str,
    t: &TextureDesc,
    base: &Path,
    cache: &mut AssetCache,
) -> Result<Texture> {
    texture(t, base, cache).map_err(|e| match e {
        Error::Invalid { path, message } => Error::Invalid {
            path,
            message: format!("{what}.{message}"),
        },
        other => other,
    })
}

/// A coefficient: a constant stays a plain number (a constant texture becomes one), so it
/// costs nothing when shading.
fn scalar(what: &str, s: &ScalarDesc, base: &Path, cache: &mut AssetCache) -> Result<Scalar> {
    let (t, channel) = match s {
        ScalarDesc::Value(v) => {
            finite_non_negative(what, &[*v]).map_err(|m| Error::invalid(base, m))?;
            return Ok(Scalar::Const(*v));
        }
        ScalarDesc::Texture(t) => (t, Channel::Luminance),
        ScalarDesc::Channel(c) => (&c.texture, c.channel),
    };
    if channel == Channel::Alpha {
        let texture = alpha_texture(t, base, cache).map_err(|e| match e {
            Error::Invalid { path, message } => Error::Invalid {
                path,
                message: format!("{what}.{message}"),
            },
            other => other,
        })?;
        return Ok(Scalar::Texture(Box::new(ScalarTexture {
            texture,
            channel,
        })));
    }
    Ok(match param_texture(what, t, base, cache)? {
        Texture::Constant(c) => Scalar::Const(channel.of(c)),
        texture => Scalar::Texture(Box::new(ScalarTexture { texture, channel })),
    })
}

/// The alpha channel of an `Image` texture, read through its mapping, filter, wrap and
/// (u, v) transform like its colour would be.
fn alpha_texture(t: &TextureDesc, base: &Path, cache: &mut AssetCache) -> Result<Texture> {
    let TextureDesc::Image {
        path,
        mapping,
        filter,
        lookup,
        wrap,
        max_anisotropy,
        uv,
        ..
    } = t
    else {
        return Err(Error::invalid(
            base,
            format!("channel Alpha needs an Image texture, not {}", t.kind()),
        ));
    };
    check_anisotropy("Image", *max_anisotropy).map_err(|m| Error::invalid(base, m))?;
    let transform = uv_transform("Image", uv).map_err(|m| Error::invalid(base, m))?;
    let image = cache.alpha(&base.join(path))?;
    let mip = filter.needs_mip().then(|| cache.mip(&image));
    Ok(Texture::Image(ImageTexture {
        image,
        mapping: *mapping,
        filter: *filter,
        lookup: *lookup,
        wrap: *wrap,
        scale: 1.0,
        mip,
        max_anisotropy: *max_anisotropy,
        transform,
    }))
}

/// A colour parameter: a constant stays a plain colour (a constant texture becomes one).
fn colour(what: &str, c: &ColorDesc, base: &Path, cache: &mut AssetCache) -> Result<Colour> {
    Ok(match c {
        ColorDesc::Value(c) => {
            finite_non_negative(what, &c.to_array()).map_err(|m| Error::invalid(base, m))?;
            Colour::Const(*c)
        }
        ColorDesc::Texture(t) => match param_texture(what, t, base, cache)? {
            Texture::Constant(c) => Colour::Const(c),
            texture => Colour::Texture(Box::new(texture)),
        },
    })
}

fn texture(t: &TextureDesc, base: &Path, cache: &mut AssetCache) -> Result<Texture> {
    let invalid = |m: String| Error::invalid(base, m);
    Ok(match t {
        TextureDesc::Constant(c) => {
            finite_non_negative("Constant", &c.to_array()).map_err(invalid)?;
            Texture::Constant(*c)
        }
        TextureDesc::Image {
            path,
            mapping,
            filter,
            lookup,
            wrap,
            scale,
            srgb,
            max_anisotropy,
            uv,
        } => {
            finite_non_negative("Image.scale", &[*scale]).map_err(invalid)?;
            let transform = uv_transform("Image", uv).map_err(invalid)?;
            check_anisotropy("Image", *max_anisotropy).map_err(invalid)?;
            let image = cache.image(&base.join(path), *srgb)?;
            let mip = filter.needs_mip().then(|| cache.mip(&image));
            Texture::Image(ImageTexture {
                image,
                mapping: *mapping,
                filter: *filter,
                lookup: *lookup,
                wrap: *wrap,
                scale: *scale,
                mip,
                max_anisotropy: *max_anisotropy,
                transform,
            })
        }
        TextureDesc::Checker {
            mapping,
            squares,
            colors,
            filter,
            uv,
        } => {
            let transform = uv_transform("Checker", uv).map_err(invalid)?;
            let ok = |s: f32| s.is_finite() && s > 0.0 && s <= 1e6;
            if !ok(squares.0) || !ok(squares.1) {
                return Err(invalid(format!(
                    "Checker.squares: {squares:?} must be positive and at most 1e6"
                )));
            }
            finite_non_negative(
                "Checker.colors",
                &[colors.0.to_array(), colors.1.to_array()].concat(),
            )
            .map_err(invalid)?;
            Texture::Checker(Checker {
                mapping: *mapping,
                squares: *squares,
                colors: *colors,
                filter: *filter,
                transform,
            })
        }
        TextureDesc::MeshMaterial { .. } => {
            return Err(invalid(
                "MeshMaterial: only a Mesh shape names a material".into(),
            ));
        }
        TextureDesc::UvGrid {
            mapping,
            filter,
            wrap,
            max_anisotropy,
            uv,
        } => {
            check_anisotropy("UvGrid", *max_anisotropy).map_err(invalid)?;
            let transform = uv_transform("UvGrid", uv).map_err(invalid)?;
            let image = cache.uv_grid();
            let mip = filter.needs_mip().then(|| cache.mip(&image));
            Texture::Image(ImageTexture {
                image,
                mapping: *mapping,
                filter: *filter,
                lookup: Lookup::Centred,
                wrap: *wrap,
                scale: 1.0,
                mip,
                max_anisotropy: *max_anisotropy,
                transform,
            })
        }
    })
}

/// The runtime (u, v) transform (`None` for the identity); the scale must be finite and at
/// least 1e-6 in size on both axes, the rest finite.
fn uv_transform(what: &str, t: &UvTransform) -> std::result::Result<Option<UvAffine>, String> {
    let ok = |s: f32| s.is_finite() && s.abs() >= 1e-6 && s.abs() <= 1e6;
    if !ok(t.scale.x) || !ok(t.scale.y) {
        return Err(format!(
            "{what}.uv.scale: {} must be non-zero, between 1e-6 and 1e6 in size",
            t.scale
        ));
    }
    if !t.rotate.is_finite() || !t.offset.is_finite() {
        return Err(format!("{what}.uv: rotate and offset must be finite"));
    }
    Ok(t.affine())
}

fn check_anisotropy(what: &str, a: f32) -> std::result::Result<(), String> {
    if (1.0..=MAX_ANISOTROPY_LIMIT).contains(&a) {
        Ok(())
    } else {
        Err(format!(
            "{what}.max_anisotropy: {a} is out of range (1 to {MAX_ANISOTROPY_LIMIT})"
        ))
    }
}

/// Applies command-line overrides to a preset's render settings.
pub fn apply_overrides(desc: &mut SceneDesc, o: Overrides) {
    let r = &mut desc.render;
    r.width = o.width.unwrap_or(r.width);
    r.height = o.height.unwrap_or(r.height);
    r.spp = o.spp.unwrap_or(r.spp);
    r.seed = o.seed.unwrap_or(r.seed);
    r.sampler = o.sampler.unwrap_or(r.sampler);
    r.pixel_filter = o.pixel_filter.unwrap_or(r.pixel_filter);
    r.view = o.view.unwrap_or(r.view);
    if o.no_adaptive {
        r.adaptive = None;
    }
    if let Some(a) = o.adaptive {
        r.adaptive = Some(a);
    }
    for obj in &mut desc.objects {
        let alpha = obj.alpha.as_mut().and_then(ScalarDesc::texture_mut);
        let bump = obj.bump.as_mut().map(|b| &mut b.height);
        let normal = obj.normal.as_mut().map(|n| &mut n.map);
        let displace = obj.displace.as_mut().map(|d| &mut d.height);
        for t in obj
            .material
            .textures_mut()
            .into_iter()
            .chain(alpha)
            .chain(bump)
            .chain(normal)
            .chain(displace)
        {
            match t {
                TextureDesc::Image {
                    filter,
                    max_anisotropy,
                    ..
                }
                | TextureDesc::UvGrid {
                    filter,
                    max_anisotropy,
                    ..
                }
                | TextureDesc::MeshMaterial {
                    filter,
                    max_anisotropy,
                    ..
                } => {
                    *filter = o.filter.unwrap_or(*filter);
                    *max_anisotropy = o.max_anisotropy.unwrap_or(*max_anisotropy);
                }
                TextureDesc::Checker { filter, .. } => *filter = o.filter.unwrap_or(*filter),
                TextureDesc::Constant(_) => {}
            }
        }
    }
}
