//! The Lessons panel: a picker of the lessons (the shipped ones and the teacher's own, see
//! [`crate::lesson::default_dirs`]), the lesson's text (Markdown), its *Try this* experiments
//! (each a button that puts the lesson's scene with that experiment's edits in place, with
//! *Undo* back to the scene it started from), their *Look for* sentences, the question with
//! *Show answer*, and Previous / Next.
//!
//! Experiments are independent: each applies to the lesson's own scene (as its preset opened),
//! or, when it says `after = "label"`, to that experiment's scene. Which experiment shows as
//! applied is read from the scene itself, so *Edit → Undo* and the panel always agree.
//!
//! The panel never touches the app: it returns a [`Command`] (open a lesson's preset, put
//! an edited description in place) that the app carries out the way it carries out every
//! other panel's edit.

pub mod captions;
mod exercise;

use super::command::Command;
use crate::lesson::{Lesson, Lessons, edit::value_at, load_default, load_dirs};
use crate::scene::SceneDesc;
use std::path::{Path, PathBuf};

/// Which experiments the scene shows, worked out once per change of the scene.
struct Shown {
    lesson: usize,
    desc: SceneDesc,
    applied: Vec<bool>,
}

/// The panel's state.
pub struct LessonsPanel {
    /// Whether the panel shows (View → Lessons).
    pub open: bool,
    /// The folders read; `None`: the shipped lessons and the teacher's own.
    dirs: Option<Vec<PathBuf>>,
    loaded: Option<Lessons>,
    /// The lesson the picker shows.
    selected: usize,
    /// Whether the scene is the selected lesson's (opened from it, perhaps with experiments).
    active: bool,
    /// The lesson whose preset the app was asked to open.
    pending: Option<usize>,
    /// The lesson's scene as its preset opened: what every experiment applies to.
    base: Option<SceneDesc>,
    /// The experiment the panel applied last (shown as applied while the scene has its edits).
    last: Option<usize>,
    shown: Option<Shown>,
    show_answer: bool,
    /// The lesson whose text was drawn last: the text scrolls back to its top when another
    /// one is drawn.
    drawn: Option<usize>,
    markdown: egui_commonmark::CommonMarkCache,
    /// The lesson whose exercises are being written, and each exercise's fields and verdict.
    attempts: (Option<usize>, Vec<exercise::Attempt>),
    /// The experiment whose link was copied last, and the link.
    link: Option<(usize, String)>,
    /// The experiment to put in place once the pending lesson's scene has opened (a link to
    /// it, or a reload of the page on it).
    then: Option<usize>,
}

impl Default for LessonsPanel {
    fn default() -> Self {
        Self::with_dirs(None)
    }
}

impl LessonsPanel {
    /// A closed panel over the lessons in `dir` (read when the panel first shows); the shipped
    /// lessons' folder means the default folders (the shipped lessons and the teacher's own).
    #[must_use]
    pub fn new(dir: PathBuf) -> Self {
        let canonical = |p: &Path| std::fs::canonicalize(p).ok();
        let shipped = crate::shipped::lessons_dir().ok();
        if shipped.is_some_and(|s| canonical(&s).is_some() && canonical(&s) == canonical(&dir)) {
            Self::with_dirs(None)
        } else {
            Self::with_dirs(Some(vec![dir]))
        }
    }

    fn with_dirs(dirs: Option<Vec<PathBuf>>) -> Self {
        Self {
            open: false,
            dirs,
            loaded: None,
            selected: 0,
            active: false,
            pending: None,
            base: None,
            last: None,
            shown: None,
            show_answer: false,
            drawn: None,
            markdown: egui_commonmark::CommonMarkCache::default(),
            attempts: (None, Vec::new()),
            link: None,
            then: None,
        }
    }

