//! The asset cache: images, meshes, mip pyramids and displaced meshes loaded once and shared
//! between builds.

use crate::error::Result;
use crate::geometry::Mesh;
use crate::texture::{ImageData, MipPyramid, load_alpha, load_image, uv_grid_image};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Side of the generated UV test grid image.
pub const UV_GRID_SIZE: u32 = 1024;

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
    pub(super) fn displaced(&self, key: &DisplacedKey) -> Option<Arc<Mesh>> {
        self.displaced
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, m)| m.clone())
    }

    /// Keeps `mesh` as the displaced mesh of `key`, forgetting the oldest beyond
    /// [`DISPLACED_KEPT`].
    pub(super) fn keep_displaced(&mut self, key: DisplacedKey, mesh: Arc<Mesh>) {
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
