//! A render job, the one owner of a progressive render's lifecycle: a task on the shared worker
//! pool runs preview passes, then one-sample passes until the target, publishing a display image
//! after each; bumping a generation counter cancels it within one tile, and dropping the job
//! cancels it without blocking the caller.

use super::pool::PoolError;
#[cfg(target_arch = "wasm32")]
use super::slices::{self, SlicedRender};
use super::{DisplayImage, Film};
#[cfg(not(target_arch = "wasm32"))]
use super::{PREVIEW_BLOCKS, pool::thread_pool, render_preview, render_scheduled_pass, task::Task};
use crate::scene::Scene;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::Duration;
#[cfg(not(target_arch = "wasm32"))]
use web_time::Instant;

/// A shared counter: a job runs while the counter equals the value it started with. An edit
/// bumps it, and stale work stops within one tile.
#[derive(Clone, Debug, Default)]
pub struct Generation(Arc<AtomicU64>);

impl Generation {
    /// A new counter at 0.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The current value: a job started now runs until the next [`Generation::bump`].
    #[must_use]
    pub fn current(&self) -> u64 {
        self.0.load(Ordering::Acquire)
    }

    /// Invalidates every running job.
    pub fn bump(&self) {
        self.0.fetch_add(1, Ordering::AcqRel);
    }
}

/// How a job runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderOptions {
    /// Worker threads (0: one per core).
    pub threads: usize,
    /// Render the coarse preview passes first.
    pub preview: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            threads: 0,
            preview: true,
        }
    }
}

/// What a job has done so far.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Progress {
    /// Full-resolution passes done (samples per pixel where every pixel is sampled; adaptive
    /// passes sample only some pixels).
    pub spp_done: u32,
    /// Most passes: the target samples per pixel, or the adaptive `max_spp`.
    pub spp_target: u32,
    /// Pixels sampled by the last pass (all of them, except in adaptive passes).
    pub last_pass_pixels: usize,
    /// Block size of the last preview shown, while no full pass is done yet.
    pub preview_block: Option<u32>,
    /// Duration of the last full pass.
    pub last_pass: Duration,
    /// Time since the job started.
    pub elapsed: Duration,
    /// Primary rays per second over the full passes so far.
    pub rays_per_second: f64,
    /// All passes done.
    pub finished: bool,
    /// Stopped by a newer generation.
    pub cancelled: bool,
}

#[derive(Default)]
pub(super) struct Published {
    image: Option<Arc<DisplayImage>>,
    pub(super) film: Option<Arc<Film>>,
    pub(super) progress: Progress,
    pub(super) serial: u64,
    /// Called after each publication (a viewer asking for a repaint).
    on_publish: Option<Arc<dyn Fn() + Send + Sync>>,
}

/// What a job and its viewers share: the published state.
#[derive(Default)]
pub(super) struct Shared {
    published: Mutex<Published>,
}

impl Shared {
    pub(super) fn lock(&self) -> MutexGuard<'_, Published> {
        self.published
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// Publishes `image` (and `film`, when given) with `progress`, and tells the viewer.
    pub(super) fn publish(&self, image: DisplayImage, film: Option<Arc<Film>>, progress: Progress) {
        let mut p = self.lock();
        p.image = Some(Arc::new(image));
        if film.is_some() {
            p.film = film;
        }
        p.progress = progress;
        p.serial += 1;
        let notify = p.on_publish.clone();
        drop(p);
        if let Some(f) = notify {
            f();
        }
    }
}

/// A progressive render running as a [`Task`](super::Task) on the shared worker pool
/// ([`thread_pool`](super::thread_pool)); on wasm32, in slices between the page's frames
/// (`render::run_slices`).
///
/// Dropping a job cancels it without waiting: its task notices within one tile and returns, and
/// everything it writes belongs to the job's shared state. [`RenderJob::wait`] and
/// [`RenderJob::film_when_done`] block until the task has returned; do not call them from a
/// worker of the same pool.
pub struct RenderJob {
    shared: Arc<Shared>,
    #[cfg(not(target_arch = "wasm32"))]
    task: Task<()>,
    #[cfg(target_arch = "wasm32")]
    slices: Arc<Mutex<SlicedRender>>,
    generation: Generation,
    started_at: u64,
}

impl RenderJob {
    /// Starts rendering `scene` on the pool of `options.threads` workers. The job stops when
    /// done or when `generation` moves on.
    ///
    /// # Errors
    /// The worker pool could not be had (too many threads asked for, or the OS refused them).
    pub fn start(
        scene: Arc<Scene>,
        options: RenderOptions,
        generation: &Generation,
    ) -> Result<Self, PoolError> {
        let shared = Arc::new(Shared::default());
        let started_at = generation.current();
        let (task_shared, task_generation) = (shared.clone(), generation.clone());
        #[cfg(not(target_arch = "wasm32"))]
        let task = {
            let pool = thread_pool(options.threads)?;
            // The job stops on its generation, not on the task's flag.
            Task::spawn_on(&pool, move |_| {
                run(&scene, options, &task_generation, started_at, &task_shared);
                Some(())
            })
        };
        // On the page's workers when the window described how the scene was built
        // (`render::describe_scene`), else on the page's thread alone.
        #[cfg(target_arch = "wasm32")]
        let slices = {
            let source = slices::source_of(&scene);
            slices::register(SlicedRender::new(
                scene,
                options,
                task_generation,
                started_at,
                task_shared,
                source,
            ))
        };
        Ok(Self {
            shared,
            #[cfg(not(target_arch = "wasm32"))]
            task,
            #[cfg(target_arch = "wasm32")]
            slices,
            generation: generation.clone(),
            started_at,
        })
    }

