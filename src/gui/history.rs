//! Undo and redo over the scene description.
//!
//! The history does not know which panel edits the scene: the app hands it the description at
//! the end of every frame ([`History::observe`]), and any difference from the last one it saw
//! (by `PartialEq`) becomes an undo step holding the old description. So the scene panel, the
//! viewport's camera, the file actions and any panel added later are all undone the same way,
//! and a new field of the description needs nothing here.
//!
//! Changes that belong to one gesture (an orbit drag, a number dragged, a run of wheel clicks,
//! the typing in one text field) carry the same [`Gesture`] and merge into one step.

use crate::scene::{ObjectDesc, SceneDesc, TextureDesc};
use crate::texture::Filter;

/// How many steps are kept (older ones are forgotten).
pub const MAX_STEPS: usize = 200;

/// What a change belongs to: changes of the same gesture in a row merge into one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gesture {
    /// Made while a pointer button was held (the number of that press).
    Press(u64),
    /// Made by a run of wheel clicks (the number of that run).
    Wheel(u64),
    /// Made while the keyboard stayed in one text field (the number of that stay): a formula
    /// typed key by key is one step, however many of its prefixes were valid.
    Typing(u64),
}

/// A pause longer than this between wheel clicks starts a new zoom step.
pub const WHEEL_RUN_GAP: std::time::Duration = std::time::Duration::from_millis(800);

/// Turns the pointer's state, frame by frame, into the [`Gesture`] a change belongs to.
#[derive(Debug, Default)]
pub struct Gestures {
    presses: u64,
    runs: u64,
    last_wheel: Option<web_time::Instant>,
    stays: u64,
    /// The text field the keyboard is in (egui's id of it, as a number).
    typing_in: Option<u64>,
}

impl Gestures {
    /// This frame's gesture: `pressed` a button went down this frame, `held` one is down or was
    /// released this frame (a click lands on release), `scrolled` the wheel moved, `typing`
    /// the text field the keyboard is in (any number naming it), if any.
    pub fn update(
        &mut self,
        now: web_time::Instant,
        pressed: bool,
        held: bool,
        scrolled: bool,
        typing: Option<u64>,
    ) -> Option<Gesture> {
        if pressed {
            self.presses += 1;
        }
        if typing != self.typing_in {
            self.typing_in = typing;
            self.stays += 1;
        }
        if pressed || held {
            self.last_wheel = None;
            return Some(Gesture::Press(self.presses));
        }
        if typing.is_some() {
            self.last_wheel = None;
            return Some(Gesture::Typing(self.stays));
        }
        if scrolled {
            if self
                .last_wheel
                .is_none_or(|t| now.saturating_duration_since(t) > WHEEL_RUN_GAP)
            {
                self.runs += 1;
            }
            self.last_wheel = Some(now);
            return Some(Gesture::Wheel(self.runs));
        }
        None
    }
}

/// One undoable step: the description before it and what it did.
#[derive(Clone, Debug)]
struct Step<T> {
    before: T,
    label: String,
}

/// Undo and redo stacks over values of `T` (the window's [`SceneDesc`]).
#[derive(Clone, Debug)]
pub struct History<T> {
    /// The value as last observed, undone or redone.
    committed: Option<T>,
    undo: Vec<Step<T>>,
    redo: Vec<Step<T>>,
    /// The gesture of the step on top of `undo`, while later changes may still merge into it.
    open: Option<Gesture>,
}

impl<T> Default for History<T> {
    fn default() -> Self {
        Self {
            committed: None,
            undo: Vec::new(),
            redo: Vec::new(),
            open: None,
        }
    }
}

impl<T: Clone + PartialEq> History<T> {
    /// Forgets every step and starts from `value` (another scene was opened).
    pub fn reset(&mut self, value: Option<&T>) {
        self.committed = value.cloned();
        self.undo.clear();
        self.redo.clear();
        self.open = None;
    }

    /// Records `current` if it differs from the last value seen: the old value becomes an undo
    /// step named by `describe(old, new)`, unless `gesture` continues the gesture of the step
    /// on top (then that step grows to cover this change). A new step clears the redo stack.
    pub fn observe(
        &mut self,
        current: Option<&T>,
        gesture: Option<Gesture>,
        describe: impl FnOnce(&T, &T) -> String,
    ) {
        let Some(current) = current else {
            return;
        };
        let Some(old) = self.committed.as_ref() else {
            self.committed = Some(current.clone());
            return;
        };
        if old == current {
            return;
        }
        let merges = gesture.is_some() && gesture == self.open && !self.undo.is_empty();
        if !merges {
            let label = describe(old, current);
            let before = self.committed.take().unwrap_or_else(|| current.clone());
            self.undo.push(Step { before, label });
            if self.undo.len() > MAX_STEPS {
                self.undo.remove(0);
            }
        }
        self.redo.clear();
        self.open = gesture;
        self.committed = Some(current.clone());
    }

