//! Small shared widgets: a combo box over any named enum, labelled number rows, tooltips.

use crate::math::{Rgb, Vec3};
use crate::names::Named;

/// A combo box over every variant of a named enum (`ALL` in menu order, `name()` as text), with
/// `tip(variant)` as each entry's and the box's tooltip. Returns whether the value changed.
pub fn enum_combo<T: Named + PartialEq>(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut T,
    tip: impl Fn(T) -> &'static str,
) -> bool {
    let before = *value;
    ui.horizontal(|ui| {
        let l = ui.label(label);
        egui::ComboBox::from_id_salt(label)
            .selected_text(value.label())
            .show_ui(ui, |ui| {
                for &option in T::VARIANTS {
                    ui.selectable_value(value, option, option.label())
                        .on_hover_text(tip(option));
                }
            })
            .response
            .labelled_by(l.id)
            .on_hover_text(tip(*value));
    });
    *value != before
}

/// A combo box over a list of named choices that are not a library enum (shapes, material and
/// texture kinds). Returns the index picked this frame.
pub fn choice_combo(
    ui: &mut egui::Ui,
    label: &str,
    current: &str,
    choices: &[(&str, &str)],
) -> Option<usize> {
    let mut picked = None;
    ui.horizontal(|ui| {
        let l = ui.label(label);
        let tip = choices
            .iter()
            .find(|(n, _)| *n == current)
            .map_or("", |(_, t)| *t);
        egui::ComboBox::from_id_salt(label)
            .selected_text(current)
            .show_ui(ui, |ui| {
                for (i, (name, tip)) in choices.iter().enumerate() {
                    if ui
                        .selectable_label(*name == current, *name)
                        .on_hover_text(*tip)
                        .clicked()
                    {
                        picked = Some(i);
                    }
                }
            })
            .response
            .labelled_by(l.id)
            .on_hover_text(tip);
    });
    picked.filter(|&i| choices[i].0 != current)
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

/// One sentence on a texture filter. Filters other helpers add fall back to a generic line.
#[must_use]
pub fn filter_tip(name: &str) -> &'static str {
    match name {
        "nearest" => "Reads the one texel the lookup picks: sharp, but aliases when minified.",
        "bilinear" => {
            "Blends the four nearest texel centres: smooth when magnified, aliases when minified."
        }
        "trilinear" | "mip" | "trilinear-mip" => {
            "Blends two mip levels chosen from the pixel's footprint: no aliasing, a little blurry."
        }
        "ewa" => {
            "Averages the texels under the pixel's elliptical footprint: sharp and alias-free."
        }
        "anisotropic" => "Takes several mip lookups along the footprint's long axis.",
        _ => "A texture filter: how the texels under a pixel become one colour.",
    }
}

/// One sentence on a wrap mode.
#[must_use]
pub fn wrap_tip(name: &str) -> &'static str {
    match name {
        "repeat" => "Tiles the texture outside [0, 1].",
        "clamp" => "Extends the edge texels outside [0, 1].",
        "mirror" => "Tiles with every other copy mirrored, so the edges meet seamlessly.",
        "black" => "Black outside [0, 1], to show where the mapping leaves the texture.",
        _ => "What the texture does outside [0, 1].",
    }
}

/// One sentence on a texel lookup.
#[must_use]
pub fn lookup_tip(name: &str) -> &'static str {
    match name {
        "lecture" => {
            "The lecture's column = (int)((hres - 1) u): stretches the image by hres / (hres - 1)."
        }
        "centred" => "column = min(floor(u hres), hres - 1): every texel covers an equal share.",
        _ => "Which texel a nearest lookup picks.",
    }
}
