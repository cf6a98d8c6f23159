//! Rendering in a page: slices between frames on the page's thread, and chunks of tiles on Web
//! Workers (wasm32 has no threads unless built with atomics and served cross-origin isolated;
//! workers need neither).
//!
//! [`SlicedRender`] is a render job's work cut at tile boundaries. A preview is rendered whole
//! on the page's thread; each pass's tiles go in chunks to the workers that have built the
//! scene ([`Farm`]: each worker its own instance of the same module, its own copy of the scene
//! built from the preset's text, [`Worker`]), and the page adds the rows they send back to
//! its film ([`TileRows::add_to`]); tiles no worker can take yet (while the workers build the
//! scene, or without workers) are rendered on the page's thread, a few milliseconds a frame
//! ([`SlicedRender::step`]). Passes are
//! [`render_scheduled_pass`](super::render_scheduled_pass)'s, tile for tile, and a pass's rows
//! go into the film only after the pass before it, so the film is the threaded job's bit for
//! bit (the tests compare them). While every pixel is sampled, the next pass's tiles are handed
//! out ahead, so no worker waits for the page between passes.
//!
//! On wasm32, [`RenderJob`](super::RenderJob)s and [`Task`](super::Task)s register here and
//! `run_slices` (called once per frame by the web entry point) runs them: queued tasks whole,
//! then the renders until the frame's budget is spent; `worker_message` takes a worker's
//! answer as it arrives.

use super::job::{Generation, Progress, RenderOptions, Shared};
use super::{
    Film, PREVIEW_BLOCKS, PassPixels, TILE_ROWS, pass_pixels, render_preview, render_tiles_with,
    tile_count,
};
use crate::math::DisplayImage;
use crate::scene::Scene;
use std::ops::Range;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;
use web_time::Instant;

mod farm;
mod protocol;
mod worker;

pub use farm::{Farm, Landed, Port, SceneSource, describe, source_of};
pub use protocol::Chunk;
#[cfg(test)]
use protocol::TileRows;
#[cfg(test)]
use protocol::{FromWorker, ToWorker};
pub use worker::Worker;

/// The finest preview block a sliced render shows: a preview is rendered whole, and a block of
/// 2 x 2 pixels costs a quarter of a pass in one piece.
pub const SLICED_PREVIEW_MIN_BLOCK: u32 = 4;

/// A pass under way: its pixels, the tiles not handed out yet, and those not in the film yet.
#[derive(Debug)]
struct PassWork {
    pass: u32,
    pixels: PassPixels,
    /// Tiles before this one are handed out (or skipped: no pixel of theirs is sampled).
    next_tile: usize,
    tiles: usize,
    /// Tiles handed out whose worker gave them back: to hand out again.
    back: Vec<Range<usize>>,
    /// Tiles whose samples are not in the film yet.
    left: usize,
    /// Rows of this pass that arrived while the pass before it was still under way.
    held: Vec<(usize, usize, protocol::TileRows)>,
    /// Per tile, whether an adaptive pass samples none of its pixels.
    empty: Vec<bool>,
    /// Tiles handed to workers and not back yet.
    out: Vec<Range<usize>>,
}

impl PassWork {
    fn new(pass: u32, pixels: PassPixels, film: &Film) -> Self {
        let tiles = tile_count(film.height());
        let rows = film.width() as usize * TILE_ROWS;
        let empty = match &pixels {
            PassPixels::Masked(mask, _) => mask
                .chunks(rows.max(1))
                .map(|t| !t.contains(&true))
                .collect(),
            _ => Vec::new(),
        };
        // Tiles an adaptive pass samples nothing of are never handed out.
        let left = if matches!(pixels, PassPixels::None) {
            0
        } else {
            tiles - empty.iter().filter(|e| **e).count()
        };
        Self {
            pass,
            pixels,
            next_tile: 0,
            tiles,
            back: Vec::new(),
            left,
            held: Vec::new(),
            empty,
            out: Vec::new(),
        }
    }

    fn is_empty_tile(&self, t: usize) -> bool {
        self.empty.get(t).copied().unwrap_or(false)
    }

    /// Whether tiles are left to hand out.
    fn has_more(&self) -> bool {
        !self.back.is_empty()
            || !matches!(self.pixels, PassPixels::None)
                && (self.next_tile..self.tiles).any(|t| !self.is_empty_tile(t))
    }

    /// Up to `n` consecutive tiles to render, or none left to hand out.
    fn take(&mut self, n: usize) -> Option<Range<usize>> {
        if let Some(r) = self.back.pop() {
            if r.len() > n {
                self.back.push(r.start + n..r.end);
                return Some(r.start..r.start + n);
            }
            return Some(r);
        }
        if matches!(self.pixels, PassPixels::None) {
            return None;
        }
        while self.next_tile < self.tiles && self.is_empty_tile(self.next_tile) {
            self.next_tile += 1;
        }
        if self.next_tile >= self.tiles {
            return None;
        }
        let start = self.next_tile;
        let mut end = start + 1;
        while end < self.tiles && end - start < n && !self.is_empty_tile(end) {
            end += 1;
        }
        self.next_tile = end;
        Some(start..end)
    }

