//! A render job's display image as an egui texture, uploaded only when the job publishes a new
//! one.

use crate::render::RenderJob;

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

    /// Uploads the job's image if it published a new one since the last call.
    pub fn update(&mut self, ctx: &egui::Context, job: &RenderJob) {
        let Some((img, serial)) = job.image() else {
            return;
        };
        if serial == self.serial {
            return;
        }
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
    }

    /// The texture, once something was uploaded.
    #[must_use]
    pub fn texture(&self) -> Option<&egui::TextureHandle> {
        self.texture.as_ref()
    }
}
