//! The page's side of its render workers: which scene each worker has built, which chunks of
//! tiles each is rendering, and the answers waiting for their render. A [`SlicedRender`]
//! (super::SlicedRender) asks the farm for free workers, hands them chunks, and takes back the
//! rows they rendered; the page's glue passes the workers' messages in ([`Farm::receive`]).
//!
//! A scene reaches a worker as its preset's text and the files it names ([`SceneSource`],
//! recorded by [`describe`] when the window builds the scene), so every worker builds its own
//! copy with its own asset cache: no memory is shared, so no cross-origin isolation is needed.

use super::protocol::{Chunk, FromWorker, SentFile, TileRows, ToWorker, decode, encode};
use crate::scene::{Scene, SceneDesc, SimdMode, asset_paths, to_ron};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Weak};

/// How long a chunk should take a worker: long enough that messages cost little beside it,
/// short enough that an edit's cancellation waits no longer than this for the chunk under way.
pub const CHUNK_MILLIS: f64 = 12.0;
/// Chunks a worker holds at once: one rendering, one waiting, so it never idles on the page.
pub const IN_FLIGHT: usize = 2;
/// The most tiles in one chunk.
pub const MAX_CHUNK_TILES: u32 = 16;
/// The largest file sent to a worker (the scene's loaders bound what they read far below this).
const MAX_SENT_FILE: u64 = 1 << 30;

/// What a worker needs to build a scene the window built.
#[derive(Debug)]
pub struct SceneSource {
    /// The scene's number (unique in the page).
    pub id: u64,
    /// The scene built.
    scene: Weak<Scene>,
    /// The preset's text.
    pub ron: String,
    /// The preset's path.
    pub path: PathBuf,
    /// The primary rays' path.
    pub simd: SimdMode,
    /// The files the preset names.
    pub files: Vec<PathBuf>,
}

thread_local! {
    static SOURCES: RefCell<Vec<Arc<SceneSource>>> = const { RefCell::new(Vec::new()) };
    static NEXT_ID: std::cell::Cell<u64> = const { std::cell::Cell::new(1) };
}

/// Records that `scene` was built from `desc` read as if from `path`: its renders can then run
/// on the workers (a scene not described renders on the page's thread).
pub fn describe(scene: &Arc<Scene>, desc: &SceneDesc, path: &Path) {
    let folder = path.parent().unwrap_or(Path::new(""));
    let id = NEXT_ID.with(|n| {
        let id = n.get();
        n.set(id + 1);
        id
    });
    let source = Arc::new(SceneSource {
        id,
        scene: Arc::downgrade(scene),
        ron: to_ron(desc),
        path: path.to_path_buf(),
        simd: scene.settings.simd,
        files: asset_paths(desc, folder),
    });
    SOURCES.with(|s| {
        let mut s = s.borrow_mut();
        s.retain(|x| x.scene.strong_count() > 0);
        s.push(source);
    });
}

/// What [`describe`] recorded for `scene`.
#[must_use]
pub fn source_of(scene: &Arc<Scene>) -> Option<Arc<SceneSource>> {
    SOURCES.with(|s| {
        s.borrow()
            .iter()
            .find(|x| std::ptr::eq(x.scene.as_ptr(), Arc::as_ptr(scene)))
            .cloned()
    })
}

/// How the farm talks to one worker.
pub trait Port {
    /// Sends `message` (bytes of a [`ToWorker`]).
    fn post(&self, message: Vec<u8>);
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Build {
    Building,
    Ready,
    Failed,
}

/// A chunk a worker holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Held {
    job: u64,
    pass: u32,
    first: u32,
    tiles: u32,
}

struct Slot {
    port: Box<dyn Port>,
    alive: bool,
    scenes: HashMap<u64, Build>,
    /// The files sent, with the stamp they had.
    files: HashMap<PathBuf, u64>,
    held: Vec<Held>,
    /// Milliseconds a tile took, lately.
    tile_millis: Option<f64>,
    memory: u64,
    /// Chunks it rendered.
    chunks: u64,
}

/// An answer for a render.
#[derive(Debug, PartialEq)]
pub enum Landed {
    /// Tiles rendered: their rows.
    Rows {
        /// The pass.
        pass: u32,
        /// The first tile.
        first: u32,
        /// How many tiles.
        tiles: u32,
        /// The samples.
        rows: TileRows,
    },
    /// Tiles to render again (their worker dropped them or was lost).
    Back {
        /// The pass.
        pass: u32,
        /// The first tile.
        first: u32,
        /// How many tiles.
        tiles: u32,
    },
}

