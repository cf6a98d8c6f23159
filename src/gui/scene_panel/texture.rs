//! The texture editor: the kind, the mapping, the (u, v) transform and the chosen texture's
//! settings (an image's path, filter, lookup, wrap and scale; a checker's squares and
//! colours), with the list of images in `assets/`.

use super::formula_fields::{check_colour, check_mapping, formula_group};
use super::{PathText, ScenePanel, browse_button};
use crate::gui::files::{BrowseFor, IMAGE_EXTENSIONS};
use crate::gui::widgets::{colour, enum_combo, number, number_tip, uv_transform};
use crate::mapping::formula::compare::lecture_formula;
use crate::mapping::{FormulaMapping, Mapping};
use crate::names::Named as _;
use crate::scene::{MappingDesc, RenderDesc, TextureDesc, TextureKind, relative_asset_path};
use crate::texture::{Filter, MAX_ANISOTROPY_LIMIT};
use std::path::{Path, PathBuf};

/// The folders the image list is read from: `assets/` in the preset's folder and beside it
/// (the built-in presets' `../assets`).
fn asset_dirs(preset: &Path) -> Vec<PathBuf> {
    let dir = preset
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    vec![dir.join("assets"), dir.join("../assets")]
}

fn list_images(dirs: &[PathBuf]) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = Vec::new();
    for dir in dirs {
        let Ok(entries) = crate::input::list_dir(dir) else {
            continue;
        };
        for p in entries {
            let ok = p
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| IMAGE_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()));
            let canon = std::fs::canonicalize(&p).unwrap_or_else(|_| p.clone());
            if ok
                && !out
                    .iter()
                    .any(|q| std::fs::canonicalize(q).unwrap_or_else(|_| q.clone()) == canon)
            {
                out.push(p);
            }
        }
    }
    out.sort_by_key(|p| p.file_name().map(std::ffi::OsStr::to_owned));
    out
}

impl ScenePanel {
    pub(super) fn texture_ui(
        &mut self,
        ui: &mut egui::Ui,
        tex: &mut TextureDesc,
        render: &mut RenderDesc,
        preset: &Path,
    ) -> bool {
        let mut changed = false;
        let mut kind = tex.kind();
        if enum_combo(ui, "Texture", &mut kind) {
            *tex = self.switched(tex, kind, preset);
            self.path_text = None;
            changed = true;
        }
        if let Some(current) = tex.mapping() {
            let mut m = current.clone();
            if mapping_ui(ui, "Mapping", &mut m, self.key.number()) {
                tex.set_mapping(m);
                changed = true;
            }
            if matches!(tex.mapping(), Some(MappingDesc::Formula { .. })) {
                changed |= self.formula_check_ui(ui, render);
            }
        }
        if let Some(uv) = tex.uv_transform_mut() {
            changed |= uv_transform(ui, uv);
        }
        match tex {
            TextureDesc::Constant(c) => changed |= colour(ui, "colour", c),
            TextureDesc::Image {
                path,
                filter,
                lookup,
                wrap,
                scale,
                srgb,
                max_anisotropy,
                ..
            } => {
                changed |= self.image_path_ui(ui, path, preset);
                changed |= enum_combo(ui, "Filter", filter);
                changed |= anisotropy(ui, *filter, max_anisotropy);
                changed |= enum_combo(ui, "Lookup", lookup);
                changed |= enum_combo(ui, "Wrap", wrap);
                changed |= number_tip(
                    ui,
                    "brightness multiplier",
                    "Multiplies every texel value: 1 shows the file as it is, 2 twice as \
                     bright, 0.5 half (the preset's `scale`)",
                    scale,
                    0.0..=1e4,
                    0.01,
                );
                changed |= ui
                    .checkbox(srgb, "sRGB file")
                    .on_hover_text(
                        "8- and 16-bit files hold sRGB-encoded values (almost always true)",
                    )
                    .changed();
            }
            TextureDesc::Checker {
                squares,
                colors,
                filter,
                ..
            } => {
                changed |= enum_combo(ui, "Filter", filter);
                changed |= number(ui, "squares along u", &mut squares.0, 0.01..=1e6, 0.1);
                changed |= number(ui, "squares along v", &mut squares.1, 0.01..=1e6, 0.1);
                changed |= colour(ui, "colour 1", &mut colors.0);
                changed |= colour(ui, "colour 2", &mut colors.1);
            }
            TextureDesc::MeshMaterial {
                filter,
                lookup,
                wrap,
                max_anisotropy,
                ..
            } => {
                changed |= enum_combo(ui, "Filter", filter);
                changed |= anisotropy(ui, *filter, max_anisotropy);
                changed |= enum_combo(ui, "Lookup", lookup);
                changed |= enum_combo(ui, "Wrap", wrap);
            }
            TextureDesc::UvGrid {
                filter,
                wrap,
                max_anisotropy,
                ..
            } => {
                changed |= enum_combo(ui, "Filter", filter);
                changed |= anisotropy(ui, *filter, max_anisotropy);
                changed |= enum_combo(ui, "Wrap", wrap);
            }
            TextureDesc::Formula {
                grey,
                r,
                g,
                b,
                mapping,
                ..
            } => {
                changed |= colour_formulas_ui(ui, "colour", self.key.number(), grey, [r, g, b]);
                // A formula mapping's editor above already counts the texture's NaNs.
                if !matches!(mapping, MappingDesc::Formula { .. }) {
                    self.non_finite_ui(ui);
                }
            }
        }
        changed
    }

