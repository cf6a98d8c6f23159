//! The asset cache: images, meshes, mip pyramids and displaced meshes loaded once and shared
//! between builds, each file known by its identity (not the path that spelled it), and the
//! scene's budget: the texels of all its images with their mip pyramids and summed-area
//! tables, and the triangles of all its displaced meshes.

use crate::error::{Error, Result};
use crate::geometry::Mesh;
use crate::geometry::displace::MAX_DISPLACED_TRIANGLES;
use crate::input::{FileId, file_id, open_input};
use crate::texture::{
    Filter, ImageData, ImageRequest, MAX_IMAGE_BYTES, MipPyramid, TablePlan, approx_bytes,
    load_opened, uv_grid_image,
};
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Side of the generated UV test grid image.
pub const UV_GRID_SIZE: u32 = 1024;

/// The texture budget of a whole scene, [`MAX_IMAGE_BYTES`] (1 GiB): the texel storage of
/// every image it reads (colours, coefficients, clip, bump, normal and displacement maps; one
/// file read twice counts once), the mip pyramids its trilinear, EWA and footprint filters read
/// (a third of an image's bytes), and the summed-area tables of its footprint filters (12 bytes
/// a texel for images within [0, 1], 24 for brighter ones, a third more for the coarser levels:
/// [`crate::texture::TablePlan`]), together. Images and pyramids must fit, or the scene is
/// refused naming the field; the tables are reserved after them, in the order the scene names
/// their textures, and a texture whose tables no longer fit is read with EWA, with a notice
/// ([`AssetCache::notices`]).
pub const MAX_SCENE_TEXEL_BYTES: u64 = MAX_IMAGE_BYTES;

/// The most triangles the displaced meshes of one scene may hold together (a displaced mesh
/// two objects share counts once): [`MAX_DISPLACED_TRIANGLES`] (4 M), about 320 MB.
pub const MAX_SCENE_DISPLACED_TRIANGLES: usize = MAX_DISPLACED_TRIANGLES;

/// An image of a file: the file, sRGB or not, colour or alpha.
type ImageKey = (FileId, bool, bool);

/// Decoded images shared between builds, so an edit in the GUI does not decode the Earth again.
#[derive(Debug, Default)]
pub struct AssetCache {
    /// Each image with the bytes its texel storage takes (counted against the scene budget).
    images: HashMap<ImageKey, (Arc<ImageData>, u64)>,
    uv_grid: Option<Arc<ImageData>>,
    meshes: HashMap<FileId, Arc<Mesh>>,
    /// Mip pyramids, built on first use by a mip filter and keyed by their base image (the
    /// cache holds every base image, so an `Arc` pointer stays a unique key), with their
    /// summed-area tables once a footprint filter's budget allowed them.
    mips: Vec<(Arc<ImageData>, Arc<MipPyramid>)>,
    /// What the last scene built said about its textures (tables it could not have).
    notices: Vec<String>,
    /// The latest displaced meshes (at most [`DISPLACED_KEPT`]), by mesh file, the folder the
    /// height texture's path is relative to, and the displacement.
    displaced: Vec<(DisplacedKey, Arc<Mesh>)>,
    /// What the scene being built has used so far (`None` outside [`AssetCache::scene`]).
    scene: Option<SceneUse>,
    /// Read images' headers only and do not subdivide (see [`AssetCache::checking`]).
    checking: bool,
    /// In a page: stand in for a shipped file not downloaded yet (see
    /// [`AssetCache::stand_in`]).
    stand_in: bool,
    /// The files stood in since [`AssetCache::take_stood_in`].
    stood_in: Vec<PathBuf>,
    /// The scene's texture budget when not [`MAX_SCENE_TEXEL_BYTES`] (tests lower it:
    /// [`AssetCache::set_texture_budget`]).
    budget: Option<u64>,
}