/// The workers and what they hold.
#[derive(Default)]
pub struct Farm {
    slots: Vec<Slot>,
    landed: HashMap<u64, Vec<Landed>>,
    /// Scenes sent to workers, to forget when no render uses them.
    known: Vec<(u64, Weak<Scene>)>,
    /// What went wrong in workers, for the page to report.
    errors: Vec<String>,
}

/// A number that changes when the file at `path` does (`None`: it cannot be read).
fn stamp(path: &Path) -> Option<u64> {
    #[cfg(target_arch = "wasm32")]
    return crate::input::stamp(path);
    #[cfg(not(target_arch = "wasm32"))]
    std::fs::metadata(path).ok().map(|m| {
        let t = m
            .modified()
            .ok()
            .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
            .map_or(0, |d| d.as_nanos() as u64);
        m.len() ^ t.rotate_left(17)
    })
}

impl Farm {
    /// A farm without workers.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a worker; returns its number.
    pub fn add(&mut self, port: Box<dyn Port>) -> usize {
        self.slots.push(Slot {
            port,
            alive: true,
            scenes: HashMap::new(),
            files: HashMap::new(),
            held: Vec::new(),
            tile_millis: None,
            memory: 0,
            chunks: 0,
        });
        self.slots.len() - 1
    }

    /// Each worker's memory in bytes, as it last said (after a build or a chunk; 0: not yet),
    /// the chunks it rendered, and whether it is alive.
    #[must_use]
    pub fn memory(&self) -> Vec<(u64, u64, bool)> {
        self.slots
            .iter()
            .map(|s| (s.memory, s.chunks, s.alive))
            .collect()
    }

    /// Sends `source`'s scene (and the files it names that a worker lacks) to every worker
    /// that has not got it.
    pub fn prepare(&mut self, source: &SceneSource) {
        if !self.known.iter().any(|(id, _)| *id == source.id) {
            self.known.push((source.id, source.scene.clone()));
        }
        for slot in self.slots.iter_mut().filter(|s| s.alive) {
            if slot.scenes.contains_key(&source.id) {
                continue;
            }
            let mut files = Vec::new();
            for path in &source.files {
                let Some(now) = stamp(path) else { continue };
                if slot.files.get(path) == Some(&now) {
                    continue;
                }
                let Ok(bytes) = crate::input::read_input(path, MAX_SENT_FILE) else {
                    continue;
                };
                slot.files.insert(path.clone(), now);
                files.push(SentFile {
                    path: path.to_string_lossy().into_owned(),
                    bytes,
                });
            }
            if !files.is_empty() {
                slot.port.post(encode(&ToWorker::Files(files)));
            }
            slot.port.post(encode(&ToWorker::Build {
                scene: source.id,
                path: source.path.to_string_lossy().into_owned(),
                ron: source.ron.clone(),
                simd: source.simd.to_string(),
            }));
            slot.scenes.insert(source.id, Build::Building);
        }
    }

    /// Workers that have built `scene`, whatever they hold.
    #[must_use]
    pub fn ready(&self, scene: u64) -> usize {
        self.slots
            .iter()
            .filter(|s| s.alive && s.scenes.get(&scene) == Some(&Build::Ready))
            .count()
    }

    /// Workers that have built `scene` and can take a chunk, each with the tiles its chunk
    /// should hold ([`CHUNK_MILLIS`] of work at its speed so far).
    #[must_use]
    pub fn free(&self, scene: u64) -> Vec<(usize, u32)> {
        self.slots
            .iter()
            .enumerate()
            .filter(|(_, s)| {
                s.alive && s.held.len() < IN_FLIGHT && s.scenes.get(&scene) == Some(&Build::Ready)
            })
            .map(|(i, s)| {
                let tiles = s.tile_millis.map_or(2.0, |ms| CHUNK_MILLIS / ms.max(1e-3));
                (i, (tiles.round() as u32).clamp(1, MAX_CHUNK_TILES))
            })
            .collect()
    }

    /// Hands `chunk` to worker `worker`.
    pub fn send(&mut self, worker: usize, chunk: Chunk) {
        let Some(slot) = self.slots.get_mut(worker) else {
            return;
        };
        slot.held.push(Held {
            job: chunk.job,
            pass: chunk.pass,
            first: chunk.first,
            tiles: chunk.tiles,
        });
        slot.port.post(encode(&ToWorker::Render(chunk)));
    }

