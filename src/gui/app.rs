//! The application state and its frame-by-frame UI.

use crate::mapping::Mapping;
use crate::render::{Generation, RenderJob, RenderOptions};
use crate::scene::{AssetCache, SceneDesc, build_scene, read_preset_or_png};
use crate::texture::Filter;
use std::path::PathBuf;
use std::sync::Arc;

/// The explorer: the scene being edited, the render job showing it, and what the viewport shows.
pub struct ExplorerApp {
    desc: Option<SceneDesc>,
    path: PathBuf,
    cache: AssetCache,
    generation: Generation,
    job: Option<RenderJob>,
    texture: Option<egui::TextureHandle>,
    shown_serial: u64,
    selected: usize,
    error: Option<String>,
}

impl ExplorerApp {
    /// Opens a preset (or a texplore PNG); a failure shows in the window.
    #[must_use]
    pub fn open(path: PathBuf) -> Self {
        let mut app = Self {
            desc: None,
            path: path.clone(),
            cache: AssetCache::new(),
            generation: Generation::new(),
            job: None,
            texture: None,
            shown_serial: 0,
            selected: 0,
            error: None,
        };
        match read_preset_or_png(&path) {
            Ok(desc) => {
                app.desc = Some(desc);
                app.restart();
            }
            Err(e) => app.error = Some(e.to_string()),
        }
        app
    }

    /// Rebuilds the scene from the description and starts a new progressive render; on an
    /// error the previous render stays and the message is shown.
    fn restart(&mut self) {
        let Some(desc) = &self.desc else { return };
        match build_scene(desc, &self.path, &mut self.cache) {
            Ok(scene) => {
                self.generation.bump();
                self.job = Some(RenderJob::start(
                    Arc::new(scene),
                    RenderOptions::default(),
                    &self.generation,
                ));
                self.error = None;
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    fn side_panel(&mut self, ui: &mut egui::Ui) -> bool {
        let Some(desc) = &mut self.desc else {
            return false;
        };
        let mut changed = false;
        ui.heading("Objects");
        for (i, o) in desc.objects.iter().enumerate() {
            let name = if o.name.is_empty() {
                format!("{i}: {:?}", o.shape)
            } else {
                o.name.clone()
            };
            if ui.selectable_label(self.selected == i, name).clicked() {
                self.selected = i;
            }
        }
        if let Some(obj) = desc.objects.get_mut(self.selected) {
            let tex = obj.material.texture_mut();
            if let Some(current) = tex.mapping() {
                let mut m = current;
                egui::ComboBox::from_label("Mapping")
                    .selected_text(m.name())
                    .show_ui(ui, |ui| {
                        for option in Mapping::ALL {
                            ui.selectable_value(&mut m, option, option.name())
                                .on_hover_text(option.description());
                        }
                    });
                if m != current {
                    tex.set_mapping(m);
                    changed = true;
                }
            }
            if let crate::scene::TextureDesc::Image { filter, .. } = tex {
                let before = *filter;
                egui::ComboBox::from_label("Filter")
                    .selected_text(filter.name())
                    .show_ui(ui, |ui| {
                        for option in Filter::ALL {
                            ui.selectable_value(filter, option, option.name());
                        }
                    });
                changed |= *filter != before;
            }
        }
        ui.separator();
        ui.heading("Render");
        changed |= ui
            .add(
                egui::Slider::new(&mut desc.render.spp, 1..=256)
                    .logarithmic(true)
                    .text("spp"),
            )
            .changed();
        changed |= ui
            .add(egui::Slider::new(&mut desc.render.exposure, -8.0..=8.0).text("exposure (stops)"))
            .changed();
        changed
    }
}

impl eframe::App for ExplorerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        let changed = egui::Panel::left("scene")
            .default_size(260.0)
            .show(ui, |ui| self.side_panel(ui))
            .inner;
        if changed {
            self.restart();
        }
        egui::Panel::bottom("status").show(ui, |ui| {
            if let Some(err) = &self.error {
                ui.colored_label(egui::Color32::LIGHT_RED, err);
            } else if let Some(job) = &self.job {
                let p = job.progress();
                ui.label(format!(
                    "{} / {} spp · last pass {:.1} ms · {:.1} M rays/s{}",
                    p.spp_done,
                    p.spp_target,
                    p.last_pass.as_secs_f64() * 1e3,
                    p.rays_per_second / 1e6,
                    if p.finished { " · done" } else { "" }
                ));
            }
        });
        if let Some(job) = &self.job {
            if let Some((img, serial)) = job.image()
                && serial != self.shown_serial
            {
                let color = egui::ColorImage::from_rgba_unmultiplied(
                    [img.width as usize, img.height as usize],
                    &img.rgba,
                );
                match &mut self.texture {
                    Some(t) => t.set(color, egui::TextureOptions::NEAREST),
                    None => {
                        self.texture =
                            Some(ctx.load_texture("render", color, egui::TextureOptions::NEAREST))
                    }
                }
                self.shown_serial = serial;
            }
            if !job.progress().finished {
                ctx.request_repaint();
            }
        }
        egui::CentralPanel::default().show(ui, |ui| {
            if let Some(t) = &self.texture {
                let size = t.size_vec2();
                let avail = ui.available_size();
                let scale = (avail.x / size.x).min(avail.y / size.y).min(4.0);
                ui.centered_and_justified(|ui| ui.image((t.id(), size * scale)));
            }
        });
    }
}
