//! The scene panel: the objects and, for the selected one, shape, transform, material, texture,
//! mapping, filter and wrap; globally the sampler, samples, camera, lights, exposure and the
//! resolution scale. Returns whether anything changed, so the app re-renders.

use super::widgets::{
    choice_combo, colour, enum_combo, filter_tip, lookup_tip, number, vec3, wrap_tip,
};
use crate::geometry::Shading;
use crate::mapping::Mapping;
use crate::math::{Rgb, Vec3};
use crate::sampler::PixelSampler;
use crate::scene::{
    LightDesc, MaterialDesc, ObjectDesc, ProjectionDesc, SceneDesc, ShapeDesc, TextureDesc,
    relative_asset_path,
};
use crate::texture::{DEFAULT_MAX_ANISOTROPY, Filter, Lookup, Wrap};
use std::path::{Path, PathBuf};

/// Image files the texture list offers.
const IMAGE_EXTENSIONS: [&str; 9] = [
    "png", "jpg", "jpeg", "hdr", "exr", "tif", "tiff", "ppm", "pgm",
];

/// The panel's own state.
#[derive(Default)]
pub struct ScenePanel {
    /// Index of the selected object.
    pub selected: usize,
    /// The image path being typed, applied with Enter or "Load".
    path_text: Option<(usize, String)>,
    /// The mesh path being typed.
    mesh_text: Option<(usize, String)>,
    assets: Option<Vec<PathBuf>>,
}

const SHAPES: [(&str, &str); 6] = [
    (
        "Sphere",
        "The unit sphere at the origin (place it with the transform).",
    ),
    (
        "Cylinder",
        "The open cylinder of radius 1 around y, from y = -1 to 1.",
    ),
    ("Plane", "The infinite plane y = 0."),
    (
        "Rectangle",
        "The generic rectangle (x, z) in [-1, 1]^2 in the plane y = 0.",
    ),
    ("Disk", "The unit disk in the plane y = 0."),
    (
        "Mesh",
        "A triangle mesh from a PLY or OBJ file: type its path or drop the file on the window.",
    ),
];

const MATERIALS: [(&str, &str); 3] = [
    (
        "Matte",
        "The lecture's SV_Matte: ambient plus Lambertian diffuse with a textured colour.",
    ),
    ("Phong", "Matte with a Phong highlight."),
    (
        "Emissive",
        "The lecture's SV_Emissive: glows with its texture and ignores the lights.",
    ),
];

const TEXTURES: [(&str, &str); 5] = [
    ("Constant", "One colour everywhere."),
    ("Image", "An image file read through a mapping."),
    ("Checker", "A procedural checkerboard in (u, v)."),
    (
        "UV grid",
        "The labelled UV test grid: cells A1 (u = v = 0) to H8.",
    ),
    (
        "Mesh material",
        "The image or colour the mesh file's material names (OBJ .mtl); meshes only.",
    ),
];

const PROJECTIONS: [(&str, &str); 3] = [
    ("Pinhole", "Perspective with a vertical field of view."),
    (
        "Fisheye",
        "Equidistant fisheye: the angle from the axis grows linearly to the rim.",
    ),
    (
        "Spherical",
        "Equirectangular panorama: longitude across, latitude up.",
    ),
];

fn shape_name(s: &ShapeDesc) -> &'static str {
    match s {
        ShapeDesc::Sphere => "Sphere",
        ShapeDesc::Cylinder { .. } => "Cylinder",
        ShapeDesc::Plane => "Plane",
        ShapeDesc::Rectangle => "Rectangle",
        ShapeDesc::Disk => "Disk",
        ShapeDesc::Mesh { .. } => "Mesh",
    }
}

fn object_label(i: usize, o: &ObjectDesc) -> String {
    if o.name.is_empty() {
        format!("{i}: {}", shape_name(&o.shape))
    } else {
        format!("{i}: {}", o.name)
    }
}

