//! Small shared widgets: a combo box over any named enum, labelled number rows, colours.

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

/// A labelled drag value. Returns whether it changed.
pub fn number(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut f32,
    range: std::ops::RangeInclusive<f32>,
    speed: f64,
) -> bool {
    ui.horizontal(|ui| {
        let l = ui.label(label);
        ui.add(egui::DragValue::new(value).range(range).speed(speed))
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
        ui.add(egui::DragValue::new(value).range(range).speed(speed))
            .labelled_by(l.id)
            .on_hover_text(tip)
            .changed()
    })
    .inner
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
