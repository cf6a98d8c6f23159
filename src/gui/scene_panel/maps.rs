//! The surface maps of an object, beside its material: a clip map (`alpha`: where the surface
//! exists), a bump map (`bump`: a height texture and its scale) and a normal map (`normal`: a
//! map of tangent-space normals and its strength). Each is off ("None") or a texture, edited
//! with the textured coefficients' own editor (its (u, v) transform, mapping, image path with
//! *Browse…*, filter and wrap). An object has a bump map or a normal map, not both: switching
//! one on switches the other off, with a note saying so; switching a map off and on again
//! brings it back as it was.

use super::material::{channel_ui, texture_settings_ui};
use super::{ImagePicker, ScenePanel};
use crate::gui::widgets::{number_drag_range, number_tip};
use crate::math::Rgb;
use crate::names::Named;
use crate::scene::{
    BumpDesc, ChannelDesc, NormalMapDesc, ObjectDesc, ScalarDesc, TextureDesc, TextureKind,
    relative_asset_path,
};
use crate::texture::{Channel, Filter};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The textures a map can switch to.
const MAP_KINDS: [TextureKind; 3] = [
    TextureKind::Image,
    TextureKind::Checker,
    TextureKind::UvGrid,
];

/// A new bump map's scale: the preset's default for `bump: (scale)`.
const BUMP_SCALE: f32 = 0.02;

/// The three maps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Map {
    /// `alpha`.
    Clip,
    /// `bump`.
    Bump,
    /// `normal`.
    Normal,
}

impl Map {
    /// The editor's label (also the combo box's name).
    pub(super) const fn label(self) -> &'static str {
        match self {
            Self::Clip => "clip map",
            Self::Bump => "bump map",
            Self::Normal => "normal map",
        }
    }

    /// What the map does, in the lecture's words.
    const fn tip(self) -> &'static str {
        match self {
            Self::Clip => {
                "A clip map says where the surface exists: 1 solid, 0 absent, in between \
                 partly (a filtered, soft edge). Camera, mirrored and shadow rays all pass \
                 where it is below 1, so a cut-out casts a cut-out shadow. Usually an image's \
                 alpha channel (the preset's `alpha`)."
            }
            Self::Bump => {
                "A bump map tilts the shading normal by the height's slope (the height \
                 texture's filtered derivatives, carried to the surface through the mapping's \
                 dp/du and dp/dv); the surface itself does not move, so the silhouette stays \
                 round. An object has a bump map or a normal map, not both (the preset's \
                 `bump`)."
            }
            Self::Normal => {
                "A normal map replaces the shading normal by the one its texel stores, in \
                 tangent space: red along dp/du, green along dp/dv (the mapping's tangent \
                 frame), blue out of the surface; (128, 128, 255) is the unchanged normal. \
                 Read raw, not as a colour; usually an image derived from a height field. An \
                 object has a normal map or a bump map, not both (the preset's `normal`)."
            }
        }
    }

    /// The other of bump and normal map (the one switching this on switches off).
    const fn rival(self) -> Option<Self> {
        match self {
            Self::Clip => None,
            Self::Bump => Some(Self::Normal),
            Self::Normal => Some(Self::Bump),
        }
    }
}

/// What a map's menu offers: off, a plain value (a clip map only: the same alpha
/// everywhere), or a texture of a kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Choice {
    Off,
    Value,
    Texture(TextureKind),
}

impl Choice {
    fn name(self) -> &'static str {
        match self {
            Self::Off => "None",
            Self::Value => "value",
            Self::Texture(k) => k.name(),
        }
    }
}

/// A map as it was switched off, and the preset its image paths are relative to.
#[derive(Clone, Debug)]
enum Kept {
    Clip(ScalarDesc),
    Bump(BumpDesc),
    Normal(NormalMapDesc),
}

/// What the map editors keep between frames: the maps switched off (per object and map, to
/// bring them back), and the note that one of bump and normal map switched the other off.
#[derive(Default)]
pub(super) struct MapMemory {
    kept: HashMap<(usize, Map), (PathBuf, Kept)>,
    /// (object, the map switched on) when that switched its rival off.
    note: Option<(usize, Map)>,
}

