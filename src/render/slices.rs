//! Rendering without threads, in slices between frames: the page's way (wasm32 has no threads
//! unless built with atomics and served cross-origin isolated).
//!
//! [`SlicedRender`] is a render job's work cut at tile boundaries: each [`SlicedRender::step`]
//! renders tiles until its deadline, so a frame spends a few milliseconds on the render and the
//! page never freezes. Its passes are [`render_scheduled_pass`](super::render_scheduled_pass)'s,
//! tile for tile, so the film is the threaded job's bit for bit (the tests below compare them).
//! On wasm32, [`RenderJob`](super::RenderJob)s and [`Task`](super::Task)s register here and
//! [`run_slices`] (called once per frame by the web entry point) runs them: queued tasks whole,
//! then the renders' tiles until the frame's budget is spent.

use super::job::{Generation, Progress, RenderOptions, Shared};
use super::{
    Film, PREVIEW_BLOCKS, PassPixels, pass_pixels, render_preview, render_tiles_with, tile_count,
};
use crate::math::DisplayImage;
use crate::scene::Scene;
use std::sync::Arc;
use std::time::Duration;
use web_time::Instant;

/// The finest preview block a sliced render shows: a preview is rendered whole, and a block of
/// 2 x 2 pixels costs a quarter of a pass in one piece.
pub const SLICED_PREVIEW_MIN_BLOCK: u32 = 4;

/// Where a sliced render is.
#[derive(Debug)]
enum Stage {
    /// The preview of `PREVIEW_BLOCKS[i]` is next.
    Preview(usize),
    /// Pass `pass` is under way: its pixels, the next tile, the time its tiles took.
    Pass {
        pass: u32,
        pixels: PassPixels,
        tile: usize,
        traced: Duration,
    },
    /// Finished or cancelled.
    Done,
}

