//! Files: the menu bar, built-in presets, open / save / save-as / screenshot dialogs (a path
//! field with quick picks, no native dialog), recent files, dropped files, and the prompts that
//! guard unsaved changes and existing files.

use crate::scene::read_png_preset;
use std::path::{Path, PathBuf};

/// How many recent files are remembered.
const MAX_RECENT: usize = 10;
/// Where the built-in presets live.
const PRESET_DIR: &str = "presets";

/// What the user asked the app to do with a file.
#[derive(Clone, Debug, PartialEq)]
pub enum FileAction {
    /// Replace the scene with this preset or texplore PNG.
    Open(PathBuf),
    /// Save the scene as a RON preset here.
    Save(PathBuf),
    /// Save the image here as a PNG with the scene embedded.
    Screenshot(PathBuf),
    /// Put this image on the selected object.
    UseImage(PathBuf),
    /// Make the selected object this mesh (PLY or OBJ).
    UseMesh(PathBuf),
    /// Show this message.
    Error(String),
    /// Close the window.
    Quit,
}

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

/// The files state.
pub struct Files {
    recent: Vec<PathBuf>,
    recent_file: Option<PathBuf>,
    dialog: Option<(DialogKind, String)>,
    requested: Option<Pending>,
    prompt: Option<Pending>,
    overwrite: Option<FileAction>,
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

fn list_presets() -> Vec<PathBuf> {
    crate::scene::list_presets(Path::new(PRESET_DIR)).unwrap_or_default()
}

fn stem(p: &Path) -> String {
    p.file_stem().map_or_else(
        || p.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    )
}

fn is_image(p: &Path) -> bool {
    p.extension().and_then(|e| e.to_str()).is_some_and(|e| {
        [
            "png", "jpg", "jpeg", "hdr", "exr", "tif", "tiff", "ppm", "pgm",
        ]
        .contains(&e.to_ascii_lowercase().as_str())
    })
}

/// Largest recent-files list read (a list of paths takes a few kilobytes).
const MAX_RECENT_BYTES: u64 = 1 << 20;

impl Files {
    /// Reads the recent-files list from `recent_file` (a missing or bad file is an empty list).
    #[must_use]
    pub fn new(recent_file: Option<PathBuf>) -> Self {
        let recent = recent_file
            .as_deref()
            .and_then(|f| crate::input::read_input_text(f, MAX_RECENT_BYTES).ok())
            .and_then(|t| ron::from_str::<Vec<PathBuf>>(&t).ok())
            .unwrap_or_default();
        Self {
            recent,
            recent_file,
            dialog: None,
            requested: None,
            prompt: None,
            overwrite: None,
            close_ok: false,
            current: PathBuf::new(),
        }
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

    /// The menu bar. `toggles` are the View menu's panels.
    pub fn menu_bar<const N: usize>(
        &mut self,
        ui: &mut egui::Ui,
        current: &Path,
        toggles: [(&mut bool, &str); N],
    ) {
        self.current = current.to_path_buf();
        // Ctrl+S saves (over a .ron, else asks where), Ctrl+O opens.
        let (save, open) = ui.input_mut(|i| {
            (
                i.consume_shortcut(&egui::KeyboardShortcut::new(
                    egui::Modifiers::COMMAND,
                    egui::Key::S,
                )),
                i.consume_shortcut(&egui::KeyboardShortcut::new(
                    egui::Modifiers::COMMAND,
                    egui::Key::O,
                )),
            )
        });
        if save {
            if current.extension().is_some_and(|e| e == "ron") {
                // Never overwrite without asking: the replace prompt confirms.
                self.overwrite = Some(FileAction::Save(current.to_path_buf()));
            } else {
                self.dialog = Some((DialogKind::SaveAs, String::new()));
            }
        }
        if open {
            self.dialog = Some((DialogKind::Open, String::new()));
        }
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("Open…").clicked() {
                    self.dialog = Some((DialogKind::Open, String::new()));
                }
                let is_ron = current.extension().is_some_and(|e| e == "ron");
                if ui
                    .button("Save")
                    .on_hover_text("Save the scene over the preset it came from")
                    .clicked()
                {
                    if is_ron {
                        // Never overwrite without asking: the replace prompt confirms.
                        self.overwrite = Some(FileAction::Save(current.to_path_buf()));
                    } else {
                        self.dialog = Some((DialogKind::SaveAs, String::new()));
                    }
                }
                if ui.button("Save as…").clicked() {
                    let name = current.with_extension("ron").display().to_string();
                    self.dialog = Some((DialogKind::SaveAs, name));
                }
                if ui
                    .button("Save screenshot…")
                    .on_hover_text(concat!(
                        "A PNG of the image with the scene inside: ",
                        "open or drop it to restore the scene"
                    ))
                    .clicked()
                {
                    let name = format!("{}-shot.png", stem(current));
                    self.dialog = Some((DialogKind::Screenshot, name));
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
            ui.menu_button("Presets", |ui| {
                for p in list_presets() {
                    if ui.button(stem(&p)).clicked() {
                        self.requested = Some(Pending::Open(p));
                    }
                }
            });
            ui.menu_button("View", |ui| {
                for (flag, name) in toggles {
                    ui.checkbox(flag, name);
                }
            });
            let name = current
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
            ui.weak(format!("  {name}"))
                .on_hover_text(current.display().to_string());
        });
    }

