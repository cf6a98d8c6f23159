//! Files: the menu bar, built-in presets, open / save / save-as / screenshot dialogs (a path
//! field with quick picks and a *Browse…* button for the system's file dialog), recent files,
//! dropped files, and the prompts that guard unsaved changes and existing files.

use super::command::Command;
use crate::scene::read_png_preset;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What a *Browse…* button asks the file dialog for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BrowseFor {
    /// An image for the texture.
    Image,
    /// A PLY or OBJ mesh for the shape.
    Mesh,
    /// A preset or a texplore PNG to open.
    Scene,
    /// Where to save the preset.
    Preset,
    /// Where to save the screenshot.
    Screenshot,
}

/// A file chooser: what is asked for, the folder to start in, the file name to suggest;
/// `None` when the user cancels.
pub type BrowseFn = dyn Fn(BrowseFor, &Path, &str) -> Option<PathBuf> + Send + Sync;

/// The file chooser behind every *Browse…* button: the system's dialog (`rfd`: the XDG desktop
/// portal on Linux, the native panels on macOS and Windows), or, in tests, a function that
/// answers in its place.
#[derive(Clone, Default)]
pub struct Browser(Option<Arc<BrowseFn>>);

impl std::fmt::Debug for Browser {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.is_some() {
            "Browser(replaced)"
        } else {
            "Browser(native)"
        })
    }
}

impl Browser {
    /// A chooser that calls `f` instead of showing the system's dialog.
    #[must_use]
    pub fn replaced_by(
        f: impl Fn(BrowseFor, &Path, &str) -> Option<PathBuf> + Send + Sync + 'static,
    ) -> Self {
        Self(Some(Arc::new(f)))
    }

    /// Asks for a file: `start` is the folder shown first, `name` the suggested file name of a
    /// save. Blocks until the dialog closes.
    #[must_use]
    pub fn pick(&self, what: BrowseFor, start: &Path, name: &str) -> Option<PathBuf> {
        if let Some(f) = &self.0 {
            return f(what, start, name);
        }
        // The page's dialogs are asynchronous: what the user chooses arrives later, as a drop.
        #[cfg(target_arch = "wasm32")]
        return super::web::pick(what, start, name);
        #[cfg(not(target_arch = "wasm32"))]
        {
            let start = std::path::absolute(start).unwrap_or_else(|_| start.to_path_buf());
            let d = rfd::FileDialog::new().set_directory(start);
            match what {
                BrowseFor::Image => d
                    .set_title("Choose an image")
                    .add_filter("Images", &IMAGE_EXTENSIONS)
                    .pick_file(),
                BrowseFor::Mesh => d
                    .set_title("Choose a mesh")
                    .add_filter("Meshes (PLY, OBJ)", &["ply", "obj"])
                    .pick_file(),
                BrowseFor::Scene => d
                    .set_title("Open a preset or a texplore PNG")
                    .add_filter("Presets and texplore PNGs", &["ron", "png"])
                    .pick_file(),
                BrowseFor::Preset => d
                    .set_title("Save the scene as a preset")
                    .add_filter("Preset (.ron)", &["ron"])
                    .set_file_name(name)
                    .save_file(),
                BrowseFor::Screenshot => d
                    .set_title("Save a screenshot")
                    .add_filter("PNG", &["png"])
                    .set_file_name(name)
                    .save_file(),
            }
        }
    }
}

/// The image files texplore reads, by extension.
pub const IMAGE_EXTENSIONS: [&str; 9] = [
    "png", "jpg", "jpeg", "hdr", "exr", "tif", "tiff", "ppm", "pgm",
];

/// How many recent files are remembered.
const MAX_RECENT: usize = 10;
/// Where the built-in presets live.
const PRESET_DIR: &str = "presets";

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum DialogKind {
    Open,
    SaveAs,
    Screenshot,
}

#[derive(Clone, Debug, PartialEq)]
enum Pending {
    Open(PathBuf),
    Quit,
}

