//! Links that open a scene, in the window (issue 36 §5): *File > Copy link to this scene* (and
//! the link beside each lesson experiment) put the scene in an address's fragment
//! ([`crate::link`]), shown in a dialog and copied; *File > Open link…* opens one pasted (a
//! lesson link opens the lesson, with the Lessons panel, at its experiment).

use super::command::Command;
use crate::scene::SceneDesc;
use std::path::Path;

/// What the File menu asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LinkAsk {
    /// Copy a link to the scene showing.
    Copy,
    /// Open a link pasted.
    Open,
}

/// The link dialogs' state.
#[derive(Debug, Default)]
pub struct LinkDialog {
    /// The link made, with the notices (files left out), shown until closed.
    made: Option<(String, Vec<String>)>,
    /// The link being pasted, and why it was refused.
    open: Option<(String, Option<String>)>,
    /// A lesson link opened: the lesson and its experiment, for the Lessons panel.
    lesson: Option<(String, Option<usize>)>,
    /// A link to open at the next frame (in a page, one put in the address bar).
    follow: Option<String>,
}

/// The page's address without its fragment (in a page), so a link is whole; elsewhere nothing:
/// the teacher's page address goes before the `#`.
pub(super) fn page_address() -> String {
    #[cfg(target_arch = "wasm32")]
    if let Some(l) = web_sys::window().map(|w| w.location()) {
        return format!(
            "{}{}",
            l.origin().unwrap_or_default(),
            l.pathname().unwrap_or_default()
        );
    }
    String::new()
}

/// In a page, puts `fragment` in the address bar (replacing the entry, so Back is unchanged):
/// the address is then the link, and a reload opens the page where it was (the page's start
/// makes the link's scene again). Elsewhere nothing.
pub(super) fn show_in_address(fragment: &str) {
    #[cfg(target_arch = "wasm32")]
    if let Some(history) = web_sys::window().and_then(|w| w.history().ok()) {
        let _ = history.replace_state_with_url(
            &wasm_bindgen::JsValue::NULL,
            "",
            Some(&format!("#{fragment}")),
        );
    }
    #[cfg(not(target_arch = "wasm32"))]
    let _ = fragment;
}

impl LinkDialog {
    /// The lesson (its name) and experiment of a lesson link just opened, for the Lessons
    /// panel to start on while its preset opens.
    pub fn take_lesson(&mut self) -> Option<(String, Option<usize>)> {
        self.lesson.take()
    }

    /// Opens `link` at the next frame (a refused link's reason shows in the status line): in a
    /// page, a link put in the address bar.
    #[cfg_attr(not(target_arch = "wasm32"), allow(dead_code))]
    pub fn follow(&mut self, link: String) {
        self.follow = Some(link);
    }

    /// The command that opens `link`'s scene file, or none for a lesson link (the lesson and
    /// experiment then wait in [`LinkDialog::take_lesson`] for the Lessons panel to open).
    fn command_for(&mut self, link: &str) -> Result<Option<Command>, String> {
        match crate::link::resolve(link).map_err(|e| e.to_string())? {
            crate::link::Target::Scene(path) => Ok(Some(Command::Open(path))),
            crate::link::Target::Lesson(lesson, k) => {
                self.lesson = Some((lesson.name.clone(), k));
                Ok(None)
            }
        }
    }

    /// Handles `ask` and draws the dialogs open; returns the command to run (a file to open,
    /// an error).
    pub fn ui(
        &mut self,
        ctx: &egui::Context,
        ask: Option<LinkAsk>,
        desc: Option<&SceneDesc>,
        folder: &Path,
    ) -> Option<Command> {
        let mut out = None;
        if let Some(link) = self.follow.take() {
            out = self
                .command_for(&link)
                .unwrap_or_else(|e| Some(Command::Error(e)));
        }
        match ask {
            Some(LinkAsk::Copy) => match desc.map(|d| crate::link::scene_fragment(d, folder)) {
                Some(Ok((fragment, notices))) => {
                    show_in_address(&fragment);
                    let link = format!("{}#{fragment}", page_address());
                    ctx.copy_text(link.clone());
                    self.made = Some((link, notices));
                }
                Some(Err(e)) => out = Some(Command::Error(e.to_string())),
                None => {}
            },
            Some(LinkAsk::Open) => self.open = Some((String::new(), None)),
            None => {}
        }
        if let Some((link, notices)) = &self.made {
            let mut close = false;
            egui::Modal::new(egui::Id::unique("texplore-link-made")).show(ctx, |ui| {
                ui.heading("Link to this scene");
                ui.label("Copied. Anyone who opens it sees this scene (the page needs no server):");
                let mut text = link.clone();
                let label = ui.label("Link");
                ui.add(
                    egui::TextEdit::multiline(&mut text)
                        .desired_rows(3)
                        .desired_width(480.0),
                )
                .labelled_by(label.id);
                if link.starts_with('#') {
                    ui.weak("Put your page's address (where students open texplore) before the #.");
                }
                for n in notices {
                    ui.colored_label(egui::Color32::from_rgb(230, 160, 60), n);
                }
                close = ui.button("Close").clicked();
            });
            if close {
                self.made = None;
            }
        }
        if let Some((text, error)) = &mut self.open {
            let (mut go, mut close) = (false, false);
            egui::Modal::new(egui::Id::unique("texplore-link-open")).show(ctx, |ui| {
                ui.heading("Open link");
                ui.label("Paste a link to a scene (it ends in #texplore1-…):");
                let field = ui.horizontal(|ui| {
                    let label = ui.label("Link");
                    ui.add(egui::TextEdit::singleline(text).desired_width(440.0))
                        .labelled_by(label.id)
                });
                let field = field.inner;
                go = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                if let Some(e) = error.as_ref() {
                    ui.colored_label(egui::Color32::from_rgb(230, 90, 80), e);
                }
                ui.horizontal(|ui| {
                    go |= ui.button("Open").clicked();
                    close = ui.button("Cancel").clicked();
                });
            });
            let link = text.clone();
            if go {
                if let Ok(f) = crate::link::fragment(&link) {
                    show_in_address(f);
                }
                match self.command_for(&link) {
                    Ok(c) => {
                        out = c;
                        close = true;
                    }
                    Err(e) => {
                        if let Some((_, error)) = &mut self.open {
                            *error = Some(e);
                        }
                    }
                }
            }
            if close {
                self.open = None;
            }
        }
        out
    }
}
