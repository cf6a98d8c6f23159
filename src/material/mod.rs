//! Materials (the lecture's `SV_Matte` and `SV_Emissive`, plus Phong) and lights.
//!
//! Every coefficient and colour may be a texture (the lecture's "any c* or k* value can be a
//! texture"): see [`Scalar`] and [`Colour`], which cost nothing when constant.

mod bump;
mod normal;
mod param;
mod table;
mod terms;

pub use bump::{Bump, MIN_BUMP_STEP, UvLanes, dual_basis, through_transform, uv_gradients};
pub use normal::{NormalMap, decode_normal, encode_normal, tangent_frame};
pub use param::{Colour, ParamValue, Scalar, ScalarTexture};
pub(crate) use table::material_table;
pub use table::{ParamDefault, ParamSpec};
pub use terms::{C3, ParamLanes, Terms, splat_rgb};

use crate::math::lanes::V3;
use crate::math::{Rgb, Vec3A};
use crate::texture::{Texture, TextureContext};

/// How a surface responds to light. Colours that vary over the surface are [`Texture`]s.
///
/// `repr(u8)` gives the enum an explicit tag: with the textured parameters' boxes inside,
/// Rust otherwise hides the variant in a niche of a field, and every `match` on a material
/// (twice per hit) decodes it in several instructions.
#[derive(Clone, Debug)]
#[repr(u8)]
pub enum Material {
    /// `SV_Matte`: ambient + Lambertian diffuse, both with the textured colour `cd`.
    Matte {
        /// Ambient reflection coefficient (not negative): the term is `ka cd L_ambient`.
        ka: Scalar,
        /// Diffuse reflection coefficient (not negative): the BRDF is `kd cd / pi`.
        kd: Scalar,
        /// Linear reflectance, used by both the ambient and the diffuse term.
        cd: Texture,
    },
    /// Matte plus a glossy highlight `ks cs (r . wo)^exp`.
    Phong {
        /// Ambient reflection coefficient, as for [`Material::Matte`].
        ka: Scalar,
        /// Diffuse reflection coefficient, as for [`Material::Matte`].
        kd: Scalar,
        /// Linear reflectance of the ambient and diffuse terms (the highlight uses `cs`).
        cd: Texture,
        /// Strength of the highlight (not negative).
        ks: Scalar,
        /// Linear colour of the highlight.
        cs: Colour,
        /// Sharpness of the highlight: `(r . wo)^exp`, larger is tighter.
        exp: Scalar,
        /// Glow on the dark side, added where direct light does not reach (black: none).
        ce: Colour,
    },
    /// Phong plus a perfect mirror: adds `kr cr` times the radiance along the mirrored ray.
    Reflective {
        /// Ambient reflection coefficient, as for [`Material::Matte`].
        ka: Scalar,
        /// Diffuse reflection coefficient, as for [`Material::Matte`].
        kd: Scalar,
        /// Linear reflectance of the ambient and diffuse terms.
        cd: Texture,
        /// Strength of the highlight (not negative).
        ks: Scalar,
        /// Linear colour of the highlight.
        cs: Colour,
        /// Sharpness of the highlight.
        exp: Scalar,
        /// Share of the mirrored radiance reflected (not negative).
        kr: Scalar,
        /// Linear colour of the mirror.
        cr: Colour,
    },
    /// `SV_Emissive`: radiance `ls ce`, independent of lights (the environment sphere).
    Emissive {
        /// Multiplier on `ce` (not negative).
        ls: Scalar,
        /// Emitted linear radiance before `ls`.
        ce: Texture,
    },
}

impl Material {
    /// The texture that gives the surface its colour.
    #[must_use]
    pub fn texture(&self) -> &Texture {
        match self {
            Self::Matte { cd, .. } | Self::Phong { cd, .. } | Self::Reflective { cd, .. } => cd,
            Self::Emissive { ce, .. } => ce,
        }
    }

    /// Whether any coefficient or colour besides the colour texture is a texture (what
    /// [`Material::params`] lists, without building the list: the render kernel asks per
    /// packet).
    #[must_use]
    pub fn has_textured_params(&self) -> bool {
        !self.textured_params_all(|_| false)
    }

