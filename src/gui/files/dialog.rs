//! The path dialog (Open, Save as, Save screenshot, and an image or a mesh where the system
//! has no file dialog): a path field, *Browse…* (the system's dialog, or texplore's own folder
//! list), the quick picks, and for a save why the path is refused, at the button, with the
//! user's own folder offered.

use super::{Command, DialogKind, Files, Pending, extensions, folder, save};
use std::path::{Path, PathBuf};

impl Files {
    /// The path dialog (Open, Save as, Save screenshot), while open; what it confirms goes to
    /// `out` (or to the replace prompt).
    pub(super) fn path_dialog(
        &mut self,
        ctx: &egui::Context,
        description: &str,
        out: &mut Vec<Command>,
    ) {
        if let Some(mut dialog) = self.dialog.take() {
            let kind = dialog.kind;
            let mut keep = true;
            let title = match kind {
                DialogKind::Open => "Open a preset or a texplore PNG",
                DialogKind::SaveAs => "Save the scene as a preset (.ron)",
                DialogKind::Screenshot => "Save a screenshot (.png, with the scene inside)",
                DialogKind::Image => "Choose an image for the selected object",
                DialogKind::Mesh => "Choose a mesh (PLY, OBJ) for the selected object",
            };
            let modal = egui::Modal::new(egui::Id::unique("path-dialog")).show(ctx, |ui| {
                ui.heading(title);
                if let Some(note) = &dialog.note {
                    ui.label(note);
                } else if let Some(why) = self.browser.missing() {
                    // No system dialog: Browse… lists the folders here instead, and says why.
                    ui.weak(why);
                }
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
                    let native = self.browser.missing().is_none();
                    if ui
                        .button("Browse…")
                        .on_hover_text(if native {
                            "Choose the file in the system's file dialog"
                        } else {
                            "List the folders and files here (the system has no file dialog)"
                        })
                        .clicked()
                    {
                        if native {
                            go |= self.browse(kind, text);
                        }
                        // No system dialog (known now, or found by this click): texplore's own.
                        dialog.folders = self.browser.missing().is_some() && (!native || !go);
                    }
                });
                if dialog.folders {
                    let saving = matches!(kind, DialogKind::SaveAs | DialogKind::Screenshot);
                    folder::folder_view(ui, text, extensions(kind), saving);
                }
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
                self.quick_picks(ui, kind, text);
                // Why the path typed cannot be saved to, said at the button (checked again
                // only when the path changes).
                let typed = text.trim().to_owned();
                let refused = match &dialog.refused {
                    Some((t, why)) if *t == typed => why.clone(),
                    _ => {
                        let why = save::refusal(kind, Path::new(&typed), &self.protected);
                        dialog.refused = Some((typed.clone(), why.clone()));
                        why
                    }
                };
                ui.horizontal(|ui| {
                    let ok = match kind {
                        DialogKind::Open => "Open",
                        DialogKind::Image | DialogKind::Mesh => "Use",
                        DialogKind::SaveAs | DialogKind::Screenshot => "Save",
                    };
                    let enabled = !typed.is_empty() && refused.is_none();
                    let button = ui.add_enabled(enabled, egui::Button::new(ok));
                    go |= button.clicked();
                    if let Some(why) = &refused {
                        button.on_disabled_hover_text(why);
                    }
                    if ui.button("Cancel").clicked() {
                        keep = false;
                    }
                });
                if let Some(why) = &refused {
                    // Said once: the note at the top may say it already.
                    if dialog.note.as_ref() != Some(why) {
                        ui.colored_label(ui.visuals().error_fg_color, why);
                    }
                    let offer = save::your_folder(kind, Path::new(&typed), &self.current);
                    if ui
                        .button(format!("Save in your folder: {}", offer.display()))
                        .on_hover_text("Puts this path in the field; Save then saves there")
                        .clicked()
                    {
                        *text = offer.display().to_string();
                    }
                }
                if go && !typed.is_empty() && refused.is_none() {
                    let p = PathBuf::from(&typed);
                    keep = false;
                    match kind {
                        DialogKind::Open => self.requested = Some(Pending::Open(p)),
                        DialogKind::Image => out.push(Command::UseImage(p)),
                        DialogKind::Mesh => out.push(Command::UseMesh(p)),
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
                            let then = dialog.then.take();
                            if p.exists() {
                                self.overwrite = Some((action, then));
                            } else {
                                out.push(action);
                                if let Some(then) = then {
                                    out.push(self.confirm(then));
                                }
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
}
