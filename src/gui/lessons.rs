//! The Lessons panel: a picker of the lessons in `lessons/`, the lesson's text, its *Try this*
//! experiments (each a button that edits the scene, with *Undo* back to the scene before it),
//! their *Look for* sentences, the question with *Show answer*, and Previous / Next.
//!
//! The panel never touches the app: it returns a [`Command`] (open a lesson's preset, put
//! an edited description in place) that the app carries out the way it carries out every
//! other panel's edit.

use super::command::Command;
use crate::lesson::{LESSON_DIR, Lesson, Lessons, load_dir};
use crate::scene::SceneDesc;
use std::path::{Path, PathBuf};

/// An experiment applied to the scene, and the scene before it.
struct Applied {
    experiment: usize,
    before: SceneDesc,
}

/// The panel's state.
pub struct LessonsPanel {
    /// Whether the panel shows (View → Lessons).
    pub open: bool,
    dir: PathBuf,
    loaded: Option<Lessons>,
    /// The lesson the picker shows.
    selected: usize,
    /// Whether the scene is the selected lesson's (opened from it, perhaps with experiments).
    active: bool,
    /// The lesson whose preset the app was asked to open.
    pending: Option<usize>,
    /// Experiments applied, oldest first.
    applied: Vec<Applied>,
    /// The scene as the lesson's experiments last left it (edits beyond it are the learner's).
    lesson_desc: Option<SceneDesc>,
    show_answer: bool,
}

impl Default for LessonsPanel {
    fn default() -> Self {
        Self::new(PathBuf::from(LESSON_DIR))
    }
}

impl LessonsPanel {
    /// A closed panel over the lessons in `dir` (read when the panel first shows).
    #[must_use]
    pub fn new(dir: PathBuf) -> Self {
        Self {
            open: false,
            dir,
            loaded: None,
            selected: 0,
            active: false,
            pending: None,
            applied: Vec::new(),
            lesson_desc: None,
            show_answer: false,
        }
    }

    /// Reads the lessons again (Rescan): a file dropped into the folder appears.
    pub fn rescan(&mut self) {
        let name = self.lesson().map(|l| l.name.clone());
        let loaded = load_dir(&self.dir).unwrap_or_else(|e| Lessons {
            lessons: Vec::new(),
            errors: vec![e],
        });
        self.selected = name
            .and_then(|n| loaded.lessons.iter().position(|l| l.name == n))
            .unwrap_or(0);
        self.loaded = Some(loaded);
    }

    fn lessons(&mut self) -> &Lessons {
        if self.loaded.is_none() {
            self.rescan();
        }
        self.loaded.get_or_insert_with(Lessons::default)
    }

    fn lesson(&self) -> Option<&Lesson> {
        self.loaded.as_ref()?.lessons.get(self.selected)
    }

    /// Opens the panel on the lesson named `name`, whose preset the app is opening.
    pub fn start(&mut self, name: &str) {
        self.open = true;
        let _ = self.lessons();
        if let Some(i) = self
            .loaded
            .as_ref()
            .and_then(|l| l.lessons.iter().position(|l| l.name == name))
        {
            self.selected = i;
            self.pending = Some(i);
        }
    }

    /// The app opened `path` (`ok`: successfully) with description `desc`: if it was the
    /// pending lesson's preset, that lesson becomes active; any other file ends the lesson.
    pub fn opened(&mut self, path: &Path, ok: bool, desc: Option<&SceneDesc>) {
        let pending = self.pending.take();
        if !ok {
            return;
        }
        let preset = |i: usize| {
            self.loaded
                .as_ref()
                .and_then(|l| l.lessons.get(i))
                .map(|l| l.preset.clone())
        };
        if let Some(i) = pending.filter(|&i| preset(i).as_deref() == Some(path)) {
            self.selected = i;
            self.active = true;
        } else {
            self.active = false;
        }
        self.applied.clear();
        self.lesson_desc = desc.cloned();
        self.show_answer = false;
    }

    fn go_to(&mut self, i: usize, desc: Option<&SceneDesc>, dirty: bool) -> Option<Command> {
        // The picker moves once the preset has opened (the prompt may be cancelled).
        let preset = self.loaded.as_ref()?.lessons.get(i)?.preset.clone();
        self.pending = Some(i);
        // The lesson's own experiments are not the learner's work: no prompt for them.
        let force = !dirty || (desc.is_some() && desc == self.lesson_desc.as_ref());
        Some(Command::OpenLesson { preset, force })
    }