/// What one scene's build has taken of the budgets, each asset counted once.
#[derive(Debug, Default)]
struct SceneUse {
    /// Images, pyramids and tables built, together.
    texel_bytes: u64,
    images: HashSet<ImageKey>,
    /// The pyramids counted (each once).
    pyramids: Vec<Arc<MipPyramid>>,
    /// The pyramids whose tables a footprint filter asked for and that are not built yet, in
    /// order, with the field that asked first: reserved once the scene is built.
    tables: Vec<(Arc<MipPyramid>, String)>,
    triangles: usize,
    displaced: HashSet<DisplacedKey>,
}

/// What a displaced mesh is made from: the mesh file, the preset's folder and the displacement
/// written out (its `Debug` text, which is exact: a float prints as the shortest text that
/// reads back as it), so the cache needs no scene description type.
pub(super) type DisplacedKey = (PathBuf, PathBuf, String);

/// How many displaced meshes the cache keeps (the latest), so editing a displacement in the
/// window does not pile up copies.
pub const DISPLACED_KEPT: usize = 4;

impl AssetCache {
    /// An empty cache.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty cache that checks scenes without building them at full cost: an image's header
    /// is read and its size counted against the budget, but the image is a 1 x 1 stand-in; a
    /// displacement is counted and its height texture checked, but the mesh is not subdivided.
    /// What `lesson --list` and the Lessons panel check every experiment's scene with. Its
    /// scenes are for checking only, never for rendering.
    #[must_use]
    pub fn checking() -> Self {
        Self {
            checking: true,
            ..Self::default()
        }
    }

    /// In a page (wasm32), where a shipped image or mesh may not be downloaded yet: with `on`,
    /// the builds stand such a file in (`scene::stand_in`: a grey texel, a grey octahedron)
    /// instead of failing, and note it for [`AssetCache::take_stood_in`]; the stand-in is not
    /// kept, so the next build once the file is in reads it. A checking cache always stands
    /// them in, unnoted.
    pub fn stand_in(&mut self, on: bool) {
        self.stand_in = on;
    }

    /// The files stood in since the last call (the scene built is a stand-in's until a build
    /// without them).
    pub fn take_stood_in(&mut self) -> Vec<PathBuf> {
        std::mem::take(&mut self.stood_in)
    }

    /// Whether `path` is stood in (a shipped file not downloaded yet, with stand-ins on).
    fn stands_in(&mut self, path: &Path) -> bool {
        if !(self.checking || self.stand_in) || !crate::input::is_deferred(path) {
            return false;
        }
        if !self.checking && !self.stood_in.iter().any(|p| p == path) {
            self.stood_in.push(path.to_path_buf());
        }
        true
    }

    /// Lowers (or raises) the scene's texture budget from [`MAX_SCENE_TEXEL_BYTES`] for the
    /// scenes built from now on: tests reach its limits with small images (the window's test of
    /// the summed-area tables' warning, say).
    pub fn set_texture_budget(&mut self, bytes: u64) {
        self.budget = Some(bytes);
    }

    /// The scene's texture budget: [`MAX_SCENE_TEXEL_BYTES`] unless set otherwise.
    #[must_use]
    pub fn texture_budget(&self) -> u64 {
        self.budget.unwrap_or(MAX_SCENE_TEXEL_BYTES)
    }

    /// Whether this cache only checks (see [`AssetCache::checking`]).
    #[must_use]
    pub const fn is_checking(&self) -> bool {
        self.checking
    }

    /// Runs `build` as the build of one scene: every image, mip pyramid and displaced mesh it
    /// asks for is counted once against [`MAX_SCENE_TEXEL_BYTES`] and
    /// [`MAX_SCENE_DISPLACED_TRIANGLES`]; once it is built, the summed-area tables its
    /// footprint filters asked for are reserved in what is left and built, or refused with a
    /// notice ([`AssetCache::notices`]). Afterwards the cache keeps the images this scene read
    /// and, of the others, no more than fit in [`MAX_SCENE_TEXEL_BYTES`] with them: a window or
    /// a command going through many scenes (lessons' experiments, `snapshot update`) does not
    /// keep every image it met.
    pub(super) fn scene<T>(&mut self, build: impl FnOnce(&mut Self) -> Result<T>) -> Result<T> {
        let outer = self.scene.replace(SceneUse::default());
        let out = build(self);
        if let Some(mut used) = self.scene.take() {
            if out.is_ok() {
                self.notices = self.reserve_tables(&mut used);
            }
            self.trim(&used.images);
        }
        self.scene = outer;
        out
    }