/// The path dialog while it is open.
struct Dialog {
    kind: DialogKind,
    /// The path typed.
    text: String,
    /// *Save as*: the description typed (filled from the scene's when first shown).
    description: Option<String>,
    /// The path field takes the keyboard on the dialog's first frame.
    focus: bool,
}

/// The files state.
pub struct Files {
    recent: Vec<PathBuf>,
    recent_file: Option<PathBuf>,
    dialog: Option<Dialog>,
    browser: Browser,
    /// The built-in presets in the lecture's order with their descriptions (read once).
    presets: Option<Vec<(PathBuf, String)>>,
    requested: Option<Pending>,
    prompt: Option<Pending>,
    overwrite: Option<Command>,
    close_ok: bool,
    current: PathBuf,
}

/// The user's config folder for texplore, from the `dirs` crate: `$XDG_CONFIG_HOME/texplore`
/// or `~/.config/texplore` on Linux, `~/Library/Application Support/texplore` on macOS,
/// `%APPDATA%\texplore` on Windows.
#[must_use]
pub fn config_dir() -> Option<PathBuf> {
    dirs::config_dir().map(|d| d.join("texplore"))
}

fn stem(p: &Path) -> String {
    p.file_stem().map_or_else(
        || p.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    )
}

fn is_image(p: &Path) -> bool {
    p.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| IMAGE_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
}

fn canonical(p: &Path) -> PathBuf {
    std::fs::canonicalize(p)
        .unwrap_or_else(|_| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf()))
}