    /// The panel. `desc` is the app's scene, `dirty` whether it has unsaved changes.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        desc: Option<&SceneDesc>,
        dirty: bool,
    ) -> Option<Command> {
        let mut action = None;
        let count = self.lessons().lessons.len();
        ui.horizontal(|ui| {
            ui.heading("Lessons");
            if ui
                .button("Rescan lessons")
                .on_hover_text(format!(
                    "Read {} again (a lesson file dropped there appears)",
                    self.dir.display()
                ))
                .clicked()
            {
                self.rescan();
            }
        });
        let errors: Vec<String> = self
            .loaded
            .as_ref()
            .map(|l| l.errors.iter().map(ToString::to_string).collect())
            .unwrap_or_default();
        for e in errors {
            ui.colored_label(egui::Color32::LIGHT_RED, e);
        }
        if count == 0 {
            ui.label(format!("No lessons in {}.", self.dir.display()));
            return None;
        }
        let titles: Vec<String> = self
            .loaded
            .as_ref()
            .map(|l| {
                l.lessons
                    .iter()
                    .enumerate()
                    .map(|(i, l)| format!("{}. {}", i + 1, l.title))
                    .collect()
            })
            .unwrap_or_default();
        let mut pick = self.selected.min(count - 1);
        // The label on the left, the picker filling the rest (a label on the right, squeezed by
        // the picker, wrapped one letter per line). A little under the available width: the
        // full width would widen the panel every frame.
        ui.horizontal(|ui| {
            let label = ui.label("Lesson");
            egui::ComboBox::from_id_salt("lesson-picker")
                .width((ui.available_width() - 24.0).max(160.0))
                .selected_text(titles[pick].clone())
                .show_ui(ui, |ui| {
                    for (i, t) in titles.iter().enumerate() {
                        ui.selectable_value(&mut pick, i, t);
                    }
                })
                .response
                .labelled_by(label.id);
        });
        if pick != self.selected {
            action = self.go_to(pick, desc, dirty);
        }
        ui.horizontal(|ui| {
            let i = self.selected;
            if ui
                .add_enabled(i > 0, egui::Button::new("Previous lesson"))
                .clicked()
            {
                action = self.go_to(i - 1, desc, dirty);
            }
            if ui
                .add_enabled(i + 1 < count, egui::Button::new("Next lesson"))
                .clicked()
            {
                action = self.go_to(i + 1, desc, dirty);
            }
        });
        ui.separator();
        let Some(lesson) = self.lesson().cloned() else {
            return action;
        };
        egui::ScrollArea::vertical().show(ui, |ui| {
            ui.heading(&lesson.title);
            for para in lesson.text.split("\n\n") {
                let para = para.trim_end();
                if para.lines().all(|l| l.starts_with("    ")) {
                    // Indented paragraphs are formulas: keep their lines and spacing.
                    ui.label(egui::RichText::new(para).monospace());
                } else {
                    ui.label(para.replace('\n', " "));
                }
                ui.add_space(4.0);
            }
            ui.separator();
            if !self.active {
                ui.label("The scene is not this lesson's.");
                if ui.button("Open the lesson's scene").clicked() {
                    action = self.go_to(self.selected, desc, dirty);
                }
            }
            ui.strong("Try this");
            self.experiments_ui(ui, &lesson, desc, &mut action);
            ui.separator();
            ui.strong("Question");
            ui.label(&lesson.question);
            ui.toggle_value(&mut self.show_answer, "Show answer");
            if self.show_answer {
                ui.label(egui::RichText::new(&lesson.answer).italics());
            }
        });
        action
    }

    /// The *Try this* buttons with their Undo and Look-for lines.
    fn experiments_ui(
        &mut self,
        ui: &mut egui::Ui,
        lesson: &Lesson,
        desc: Option<&SceneDesc>,
        action: &mut Option<Command>,
    ) {
        for (k, x) in lesson.experiments.iter().enumerate() {
            let applied = self.applied.iter().any(|a| a.experiment == k);
            ui.horizontal(|ui| {
                let button = egui::Button::new(&x.label).selected(applied);
                if ui
                    .add_enabled(self.active && desc.is_some(), button)
                    .on_hover_text(
                        x.edits
                            .iter()
                            .map(|e| format!("{} = {}", e.path, e.value))
                            .collect::<Vec<_>>()
                            .join("\n"),
                    )
                    .clicked()
                    && let Some(d) = desc
                {
                    match x.apply(d) {
                        Ok(new) => {
                            // Pressed again: Undo still goes back to before the first press.
                            if !applied {
                                self.applied.push(Applied {
                                    experiment: k,
                                    before: d.clone(),
                                });
                            }
                            self.lesson_desc = Some(new.clone());
                            *action = Some(Command::Apply(new));
                        }
                        Err(e) => {
                            *action = Some(Command::Error(format!(
                                "{}: \"{}\": {e}",
                                lesson.file.display(),
                                x.label
                            )));
                        }
                    }
                }
                if applied
                    && ui
                        .button("Undo")
                        .on_hover_text("Back to the scene before this experiment")
                        .clicked()
                    && let Some(pos) = self.applied.iter().position(|a| a.experiment == k)
                {
                    // Undoing an experiment also drops those applied after it.
                    let before = self.applied[pos].before.clone();
                    self.applied.truncate(pos);
                    self.lesson_desc = Some(before.clone());
                    *action = Some(Command::Apply(before));
                }
            });
            ui.horizontal_wrapped(|ui| {
                ui.weak("Look for:");
                ui.label(&x.look_for);
            });
            ui.add_space(4.0);
        }
    }
}

/// What presentation mode shows over the image for the lesson on screen.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Caption {
    /// The experiment applied last: its label and its *Look for*.
    pub experiment: Option<(String, String)>,
    /// The lesson's question.
    pub question: String,
}

impl LessonsPanel {
    /// The captions for presentation mode: `None` unless the scene is a lesson's.
    #[must_use]
    pub fn caption(&self) -> Option<Caption> {
        let lesson = self.lesson().filter(|_| self.active)?;
        let experiment = self
            .applied
            .last()
            .and_then(|a| lesson.experiments.get(a.experiment))
            .map(|x| (x.label.clone(), x.look_for.clone()));
        Some(Caption {
            experiment,
            question: lesson.question.clone(),
        })
    }
}