    /// What the last scene built said about its textures: each texture whose footprint filter
    /// reads EWA because its image has no summed-area tables, and why (they did not fit the
    /// budget, or a texel is too large to sum exactly). Empty for most scenes.
    #[must_use]
    pub fn notices(&self) -> &[String] {
        &self.notices
    }

    /// Reserves and builds, in order, the tables `used` asked for, while they fit what is left
    /// of the budget; the notices for those that did not.
    fn reserve_tables(&self, used: &mut SceneUse) -> Vec<String> {
        let mut notices = Vec::new();
        for (mip, field) in std::mem::take(&mut used.tables) {
            let fallback = "the footprint filter reads it with EWA instead";
            if let Some(why) = mip.summed_area_refusal() {
                notices.push(format!("{field}: {why}; {fallback}"));
                continue;
            }
            if mip.has_summed_area() {
                continue; // built for an earlier scene, counted when asked for
            }
            let bytes = if self.checking {
                // A checked scene's images are 1 x 1 stand-ins: count the tables of the image
                // each stands for, under the plan of every 8- and 16-bit image (a float image's
                // texels are not read: above 1 they take twice this, or have no table).
                let (w, h) = mip.level(0).full_size();
                TablePlan::Narrow.table_bytes(w, h)
            } else {
                mip.table_bytes()
            };
            let left = self.texture_budget().saturating_sub(used.texel_bytes);
            if bytes > left {
                notices.push(format!(
                    "{field}: its summed-area tables need {}, above the {} left of the \
                     scene's {} texture budget (its images, mip pyramids and other tables take \
                     {}); {fallback}",
                    approx_bytes(bytes),
                    approx_bytes(left),
                    approx_bytes(self.texture_budget()),
                    approx_bytes(used.texel_bytes)
                ));
                continue;
            }
            if self.checking {
                used.texel_bytes += bytes;
                continue;
            }
            match mip.build_summed_area() {
                Ok(t) => used.texel_bytes += t.bytes() as u64,
                Err(why) => notices.push(format!("{field}: {why}; {fallback}")),
            }
        }
        notices
    }

    /// Forgets images not in `keep` (and their mip pyramids and tables) while the cache's
    /// images, pyramids and tables take more than [`MAX_SCENE_TEXEL_BYTES`].
    fn trim(&mut self, keep: &HashSet<ImageKey>) {
        let mut total: u64 = self.images.values().map(|(_, bytes)| bytes).sum::<u64>()
            + self.mips.iter().map(|(_, m)| m.extra_bytes()).sum::<u64>();
        let others: Vec<ImageKey> = self
            .images
            .keys()
            .filter(|k| !keep.contains(*k))
            .cloned()
            .collect();
        for key in others {
            if total <= self.texture_budget() {
                break;
            }
            if let Some((image, bytes)) = self.images.remove(&key) {
                total = total.saturating_sub(bytes);
                self.mips.retain(|(base, m)| {
                    let keep = !Arc::ptr_eq(base, &image);
                    if !keep {
                        total = total.saturating_sub(m.extra_bytes());
                    }
                    keep
                });
            }
        }
    }

    /// The image at `path`, decoded once per file (whatever path names it).
    ///
    /// # Errors
    /// See [`crate::texture::load_image`]; the image does not fit what is left of the scene's
    /// texture budget.
    pub fn image(&mut self, path: &Path, srgb: bool) -> Result<Arc<ImageData>> {
        self.load(path, ImageRequest::colour(srgb))
    }

    /// The alpha channel of the image at `path` as a grey image, decoded once per file.
    ///
    /// # Errors
    /// See [`crate::texture::load_alpha`]; the image does not fit what is left of the scene's
    /// texture budget.
    pub fn alpha(&mut self, path: &Path) -> Result<Arc<ImageData>> {
        self.load(path, ImageRequest::alpha())
    }