impl MapMemory {
    /// Object `i` was removed: its maps go, the later objects' move down by one.
    pub(super) fn object_removed(&mut self, i: usize) {
        self.kept = std::mem::take(&mut self.kept)
            .into_iter()
            .filter(|((k, _), _)| *k != i)
            .map(|((k, m), v)| ((if k > i { k - 1 } else { k }, m), v))
            .collect();
        self.note = None;
    }
}

/// The map's current choice on `obj`.
fn choice(obj: &ObjectDesc, map: Map) -> Choice {
    let texture = match map {
        Map::Clip => match &obj.alpha {
            None => return Choice::Off,
            Some(ScalarDesc::Value(_)) => return Choice::Value,
            Some(s) => s.texture(),
        },
        Map::Bump => obj.bump.as_ref().map(|b| &b.height),
        Map::Normal => obj.normal.as_ref().map(|n| &n.map),
    };
    texture.map_or(Choice::Off, |t| Choice::Texture(t.kind()))
}

/// Takes the map off `obj`, returning what it was.
fn take(obj: &mut ObjectDesc, map: Map) -> Option<Kept> {
    match map {
        Map::Clip => obj.alpha.take().map(Kept::Clip),
        Map::Bump => obj.bump.take().map(Kept::Bump),
        Map::Normal => obj.normal.take().map(Kept::Normal),
    }
}

/// The texture of a kept map.
fn kept_texture(k: &mut Kept) -> Option<&mut TextureDesc> {
    match k {
        Kept::Clip(s) => s.texture_mut(),
        Kept::Bump(b) => Some(&mut b.height),
        Kept::Normal(n) => Some(&mut n.map),
    }
}

