//! A lesson's exercises in the Lessons panel: the task, a field per formula (starting from the
//! lesson's), *Check* (the formulas go on the scene, one undoable step like an experiment, and
//! the panel says how much of the target's surface agrees, which formula agrees and what is
//! wrong: [`crate::lesson::exercise::Exercise::check`]), then *Show the fix* (the hint's second
//! step), and *Show solution* (fills the fields).

use super::LessonsPanel;
use crate::gui::command::Command;
use crate::lesson::Lesson;
use crate::lesson::exercise::{Checked, Exercise};
use crate::scene::SceneDesc;

/// The label of the button that shows a hint's second step.
const SHOW_FIX: &str = "Show the fix";

/// One exercise's fields and its last verdict.
#[derive(Clone, Debug, Default)]
pub(super) struct Attempt {
    /// The formulas typed, one per field.
    formulas: Vec<String>,
    /// The formulas of the last *Check* and what it found, or their mistake.
    verdict: Option<(Vec<String>, Result<Checked, String>)>,
    /// Whether the hint's second step, the fix, is shown (after *Show the fix*).
    fix_shown: bool,
}

impl LessonsPanel {
    /// The exercises of `lesson` (shown while the scene is the lesson's, `desc`).
    pub(super) fn exercises_ui(
        &mut self,
        ui: &mut egui::Ui,
        lesson: &Lesson,
        desc: Option<&SceneDesc>,
        action: &mut Option<Command>,
    ) {
        if lesson.exercises.is_empty() {
            return;
        }
        if self.attempts.0 != Some(self.selected) || self.attempts.1.len() != lesson.exercises.len()
        {
            self.attempts = (
                Some(self.selected),
                lesson
                    .exercises
                    .iter()
                    .map(|x| Attempt {
                        formulas: x.start.clone(),
                        verdict: None,
                        fix_shown: false,
                    })
                    .collect(),
            );
        }
        ui.separator();
        ui.strong("Exercise");
        let enabled = self.active;
        // Check puts the formulas on the exercise's own scene (the lesson's, as it opened),
        // whatever experiment is showing.
        let own = self.base.clone();
        for (k, x) in lesson.exercises.iter().enumerate() {
            let attempt = &mut self.attempts.1[k];
            ui.push_id(("exercise", k), |ui| {
                if let Some(a) = exercise_ui(ui, x, attempt, desc, own.as_ref(), enabled) {
                    *action = Some(a);
                }
            });
            ui.add_space(4.0);
        }
    }
}

/// One exercise: the task, the fields, *Check*, *Show solution* and the verdict.
fn exercise_ui(
    ui: &mut egui::Ui,
    x: &Exercise,
    attempt: &mut Attempt,
    desc: Option<&SceneDesc>,
    own: Option<&SceneDesc>,
    enabled: bool,
) -> Option<Command> {
    let mut action = None;
    ui.label(&x.task);
    ui.weak(format!("Checked against {}.", x.target_name()));
    for (name, text) in x.fields().iter().zip(attempt.formulas.iter_mut()) {
        ui.horizontal(|ui| {
            let l = ui.label(format!("your {name} ="));
            ui.add(
                egui::TextEdit::singleline(text)
                    .font(egui::TextStyle::Monospace)
                    .desired_width(f32::INFINITY),
            )
            .labelled_by(l.id);
        });
    }
    ui.horizontal(|ui| {
        let check = ui
            .add_enabled(enabled && own.is_some(), egui::Button::new("Check"))
            .on_hover_text(
                "Puts your formulas on the scene (Ctrl+Z takes them off) and compares them \
                 with the built-in one",
            );
        if check.clicked()
            && let Some(own) = own
        {
            let verdict = x.check(&attempt.formulas).map_err(|e| {
                e.pointer()
                    .map_or_else(|| e.to_string(), |p| format!("{e}\n{p}"))
            });
            if verdict.is_ok() {
                match x.apply(own, &attempt.formulas) {
                    Ok(new) => action = Some(Command::Apply(new)),
                    Err(e) => action = Some(Command::Error(e)),
                }
            }
            attempt.verdict = Some((attempt.formulas.clone(), verdict));
            attempt.fix_shown = false;
        }
        if ui
            .button("Show solution")
            .on_hover_text(
                "Fills the fields with the lesson's solution; Check puts it on the scene",
            )
            .clicked()
        {
            attempt.formulas.clone_from(&x.solution);
            attempt.verdict = None;
            attempt.fix_shown = false;
        }
    });
    // A verdict holds while the scene has the formulas it checked (Ctrl+Z takes both away);
    // a mistake, until the fields change.
    let current = |checked: &Vec<String>| match desc {
        Some(d) => x.formulas_in(d).as_ref() == Some(checked),
        None => false,
    };
    let shown = match &attempt.verdict {
        Some((checked, Err(e))) if *checked == attempt.formulas => Some(Err(e)),
        Some((checked, Ok(c))) if current(checked) => Some(Ok(c)),
        _ => None,
    };
    match shown {
        None => {}
        Some(Err(e)) => {
            ui.label(
                egui::RichText::new(e)
                    .monospace()
                    .color(ui.visuals().error_fg_color),
            );
        }
        Some(Ok(c)) => {
            let text = c.summary(&x.target);
            if c.correct() {
                ui.colored_label(
                    egui::Color32::from_rgb(90, 200, 110),
                    format!("Correct: {text}"),
                );
            } else {
                ui.label(text);
            }
            // Two steps: what is wrong at once, the fix only when asked for.
            if let Some(h) = &c.hint {
                ui.colored_label(ui.visuals().warn_fg_color, format!("hint: {}", h.what));
                if let Some(fix) = &h.fix {
                    if attempt.fix_shown {
                        ui.colored_label(ui.visuals().warn_fg_color, format!("fix: {fix}"));
                    } else if ui
                        .button(SHOW_FIX)
                        .on_hover_text("The hint's second step: how to repair the formula")
                        .clicked()
                    {
                        attempt.fix_shown = true;
                    }
                }
            }
        }
    }
    action
}
