//! Materials (the lecture's `SV_Matte` and `SV_Emissive`, plus Phong) and lights.

use crate::math::{INV_PI, Rgb, Vec3A};
use crate::texture::{Texture, TextureContext};

/// How a surface responds to light. Colours that vary over the surface are [`Texture`]s.
#[derive(Clone, Debug)]
pub enum Material {
    /// `SV_Matte`: ambient + Lambertian diffuse, both with the textured colour `cd`.
    Matte {
        /// Ambient reflection coefficient (not negative): the term is `ka cd L_ambient`.
        ka: f32,
        /// Diffuse reflection coefficient (not negative): the BRDF is `kd cd / pi`.
        kd: f32,
        /// Linear reflectance, used by both the ambient and the diffuse term.
        cd: Texture,
    },
    /// Matte plus a glossy highlight `ks cs (r . wo)^exp`.
    Phong {
        /// Ambient reflection coefficient, as for [`Material::Matte`].
        ka: f32,
        /// Diffuse reflection coefficient, as for [`Material::Matte`].
        kd: f32,
        /// Linear reflectance of the ambient and diffuse terms (the highlight uses `cs`).
        cd: Texture,
        /// Strength of the highlight (not negative).
        ks: f32,
        /// Linear colour of the highlight.
        cs: Rgb,
        /// Sharpness of the highlight: `(r . wo)^exp`, larger is tighter.
        exp: f32,
    },
    /// `SV_Emissive`: radiance `ls ce`, independent of lights (the environment sphere).
    Emissive {
        /// Multiplier on `ce` (not negative).
        ls: f32,
        /// Emitted linear radiance before `ls`.
        ce: Texture,
    },
}

impl Material {
    /// The texture that gives the surface its colour.
    #[must_use]
    pub fn texture(&self) -> &Texture {
        match self {
            Self::Matte { cd, .. } | Self::Phong { cd, .. } => cd,
            Self::Emissive { ce, .. } => ce,
        }
    }

    /// Whether lights affect this material (emissive surfaces ignore them).
    #[must_use]
    pub const fn is_lit(&self) -> bool {
        !matches!(self, Self::Emissive { .. })
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
}

impl Material {
    /// Evaluates the texture once and prepares the terms for [`ShadePoint::direct`].
    #[must_use]
    #[inline]
    pub fn shade_point(&self, ctx: &TextureContext, ambient: Rgb) -> ShadePoint {
        match self {
            Self::Matte { ka, kd, cd } => {
                let c = cd.eval(ctx);
                ShadePoint {
                    base: c * ambient * *ka,
                    diffuse: c * (*kd * INV_PI),
                    specular: None,
                }
            }
            Self::Phong {
                ka,
                kd,
                cd,
                ks,
                cs,
                exp,
            } => {
                let c = cd.eval(ctx);
                ShadePoint {
                    base: c * ambient * *ka,
                    diffuse: c * (*kd * INV_PI),
                    specular: Some((*cs * *ks, *exp)),
                }
            }
            Self::Emissive { ls, ce } => ShadePoint {
                base: ce.eval(ctx) * *ls,
                diffuse: Rgb::BLACK,
                specular: None,
            },
        }
    }
}

impl ShadePoint {
    /// Radiance reflected toward `wo` from one light arriving along `wi` with radiance `li`,
    /// at a surface with unit normal `n` facing `wo` (the lecture's `f * L * (n . wi)`).
    #[must_use]
    #[inline]
    pub fn direct(&self, n: Vec3A, wo: Vec3A, wi: Vec3A, li: Rgb) -> Rgb {
        let ndotwi = n.dot(wi);
        if ndotwi <= 0.0 {
            return Rgb::BLACK;
        }
        let mut f = self.diffuse;
        if let Some((ks, exp)) = self.specular {
            let r = -wi + 2.0 * ndotwi * n;
            let rdotwo = r.dot(wo);
            if rdotwo > 0.0 {
                f += ks * rdotwo.powf(exp);
            }
        }
        f * li * ndotwi
    }
}