/// The folder a preset's paths are relative to.
fn folder(preset: &Path) -> &Path {
    preset
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// The filter of a texture that has one.
const fn filter_of(t: &TextureDesc) -> Option<Filter> {
    match t {
        TextureDesc::Constant(_) => None,
        TextureDesc::Image { filter, .. }
        | TextureDesc::Checker { filter, .. }
        | TextureDesc::MeshMaterial { filter, .. }
        | TextureDesc::UvGrid { filter, .. } => Some(*filter),
    }
}

/// Whether the image file at `path` has an alpha channel (read from its header only).
fn has_alpha(path: &Path) -> bool {
    use image::ImageDecoder as _;
    image::ImageReader::open(path)
        .ok()
        .and_then(|r| r.with_guessed_format().ok())
        .and_then(|r| r.into_decoder().ok())
        .is_some_and(|d| d.color_type().has_alpha())
}

impl ScenePanel {
    /// The clip, bump and normal map editors of the selected object `obj`. Returns whether
    /// any changed.
    pub(super) fn maps_ui(
        &mut self,
        ui: &mut egui::Ui,
        obj: &mut ObjectDesc,
        picker: &ImagePicker,
    ) -> bool {
        let mut changed = false;
        for map in [Map::Clip, Map::Bump, Map::Normal] {
            ui.push_id(map.label(), |ui| {
                changed |= self.map_ui(ui, obj, map, picker);
            });
        }
        if let Some((object, on)) = self.maps.note
            && object == self.selected
            && let Some(off) = on.rival()
            && choice(obj, on) != Choice::Off
            && choice(obj, off) == Choice::Off
        {
            ui.colored_label(
                ui.visuals().warn_fg_color,
                format!(
                    "The {} is off: an object has a bump map or a normal map, not both \
                     (switching it back on brings it back and turns the {} off).",
                    off.label(),
                    on.label()
                ),
            );
        }
        changed
    }

    /// One map: its menu, then its texture's editor and its number (alpha, bump scale,
    /// normal strength).
    fn map_ui(
        &mut self,
        ui: &mut egui::Ui,
        obj: &mut ObjectDesc,
        map: Map,
        picker: &ImagePicker,
    ) -> bool {
        let mut changed = false;
        let current = choice(obj, map);
        let mut chosen = current;
        ui.horizontal(|ui| {
            let l = ui.label(map.label()).on_hover_text(map.tip());
            egui::ComboBox::from_id_salt(map.label())
                .selected_text(chosen.name())
                .width(80.0)
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut chosen, Choice::Off, "None")
                        .on_hover_text("No map: the object as its material shades it");
                    if map == Map::Clip {
                        ui.selectable_value(&mut chosen, Choice::Value, "value")
                            .on_hover_text(
                                "The same alpha everywhere: 0.5 lets half the light through",
                            );
                    }
                    for k in MAP_KINDS {
                        ui.selectable_value(&mut chosen, Choice::Texture(k), k.name())
                            .on_hover_text(k.description());
                    }
                })
                .response
                .labelled_by(l.id)
                .on_hover_text(map.tip());
        });
        if chosen != current {
            self.switch(obj, map, chosen, picker.preset);
            changed = true;
        }
        ui.indent(map.label(), |ui| match map {
            Map::Clip => match &mut obj.alpha {
                Some(ScalarDesc::Value(a)) => {
                    changed |= number_tip(
                        ui,
                        "alpha",
                        "How much of the surface exists: 1 solid, 0 absent",
                        a,
                        0.0..=1.0,
                        0.01,
                    );
                }
                Some(s) => {
                    changed |= channel_ui(ui, s);
                    if let Some(t) = s.texture_mut() {
                        changed |= texture_settings_ui(ui, t, picker, "alpha image");
                    }
                }
                None => {}
            },
            Map::Bump => {
                if let Some(b) = &mut obj.bump {
                    changed |= number_drag_range(
                        ui,
                        "bump scale",
                        "The height of a texture value of 1, in the object's own units: \
                         larger tilts the normal more, 0 flattens it, negative engraves \
                         instead of embossing",
                        &mut b.scale,
                        -1.0..=1.0,
                        0.001,
                    );
                    changed |= texture_settings_ui(ui, &mut b.height, picker, "height image");
                }
            }
            Map::Normal => {
                if let Some(n) = &mut obj.normal {
                    changed |= number_drag_range(
                        ui,
                        "normal strength",
                        "Multiplies the map's tangential part (red and green): 0 flattens \
                         it, 2 doubles its slopes, negative inverts them",
                        &mut n.strength,
                        -10.0..=10.0,
                        0.01,
                    );
                    changed |= texture_settings_ui(ui, &mut n.map, picker, "normal image");
                }
            }
        });
        changed
    }

    /// Switches `map` of the selected object to `to`: the map it had is kept (to come back
    /// when switched to its kind again), and a bump or normal map switched on switches the
    /// other off.
    fn switch(&mut self, obj: &mut ObjectDesc, map: Map, to: Choice, preset: &Path) {
        let key = self.selected;
        // Made while the object still has its maps: a new one starts on their mapping.
        let new = match to {
            Choice::Off => None,
            _ => Some(match self.restored(map, to, preset) {
                Some(kept) => kept,
                None => self.new_map(obj, map, to, preset),
            }),
        };
        if let Some(old) = take(obj, map) {
            self.maps
                .kept
                .insert((key, map), (preset.to_path_buf(), old));
        }
        self.maps.note = None;
        let Some(new) = new else {
            return;
        };
        if let Some(rival) = map.rival()
            && let Some(old) = take(obj, rival)
        {
            self.maps
                .kept
                .insert((key, rival), (preset.to_path_buf(), old));
            self.maps.note = Some((key, map));
        }
        match new {
            Kept::Clip(s) => obj.alpha = Some(s),
            Kept::Bump(b) => obj.bump = Some(b),
            Kept::Normal(n) => obj.normal = Some(n),
        }
    }

    /// A first `map` of `to`: a clip map's value 0.5, or a texture ([`Self::new_texture`]).
    /// A clip map's image is read through its alpha channel if the file has one, else its
    /// luminance; a bump map starts at the preset's default scale, a normal map at strength 1.
    fn new_map(&mut self, obj: &ObjectDesc, map: Map, to: Choice, preset: &Path) -> Kept {
        let Choice::Texture(kind) = to else {
            return Kept::Clip(ScalarDesc::Value(0.5));
        };
        let texture = self.new_texture(obj, map, kind, preset);
        match map {
            Map::Clip => Kept::Clip(match &texture {
                TextureDesc::Image { path, .. } if has_alpha(&folder(preset).join(path)) => {
                    ScalarDesc::Channel(ChannelDesc {
                        texture,
                        channel: Channel::Alpha,
                    })
                }
                _ => ScalarDesc::Texture(texture),
            }),
            Map::Bump => Kept::Bump(BumpDesc {
                height: texture,
                scale: BUMP_SCALE,
            }),
            Map::Normal => Kept::Normal(NormalMapDesc {
                map: texture,
                strength: 1.0,
            }),
        }
    }

    /// The map the selected object had as `to` before it was switched away, its image paths
    /// made relative to `preset` (which may have moved since, after *Save as*).
    fn restored(&mut self, map: Map, to: Choice, preset: &Path) -> Option<Kept> {
        let key = (self.selected, map);
        let (_, kept) = self.maps.kept.get(&key)?;
        let kind = match kept {
            Kept::Clip(ScalarDesc::Value(_)) => Choice::Value,
            Kept::Clip(s) => Choice::Texture(s.texture()?.kind()),
            Kept::Bump(b) => Choice::Texture(b.height.kind()),
            Kept::Normal(n) => Choice::Texture(n.map.kind()),
        };
        if kind != to {
            return None;
        }
        let (from, mut kept) = self.maps.kept.remove(&key)?;
        if let Some(TextureDesc::Image { path, .. }) = kept_texture(&mut kept)
            && from != preset
        {
            *path = relative_asset_path(&folder(&from).join(path.as_str()), folder(preset));
        }
        Some(kept)
    }

    /// A first texture of `kind` for `map`, on the mapping, (u, v) transform and filter of
    /// the map's own texture (switched to another kind), else of the colour texture, else (a
    /// constant colour has none) of another map of the object; the filter trilinear if none
    /// has one. An image starts on the colour's image (a normal map: on an image in
    /// `assets/` named as a normal map, if there is one), else on the first image in
    /// `assets/`; a clip map's checker is white and black (solid and absent squares).
    fn new_texture(
        &mut self,
        obj: &ObjectDesc,
        map: Map,
        kind: TextureKind,
        preset: &Path,
    ) -> TextureDesc {
        let colour = obj.material.texture();
        let (clip, bump, normal) = (
            obj.alpha.as_ref().and_then(ScalarDesc::texture),
            obj.bump.as_ref().map(|b| &b.height),
            obj.normal.as_ref().map(|n| &n.map),
        );
        let own = match map {
            Map::Clip => clip,
            Map::Bump => bump,
            Map::Normal => normal,
        };
        // The map's own texture (switched to another kind), the colour, else the object's
        // other maps (the one a bump or normal map replaces first): the first with a mapping.
        let source = own
            .into_iter()
            .chain(std::iter::once(colour))
            .chain(normal)
            .chain(bump)
            .chain(clip)
            .find(|t| t.mapping().is_some())
            .unwrap_or(colour);
        let mut t = source.converted(kind);
        // The source's filter, else (a constant has none) one that averages over the pixel's
        // footprint: a height's slope or a normal read at one texel aliases.
        t.set_filter(filter_of(source).unwrap_or(Filter::Trilinear));
        match &mut t {
            TextureDesc::Image { path, .. } => {
                let dir = folder(preset).to_path_buf();
                let assets = self.assets(preset).to_vec();
                let named_normal = assets.iter().find(|a| {
                    a.file_name()
                        .is_some_and(|n| n.to_string_lossy().to_lowercase().contains("normal"))
                });
                if map == Map::Normal
                    && let Some(a) = named_normal
                {
                    *path = relative_asset_path(a, &dir);
                } else if matches!(colour, TextureDesc::Image { .. }) {
                    return colour.clone();
                } else if let Some(a) = assets.first() {
                    *path = relative_asset_path(a, &dir);
                }
            }
            TextureDesc::Checker { colors, .. } if map == Map::Clip => {
                *colors = (Rgb::WHITE, Rgb::BLACK);
            }
            _ => {}
        }
        t
    }
}
