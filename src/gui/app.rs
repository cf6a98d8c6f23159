//! The application state and its frame-by-frame layout: menus, scene panel, inspector, viewport,
//! status line. Each panel lives in its own file; this one owns the scene and the render jobs.

use super::compare::{AbSplit, SpeedPanel};
use super::files::{FileAction, Files};
use super::inspector::Inspector;
use super::lessons::{LessonAction, LessonsPanel};
use super::live::LiveImage;
use super::scene_panel::ScenePanel;
use super::texture_panel::TexturePanel;
use super::viewport::{self, ViewEdit};
use crate::math::Vec2;
use crate::render::{DisplayImage, Generation, RenderJob, RenderOptions};
use crate::scene::{AssetCache, CameraDesc, Scene, SceneDesc, build_scene, read_preset_or_png};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// How often the window polls a running render for a new image (30 frames per second).
const FRAME_INTERVAL: std::time::Duration = std::time::Duration::from_millis(33);

/// How the window starts.
#[derive(Clone, Debug, Default)]
pub struct AppOptions {
    /// Where the recent-files list is kept (`None`: not kept, as in tests).
    pub recent_file: Option<PathBuf>,
    /// Start on this lesson (its preset, the Lessons panel open on it).
    pub lesson: Option<crate::lesson::Lesson>,
}

/// The explorer: the scene being edited, the render job showing it, and the panels.
pub struct ExplorerApp {
    /// The scene the panels edit, unsaved edits included; an edit that fails to build is rolled
    /// back to the last description that built. `None` until a preset opens.
    pub(super) desc: Option<SceneDesc>,
    /// The last description that built (restored when an edit fails).
    good_desc: Option<SceneDesc>,
    /// The description as last opened or saved (for the unsaved-changes prompt).
    pub(super) saved_desc: Option<SceneDesc>,
    /// The camera as opened, for "reset view".
    home_camera: Option<CameraDesc>,
    /// The file the scene came from; asset paths are relative to it.
    pub(super) path: PathBuf,
    pub(super) cache: AssetCache,
    generation: Generation,
    job: Option<RenderJob>,
    scene: Option<Arc<Scene>>,
    live: LiveImage,
    /// Render at this fraction of the preset's resolution (a view setting, not saved).
    pub(super) resolution_scale: f32,
    pub(super) error: Option<String>,
    pub(super) scene_panel: ScenePanel,
    pub(super) inspector: Inspector,
    pub(super) texture_panel: TexturePanel,
    pub(super) ab: AbSplit,
    pub(super) speed: SpeedPanel,
    pub(super) files: Files,
    pub(super) lessons: LessonsPanel,
    /// Running mean of the time between frames while rendering (seconds).
    frame_time: f32,
    /// Running mean of the time `ui()` itself takes (seconds): the rest of a frame is painting.
    layout_time: f32,
}

impl ExplorerApp {
    /// Opens a preset (or a texplore PNG); a failure shows in the window.
    #[must_use]
    pub fn open(path: PathBuf) -> Self {
        Self::with_options(path, AppOptions::default())
    }

    /// [`ExplorerApp::open`], keeping the recent-files list where `options` says.
    #[must_use]
    pub fn with_options(path: PathBuf, options: AppOptions) -> Self {
        let mut app = Self {
            desc: None,
            good_desc: None,
            saved_desc: None,
            home_camera: None,
            path,
            cache: AssetCache::new(),
            generation: Generation::new(),
            job: None,
            scene: None,
            live: LiveImage::new("render"),
            resolution_scale: 1.0,
            error: None,
            scene_panel: ScenePanel::default(),
            inspector: Inspector::default(),
            texture_panel: TexturePanel::default(),
            ab: AbSplit::default(),
            speed: SpeedPanel::default(),
            files: Files::new(options.recent_file),
            lessons: LessonsPanel::default(),
            frame_time: FRAME_INTERVAL.as_secs_f32(),
            layout_time: 0.0,
        };
        if let Some(lesson) = &options.lesson {
            let dir = lesson.file.parent().unwrap_or(Path::new("."));
            app.lessons = LessonsPanel::new(dir.to_path_buf());
            app.lessons.start(&lesson.name);
        }
        let path = app.path.clone();
        app.open_file(&path);
        app
    }

