//! The render the viewport shows: the scene that last built, its progressive render job, the
//! texture its images go to, and the status line's account of it.

use super::live::{Latency, LiveImage};
use crate::render::{DisplayImage, Generation, RenderJob, RenderOptions};
use crate::scene::Scene;
use std::sync::Arc;

/// The scene shown and its render.
pub struct Viewer {
    generation: Generation,
    job: Option<RenderJob>,
    scene: Option<Arc<Scene>>,
    pub(super) live: LiveImage,
    /// `TEXPLORE_LATENCY=1`: where the time goes from an edit to its first preview.
    pub(super) latency: Latency,
    /// The window's context once a frame has run: a new job asks it for a repaint as soon as
    /// its first preview is published.
    pub(super) ctx: Option<egui::Context>,
}

impl Default for Viewer {
    fn default() -> Self {
        Self {
            generation: Generation::new(),
            job: None,
            scene: None,
            live: LiveImage::new("render"),
            latency: Latency::from_env(),
            ctx: None,
        }
    }
}

impl Viewer {
    /// The scene shown, once one has built.
    #[must_use]
    pub fn scene(&self) -> Option<&Scene> {
        self.scene.as_deref()
    }

    /// The scene shown, shared.
    #[must_use]
    pub fn scene_arc(&self) -> Option<&Arc<Scene>> {
        self.scene.as_ref()
    }

    /// The counter every render of the window runs under (the A/B split's too).
    #[must_use]
    pub fn generation(&self) -> &Generation {
        &self.generation
    }

    /// Shows `scene` (its render started by [`Viewer::start`] or by the A/B split).
    pub fn show(&mut self, scene: Arc<Scene>) {
        self.live.reset();
        self.scene = Some(scene);
    }

    /// Stops the render (dropping a job cancels it without waiting for its task).
    pub fn stop(&mut self) {
        self.generation.bump();
        self.job = None;
    }

    /// Starts rendering `scene`, stopping the render before.
    ///
    /// # Errors
    /// No worker pool could be had.
    pub fn start(&mut self, scene: Arc<Scene>) -> Result<(), String> {
        self.stop();
        let job = RenderJob::start(scene, RenderOptions::default(), &self.generation)
            .map_err(|e| e.to_string())?;
        let published = self.latency.restarted();
        if let Some(ctx) = self.ctx.clone() {
            // The first preview takes a few milliseconds: paint it at once rather than at the
            // next poll (later passes are polled at the frame interval, so the UI never
            // repaints faster than that).
            let woken = std::sync::atomic::AtomicBool::new(false);
            job.on_publish(move || {
                published.get_or_init(web_time::Instant::now);
                if !woken.swap(true, std::sync::atomic::Ordering::Relaxed) {
                    ctx.request_repaint();
                }
            });
        }
        self.job = Some(job);
        Ok(())
    }

    /// Uploads the render's newest image; returns whether the render is still running.
    pub fn poll(&mut self, ctx: &egui::Context) -> bool {
        let Some(job) = &self.job else {
            return false;
        };
        if self.live.update(ctx, job) {
            self.latency.uploaded();
        }
        let p = job.progress();
        !p.finished && !p.cancelled
    }

    /// The render's progress, once one has started (the page publishes it for scripts).
    #[cfg_attr(not(target_arch = "wasm32"), allow(dead_code))]
    #[must_use]
    pub fn progress(&self) -> Option<crate::render::Progress> {
        self.job.as_ref().map(RenderJob::progress)
    }

    /// The latest image of the render (preview or accumulated).
    #[must_use]
    pub fn image(&self) -> Option<Arc<DisplayImage>> {
        self.job.as_ref().and_then(RenderJob::image).map(|(i, _)| i)
    }

    /// Blocks until the render has finished, stopped or failed, or `deadline` has passed.
    ///
    /// # Errors
    /// The render failed, or it was still running at the deadline.
    pub fn wait(&self, deadline: std::time::Duration) -> Result<(), String> {
        let start = web_time::Instant::now();
        while let Some(job) = &self.job {
            if let Some(failure) = job.failure() {
                return Err(failure);
            }
            let p = job.progress();
            if p.finished || p.cancelled {
                break;
            }
            if start.elapsed() > deadline {
                return Err(format!(
                    "the render was still running after {:.1} s ({} of {} spp)",
                    deadline.as_secs_f64(),
                    p.spp_done,
                    p.spp_target
                ));
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        Ok(())
    }

    /// The status line's account of the render: size, passes, state, speed.
    pub fn status(&self, ui: &mut egui::Ui, frame_time: f32, layout_time: f32) {
        let (Some(job), Some(scene)) = (&self.job, &self.scene) else {
            return;
        };
        let p = job.progress();
        let s = scene.settings;
        let state = if p.finished {
            "done".to_owned()
        } else if let Some(b) = p.preview_block {
            format!("preview {b}x{b}")
        } else {
            "refining".to_owned()
        };
        ui.label(format!(
            "{}x{} · pass {} of {} ({} spp) · {state}",
            s.width, s.height, p.spp_done, p.spp_target, p.spp_done
        ));
        ui.separator();
        ui.label(format!(
            "{:.1} ms/pass · {:.2} M rays/s · {:.2} s",
            p.last_pass.as_secs_f64() * 1e3,
            p.rays_per_second / 1e6,
            p.elapsed.as_secs_f64()
        ));
        // The UI's own frame rate while it renders (idle, it only redraws on input).
        if !p.finished {
            ui.separator();
            ui.label(format!(
                "UI {:.0} fps ({:.1} ms to lay out a frame)",
                1.0 / frame_time.max(1e-3),
                layout_time * 1e3
            ))
            .on_hover_text("Frames per second of the window while it renders");
        }
    }
}

impl Drop for Viewer {
    fn drop(&mut self) {
        self.generation.bump();
    }
}