/// The folders the image list is read from: `assets/` beside the preset's folder and in the
/// working directory.
fn asset_dirs(preset: &Path) -> Vec<PathBuf> {
    let mut v = Vec::new();
    if let Some(dir) = preset.parent() {
        v.push(dir.join("../assets"));
        v.push(dir.join("assets"));
    }
    v.push(PathBuf::from("assets"));
    v
}

fn list_images(preset: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = Vec::new();
    for dir in asset_dirs(preset) {
        let Ok(rd) = std::fs::read_dir(&dir) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
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
    /// Puts the image at `path` (relative to the preset) on the selected object, keeping its
    /// mapping.
    pub fn use_image(&mut self, desc: &mut SceneDesc, path: String) {
        let Some(obj) = desc.objects.get_mut(self.selected) else {
            return;
        };
        let tex = obj.material.texture_mut();
        match tex {
            TextureDesc::Image { path: p, .. } => *p = path,
            other => {
                let mapping = other.mapping().unwrap_or_default();
                *other = image_texture(path, mapping);
            }
        }
        self.path_text = None;
    }

    /// Makes the selected object the mesh at `path` (relative to the preset).
    pub fn use_mesh(&mut self, desc: &mut SceneDesc, path: String) {
        if let Some(obj) = desc.objects.get_mut(self.selected) {
            obj.shape = ShapeDesc::Mesh {
                path,
                shading: Shading::default(),
            };
            self.mesh_text = None;
        }
    }

    /// The panel. Returns whether the scene changed.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        desc: &mut SceneDesc,
        resolution_scale: &mut f32,
        preset: &Path,
    ) -> bool {
        let mut changed = false;
        ui.heading("Objects");
        let mut remove = None;
        for (i, o) in desc.objects.iter().enumerate() {
            if ui
                .selectable_label(self.selected == i, object_label(i, o))
                .clicked()
            {
                self.selected = i;
                self.path_text = None;
                self.mesh_text = None;
            }
        }
        ui.horizontal(|ui| {
            if ui
                .button("Duplicate")
                .on_hover_text("Adds a copy of the selected object, moved up by 2")
                .clicked()
                && let Some(o) = desc.objects.get(self.selected).cloned()
            {
                let mut o = o;
                o.transform.translate.y += 2.0;
                o.name = String::new();
                desc.objects.push(o);
                self.selected = desc.objects.len() - 1;
                changed = true;
            }
            if desc.objects.len() > 1
                && ui
                    .button("Remove")
                    .on_hover_text("Removes the selected object")
                    .clicked()
            {
                remove = Some(self.selected);
            }
        });
        if let Some(i) = remove {
            desc.objects.remove(i);
            self.selected = self.selected.min(desc.objects.len().saturating_sub(1));
            changed = true;
        }
        if let Some(obj) = desc.objects.get_mut(self.selected) {
            ui.separator();
            changed |= self.object_ui(ui, obj, preset);
        }
        ui.separator();
        changed |= render_ui(ui, desc, resolution_scale);
        ui.separator();
        changed |= camera_ui(ui, desc);
        ui.separator();
        changed |= lights_ui(ui, desc);
        changed
    }

    fn object_ui(&mut self, ui: &mut egui::Ui, obj: &mut ObjectDesc, preset: &Path) -> bool {
        let mut changed = false;
        egui::CollapsingHeader::new("Shape and transform")
            .default_open(true)
            .show(ui, |ui| {
                let current = shape_name(&obj.shape);
                if let Some(i) = choice_combo(ui, "Shape", current, &SHAPES) {
                    obj.shape = match i {
                        0 => ShapeDesc::Sphere,
                        1 => ShapeDesc::Cylinder { capped: false },
                        2 => ShapeDesc::Plane,
                        3 => ShapeDesc::Rectangle,
                        4 => ShapeDesc::Disk,
                        _ => ShapeDesc::Mesh {
                            path: String::new(),
                            shading: Shading::default(),
                        },
                    };
                    // An empty mesh path builds nothing: wait for a path before re-rendering.
                    changed =
                        !matches!(&obj.shape, ShapeDesc::Mesh { path, .. } if path.is_empty());
                }
                match &mut obj.shape {
                    ShapeDesc::Cylinder { capped } => {
                        changed |= ui
                            .checkbox(capped, "capped")
                            .on_hover_text("Close the cylinder's ends with disks")
                            .changed();
                    }
                    ShapeDesc::Mesh { path, shading } => {
                        changed |= path_field(ui, "mesh file", path, &mut self.mesh_text);
                        changed |=
                            enum_combo(ui, "Shading", shading, |s: Shading| match s.name() {
                                "flat" => "One normal per triangle: facets show.",
                                _ => "Vertex normals interpolated across each triangle: smooth.",
                            });
                    }
                    _ => {}
                }
                let t = &mut obj.transform;
                changed |= vec3(ui, "translate", &mut t.translate, 0.02);
                changed |= vec3(ui, "rotate", &mut t.rotate, 0.5);
                let mut scale = t.scale;
                if vec3(ui, "scale", &mut scale, 0.01) {
                    // Zero scale is refused by the builder; keep it invertible while dragging.
                    t.scale = scale.map(|s| {
                        if s.abs() < 1e-3 {
                            1e-3_f32.copysign(s)
                        } else {
                            s
                        }
                    });
                    changed = true;
                }
            });
        egui::CollapsingHeader::new("Material")
            .default_open(true)
            .show(ui, |ui| changed |= material_ui(ui, &mut obj.material));
        egui::CollapsingHeader::new("Texture")
            .default_open(true)
            .show(ui, |ui| {
                changed |= self.texture_ui(ui, obj.material.texture_mut(), preset)
            });
        changed
    }

    fn texture_ui(&mut self, ui: &mut egui::Ui, tex: &mut TextureDesc, preset: &Path) -> bool {
        let mut changed = false;
        let kind = match tex {
            TextureDesc::Constant(_) => 0,
            TextureDesc::Image { .. } => 1,
            TextureDesc::Checker { .. } => 2,
            TextureDesc::UvGrid { .. } => 3,
            TextureDesc::MeshMaterial { .. } => 4,
        };
        if let Some(i) = choice_combo(ui, "Texture", TEXTURES[kind].0, &TEXTURES) {
            let mapping = tex.mapping().unwrap_or_default();
            *tex = match i {
                0 => TextureDesc::Constant(Rgb::grey(0.7)),
                1 => {
                    let first = self.assets(preset).first().cloned();
                    let dir = preset.parent().unwrap_or(Path::new("."));
                    let path = first.map_or_else(String::new, |p| relative_asset_path(&p, dir));
                    image_texture(path, mapping)
                }
                2 => TextureDesc::Checker {
                    mapping,
                    squares: (8.0, 8.0),
                    colors: (Rgb::grey(0.8), Rgb::grey(0.05)),
                    filter: Filter::default(),
                },
                3 => TextureDesc::UvGrid {
                    mapping,
                    filter: Filter::default(),
                    wrap: Wrap::default(),
                    max_anisotropy: DEFAULT_MAX_ANISOTROPY,
                },
                _ => TextureDesc::MeshMaterial {
                    mapping: Mapping::Uv,
                    filter: Filter::default(),
                    lookup: Lookup::default(),
                    wrap: Wrap::default(),
                    max_anisotropy: DEFAULT_MAX_ANISOTROPY,
                },
            };
            self.path_text = None;
            changed = true;
        }
        if let Some(current) = tex.mapping() {
            let mut m = current;
            if enum_combo(ui, "Mapping", &mut m, Mapping::description) {
                tex.set_mapping(m);
                changed = true;
            }
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
                ..
            } => {
                changed |= self.image_path_ui(ui, path, preset);
                changed |= enum_combo(ui, "Filter", filter, |f: Filter| filter_tip(f.name()));
                changed |= enum_combo(ui, "Lookup", lookup, |l: Lookup| lookup_tip(l.name()));
                changed |= enum_combo(ui, "Wrap", wrap, |w: Wrap| wrap_tip(w.name()));
                changed |= number(ui, "scale", scale, 0.0..=1e4, 0.01);
                changed |= ui
                    .checkbox(srgb, "sRGB file")
                    .on_hover_text(
                        "8- and 16-bit files hold sRGB-encoded values (almost always true)",
                    )
                    .changed();
            }
            TextureDesc::Checker {
                squares, colors, ..
            } => {
                changed |= number(ui, "squares along u", &mut squares.0, 0.01..=1e6, 0.1);
                changed |= number(ui, "squares along v", &mut squares.1, 0.01..=1e6, 0.1);
                changed |= colour(ui, "colour 1", &mut colors.0);
                changed |= colour(ui, "colour 2", &mut colors.1);
            }
            TextureDesc::MeshMaterial {
                filter,
                lookup,
                wrap,
                ..
            } => {
                changed |= enum_combo(ui, "Filter", filter, |f: Filter| filter_tip(f.name()));
                changed |= enum_combo(ui, "Lookup", lookup, |l: Lookup| lookup_tip(l.name()));
                changed |= enum_combo(ui, "Wrap", wrap, |w: Wrap| wrap_tip(w.name()));
            }
            TextureDesc::UvGrid { filter, wrap, .. } => {
                changed |= enum_combo(ui, "Filter", filter, |f: Filter| filter_tip(f.name()));
                changed |= enum_combo(ui, "Wrap", wrap, |w: Wrap| wrap_tip(w.name()));
            }
        }
        changed
    }

    fn assets(&mut self, preset: &Path) -> &[PathBuf] {
        self.assets.get_or_insert_with(|| list_images(preset))
    }

    fn image_path_ui(&mut self, ui: &mut egui::Ui, path: &mut String, preset: &Path) -> bool {
        let mut changed = false;
        let key = self.selected;
        let dir = preset.parent().unwrap_or(Path::new(".")).to_path_buf();
        let assets = self.assets(preset).to_vec();
        if self.path_text.as_ref().is_none_or(|(k, _)| *k != key) {
            self.path_text = Some((key, path.clone()));
        }
        let Some((_, text)) = &mut self.path_text else {
            return false;
        };
        ui.horizontal(|ui| {
            let l = ui.label("image");
            let r = ui
                .add(egui::TextEdit::singleline(text).desired_width(150.0))
                .labelled_by(l.id)
                .on_hover_text("Path relative to the preset's folder; Enter loads it. You can also drop an image on the window.");
            let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if (ui.button("Load").on_hover_text("Load the image at this path").clicked() || enter)
                && *text != *path
            {
                path.clone_from(text);
                changed = true;
            }
        });
        ui.horizontal(|ui| {
            let l = ui.label("from assets/");
            let shown = Path::new(path.as_str())
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
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
                .on_hover_text("The images in assets/");
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

/// A labelled path field applied with Enter or "Load"; `text` holds the typing (keyed by
/// nothing more than being present: cleared when the path is applied).
fn path_field(
    ui: &mut egui::Ui,
    label: &str,
    path: &mut String,
    text: &mut Option<(usize, String)>,
) -> bool {
    let buf = &mut text.get_or_insert_with(|| (0, path.clone())).1;
    let mut changed = false;
    ui.horizontal(|ui| {
        let l = ui.label(label);
        let r = ui
            .add(egui::TextEdit::singleline(buf).desired_width(150.0))
            .labelled_by(l.id)
            .on_hover_text("Path relative to the preset's folder; Enter loads it");
        let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        if (ui
            .button("Load")
            .on_hover_text("Load the file at this path")
            .clicked()
            || enter)
            && *buf != *path
        {
            path.clone_from(buf);
            changed = true;
        }
    });
    if changed {
        *text = None;
    }
    changed
}

fn image_texture(path: String, mapping: Mapping) -> TextureDesc {
    TextureDesc::Image {
        path,
        mapping,
        filter: Filter::default(),
        lookup: Lookup::default(),
        wrap: Wrap::default(),
        scale: 1.0,
        srgb: true,
        max_anisotropy: DEFAULT_MAX_ANISOTROPY,
    }
}

fn material_ui(ui: &mut egui::Ui, m: &mut MaterialDesc) -> bool {
    let mut changed = false;
    let kind = match m {
        MaterialDesc::Matte { .. } => 0,
        MaterialDesc::Phong { .. } => 1,
        MaterialDesc::Emissive { .. } => 2,
    };
    if let Some(i) = choice_combo(ui, "Material", MATERIALS[kind].0, &MATERIALS) {
        let tex = m.texture().clone();
        let (ka, kd) = match m {
            MaterialDesc::Matte { ka, kd, .. } | MaterialDesc::Phong { ka, kd, .. } => (*ka, *kd),
            MaterialDesc::Emissive { .. } => (0.25, 0.75),
        };
        *m = match i {
            0 => MaterialDesc::Matte { ka, kd, cd: tex },
            1 => MaterialDesc::Phong {
                ka,
                kd,
                cd: tex,
                ks: 0.25,
                cs: Rgb::WHITE,
                exp: 20.0,
            },
            _ => MaterialDesc::Emissive { ls: 1.0, ce: tex },
        };
        changed = true;
    }
    match m {
        MaterialDesc::Matte { ka, kd, .. } => {
            changed |= number(ui, "ka (ambient)", ka, 0.0..=10.0, 0.01);
            changed |= number(ui, "kd (diffuse)", kd, 0.0..=10.0, 0.01);
        }
        MaterialDesc::Phong {
            ka,
            kd,
            ks,
            cs,
            exp,
            ..
        } => {
            changed |= number(ui, "ka (ambient)", ka, 0.0..=10.0, 0.01);
            changed |= number(ui, "kd (diffuse)", kd, 0.0..=10.0, 0.01);
            changed |= number(ui, "ks (specular)", ks, 0.0..=10.0, 0.01);
            changed |= number(ui, "exponent", exp, 0.0..=10_000.0, 0.5);
            changed |= colour(ui, "specular colour", cs);
        }
        MaterialDesc::Emissive { ls, .. } => {
            changed |= number(ui, "ls (radiance)", ls, 0.0..=1e4, 0.01);
        }
    }
    changed
}

fn render_ui(ui: &mut egui::Ui, desc: &mut SceneDesc, resolution_scale: &mut f32) -> bool {
    let mut changed = false;
    ui.heading("Render");
    let r = &mut desc.render;
    changed |= enum_combo(ui, "Sampler", &mut r.sampler, PixelSampler::description);
    ui.horizontal(|ui| {
        let l = ui.label("spp");
        changed |= ui
            .add(egui::Slider::new(&mut r.spp, 1..=1024).logarithmic(true))
            .labelled_by(l.id)
            .on_hover_text("Samples per pixel: the render refines pass by pass up to this")
            .changed();
    });
    ui.horizontal(|ui| {
        let l = ui.label("exposure");
        changed |= ui
            .add(egui::Slider::new(&mut r.exposure, -8.0..=8.0).suffix(" stops"))
            .labelled_by(l.id)
            .on_hover_text("Multiplies the radiance by 2^exposure before display")
            .changed();
    });
    ui.horizontal(|ui| {
        let l = ui.label("resolution");
        changed |= ui
            .add(
                egui::Slider::new(resolution_scale, 0.125..=2.0)
                    .logarithmic(true)
                    .suffix(" x"),
            )
            .labelled_by(l.id)
            .on_hover_text(
                "Renders at this fraction of the preset's resolution (a view setting, not saved)",
            )
            .changed();
    });
    ui.horizontal(|ui| {
        let l = ui.label("seed");
        changed |= ui
            .add(egui::DragValue::new(&mut r.seed))
            .labelled_by(l.id)
            .on_hover_text("Seed of every random number: the same seed renders the same image")
            .changed();
    });
    changed |= colour(ui, "background", &mut r.background);
    changed
}

fn camera_ui(ui: &mut egui::Ui, desc: &mut SceneDesc) -> bool {
    let mut changed = false;
    ui.heading("Camera");
    let c = &mut desc.camera;
    let kind = match c.projection {
        ProjectionDesc::Pinhole { .. } => 0,
        ProjectionDesc::Fisheye { .. } => 1,
        ProjectionDesc::Spherical { .. } => 2,
    };
    if let Some(i) = choice_combo(ui, "Camera", PROJECTIONS[kind].0, &PROJECTIONS) {
        c.projection = match i {
            0 => ProjectionDesc::Pinhole { fov: 45.0 },
            1 => ProjectionDesc::Fisheye { fov: 180.0 },
            _ => ProjectionDesc::Spherical {
                h_fov: 360.0,
                v_fov: 180.0,
            },
        };
        changed = true;
    }
    match &mut c.projection {
        ProjectionDesc::Pinhole { fov } => {
            changed |= number(ui, "field of view (deg)", fov, 1.0..=179.0, 0.2)
        }
        ProjectionDesc::Fisheye { fov } => {
            changed |= number(ui, "field of view (deg)", fov, 1.0..=360.0, 0.5)
        }
        ProjectionDesc::Spherical { h_fov, v_fov } => {
            changed |= number(ui, "horizontal fov (deg)", h_fov, 1.0..=360.0, 0.5);
            changed |= number(ui, "vertical fov (deg)", v_fov, 1.0..=180.0, 0.5);
        }
    }
    let mut eye = c.eye;
    if vec3(ui, "eye", &mut eye, 0.02) && eye != c.look_at {
        c.eye = eye;
        changed = true;
    }
    let mut at = c.look_at;
    if vec3(ui, "look at", &mut at, 0.02) && at != c.eye {
        c.look_at = at;
        changed = true;
    }
    changed
}

fn lights_ui(ui: &mut egui::Ui, desc: &mut SceneDesc) -> bool {
    let mut changed = false;
    ui.heading("Lights");
    changed |= number(ui, "ambient ls", &mut desc.ambient.ls, 0.0..=100.0, 0.01);
    changed |= colour(ui, "ambient colour", &mut desc.ambient.color);
    let mut remove = None;
    for (i, l) in desc.lights.iter_mut().enumerate() {
        ui.push_id(i, |ui| {
            let (name, pos, ls, color, shadows) = match l {
                LightDesc::Directional {
                    direction,
                    ls,
                    color,
                    shadows,
                } => ("directional", direction, ls, color, shadows),
                LightDesc::Point {
                    position,
                    ls,
                    color,
                    shadows,
                } => ("point", position, ls, color, shadows),
            };
            ui.horizontal(|ui| {
                ui.strong(format!("light {i}: {name}"));
                if ui
                    .button("Remove")
                    .on_hover_text("Removes this light")
                    .clicked()
                {
                    remove = Some(i);
                }
            });
            let label = if name == "point" {
                "position"
            } else {
                "direction"
            };
            let mut v = *pos;
            if vec3(ui, label, &mut v, 0.02) && (name == "point" || v != Vec3::ZERO) {
                *pos = v;
                changed = true;
            }
            changed |= number(ui, "ls", ls, 0.0..=1e4, 0.01);
            changed |= colour(ui, "colour", color);
            changed |= ui
                .checkbox(shadows, "shadows")
                .on_hover_text("Objects cast shadows from this light")
                .changed();
        });
    }
    if let Some(i) = remove {
        desc.lights.remove(i);
        changed = true;
    }
    ui.horizontal(|ui| {
        if ui
            .button("Add directional")
            .on_hover_text("A light from one direction, like the sun")
            .clicked()
        {
            desc.lights.push(LightDesc::Directional {
                direction: Vec3::new(1.0, 1.0, 1.0),
                ls: 1.0,
                color: Rgb::WHITE,
                shadows: true,
            });
            changed = true;
        }
        if ui
            .button("Add point")
            .on_hover_text("A light from a point, without fall-off")
            .clicked()
        {
            desc.lights.push(LightDesc::Point {
                position: Vec3::new(0.0, 4.0, 4.0),
                ls: 1.0,
                color: Rgb::WHITE,
                shadows: true,
            });
            changed = true;
        }
    });
    changed
}
