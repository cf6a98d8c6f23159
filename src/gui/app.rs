//! The application state and its frame-by-frame layout: menus, scene panel, inspector, viewport,
//! status line. Each panel lives in its own file; the scene, its history and its builds are the
//! [`Document`]'s, the render shown is the [`Viewer`]'s, and what the panels ask for is a
//! [`Command`], carried out once the panels are drawn; then the scene is rebuilt, at most once
//! a frame, whatever changed it.

use super::command::Command;
use super::compare::{AbSplit, SpeedPanel};
use super::document::{Document, Recipe, Version};
use super::files::{Browser, Files};
use super::help;
use super::history::{Gesture, Gestures, History};
use super::inspector::Inspector;
use super::layout::{Layout, Pane};
use super::lessons::LessonsPanel;
use super::resolution::ViewResolution;
use super::scene_panel::ScenePanel;
use super::texture_panel::TexturePanel;
use super::viewer::Viewer;
use crate::render::DisplayImage;
use crate::scene::SceneDesc;
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
    /// Render at the image pane's size (the window) rather than the preset's resolution
    /// (tests, which render small presets at their own size).
    pub follow_viewport: bool,
    /// Which path every render's primary rays take (the command line's `--simd`).
    pub simd: crate::scene::SimdMode,
    /// What the check of the window's memory file repaired or refused, said once in the status
    /// line as the window opens (and on stderr).
    pub startup_notes: Vec<String>,
}

/// What the window remembers between runs besides its size (which eframe keeps) and the
/// arrangement of its panels (the layout): the scene it had open, the unsaved-changes rule and
/// the UI scale.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Prefs {
    /// The file open when the window closed (absolute).
    pub last_scene: Option<PathBuf>,
    /// *Edit → Camera moves are unsaved changes*.
    pub camera_is_unsaved: bool,
    /// *View → UI scale* (Ctrl+= / Ctrl+- / Ctrl+0): egui's zoom factor.
    pub ui_scale: f32,
    /// The lesson open when the window closed (its name), if its scene was open: the page
    /// opens on it again after a reload.
    pub lesson: Option<String>,
    /// The lesson's experiment that scene showed (0-based), put back with it.
    pub experiment: Option<usize>,
}

impl Default for Prefs {
    fn default() -> Self {
        Self {
            last_scene: None,
            camera_is_unsaved: false,
            ui_scale: 1.0,
            lesson: None,
            experiment: None,
        }
    }
}

/// The UI scales *View → UI scale* and its shortcuts reach.
pub const UI_SCALES: std::ops::RangeInclusive<f32> = 0.5..=3.0;
/// One step of Ctrl+= and Ctrl+-.
const UI_SCALE_STEP: f32 = 0.1;

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