    /// Where the lessons come from, for the Rescan button's tooltip.
    fn place(&self) -> String {
        match &self.dirs {
            Some(d) => d
                .iter()
                .map(|d| d.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
            None => crate::lesson::user_dir().map_or_else(
                || "the shipped lessons".to_owned(),
                |u| format!("the shipped lessons and {}", u.display()),
            ),
        }
    }

    /// Reads the lessons again (Rescan): a file dropped into the folder appears.
    pub fn rescan(&mut self) {
        let name = self.lesson().map(|l| l.file.clone());
        let loaded = match &self.dirs {
            Some(d) => load_dirs(d),
            None => load_default(),
        };
        self.selected = name
            .and_then(|n| loaded.lessons.iter().position(|l| l.file == n))
            .unwrap_or(0);
        self.loaded = Some(loaded);
        self.shown = None;
        self.attempts = (None, Vec::new());
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

    /// The scenes of the lessons (their presets): the window saves them only under another name.
    #[must_use]
    pub fn scenes(&self) -> Vec<PathBuf> {
        self.loaded
            .as_ref()
            .map(|l| l.lessons.iter().map(|l| l.preset.clone()).collect())
            .unwrap_or_default()
    }

    /// Opens the panel on the lesson named `name`, whose preset the app is opening.
    pub fn start(&mut self, name: &str) {
        self.then = None;
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

    /// Opens the panel on lesson `name` at its experiment `k` (a link to it): the command that
    /// opens its preset, through the unsaved-changes prompt unless the scene is this lesson's
    /// own (as the panel's own Next and Previous do).
    pub fn open_at(
        &mut self,
        name: &str,
        k: Option<usize>,
        desc: Option<&SceneDesc>,
        dirty: bool,
    ) -> Command {
        let force = !dirty || desc.is_some_and(|d| self.is_lessons_own(d));
        self.start(name);
        self.then_experiment(k);
        let preset = self
            .pending
            .and_then(|i| self.loaded.as_ref()?.lessons.get(i))
            .map(|l| l.preset.clone());
        match preset {
            Some(preset) => Command::OpenLesson { preset, force },
            None => Command::Error(format!(
                "the link opens lesson {name}, which is not among {}",
                self.place()
            )),
        }
    }

    /// Once the lesson [`LessonsPanel::start`] opens has opened, its experiment `k` (0-based)
    /// is put in place ([`LessonsPanel::due`]), as if pressed.
    pub fn then_experiment(&mut self, k: Option<usize>) {
        self.then = k;
    }

    /// The experiment asked for by [`LessonsPanel::then_experiment`], once its lesson is the
    /// scene: the command that puts it in place.
    pub fn due(&mut self) -> Option<Command> {
        if self.pending.is_some() || !self.active {
            return None;
        }
        let k = self.then.take()?;
        let (lesson, base) = (self.lesson()?.clone(), self.base.clone()?);
        match lesson.scene(k, &base) {
            Ok(new) => {
                self.last = Some(k);
                Some(Command::Apply(new))
            }
            Err(e) => Some(Command::Error(format!("{}: {e}", lesson.file.display()))),
        }
    }

    /// The experiment the scene `desc` shows (the one pressed last if several), when it is the
    /// active lesson's: what a reload of the page puts back.
    #[must_use]
    pub fn experiment_shown(&self, desc: Option<&SceneDesc>) -> Option<usize> {
        if !self.active {
            return None;
        }
        let applied = self.applied_now(desc);
        self.last
            .filter(|&k| applied.get(k) == Some(&true))
            .or_else(|| applied.iter().position(|&a| a))
    }

    /// The app opened `path` (`ok`: successfully) with description `desc`: if it was the
    /// pending lesson's preset, that lesson becomes active; any other file ends the lesson.
    pub fn opened(&mut self, path: &Path, ok: bool, desc: Option<&SceneDesc>) {
        let pending = self.pending.take();
        if !ok {
            self.then = None;
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
            self.then = None;
        }
        self.base = desc.cloned();
        self.last = None;
        self.shown = None;
        self.show_answer = false;
    }

    /// The name of the lesson under way (its scene open from the panel), if any.
    #[must_use]
    pub fn active_lesson(&self) -> Option<String> {
        self.active
            .then(|| self.lesson().map(|l| l.name.clone()))
            .flatten()
    }

    /// Whether `desc` is the lesson's scene or one of its experiments' (not the learner's
    /// work: switching lessons asks nothing).
    fn is_lessons_own(&self, desc: &SceneDesc) -> bool {
        let (Some(base), Some(lesson)) = (&self.base, self.lesson()) else {
            return false;
        };
        self.active
            && (desc == base
                || (0..lesson.experiments.len())
                    .any(|k| lesson.scene(k, base).is_ok_and(|s| s == *desc)))
    }

    fn go_to(&mut self, i: usize, desc: Option<&SceneDesc>, dirty: bool) -> Option<Command> {
        // The picker moves once the preset has opened (the prompt may be cancelled).
        let preset = self.loaded.as_ref()?.lessons.get(i)?.preset.clone();
        self.pending = Some(i);
        let force = !dirty || desc.is_some_and(|d| self.is_lessons_own(d));
        Some(Command::OpenLesson { preset, force })
    }

    /// Which experiments `desc` shows: those whose scene it matches on every path the lesson's
    /// experiments set (read from the scene, so *Edit → Undo* and the panel agree).
    fn applied(&mut self, desc: Option<&SceneDesc>) -> Vec<bool> {
        let applied = self.applied_now(desc);
        if let Some(desc) = desc
            && self.active
        {
            self.shown = Some(Shown {
                lesson: self.selected,
                desc: desc.clone(),
                applied: applied.clone(),
            });
        }
        applied
    }

    /// [`LessonsPanel::applied`] without keeping the answer.
    fn applied_now(&self, desc: Option<&SceneDesc>) -> Vec<bool> {
        let count = self.lesson().map_or(0, |l| l.experiments.len());
        let (Some(desc), Some(base), Some(lesson), true) =
            (desc, self.base.as_ref(), self.lesson(), self.active)
        else {
            return vec![false; count];
        };
        if let Some(s) = &self.shown
            && s.lesson == self.selected
            && s.desc == *desc
        {
            return s.applied.clone();
        }
        // Every path any experiment of the lesson sets: an experiment shows when the scene
        // agrees with its own scene on all of them (so one that leaves the lookup alone is not
        // shown over another that changed it).
        let mut paths: Vec<&str> = lesson
            .experiments
            .iter()
            .flat_map(|x| x.edits.iter().map(|e| e.path.as_str()))
            .collect();
        paths.sort_unstable();
        paths.dedup();
        let now: Vec<_> = paths.iter().map(|p| value_at(desc, p)).collect();
        let holds: Vec<bool> = (0..count)
            .map(|k| {
                lesson.scene(k, base).is_ok_and(|scene| {
                    paths
                        .iter()
                        .zip(&now)
                        .all(|(p, v)| value_at(&scene, p) == *v)
                })
            })
            .collect();
        // Two experiments with the same scene: the one pressed last.
        match self.last.filter(|&k| holds.get(k) == Some(&true)) {
            Some(last) => (0..count).map(|k| k == last).collect(),
            None => holds,
        }
    }

    /// The panel. `desc` is the app's scene, `dirty` whether it has unsaved changes.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        desc: Option<&SceneDesc>,
        dirty: bool,
    ) -> Option<Command> {
        // Everything below wraps or truncates to the pane's width (the layout's, which the user
        // drags): a long title does not widen the pane.
        let width = ui.available_width();
        ui.set_max_width(width);
        let mut action = None;
        let count = self.lessons().lessons.len();
        ui.horizontal(|ui| {
            ui.heading("Lessons");
            if ui
                .button("Rescan lessons")
                .on_hover_text(format!(
                    "Read {} again (a lesson file dropped there appears)",
                    self.place()
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
            ui.label(format!("No lessons in {}.", self.place()));
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
        // The label on the left, the picker filling the rest, its text truncated.
        ui.horizontal(|ui| {
            let label = ui.label("Lesson");
            egui::ComboBox::from_id_salt("lesson-picker")
                .width((ui.available_width() - 8.0).max(120.0))
                .truncate()
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
        let mut scroll = egui::ScrollArea::vertical()
            .id_salt("lesson-text")
            .auto_shrink([false, false]);
        if self.drawn.replace(self.selected) != Some(self.selected) {
            scroll = scroll.vertical_scroll_offset(0.0);
        }
        scroll.show(ui, |ui| {
            ui.set_max_width(width);
            ui.heading(&lesson.title);
            for block in blocks(&lesson.text) {
                match block {
                    Block::Markdown(md) => {
                        egui_commonmark::CommonMarkViewer::new().show(ui, &mut self.markdown, &md);
                    }
                    Block::Formula(f) => {
                        egui::Frame::new()
                            .fill(ui.visuals().extreme_bg_color)
                            .inner_margin(4.0)
                            .show(ui, |ui| ui.label(egui::RichText::new(f).monospace()));
                        ui.add_space(4.0);
                    }
                }
            }
            ui.separator();
            if !self.active {
                ui.label("The scene is not this lesson's.");
                if ui.button("Open the lesson's scene").clicked() {
                    action = self.go_to(self.selected, desc, dirty);
                }
            }
            ui.strong("Try this");
            ui.weak("Each experiment starts from the lesson's scene.");
            self.experiments_ui(ui, &lesson, desc, &mut action);
            self.exercises_ui(ui, &lesson, desc, &mut action);
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
        let applied = self.applied(desc);
        for (k, x) in lesson.experiments.iter().enumerate() {
            let on = applied.get(k).copied().unwrap_or(false);
            ui.horizontal_wrapped(|ui| {
                let button = egui::Button::new(&x.label).selected(on);
                if ui
                    .add_enabled(self.active && self.base.is_some(), button)
                    .on_hover_text(
                        x.edits
                            .iter()
                            .map(|e| format!("{} = {}", e.path, e.value))
                            .collect::<Vec<_>>()
                            .join("\n"),
                    )
                    .clicked()
                    && let Some(base) = &self.base
                {
                    match lesson.scene(k, base) {
                        Ok(new) => {
                            self.last = Some(k);
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
                if ui
                    .small_button("Link")
                    .on_hover_text("Copies a link that opens this lesson at this experiment")
                    .clicked()
                {
                    let fragment = crate::link::lesson_fragment(&lesson.name, Some(k));
                    super::links::show_in_address(&fragment);
                    let link = format!("{}#{fragment}", super::links::page_address());
                    ui.ctx().copy_text(link.clone());
                    self.link = Some((k, link));
                }
                if on
                    && let Some(base) = &self.base
                    && ui
                        .button("Undo")
                        .on_hover_text(match x.after {
                            Some(a) => {
                                format!("Back to the scene of \"{}\"", lesson.experiments[a].label)
                            }
                            None => "Back to the lesson's scene".to_owned(),
                        })
                        .clicked()
                {
                    let back = match x.after {
                        Some(a) => lesson.scene(a, base).unwrap_or_else(|_| base.clone()),
                        None => base.clone(),
                    };
                    self.last = x.after;
                    *action = Some(Command::Apply(back));
                }
            });
            if let Some((_, link)) = self.link.as_ref().filter(|(j, _)| *j == k) {
                ui.weak(format!("Link copied: {link}"));
            }
            if let Some(a) = x.after {
                ui.weak(format!(
                    "Builds on \"{}\": its edits come first.",
                    lesson.experiments[a].label
                ));
            }
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
    /// The experiment the scene shows (the one pressed last if several): its label and its
    /// *Look for*.
    pub experiment: Option<(String, String)>,
    /// The lesson's question.
    pub question: String,
}

impl LessonsPanel {
    /// The captions for presentation mode over the scene `desc`: `None` unless the scene is a
    /// lesson's. The experiment is the one the panel shows as applied (read from the scene, so
    /// Undo takes its caption away too).
    pub fn caption(&mut self, desc: Option<&SceneDesc>) -> Option<Caption> {
        if !self.active {
            return None;
        }
        let _ = self.applied(desc);
        let shown = self.experiment_shown(desc);
        let lesson = self.lesson()?;
        let experiment = shown
            .and_then(|k| lesson.experiments.get(k))
            .map(|x| (x.label.clone(), x.look_for.clone()));
        Some(Caption {
            experiment,
            question: lesson.question.clone(),
        })
    }
}

/// A piece of a lesson's text.
#[derive(Debug, PartialEq)]
enum Block {
    /// Markdown (paragraphs, lists, emphasis, inline code), drawn by `egui_commonmark`.
    Markdown(String),
    /// A formula: a paragraph whose lines are all indented by four spaces (or a fenced code
    /// block), drawn as written in the monospace font. Kept out of `egui_commonmark`, whose code
    /// blocks carry a copy button in a glyph egui's bundled fonts do not have.
    Formula(String),
}

/// `text` split into Markdown and formulas, in order.
fn blocks(text: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut markdown: Vec<String> = Vec::new();
    let flush = |markdown: &mut Vec<String>, out: &mut Vec<Block>| {
        if !markdown.is_empty() {
            out.push(Block::Markdown(markdown.join("\n\n")));
            markdown.clear();
        }
    };
    let mut fence: Option<Vec<&str>> = None;
    let mut paragraph: Vec<&str> = Vec::new();
    let end_paragraph =
        |paragraph: &mut Vec<&str>, markdown: &mut Vec<String>, out: &mut Vec<Block>| {
            if paragraph.is_empty() {
                return;
            }
            if paragraph.iter().all(|l| l.starts_with("    ")) {
                flush(markdown, out);
                let lines: Vec<&str> = paragraph.iter().map(|l| &l[4..]).collect();
                out.push(Block::Formula(lines.join("\n")));
            } else {
                markdown.push(paragraph.join("\n"));
            }
            paragraph.clear();
        };
    for line in text.lines() {
        if let Some(lines) = &mut fence {
            if line.trim_start().starts_with("```") {
                flush(&mut markdown, &mut out);
                out.push(Block::Formula(lines.join("\n")));
                fence = None;
            } else {
                lines.push(line);
            }
        } else if line.trim_start().starts_with("```") {
            end_paragraph(&mut paragraph, &mut markdown, &mut out);
            fence = Some(Vec::new());
        } else if line.trim().is_empty() {
            end_paragraph(&mut paragraph, &mut markdown, &mut out);
        } else {
            paragraph.push(line);
        }
    }
    if let Some(lines) = fence {
        // An unclosed fence runs to the end, as in Markdown.
        flush(&mut markdown, &mut out);
        out.push(Block::Formula(lines.join("\n")));
    }
    end_paragraph(&mut paragraph, &mut markdown, &mut out);
    flush(&mut markdown, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::{Block, blocks};

    #[test]
    fn formulas_are_split_from_the_markdown() {
        let text = "A *map*:\n\n    u = x\n    v = y\n\n- one\n- two\n\n```\nz = 1\n```\nafter";
        assert_eq!(
            blocks(text),
            vec![
                Block::Markdown("A *map*:".into()),
                Block::Formula("u = x\nv = y".into()),
                Block::Markdown("- one\n- two".into()),
                Block::Formula("z = 1".into()),
                Block::Markdown("after".into()),
            ]
        );
    }
}
