//! The material editor: the kind (matte, Phong, emissive) and its coefficients and colours,
//! each either a plain value or a texture with its own mapping, filter and wrap.

use crate::gui::widgets::{colour, enum_combo, number};
use crate::names::Named;
use crate::scene::{
    ChannelDesc, ColorDesc, MaterialDesc, ParamMut, ParamRef, ScalarDesc, TextureDesc, TextureKind,
};
use crate::texture::Channel;

/// The texture kinds a parameter can switch to (a mesh's own material is only for `cd`).
const PARAM_KINDS: [TextureKind; 4] = [
    TextureKind::Constant,
    TextureKind::Image,
    TextureKind::Checker,
    TextureKind::UvGrid,
];

/// The material menu and the chosen material's coefficients. Returns whether it changed.
pub(super) fn material_ui(ui: &mut egui::Ui, m: &mut MaterialDesc) -> bool {
    let mut changed = false;
    let mut kind = m.kind();
    if enum_combo(ui, "Material", &mut kind) {
        *m = m.converted(kind);
        changed = true;
    }
    let defaults = m.kind().default_desc();
    // A parameter switched to an image starts on the colour's image, if it has one.
    let colour_image = match m.texture() {
        t @ TextureDesc::Image { .. } => Some(t.clone()),
        _ => None,
    };
    let default_of = |name: &str| {
        defaults
            .params()
            .into_iter()
            .find(|(n, _)| *n == name)
            .map(|(_, p)| p)
    };
    for (name, p) in m.params_mut() {
        let label = label(name);
        ui.push_id(name, |ui| match p {
            ParamMut::Scalar(s) => {
                let fallback = match default_of(name) {
                    Some(ParamRef::Scalar(ScalarDesc::Value(v))) => *v,
                    _ => 1.0,
                };
                changed |= scalar_ui(ui, label, s, fallback, colour_image.as_ref());
            }
            ParamMut::Color(c) => {
                changed |= colour_param_ui(ui, label, c, colour_image.as_ref());
            }
        });
    }
    changed
}

/// What the editor calls a parameter.
fn label(name: &str) -> &'static str {
    match name {
        "ka" => "ka (ambient)",
        "kd" => "kd (diffuse)",
        "ks" => "ks (specular)",
        "exp" => "exponent",
        "cs" => "specular colour",
        "ls" => "ls (radiance)",
        "kr" => "kr (mirror)",
        "cr" => "mirror colour",
        "ce" => "ce (night glow)",
        _ => "parameter",
    }
}

/// The largest value and the drag speed of a coefficient's editor.
fn range_of(label: &str) -> (f32, f64) {
    match label {
        "exponent" => (10_000.0, 0.5),
        "ls (radiance)" => (1e4, 0.01),
        _ => (10.0, 0.01),
    }
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
    label: &str,
    s: &mut ScalarDesc,
    fallback: f32,
    colour_image: Option<&TextureDesc>,
) -> bool {
    let mut changed = false;
    let mut kind = s.texture().map_or(TextureKind::Constant, TextureDesc::kind);
    ui.horizontal(|ui| {
        if let ScalarDesc::Value(v) = s {
            let (max, speed) = range_of(label);
            changed |= number(ui, label, v, 0.0..=max, speed);
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
    if let Some(mut channel) = s.channel() {
        ui.indent(label, |ui| {
            if enum_combo(ui, "channel", &mut channel) {
                let texture = s
                    .texture()
                    .cloned()
                    .unwrap_or(TextureDesc::Constant(crate::math::Rgb::grey(fallback)));
                *s = if channel == Channel::Luminance {
                    ScalarDesc::Texture(texture)
                } else {
                    ScalarDesc::Channel(ChannelDesc { texture, channel })
                };
                changed = true;
            }
            if let Some(t) = s.texture_mut() {
                changed |= texture_settings_ui(ui, t);
            }
        });
    }
    changed
}

fn colour_param_ui(
    ui: &mut egui::Ui,
    label: &str,
    c: &mut ColorDesc,
    colour_image: Option<&TextureDesc>,
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
        ui.indent(label, |ui| changed |= texture_settings_ui(ui, t));
    }
    changed
}

/// A parameter texture's own settings: the image path (applied with Enter), mapping, filter
/// and wrap; a checker's squares and colours; the (u, v) transform.
fn texture_settings_ui(ui: &mut egui::Ui, t: &mut TextureDesc) -> bool {
    let mut changed = false;
    if let Some(uv) = t.uv_transform_mut() {
        changed |= uv_transform_ui(ui, uv);
    }
    if let Some(current) = t.mapping() {
        let mut m = current;
        if enum_combo(ui, "mapping", &mut m) {
            t.set_mapping(m);
            changed = true;
        }
    }
    match t {
        TextureDesc::Image {
            path, filter, wrap, ..
        } => {
            let id = ui.make_persistent_id("path");
            let mut text = ui
                .data_mut(|d| d.get_temp::<String>(id))
                .unwrap_or_else(|| path.clone());
            ui.horizontal(|ui| {
                let l = ui.label("image");
                let r = ui
                    .add(egui::TextEdit::singleline(&mut text).desired_width(150.0))
                    .labelled_by(l.id)
                    .on_hover_text("Path relative to the preset's folder; Enter loads it");
                if r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) && text != *path
                {
                    path.clone_from(&text);
                    changed = true;
                }
            });
            ui.data_mut(|d| d.insert_temp(id, text));
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
    }
    changed
}

/// The (u, v) scale, rotation and offset of a texture. Returns whether they changed.
pub(super) fn uv_transform_ui(ui: &mut egui::Ui, uv: &mut crate::mapping::UvTransform) -> bool {
    let mut changed = false;
    ui.horizontal(|ui| {
        ui.label("uv scale");
        for (axis, v) in [("u", &mut uv.scale.x), ("v", &mut uv.scale.y)] {
            let before = *v;
            changed |= ui
                .add(
                    egui::DragValue::new(v)
                        .speed(0.05)
                        .range(-1e6..=1e6)
                        .prefix(format!("{axis} ")),
                )
                .on_hover_text("Tiles the texture: 2 repeats it twice across the mapping")
                .changed();
            // Zero is refused by the scene: step over it.
            if *v == 0.0 {
                *v = if before < 0.0 { -1e-3 } else { 1e-3 };
            }
        }
    });
    changed |= number(
        ui,
        "uv rotate (degrees)",
        &mut uv.rotate,
        -360.0..=360.0,
        1.0,
    );
    ui.horizontal(|ui| {
        ui.label("uv offset");
        for (axis, v) in [("u", &mut uv.offset.x), ("v", &mut uv.offset.y)] {
            changed |= ui
                .add(
                    egui::DragValue::new(v)
                        .speed(0.01)
                        .range(-1e6..=1e6)
                        .prefix(format!("{axis} ")),
                )
                .changed();
        }
    });
    changed
}