/// The explorer: the document being edited, the render showing it, and the panels.
pub struct ExplorerApp {
    /// The scene, its history, its file and its builds.
    pub(super) doc: Document,
    /// The scene shown and its render.
    pub(super) viewer: Viewer,
    /// The resolution renders follow (a view setting, not saved in the scene).
    pub(super) resolution: ViewResolution,
    /// The arrangement of the panels, and presentation mode.
    pub(super) layout: Layout,
    /// The UI scale (egui's zoom factor), kept in [`Prefs`].
    pub(super) ui_scale: f32,
    /// The image pane's space for the image at the last frame (points).
    pub(super) image_space: Option<egui::Rect>,
    /// The image as drawn at the last frame (points).
    pub(super) image_rect: Option<egui::Rect>,
    pub(super) error: Option<String>,
    /// A confirmation shown for a few seconds ("Screenshot saved to ...") and when it came.
    notice: Option<(String, web_time::Instant)>,
    /// What the last build said about its textures, shown until the next
    /// ([`super::scene_notices`]).
    pub(super) scene_notices: Vec<String>,
    pub(super) scene_panel: ScenePanel,
    pub(super) inspector: Inspector,
    pub(super) texture_panel: TexturePanel,
    pub(super) ab: AbSplit,
    pub(super) speed: SpeedPanel,
    pub(super) files: Files,
    pub(super) lessons: LessonsPanel,
    /// Running mean of the time between frames while rendering or building (seconds).
    frame_time: f32,
    /// Running mean of the time `ui()` itself takes (seconds): the rest of a frame is painting.
    layout_time: f32,
    gestures: Gestures,
    /// Whether a camera move alone counts as an unsaved change (off: orbiting does not make
    /// switching presets ask to save; *Save* still writes the camera).
    pub(super) camera_is_unsaved: bool,
    /// A pixel was clicked: the inspector's tab comes forward once the tiles are drawn.
    pub(super) show_inspector: bool,
    /// The *Help → Keyboard shortcuts* window is open.
    pub(super) shortcuts_open: bool,
    /// The window title last sent, so it is sent only when it changes.
    title_sent: String,
    /// Which path every render's primary rays take.
    simd: crate::scene::SimdMode,
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
            doc: Document::new(path),
            viewer: Viewer::default(),
            resolution: ViewResolution::new(options.follow_viewport),
            layout: Layout::default(),
            ui_scale: 1.0,
            image_space: None,
            image_rect: None,
            error: None,
            notice: None,
            scene_notices: Vec::new(),
            scene_panel: ScenePanel::with_browser(options.browser.clone()),
            inspector: Inspector::default(),
            texture_panel: TexturePanel::default(),
            ab: AbSplit::default(),
            speed: SpeedPanel::new(options.simd),
            simd: options.simd,
            files: Files::new(options.recent_file, options.browser),
            lessons: LessonsPanel::default(),
            frame_time: FRAME_INTERVAL.as_secs_f32(),
            layout_time: 0.0,
            gestures: Gestures::default(),
            camera_is_unsaved: false,
            show_inspector: false,
            shortcuts_open: false,
            title_sent: String::new(),
        };
        if let Some(lesson) = &options.lesson {
            let dir = lesson.file.parent().unwrap_or(Path::new("."));
            app.lessons = LessonsPanel::new(dir.to_path_buf());
            app.lessons.start(&lesson.name);
            // A lesson opens on its text and the image: with the inspector beside them the
            // viewport was left a third of the window. View > Inspector brings it back.
            app.inspector.open = false;
        }
        let path = app.doc.path.clone();
        app.open_file(&path);
        app
    }

    /// The window as it starts: on `open` if given, else on the scene `storage` says was open
    /// last (if that file is still there), else on [`super::default_preset`]; with the
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
            .unwrap_or_else(super::default_preset);
        let notes = options.startup_notes.clone();
        let mut app = Self::with_options(path, options);
        app.camera_is_unsaved = prefs.camera_is_unsaved;
        app.ui_scale = prefs.ui_scale.clamp(*UI_SCALES.start(), *UI_SCALES.end());
        if !app.ui_scale.is_finite() {
            app.ui_scale = 1.0;
        }
        let (layout, refused) = Layout::restore(storage);
        app.layout = layout;
        let notes: Vec<String> = notes.into_iter().chain(refused).collect();
        if !notes.is_empty() {
            app.notify(notes.join("; "));
        }
        app
    }

    /// What [`eframe::App::save`] keeps.
    #[must_use]
    pub fn prefs(&self) -> Prefs {
        let path = &self.doc.path;
        Prefs {
            last_scene: Some(std::path::absolute(path).unwrap_or_else(|_| path.clone())),
            camera_is_unsaved: self.camera_is_unsaved,
            ui_scale: self.ui_scale,
            lesson: self.lessons.active_lesson(),
            experiment: self.lessons.experiment_shown(self.doc.desc.as_ref()),
        }
    }

    /// The space the image pane gave the image at the last frame (points), if it was drawn.
    #[must_use]
    pub fn image_space(&self) -> Option<egui::Rect> {
        self.image_space
    }

    /// The image as drawn at the last frame (points), once there is one.
    #[must_use]
    pub fn image_rect(&self) -> Option<egui::Rect> {
        self.image_rect
    }

    /// Whether presentation mode is on (*View → Presentation mode*, F5).
    #[must_use]
    pub fn presenting(&self) -> bool {
        self.layout.presenting()
    }

    /// The scene with the window's edits, saved or not (`None` until a preset opens).
    #[must_use]
    pub fn desc(&self) -> Option<&SceneDesc> {
        self.doc.desc.as_ref()
    }

    /// The file the scene came from.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.doc.path
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
        match (&self.doc.desc, &self.doc.saved) {
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
            .doc
            .path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        let mark = if self.is_dirty() { "• " } else { "" };
        format!("{mark}{name} — texplore")
    }

    /// Edits the scene: `f` changes the description; at the end of the next frame the scene is
    /// rebuilt off the UI thread and rendered again (an edit that does not build is rolled back
    /// and its error shown). The change is an undo step like any other.
    pub fn edit_scene(&mut self, f: impl FnOnce(&mut SceneDesc)) {
        if let Some(desc) = &mut self.doc.desc {
            f(desc);
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
        self.doc.history.undo_label()
    }

    /// What *Edit → Redo* would redo, if anything.
    #[must_use]
    pub fn redo_label(&self) -> Option<&str> {
        self.doc.history.redo_label()
    }

    /// The latest image of the render (preview or accumulated).
    #[must_use]
    pub fn image(&self) -> Option<Arc<DisplayImage>> {
        self.viewer.image()
    }

    /// Whether a scene build is running (the status line says so).
    #[must_use]
    pub fn building(&self) -> bool {
        self.doc.building()
    }

    /// Blocks until the scene build running (if any) has ended, then until the current render
    /// has finished, stopped or failed, or `deadline` has passed (for tests and scripted
    /// screenshots). A build that ended is taken in by the next frame: step the window while
    /// [`ExplorerApp::building`].
    ///
    /// # Errors
    /// The render failed, or the build or the render was still running at the deadline.
    pub fn wait_for_render(&self, deadline: std::time::Duration) -> Result<(), String> {
        let start = web_time::Instant::now();
        self.doc.wait(deadline)?;
        self.viewer.wait(deadline.saturating_sub(start.elapsed()))
    }

    /// Saves the current image as a PNG with the scene embedded.
    ///
    /// # Errors
    /// Nothing rendered yet, or the file cannot be written.
    pub fn save_screenshot(&self, png: &Path) -> crate::Result<()> {
        let (Some(desc), Some(image)) = (&self.doc.desc, self.image()) else {
            return Err(crate::Error::invalid(png, "nothing has been rendered yet"));
        };
        crate::scene::save_render_png(png, &image, desc, self.doc.folder())
    }

    /// What the renders need of `desc`: the description at the view's resolution scale and,
    /// with the A/B split shown, the split's descriptions.
    pub(super) fn recipe(&self, desc: &SceneDesc) -> Recipe {
        let mut d = desc.clone();
        (d.render.width, d.render.height) = self.resolution.film((d.render.width, d.render.height));
        Recipe {
            split: self.ab.enabled.then(|| self.ab.descs(&d)),
            render: d,
            simd: self.simd,
        }
    }

    /// Shows `text` in the status line for a few seconds.
    pub(super) fn notify(&mut self, text: String) {
        self.notice = Some((text, web_time::Instant::now()));
    }
}