    /// Tiles `first..first + tiles` are back from a worker (rendered or not).
    fn returned(&mut self, first: usize, tiles: usize) {
        if let Some(i) = self.out.iter().position(|r| *r == (first..first + tiles)) {
            self.out.remove(i);
        }
    }

    /// The mask over `tiles`' rows of `film`, for an adaptive pass.
    fn chunk_mask(&self, tiles: &Range<usize>, width: usize) -> Option<Vec<bool>> {
        let PassPixels::Masked(mask, _) = &self.pixels else {
            return None;
        };
        let rows = width * TILE_ROWS;
        let end = (tiles.end * rows).min(mask.len());
        Some(mask[(tiles.start * rows).min(end)..end].to_vec())
    }

    /// Pixels this pass samples.
    fn pixel_count(&self, film: &Film) -> usize {
        match &self.pixels {
            PassPixels::All => film.pixels().len(),
            PassPixels::Masked(_, n) => *n,
            PassPixels::None => 0,
        }
    }
}

/// The passes under way: the one whose samples go into the film now, and (on workers, while
/// every pixel is sampled) the next, handed out ahead so no worker waits between passes.
#[derive(Debug)]
struct Passes {
    now: PassWork,
    next: Option<PassWork>,
    /// The time the page's thread spent in this pass's tiles.
    traced: Duration,
    /// Whether a worker rendered some of this pass.
    on_workers: bool,
}

/// Where a sliced render is.
#[derive(Debug)]
enum Stage {
    /// The preview of `PREVIEW_BLOCKS[i]` is next.
    Preview(usize),
    /// Passes are under way.
    Passes(Box<Passes>),
    /// Finished or cancelled.
    Done,
}

/// What one round of a render's work did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Did {
    /// Nothing: the workers have the work.
    Nothing,
    /// Answers went into the film or chunks went out.
    Moved,
    /// The page's thread rendered a preview or a tile.
    Rendered,
}

static NEXT_JOB: AtomicU64 = AtomicU64::new(1);

/// A render job's work, resumable at every tile, on the page's thread and its workers (see the
/// module's documentation).
pub struct SlicedRender {
    scene: Arc<Scene>,
    generation: Generation,
    started_at: u64,
    out: Arc<Shared>,
    start: Instant,
    stage: Stage,
    film: Film,
    tracing: Duration,
    rays: f64,
    progress: Progress,
    /// The render's number among the workers' chunks.
    job: u64,
    /// How workers rebuild the scene (none: the page's thread renders it alone).
    source: Option<Arc<SceneSource>>,
    /// When the last pass ended (or the passes began).
    last_end: Instant,
}

impl std::fmt::Debug for SlicedRender {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SlicedRender")
            .field("stage", &self.stage)
            .field("progress", &self.progress)
            .finish_non_exhaustive()
    }
}

impl SlicedRender {
    /// The render of `scene` that publishes into `out` and stops when `generation` leaves
    /// `started_at`; with `source`, workers that rebuild the scene from it render its passes.
    pub(super) fn new(
        scene: Arc<Scene>,
        options: RenderOptions,
        generation: Generation,
        started_at: u64,
        out: Arc<Shared>,
        source: Option<Arc<SceneSource>>,
    ) -> Self {
        let s = scene.settings;
        let film = Film::new(s.width, s.height);
        let first = if options.preview {
            Stage::Preview(0)
        } else {
            Self::passes_from(0, &scene, &film, source.is_some())
        };
        Self {
            film,
            scene,
            generation,
            started_at,
            out,
            start: Instant::now(),
            stage: first,
            tracing: Duration::ZERO,
            rays: 0.0,
            progress: Progress {
                spp_target: s.max_spp(),
                ..Progress::default()
            },
            job: NEXT_JOB.fetch_add(1, Ordering::Relaxed),
            source,
            last_end: Instant::now(),
        }
    }

    /// Whether the render has finished or was cancelled.
    #[must_use]
    pub fn is_done(&self) -> bool {
        matches!(self.stage, Stage::Done)
    }

    /// Renders until `deadline` (at least one preview or tile, when the page's thread has one
    /// to render) or the end, handing tiles to `farm`'s workers and taking in what they sent
    /// back; returns whether the page's thread has work left (it asks for another frame).
    pub fn step(&mut self, deadline: Instant, farm: &mut Farm) -> bool {
        self.run(Some(deadline), farm)
    }