/// The folder of `file` ("." for a bare name).
fn folder_of(file: &Path) -> &Path {
    file.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// Where a screenshot of the scene from `current` goes by default: beside its preset, or, for a
/// built-in preset, in the user's Pictures folder (else the home folder; the program's presets
/// folder is no place for it); named `<preset>-shot.png`, or `-shot-2.png`... so that the
/// default never replaces a file.
#[must_use]
pub fn screenshot_default(current: &Path) -> PathBuf {
    let folder = folder_of(current);
    let dir = if canonical(folder) == canonical(Path::new(PRESET_DIR)) {
        dirs::picture_dir()
            .or_else(dirs::home_dir)
            .unwrap_or_else(|| folder.to_path_buf())
    } else {
        folder.to_path_buf()
    };
    let stem = stem(current);
    let mut p = dir.join(format!("{stem}-shot.png"));
    let mut n = 2;
    while p.exists() && n < 10_000 {
        p = dir.join(format!("{stem}-shot-{n}.png"));
        n += 1;
    }
    p
}

/// Largest recent-files list read (a list of paths takes a few kilobytes).
const MAX_RECENT_BYTES: u64 = 1 << 20;

impl Files {
    /// Reads the recent-files list from `recent_file` (a missing or bad file is an empty list);
    /// *Browse…* asks `browser`.
    #[must_use]
    pub fn new(recent_file: Option<PathBuf>, browser: Browser) -> Self {
        let recent = recent_file
            .as_deref()
            .and_then(|f| crate::input::read_input_text(f, MAX_RECENT_BYTES).ok())
            .and_then(|t| ron::from_str::<Vec<PathBuf>>(&t).ok())
            .unwrap_or_default();
        Self {
            recent,
            recent_file,
            dialog: None,
            browser,
            presets: None,
            requested: None,
            prompt: None,
            overwrite: None,
            close_ok: false,
            current: PathBuf::new(),
        }
    }

    /// The built-in presets in the lecture's order ([`crate::scene::LECTURE_ORDER`]), each
    /// with its description.
    fn presets(&mut self) -> Vec<(PathBuf, String)> {
        self.presets
            .get_or_insert_with(|| crate::scene::presets_in_lecture_order(Path::new(PRESET_DIR)))
            .clone()
    }

    fn open_dialog(&mut self, kind: DialogKind, text: String) {
        self.dialog = Some(Dialog {
            kind,
            text,
            description: None,
            focus: true,
        });
    }

    /// Puts `path` first in the recent list and writes the list (errors writing it are ignored:
    /// the list is a convenience).
    pub fn add_recent(&mut self, path: &Path) {
        let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        self.recent.retain(|p| *p != abs);
        self.recent.insert(0, abs);
        self.recent.truncate(MAX_RECENT);
        if let Some(f) = &self.recent_file {
            if let Some(dir) = f.parent() {
                let _ = std::fs::create_dir_all(dir);
            }
            if let Ok(text) = ron::to_string(&self.recent) {
                let _ = crate::output::write_bytes(f, &[], text.as_bytes());
            }
        }
    }

    /// The menu bar. `toggles` are the View menu's panels; `edit` fills the Edit menu and `help`
    /// the Help menu.
    pub fn menu_bar<const N: usize>(
        &mut self,
        ui: &mut egui::Ui,
        current: &Path,
        toggles: [(&mut bool, &str); N],
        edit: impl FnOnce(&mut egui::Ui),
        help: impl FnOnce(&mut egui::Ui),
    ) {
        self.current = current.to_path_buf();
        // Ctrl+S saves (over a .ron, else asks where), Ctrl+O opens.
        let (save, open) = ui.input_mut(|i| {
            (
                i.consume_shortcut(&super::help::SAVE),
                i.consume_shortcut(&super::help::OPEN),
            )
        });
        if save {
            if current.extension().is_some_and(|e| e == "ron") {
                // Never overwrite without asking: the replace prompt confirms.
                self.overwrite = Some(Command::Save(current.to_path_buf()));
            } else {
                self.open_dialog(DialogKind::SaveAs, String::new());
            }
        }
        if open {
            self.open_dialog(DialogKind::Open, String::new());
        }
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("Open…").clicked() {
                    self.open_dialog(DialogKind::Open, String::new());
                }
                let is_ron = current.extension().is_some_and(|e| e == "ron");
                if ui
                    .button("Save")
                    .on_hover_text("Save the scene over the preset it came from")
                    .clicked()
                {
                    if is_ron {
                        // Never overwrite without asking: the replace prompt confirms.
                        self.overwrite = Some(Command::Save(current.to_path_buf()));
                    } else {
                        self.open_dialog(DialogKind::SaveAs, String::new());
                    }
                }
                if ui.button("Save as…").clicked() {
                    let name = current.with_extension("ron").display().to_string();
                    self.open_dialog(DialogKind::SaveAs, name);
                }
                if ui
                    .button("Save screenshot…")
                    .on_hover_text(concat!(
                        "A PNG of the image with the scene inside: ",
                        "open or drop it to restore the scene"
                    ))
                    .clicked()
                {
                    let name = screenshot_default(current).display().to_string();
                    self.open_dialog(DialogKind::Screenshot, name);
                }
                ui.menu_button("Recent", |ui| {
                    if self.recent.is_empty() {
                        ui.weak("(none yet)");
                    }
                    for p in self.recent.clone() {
                        if ui.button(p.display().to_string()).clicked() {
                            self.requested = Some(Pending::Open(p));
                        }
                    }
                });
                ui.separator();
                if ui.button("Quit").clicked() {
                    self.requested = Some(Pending::Quit);
                }
            });
            ui.menu_button("Edit", edit);
            ui.menu_button("Presets", |ui| {
                // In the lecture's order, each with the description its file holds.
                egui::Grid::new("presets").num_columns(2).show(ui, |ui| {
                    for (p, description) in self.presets() {
                        let button = ui.button(stem(&p)).on_hover_text(&description);
                        ui.weak(&description);
                        ui.end_row();
                        if button.clicked() {
                            self.requested = Some(Pending::Open(p));
                            ui.close();
                        }
                    }
                });
            });
            ui.menu_button("View", |ui| {
                for (flag, name) in toggles {
                    ui.checkbox(flag, name);
                }
            });
            ui.menu_button("Help", help);
            let name = current
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
            ui.weak(format!("  {name}"))
                .on_hover_text(current.display().to_string());
        });
    }

    /// Files dropped on the window: presets and texplore PNGs open; other images and meshes go
    /// on the selected object.
    pub fn dropped(&mut self, ctx: &egui::Context) -> Vec<Command> {
        let dropped = ctx.input(|i| i.raw.dropped_files.clone());
        let mut out = Vec::new();
        for f in dropped {
            let p = f.path().to_path_buf();
            let ext = p
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            match ext.as_deref() {
                Some("ron") => self.requested = Some(Pending::Open(p)),
                Some("png") if read_png_preset(&p).is_ok() => {
                    self.requested = Some(Pending::Open(p));
                }
                Some("ply" | "obj") => out.push(Command::UseMesh(p)),
                _ if is_image(&p) => out.push(Command::UseImage(p)),
                _ => out.push(Command::Error(format!(
                    "{}: not a preset (.ron), a texplore PNG, an image or a mesh (.ply, .obj)",
                    p.display()
                ))),
            }
        }
        out
    }

    /// Opens `path` as the Open menu does: through the unsaved-changes prompt if the scene
    /// has changes.
    pub fn request_open(&mut self, path: PathBuf) {
        self.requested = Some(Pending::Open(path));
    }

    /// Whether a close must be cancelled to ask about unsaved changes first.
    pub fn close_requested(&mut self, ctx: &egui::Context, dirty: bool) -> bool {
        let asked = ctx.input(|i| i.viewport().close_requested());
        if asked && dirty && !self.close_ok {
            self.prompt = Some(Pending::Quit);
            return true;
        }
        false
    }

    /// The dialogs and prompts; returns what the user confirmed. `description` is the scene's,
    /// which *Save as* offers to edit.
    pub fn dialogs(&mut self, ctx: &egui::Context, dirty: bool, description: &str) -> Vec<Command> {
        let mut out = Vec::new();
        if let Some(req) = self.requested.take() {
            if dirty {
                self.prompt = Some(req);
            } else {
                out.push(self.confirm(req));
            }
        }
        if let Some(pending) = self.prompt.clone() {
            egui::Modal::new(egui::Id::unique("unsaved")).show(ctx, |ui| {
                ui.heading("Unsaved changes");
                ui.label("The scene has changes that are not saved. Discard them?");
                ui.horizontal(|ui| {
                    let is_ron = self.current.extension().is_some_and(|e| e == "ron");
                    if is_ron
                        && ui
                            .button("Save and continue")
                            .on_hover_text(format!("Save to {}", self.current.display()))
                            .clicked()
                    {
                        out.push(Command::Save(self.current.clone()));
                        out.push(self.confirm(pending.clone()));
                        self.prompt = None;
                    }
                    if ui.button("Discard changes").clicked() {
                        out.push(self.confirm(pending.clone()));
                        self.prompt = None;
                    }
                    if ui.button("Cancel").clicked() {
                        self.prompt = None;
                    }
                });
            });
        }
        if let Some(action) = self.overwrite.clone() {
            let path = match &action {
                Command::Save(p) | Command::Screenshot(p) => p.display().to_string(),
                _ => String::new(),
            };
            egui::Modal::new(egui::Id::unique("overwrite")).show(ctx, |ui| {
                ui.heading("Replace the file?");
                ui.label(format!("{path} exists."));
                ui.horizontal(|ui| {
                    if ui.button("Replace").clicked() {
                        out.push(action.clone());
                        self.overwrite = None;
                    }
                    if ui.button("Cancel").clicked() {
                        self.overwrite = None;
                    }
                });
            });
        }
        self.path_dialog(ctx, description, &mut out);
        out
    }

    /// The path dialog (Open, Save as, Save screenshot), while open; what it confirms goes to
    /// `out` (or to the replace prompt).
    fn path_dialog(&mut self, ctx: &egui::Context, description: &str, out: &mut Vec<Command>) {
        if let Some(mut dialog) = self.dialog.take() {
            let kind = dialog.kind;
            let mut keep = true;
            let title = match kind {
                DialogKind::Open => "Open a preset or a texplore PNG",
                DialogKind::SaveAs => "Save the scene as a preset (.ron)",
                DialogKind::Screenshot => "Save a screenshot (.png, with the scene inside)",
            };
            let modal = egui::Modal::new(egui::Id::unique("path-dialog")).show(ctx, |ui| {
                ui.heading(title);
                let mut go = false;
                let text = &mut dialog.text;
                ui.horizontal(|ui| {
                    let l = ui.label("Path");
                    let r = ui
                        .add(egui::TextEdit::singleline(text).desired_width(360.0))
                        .labelled_by(l.id);
                    if std::mem::take(&mut dialog.focus) {
                        r.request_focus();
                    }
                    go |= r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                    if ui
                        .button("Browse…")
                        .on_hover_text("Choose the file in the system's file dialog")
                        .clicked()
                    {
                        let what = match kind {
                            DialogKind::Open => BrowseFor::Scene,
                            DialogKind::SaveAs => BrowseFor::Preset,
                            DialogKind::Screenshot => BrowseFor::Screenshot,
                        };
                        let typed = Path::new(text.trim());
                        let start = if text.trim().is_empty() {
                            folder_of(&self.current)
                        } else {
                            folder_of(typed)
                        };
                        let name = typed
                            .file_name()
                            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
                        if let Some(p) = self.browser.pick(what, start, &name) {
                            *text = p.display().to_string();
                            go = true;
                        }
                    }
                });
                if kind == DialogKind::SaveAs {
                    let d = dialog
                        .description
                        .get_or_insert_with(|| description.to_owned());
                    let l = ui.label("Description (shown in the Presets menu)");
                    ui.add(
                        egui::TextEdit::multiline(d)
                            .desired_rows(2)
                            .desired_width(420.0),
                    )
                    .labelled_by(l.id);
                }
                if kind == DialogKind::Open {
                    ui.label("Built-in presets and recent files:");
                    let presets: Vec<PathBuf> =
                        self.presets().into_iter().map(|(p, _)| p).collect();
                    let builtin: Vec<PathBuf> = presets.iter().map(|p| canonical(p)).collect();
                    let recent = self
                        .recent
                        .iter()
                        .filter(|r| !builtin.contains(&canonical(r)))
                        .cloned();
                    egui::ScrollArea::vertical()
                        .max_height(200.0)
                        .show(ui, |ui| {
                            for p in presets.into_iter().chain(recent) {
                                if ui
                                    .selectable_label(false, p.display().to_string())
                                    .clicked()
                                {
                                    *text = p.display().to_string();
                                }
                            }
                        });
                }
                ui.horizontal(|ui| {
                    let ok = match kind {
                        DialogKind::Open => "Open",
                        _ => "Save",
                    };
                    go |= ui
                        .add_enabled(!text.trim().is_empty(), egui::Button::new(ok))
                        .clicked();
                    if ui.button("Cancel").clicked() {
                        keep = false;
                    }
                });
                if go && !text.trim().is_empty() {
                    let p = PathBuf::from(text.trim());
                    keep = false;
                    match kind {
                        DialogKind::Open => self.requested = Some(Pending::Open(p)),
                        DialogKind::SaveAs | DialogKind::Screenshot => {
                            if let Some(d) = dialog.description.take()
                                && d != description
                            {
                                out.push(Command::Describe(d));
                            }
                            let action = if kind == DialogKind::SaveAs {
                                Command::Save(p.clone())
                            } else {
                                Command::Screenshot(p.clone())
                            };
                            if p.exists() {
                                self.overwrite = Some(action);
                            } else {
                                out.push(action);
                            }
                        }
                    }
                }
            });
            // Esc (or a click beside the dialog) closes it, as Cancel does.
            if keep && !modal.should_close() {
                self.dialog = Some(dialog);
            }
        }
    }

    fn confirm(&mut self, p: Pending) -> Command {
        match p {
            Pending::Open(path) => Command::Open(path),
            Pending::Quit => {
                self.close_ok = true;
                Command::Quit
            }
        }
    }
}