    /// Whether every textured coefficient and colour (besides the colour texture) has a texture
    /// `ok` accepts (true when none is textured).
    #[must_use]
    pub fn textured_params_all(&self, ok: impl Fn(&Texture) -> bool) -> bool {
        let s = |p: &Scalar| match p {
            Scalar::Const(_) => true,
            Scalar::Texture(t) => ok(&t.texture),
        };
        let c = |p: &Colour| match p {
            Colour::Const(_) => true,
            Colour::Texture(t) => ok(t),
        };
        match self {
            Self::Matte { ka, kd, .. } => s(ka) && s(kd),
            Self::Phong {
                ka,
                kd,
                ks,
                cs,
                exp,
                ce,
                ..
            } => s(ka) && s(kd) && s(ks) && c(cs) && s(exp) && c(ce),
            Self::Reflective {
                ka,
                kd,
                ks,
                cs,
                exp,
                kr,
                cr,
                ..
            } => s(ka) && s(kd) && s(ks) && c(cs) && s(exp) && s(kr) && c(cr),
            Self::Emissive { ls, .. } => s(ls),
        }
    }

    /// Whether lights affect this material (emissive surfaces ignore them).
    #[must_use]
    pub const fn is_lit(&self) -> bool {
        !matches!(self, Self::Emissive { .. })
    }

    /// Whether any texture of the material (the colour or a textured parameter) needs the
    /// hit's footprint.
    #[must_use]
    pub fn needs_differentials(&self) -> bool {
        self.texture().needs_differentials()
            || self.params().iter().any(|(_, p)| p.needs_differentials())
    }

    /// The value at a hit of every parameter that is a texture (constants are left out), by
    /// preset name: what the inspector lists.
    #[must_use]
    pub fn textured_values(&self, ctx: &TextureContext) -> Vec<(&'static str, ParamValue)> {
        self.params()
            .into_iter()
            .filter_map(|(name, p)| match p {
                Param::Scalar(s @ Scalar::Texture(_)) => {
                    Some((name, ParamValue::Scalar(s.eval(ctx))))
                }
                Param::Colour(c @ Colour::Texture(_)) => {
                    Some((name, ParamValue::Colour(c.eval(ctx))))
                }
                _ => None,
            })
            .collect()
    }
}

/// A material's coefficient or colour ([`Material::params`]).
#[derive(Clone, Copy, Debug)]
pub enum Param<'a> {
    /// A coefficient.
    Scalar(&'a Scalar),
    /// A colour.
    Colour(&'a Colour),
}

impl<'a> Param<'a> {
    /// Whether evaluating it needs the hit's footprint.
    #[must_use]
    pub fn needs_differentials(self) -> bool {
        match self {
            Self::Scalar(s) => s.needs_differentials(),
            Self::Colour(c) => c.needs_differentials(),
        }
    }

    /// The texture it reads, if it is not a constant.
    #[must_use]
    pub fn texture(self) -> Option<&'a Texture> {
        match self {
            Self::Scalar(s) => s.texture(),
            Self::Colour(c) => c.texture(),
        }
    }
}

/// A light that illuminates from one direction at a hit point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A light at infinity: same direction and radiance everywhere.
    Directional {
        /// Unit vector from surfaces toward the light.
        to_light: Vec3A,
        /// Incident radiance `ls * color`.
        radiance: Rgb,
        /// Whether occluders cast shadows from it.
        shadows: bool,
    },
    /// A point light; the lecture's has no fall-off (radiance `ls * color` at any distance).
    Point {
        /// Position in world space.
        position: Vec3A,
        /// Incident radiance `ls * color`.
        radiance: Rgb,
        /// Whether occluders cast shadows from it.
        shadows: bool,
    },
}

impl Light {
    /// Unit direction toward the light from `p`, the distance to it (infinite for a directional
    /// light), its radiance, and whether it casts shadows.
    #[must_use]
    #[inline]
    pub fn incident(&self, p: Vec3A) -> (Vec3A, f32, Rgb, bool) {
        match *self {
            Self::Directional {
                to_light,
                radiance,
                shadows,
            } => (to_light, f32::INFINITY, radiance, shadows),
            Self::Point {
                position,
                radiance,
                shadows,
            } => {
                let d = position - p;
                let dist = d.length();
                let dir = if dist > 0.0 { d / dist } else { Vec3A::Y };
                (dir, dist, radiance, shadows)
            }
        }
    }
}

