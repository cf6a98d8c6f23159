//! A render job on its own thread: preview passes, then one-sample passes until the target,
//! publishing a display image after each; cancelled at once by bumping a generation counter.

use super::{DisplayImage, Film, PREVIEW_BLOCKS, render_preview, render_scheduled_pass};
use crate::scene::Scene;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

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

    /// The current value.
    #[must_use]
    pub fn current(&self) -> u64 {
        self.0.load(Ordering::Acquire)
    }

    /// Invalidates every running job; returns the new value.
    pub fn bump(&self) -> u64 {
        self.0.fetch_add(1, Ordering::AcqRel) + 1
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
struct Published {
    image: Option<Arc<DisplayImage>>,
    film: Option<Arc<Film>>,
    progress: Progress,
    serial: u64,
}

/// A progressive render running on a background thread.
pub struct RenderJob {
    published: Arc<Mutex<Published>>,
    generation: Generation,
    started_at: u64,
    handle: Option<JoinHandle<()>>,
}

fn lock(m: &Mutex<Published>) -> MutexGuard<'_, Published> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

impl RenderJob {
    /// Starts rendering `scene`. The job stops when done or when `generation` moves on.
    #[must_use]
    pub fn start(scene: Arc<Scene>, options: RenderOptions, generation: &Generation) -> Self {
        let published = Arc::new(Mutex::new(Published::default()));
        let started_at = generation.current();
        let (pub2, gen2) = (published.clone(), generation.clone());
        let handle = std::thread::Builder::new()
            .name("texplore-render".into())
            .spawn(move || run(&scene, options, &gen2, started_at, &pub2))
            .ok();
        Self {
            published,
            generation: generation.clone(),
            started_at,
            handle,
        }
    }

    /// Progress so far.
    #[must_use]
    pub fn progress(&self) -> Progress {
        lock(&self.published).progress
    }

    /// The latest display image and a serial number that changes whenever a new one is
    /// published (so a viewer uploads only new images).
    #[must_use]
    pub fn image(&self) -> Option<(Arc<DisplayImage>, u64)> {
        let p = lock(&self.published);
        p.image.clone().map(|i| (i, p.serial))
    }

    /// The accumulated film after the last full pass (for metrics and saving).
    #[must_use]
    pub fn film(&self) -> Option<Arc<Film>> {
        lock(&self.published).film.clone()
    }

    /// Stops this job (and any other of the same generation).
    pub fn cancel(&self) {
        if self.generation.current() == self.started_at {
            self.generation.bump();
        }
    }

    /// Waits for the job to finish or stop and returns the final film (`None` if cancelled).
    #[must_use]
    pub fn film_when_done(mut self) -> Option<Arc<Film>> {
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
        self.film()
    }

    /// Waits for the job to finish or stop.
    pub fn wait(mut self) -> Progress {
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
        self.progress()
    }
}

impl Drop for RenderJob {
    fn drop(&mut self) {
        self.cancel();
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

fn run(
    scene: &Scene,
    options: RenderOptions,
    generation: &Generation,
    started_at: u64,
    out: &Mutex<Published>,
) {
    let start = Instant::now();
    let cancelled = || generation.current() != started_at;
    let s = scene.settings;
    let pool = match rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()
    {
        Ok(p) => p,
        Err(_) => return,
    };
    let publish = |image: DisplayImage, film: Option<Arc<Film>>, progress: Progress| {
        let mut p = lock(out);
        p.image = Some(Arc::new(image));
        if film.is_some() {
            p.film = film;
        }
        p.progress = progress;
        p.serial += 1;
    };
    let mut progress = Progress {
        spp_target: s.max_spp(),
        ..Progress::default()
    };
    pool.install(|| {
        if options.preview {
            for block in PREVIEW_BLOCKS {
                let Ok(pixels) = render_preview(scene, block, &cancelled) else {
                    lock(out).progress.cancelled = true;
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
                lock(out).progress.cancelled = true;
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
    });
}
