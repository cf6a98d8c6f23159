//! The application state and its frame-by-frame layout: menus, scene panel, inspector, viewport,
//! status line. Each panel lives in its own file; this one owns the scene and the render jobs.

use super::compare::{AbSplit, SpeedPanel};
use super::files::{Browser, FileAction, Files};
use super::help;
use super::history::{self, Gesture, Gestures, History};
use super::inspector::Inspector;
use super::lessons::{LessonAction, LessonsPanel};
use super::live::{Latency, LiveImage};
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
    /// What every *Browse…* button asks (the system's file dialog unless replaced).
    pub browser: Browser,
}

/// What the window remembers between runs besides its size and panel widths (which eframe and
/// egui keep themselves): the scene it had open and the unsaved-changes rule.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Prefs {
    /// The file open when the window closed (absolute).
    pub last_scene: Option<PathBuf>,
    /// *Edit → Camera moves are unsaved changes*.
    pub camera_is_unsaved: bool,
}

impl Prefs {
    /// The key [`Prefs`] is stored under in eframe's storage.
    pub const KEY: &str = "texplore-prefs";

    /// The preferences kept in `storage` (none kept, or unreadable: the defaults).
    #[must_use]
    pub fn load(storage: Option<&dyn eframe::Storage>) -> Self {
        storage
            .and_then(|s| eframe::get_value(s, Self::KEY))
            .unwrap_or_default()
    }
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
    /// A confirmation shown for a few seconds ("Screenshot saved to ...") and when it came.
    notice: Option<(String, std::time::Instant)>,
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
    /// Undo and redo over every change of `desc`, whichever panel made it.
    history: History<SceneDesc>,
    gestures: Gestures,
    /// Whether a camera move alone counts as an unsaved change (off: orbiting does not make
    /// switching presets ask to save; *Save* still writes the camera).
    pub(super) camera_is_unsaved: bool,
    /// The *Help → Keyboard shortcuts* window is open.
    pub(super) shortcuts_open: bool,
    /// The window title last sent, so it is sent only when it changes.
    title_sent: String,
    /// `TEXPLORE_LATENCY=1`: where the time goes from an edit to its first preview.
    latency: Latency,
    /// The window's context once a frame has run: a new job asks it for a repaint as soon as
    /// its first preview is published.
    ctx: Option<egui::Context>,
}

