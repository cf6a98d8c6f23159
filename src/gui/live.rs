//! A render job's display image as an egui texture, uploaded only when the job publishes a new
//! one.

use crate::render::RenderJob;
use std::sync::{Arc, OnceLock};
use web_time::Instant;

/// The texture showing a job's latest image.
pub struct LiveImage {
    name: &'static str,
    texture: Option<egui::TextureHandle>,
    serial: u64,
}

impl LiveImage {
    /// An empty image; `name` names the egui texture the job's first published image creates.
    #[must_use]
    pub fn new(name: &'static str) -> Self {
        Self {
            name,
            texture: None,
            serial: 0,
        }
    }

    /// A new job starts: its first image (serial 1) must be uploaded.
    pub fn reset(&mut self) {
        self.serial = 0;
    }

    /// Uploads the job's image if it published a new one since the last call; returns whether
    /// this was the job's first image.
    pub fn update(&mut self, ctx: &egui::Context, job: &RenderJob) -> bool {
        let Some((img, serial)) = job.image() else {
            return false;
        };
        if serial == self.serial {
            return false;
        }
        let first = self.serial == 0;
        let color = egui::ColorImage::from_rgba_unmultiplied(
            [img.width as usize, img.height as usize],
            &img.rgba,
        );
        match &mut self.texture {
            Some(t) => t.set(color, egui::TextureOptions::NEAREST),
            None => {
                self.texture =
                    Some(ctx.load_texture(self.name, color, egui::TextureOptions::NEAREST));
            }
        }
        self.serial = serial;
        first
    }

    /// The texture, once something was uploaded.
    #[must_use]
    pub fn texture(&self) -> Option<&egui::TextureHandle> {
        self.texture.as_ref()
    }
}

/// Where the time goes between an edit and its first preview on screen, measured when the
/// environment has `TEXPLORE_LATENCY=1`: one line per edit on stderr, from the start of the
/// frame that made the edit to
/// - the render restarted (scene built, job started),
/// - the job's first preview published (the job's publish hook),
/// - the start of the frame that uploads it, and the end of that frame's layout,
/// - the start of the next frame (the upload frame has been painted by then).
#[derive(Debug)]
pub struct Latency {
    enabled: bool,
    frame_start: Instant,
    edit: Option<EditTrace>,
}

#[derive(Debug)]
struct EditTrace {
    frame_start: Instant,
    restarted: Instant,
    /// Set by the job's publish hook on its first image.
    published: Arc<OnceLock<Instant>>,
    /// The upload frame's start and the end of its layout.
    uploaded: Option<(Instant, Option<Instant>)>,
}

impl Latency {
    /// Tracing on if `TEXPLORE_LATENCY` is set to anything but `0`.
    #[must_use]
    pub fn from_env() -> Self {
        Self {
            enabled: std::env::var_os("TEXPLORE_LATENCY").is_some_and(|v| v != "0"),
            frame_start: Instant::now(),
            edit: None,
        }
    }

    /// A frame starts: if the previous one uploaded an edit's first preview, report the edit.
    pub fn frame_started(&mut self) {
        let now = Instant::now();
        self.frame_start = now;
        let Some(e) = &self.edit else { return };
        let (Some(published), Some((upload_frame, Some(laid_out)))) =
            (e.published.get(), e.uploaded)
        else {
            return;
        };
        let since = |t: Instant| t.saturating_duration_since(e.frame_start).as_secs_f64() * 1e3;
        eprintln!(
            "latency: restarted +{:.1} ms · first preview published +{:.1} ms · frame \
             uploading it starts +{:.1} ms, laid out +{:.1} ms · next frame (upload painted) \
             +{:.1} ms",
            since(e.restarted),
            since(*published),
            since(upload_frame),
            since(laid_out),
            since(now),
        );
        self.edit = None;
    }

    /// The render restarted in this frame; returns the slot the new job's publish hook fills
    /// with the time of its first image.
    pub fn restarted(&mut self) -> Arc<OnceLock<Instant>> {
        let published = Arc::new(OnceLock::new());
        if self.enabled {
            self.edit = Some(EditTrace {
                frame_start: self.frame_start,
                restarted: Instant::now(),
                published: published.clone(),
                uploaded: None,
            });
        }
        published
    }

    /// This frame uploaded the new job's first image.
    pub fn uploaded(&mut self) {
        if let Some(e) = &mut self.edit
            && e.uploaded.is_none()
        {
            e.uploaded = Some((self.frame_start, None));
        }
    }

    /// This frame's layout is done.
    pub fn frame_laid_out(&mut self) {
        if let Some(EditTrace {
            uploaded: Some((start, end @ None)),
            ..
        }) = &mut self.edit
            && *start == self.frame_start
        {
            *end = Some(Instant::now());
        }
    }
}
