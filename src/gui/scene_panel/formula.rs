//! Under the formula mapping of the selected object's colour texture: *Compare with* a built-in
//! mapping (the `Difference` view on the object, the share of the visible surface where the two
//! agree within a tolerance and the common mistake's hint, from
//! [`crate::coverage::visible_agreement`], the same code as `texplore map --compare`), and how
//! many hits of the render gave NaN or an infinity.

use super::ScenePanel;
use crate::coverage::{VisibleAgreement, visible_agreement};
use crate::gui::widgets::{enum_combo, number_tip};
use crate::mapping::formula::compare::CORRECT_SHARE;
use crate::names::Named as _;
use crate::render::Task;
use crate::scene::{RenderDesc, Scene};
use crate::texture::{Compare, MAX_COMPARE_TOLERANCE, View};
use std::sync::Arc;

/// What a comparison was computed for: the scene shown (by address), the object, the settings.
type Key = (usize, usize, Compare);

/// A comparison's outcome: `Ok(None)` when the object has no formula mapping.
type Outcome = Result<Option<VisibleAgreement>, String>;

/// The comparison's number, computed off the UI thread for the scene shown.
#[derive(Default)]
pub(super) struct FormulaCheck {
    /// The scene the viewport shows (set by the window each frame).
    pub(super) shown: Option<Arc<Scene>>,
    /// The comparison being computed.
    running: Option<(Key, Task<Outcome>)>,
    /// The last comparison computed.
    done: Option<(Key, Outcome)>,
}

impl FormulaCheck {
    /// The comparison for `object` under `compare`: started when the scene or the settings
    /// changed, collected when done. `None` while it runs.
    fn poll(&mut self, ctx: &egui::Context, object: usize, compare: Compare) -> Option<&Outcome> {
        let scene = self.shown.clone()?;
        let key = (Arc::as_ptr(&scene) as usize, object, compare);
        if let Some((k, task)) = &self.running
            && *k == key
        {
            let finished = task.take().or_else(|| {
                task.failure()
                    .map(|why| Err(format!("the comparison failed: {why}")))
            });
            if let Some(result) = finished {
                self.done = Some((key, result));
                self.running = None;
            }
        }
        let current = self.done.as_ref().is_some_and(|(k, _)| *k == key);
        let started = self.running.as_ref().is_some_and(|(k, _)| *k == key);
        if !current && !started {
            let work = move |cancel: &std::sync::atomic::AtomicBool| match visible_agreement(
                &scene, object, compare, cancel,
            ) {
                Ok(found) => Some(Ok(found)),
                Err(crate::coverage::FieldError::Cancelled) => None,
                Err(e) => Some(Err(e.to_string())),
            };
            match Task::spawn(work) {
                Ok(task) => self.running = Some((key, task)),
                Err(e) => self.done = Some((key, Err(e.to_string()))),
            }
        }
        if self.running.is_some() {
            ctx.request_repaint_after(std::time::Duration::from_millis(30));
        }
        self.done
            .as_ref()
            .filter(|(k, _)| *k == key)
            .map(|(_, result)| result)
    }
}

impl ScenePanel {
    /// The comparison and the NaN count under a formula mapping of the colour texture of the
    /// selected object; edits `render` (the view and `render.compare`). Returns whether it
    /// changed the scene.
    pub(super) fn formula_check_ui(&mut self, ui: &mut egui::Ui, render: &mut RenderDesc) -> bool {
        let object = self.selected;
        let mut changed = false;
        ui.push_id("formula-check", |ui| {
            self.non_finite_ui(ui);
            let mut on = render.view == View::Difference;
            if ui
                .checkbox(&mut on, "Compare with a built-in mapping")
                .on_hover_text(
                    "Paints the difference between your formula and the built-in mapping on the \
                     object (the Difference view) and says how much of the visible surface agrees",
                )
                .changed()
            {
                render.view = if on { View::Difference } else { View::Shaded };
                changed = true;
            }
            if !on {
                return;
            }
            changed |= enum_combo(ui, "compare with", &mut render.compare.with);
            changed |= number_tip(
                ui,
                "tolerance (texels)",
                "How far apart (u, v) may be and still agree, in texels of the texture's image",
                &mut render.compare.tolerance,
                0.01..=MAX_COMPARE_TOLERANCE,
                0.05,
            );
            let compare = render.compare;
            match self.formula.poll(ui.ctx(), object, compare) {
                None => {
                    ui.horizontal(|ui| {
                        ui.spinner();
                        ui.label("Comparing…");
                    });
                }
                Some(Err(e)) => {
                    ui.colored_label(ui.visuals().error_fg_color, e);
                }
                Some(Ok(None)) => {
                    ui.label("The scene shown has no formula mapping on this object yet.");
                }
                Some(Ok(Some(found))) => verdict_ui(ui, found, compare),
            }
        });
        changed
    }
}

impl ScenePanel {
    /// How many hits gave NaN or an infinity (a formula mapping's or a colour formula's) in the
    /// render of the scene shown, on the selected object.
    pub(super) fn non_finite_ui(&self, ui: &mut egui::Ui) {
        let scene = self.formula.shown.as_deref();
        non_finite_line(ui, scene, self.selected);
    }
}

/// How many hits gave NaN or an infinity in the render of `scene`, on `object`.
fn non_finite_line(ui: &mut egui::Ui, scene: Option<&Scene>, object: usize) {
    let Some(texture) = scene.and_then(|s| crate::coverage::object_texture(s, object)) else {
        return;
    };
    let n = texture.non_finite_count();
    if n == 0 {
        ui.label("NaN or infinity: at no hit of this render");
    } else {
        ui.colored_label(
            ui.visuals().warn_fg_color,
            format!("NaN or infinity: at {n} hits of this render (the pixels are magenta)"),
        )
        .on_hover_text(
            "Every sample that hit this object and got a (u, v) that is not a finite number \
             counts, since the scene was last built",
        );
    }
}

/// The share of the visible surface that agrees, and the hints.
fn verdict_ui(ui: &mut egui::Ui, found: &VisibleAgreement, compare: Compare) {
    let a = &found.agreement;
    if a.points == 0 {
        ui.label("The object is not in view: nothing to compare.");
        return;
    }
    let share = a.share();
    let text = format!(
        "{:.1} % of the visible surface agrees with {} within {} texel{} ({} points)",
        100.0 * share,
        compare.with.name(),
        compare.tolerance,
        if (compare.tolerance - 1.0).abs() < f32::EPSILON {
            ""
        } else {
            "s"
        },
        a.points
    );
    if share >= CORRECT_SHARE {
        ui.colored_label(egui::Color32::from_rgb(90, 200, 110), text);
    } else {
        ui.label(text);
    }
    ui.label(
        egui::RichText::new(format!(
            "largest |du| = {:.4}, |dv| = {:.4}{}",
            a.max_difference.x,
            a.max_difference.y,
            if a.non_finite > 0 {
                format!("; {} points NaN or infinite", a.non_finite)
            } else {
                String::new()
            }
        ))
        .weak(),
    );
    for m in &found.mistakes {
        ui.colored_label(
            ui.visuals().warn_fg_color,
            format!("hint: {}", m.hint(compare.with)),
        );
    }
}