impl eframe::App for ExplorerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let started = web_time::Instant::now();
        self.viewer.latency.frame_started();
        self.frame(ui);
        self.viewer.latency.frame_laid_out();
        let t = started.elapsed().as_secs_f32();
        self.layout_time += (t - self.layout_time) * 0.2;
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, Prefs::KEY, &self.prefs());
        self.layout.save(storage);
    }
}

impl ExplorerApp {
    /// One frame: the build that landed comes in, the panels draw and push their commands, the
    /// commands run, and the scene is rebuilt if anything changed it.
    fn frame(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        self.viewer.ctx.get_or_insert_with(|| ctx.clone());
        let gesture = self.gesture(&ctx);
        self.collect_build();
        let mut commands = self.edit_shortcuts(&ctx);
        self.menu_bar(ui, &mut commands);
        help::shortcuts_window(&ctx, &mut self.shortcuts_open);
        self.file_dialogs(&ctx, &mut commands);
        self.status_bar(ui, &ctx);
        self.poll(&ctx);
        if self.layout.presenting() {
            self.strip(ui);
        }
        self.tiles(ui, &mut commands);
        self.speed
            .window(&ctx, self.doc.desc.as_ref(), &self.doc.path);
        for c in commands {
            self.run(&ctx, c);
        }
        if let Some(desc) = &self.doc.desc {
            let recipe = self.recipe(desc);
            self.doc.rebuild(recipe, gesture);
        }
        let title = self.title();
        if title != self.title_sent {
            // A page's title is its document's (eframe's web runner has no viewport title).
            #[cfg(target_arch = "wasm32")]
            if let Some(d) = web_sys::window().and_then(|w| w.document()) {
                d.set_title(&title);
            }
            #[cfg(not(target_arch = "wasm32"))]
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title_sent = title;
        }
    }