    /// Applies `f` to every value kept (after *Save as* rewrote the asset paths for another
    /// folder, the older steps need the same rewrite).
    pub fn rewrite(&mut self, mut f: impl FnMut(&mut T)) {
        if let Some(c) = &mut self.committed {
            f(c);
        }
        for s in self.undo.iter_mut().chain(&mut self.redo) {
            f(&mut s.before);
        }
    }

    /// Undoes the last step: returns the value to restore, `current` going on the redo stack.
    pub fn undo(&mut self, current: &T) -> Option<T> {
        let step = self.undo.pop()?;
        self.redo.push(Step {
            before: current.clone(),
            label: step.label,
        });
        self.open = None;
        self.committed = Some(step.before.clone());
        Some(step.before)
    }

    /// Redoes the last undone step: returns the value to restore.
    pub fn redo(&mut self, current: &T) -> Option<T> {
        let step = self.redo.pop()?;
        self.undo.push(Step {
            before: current.clone(),
            label: step.label,
        });
        self.open = None;
        self.committed = Some(step.before.clone());
        Some(step.before)
    }

    /// What undo would undo ("mapping", "camera"...), if anything.
    #[must_use]
    pub fn undo_label(&self) -> Option<&str> {
        self.undo.last().map(|s| s.label.as_str())
    }

    /// What redo would redo, if anything.
    #[must_use]
    pub fn redo_label(&self) -> Option<&str> {
        self.redo.last().map(|s| s.label.as_str())
    }

    /// How many steps can be undone.
    #[cfg(test)]
    #[must_use]
    pub fn undo_len(&self) -> usize {
        self.undo.len()
    }
}

fn filter_of(t: &TextureDesc) -> Option<Filter> {
    match t {
        TextureDesc::Constant(_) | TextureDesc::Formula { .. } => None,
        TextureDesc::Image { filter, .. }
        | TextureDesc::Checker { filter, .. }
        | TextureDesc::MeshMaterial { filter, .. }
        | TextureDesc::UvGrid { filter, .. } => Some(*filter),
    }
}

fn object_name(i: usize, o: &ObjectDesc) -> String {
    if o.name.is_empty() {
        format!("object {i}")
    } else {
        o.name.clone()
    }
}