    /// Progress so far.
    #[must_use]
    pub fn progress(&self) -> Progress {
        self.shared.lock().progress
    }

    /// Why the job stopped without finishing, other than cancellation (a renderer bug).
    #[must_use]
    pub fn failure(&self) -> Option<String> {
        // A bug in the renderer, reported to the viewer instead of aborting the process.
        #[cfg(not(target_arch = "wasm32"))]
        return self
            .task
            .failure()
            .map(|what| format!("the render stopped: {what}"));
        // A panic aborts a wasm32 page: there is nothing to report.
        #[cfg(target_arch = "wasm32")]
        None
    }

    /// The latest display image and a serial number that changes whenever a new one is
    /// published (so a viewer uploads only new images).
    #[must_use]
    pub fn image(&self) -> Option<(Arc<DisplayImage>, u64)> {
        let p = self.shared.lock();
        p.image.clone().map(|i| (i, p.serial))
    }

    /// The accumulated film after the last full pass (for metrics and saving).
    #[must_use]
    pub fn film(&self) -> Option<Arc<Film>> {
        self.shared.lock().film.clone()
    }

    /// Calls `f` (on a render thread) after each image the job publishes from now on, and at
    /// once if one is already published: a viewer repaints when there is something new instead
    /// of polling for it.
    pub fn on_publish(&self, f: impl Fn() + Send + Sync + 'static) {
        let f: Arc<dyn Fn() + Send + Sync> = Arc::new(f);
        let published = {
            let mut p = self.shared.lock();
            p.on_publish = Some(f.clone());
            p.serial > 0
        };
        if published {
            f();
        }
    }

    /// Stops this job (and any other of the same generation).
    pub fn cancel(&self) {
        if self.generation.current() == self.started_at {
            self.generation.bump();
        }
    }

    fn wait_for_task(&self) {
        #[cfg(not(target_arch = "wasm32"))]
        self.task.wait();
        #[cfg(target_arch = "wasm32")]
        slices::finish(&self.slices);
    }

    /// Waits for the job to finish or stop and returns the final film (`None` if cancelled).
    #[must_use]
    pub fn film_when_done(self) -> Option<Arc<Film>> {
        self.wait_for_task();
        self.film()
    }

    /// Waits for the job to finish or stop.
    #[must_use]
    pub fn wait(self) -> Progress {
        self.wait_for_task();
        self.progress()
    }
}

impl Drop for RenderJob {
    fn drop(&mut self) {
        self.cancel();
    }
}

#[cfg(not(target_arch = "wasm32"))]
fn run(
    scene: &Scene,
    options: RenderOptions,
    generation: &Generation,
    started_at: u64,
    out: &Shared,
) {
    let start = Instant::now();
    let cancelled = || generation.current() != started_at;
    let s = scene.settings;
    let publish = |image, film, progress| out.publish(image, film, progress);
    let mut progress = Progress {
        spp_target: s.max_spp(),
        ..Progress::default()
    };
    if options.preview {
        for block in PREVIEW_BLOCKS {
            let Ok(pixels) = render_preview(scene, block, &cancelled) else {
                out.lock().progress.cancelled = true;
                return;
            };
            progress.preview_block = Some(block);
            progress.elapsed = start.elapsed();
            publish(
                DisplayImage::from_linear(s.width, s.height, &pixels, s.exposure_scale),
                None,
                progress,
            );
        }
    }
    let mut film = Film::new(s.width, s.height);
    let mut tracing = Duration::ZERO;
    let mut rays = 0.0;
    let passes = s.max_spp();
    for pass in 0..passes {
        let t0 = Instant::now();
        let Ok(pixels) = render_scheduled_pass(scene, &mut film, pass, &cancelled) else {
            out.lock().progress.cancelled = true;
            return;
        };
        let dt = t0.elapsed();
        tracing += dt;
        rays += pixels as f64;
        // An adaptive render ends early once every pixel has converged.
        progress.finished = pixels == 0 || pass + 1 == passes;
        if pixels > 0 {
            progress.spp_done = pass + 1;
            progress.last_pass = dt;
            progress.last_pass_pixels = pixels;
        }
        progress.preview_block = None;
        progress.elapsed = start.elapsed();
        progress.rays_per_second = rays / tracing.as_secs_f64().max(1e-9);
        let image = film.to_display(s.exposure_scale);
        let snapshot = progress.finished.then(|| Arc::new(film.clone()));
        publish(image, snapshot, progress);
        if progress.finished {
            break;
        }
    }
}