    /// Which gesture this frame's changes belong to (one undo step per drag, wheel run or stay
    /// of the keyboard in one text field).
    fn gesture(&mut self, ctx: &egui::Context) -> Option<Gesture> {
        let typing = ctx
            .egui_wants_keyboard_input()
            .then(|| ctx.memory(egui::Memory::focused))
            .flatten()
            .map(|id| id.value());
        ctx.input(|i| {
            self.gestures.update(
                web_time::Instant::now(),
                i.pointer.any_pressed(),
                i.pointer.any_down() || i.pointer.any_released(),
                i.smooth_scroll_delta != egui::Vec2::ZERO
                    || i.raw
                        .events
                        .iter()
                        .any(|e| matches!(e, egui::Event::MouseWheel { .. })),
                typing,
            )
        })
    }

    /// Files: drops, the path dialogs, the unsaved-changes prompt, closing the window.
    fn file_dialogs(&mut self, ctx: &egui::Context, commands: &mut Vec<Command>) {
        commands.extend(self.files.dropped(ctx));
        let description = self
            .doc
            .desc
            .as_ref()
            .map_or("", |d| d.description.as_str());
        let dirty = self.is_dirty();
        commands.extend(self.files.dialogs(ctx, dirty, description));
        commands.extend(
            self.files
                .link_dialogs(ctx, self.doc.desc.as_ref(), self.doc.folder()),
        );
        // A lesson link: the panel opens the lesson, then puts its experiment in place.
        if let Some((name, k)) = self.files.links.take_lesson() {
            commands.push(
                self.lessons
                    .open_at(&name, k, self.doc.desc.as_ref(), dirty),
            );
        }
        commands.extend(self.lessons.due());
        if self.files.close_requested(ctx, dirty) {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
        }
    }

    /// The status line at the bottom (the notice expires after a few seconds).
    fn status_bar(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
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
    }

    /// Polls the render, the A/B split and the scene build, at the target frame rate while
    /// any of them runs; the texture panel follows the scene shown.
    fn poll(&mut self, ctx: &egui::Context) {
        let busy = self.viewer.poll(ctx) | self.ab.poll(ctx) | self.doc.building();
        if busy {
            let dt = ctx.input(|i| i.unstable_dt).min(1.0);
            self.frame_time += (dt - self.frame_time) * 0.2;
            // Poll the render and the build at the target frame rate, not as fast as possible:
            // a software rasteriser (lavapipe) would otherwise take a core from the workers.
            ctx.request_repaint_after(FRAME_INTERVAL);
        }
        self.texture_panel.update(ctx, self.viewer.scene_arc());
    }