    /// Opens a preset or a texplore PNG, replacing the scene; on an error the current scene
    /// stays and the message shows.
    pub fn open_file(&mut self, path: &Path) {
        let ok = self.open_file_inner(path);
        self.lessons.opened(path, ok, self.desc.as_ref());
    }

    fn open_file_inner(&mut self, path: &Path) -> bool {
        match read_preset_or_png(path) {
            Ok(desc) => {
                // Try the new scene; if it does not build (a missing image), keep the old one.
                let old_desc = self.desc.replace(desc.clone());
                let old_good = self.good_desc.take();
                let old_path = std::mem::replace(&mut self.path, path.to_path_buf());
                if self.restart() {
                    self.home_camera = Some(desc.camera);
                    self.saved_desc = Some(desc);
                    self.scene_panel.scene_replaced();
                    self.inspector.clear();
                    self.files.add_recent(path);
                    true
                } else {
                    self.desc = old_desc;
                    self.good_desc = old_good;
                    self.path = old_path;
                    false
                }
            }
            Err(e) => {
                self.error = Some(e.to_string());
                false
            }
        }
    }

    /// The scene with the window's edits, saved or not (`None` until a preset opens).
    #[must_use]
    pub fn desc(&self) -> Option<&SceneDesc> {
        self.desc.as_ref()
    }

    /// The file the scene came from.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The error shown in the window, if any.
    #[must_use]
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// What the inspector shows (the pixel hovered or pinned).
    #[must_use]
    pub fn inspection(&self) -> Option<&crate::inspect::Inspection> {
        self.inspector.shown()
    }

    /// Whether the scene differs from the file it came from.
    #[must_use]
    pub fn is_dirty(&self) -> bool {
        self.desc != self.saved_desc
    }

    /// The latest image of the render (preview or accumulated).
    #[must_use]
    pub fn image(&self) -> Option<Arc<DisplayImage>> {
        self.job.as_ref().and_then(RenderJob::image).map(|(i, _)| i)
    }

    /// Blocks until the current render has finished, stopped or failed, or `deadline` has
    /// passed (for tests and scripted screenshots).
    ///
    /// # Errors
    /// The render failed, or it was still running at the deadline.
    pub fn wait_for_render(&self, deadline: std::time::Duration) -> Result<(), String> {
        let start = std::time::Instant::now();
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

    /// Saves the current image as a PNG with the scene embedded.
    ///
    /// # Errors
    /// Nothing rendered yet, or the file cannot be written.
    pub fn save_screenshot(&self, png: &Path) -> crate::Result<()> {
        let (Some(desc), Some(image)) = (&self.desc, self.image()) else {
            return Err(crate::Error::invalid(png, "nothing has been rendered yet"));
        };
        let dir = self
            .path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        crate::scene::save_render_png(png, &image, desc, dir)
    }

    /// The description rendered: the edited one at the view's resolution scale.
    fn render_desc(&self, desc: &SceneDesc) -> SceneDesc {
        let mut d = desc.clone();
        let s = self.resolution_scale;
        d.render.width = ((d.render.width as f32 * s).round() as u32).max(1);
        d.render.height = ((d.render.height as f32 * s).round() as u32).max(1);
        d
    }

    /// Rebuilds the scene from the description and starts a new progressive render; on an
    /// error the previous scene and render stay, the description goes back to the last one that
    /// built, and the message is shown.
    pub(super) fn restart(&mut self) -> bool {
        let Some(desc) = self.desc.clone() else {
            return false;
        };
        let rdesc = self.render_desc(&desc);
        match build_scene(&rdesc, &self.path, &mut self.cache) {
            Ok(scene) => {
                self.generation.bump();
                let scene = Arc::new(scene);
                // Dropping a job cancels it without waiting for its task.
                self.job = None;
                let mut started = Ok(());
                if self.ab.enabled {
                    self.ab
                        .restart(&rdesc, &self.path, &mut self.cache, &self.generation);
                } else {
                    self.ab.stop();
                    match RenderJob::start(
                        scene.clone(),
                        RenderOptions::default(),
                        &self.generation,
                    ) {
                        Ok(job) => self.job = Some(job),
                        Err(e) => started = Err(e.to_string()),
                    }
                }
                self.live.reset();
                self.scene = Some(scene);
                self.good_desc = Some(desc);
                self.error = started.err();
                self.inspector.refresh(self.scene.as_deref());
                true
            }
            Err(e) => {
                self.error = Some(e.to_string());
                if let Some(good) = &self.good_desc {
                    self.desc = Some(good.clone());
                }
                false
            }
        }
    }

    fn apply_view_edit(&mut self, edit: ViewEdit) {
        let Some(desc) = &mut self.desc else { return };
        let c = &mut desc.camera;
        match edit {
            ViewEdit::Orbit(d) => {
                c.eye = crate::camera::orbit(c.eye, c.look_at, c.up, -d.x * 0.01, d.y * 0.01);
            }
            ViewEdit::Pan(d) => {
                let shift = crate::camera::pan_offset(c.eye, c.look_at, c.up, -d.x, d.y);
                c.eye += shift;
                c.look_at += shift;
            }
            ViewEdit::Zoom(f) => {
                c.eye = viewport::zoomed_eye(self.scene.as_deref(), c.eye, c.look_at, f);
            }
            ViewEdit::Reset => {
                if let Some(home) = self.home_camera {
                    *c = home;
                }
            }
        }
        self.restart();
    }

    /// The status line; returns whether the user dismissed the error.
    fn status_line(&self, ui: &mut egui::Ui) -> bool {
        ui.horizontal(|ui| {
            if let Some(err) = &self.error {
                let dismiss = ui
                    .button("Dismiss")
                    .on_hover_text("Dismiss the message")
                    .clicked();
                ui.colored_label(egui::Color32::LIGHT_RED, err);
                return dismiss;
            }
            if self.ab.enabled {
                ui.label(self.ab.status());
                return false;
            }
            let (Some(job), Some(scene)) = (&self.job, &self.scene) else {
                return false;
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
                    1.0 / self.frame_time.max(1e-3),
                    self.layout_time * 1e3
                ))
                .on_hover_text("Frames per second of the window while it renders");
            }
            false
        })
        .inner
    }
}