    /// The image of `path` as `req` asks, from the cache or decoded, counted against the scene.
    fn load(&mut self, path: &Path, req: ImageRequest) -> Result<Arc<ImageData>> {
        if self.stands_in(path) {
            // In a page, a shipped image not downloaded yet. A check stands it in unread (the
            // shipped lessons' scenes are checked in full by the test suite,
            // `tests/headless/lessons.rs`, and a page has no lessons of its own); a scene shows
            // the stand-in until the image is in.
            return Ok(Arc::new(super::stand_in::image(path)));
        }
        let file = open_input(path)?;
        let key = (file_id(&file, path), req.srgb, req.alpha);
        let counted = self.scene.as_ref().is_some_and(|s| s.images.contains(&key));
        let left = match &self.scene {
            Some(s) if !counted => self.texture_budget().saturating_sub(s.texel_bytes),
            _ => MAX_IMAGE_BYTES,
        };
        let (image, bytes) = if let Some((image, bytes)) = self.images.get(&key) {
            drop(file);
            if *bytes > left {
                // The message the decoder gives for the same size (read from the header again).
                let req = ImageRequest {
                    max_bytes: left,
                    header_only: true,
                    ..req
                };
                load_opened(open_input(path)?, path, req)?;
                return Err(Error::Image {
                    path: path.to_path_buf(),
                    message: format!(
                        "its texels do not fit what is left of the scene's texture budget ({left} bytes)"
                    ),
                });
            }
            (image.clone(), *bytes)
        } else {
            let req = ImageRequest {
                max_bytes: left,
                header_only: self.checking,
                ..req
            };
            let (image, bytes) = load_opened(file, path, req)?;
            let image = Arc::new(image);
            self.images.insert(key.clone(), (image.clone(), bytes));
            (image, bytes)
        };
        if let Some(s) = &mut self.scene
            && s.images.insert(key)
        {
            s.texel_bytes += bytes;
        }
        Ok(image)
    }

    /// The mesh at `path`, read and its BVH built once per file (every instance shares it).
    ///
    /// # Errors
    /// See [`crate::meshio::load_mesh`] and [`Mesh::new`].
    pub fn mesh(&mut self, path: &Path) -> Result<Arc<Mesh>> {
        if let Some(m) = self.meshes.get(&FileId::Path(path.to_path_buf())) {
            return Ok(m.clone());
        }
        if self.stands_in(path) {
            // In a page, a shipped mesh not downloaded yet: as an image, above.
            return Ok(Arc::new(super::stand_in::mesh(path)?));
        }
        let id = file_id(&open_input(path)?, path);
        if let Some(m) = self.meshes.get(&id) {
            return Ok(m.clone());
        }
        let mesh = Arc::new(Mesh::new(crate::meshio::load_mesh(path)?, path)?);
        self.meshes.insert(id, mesh.clone());
        Ok(mesh)
    }

    /// Makes `mesh` what presets naming `path` get (a generated mesh, for benchmarks).
    pub fn insert_mesh(&mut self, path: &Path, mesh: Arc<Mesh>) {
        self.meshes.insert(FileId::Path(path.to_path_buf()), mesh);
    }

    /// Counts a displaced mesh of `triangles` made for `key` against the scene's
    /// [`MAX_SCENE_DISPLACED_TRIANGLES`] (once per key).
    ///
    /// # Errors
    /// The scene's displaced meshes would hold more: the message says how many the others hold.
    pub(super) fn count_displaced(
        &mut self,
        key: &DisplacedKey,
        triangles: usize,
    ) -> std::result::Result<(), String> {
        let Some(s) = &mut self.scene else {
            return Ok(());
        };
        if s.displaced.contains(key) {
            return Ok(());
        }
        let total = s.triangles.saturating_add(triangles);
        if total > MAX_SCENE_DISPLACED_TRIANGLES {
            return Err(format!(
                "{triangles} triangles, and the scene's other displaced meshes hold {}: {total} \
                 in all, above the {MAX_SCENE_DISPLACED_TRIANGLES} (4 M) a scene may hold; use \
                 fewer levels or fewer displaced objects",
                s.triangles
            ));
        }
        s.triangles = total;
        s.displaced.insert(key.clone());
        Ok(())
    }