/// What changed from `old` to `new`, in a few words for the Edit menu ("mapping of earth",
/// "camera", "remove object 1"); the first difference found names the step.
#[must_use]
pub fn describe(old: &SceneDesc, new: &SceneDesc) -> String {
    use std::cmp::Ordering;
    match new.objects.len().cmp(&old.objects.len()) {
        Ordering::Greater => return "add object".to_owned(),
        Ordering::Less => {
            let gone = old
                .objects
                .iter()
                .enumerate()
                .find(|(i, o)| new.objects.get(*i) != Some(*o))
                .map_or_else(|| "object".to_owned(), |(i, o)| object_name(i, o));
            return format!("remove {gone}");
        }
        Ordering::Equal => {}
    }
    if let Some((i, (a, b))) = old
        .objects
        .iter()
        .zip(&new.objects)
        .enumerate()
        .find(|(_, (a, b))| a != b)
    {
        let (ta, tb) = (a.material.texture(), b.material.texture());
        let what = if a.shape != b.shape {
            "shape"
        } else if a.transform != b.transform {
            "transform"
        } else if ta.kind() != tb.kind() {
            "texture"
        } else if ta.mapping() != tb.mapping() {
            "mapping"
        } else if filter_of(ta) != filter_of(tb) {
            "filter"
        } else if ta != tb {
            "texture settings"
        } else if a.material != b.material {
            "material"
        } else if a.alpha != b.alpha {
            "clip map"
        } else if a.bump != b.bump {
            "bump map"
        } else if a.normal != b.normal {
            "normal map"
        } else if a.displace != b.displace {
            "displacement"
        } else {
            "object"
        };
        return format!("{what} of {}", object_name(i, b));
    }
    if old.camera != new.camera {
        "camera".to_owned()
    } else if old.render.view != new.render.view {
        "debug view".to_owned()
    } else if old.render != new.render {
        "render settings".to_owned()
    } else if old.lights != new.lights || old.ambient != new.ambient {
        "lights".to_owned()
    } else if old.description != new.description {
        "description".to_owned()
    } else {
        "edit".to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mapping::Mapping;
    use crate::scene::{MaterialKind, ShapeDesc, load_preset};

    // The shape `History::observe` asks of a describer: references to the two values.
    #[allow(clippy::trivially_copy_pass_by_ref)]
    fn label(a: &i32, b: &i32) -> String {
        format!("{a}->{b}")
    }

    fn earth() -> SceneDesc {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        load_preset(&root.join("presets/earth.ron")).expect("earth preset")
    }

    #[test]
    fn each_change_is_a_step_and_undo_redo_walk_them_in_order() {
        let mut h = History::default();
        h.reset(Some(&1));
        h.observe(Some(&1), None, label);
        assert_eq!(h.undo_len(), 0, "no change, no step");
        h.observe(Some(&2), None, label);
        h.observe(Some(&3), None, label);
        assert_eq!(h.undo_label(), Some("2->3"));
        assert_eq!(h.undo(&3), Some(2));
        assert_eq!(h.undo(&2), Some(1));
        assert_eq!(h.undo(&1), None, "nothing left to undo");
        assert_eq!(h.redo_label(), Some("1->2"));
        assert_eq!(h.redo(&1), Some(2));
        assert_eq!(h.redo(&2), Some(3));
        assert_eq!(h.redo(&3), None);
        // Undoing does not make a step of its own when the app observes the restored value.
        assert_eq!(h.undo(&3), Some(2));
        h.observe(Some(&2), None, label);
        assert_eq!(h.undo_len(), 1);
        assert_eq!(h.redo_label(), Some("2->3"));
    }

    #[test]
    fn a_new_change_after_undo_clears_the_redo_stack() {
        let mut h = History::default();
        h.reset(Some(&0));
        h.observe(Some(&1), None, label);
        assert_eq!(h.undo(&1), Some(0));
        h.observe(Some(&5), None, label);
        assert_eq!(h.redo_label(), None);
        assert_eq!(h.undo(&5), Some(0));
    }

    #[test]
    fn changes_of_one_gesture_merge_into_one_step() {
        let mut h = History::default();
        h.reset(Some(&0));
        let drag = Some(Gesture::Press(1));
        for v in 1..=10 {
            h.observe(Some(&v), drag, label);
        }
        assert_eq!(h.undo_len(), 1);
        assert_eq!(h.undo_label(), Some("0->1"), "named by its first change");
        // The next press is a step of its own, and so is a wheel run.
        h.observe(Some(&11), Some(Gesture::Press(2)), label);
        h.observe(Some(&12), Some(Gesture::Wheel(1)), label);
        h.observe(Some(&13), Some(Gesture::Wheel(1)), label);
        assert_eq!(h.undo_len(), 3);
        assert_eq!(h.undo(&13), Some(11));
        assert_eq!(h.undo(&11), Some(10));
        assert_eq!(h.undo(&10), Some(0));
    }

    #[test]
    fn a_gesture_does_not_merge_into_a_step_that_was_undone() {
        let mut h = History::default();
        h.reset(Some(&0));
        let drag = Some(Gesture::Press(1));
        h.observe(Some(&1), drag, label);
        assert_eq!(h.undo(&1), Some(0));
        h.observe(Some(&2), drag, label);
        assert_eq!(h.undo_len(), 1);
        assert_eq!(h.undo(&2), Some(0));
    }

    #[test]
    fn changes_without_a_gesture_never_merge() {
        let mut h = History::default();
        h.reset(Some(&0));
        h.observe(Some(&1), None, label);
        h.observe(Some(&2), None, label);
        assert_eq!(h.undo_len(), 2);
    }

    #[test]
    fn reset_forgets_everything_and_the_oldest_steps_go_first() {
        let mut h = History::default();
        h.reset(Some(&0));
        for v in 1..=(MAX_STEPS as i32 + 5) {
            h.observe(Some(&v), None, label);
        }
        assert_eq!(h.undo_len(), MAX_STEPS);
        let mut v = MAX_STEPS as i32 + 5;
        while let Some(old) = h.undo(&v) {
            v = old;
        }
        assert_eq!(v, 5, "the first five steps were forgotten");
        h.reset(Some(&100));
        assert_eq!(h.undo_len(), 0);
        assert_eq!(h.redo_label(), None);
        h.observe(Some(&101), None, label);
        assert_eq!(h.undo(&101), Some(100));
    }

    #[test]
    fn the_first_value_seen_is_the_start_not_a_step() {
        let mut h: History<i32> = History::default();
        h.observe(None, None, label);
        h.observe(Some(&4), None, label);
        assert_eq!(h.undo_len(), 0);
        h.observe(Some(&5), None, label);
        assert_eq!(h.undo(&5), Some(4));
    }

    #[test]
    fn a_press_and_a_wheel_run_are_gestures_and_a_pause_ends_a_run() {
        let mut g = Gestures::default();
        let t0 = web_time::Instant::now();
        let ms = |n| t0 + std::time::Duration::from_millis(n);
        assert_eq!(g.update(t0, false, false, false, None), None);
        let press = g.update(ms(10), true, true, false, None);
        assert_eq!(
            g.update(ms(20), false, true, false, None),
            press,
            "the drag goes on"
        );
        assert_eq!(
            g.update(ms(30), false, true, false, None),
            press,
            "released: the click lands"
        );
        assert_ne!(
            g.update(ms(40), true, true, false, None),
            press,
            "another press"
        );
        let run = g.update(ms(100), false, false, true, None);
        assert!(matches!(run, Some(Gesture::Wheel(_))));
        assert_eq!(
            g.update(ms(500), false, false, true, None),
            run,
            "clicks in a run"
        );
        assert_eq!(
            g.update(ms(1200), false, false, true, None),
            run,
            "0.7 s apart still runs"
        );
        assert_ne!(
            g.update(ms(2100), false, false, true, None),
            run,
            "a pause starts a new run"
        );
        assert_eq!(g.update(ms(2200), false, false, false, None), None);
    }

    #[test]
    fn the_typing_in_one_text_field_is_one_gesture() {
        let mut g = Gestures::default();
        let t0 = web_time::Instant::now();
        let field = g.update(t0, false, false, false, Some(7));
        assert!(matches!(field, Some(Gesture::Typing(_))));
        assert_eq!(
            g.update(t0, false, false, false, Some(7)),
            field,
            "key after key"
        );
        let other = g.update(t0, false, false, false, Some(8));
        assert!(matches!(other, Some(Gesture::Typing(_))) && other != field);
        assert_eq!(g.update(t0, false, false, false, None), None);
        assert_ne!(
            g.update(t0, false, false, false, Some(8)),
            other,
            "back in the field: a new stay"
        );
        let mut h = History::default();
        h.reset(Some(&0));
        for v in 1..=5 {
            h.observe(Some(&v), field, label);
        }
        assert_eq!(h.undo_len(), 1);
    }

    #[test]
    fn rewrite_reaches_every_kept_value() {
        let mut h = History::default();
        h.reset(Some(&1));
        h.observe(Some(&2), None, label);
        h.observe(Some(&3), None, label);
        assert_eq!(h.undo(&3), Some(2));
        h.rewrite(|v| *v *= 10);
        assert_eq!(h.undo(&20), Some(10));
        assert_eq!(h.redo(&10), Some(20));
        assert_eq!(h.redo(&20), Some(30));
    }

    #[test]
    fn describe_names_the_part_of_the_scene_that_changed() {
        let a = earth();
        let name = object_name(0, &a.objects[0]);

        let mut b = a.clone();
        b.objects[0]
            .material
            .texture_mut()
            .set_mapping(Mapping::Cylindrical.into());
        assert_eq!(describe(&a, &b), format!("mapping of {name}"));

        let mut b = a.clone();
        b.objects[0].material.texture_mut().set_filter(Filter::Ewa);
        assert_eq!(describe(&a, &b), format!("filter of {name}"));

        let mut b = a.clone();
        b.objects[0].shape = ShapeDesc::Plane;
        assert_eq!(describe(&a, &b), format!("shape of {name}"));

        let mut b = a.clone();
        b.objects[0].material = b.objects[0].material.converted(MaterialKind::Phong);
        assert_eq!(describe(&a, &b), format!("material of {name}"));

        let mut b = a.clone();
        b.objects[0].displace = Some(crate::scene::DisplaceDesc {
            height: crate::scene::TextureKind::Constant.default_desc(),
            scale: 0.1,
            subdivide: 1,
        });
        assert_eq!(describe(&a, &b), format!("displacement of {name}"));

        let mut b = a.clone();
        b.camera.eye.x += 1.0;
        assert_eq!(describe(&a, &b), "camera");

        let mut b = a.clone();
        b.objects.push(a.objects[0].clone());
        b.objects[1].name = String::new();
        assert_eq!(describe(&a, &b), "add object");
        assert_eq!(describe(&b, &a), "remove object 1");
        b.objects[1].name = "Moon".to_owned();
        assert_eq!(describe(&b, &a), "remove Moon");

        let mut b = a.clone();
        b.render.spp += 1;
        assert_eq!(describe(&a, &b), "render settings");
    }
}
