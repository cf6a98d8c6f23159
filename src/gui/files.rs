//! Files: the menu bar, built-in presets, open / save / save-as / screenshot dialogs (a path
//! field with quick picks and a *Browse…* button for the system's file dialog), recent files,
//! dropped files, and the prompts that guard unsaved changes and existing files.
//!
//! Shipped presets and lessons ([`crate::shipped::is_shipped`]) and the scenes of lessons are
//! read-only here: *Save* on one (the menu, Ctrl+S, the unsaved-changes prompt) is always
//! *Save as*, and *Save as* refuses them as targets.

mod dialog;
mod folder;
mod save;

pub use super::browse::{BrowseFor, Browser, IMAGE_EXTENSIONS};
use super::command::Command;
use crate::scene::read_png_preset;
use std::path::{Path, PathBuf};

/// How many recent files are remembered.
const MAX_RECENT: usize = 10;

/// The built-in presets' folder: the copy of those shipped in the binary.
fn preset_dir() -> PathBuf {
    crate::shipped::presets_dir().unwrap_or_else(|_| PathBuf::from("presets"))
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum DialogKind {
    Open,
    SaveAs,
    Screenshot,
    /// An image for the selected object (a *Browse…* with no system dialog).
    Image,
    /// A mesh for the selected object (likewise).
    Mesh,
}

#[derive(Clone, Debug, PartialEq)]
enum Pending {
    Open(PathBuf),
    Quit,
}

/// Why a file is not saved over (or, a new one, written), if it is not: a shipped file, a
/// lesson's scene, or a path in the folder of texplore's copy of the shipped files.
fn read_only_reason(path: &Path, protected: &[PathBuf]) -> Option<String> {
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    if crate::shipped::is_shipped(path) {
        Some(format!(
            "{name} ships with texplore and is read-only: save your scene under another name"
        ))
    } else if protected.iter().any(|p| canonical(p) == canonical(path)) {
        Some(format!(
            "{name} is a lesson's scene and is read-only here: save your scene under another name"
        ))
    } else {
        save::shipped_folder_reason(path)
    }
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
    /// Why the dialog is shown or what was wrong with the path typed.
    note: Option<String>,
    /// *Save as* from the unsaved-changes prompt: what to do once saved.
    then: Option<Pending>,
    /// The path last checked for a save, and why it is refused, if it is.
    refused: Option<(String, Option<String>)>,
    /// texplore's own chooser is shown under the path (no system dialog).
    folders: bool,
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
    /// The replace prompt: the save it confirms, and what to do after it.
    overwrite: Option<(Command, Option<Pending>)>,
    close_ok: bool,
    current: PathBuf,
    /// The scenes of lessons ([`Files::protect`]): read-only, as shipped files are.
    protected: Vec<PathBuf>,
    /// Whether `current` is read-only, and why (worked out once per file).
    read_only: Option<(PathBuf, Option<String>)>,
    /// *Copy link to this scene* or *Open link…*, asked this frame.
    link_ask: Option<super::links::LinkAsk>,
    /// The link dialogs.
    pub(super) links: super::links::LinkDialog,
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

/// Where *Save as* suggests saving a copy of the read-only `current`: the user's Documents
/// folder (else the home folder), under its name, or `-2`, `-3`... so that it replaces nothing.
fn copy_default(current: &Path) -> PathBuf {
    let dir = dirs::document_dir()
        .or_else(dirs::home_dir)
        .unwrap_or_else(|| PathBuf::from("."));
    let stem = stem(current);
    let mut p = dir.join(format!("{stem}.ron"));
    let mut n = 2;
    while p.exists() && n < 10_000 {
        p = dir.join(format!("{stem}-{n}.ron"));
        n += 1;
    }
    p
}

/// Where a screenshot of the scene from `current` goes by default: beside its preset, or, for a
/// built-in preset, in the user's Pictures folder (else the home folder; the program's presets
/// folder is no place for it); named `<preset>-shot.png`, or `-shot-2.png`... so that the
/// default never replaces a file.
#[must_use]
pub fn screenshot_default(current: &Path) -> PathBuf {
    let folder = folder_of(current);
    let dir =
        if canonical(folder) == canonical(&preset_dir()) || crate::shipped::is_shipped(current) {
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

/// The files a path dialog of `kind` lists in texplore's own chooser.
fn extensions(kind: DialogKind) -> &'static [&'static str] {
    match kind {
        DialogKind::Open => &["ron", "png"],
        DialogKind::SaveAs => &["ron"],
        DialogKind::Screenshot => &["png"],
        DialogKind::Image => &IMAGE_EXTENSIONS,
        DialogKind::Mesh => &["ply", "obj"],
    }
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
            protected: Vec::new(),
            read_only: None,
            link_ask: None,
            links: super::links::LinkDialog::default(),
        }
    }

    /// Makes `scenes` (the lessons' presets) read-only in the window, as shipped files are.
    pub fn protect(&mut self, scenes: Vec<PathBuf>) {
        if scenes != self.protected {
            self.protected = scenes;
            self.read_only = None;
        }
    }

    /// Why the scene's file `current` cannot be saved over, if it cannot.
    fn read_only(&mut self, current: &Path) -> Option<String> {
        match &self.read_only {
            Some((p, why)) if p == current => why.clone(),
            _ => {
                let why = read_only_reason(current, &self.protected);
                self.read_only = Some((current.to_path_buf(), why.clone()));
                why
            }
        }
    }

    /// Save: over the preset the scene came from, after the replace prompt; a read-only file
    /// (shipped, or a lesson's scene) or a PNG opens *Save as*, saying why.
    fn save(&mut self, current: &Path) {
        if let Some(why) = self.read_only(current) {
            self.save_as_copy(current, why, None);
        } else if current.extension().is_some_and(|e| e == "ron") {
            // Never overwrite without asking: the replace prompt confirms.
            self.overwrite = Some((Command::Save(current.to_path_buf()), None));
        } else {
            self.open_dialog(DialogKind::SaveAs, String::new());
        }
    }

    /// *Save as* for a read-only `current`, suggesting a copy in the user's folder; `then` runs
    /// once it is saved.
    fn save_as_copy(&mut self, current: &Path, why: String, then: Option<Pending>) {
        self.open_dialog(
            DialogKind::SaveAs,
            copy_default(current).display().to_string(),
        );
        if let Some(d) = &mut self.dialog {
            d.note = Some(why);
            d.then = then;
        }
    }

    /// The built-in presets in the lecture's order ([`crate::scene::LECTURE_ORDER`]), each
    /// with its description.
    fn presets(&mut self) -> Vec<(PathBuf, String)> {
        self.presets
            .get_or_insert_with(|| crate::scene::presets_in_lecture_order(&preset_dir()))
            .clone()
    }

    fn open_dialog(&mut self, kind: DialogKind, text: String) {
        self.dialog = Some(Dialog {
            kind,
            text,
            description: None,
            focus: true,
            note: None,
            then: None,
            refused: None,
            folders: false,
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

    /// The File menu's links: *Copy link to this scene*, *Open link…*.
    fn link_items(&mut self, ui: &mut egui::Ui) {
        if ui
            .button("Copy link to this scene")
            .on_hover_text(
                "A link that opens this scene: the scene travels inside it (no server); \
                 only the shipped images and meshes go with it",
            )
            .clicked()
        {
            self.link_ask = Some(super::links::LinkAsk::Copy);
        }
        if ui
            .button("Open link…")
            .on_hover_text("Opens a link made by Copy link to this scene")
            .clicked()
        {
            self.link_ask = Some(super::links::LinkAsk::Open);
        }
    }

    /// The link dialogs, for the scene `desc` of the folder `folder`; returns the command to
    /// run.
    pub fn link_dialogs(
        &mut self,
        ctx: &egui::Context,
        desc: Option<&crate::scene::SceneDesc>,
        folder: &Path,
    ) -> Option<Command> {
        let ask = self.link_ask.take();
        match self.links.ui(ctx, ask, desc, folder) {
            // A scene link opens as File > Open does: unsaved changes are asked about first.
            Some(Command::Open(path)) => {
                self.request_open(path);
                None
            }
            other => other,
        }
    }

    /// The menu bar. `edit` fills the Edit menu, `view` the View menu and `help` the Help
    /// menu.
    pub fn menu_bar(
        &mut self,
        ui: &mut egui::Ui,
        current: &Path,
        edit: impl FnOnce(&mut egui::Ui),
        view: impl FnOnce(&mut egui::Ui),
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
            self.save(current);
        }
        if open {
            self.open_dialog(DialogKind::Open, String::new());
        }
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("Open…").clicked() {
                    self.open_dialog(DialogKind::Open, String::new());
                }
                self.link_items(ui);
                let read_only = self.read_only(current);
                if ui
                    .button("Save")
                    .on_hover_text(read_only.clone().unwrap_or_else(|| {
                        "Save the scene over the preset it came from".to_owned()
                    }))
                    .clicked()
                {
                    self.save(current);
                }
                if ui.button("Save as…").clicked() {
                    if let Some(why) = read_only {
                        self.save_as_copy(current, why, None);
                    } else {
                        let name = current.with_extension("ron").display().to_string();
                        self.open_dialog(DialogKind::SaveAs, name);
                    }
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
                // A page is closed with its tab: no Quit there.
                #[cfg(not(target_arch = "wasm32"))]
                {
                    ui.separator();
                    if ui.button("Quit").clicked() {
                        self.requested = Some(Pending::Quit);
                    }
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
            ui.menu_button("View", view);
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
        self.fall_back();
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
                let current = self.current.clone();
                let read_only = self.read_only(&current);
                if let Some(why) = &read_only {
                    ui.weak(why);
                }
                ui.horizontal(|ui| {
                    let is_ron = current.extension().is_some_and(|e| e == "ron");
                    if let Some(why) = &read_only {
                        if ui
                            .button("Save as… and continue")
                            .on_hover_text("Save the scene under another name, then go on")
                            .clicked()
                        {
                            self.save_as_copy(&current, why.clone(), Some(pending.clone()));
                            self.prompt = None;
                        }
                    } else if is_ron
                        && ui
                            .button("Save and continue")
                            .on_hover_text(format!("Save to {}", current.display()))
                            .clicked()
                    {
                        out.push(Command::Save(current.clone()));
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
        if let Some((action, then)) = self.overwrite.clone() {
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
                        if let Some(then) = then.clone() {
                            out.push(self.confirm(then));
                        }
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

    /// The system's file dialog for a path dialog of `kind`, starting at the folder of the path
    /// `text` (or of the scene's file); returns whether a file was chosen (then in `text`).
    fn browse(&self, kind: DialogKind, text: &mut String) -> bool {
        let what = match kind {
            DialogKind::Open => BrowseFor::Scene,
            DialogKind::SaveAs => BrowseFor::Preset,
            DialogKind::Screenshot => BrowseFor::Screenshot,
            DialogKind::Image => BrowseFor::Image,
            DialogKind::Mesh => BrowseFor::Mesh,
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
        let picked = self.browser.pick(what, start, &name);
        if let Some(p) = &picked {
            *text = p.display().to_string();
        }
        picked.is_some()
    }

    /// A *Browse…* found no system dialog: the path dialog says why, and an image or a mesh
    /// asked for by the scene panel gets a path dialog of its own.
    fn fall_back(&mut self) {
        let Some((what, start)) = self.browser.take_fallback() else {
            return;
        };
        let why = self.browser.missing().unwrap_or_default();
        let kind = match what {
            BrowseFor::Image => Some(DialogKind::Image),
            BrowseFor::Mesh => Some(DialogKind::Mesh),
            BrowseFor::Scene | BrowseFor::Preset | BrowseFor::Screenshot => None,
        };
        if let Some(kind) = kind {
            let folder = std::path::absolute(&start).unwrap_or(start);
            let text = format!("{}{}", folder.display(), std::path::MAIN_SEPARATOR);
            self.open_dialog(kind, text);
        }
        if let Some(d) = &mut self.dialog {
            d.note = Some(why);
        }
    }

    /// The shipped files of one kind, for the quick picks of the image and mesh dialogs.
    fn shipped_assets(kind: DialogKind) -> Vec<PathBuf> {
        let Ok(root) = crate::shipped::root() else {
            return Vec::new();
        };
        crate::shipped::files()
            .into_iter()
            .map(|(p, _)| root.join(p))
            .filter(|p| p.starts_with(root.join("assets")))
            .filter(|p| match kind {
                DialogKind::Image => is_image(p),
                _ => p.extension().is_some_and(|e| {
                    e.eq_ignore_ascii_case("ply") || e.eq_ignore_ascii_case("obj")
                }),
            })
            .collect()
    }

    /// The files a path dialog offers to pick (a click puts the path in `text`): the shipped
    /// images or meshes, or the built-in presets and the recent files not among them.
    fn quick_picks(&mut self, ui: &mut egui::Ui, kind: DialogKind, text: &mut String) {
        let (heading, files): (&str, Vec<PathBuf>) = match kind {
            DialogKind::Image | DialogKind::Mesh => {
                ("Shipped with texplore:", Self::shipped_assets(kind))
            }
            DialogKind::Open => {
                let presets: Vec<PathBuf> = self.presets().into_iter().map(|(p, _)| p).collect();
                let builtin: Vec<PathBuf> = presets.iter().map(|p| canonical(p)).collect();
                let recent = self
                    .recent
                    .iter()
                    .filter(|r| !builtin.contains(&canonical(r)))
                    .cloned();
                (
                    "Built-in presets and recent files:",
                    presets.iter().cloned().chain(recent).collect(),
                )
            }
            DialogKind::SaveAs | DialogKind::Screenshot => return,
        };
        ui.label(heading);
        egui::ScrollArea::vertical()
            .max_height(200.0)
            .show(ui, |ui| {
                for p in files {
                    if ui
                        .selectable_label(false, p.display().to_string())
                        .clicked()
                    {
                        *text = p.display().to_string();
                    }
                }
            });
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