/// A render job's work, resumable at every tile (see the module's documentation).
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
    /// `started_at`.
    pub(super) fn new(
        scene: Arc<Scene>,
        options: RenderOptions,
        generation: Generation,
        started_at: u64,
        out: Arc<Shared>,
    ) -> Self {
        let s = scene.settings;
        let first = if options.preview {
            Stage::Preview(0)
        } else {
            Stage::Pass {
                pass: 0,
                pixels: PassPixels::All,
                tile: 0,
                traced: Duration::ZERO,
            }
        };
        Self {
            film: Film::new(s.width, s.height),
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
        }
    }

    /// Whether the render has finished or was cancelled.
    #[must_use]
    pub fn is_done(&self) -> bool {
        matches!(self.stage, Stage::Done)
    }

    /// Renders until `deadline` (at least one preview or tile) or the end; false once done.
    pub fn step(&mut self, deadline: Instant) -> bool {
        loop {
            if self.generation.current() != self.started_at {
                self.out.lock().progress.cancelled = true;
                self.stage = Stage::Done;
            }
            match self.stage {
                Stage::Done => return false,
                Stage::Preview(i) => self.preview(i),
                Stage::Pass { .. } => self.tile(),
            }
            if Instant::now() >= deadline {
                return !self.is_done();
            }
        }
    }

    fn preview(&mut self, i: usize) {
        let Some(&block) = PREVIEW_BLOCKS.get(i) else {
            self.stage = self.pass_stage(0);
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

    /// Pass `pass`'s first stage, with its pixels chosen from the film as it is now.
    fn pass_stage(&self, pass: u32) -> Stage {
        Stage::Pass {
            pass,
            pixels: pass_pixels(&self.scene, &self.film, pass),
            tile: 0,
            traced: Duration::ZERO,
        }
    }

    /// Renders the next tile of the pass under way; publishes the image after its last.
    fn tile(&mut self) {
        let Stage::Pass {
            pass,
            ref pixels,
            tile,
            traced,
        } = self.stage
        else {
            return;
        };
        let mask = match pixels {
            PassPixels::All => None,
            PassPixels::Masked(mask, _) => Some(mask.as_slice()),
            PassPixels::None => return self.end_pass(pass, 0, traced),
        };
        let t0 = Instant::now();
        let tiles = tile..tile + 1;
        let mode = self.scene.settings.simd;
        // Not cancellable inside: a tile is the unit of cancellation, checked by `step`.
        let _ = render_tiles_with(
            &self.scene,
            &mut self.film,
            pass,
            mask,
            mode,
            tiles,
            &|| false,
        );
        let traced = traced + t0.elapsed();
        if tile + 1 < tile_count(self.film.height()) {
            if let Stage::Pass {
                tile: t, traced: d, ..
            } = &mut self.stage
            {
                *t = tile + 1;
                *d = traced;
            }
            return;
        }
        let count = match pixels {
            PassPixels::All => self.film.pixels().len(),
            PassPixels::Masked(_, n) => *n,
            PassPixels::None => 0,
        };
        self.end_pass(pass, count, traced);
    }

    /// What the threaded job does after a pass of `pixels` samples that took `dt`.
    fn end_pass(&mut self, pass: u32, pixels: usize, dt: Duration) {
        let s = self.scene.settings;
        let passes = s.max_spp();
        let p = &mut self.progress;
        self.tracing += dt;
        self.rays += pixels as f64;
        p.finished = pixels == 0 || pass + 1 >= passes;
        if pixels > 0 {
            p.spp_done = pass + 1;
            p.last_pass = dt;
            p.last_pass_pixels = pixels;
        }
        p.preview_block = None;
        p.elapsed = self.start.elapsed();
        p.rays_per_second = self.rays / self.tracing.as_secs_f64().max(1e-9);
        let image = self.film.to_display(s.exposure_scale);
        let snapshot = p.finished.then(|| Arc::new(self.film.clone()));
        let progress = *p;
        self.out.publish(image, snapshot, progress);
        self.stage = if progress.finished {
            Stage::Done
        } else {
            self.pass_stage(pass + 1)
        };
    }
}

#[cfg(target_arch = "wasm32")]
mod driver {
    use super::SlicedRender;
    use std::cell::RefCell;
    use std::collections::VecDeque;
    use std::sync::{Arc, Mutex, PoisonError, Weak};
    use std::time::Duration;
    use web_time::Instant;

    thread_local! {
        /// Tasks not run yet, oldest first.
        static QUEUE: RefCell<VecDeque<Box<dyn FnOnce()>>> = RefCell::new(VecDeque::new());
        /// Every render job alive (a dropped job's entry no longer upgrades).
        static RENDERS: RefCell<Vec<Weak<Mutex<SlicedRender>>>> = const { RefCell::new(Vec::new()) };
    }

    /// Queues a task's work for [`run_slices`].
    pub(in crate::render) fn queue(work: Box<dyn FnOnce()>) {
        QUEUE.with(|q| q.borrow_mut().push_back(work));
    }

    /// Runs the oldest queued task; false when there was none.
    pub(in crate::render) fn run_one() -> bool {
        // Out of the borrow: the work may queue more.
        let next = QUEUE.with(|q| q.borrow_mut().pop_front());
        next.map(|work| work()).is_some()
    }

    /// Registers a render for [`run_slices`].
    pub(in crate::render) fn register(render: SlicedRender) -> Arc<Mutex<SlicedRender>> {
        let render = Arc::new(Mutex::new(render));
        RENDERS.with(|r| r.borrow_mut().push(Arc::downgrade(&render)));
        render
    }

    /// Runs `render` to its end (what waiting for a job means without threads).
    pub(in crate::render) fn finish(render: &Mutex<SlicedRender>) {
        let mut r = render.lock().unwrap_or_else(PoisonError::into_inner);
        while r.step(Instant::now() + Duration::from_hours(1)) {}
    }

    /// Runs the page's background work for about `budget`: the queued tasks (scene builds,
    /// coverage passes; each runs whole), then the live renders' tiles, the time left shared
    /// between them. Returns whether work remains (the caller asks for another frame).
    pub fn run_slices(budget: Duration) -> bool {
        let deadline = Instant::now() + budget;
        while Instant::now() < deadline && run_one() {}
        let live: Vec<_> = RENDERS.with(|r| {
            let mut r = r.borrow_mut();
            r.retain(|w| w.strong_count() > 0);
            r.iter().filter_map(Weak::upgrade).collect()
        });
        let mut busy = 0;
        for (i, render) in live.iter().enumerate() {
            let mut render = render.lock().unwrap_or_else(PoisonError::into_inner);
            if render.is_done() {
                continue;
            }
            let left = deadline.saturating_duration_since(Instant::now());
            let share = left / u32::try_from(live.len() - i).unwrap_or(u32::MAX);
            busy += usize::from(render.step(Instant::now() + share));
        }
        busy > 0 || QUEUE.with(|q| !q.borrow().is_empty())
    }
}

#[cfg(target_arch = "wasm32")]
pub use driver::run_slices;
#[cfg(target_arch = "wasm32")]
pub(super) use driver::{finish, queue, register, run_one};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{RenderJob, render_blocking};

    fn earth(spp: u32, adaptive: bool) -> Scene {
        let mut desc =
            crate::scene::load_preset(std::path::Path::new("presets/earth.ron")).unwrap();
        desc.render.width = 96;
        desc.render.height = 61;
        desc.render.spp = spp;
        desc.render.adaptive = adaptive.then_some(crate::scene::AdaptiveDesc {
            max_spp: 8,
            threshold: crate::scene::DEFAULT_ADAPTIVE_THRESHOLD,
        });
        let mut assets = crate::scene::AssetCache::new();
        crate::scene::build_scene(
            &desc,
            std::path::Path::new("presets/earth.ron"),
            &mut assets,
        )
        .unwrap()
    }

    /// Steps `render` with deadlines already past: one preview or tile per step.
    fn run_in_single_tiles(render: &mut SlicedRender) -> usize {
        let mut steps = 0;
        while render.step(Instant::now()) {
            steps += 1;
        }
        steps
    }

    #[test]
    fn a_render_in_slices_is_the_render_at_once() {
        for adaptive in [false, true] {
            let scene = Arc::new(earth(3, adaptive));
            let out = Arc::new(Shared::default());
            let generation = Generation::new();
            let options = RenderOptions::default();
            let mut sliced = SlicedRender::new(scene.clone(), options, generation, 0, out.clone());
            let steps = run_in_single_tiles(&mut sliced);
            // Two previews (8 and 4), then 8 tiles of 61 rows per pass.
            assert!(steps >= 2 + 3 * 8 - 1, "{steps}");
            let p = out.lock().progress;
            assert!(p.finished && !p.cancelled);
            let whole = render_blocking(&scene, |_| {});
            let film = out.lock().film.clone().unwrap();
            assert_eq!(film.pixels(), whole.pixels(), "adaptive {adaptive}");
            let job = RenderJob::start(scene, options, &Generation::new()).unwrap();
            assert_eq!(p.spp_done, job.wait().spp_done);
        }
    }

    #[test]
    fn a_newer_generation_stops_a_sliced_render_at_the_next_tile() {
        let scene = Arc::new(earth(4, false));
        let out = Arc::new(Shared::default());
        let generation = Generation::new();
        let options = RenderOptions {
            preview: false,
            ..RenderOptions::default()
        };
        let mut sliced = SlicedRender::new(scene, options, generation.clone(), 0, out.clone());
        assert!(sliced.step(Instant::now()));
        generation.bump();
        assert!(!sliced.step(Instant::now() + Duration::from_mins(1)));
        assert!(out.lock().progress.cancelled);
        assert_eq!(out.lock().serial, 0, "nothing published");
    }
}
