//! The surface maps of an object, beside its material: a clip map (`alpha`: where the surface
//! exists), a bump map (`bump`: a height texture and its scale), a normal map (`normal`: a
//! map of tangent-space normals and its strength) and, on a mesh, a displacement map
//! (`displace`: a height texture, its scale and the subdivision levels). Each is off ("None")
//! or a texture, edited with the textured coefficients' own editor (its (u, v) transform,
//! mapping, image path with *Browse…*, filter and wrap). An object has a bump map or a normal
//! map, not both: switching one on switches the other off, with a note saying so; switching a
//! map off and on again brings it back as it was.
//!
//! A displaced mesh is rebuilt on the UI thread at every edit (0.4 s for the `displaced`
//! preset's knot at 3 levels, 2 s at 4, in the debug build), so its scale is applied when a
//! drag ends (or a typed value on Enter), not at every frame of the drag, and its levels are
//! chosen from a menu.

use super::material::{channel_ui, texture_settings_ui};
use super::{ImagePicker, ScenePanel};
use crate::geometry::displace::MAX_DISPLACED_TRIANGLES;
use crate::gui::document::ObjectId;
use crate::gui::widgets::number_tip;
use crate::math::Rgb;
use crate::names::Named;
use crate::scene::{
    BumpDesc, ChannelDesc, DEFAULT_SUBDIVIDE, DisplaceDesc, NormalMapDesc, ObjectDesc, ScalarDesc,
    TextureDesc, TextureKind, relative_asset_path,
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

/// The textures a displacement map can switch to: a constant height too (it moves the whole
/// surface out along its normals by the same distance).
const DISPLACE_KINDS: [TextureKind; 4] = [
    TextureKind::Image,
    TextureKind::Checker,
    TextureKind::UvGrid,
    TextureKind::Constant,
];

/// A new bump map's scale: the preset's default for `bump: (scale)`.
const BUMP_SCALE: f32 = 0.02;

/// The most subdivision levels the menu offers: the most a mesh of one triangle may have
/// within [`MAX_DISPLACED_TRIANGLES`] (4^11 = 4 M). A real mesh has fewer; the scene builder
/// refuses levels beyond its limit with an error, and the scene stays as it was.
const MAX_LEVELS: u32 = MAX_DISPLACED_TRIANGLES.ilog2() / 2;

/// The maps: clip, bump, normal and displacement.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Map {
    /// `alpha`.
    Clip,
    /// `bump`.
    Bump,
    /// `normal`.
    Normal,
    /// `displace` (meshes only).
    Displace,
}