impl Drop for ExplorerApp {
    fn drop(&mut self) {
        self.generation.bump();
    }
}

impl eframe::App for ExplorerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let started = std::time::Instant::now();
        self.frame(ui);
        let t = started.elapsed().as_secs_f32();
        self.layout_time += (t - self.layout_time) * 0.2;
    }
}

impl ExplorerApp {
    fn frame(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();

        // Files: menus, dialogs, drops, the unsaved-changes prompt.
        let ab_before = self.ab.enabled;
        egui::Panel::top("menu").show(ui, |ui| {
            self.files.menu_bar(
                ui,
                &self.path,
                [
                    (&mut self.inspector.open, "Inspector"),
                    (&mut self.texture_panel.open, "Texture panel"),
                    (&mut self.ab.enabled, "A/B split"),
                    (&mut self.speed.open, "Speed and error"),
                    (&mut self.lessons.open, "Lessons"),
                ],
            );
        });
        let mut actions: Vec<FileAction> = Vec::new();
        actions.extend(self.files.dropped(&ctx));
        actions.extend(self.files.dialogs(&ctx, self.is_dirty()));
        if self.files.close_requested(&ctx, self.is_dirty()) {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
        }
        for a in actions {
            self.run_action(&ctx, a);
        }

        let dismiss = egui::Panel::bottom("status")
            .show(ui, |ui| self.status_line(ui))
            .inner;
        if dismiss {
            self.error = None;
        }

        let changed = egui::Panel::left("scene")
            .default_size(300.0)
            .resizable(true)
            .show(ui, |ui| {
                egui::ScrollArea::vertical()
                    .show(ui, |ui| {
                        let Self {
                            desc,
                            scene_panel,
                            resolution_scale,
                            path,
                            ..
                        } = self;
                        if let Some(desc) = desc {
                            scene_panel.ui(ui, desc, resolution_scale, path)
                        } else {
                            ui.label("No scene: open a preset from the Presets menu.");
                            false
                        }
                    })
                    .inner
            })
            .inner;
        if changed {
            self.restart();
        }
        if self.ab.enabled != ab_before {
            self.restart();
        }

        if self.lessons.open {
            let dirty = self.is_dirty();
            let action = egui::Panel::right("lessons")
                .default_size(380.0)
                .resizable(true)
                .show(ui, |ui| self.lessons.ui(ui, self.desc.as_ref(), dirty))
                .inner;
            match action {
                Some(LessonAction::Open {
                    preset,
                    force: true,
                }) => self.open_file(&preset),
                Some(LessonAction::Open { preset, .. }) => {
                    self.files.request_open(preset);
                    ctx.request_repaint();
                }
                Some(LessonAction::Apply(d)) => {
                    self.desc = Some(d);
                    self.restart();
                }
                Some(LessonAction::Error(e)) => self.error = Some(e),
                None => {}
            }
        }

        self.texture_panel.update(&ctx, self.scene.as_ref());
        if self.inspector.open {
            egui::Panel::right("inspector")
                .default_size(440.0)
                .resizable(true)
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| self.inspector.ui(ui));
                });
        }

        if self.texture_panel.open {
            egui::Panel::right("texture-panel")
                .default_size(380.0)
                .resizable(true)
                .show(ui, |ui| self.texture_panel.ui(ui, self.inspector.shown()));
        }

        self.speed.window(&ctx, self.desc.as_ref(), &self.path);

        // The viewport.
        let mut busy = false;
        if let Some(job) = &self.job {
            self.live.update(&ctx, job);
            busy |= !job.progress().finished && !job.progress().cancelled;
        }
        busy |= self.ab.poll(&ctx);
        if busy {
            let dt = ctx.input(|i| i.unstable_dt).min(1.0);
            self.frame_time += (dt - self.frame_time) * 0.2;
            // Poll the render at the target frame rate, not as fast as possible: a software
            // rasteriser (lavapipe) would otherwise take a core from the render threads.
            ctx.request_repaint_after(FRAME_INTERVAL);
        }
        let size = self
            .scene
            .as_ref()
            .map(|s| Vec2::new(s.settings.width as f32, s.settings.height as f32));
        let out = egui::CentralPanel::default()
            .show(ui, |ui| {
                let view = self.desc.as_mut().map(|d| &mut d.render.view);
                if self.ab.enabled {
                    viewport::show_split(ui, &mut self.ab, size, view)
                } else {
                    viewport::show(ui, self.live.texture(), size, view)
                }
            })
            .inner;
        if let Some(edit) = out.edit {
            self.apply_view_edit(edit);
        }
        if out.view_changed {
            self.restart();
        }
        if self.ab.take_restart() {
            self.restart();
        }
        if let Some(scene) = &self.scene {
            self.inspector.pointer(scene, out.hover, out.click);
        }
    }
}