    /// Files dropped on the window: presets and texplore PNGs open; other images and meshes go
    /// on the selected object.
    pub fn dropped(&mut self, ctx: &egui::Context) -> Vec<FileAction> {
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
                Some("ply" | "obj") => out.push(FileAction::UseMesh(p)),
                _ if is_image(&p) => out.push(FileAction::UseImage(p)),
                _ => out.push(FileAction::Error(format!(
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

    /// The dialogs and prompts; returns what the user confirmed.
    pub fn dialogs(&mut self, ctx: &egui::Context, dirty: bool) -> Vec<FileAction> {
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
                        out.push(FileAction::Save(self.current.clone()));
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
                FileAction::Save(p) | FileAction::Screenshot(p) => p.display().to_string(),
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
        if let Some((kind, mut text)) = self.dialog.take() {
            let mut keep = true;
            let title = match kind {
                DialogKind::Open => "Open a preset or a texplore PNG",
                DialogKind::SaveAs => "Save the scene as a preset (.ron)",
                DialogKind::Screenshot => "Save a screenshot (.png, with the scene inside)",
            };
            egui::Modal::new(egui::Id::unique("path-dialog")).show(ctx, |ui| {
                ui.heading(title);
                let mut go = false;
                ui.horizontal(|ui| {
                    let l = ui.label("Path");
                    let r = ui
                        .add(egui::TextEdit::singleline(&mut text).desired_width(360.0))
                        .labelled_by(l.id);
                    go |= r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                });
                if kind == DialogKind::Open {
                    ui.label("Built-in presets and recent files:");
                    egui::ScrollArea::vertical()
                        .max_height(200.0)
                        .show(ui, |ui| {
                            for p in list_presets()
                                .into_iter()
                                .chain(self.recent.iter().cloned())
                            {
                                if ui
                                    .selectable_label(false, p.display().to_string())
                                    .clicked()
                                {
                                    text = p.display().to_string();
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
                            let action = if kind == DialogKind::SaveAs {
                                FileAction::Save(p.clone())
                            } else {
                                FileAction::Screenshot(p.clone())
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
            if keep {
                self.dialog = Some((kind, text));
            }
        }
        out
    }

    fn confirm(&mut self, p: Pending) -> FileAction {
        match p {
            Pending::Open(path) => FileAction::Open(path),
            Pending::Quit => {
                self.close_ok = true;
                FileAction::Quit
            }
        }
    }
}