impl Map {
    /// The editor's label (also the combo box's name).
    pub(super) const fn label(self) -> &'static str {
        match self {
            Self::Clip => "clip map",
            Self::Bump => "bump map",
            Self::Normal => "normal map",
            Self::Displace => "displacement",
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
                 `bump`). A mesh can also be displaced (its Displacement editor), which moves \
                 the surface itself; the other shapes have only the bump map."
            }
            Self::Normal => {
                "A normal map replaces the shading normal by the one its texel stores, in \
                 tangent space: red along dp/du, green along dp/dv (the mapping's tangent \
                 frame), blue out of the surface; (128, 128, 255) is the unchanged normal. \
                 Read raw, not as a colour; usually an image derived from a height field. An \
                 object has a normal map or a bump map, not both (the preset's `normal`)."
            }
            Self::Displace => {
                "A displacement map moves the surface itself: the mesh is subdivided and \
                 every vertex moves along its normal by the height texture's luminance times \
                 the scale, so the outline and the shadows change, unlike a bump map, which \
                 only tilts the shading normal and leaves the silhouette as it was. Each \
                 subdivision level makes 4x the triangles (and about 4x the time to build \
                 them); the window rebuilds the mesh at every edit, so a dragged scale applies \
                 when the drag ends. Meshes only (the preset's `displace`)."
            }
        }
    }

    /// The other of bump and normal map (the one switching this on switches off).
    const fn rival(self) -> Option<Self> {
        match self {
            Self::Clip | Self::Displace => None,
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
    Displace(DisplaceDesc),
}

/// What the map editors keep between frames: the maps switched off (per object and map, to
/// bring them back), and the note that one of bump and normal map switched the other off.
#[derive(Default)]
pub(super) struct MapMemory {
    kept: HashMap<(ObjectId, Map), (PathBuf, Kept)>,
    /// (object, the map switched on) when that switched its rival off.
    note: Option<(ObjectId, Map)>,
    /// (object, value) while the displacement scale of that object is dragged: applied (and
    /// the mesh rebuilt) when the drag ends.
    scale_drag: Option<(ObjectId, f32)>,
}

impl MapMemory {
    /// An object was removed: the note and a drag in progress go; the maps kept stay under
    /// their objects' ids (Undo may bring the object back).
    pub(super) fn object_removed(&mut self) {
        self.note = None;
        self.scale_drag = None;
    }

    /// Object `key`'s shape is no longer a mesh: its displacement map is kept (in the
    /// preset `preset`), to come back when the object is a mesh again and displacement is
    /// switched on.
    pub(super) fn keep_displacement(&mut self, key: ObjectId, obj: &mut ObjectDesc, preset: &Path) {
        if let Some(d) = obj.displace.take() {
            self.kept.insert(
                (key, Map::Displace),
                (preset.to_path_buf(), Kept::Displace(d)),
            );
        }
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
        Map::Displace => obj.displace.as_ref().map(|d| &d.height),
    };
    texture.map_or(Choice::Off, |t| Choice::Texture(t.kind()))
}

/// Takes the map off `obj`, returning what it was.
fn take(obj: &mut ObjectDesc, map: Map) -> Option<Kept> {
    match map {
        Map::Clip => obj.alpha.take().map(Kept::Clip),
        Map::Bump => obj.bump.take().map(Kept::Bump),
        Map::Normal => obj.normal.take().map(Kept::Normal),
        Map::Displace => obj.displace.take().map(Kept::Displace),
    }
}

/// The texture of a kept map.
fn kept_texture(k: &mut Kept) -> Option<&mut TextureDesc> {
    match k {
        Kept::Clip(s) => s.texture_mut(),
        Kept::Bump(b) => Some(&mut b.height),
        Kept::Normal(n) => Some(&mut n.map),
        Kept::Displace(d) => Some(&mut d.height),
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
        TextureDesc::Constant(_) | TextureDesc::Formula { .. } => None,
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
            && object == self.key
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

    /// The displacement map editor of the selected object `obj` (a mesh: the caller shows
    /// none for a generic shape): its menu, then its scale, levels and height texture.
    /// Returns whether it changed.
    pub(super) fn displacement_ui(
        &mut self,
        ui: &mut egui::Ui,
        obj: &mut ObjectDesc,
        picker: &ImagePicker,
    ) -> bool {
        ui.push_id(Map::Displace.label(), |ui| {
            self.map_ui(ui, obj, Map::Displace, picker)
        })
        .inner
    }

    /// One map: its menu, then its texture's editor and its number (alpha, bump scale,
    /// normal strength; a displacement's scale and levels).
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
                    let kinds: &[TextureKind] = if map == Map::Displace {
                        &DISPLACE_KINDS
                    } else {
                        &MAP_KINDS
                    };
                    for &k in kinds {
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
                    changed |= number_tip(
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
                    changed |= number_tip(
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
            Map::Displace => changed |= self.displace_settings_ui(ui, obj, picker),
        });
        changed
    }

    /// A displacement's scale (applied when a drag ends), levels and height texture.
    fn displace_settings_ui(
        &mut self,
        ui: &mut egui::Ui,
        obj: &mut ObjectDesc,
        picker: &ImagePicker,
    ) -> bool {
        let key = self.key;
        let Some(d) = &mut obj.displace else {
            return false;
        };
        let mut changed = false;
        let tip = "How far a height of 1 moves the surface along its normal, in the mesh \
                   file's units; negative pushes in. Applied when the drag ends (or a typed \
                   value on Enter): each change rebuilds the mesh";
        let dragged = self
            .maps
            .scale_drag
            .filter(|(object, _)| *object == key)
            .map(|(_, v)| v);
        let mut value = dragged.unwrap_or(d.scale);
        let r = ui
            .horizontal(|ui| {
                let l = ui.label("displacement scale").on_hover_text(tip);
                let r = ui
                    .add(
                        egui::DragValue::new(&mut value)
                            .range(-1.0..=1.0)
                            .clamp_existing_to_range(false)
                            .speed(0.001)
                            .update_while_editing(false),
                    )
                    .labelled_by(l.id)
                    .on_hover_text(tip);
                if dragged.is_some() {
                    ui.weak("(on release)");
                }
                r
            })
            .inner;
        if r.dragged() {
            // Not yet: the mesh is rebuilt once, when the drag ends.
            self.maps.scale_drag = Some((key, value));
        } else if dragged.is_some() || r.changed() {
            // A drag ended (this frame, or the field went away while dragged), or a value was
            // typed, stepped with the keys or set by a screen reader.
            self.maps.scale_drag = None;
            if value != d.scale {
                d.scale = value;
                changed = true;
            }
        }
        changed |= levels_ui(ui, &mut d.subdivide);
        changed |= texture_settings_ui(ui, &mut d.height, picker, "displacement image");
        changed
    }

    /// Switches `map` of the selected object to `to`: the map it had is kept (to come back
    /// when switched to its kind again), and a bump or normal map switched on switches the
    /// other off.
    fn switch(&mut self, obj: &mut ObjectDesc, map: Map, to: Choice, preset: &Path) {
        let key = self.key;
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
            Kept::Displace(d) => obj.displace = Some(d),
        }
    }

    /// A first `map` of `to`: a clip map's value 0.5, or a texture ([`Self::new_texture`]).
    /// A clip map's image is read through its alpha channel if the file has one, else its
    /// luminance; a bump map starts at the preset's default scale, a normal map at strength 1,
    /// a displacement at the bump map's scale if the object has one (else the bump map's
    /// default) and the preset's default levels.
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
            Map::Displace => Kept::Displace(DisplaceDesc {
                height: texture,
                scale: obj.bump.as_ref().map_or(BUMP_SCALE, |b| b.scale),
                subdivide: DEFAULT_SUBDIVIDE,
            }),
        }
    }

    /// The map the selected object had as `to` before it was switched away, its image paths
    /// made relative to `preset` (which may have moved since, after *Save as*).
    fn restored(&mut self, map: Map, to: Choice, preset: &Path) -> Option<Kept> {
        let key = (self.key, map);
        let (_, kept) = self.maps.kept.get(&key)?;
        let kind = match kept {
            Kept::Clip(ScalarDesc::Value(_)) => Choice::Value,
            Kept::Clip(s) => Choice::Texture(s.texture()?.kind()),
            Kept::Bump(b) => Choice::Texture(b.height.kind()),
            Kept::Normal(n) => Choice::Texture(n.map.kind()),
            Kept::Displace(d) => Choice::Texture(d.height.kind()),
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
    /// `assets/`; a clip map's checker is white and black (solid and absent squares). A
    /// displacement of the bump map's kind starts as the bump map's heights (the same
    /// texture, now moving the surface).
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
        if map == Map::Displace
            && let Some(b) = bump
            && b.kind() == kind
        {
            return b.clone();
        }
        let own = match map {
            Map::Clip => clip,
            Map::Bump => bump,
            Map::Normal => normal,
            Map::Displace => obj.displace.as_ref().map(|d| &d.height),
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

/// The subdivision levels' menu, 0 to [`MAX_LEVELS`], each with the factor it multiplies the
/// triangles by. Returns whether the levels changed (one choice, one rebuild).
fn levels_ui(ui: &mut egui::Ui, levels: &mut u32) -> bool {
    let tip = format!(
        "How many times every triangle is split into four before the vertices move (0 moves \
         only the file's vertices). Each level makes 4x the triangles, and the mesh takes \
         about 4x longer to build; at most {MAX_DISPLACED_TRIANGLES} triangles in all (more is \
         refused, and the scene stays as it was)"
    );
    let factor = |l: u32| 4usize.saturating_pow(l);
    let before = *levels;
    ui.horizontal(|ui| {
        let l = ui.label("subdivision levels").on_hover_text(&tip);
        egui::ComboBox::from_id_salt("subdivision levels")
            .selected_text(format!("{before} (x{})", factor(before)))
            .width(80.0)
            .show_ui(ui, |ui| {
                for n in 0..=MAX_LEVELS.max(before.min(32)) {
                    ui.selectable_value(levels, n, format!("{n} (x{})", factor(n)));
                }
            })
            .response
            .labelled_by(l.id)
            .on_hover_text(&tip);
    });
    *levels != before
}