    /// The displaced mesh made for `key`, if one is kept.
    pub(super) fn displaced(&self, key: &DisplacedKey) -> Option<Arc<Mesh>> {
        self.displaced
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, m)| m.clone())
    }

    /// Keeps `mesh` as the displaced mesh of `key`, forgetting the oldest beyond
    /// [`DISPLACED_KEPT`].
    pub(super) fn keep_displaced(&mut self, key: DisplacedKey, mesh: Arc<Mesh>) {
        // A build that stood a file in may have displaced a stand-in (its mesh, or by its
        // height image): not kept, so the build once the file is in makes it again.
        if !self.stood_in.is_empty() {
            return;
        }
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

    /// The mip pyramid of `image` for a texture read with `filter`, built once and counted
    /// once against the scene's budget; for [`Filter::Footprint`], its summed-area tables are
    /// asked for too (for the texture at `field`): reserved and built once the scene is built,
    /// if they fit (the scene build, `AssetCache::scene`).
    ///
    /// # Errors
    /// The pyramid (or tables built for an earlier scene, which it keeps) does not fit what is
    /// left of the scene's budget: the message says how much it needs and what is left.
    pub fn mip(
        &mut self,
        image: &Arc<ImageData>,
        filter: Filter,
        field: &str,
    ) -> std::result::Result<Arc<MipPyramid>, String> {
        let found = self
            .mips
            .iter()
            .find(|(i, _)| Arc::ptr_eq(i, image))
            .map(|(_, m)| m.clone());
        let counted = self.scene.as_ref().is_some_and(|s| {
            found
                .as_ref()
                .is_some_and(|m| s.pyramids.iter().any(|p| Arc::ptr_eq(p, m)))
        });
        // A stand-in (a checking cache) is 1 x 1: the pyramid it stands for is a third of the
        // image's bytes.
        let stood_for = self.checking.then(|| self.image_bytes(image).div_ceil(3));
        if !counted && let Some(s) = &self.scene {
            let bytes = match (&found, stood_for) {
                (_, Some(bytes)) => bytes,
                (Some(m), None) => m.extra_bytes(),
                (None, None) => MipPyramid::planned_bytes(image),
            };
            let left = self.texture_budget().saturating_sub(s.texel_bytes);
            if bytes > left {
                return Err(format!(
                    "{filter:?} reads a mip pyramid of {}: {} (with any summed-area tables already \
                     built), above the {} left of the scene's {} texture budget (its images, mip \
                     pyramids and tables take {}); use Bilinear, or fewer or smaller images",
                    image.name,
                    approx_bytes(bytes),
                    approx_bytes(left),
                    approx_bytes(self.texture_budget()),
                    approx_bytes(s.texel_bytes)
                ));
            }
        }
        let m = found.unwrap_or_else(|| {
            let m = Arc::new(MipPyramid::build(image.clone()));
            self.mips.push((image.clone(), m.clone()));
            m
        });
        if let Some(s) = &mut self.scene {
            if !counted {
                s.texel_bytes += stood_for.unwrap_or_else(|| m.extra_bytes());
                s.pyramids.push(m.clone());
            }
            if filter == Filter::Footprint && !s.tables.iter().any(|(p, _)| Arc::ptr_eq(p, &m)) {
                s.tables.push((m.clone(), field.to_owned()));
            }
        } else if filter == Filter::Footprint {
            // Outside a scene's build (a tool's own texture): no budget to reserve in.
            let _ = m.build_summed_area();
        }
        Ok(m)
    }

    /// The bytes `image` was counted with (its decoded storage; a stand-in's full image's).
    fn image_bytes(&self, image: &Arc<ImageData>) -> u64 {
        self.images
            .values()
            .find(|(i, _)| Arc::ptr_eq(i, image))
            .map_or(image.storage_bytes() as u64, |(_, b)| *b)
    }

    /// How many mip pyramids have been built (each at most once).
    #[must_use]
    pub fn mip_count(&self) -> usize {
        self.mips.len()
    }

    /// How many images have been decoded (each file once per colour space and channel).
    #[must_use]
    pub fn image_count(&self) -> usize {
        self.images.len()
    }
}