/// The part of shading that depends on the material at one hit: the textured colour and the
/// BRDF, evaluated once and then applied per light.
#[derive(Clone, Copy, Debug)]
pub struct ShadePoint {
    /// Ambient term `ka cd * L_ambient` (or the emitted radiance for emissive surfaces).
    pub base: Rgb,
    /// `kd cd / pi`, the Lambertian BRDF.
    pub diffuse: Rgb,
    /// Specular `ks cs` and exponent, if Phong.
    pub specular: Option<(Rgb, f32)>,
    /// The mirror's `kr cr`, what multiplies the radiance along the mirrored ray: `None` unless
    /// the material is reflective and `kr cr` is not black here (a matte or Phong hit then pays
    /// no colour comparison).
    pub mirror: Option<Rgb>,
    /// Phong's glow `ce`, added where direct light does not reach: `None` unless the material is
    /// Phong and its glow is not black here.
    pub glow: Option<Rgb>,
}

/// The summed `n . wi` of the unshadowed lights over which a glow fades out past the
/// terminator.
pub const GLOW_FADE: f32 = 0.2;

impl ShadePoint {
    /// The glow's weight given the summed `n . wi` of the lights that reach the point: 1 in
    /// the dark, fading linearly to 0 at [`GLOW_FADE`].
    #[must_use]
    #[inline]
    pub fn glow_weight(lit: f32) -> f32 {
        (1.0 - lit / GLOW_FADE).clamp(0.0, 1.0)
    }
}

impl Material {
    /// Evaluates the texture once and prepares the terms for [`ShadePoint::direct`]: the
    /// width-1 instance of [`Material::terms`].
    #[must_use]
    #[inline]
    pub fn shade_point(&self, ctx: &TextureContext, ambient: Rgb) -> ShadePoint {
        let s = pulp::Scalar;
        let c = self.texture().eval(ctx);
        let t = self.terms(s, &[c.0, c.1, c.2], ambient, &AtHit(ctx));
        let rgb = |c: [f32; 3]| Rgb(c[0], c[1], c[2]);
        ShadePoint {
            base: rgb(t.base),
            diffuse: rgb(t.diffuse),
            specular: t.specular.map(|(ks, e)| (rgb(ks), e)),
            mirror: t.mirror.and_then(|(m, on)| on.then(|| rgb(m))),
            glow: t.glow.and_then(|(g, on)| on.then(|| rgb(g))),
        }
    }
}

/// A material's parameters evaluated at one hit (the width-1 [`ParamLanes`]).
struct AtHit<'a>(&'a TextureContext);

impl ParamLanes<pulp::Scalar> for AtHit<'_> {
    #[inline(always)]
    fn scalar(&self, p: &Scalar) -> f32 {
        p.eval(self.0)
    }

    #[inline(always)]
    fn colour(&self, p: &Colour) -> [f32; 3] {
        let c = p.eval(self.0);
        [c.0, c.1, c.2]
    }
}

impl ShadePoint {
    /// Radiance reflected toward `wo` from one light arriving along `wi` with radiance `li`,
    /// at a surface with unit normal `n` facing `wo` (the lecture's `f * L * (n . wi)`): the
    /// width-1 instance of [`Terms::add_light`].
    #[must_use]
    #[inline]
    pub fn direct(&self, n: Vec3A, wo: Vec3A, wi: Vec3A, li: Rgb) -> Rgb {
        let ndotwi = n.dot(wi);
        if ndotwi <= 0.0 {
            return Rgb::BLACK;
        }
        let c = |c: Rgb| [c.0, c.1, c.2];
        let t = Terms::<pulp::Scalar> {
            base: c(self.base),
            diffuse: c(self.diffuse),
            specular: self.specular.map(|(ks, e)| (c(ks), e)),
            mirror: None,
            glow: None,
            lit: true,
        };
        let mut l = [0.0; 3];
        let mut lit = 0.0;
        let v = |v: Vec3A| V3::one(v);
        t.add_light(
            pulp::Scalar,
            true,
            &v(n),
            &v(wo),
            &v(wi),
            li,
            ndotwi,
            None,
            &mut l,
            &mut lit,
        );
        Rgb(l[0], l[1], l[2])
    }
}
