//! A render worker's side (in the page, a Web Worker running its own instance of the same
//! WebAssembly module): it mounts the files it is sent, builds each scene from its preset's text
//! with its own asset cache, and renders the chunks of tiles it is given into a film of its own,
//! answering with the chunk's rows. Chunks wait in a queue, so a [`ToWorker::Cancel`] that
//! arrives while one renders drops the render's others before they start.

use super::protocol::{Chunk, FromWorker, SentFile, TileRows, ToWorker, decode, encode};
use crate::render::{Film, TILE_ROWS, render_tiles_with, tile_count};
use crate::scene::{AssetCache, Scene, SimdMode, build_scene, parse_preset};
use std::collections::VecDeque;
use std::path::Path;
use std::sync::Arc;
use web_time::Instant;

/// The most scenes a worker keeps (the viewport's, the A/B split's three, and one being
/// replaced).
pub const KEPT_SCENES: usize = 5;

/// A worker's state.
pub struct Worker {
    cache: AssetCache,
    scenes: VecDeque<(u64, Arc<Scene>)>,
    /// The film chunks render into: zero outside a chunk being rendered.
    film: Film,
    /// An adaptive chunk's mask, over the whole film (false outside the chunk).
    mask: Vec<bool>,
    queue: VecDeque<Chunk>,
    /// The worker's memory in bytes (the page's glue knows it), reported after each build.
    memory: fn() -> u64,
}

impl Worker {
    /// A worker with nothing built; `memory` reports its memory in bytes.
    #[must_use]
    pub fn new(memory: fn() -> u64) -> Self {
        Self {
            cache: AssetCache::new(),
            scenes: VecDeque::new(),
            film: Film::new(0, 0),
            mask: Vec::new(),
            queue: VecDeque::new(),
            memory,
        }
    }

    /// Handles one message; returns the answers due at once (a build's). Chunks are queued for
    /// [`Worker::work`].
    ///
    /// # Errors
    /// The bytes are not a message.
    pub fn receive(&mut self, bytes: &[u8]) -> Result<Vec<Vec<u8>>, String> {
        let mut out = Vec::new();
        match decode::<ToWorker>(bytes)? {
            ToWorker::Files(files) => self.mount(files),
            ToWorker::Build {
                scene,
                path,
                ron,
                simd,
            } => {
                let error = self.build(scene, Path::new(&path), &ron, &simd).err();
                out.push(encode(&FromWorker::Built {
                    scene,
                    error,
                    memory: (self.memory)(),
                }));
            }
            ToWorker::Forget { scene } => self.scenes.retain(|(id, _)| *id != scene),
            ToWorker::Render(chunk) => self.queue.push_back(chunk),
            ToWorker::Cancel { job } => self.queue.retain(|c| c.job != job),
        }
        Ok(out)
    }

    /// Whether chunks are waiting.
    #[must_use]
    pub fn has_work(&self) -> bool {
        !self.queue.is_empty()
    }

    /// Renders the oldest waiting chunk; returns its answer.
    pub fn work(&mut self) -> Option<Vec<u8>> {
        let chunk = self.queue.pop_front()?;
        Some(encode(&self.render(chunk)))
    }

    #[cfg_attr(not(target_arch = "wasm32"), allow(clippy::unused_self))]
    fn mount(&mut self, files: Vec<SentFile>) {
        #[cfg(target_arch = "wasm32")]
        {
            let replaced = files
                .iter()
                .any(|f| crate::input::is_mounted(Path::new(&f.path)));
            for f in files {
                crate::input::mount(Path::new(&f.path), f.bytes);
            }
            // The cache knows a file by its path in a page: a file replaced under the same
            // path (an upload chosen again) must be read afresh.
            if replaced {
                self.cache = AssetCache::new();
            }
        }
        // Natively (the tests) the files are on disk already.
        #[cfg(not(target_arch = "wasm32"))]
        drop(files);
    }

    fn build(&mut self, id: u64, path: &Path, ron: &str, simd: &str) -> Result<(), String> {
        let desc = parse_preset(ron, path).map_err(|e| e.to_string())?;
        let mut scene = build_scene(&desc, path, &mut self.cache).map_err(|e| e.to_string())?;
        scene.settings.simd = simd
            .parse::<SimdMode>()
            .map_err(|_| format!("{simd}: not a SIMD mode"))?;
        self.scenes.retain(|(s, _)| *s != id);
        if self.scenes.len() >= KEPT_SCENES {
            self.scenes.pop_front();
        }
        self.scenes.push_back((id, Arc::new(scene)));
        Ok(())
    }

    fn render(&mut self, chunk: Chunk) -> FromWorker {
        let Chunk {
            job,
            scene,
            pass,
            first,
            tiles,
            mask,
        } = chunk;
        let skipped = FromWorker::Skipped {
            job,
            pass,
            first,
            tiles,
        };
        let Some(scene) = self
            .scenes
            .iter()
            .find(|(id, _)| *id == scene)
            .map(|(_, s)| s.clone())
        else {
            return skipped;
        };
        let (w, h) = (scene.settings.width, scene.settings.height);
        if self.film.width() != w || self.film.height() != h {
            self.film = Film::new(w, h);
            self.mask = vec![false; w as usize * h as usize];
        }
        let tiles_range = first as usize..(first + tiles) as usize;
        if tiles_range.end > tile_count(h) {
            return skipped;
        }
        let rows = w as usize * TILE_ROWS;
        let start = tiles_range.start * rows;
        let end = (tiles_range.end * rows).min(self.film.pixels().len());
        if let Some(m) = &mask {
            if m.len() != end - start {
                return skipped;
            }
            self.mask[start..end].copy_from_slice(m);
        }
        let t0 = Instant::now();
        // Not cancellable inside: a chunk is the unit of cancellation (see the module's
        // documentation).
        let _ = render_tiles_with(
            &scene,
            &mut self.film,
            pass,
            mask.as_ref().map(|_| self.mask.as_slice()),
            scene.settings.simd,
            tiles_range,
            &|| false,
        );
        let micros = u64::try_from(t0.elapsed().as_micros()).unwrap_or(u64::MAX);
        let stats = scene.settings.adaptive.is_some();
        let rows_out = TileRows::read(&self.film, start..end, stats);
        // Back to zero for the next chunk.
        let (sums, st, keys) = self.film.buffers_mut();
        sums[start..end].fill([0.0; 4]);
        st[start..end].fill([0.0; 2]);
        keys[start..end].fill(0);
        if mask.is_some() {
            self.mask[start..end].fill(false);
        }
        FromWorker::Rendered {
            job,
            pass,
            first,
            tiles,
            rows: rows_out,
            micros,
            memory: (self.memory)(),
        }
    }
}
