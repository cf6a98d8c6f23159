//! Small shared widgets: a combo box over any named enum, labelled number rows, colours, a
//! texture's (u, v) transform.

use crate::mapping::UvTransform;
use crate::math::{Rgb, Vec3};
use crate::names::Named;

/// A combo box over every variant of a named enum (`VARIANTS` in menu order, the name as text),
/// with the variant's description from the library as each entry's and the box's tooltip.
/// Returns whether the value changed.
pub fn enum_combo<T: Named>(ui: &mut egui::Ui, label: &str, value: &mut T) -> bool {
    let before = *value;
    ui.horizontal(|ui| {
        let l = ui.label(label);
        egui::ComboBox::from_id_salt(label)
            .selected_text(value.name())
            .show_ui(ui, |ui| {
                for &option in T::VARIANTS {
                    ui.selectable_value(value, option, option.name())
                        .on_hover_text(option.description());
                }
            })
            .response
            .labelled_by(l.id)
            .on_hover_text(value.description());
    });
    *value != before
}

/// A labelled drag value. Returns whether it changed. The range bounds dragging only: a value
/// beyond it (a preset may hold any number its validation accepts) is shown and kept as it is
/// until the user changes it, instead of being clamped as soon as it is drawn.
pub fn number(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut f32,
    range: std::ops::RangeInclusive<f32>,
    speed: f64,
) -> bool {
    ui.horizontal(|ui| {
        let l = ui.label(label);
        ui.add(drag(value, range, speed))
            .labelled_by(l.id)
            .changed()
    })
    .inner
}

/// [`number`] with a tooltip saying what the value does.
pub fn number_tip(
    ui: &mut egui::Ui,
    label: &str,
    tip: &str,
    value: &mut f32,
    range: std::ops::RangeInclusive<f32>,
    speed: f64,
) -> bool {
    ui.horizontal(|ui| {
        let l = ui.label(label).on_hover_text(tip);
        ui.add(drag(value, range, speed))
            .labelled_by(l.id)
            .on_hover_text(tip)
            .changed()
    })
    .inner
}

/// The drag value of [`number`]: `range` bounds dragging, not the value already there.
fn drag(value: &mut f32, range: std::ops::RangeInclusive<f32>, speed: f64) -> egui::DragValue<'_> {
    egui::DragValue::new(value)
        .range(range)
        .clamp_existing_to_range(false)
        .speed(speed)
}

/// Three labelled drag values for a vector. Returns whether any changed.
pub fn vec3(ui: &mut egui::Ui, label: &str, v: &mut Vec3, speed: f64) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        let mut changed = false;
        for (axis, c) in ["x", "y", "z"].into_iter().zip(v.as_mut()) {
            changed |= ui
                .add(
                    egui::DragValue::new(c)
                        .speed(speed)
                        .range(-1e6..=1e6)
                        .prefix(format!("{axis} ")),
                )
                .on_hover_text(format!("{label} {axis}"))
                .changed();
        }
        changed
    })
    .inner
}

/// A labelled colour button for a linear RGB colour (egui's picker edits linear values too).
pub fn colour(ui: &mut egui::Ui, label: &str, c: &mut Rgb) -> bool {
    ui.horizontal(|ui| {
        let l = ui.label(label);
        let mut rgb = c.to_array();
        let changed = ui
            .color_edit_button_rgb(&mut rgb)
            .labelled_by(l.id)
            .on_hover_text(format!("{label} (linear RGB)"))
            .changed();
        if changed {
            *c = Rgb::from_array(rgb);
        }
        changed
    })
    .inner
}

/// Names a widget for screen readers (and the window tests) when its visible text is shorter
/// than what it means: the "u" of a (u, v) pair becomes "uv scale u".
fn name_widget(ui: &egui::Ui, r: &egui::Response, name: &str) {
    ui.ctx()
        .accesskit_node_builder(r.id, |node| node.set_label(name.to_owned()));
}

/// A (u, v) pair of drag values after `label`, each named "`label` u" and "`label` v" for
/// screen readers; `fix` corrects a value as it is dragged. Returns whether either changed.
fn uv_pair(
    ui: &mut egui::Ui,
    label: &str,
    tip: &str,
    values: [&mut f32; 2],
    speed: f64,
    fix: impl Fn(f32, f32) -> f32,
) -> bool {
    ui.horizontal(|ui| {
        ui.label(label).on_hover_text(tip);
        let mut changed = false;
        for (axis, v) in ["u", "v"].into_iter().zip(values) {
            let before = *v;
            let r = ui
                .add(
                    egui::DragValue::new(v)
                        .speed(speed)
                        .range(-1e6..=1e6)
                        .prefix(format!("{axis} ")),
                )
                .on_hover_text(tip);
            name_widget(ui, &r, &format!("{label} {axis}"));
            if r.changed() {
                *v = fix(before, *v);
                changed = true;
            }
        }
        changed
    })
    .inner
}

/// The (u, v) transform of any texture (the main one and every textured parameter or map):
/// scale (tiling), rotation and offset, applied in that order after the mapping. Returns
/// whether it changed.
pub fn uv_transform(ui: &mut egui::Ui, uv: &mut UvTransform) -> bool {
    let mut changed = uv_pair(
        ui,
        "uv scale",
        "Tiles the texture: 2 repeats it twice across the mapping (the wrap mode decides what \
         lies beyond the first copy); negative mirrors it",
        [&mut uv.scale.x, &mut uv.scale.y],
        0.05,
        // Zero is refused by the scene: step over it.
        |before, v| {
            if v == 0.0 {
                if before < 0.0 { -1e-3 } else { 1e-3 }
            } else {
                v
            }
        },
    );
    changed |= number_tip(
        ui,
        "uv rotate (degrees)",
        "Turns the scaled (u, v) counter-clockwise about the (u, v) origin",
        &mut uv.rotate,
        -360.0..=360.0,
        1.0,
    );
    changed |= uv_pair(
        ui,
        "uv offset",
        "Slides the texture, added last: 0.25 moves it a quarter of a copy along u",
        [&mut uv.offset.x, &mut uv.offset.y],
        0.01,
        |_, v| v,
    );
    changed
}
