//! The material editor: the kind (matte, Phong, emissive) and its coefficients and colours,
//! each either a plain value or a texture with its own mapping, filter and wrap.

use super::{ImagePicker, browse_button};
use crate::gui::files::BrowseFor;
use crate::gui::widgets::{colour, enum_combo, number, number_tip, uv_transform};
use crate::material::{ParamDefault, ParamSpec};
use crate::names::Named;
use crate::scene::{
    ChannelDesc, ColorDesc, MaterialDesc, ParamMut, ScalarDesc, TextureDesc, TextureKind,
};
use crate::texture::Channel;

/// The texture kinds a parameter can switch to (a mesh's own material is only for `cd`).
const PARAM_KINDS: [TextureKind; 4] = [
    TextureKind::Constant,
    TextureKind::Image,
    TextureKind::Checker,
    TextureKind::UvGrid,
];

/// The material menu and the chosen material's coefficients (`picker` for their images).
/// Returns whether it changed.
pub(super) fn material_ui(ui: &mut egui::Ui, m: &mut MaterialDesc, picker: &ImagePicker) -> bool {
    let mut changed = false;
    let mut kind = m.kind();
    if enum_combo(ui, "Material", &mut kind) {
        *m = m.converted(kind);
        changed = true;
    }
    // A parameter switched to an image starts on the colour's image, if it has one.
    let colour_image = match m.texture() {
        t @ TextureDesc::Image { .. } => Some(t.clone()),
        _ => None,
    };
    // The table's rows come in the order of the parameters.
    let specs = m.kind().params();
    for (spec, (name, p)) in specs.iter().zip(m.params_mut()) {
        debug_assert_eq!(spec.name, name);
        ui.push_id(name, |ui| match p {
            ParamMut::Scalar(s) => {
                let fallback = match spec.default {
                    ParamDefault::Scalar(v) => v,
                    ParamDefault::Colour(_) => 1.0,
                };
                changed |= scalar_ui(ui, spec, s, fallback, colour_image.as_ref(), picker);
            }
            ParamMut::Color(c) => {
                changed |= colour_param_ui(ui, spec.label, c, colour_image.as_ref(), picker);
            }
        });
    }
    changed
}

/// A combo over the kinds a parameter may take: a plain value or one of the textures.
fn source_combo(ui: &mut egui::Ui, label: &str, kind: &mut TextureKind) -> bool {
    let before = *kind;
    let name = |k: TextureKind| {
        if k == TextureKind::Constant {
            "value"
        } else {
            k.name()
        }
    };
    egui::ComboBox::from_id_salt(label)
        .selected_text(name(*kind))
        .width(80.0)
        .show_ui(ui, |ui| {
            for k in PARAM_KINDS {
                let tip = if k == TextureKind::Constant {
                    "The same value everywhere (costs nothing)"
                } else {
                    k.description()
                };
                ui.selectable_value(kind, k, name(k)).on_hover_text(tip);
            }
        })
        .response
        .on_hover_text(format!("{label}: a plain value or a texture"));
    *kind != before
}

/// A new texture of `kind` for a parameter: an image starts on the colour's image.
fn new_texture(kind: TextureKind, colour_image: Option<&TextureDesc>) -> TextureDesc {
    match (kind, colour_image) {
        (TextureKind::Image, Some(img)) => img.clone(),
        _ => kind.default_desc(),
    }
}

fn scalar_ui(
    ui: &mut egui::Ui,
    spec: &ParamSpec,
    s: &mut ScalarDesc,
    fallback: f32,
    colour_image: Option<&TextureDesc>,
    picker: &ImagePicker,
) -> bool {
    let label = spec.label;
    let mut changed = false;
    let mut kind = s.texture().map_or(TextureKind::Constant, TextureDesc::kind);
    ui.horizontal(|ui| {
        if let ScalarDesc::Value(v) = s {
            let (max, speed) = (spec.max, spec.speed);
            changed |= number_tip(
                ui,
                label,
                &format!("Dragged from 0 to {max}; a larger value from the preset is kept"),
                v,
                0.0..=max,
                speed,
            );
        } else {
            ui.label(label);
        }
        if source_combo(ui, label, &mut kind) {
            *s = if kind == TextureKind::Constant {
                ScalarDesc::Value(fallback)
            } else {
                ScalarDesc::Texture(new_texture(kind, colour_image))
            };
            changed = true;
        }
    });
    if s.texture().is_some() {
        ui.indent(label, |ui| {
            changed |= channel_ui(ui, s);
            if let Some(t) = s.texture_mut() {
                changed |= texture_settings_ui(ui, t, picker, "image");
            }
        });
    }
    changed
}

/// Which channel of its texture a textured number reads (luminance, red, green, blue or the
/// file's alpha). Returns whether it changed; a plain number shows nothing.
pub(super) fn channel_ui(ui: &mut egui::Ui, s: &mut ScalarDesc) -> bool {
    let (Some(mut channel), Some(texture)) = (s.channel(), s.texture().cloned()) else {
        return false;
    };
    if !enum_combo(ui, "channel", &mut channel) {
        return false;
    }
    *s = if channel == Channel::Luminance {
        ScalarDesc::Texture(texture)
    } else {
        ScalarDesc::Channel(ChannelDesc { texture, channel })
    };
    true
}