    /// `tex` as a texture of `kind` ([`TextureDesc::converted`]), except that an image comes
    /// back as the object had it before it was switched away (its file, filter, wrap...), and
    /// a first image starts on the first file in assets/.
    fn switched(&mut self, tex: &TextureDesc, kind: TextureKind, preset: &Path) -> TextureDesc {
        let dir = preset.parent().unwrap_or(Path::new("."));
        if let TextureDesc::Image { path, .. } = tex {
            let mut kept = tex.clone();
            if let TextureDesc::Image { path: p, .. } = &mut kept {
                let abs = dir.join(path);
                *p = std::path::absolute(&abs)
                    .unwrap_or(abs)
                    .to_string_lossy()
                    .into_owned();
            }
            self.last_image.insert(self.key, kept);
        }
        let mut new = tex.converted(kind);
        if kind != TextureKind::Image {
            return new;
        }
        if let Some(mut earlier) = self.last_image.get(&self.key).cloned() {
            if let Some(m) = new.mapping() {
                earlier.set_mapping(m.clone());
            }
            if let TextureDesc::Image { path, .. } = &mut earlier {
                *path = relative_asset_path(Path::new(path.as_str()), dir);
            }
            return earlier;
        }
        // The preset's assets, else the working directory's (a preset saved elsewhere).
        let first = self
            .assets(preset)
            .first()
            .cloned()
            .or_else(|| list_images(&[PathBuf::from("assets")]).into_iter().next());
        if let TextureDesc::Image { path, .. } = &mut new
            && let Some(first) = first
        {
            *path = relative_asset_path(&first, dir);
        }
        new
    }

    /// The images in the preset's assets folders, listed once per preset.
    pub(super) fn assets(&mut self, preset: &Path) -> &[PathBuf] {
        if self.assets.as_ref().is_some_and(|(p, _)| p != preset) {
            self.assets = None;
        }
        &self
            .assets
            .get_or_insert_with(|| (preset.to_path_buf(), list_images(&asset_dirs(preset))))
            .1
    }

    fn image_path_ui(&mut self, ui: &mut egui::Ui, path: &mut String, preset: &Path) -> bool {
        let mut changed = false;
        let key = self.key;
        let dir = preset.parent().unwrap_or(Path::new(".")).to_path_buf();
        let assets = self.assets(preset).to_vec();
        let browser = self.browser.clone();
        let text = PathText::synced(&mut self.path_text, key, path, preset);
        ui.horizontal(|ui| {
            let l = ui.label("image");
            let r = ui
                .add(
                    egui::TextEdit::singleline(text)
                        .desired_width((ui.available_width() - 130.0).max(80.0)),
                )
                .labelled_by(l.id)
                .on_hover_text(
                    "Path relative to the preset's folder; Enter loads it. \
                     You can also drop an image on the window.",
                );
            let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if (ui
                .button("Load")
                .on_hover_text("Load the image at this path")
                .clicked()
                || enter)
                && *text != *path
            {
                path.clone_from(text);
                changed = true;
            }
            if let Some(p) = browse_button(ui, &browser, BrowseFor::Image, preset) {
                *path = p;
                changed = true;
            }
        });
        ui.horizontal(|ui| {
            let l = ui.label("from assets/");
            // The file's name when it is one of the list's, else say it is not.
            let current = dir.join(path.as_str());
            let current = std::fs::canonicalize(&current).unwrap_or(current);
            let shown = assets
                .iter()
                .find(|a| std::fs::canonicalize(a).is_ok_and(|a| a == current))
                .and_then(|a| a.file_name())
                .map_or_else(
                    || "(a file elsewhere)".to_owned(),
                    |n| n.to_string_lossy().into_owned(),
                );
            // Short enough that Rescan stays inside the panel (a long name is cut; the list
            // shows it whole).
            let shown = if shown.chars().count() > 18 {
                format!("{}…", shown.chars().take(17).collect::<String>())
            } else {
                shown
            };
            egui::ComboBox::from_id_salt("assets")
                .selected_text(shown)
                .show_ui(ui, |ui| {
                    for a in &assets {
                        let name = a
                            .file_name()
                            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
                        if ui.selectable_label(false, name).clicked() {
                            *path = relative_asset_path(a, &dir);
                            changed = true;
                        }
                    }
                })
                .response
                .labelled_by(l.id)
                .on_hover_text(format!(
                    "The images in {}",
                    asset_dirs(preset)
                        .iter()
                        .map(|d| d.display().to_string())
                        .collect::<Vec<_>>()
                        .join(" and ")
                ));
            if ui
                .button("Rescan")
                .on_hover_text("Read the assets folder again")
                .clicked()
            {
                self.assets = None;
            }
        });
        if changed {
            self.path_text = None;
        }
        changed
    }
}