impl ExplorerApp {
    fn run_action(&mut self, ctx: &egui::Context, action: FileAction) {
        match action {
            FileAction::Open(p) => self.open_file(&p),
            FileAction::Save(p) => {
                if let Some(desc) = &mut self.desc {
                    if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) {
                        self.error = Some(format!(
                            "{}: a preset is saved as .ron; use Save screenshot for a PNG",
                            p.display()
                        ));
                        return;
                    }
                    // Asset paths are relative to the preset: rewrite them for the new folder.
                    let mut out = desc.clone();
                    let from = self.path.parent().unwrap_or(Path::new("."));
                    let to = p.parent().unwrap_or(Path::new("."));
                    crate::scene::rebase_assets(&mut out, from, to);
                    match crate::scene::save_preset(&out, &p) {
                        Ok(()) => {
                            *desc = out.clone();
                            self.saved_desc = Some(out);
                            self.path.clone_from(&p);
                            self.files.add_recent(&p);
                            self.error = None;
                        }
                        Err(e) => self.error = Some(e.to_string()),
                    }
                }
            }
            FileAction::Screenshot(p) => match self.save_screenshot(&p) {
                Ok(()) => self.error = None,
                Err(e) => self.error = Some(e.to_string()),
            },
            FileAction::UseImage(p) => {
                if let Some(desc) = &mut self.desc {
                    let dir = self.path.parent().unwrap_or(Path::new("."));
                    let rel = crate::scene::relative_asset_path(&p, dir);
                    self.scene_panel.use_image(desc, rel);
                    self.restart();
                }
            }
            FileAction::UseMesh(p) => {
                if let Some(desc) = &mut self.desc {
                    let dir = self.path.parent().unwrap_or(Path::new("."));
                    let rel = crate::scene::relative_asset_path(&p, dir);
                    self.scene_panel.use_mesh(desc, rel);
                    self.restart();
                }
            }
            FileAction::Error(e) => self.error = Some(e),
            FileAction::Quit => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
        }
    }
}