fn colour_param_ui(
    ui: &mut egui::Ui,
    label: &str,
    c: &mut ColorDesc,
    colour_image: Option<&TextureDesc>,
    picker: &ImagePicker,
) -> bool {
    let mut changed = false;
    let mut kind = c.texture().map_or(TextureKind::Constant, TextureDesc::kind);
    ui.horizontal(|ui| {
        if let ColorDesc::Value(v) = c {
            changed |= colour(ui, label, v);
        } else {
            ui.label(label);
        }
        if source_combo(ui, label, &mut kind) {
            *c = if kind == TextureKind::Constant {
                ColorDesc::Value(crate::math::Rgb::WHITE)
            } else {
                ColorDesc::Texture(new_texture(kind, colour_image))
            };
            changed = true;
        }
    });
    if let Some(t) = c.texture_mut() {
        ui.indent(label, |ui| {
            changed |= texture_settings_ui(ui, t, picker, "image");
        });
    }
    changed
}

/// The texture editor of a textured parameter or map: the (u, v) transform, the mapping; an
/// image's path (`image_label`; Enter or *Load*, or *Browse…*), filter and wrap; a checker's
/// squares and colours; a UV grid's filter and wrap; a constant's colour.
pub(super) fn texture_settings_ui(
    ui: &mut egui::Ui,
    t: &mut TextureDesc,
    picker: &ImagePicker,
    image_label: &str,
) -> bool {
    let mut changed = false;
    if let Some(uv) = t.uv_transform_mut() {
        changed |= uv_transform(ui, uv);
    }
    if let Some(current) = t.mapping() {
        let mut m = current.clone();
        if super::texture::mapping_ui(ui, "mapping", &mut m, picker.object) {
            t.set_mapping(m);
            changed = true;
        }
    }
    match t {
        TextureDesc::Image {
            path, filter, wrap, ..
        } => {
            changed |= image_field(ui, image_label, path, picker);
            changed |= enum_combo(ui, "filter", filter);
            changed |= enum_combo(ui, "wrap", wrap);
        }
        TextureDesc::Checker {
            squares,
            colors,
            filter,
            ..
        } => {
            changed |= enum_combo(ui, "filter", filter);
            changed |= number(ui, "squares along u", &mut squares.0, 0.01..=1e6, 0.1);
            changed |= number(ui, "squares along v", &mut squares.1, 0.01..=1e6, 0.1);
            changed |= colour(ui, "colour 1", &mut colors.0);
            changed |= colour(ui, "colour 2", &mut colors.1);
        }
        TextureDesc::UvGrid { filter, wrap, .. }
        | TextureDesc::MeshMaterial { filter, wrap, .. } => {
            changed |= enum_combo(ui, "filter", filter);
            changed |= enum_combo(ui, "wrap", wrap);
        }
        TextureDesc::Constant(c) => changed |= colour(ui, "colour", c),
        TextureDesc::Formula { grey, r, g, b, .. } => {
            changed |=
                super::texture::colour_formulas_ui(ui, image_label, picker.object, grey, [r, g, b]);
        }
    }
    changed
}

/// An image path field: typed (Enter or *Load*) or chosen with *Browse…*. The typing is kept
/// while it is about the same object and path, so it never shows another object's path or a
/// path the scene no longer has (after a bad file is rolled back, say).
fn image_field(ui: &mut egui::Ui, label: &str, path: &mut String, picker: &ImagePicker) -> bool {
    let id = ui.make_persistent_id("path");
    let mut text = ui
        .data_mut(|d| d.get_temp::<(usize, String, String)>(id))
        .filter(|(object, seen, _)| *object == picker.object && seen == path)
        .map_or_else(|| path.clone(), |(_, _, text)| text);
    let mut changed = false;
    // The buttons on a row of their own: the field is indented under its parameter or map,
    // and one row of all three would not fit in the panel.
    let enter = ui
        .horizontal(|ui| {
            let l = ui.label(label);
            let r = ui
                .add(
                    egui::TextEdit::singleline(&mut text)
                        .desired_width((ui.available_width() - 12.0).max(80.0)),
                )
                .labelled_by(l.id)
                .on_hover_text("Path relative to the preset's folder; Enter loads it");
            r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter))
        })
        .inner;
    ui.horizontal(|ui| {
        if (ui
            .button("Load")
            .on_hover_text("Load the image at this path")
            .clicked()
            || enter)
            && text != *path
        {
            path.clone_from(&text);
            changed = true;
        }
        if let Some(p) = browse_button(ui, picker.browser, BrowseFor::Image, picker.preset) {
            text.clone_from(&p);
            *path = p;
            changed = true;
        }
    });
    ui.data_mut(|d| d.insert_temp(id, (picker.object, path.clone(), text)));
    changed
}