    /// Takes in what the workers sent back and hands them more tiles, without rendering on the
    /// page's thread (called when a worker's message arrives); returns as [`SlicedRender::step`].
    pub fn pump(&mut self, farm: &mut Farm) -> bool {
        self.run(None, farm)
    }

    fn run(&mut self, deadline: Option<Instant>, farm: &mut Farm) -> bool {
        let mut first = true;
        loop {
            if self.generation.current() != self.started_at && !self.is_done() {
                self.out.lock().progress.cancelled = true;
                farm.cancel(self.job);
                self.stage = Stage::Done;
            }
            let may_render = deadline.is_some_and(|d| first || Instant::now() < d);
            let did = match self.stage {
                Stage::Done => return false,
                Stage::Preview(_) if !may_render => Did::Nothing,
                Stage::Preview(i) => {
                    self.preview(i);
                    Did::Rendered
                }
                Stage::Passes(_) => self.advance(farm, may_render),
            };
            match did {
                Did::Nothing => return self.needs_page(farm),
                Did::Moved => {}
                Did::Rendered => first = false,
            }
        }
    }

    /// Whether the page's thread has work here: a preview, or tiles no worker can take.
    fn needs_page(&self, farm: &Farm) -> bool {
        match &self.stage {
            Stage::Done => false,
            Stage::Preview(_) => true,
            Stage::Passes(_) => self.source.as_ref().is_none_or(|s| farm.ready(s.id) == 0),
        }
    }

    fn preview(&mut self, i: usize) {
        let Some(&block) = PREVIEW_BLOCKS.get(i) else {
            self.stage = Self::passes_from(0, &self.scene, &self.film, self.source.is_some());
            self.last_end = Instant::now();
            return;
        };
        self.stage = Stage::Preview(i + 1);
        if block < SLICED_PREVIEW_MIN_BLOCK {
            return;
        }
        let s = self.scene.settings;
        // Not cancellable inside: a preview is a small fraction of a pass.
        let Ok(pixels) = render_preview(&self.scene, block, &|| false) else {
            return;
        };
        self.progress.preview_block = Some(block);
        self.progress.elapsed = self.start.elapsed();
        let image = DisplayImage::from_linear(s.width, s.height, &pixels, s.exposure_scale);
        self.out.publish(image, None, self.progress);
    }

    /// The passes from `pass`: its pixels chosen from the film as it is now, and the next one
    /// handed out ahead when workers render and it samples every pixel.
    fn passes_from(pass: u32, scene: &Scene, film: &Film, workers: bool) -> Stage {
        let now = PassWork::new(pass, pass_pixels(scene, film, pass), film);
        Stage::Passes(Box::new(Passes {
            next: Self::ahead(pass + 1, scene, film, workers),
            now,
            traced: Duration::ZERO,
            on_workers: false,
        }))
    }

    /// Pass `pass`, to hand out before the one before it is in the film: only while every
    /// pixel is sampled (an adaptive pass's pixels depend on the film).
    fn ahead(pass: u32, scene: &Scene, film: &Film, workers: bool) -> Option<PassWork> {
        (workers && pass < scene.settings.spp && pass < scene.settings.max_spp())
            .then(|| PassWork::new(pass, PassPixels::All, film))
    }

    /// One round of the passes' work: answers in, a finished pass published, chunks out, and
    /// (when `may_render` and no worker has the scene) one tile on the page's thread.
    fn advance(&mut self, farm: &mut Farm, may_render: bool) -> Did {
        let width = self.film.width() as usize;
        let rows = width * TILE_ROWS;
        let Stage::Passes(p) = &mut self.stage else {
            return Did::Nothing;
        };
        let mut did = Did::Nothing;
        for landed in farm.take(self.job) {
            did = Did::Moved;
            match landed {
                Landed::Rows {
                    pass,
                    first,
                    tiles,
                    rows: r,
                } => {
                    let (first, tiles) = (first as usize, tiles as usize);
                    if pass == p.now.pass {
                        p.now.returned(first, tiles);
                        r.add_to(&mut self.film, first * rows);
                        p.now.left -= tiles.min(p.now.left);
                    } else if let Some(next) = p.next.as_mut().filter(|n| n.pass == pass) {
                        next.returned(first, tiles);
                        next.held.push((first, tiles, r));
                    }
                }
                Landed::Back { pass, first, tiles } => {
                    let range = first as usize..(first + tiles) as usize;
                    for work in std::iter::once(&mut p.now).chain(p.next.as_mut()) {
                        if work.pass == pass {
                            work.returned(range.start, range.len());
                            work.back.push(range.clone());
                        }
                    }
                }
            }
        }
        if p.now.left == 0 {
            self.end_pass();
            return Did::Moved;
        }
        if let Some(source) = &self.source {
            farm.prepare(source);
            for (worker, n) in farm.free(source.id) {
                let work = if p.now.has_more() {
                    &mut p.now
                } else {
                    match p.next.as_mut().filter(|n| n.has_more()) {
                        Some(next) => next,
                        None => break,
                    }
                };
                let Some(range) = work.take(n as usize) else {
                    break;
                };
                work.out.push(range.clone());
                let chunk = Chunk {
                    job: self.job,
                    scene: source.id,
                    pass: work.pass,
                    first: range.start as u32,
                    tiles: range.len() as u32,
                    mask: work.chunk_mask(&range, width),
                };
                farm.send(worker, chunk);
                p.on_workers = true;
                did = Did::Moved;
            }
        }
        let ready = self.source.as_ref().map_or(0, |s| farm.ready(s.id));
        if may_render
            && ready == 0
            && let Some(tiles) = p.now.take(1)
        {
            let mask = match &p.now.pixels {
                PassPixels::Masked(mask, _) => Some(mask.as_slice()),
                _ => None,
            };
            let t0 = Instant::now();
            // Not cancellable inside: a tile is the unit of cancellation, checked by `run`.
            let _ = render_tiles_with(
                &self.scene,
                &mut self.film,
                p.now.pass,
                mask,
                self.scene.settings.simd,
                tiles.clone(),
                &|| false,
            );
            p.traced += t0.elapsed();
            p.now.left -= tiles.len().min(p.now.left);
            return Did::Rendered;
        }
        did
    }