/// The largest footprint elongation the EWA filter follows before it blurs; shown only for
/// EWA, the one filter that reads it.
fn anisotropy(ui: &mut egui::Ui, filter: Filter, value: &mut f32) -> bool {
    if filter != Filter::Ewa {
        return false;
    }
    ui.horizontal(|ui| {
        let l = ui.label("max anisotropy");
        ui.add(
            egui::DragValue::new(value)
                .range(1.0..=MAX_ANISOTROPY_LIMIT)
                .speed(0.1),
        )
        .labelled_by(l.id)
        .on_hover_text(
            "How elongated a pixel's footprint may be (longest over shortest axis) before the \
             EWA filter blurs it instead",
        )
        .changed()
    })
    .inner
}

/// The mapping menu: the built-in mappings and `formula`, whose two fields follow (see
/// [`formula_group`]: the typing is the fields' own, and goes into the scene only when valid;
/// the scene itself is rebuilt off the UI thread through the document, like every edit).
/// `owner` is the object's number. Returns whether it changed.
pub(super) fn mapping_ui(
    ui: &mut egui::Ui,
    label: &str,
    desc: &mut MappingDesc,
    owner: usize,
) -> bool {
    let mut changed = false;
    let selected = desc.builtin().map_or("formula", |m| m.name());
    ui.horizontal(|ui| {
        let l = ui.label(label);
        egui::ComboBox::from_id_salt(label)
            .selected_text(selected)
            .show_ui(ui, |ui| {
                for &m in <Mapping as strum::VariantArray>::VARIANTS {
                    if ui
                        .selectable_label(desc.builtin() == Some(m), m.name())
                        .on_hover_text(m.description())
                        .clicked()
                    {
                        *desc = MappingDesc::Builtin(m);
                        changed = true;
                    }
                }
                if ui
                    .selectable_label(desc.builtin().is_none(), "formula")
                    .on_hover_text(
                        "Your own u and v, written over x, y, z (the local hit point), mesh_u, \
                         mesh_v, pi and tau",
                    )
                    .clicked()
                    && let Some(m) = desc.builtin()
                {
                    // Start from the chosen mapping's formulas where the lecture writes them.
                    let (u, v) = lecture_formula(m)
                        .or_else(|| lecture_formula(Mapping::Spherical))
                        .unwrap_or(("x", "y"));
                    *desc = MappingDesc::Formula {
                        u: u.into(),
                        v: v.into(),
                    };
                    changed = true;
                }
            })
            .response
            .labelled_by(l.id);
    });
    if let MappingDesc::Formula { u, v } = desc {
        let id = ui.make_persistent_id(("mapping-formulas", label, owner));
        changed |= formula_group(
            ui,
            id,
            &["u =", "v ="],
            &mut [&mut *u, &mut *v],
            check_mapping,
            |_, _| {},
        );
        // The derivatives of the formulas the scene holds (the last valid ones), decided on
        // the UI thread without building them (`checked`).
        if let Ok(f) = FormulaMapping::checked(u, v) {
            ui.label(egui::RichText::new(f.derivative_note()).weak());
        }
    }
    changed
}

/// The colour formulas of a formula texture: grey, or r, g and b (`owner` is the object's
/// number; `place` tells this texture's fields from another's of the same object).
pub(super) fn colour_formulas_ui(
    ui: &mut egui::Ui,
    place: &str,
    owner: usize,
    grey: &mut String,
    rgb: [&mut String; 3],
) -> bool {
    let [r, g, b] = rgb;
    let id = ui.make_persistent_id(("colour-formulas", place, owner));
    formula_group(
        ui,
        id,
        &["grey =", "r =", "g =", "b ="],
        &mut [grey, r, g, b],
        check_colour,
        |ui, i| {
            if i == 0 {
                ui.label(
                    egui::RichText::new("or, with grey empty, one formula per channel:").weak(),
                );
            }
        },
    )
}
