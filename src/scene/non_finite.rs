//! Where a student's formulas gave NaN or an infinity: every texture of every object that
//! counts them (a formula mapping or colour formula), by the field the preset names, as
//! [`super::ObjectDesc::textures`] walks them: the colour, each textured coefficient and
//! colour (`ks`, `exp`...), the clip map, the bump or normal map, and the displacement's
//! heights (counted once, when the mesh was displaced at load).

use super::{FieldPath, Perturbation, Scene, SceneDesc};
use crate::geometry::Shape;
use crate::material::Param;

/// What counted NaN or infinity, and how often.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NonFinite {
    /// The field (`objects[0].material.ks`, `objects[0].displace.height`).
    pub field: FieldPath,
    /// How many hits (or, for a displacement, vertices) were NaN or infinite.
    pub count: u64,
    /// What was counted.
    pub counted: Counted,
}

/// What a [`NonFinite`] counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Counted {
    /// Hits of the render where the colour texture was drawn magenta.
    Drawn,
    /// Hits of the render where another texture (a coefficient, a clip, bump or normal map)
    /// gave magenta's value instead.
    Read,
    /// Vertices of a displacement, where the height read magenta's value instead.
    Vertices,
}

impl NonFinite {
    /// The warning a command prints: `objects[0].material.ks (object "Ball"): its formula was
    /// NaN or infinite at 12 hits`.
    #[must_use]
    pub fn warning(&self, desc: &SceneDesc) -> String {
        let n = self.count;
        let what = match self.counted {
            Counted::Drawn => format!("its formula was NaN or infinite at {n} hits, drawn magenta"),
            Counted::Read => format!(
                "its formula was NaN or infinite at {n} hits, read there as magenta's value"
            ),
            Counted::Vertices => format!(
                "its formula was NaN or infinite at {n} vertices, read there as magenta's value"
            ),
        };
        format!("{}: {what}", desc.name_field(&self.field))
    }
}

/// Every texture of `scene` (built from `desc`) that counted NaN or infinity so far.
#[must_use]
pub fn non_finite_fields(scene: &Scene, desc: &SceneDesc) -> Vec<NonFinite> {
    let mut out = Vec::new();
    for (i, (obj, o)) in scene.objects.iter().zip(&desc.objects).enumerate() {
        let at = |f: &str| FieldPath::field("objects").at(i).then(f);
        let material = &scene.materials[obj.material];
        let mut textures = vec![(
            at("material").then(o.material.kind().colour_name()),
            Some(material.texture()),
            Counted::Drawn,
        )];
        for (name, p) in material.params() {
            let t = match p {
                Param::Scalar(s) => s.texture(),
                Param::Colour(c) => c.texture(),
            };
            textures.push((at("material").then(name), t, Counted::Read));
        }
        if let Some(surface) = scene.surfaces.get(i) {
            let clip = surface.clip.as_ref().and_then(|c| c.texture());
            textures.push((at("alpha"), clip, Counted::Read));
            match &surface.perturbation {
                Some(Perturbation::Bump(b)) => {
                    textures.push((at("bump").then("height"), Some(&b.height), Counted::Read));
                }
                Some(Perturbation::Normal(n)) => {
                    textures.push((at("normal").then("map"), Some(&n.map), Counted::Read));
                }
                None => {}
            }
        }
        for (field, t, counted) in textures {
            let count = t.map_or(0, crate::texture::Texture::non_finite_count);
            if count > 0 {
                out.push(NonFinite {
                    field,
                    count,
                    counted,
                });
            }
        }
        if let Shape::Mesh(m) = &obj.shape
            && let Some(d) = m.mesh.displacement()
            && d.non_finite > 0
        {
            out.push(NonFinite {
                field: at("displace").then("height"),
                count: d.non_finite as u64,
                counted: Counted::Vertices,
            });
        }
    }
    out
}