    /// What the threaded job does after a pass: the progress, the image published, the next
    /// pass (with the rows of it that arrived ahead added to the film).
    fn end_pass(&mut self) {
        let Stage::Passes(p) = std::mem::replace(&mut self.stage, Stage::Done) else {
            return;
        };
        let Passes {
            now,
            next,
            traced,
            on_workers,
        } = *p;
        let pass = now.pass;
        let pixels = now.pixel_count(&self.film);
        // On workers the pass took the time since the last one ended (they render in
        // parallel, and ahead); on the page's thread alone, the time in its tiles.
        let wall = self.last_end.elapsed();
        self.last_end = Instant::now();
        let dt = if on_workers { wall } else { traced };
        let s = self.scene.settings;
        let passes = s.max_spp();
        let pr = &mut self.progress;
        self.tracing += dt;
        self.rays += pixels as f64;
        pr.finished = pixels == 0 || pass + 1 >= passes;
        if pixels > 0 {
            pr.spp_done = pass + 1;
            pr.last_pass = dt;
            pr.last_pass_pixels = pixels;
        }
        pr.preview_block = None;
        pr.elapsed = self.start.elapsed();
        pr.rays_per_second = self.rays / self.tracing.as_secs_f64().max(1e-9);
        let image = self.film.to_display(s.exposure_scale);
        let snapshot = pr.finished.then(|| Arc::new(self.film.clone()));
        let progress = *pr;
        self.out.publish(image, snapshot, progress);
        if progress.finished {
            return;
        }
        let workers = self.source.is_some();
        let rows = self.film.width() as usize * TILE_ROWS;
        self.stage = match next {
            Some(mut now) => {
                for (first, tiles, r) in std::mem::take(&mut now.held) {
                    r.add_to(&mut self.film, first * rows);
                    now.left -= tiles.min(now.left);
                }
                Stage::Passes(Box::new(Passes {
                    next: Self::ahead(now.pass + 1, &self.scene, &self.film, workers),
                    now,
                    traced: Duration::ZERO,
                    on_workers,
                }))
            }
            None => Self::passes_from(pass + 1, &self.scene, &self.film, workers),
        };
    }
}

impl SlicedRender {
    /// Takes every tile back from the workers, to render the rest on the page's thread alone.
    #[cfg_attr(not(target_arch = "wasm32"), allow(dead_code))]
    fn reclaim(&mut self) {
        self.source = None;
        if let Stage::Passes(p) = &mut self.stage {
            for work in std::iter::once(&mut p.now).chain(p.next.as_mut()) {
                let out = std::mem::take(&mut work.out);
                work.back.extend(out);
            }
        }
    }
}

impl Drop for SlicedRender {
    fn drop(&mut self) {
        // Its chunks still in workers are dropped there (the page's driver tells them).
        #[cfg(target_arch = "wasm32")]
        driver::dropped(self.job);
    }
}

#[cfg(target_arch = "wasm32")]
mod driver;
#[cfg(target_arch = "wasm32")]
pub use driver::{
    add_worker, run_slices, worker_errors, worker_lost, worker_memory, worker_message,
};
#[cfg(target_arch = "wasm32")]
pub(super) use driver::{finish, queue, queue_after, register, run_one};

#[cfg(test)]
mod tests;
