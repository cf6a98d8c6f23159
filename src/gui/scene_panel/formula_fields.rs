//! The formula fields: a mapping's u and v, a formula texture's grey or r, g and b. What is
//! typed belongs to the field and stays there, valid or not; a group of fields goes into the
//! scene, as one change, only when every formula of it is valid (and the scene keeps, and the
//! image shows, the last valid formulas until then). A mistake shows under its own field, with
//! the formula and a caret under the column the checker names.
//!
//! The typing is kept in egui's memory under the group's id, with the formulas the scene held
//! when it was last in step with the fields: when the scene's formulas change from elsewhere
//! (undo, a lesson's experiment, the mapping menu, another object selected) the fields show
//! them again.

use crate::mapping::FormulaError;
use crate::mapping::formula::{Expr, MAPPING_VARS, TEXTURE_VARS};

/// What a group of formula fields keeps between frames.
#[derive(Clone, Debug, Default)]
struct Typed {
    /// The formulas the scene held when the fields were last in step with it.
    applied: Vec<String>,
    /// What the fields hold.
    text: Vec<String>,
    /// The texts last checked and what the check found.
    checked: Option<(Vec<String>, Checked)>,
}

/// What is wrong with a group's texts: each field's mistake, and the group's own (fields
/// that do not go together). Nothing wrong: the texts can go into the scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Checked {
    /// One entry per field.
    pub fields: Vec<Option<FormulaError>>,
    /// A mistake of the fields together ("grey and r both given").
    pub group: Option<String>,
}

impl Checked {
    fn is_valid(&self) -> bool {
        self.group.is_none() && self.fields.iter().all(Option::is_none)
    }
}

/// The mapping's u and v: each compiled on its own over the mapping's inputs.
pub(super) fn check_mapping(texts: &[String]) -> Checked {
    let fields = ["u", "v"]
        .iter()
        .zip(texts)
        .map(|(name, t)| Expr::compile(name, t, &MAPPING_VARS).err())
        .collect();
    Checked {
        fields,
        group: None,
    }
}

/// A formula texture's grey, r, g and b: grey alone or all three channels (as the scene's
/// build asks), each compiled over the texture's inputs.
pub(super) fn check_colour(texts: &[String]) -> Checked {
    let names = ["grey", "r", "g", "b"];
    let given: Vec<bool> = texts.iter().map(|t| !t.trim().is_empty()).collect();
    let grey = given.first().copied().unwrap_or(false);
    let channels: Vec<&str> = (1..4).filter(|&i| given[i]).map(|i| names[i]).collect();
    let group = match (grey, channels.len()) {
        (true, 0) | (false, 3) => None,
        (true, _) => Some(format!(
            "grey and {} both given: write grey alone (and empty r, g and b), or empty grey \
             and write r, g and b",
            channels.join(", ")
        )),
        (false, _) => {
            let missing: Vec<&str> = (1..4).filter(|&i| !given[i]).map(|i| names[i]).collect();
            Some(format!(
                "{} missing: write grey alone, or r, g and b",
                missing.join(", ")
            ))
        }
    };
    let fields = names
        .iter()
        .zip(texts)
        .zip(&given)
        .map(|((name, t), &given)| {
            given
                .then(|| Expr::compile(name, t, &TEXTURE_VARS).err())
                .flatten()
        })
        .collect();
    Checked { fields, group }
}