    /// The menu bar: File, Edit, Presets, View, Help; an Edit command chosen goes to `commands`.
    fn menu_bar(&mut self, ui: &mut egui::Ui, commands: &mut Vec<Command>) {
        let mut view = ViewChoice::default();
        egui::Panel::top("menu").show(ui, |ui| {
            let mut open = self.open_panels();
            let Self {
                files,
                doc,
                camera_is_unsaved,
                shortcuts_open,
                ab,
                speed,
                ui_scale,
                layout,
                ..
            } = self;
            files.menu_bar(
                ui,
                &doc.path,
                |ui| commands.extend(edit_menu(ui, &doc.history, camera_is_unsaved)),
                |ui| {
                    view = view_menu(ui, &mut open, ab, speed, ui_scale, layout.presenting());
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
            self.set_open_panels(open);
        });
        match view {
            ViewChoice::None => {}
            ViewChoice::Present => self.toggle_presentation(),
            ViewChoice::ResetLayout => self.layout.reset(),
        }
    }

    /// Ctrl+Z undoes, Ctrl+Shift+Z and Ctrl+Y redo, F1 opens the shortcuts, F5 or P presents,
    /// I shows the inspector; not while a text field has the keyboard (it has its own undo).
    /// Ctrl+= and Ctrl+- scale the UI and Ctrl+0 resets it, always.
    fn edit_shortcuts(&mut self, ctx: &egui::Context) -> Vec<Command> {
        self.ui_scale_shortcuts(ctx);
        if ctx.egui_wants_keyboard_input() {
            return Vec::new();
        }
        ctx.input_mut(|i| {
            if i.consume_shortcut(&help::SHORTCUTS_KEY) {
                self.shortcuts_open = !self.shortcuts_open;
            }
            if i.consume_shortcut(&help::PRESENT) || i.consume_shortcut(&help::PRESENT_P) {
                self.toggle_presentation();
            }
            if i.consume_shortcut(&help::INSPECTOR) {
                self.inspector.open = !self.inspector.open;
            }
            // Shift first: Ctrl+Z would also match Ctrl+Shift+Z.
            if i.consume_shortcut(&help::REDO) || i.consume_shortcut(&help::REDO_Y) {
                vec![Command::Redo]
            } else if i.consume_shortcut(&help::UNDO) {
                vec![Command::Undo]
            } else {
                Vec::new()
            }
        })
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
            if self.doc.building() {
                ui.spinner();
                ui.label(BUILDING).on_hover_text(
                    "The scene is being built on the render threads (images loaded, meshes \
                     displaced); the window stays usable, and the new image follows",
                );
                ui.separator();
            }
            if let Some((notice, _)) = &self.notice {
                ui.colored_label(egui::Color32::LIGHT_GREEN, notice);
                ui.separator();
            }
            if self.ab.enabled {
                ui.label(self.ab.status());
            } else {
                self.viewer.status(ui, self.frame_time, self.layout_time);
            }
            super::scene_notices::status(ui, &self.scene_notices);
            false
        })
        .inner
    }
}

