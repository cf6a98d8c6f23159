//! The check that every number of a preset is finite, naming the field.

use super::super::camera::ProjectionDesc;
use super::super::light::LightDesc;
use super::super::material::{ColorDesc, ParamRef, ScalarDesc};
use super::super::object::ObjectDesc;
use super::super::texture::TextureDesc;
use super::SceneDesc;

/// Refuses a preset holding a NaN or an infinity anywhere (every `f32`, point and colour),
/// naming the field: `ambient.color: NaN is not a number`,
/// `objects[2].material.cd.scale: inf is not finite`. Ranges are checked by [`build_scene`](super::build_scene);
/// this check needs no files, so it also guards every preset written out (a saved preset or
/// the one a PNG carries never holds a value that does not read back).
///
/// # Errors
/// The first field that is not a finite number.
pub fn check_numbers(desc: &SceneDesc) -> std::result::Result<(), String> {
    let mut n = Numbers(None);
    let c = &desc.camera;
    n.check(|| "camera.eye".into(), &c.eye.to_array());
    n.check(|| "camera.look_at".into(), &c.look_at.to_array());
    n.check(|| "camera.up".into(), &c.up.to_array());
    match c.projection {
        ProjectionDesc::Pinhole { fov } | ProjectionDesc::Fisheye { fov } => {
            n.check(|| "camera.projection.fov".into(), &[fov]);
        }
        ProjectionDesc::Spherical { h_fov, v_fov } => {
            n.check(|| "camera.projection.h_fov".into(), &[h_fov]);
            n.check(|| "camera.projection.v_fov".into(), &[v_fov]);
        }
        ProjectionDesc::Orthographic { height } => {
            n.check(|| "camera.height".into(), &[height]);
        }
    }
    let r = &desc.render;
    n.check(|| "render.exposure".into(), &[r.exposure]);
    n.check(|| "render.background".into(), &r.background.to_array());
    if let Some(a) = r.adaptive {
        n.check(|| "render.adaptive.threshold".into(), &[a.threshold]);
    }
    n.check(|| "ambient.ls".into(), &[desc.ambient.ls]);
    n.check(|| "ambient.color".into(), &desc.ambient.color.to_array());
    for (i, l) in desc.lights.iter().enumerate() {
        let (point, point_name, ls, color) = match *l {
            LightDesc::Directional {
                direction,
                ls,
                color,
                ..
            } => (direction, "direction", ls, color),
            LightDesc::Point {
                position,
                ls,
                color,
                ..
            } => (position, "position", ls, color),
        };
        n.check(|| format!("lights[{i}].{point_name}"), &point.to_array());
        n.check(|| format!("lights[{i}].ls"), &[ls]);
        n.check(|| format!("lights[{i}].color"), &color.to_array());
    }
    for (i, o) in desc.objects.iter().enumerate() {
        n.object(&format!("objects[{i}]"), o);
    }
    n.0.map_or(Ok(()), Err)
}

/// The first non-finite number [`check_numbers`] met, as its message.
struct Numbers(Option<String>);

impl Numbers {
    /// Notes the first of `values` that is not finite, unless one was noted before; `what`
    /// names the field.
    fn check(&mut self, what: impl FnOnce() -> String, values: &[f32]) {
        if self.0.is_none()
            && let Some(v) = values.iter().find(|v| !v.is_finite())
        {
            self.0 = Some(format!("{}: {}", what(), not_finite(*v)));
        }
    }

    /// Every number of one object: its transform, material and texture.
    fn object(&mut self, at: &str, o: &ObjectDesc) {
        let t = &o.transform;
        self.check(
            || format!("{at}.transform.translate"),
            &t.translate.to_array(),
        );
        self.check(|| format!("{at}.transform.rotate"), &t.rotate.to_array());
        self.check(|| format!("{at}.transform.scale"), &t.scale.to_array());
        for (name, p) in o.material.params() {
            match p {
                ParamRef::Scalar(ScalarDesc::Value(v)) => {
                    self.check(|| format!("{at}.material.{name}"), &[*v]);
                }
                ParamRef::Color(ColorDesc::Value(c)) => {
                    self.check(|| format!("{at}.material.{name}"), &c.to_array());
                }
                _ => {}
            }
        }
        if let Some(ScalarDesc::Value(v)) = &o.alpha {
            self.check(|| format!("{at}.alpha"), &[*v]);
        }
        if let Some(b) = &o.bump {
            self.check(|| format!("{at}.bump.scale"), &[b.scale]);
        }
        if let Some(n) = &o.normal {
            self.check(|| format!("{at}.normal.strength"), &[n.strength]);
        }
        if let Some(d) = &o.displace {
            self.check(|| format!("{at}.displace.scale"), &[d.scale]);
        }
        for (path, t) in o.textures() {
            self.texture(&format!("{at}.{path}"), t);
        }
    }

    /// Every number of one texture; `tex` names it.
    fn texture(&mut self, tex: &str, t: &TextureDesc) {
        if let Some(uv) = t.uv_transform() {
            self.check(|| format!("{tex}.uv.scale"), &uv.scale.to_array());
            self.check(|| format!("{tex}.uv.rotate"), &[uv.rotate]);
            self.check(|| format!("{tex}.uv.offset"), &uv.offset.to_array());
        }
        match t {
            TextureDesc::Constant(c) => self.check(|| tex.to_owned(), &c.to_array()),
            TextureDesc::Image {
                scale,
                max_anisotropy,
                ..
            } => {
                self.check(|| format!("{tex}.scale"), &[*scale]);
                self.check(|| format!("{tex}.max_anisotropy"), &[*max_anisotropy]);
            }
            TextureDesc::Checker {
                squares, colors, ..
            } => {
                self.check(|| format!("{tex}.squares"), &[squares.0, squares.1]);
                self.check(
                    || format!("{tex}.colors"),
                    &[colors.0.to_array(), colors.1.to_array()].concat(),
                );
            }
            TextureDesc::MeshMaterial { max_anisotropy, .. }
            | TextureDesc::UvGrid { max_anisotropy, .. } => {
                self.check(|| format!("{tex}.max_anisotropy"), &[*max_anisotropy]);
            }
            // Formulas are text, checked when they are compiled (`build_scene`).
            TextureDesc::Formula { .. } => {}
        }
    }
}

/// Why a non-finite number is refused.
fn not_finite(v: f32) -> String {
    if v.is_nan() {
        "NaN is not a number".into()
    } else {
        format!("{v} is not finite")
    }
}