/// An Edit-menu command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum EditCommand {
    Undo,
    Redo,
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
            notice: None,
            scene_panel: ScenePanel::with_browser(options.browser.clone()),
            inspector: Inspector::default(),
            texture_panel: TexturePanel::default(),
            ab: AbSplit::default(),
            speed: SpeedPanel::default(),
            files: Files::new(options.recent_file, options.browser),
            lessons: LessonsPanel::default(),
            frame_time: FRAME_INTERVAL.as_secs_f32(),
            layout_time: 0.0,
            history: History::default(),
            gestures: Gestures::default(),
            camera_is_unsaved: false,
            shortcuts_open: false,
            title_sent: String::new(),
            latency: Latency::from_env(),
            ctx: None,
        };
        if let Some(lesson) = &options.lesson {
            let dir = lesson.file.parent().unwrap_or(Path::new("."));
            app.lessons = LessonsPanel::new(dir.to_path_buf());
            app.lessons.start(&lesson.name);
            // A lesson opens on its text and the image: with the inspector beside them the
            // viewport was left a third of the window. View > Inspector brings it back.
            app.inspector.open = false;
        }
        let path = app.path.clone();
        app.open_file(&path);
        app
    }

    /// The window as it starts: on `open` if given, else on the scene `storage` says was open
    /// last (if that file is still there), else on [`super::DEFAULT_PRESET`]; with the
    /// preferences `storage` kept. Tests pass their own storage or none, never the user's.
    #[must_use]
    pub fn restore(
        storage: Option<&dyn eframe::Storage>,
        open: Option<PathBuf>,
        options: AppOptions,
    ) -> Self {
        let prefs = Prefs::load(storage);
        let path = open
            .or(prefs.last_scene.filter(|p| p.is_file()))
            .unwrap_or_else(|| PathBuf::from(super::DEFAULT_PRESET));
        let mut app = Self::with_options(path, options);
        app.camera_is_unsaved = prefs.camera_is_unsaved;
        app
    }

    /// What [`eframe::App::save`] keeps.
    #[must_use]
    pub fn prefs(&self) -> Prefs {
        Prefs {
            last_scene: Some(std::path::absolute(&self.path).unwrap_or_else(|_| self.path.clone())),
            camera_is_unsaved: self.camera_is_unsaved,
        }
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
                    self.history.reset(self.desc.as_ref());
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

    /// The confirmation shown in the status line, if any ("Screenshot saved to ...").
    #[must_use]
    pub fn notice(&self) -> Option<&str> {
        self.notice.as_ref().map(|(n, _)| n.as_str())
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

    /// Whether the scene has unsaved changes: it differs from the file it came from, a camera
    /// move alone not counting unless *Edit → Camera moves are unsaved changes* is on.
    #[must_use]
    pub fn is_dirty(&self) -> bool {
        match (&self.desc, &self.saved_desc) {
            (Some(now), Some(saved)) if !self.camera_is_unsaved => {
                let mut now = now.clone();
                now.camera = saved.camera;
                now != *saved
            }
            (now, saved) => now != saved,
        }
    }

    /// The window's title: the file's name, `•` before it while there are unsaved changes.
    #[must_use]
    pub fn title(&self) -> String {
        let name = self
            .path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        let mark = if self.is_dirty() { "• " } else { "" };
        format!("{mark}{name} — texplore")
    }

    /// Edits the scene: `f` changes the description, and if anything changed the scene is
    /// rebuilt and re-rendered (an edit that does not build is rolled back and its error
    /// shown). The change is an undo step like any other. For panels that edit the scene.
    pub fn edit_scene(&mut self, f: impl FnOnce(&mut SceneDesc)) {
        let Some(desc) = &mut self.desc else { return };
        let before = desc.clone();
        f(desc);
        if *desc != before {
            self.restart();
        }
    }

    /// The index of the object the scene panel edits.
    #[must_use]
    pub fn selected_object(&self) -> usize {
        self.scene_panel.selected
    }

    /// What *Edit → Undo* would undo ("mapping of Earth", "camera"...), if anything.
    #[must_use]
    pub fn undo_label(&self) -> Option<&str> {
        self.history.undo_label()
    }

    /// What *Edit → Redo* would redo, if anything.
    #[must_use]
    pub fn redo_label(&self) -> Option<&str> {
        self.history.redo_label()
    }

    /// Records this frame's change of the scene, if any, as an undo step (or as part of the
    /// step of the gesture it continues).
    fn record(&mut self, gesture: Option<Gesture>) {
        self.history
            .observe(self.desc.as_ref(), gesture, history::describe);
    }

    /// Undoes or redoes one step and re-renders.
    fn run_edit(&mut self, command: EditCommand) {
        self.record(None);
        let Some(current) = self.desc.clone() else {
            return;
        };
        let kept = self.history.clone();
        let restored = match command {
            EditCommand::Undo => self.history.undo(&current),
            EditCommand::Redo => self.history.redo(&current),
        };
        let Some(restored) = restored else { return };
        let objects_before = current.objects.len();
        // The object that came back or went away is the one to look at.
        let changed_object = restored
            .objects
            .iter()
            .zip(&current.objects)
            .position(|(a, b)| a != b)
            .unwrap_or(restored.objects.len().min(objects_before));
        let count_changed = restored.objects.len() != objects_before;
        self.desc = Some(restored);
        if self.restart() {
            if count_changed {
                self.scene_panel.selected = changed_object;
            }
            let n = self.desc.as_ref().map_or(0, |d| d.objects.len());
            self.scene_panel.selected = self.scene_panel.selected.min(n.saturating_sub(1));
        } else {
            // The step does not build any more (a file it used is gone): `restart` put the
            // scene back and shows why; the history stays as it was.
            self.history = kept;
        }
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
                        Ok(job) => {
                            let published = self.latency.restarted();
                            if let Some(ctx) = self.ctx.clone() {
                                // The first preview takes a few milliseconds: paint it at once
                                // rather than at the next poll (later passes are polled at
                                // FRAME_INTERVAL, so the UI never repaints faster than that).
                                let woken = std::sync::atomic::AtomicBool::new(false);
                                job.on_publish(move || {
                                    published.get_or_init(std::time::Instant::now);
                                    if !woken.swap(true, std::sync::atomic::Ordering::Relaxed) {
                                        ctx.request_repaint();
                                    }
                                });
                            }
                            self.job = Some(job);
                        }
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
            if let Some((notice, _)) = &self.notice {
                ui.colored_label(egui::Color32::LIGHT_GREEN, notice);
                ui.separator();
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
        self.latency.frame_started();
        self.frame(ui);
        self.latency.frame_laid_out();
        let t = started.elapsed().as_secs_f32();
        self.layout_time += (t - self.layout_time) * 0.2;
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, Prefs::KEY, &self.prefs());
    }
}

impl ExplorerApp {
    /// The Lessons panel (when open) and what its buttons ask: open a lesson's preset (through
    /// the unsaved-changes prompt unless forced), apply an experiment's scene, or show an error.
    fn lessons_panel(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
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
    }

    fn frame(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        if self.ctx.is_none() {
            self.ctx = Some(ctx.clone());
        }
        // Which gesture this frame's changes belong to (one undo step per drag or wheel run).
        let gesture = ctx.input(|i| {
            self.gestures.update(
                std::time::Instant::now(),
                i.pointer.any_pressed(),
                i.pointer.any_down() || i.pointer.any_released(),
                i.smooth_scroll_delta != egui::Vec2::ZERO
                    || i.raw
                        .events
                        .iter()
                        .any(|e| matches!(e, egui::Event::MouseWheel { .. })),
            )
        });
        let mut command = self.edit_shortcuts(&ctx);

        // Files: menus, dialogs, drops, the unsaved-changes prompt.
        let ab_before = self.ab.enabled;
        self.menu_bar(ui, &mut command);
        if let Some(c) = command {
            self.run_edit(c);
        }
        help::shortcuts_window(&ctx, &mut self.shortcuts_open);
        let mut actions: Vec<FileAction> = Vec::new();
        actions.extend(self.files.dropped(&ctx));
        let description = self.desc.as_ref().map_or("", |d| d.description.as_str());
        actions.extend(self.files.dialogs(&ctx, self.is_dirty(), description));
        if self.files.close_requested(&ctx, self.is_dirty()) {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
        }
        for a in actions {
            self.run_action(&ctx, a);
        }

        if let Some((_, at)) = &self.notice {
            let left = NOTICE_TIME.saturating_sub(at.elapsed());
            if left.is_zero() {
                self.notice = None;
            } else {
                ctx.request_repaint_after(left);
            }
        }
        let dismiss = egui::Panel::bottom("status")
            .show(ui, |ui| self.status_line(ui))
            .inner;
        if dismiss {
            self.error = None;
        }

        let changed = egui::Panel::left("scene")
            .default_size(320.0)
            .resizable(true)
            .show(ui, |ui| {
                // Scrolls both ways inside the panel's own width: wide content (large numbers,
                // long paths) scrolls instead of widening the panel and moving the viewport.
                egui::ScrollArea::both()
                    .auto_shrink([false, false])
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

        self.lessons_panel(ui, &ctx);

        self.texture_panel.update(&ctx, self.scene.as_ref());
        if self.inspector.open {
            egui::Panel::right("inspector")
                .default_size(440.0)
                .resizable(true)
                .show(ui, |ui| {
                    // As the scene panel: the inspector's content changes with every pixel
                    // hovered, and must not move the viewport.
                    egui::ScrollArea::both()
                        .auto_shrink([false, false])
                        .show(ui, |ui| self.inspector.ui(ui));
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
            if self.live.update(&ctx, job) {
                self.latency.uploaded();
            }
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
                let hint = self.desc.as_ref().and_then(viewport::edge_on_hint);
                let view = self.desc.as_mut().map(|d| &mut d.render.view);
                if self.ab.enabled {
                    viewport::show_split(ui, &mut self.ab, size, view, hint.as_deref())
                } else {
                    viewport::show(ui, self.live.texture(), size, view, hint.as_deref())
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

        // Whatever changed the scene this frame (any panel, the camera, a file action) is one
        // undo step, or part of the gesture's step.
        self.record(gesture);
        let title = self.title();
        if title != self.title_sent {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title_sent = title;
        }
    }

    /// The menu bar: File, Edit, Presets, View, Help; an Edit command chosen goes to `command`.
    fn menu_bar(&mut self, ui: &mut egui::Ui, command: &mut Option<EditCommand>) {
        egui::Panel::top("menu").show(ui, |ui| {
            let Self {
                files,
                history,
                camera_is_unsaved,
                shortcuts_open,
                inspector,
                texture_panel,
                lessons,
                ab,
                speed,
                path,
                ..
            } = self;
            files.menu_bar(
                ui,
                path,
                [
                    (&mut inspector.open, "Inspector"),
                    (&mut texture_panel.open, "Texture panel"),
                    (&mut ab.enabled, "A/B split"),
                    (&mut speed.open, "Speed and error"),
                    (&mut lessons.open, "Lessons"),
                ],
                |ui| {
                    if let Some(c) = edit_menu(ui, history, camera_is_unsaved) {
                        *command = Some(c);
                    }
                },
                |ui| {
                    if ui
                        .add(
                            egui::Button::new("Keyboard shortcuts")
                                .shortcut_text(ui.ctx().format_shortcut(&help::SHORTCUTS_KEY)),
                        )
                        .clicked()
                    {
                        *shortcuts_open = true;
                        ui.close();
                    }
                },
            );
        });
    }

    /// Ctrl+Z undoes, Ctrl+Shift+Z and Ctrl+Y redo, F1 opens the shortcuts; not while a text
    /// field has the keyboard (it has its own undo).
    fn edit_shortcuts(&mut self, ctx: &egui::Context) -> Option<EditCommand> {
        if ctx.egui_wants_keyboard_input() {
            return None;
        }
        ctx.input_mut(|i| {
            if i.consume_shortcut(&help::SHORTCUTS_KEY) {
                self.shortcuts_open = !self.shortcuts_open;
            }
            // Shift first: Ctrl+Z would also match Ctrl+Shift+Z.
            if i.consume_shortcut(&help::REDO) || i.consume_shortcut(&help::REDO_Y) {
                Some(EditCommand::Redo)
            } else if i.consume_shortcut(&help::UNDO) {
                Some(EditCommand::Undo)
            } else {
                None
            }
        })
    }
}

/// The Edit menu: undo and redo, each saying what it would do, and whether camera moves count
/// as unsaved changes.
fn edit_menu(
    ui: &mut egui::Ui,
    history: &History<SceneDesc>,
    camera_is_unsaved: &mut bool,
) -> Option<EditCommand> {
    let mut command = None;
    for (c, verb, label, key) in [
        (EditCommand::Undo, "Undo", history.undo_label(), help::UNDO),
        (EditCommand::Redo, "Redo", history.redo_label(), help::REDO),
    ] {
        let text = label.map_or_else(|| verb.to_owned(), |l| format!("{verb} {l}"));
        if ui
            .add_enabled(
                label.is_some(),
                egui::Button::new(text).shortcut_text(ui.ctx().format_shortcut(&key)),
            )
            .clicked()
        {
            command = Some(c);
            ui.close();
        }
    }
    ui.separator();
    ui.checkbox(camera_is_unsaved, "Camera moves are unsaved changes")
        .on_hover_text(
            "On: orbiting, panning or zooming marks the scene unsaved, and opening another \
             preset asks first. Off: only edits of the scene do (Save still writes the camera)",
        );
    command
}

/// `p` made absolute for a message (as typed if that fails).
fn absolute_display(p: &Path) -> String {
    std::path::absolute(p)
        .unwrap_or_else(|_| p.to_path_buf())
        .display()
        .to_string()
}

/// How long a confirmation stays in the status line.
const NOTICE_TIME: std::time::Duration = std::time::Duration::from_secs(8);

impl ExplorerApp {
    fn notify(&mut self, text: String) {
        self.notice = Some((text, std::time::Instant::now()));
    }

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
                            // The steps to undo hold paths relative to the old folder too.
                            self.history
                                .rewrite(|d| crate::scene::rebase_assets(d, from, to));
                            *desc = out.clone();
                            self.saved_desc = Some(out);
                            self.path.clone_from(&p);
                            self.files.add_recent(&p);
                            self.error = None;
                            self.notify(format!("Saved {}", absolute_display(&p)));
                        }
                        Err(e) => self.error = Some(e.to_string()),
                    }
                }
            }
            FileAction::Screenshot(p) => match self.save_screenshot(&p) {
                Ok(()) => {
                    self.error = None;
                    self.notify(format!("Screenshot saved to {}", absolute_display(&p)));
                }
                Err(e) => self.error = Some(e.to_string()),
            },
            FileAction::Describe(d) => {
                // Only the text changes: nothing to render again.
                if let Some(desc) = &mut self.desc {
                    desc.description = d;
                }
            }
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