impl ExplorerApp {
    /// Ctrl+= (or Ctrl++) and Ctrl+- step the UI scale, Ctrl+0 resets it; then the scale is
    /// applied (egui's own keyboard zoom is off, so a key is never counted twice).
    fn ui_scale_shortcuts(&mut self, ctx: &egui::Context) {
        ctx.options_mut(|o| o.zoom_with_keyboard = false);
        let step = ctx.input_mut(|i| {
            if i.consume_shortcut(&help::SCALE_UP) || i.consume_shortcut(&help::SCALE_UP_PLUS) {
                Some(UI_SCALE_STEP)
            } else if i.consume_shortcut(&help::SCALE_DOWN) {
                Some(-UI_SCALE_STEP)
            } else if i.consume_shortcut(&help::SCALE_RESET) {
                Some(0.0)
            } else {
                None
            }
        });
        match step {
            Some(0.0) => self.ui_scale = 1.0,
            Some(d) => {
                // Steps land on tenths, whatever the slider left.
                let s = ((self.ui_scale + d) * 10.0).round() / 10.0;
                self.ui_scale = s.clamp(*UI_SCALES.start(), *UI_SCALES.end());
            }
            None => {}
        }
        if (ctx.zoom_factor() - self.ui_scale).abs() > 1e-4 {
            ctx.set_zoom_factor(self.ui_scale);
        }
    }
}

/// What the View menu asked for besides its toggles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum ViewChoice {
    #[default]
    None,
    Present,
    ResetLayout,
}

/// The View menu: the panels, the A/B split and the speed window, presentation mode, the UI
/// scale and the layout's reset.
fn view_menu(
    ui: &mut egui::Ui,
    open: &mut super::layout::Open,
    ab: &mut AbSplit,
    speed: &mut SpeedPanel,
    ui_scale: &mut f32,
    presenting: bool,
) -> ViewChoice {
    let mut choice = ViewChoice::None;
    for pane in Pane::ALL {
        if pane == Pane::Image {
            continue;
        }
        let mut on = open.get(pane);
        if ui.checkbox(&mut on, pane.title()).changed() {
            open.set(pane, on);
        }
    }
    ui.checkbox(&mut ab.enabled, "A/B split");
    ui.checkbox(&mut speed.open, "Speed and error");
    ui.separator();
    let text = if presenting {
        "Leave presentation mode"
    } else {
        "Presentation mode"
    };
    let keys = format!(
        "{} or {}",
        ui.ctx().format_shortcut(&help::PRESENT),
        ui.ctx().format_shortcut(&help::PRESENT_P)
    );
    if ui
        .add(egui::Button::new(text).shortcut_text(keys))
        .on_hover_text(
            "The image alone, the panels in a strip at the left (their text at least 20 px \
             high), the lesson's Look for and question beside the image in large type",
        )
        .clicked()
    {
        choice = ViewChoice::Present;
        ui.close();
    }
    ui.horizontal(|ui| {
        let l = ui.label("UI scale");
        ui.add(
            egui::Slider::new(ui_scale, UI_SCALES)
                .step_by(f64::from(UI_SCALE_STEP))
                .suffix(" x"),
        )
        .labelled_by(l.id)
        .on_hover_text("Ctrl+= larger, Ctrl+- smaller, Ctrl+0 back to 1 x (kept between runs)");
    });
    if ui
        .button("Reset layout")
        .on_hover_text("The panels back where they start: scene left, image, tabs right")
        .clicked()
    {
        choice = ViewChoice::ResetLayout;
        ui.close();
    }
    choice
}

/// What the status line says while a scene builds.
pub const BUILDING: &str = "Building the scene…";

/// The Edit menu: undo and redo, each saying what it would do, and whether camera moves count
/// as unsaved changes.
fn edit_menu(
    ui: &mut egui::Ui,
    history: &History<Version>,
    camera_is_unsaved: &mut bool,
) -> Option<Command> {
    let mut command = None;
    for (c, verb, label, key) in [
        (Command::Undo, "Undo", history.undo_label(), help::UNDO),
        (Command::Redo, "Redo", history.redo_label(), help::REDO),
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
pub(super) fn absolute_display(p: &Path) -> String {
    std::path::absolute(p)
        .unwrap_or_else(|_| p.to_path_buf())
        .display()
        .to_string()
}

/// How long a confirmation stays in the status line.
const NOTICE_TIME: std::time::Duration = std::time::Duration::from_secs(8);