/// The formula fields `labels` over the scene's `values`, in the group `id` (unique to the
/// object and the place); `check` finds the mistakes in what is typed; `note` is drawn after
/// the fields while every one is valid (the derivative note), `between(ui, i)` after field
/// `i`'s row and its mistake. Returns whether the fields changed the scene's formulas.
pub(super) fn formula_group(
    ui: &mut egui::Ui,
    id: egui::Id,
    labels: &[&str],
    values: &mut [&mut String],
    check: impl Fn(&[String]) -> Checked,
    mut between: impl FnMut(&mut egui::Ui, usize),
) -> bool {
    let scene: Vec<String> = values.iter().map(|v| (**v).clone()).collect();
    let mut typed = ui.data_mut(|d| d.get_temp::<Typed>(id)).unwrap_or_default();
    if typed.applied != scene || typed.text.len() != scene.len() {
        // New, or changed from elsewhere: the fields show the scene's formulas.
        typed.applied.clone_from(&scene);
        typed.text.clone_from(&scene);
    }
    for (i, label) in labels.iter().enumerate() {
        field(ui, id.with(i), label, &mut typed.text[i]);
        let checked = checked(&mut typed, &check);
        if let Some(Some(e)) = checked.fields.get(i) {
            mistake(ui, e);
        }
        between(ui, i);
    }
    let checked = checked(&mut typed, &check);
    if let Some(g) = &checked.group {
        ui.label(egui::RichText::new(g).color(ui.visuals().error_fg_color));
    }
    let mut changed = false;
    if checked.is_valid() && typed.text != scene {
        for (v, t) in values.iter_mut().zip(&typed.text) {
            (**v).clone_from(t);
        }
        typed.applied.clone_from(&typed.text);
        changed = true;
    }
    ui.data_mut(|d| d.insert_temp(id, typed));
    changed
}

/// The check of what is typed now (done again only when the text changed).
fn checked(typed: &mut Typed, check: &impl Fn(&[String]) -> Checked) -> Checked {
    match &typed.checked {
        Some((texts, c)) if *texts == typed.text => c.clone(),
        _ => {
            let c = check(&typed.text);
            typed.checked = Some((typed.text.clone(), c.clone()));
            c
        }
    }
}

/// One formula's text field (its own id, so a mistake shown above it never moves its caret).
fn field(ui: &mut egui::Ui, id: egui::Id, label: &str, text: &mut String) {
    ui.horizontal(|ui| {
        let l = ui.label(label);
        ui.add(
            egui::TextEdit::singleline(text)
                .id(id)
                .font(egui::TextStyle::Monospace)
                .desired_width(f32::INFINITY),
        )
        .labelled_by(l.id);
    });
}

/// A formula's mistake under its field: the message, and the formula with a caret under the
/// column.
pub(super) fn mistake(ui: &mut egui::Ui, e: &FormulaError) {
    let red = ui.visuals().error_fg_color;
    ui.label(egui::RichText::new(e.to_string()).color(red));
    if let Some(p) = e.pointer() {
        ui.label(egui::RichText::new(p).monospace().color(red));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(t: &[&str]) -> Vec<String> {
        t.iter().map(|s| (*s).to_owned()).collect()
    }

    #[test]
    fn a_mapping_is_checked_field_by_field_with_the_column() {
        let c = check_mapping(&texts(&["fract(atan2(x, z) / tau)", "y"]));
        assert!(c.is_valid(), "{c:?}");
        let c = check_mapping(&texts(&["fract(atan2(x, z) / ta", "y *"]));
        let u = c.fields[0].as_ref().expect("u is wrong");
        assert_eq!((u.field.as_str(), u.column), ("u", Some(21)), "{u}");
        assert_eq!(c.fields[1].as_ref().map(|e| e.field.as_str()), Some("v"));
    }

    #[test]
    fn colour_formulas_are_grey_alone_or_three_channels() {
        assert!(check_colour(&texts(&["u", "", "", ""])).is_valid());
        assert!(check_colour(&texts(&["", "u", "v", "0.5"])).is_valid());
        let both = check_colour(&texts(&["u", "v", "", ""]));
        assert!(
            both.group
                .as_deref()
                .is_some_and(|g| g.contains("grey and r"))
        );
        let missing = check_colour(&texts(&["", "u", "", ""]));
        assert!(
            missing
                .group
                .as_deref()
                .is_some_and(|g| g.starts_with("g, b missing")),
            "{missing:?}"
        );
        // An empty field is not checked as a formula; a written one is.
        let c = check_colour(&texts(&["", "u", "v", "w"]));
        assert_eq!(c.group, None);
        assert_eq!(c.fields[3].as_ref().and_then(|e| e.column), Some(1));
        assert!(c.fields[..3].iter().all(Option::is_none));
    }
}