    /// Takes worker `worker`'s message `bytes`.
    ///
    /// # Errors
    /// The bytes are not a worker's message.
    pub fn receive(&mut self, worker: usize, bytes: &[u8]) -> Result<(), String> {
        let message = decode::<FromWorker>(bytes)?;
        let Some(slot) = self.slots.get_mut(worker) else {
            return Ok(());
        };
        match message {
            FromWorker::Built {
                scene,
                error,
                memory,
            } => {
                slot.memory = memory;
                let state = match error {
                    // The page built the same text: a worker that cannot is left out of this
                    // scene (the page's thread or the other workers render it).
                    Some(e) => {
                        self.errors
                            .push(format!("a render worker could not build the scene: {e}"));
                        Build::Failed
                    }
                    None => Build::Ready,
                };
                if let Some(b) = slot.scenes.get_mut(&scene) {
                    *b = state;
                }
            }
            FromWorker::Rendered {
                job,
                pass,
                first,
                tiles,
                rows,
                micros,
                memory,
            } => {
                slot.memory = memory;
                let held = Held {
                    job,
                    pass,
                    first,
                    tiles,
                };
                // A chunk no longer held was cancelled: its rows are dropped.
                if let Some(i) = slot.held.iter().position(|h| *h == held) {
                    slot.held.remove(i);
                    slot.chunks += 1;
                    let ms = micros as f64 / 1e3 / f64::from(tiles.max(1));
                    slot.tile_millis = Some(slot.tile_millis.map_or(ms, |m| 0.7 * m + 0.3 * ms));
                    let landed = if rows.is_whole() {
                        Landed::Rows {
                            pass,
                            first,
                            tiles,
                            rows,
                        }
                    } else {
                        Landed::Back { pass, first, tiles }
                    };
                    self.landed.entry(job).or_default().push(landed);
                }
            }
            FromWorker::Skipped {
                job,
                pass,
                first,
                tiles,
            } => {
                let held = Held {
                    job,
                    pass,
                    first,
                    tiles,
                };
                if let Some(i) = slot.held.iter().position(|h| *h == held) {
                    slot.held.remove(i);
                    self.landed
                        .entry(job)
                        .or_default()
                        .push(Landed::Back { pass, first, tiles });
                }
            }
        }
        Ok(())
    }

    /// Worker `worker` stopped (it crashed): its chunks go back to their renders.
    pub fn lost(&mut self, worker: usize) {
        let Some(slot) = self.slots.get_mut(worker) else {
            return;
        };
        slot.alive = false;
        for h in std::mem::take(&mut slot.held) {
            self.landed.entry(h.job).or_default().push(Landed::Back {
                pass: h.pass,
                first: h.first,
                tiles: h.tiles,
            });
        }
    }

    /// What went wrong in the workers since the last call (a scene that would not build there).
    pub fn take_errors(&mut self) -> Vec<String> {
        std::mem::take(&mut self.errors)
    }

    /// The answers for render `job` since the last call.
    pub fn take(&mut self, job: u64) -> Vec<Landed> {
        self.landed.remove(&job).unwrap_or_default()
    }

    /// Render `job` stopped: its chunks still waiting in workers are dropped there, and what
    /// they send back for it is ignored.
    pub fn cancel(&mut self, job: u64) {
        self.landed.remove(&job);
        for slot in self.slots.iter_mut().filter(|s| s.alive) {
            let before = slot.held.len();
            slot.held.retain(|h| h.job != job);
            if slot.held.len() != before {
                slot.port.post(encode(&ToWorker::Cancel { job }));
            }
        }
    }

    /// Tells the workers to drop the scenes no render uses any more.
    pub fn forget_unused(&mut self) {
        let gone: Vec<u64> = self
            .known
            .iter()
            .filter(|(_, w)| w.strong_count() == 0)
            .map(|(id, _)| *id)
            .collect();
        if gone.is_empty() {
            return;
        }
        self.known.retain(|(id, _)| !gone.contains(id));
        for slot in self.slots.iter_mut().filter(|s| s.alive) {
            for id in &gone {
                if slot.scenes.remove(id).is_some() {
                    slot.port.post(encode(&ToWorker::Forget { scene: *id }));
                }
            }
        }
    }
}
