//! Materials: the description ([`MaterialDesc`]), the kinds with their defaults, the parameter
//! accessors, and the build of the runtime [`Material`].

mod param;
mod table;

pub(super) use param::scalar;
pub use param::{ChannelDesc, ColorDesc, ScalarDesc};

pub(super) use table::material;

use super::texture::TextureDesc;
use crate::math::Rgb;
use serde::{Deserialize, Serialize};

/// How a surface shades, given its textured colour `cd`. Coefficients are finite and not
/// negative. A lit material's radiance is the ambient term `ka cd L_ambient` plus, per light
/// of radiance `L` arriving along `wi`, `(kd cd / pi + ks cs (r . wo)^exp) L (n . wi)`.
///
/// Every coefficient (`ka`, `kd`, `ks`, `exp`, `ls`) is a [`ScalarDesc`] and every colour
/// besides `cd` and `ce` (`cs`) a [`ColorDesc`]: a plain number or colour, as before, or a
/// texture with its own mapping, filter and wrap (`ks: Image(path: "mask.png")`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum MaterialDesc {
    /// The lecture's `SV_Matte`: ambient + diffuse with a textured colour.
    Matte {
        /// Share of the ambient light reflected; default 0.25.
        #[serde(default = "default_ka")]
        ka: ScalarDesc,
        /// Share of direct light reflected diffusely; default 0.75.
        #[serde(default = "default_kd")]
        kd: ScalarDesc,
        /// The surface colour (linear reflectance, usually in [0, 1]); required.
        cd: TextureDesc,
    },
    /// Matte with a Phong highlight.
    Phong {
        /// Share of the ambient light reflected; default 0.25.
        #[serde(default = "default_ka")]
        ka: ScalarDesc,
        /// Share of direct light reflected diffusely; default 0.75.
        #[serde(default = "default_kd")]
        kd: ScalarDesc,
        /// The surface colour (linear reflectance, usually in [0, 1]); required.
        cd: TextureDesc,
        /// Strength of the highlight; default 0.25.
        #[serde(default = "default_ks")]
        ks: ScalarDesc,
        /// Colour of the highlight, linear RGB; default white (the light's own colour).
        #[serde(default = "white_param")]
        cs: ColorDesc,
        /// Phong exponent: larger is a smaller, sharper highlight; default 20.
        #[serde(default = "default_exp")]
        exp: ScalarDesc,
        /// Glow on the dark side (city lights at night): linear radiance added where direct
        /// light does not reach, fading in over the first 0.2 of the lights' summed `n . wi`
        /// past the terminator (and fully where every light is shadowed); default black (none).
        #[serde(default = "black_param", skip_serializing_if = "ColorDesc::is_black")]
        ce: ColorDesc,
    },
    /// The book's `Reflective`: Phong plus a perfect mirror, which adds `kr cr` times the
    /// radiance seen along the mirrored ray (traced up to `render.reflection_depth` bounces).
    Reflective {
        /// Share of the ambient light reflected; default 0.25.
        #[serde(default = "default_ka")]
        ka: ScalarDesc,
        /// Share of direct light reflected diffusely; default 0.75.
        #[serde(default = "default_kd")]
        kd: ScalarDesc,
        /// The surface colour (linear reflectance, usually in [0, 1]); required.
        cd: TextureDesc,
        /// Strength of the highlight; default 0.25.
        #[serde(default = "default_ks")]
        ks: ScalarDesc,
        /// Colour of the highlight, linear RGB; default white (the light's own colour).
        #[serde(default = "white_param")]
        cs: ColorDesc,
        /// Phong exponent: larger is a smaller, sharper highlight; default 20.
        #[serde(default = "default_exp")]
        exp: ScalarDesc,
        /// Share of the mirrored radiance reflected; default 0.75.
        #[serde(default = "default_kr")]
        kr: ScalarDesc,
        /// Colour of the mirror, linear RGB; default white.
        #[serde(default = "white_param")]
        cr: ColorDesc,
    },
    /// The lecture's `SV_Emissive`: glows with a textured colour, ignores lights.
    Emissive {
        /// Multiplier on the emitted colour (finite, not negative); default 1.
        #[serde(default = "one_param")]
        ls: ScalarDesc,
        /// The emitted colour as linear radiance (may exceed 1); required.
        ce: TextureDesc,
    },
}

fn black_param() -> ColorDesc {
    ColorDesc::Value(Rgb::BLACK)
}

fn white_param() -> ColorDesc {
    ColorDesc::Value(Rgb::WHITE)
}

fn one_param() -> ScalarDesc {
    ScalarDesc::Value(1.0)
}

fn default_ka() -> ScalarDesc {
    ScalarDesc::Value(0.25)
}

fn default_kd() -> ScalarDesc {
    ScalarDesc::Value(0.75)
}

fn default_ks() -> ScalarDesc {
    ScalarDesc::Value(0.25)
}

fn default_exp() -> ScalarDesc {
    ScalarDesc::Value(20.0)
}

fn default_kr() -> ScalarDesc {
    ScalarDesc::Value(0.75)
}

impl MaterialDesc {
    /// The texture giving the surface its colour: `cd`, or `ce` for an emissive material.
    #[must_use]
    pub fn texture(&self) -> &TextureDesc {
        match self {
            Self::Matte { cd, .. } | Self::Phong { cd, .. } | Self::Reflective { cd, .. } => cd,
            Self::Emissive { ce, .. } => ce,
        }
    }

    /// The colour texture, mutably.
    pub fn texture_mut(&mut self) -> &mut TextureDesc {
        match self {
            Self::Matte { cd, .. } | Self::Phong { cd, .. } | Self::Reflective { cd, .. } => cd,
            Self::Emissive { ce, .. } => ce,
        }
    }

    /// Every texture the material reads, by parameter name: the colour (`cd` or `ce`) first,
    /// then each textured coefficient and colour.
    #[must_use]
    pub fn textures(&self) -> Vec<(&'static str, &TextureDesc)> {
        let mut v = vec![(self.kind().colour_name(), self.texture())];
        v.extend(
            self.params()
                .into_iter()
                .filter_map(|(name, p)| p.texture().map(|t| (name, t))),
        );
        v
    }
}

/// A material's coefficient or colour, read ([`MaterialDesc::params`]).
#[derive(Clone, Copy, Debug)]
pub enum ParamRef<'a> {
    /// A coefficient.
    Scalar(&'a ScalarDesc),
    /// A colour.
    Color(&'a ColorDesc),
}

impl<'a> From<&'a ScalarDesc> for ParamRef<'a> {
    fn from(s: &'a ScalarDesc) -> Self {
        Self::Scalar(s)
    }
}

impl<'a> From<&'a ColorDesc> for ParamRef<'a> {
    fn from(c: &'a ColorDesc) -> Self {
        Self::Color(c)
    }
}

impl<'a> From<&'a mut ScalarDesc> for ParamMut<'a> {
    fn from(s: &'a mut ScalarDesc) -> Self {
        Self::Scalar(s)
    }
}

impl<'a> From<&'a mut ColorDesc> for ParamMut<'a> {
    fn from(c: &'a mut ColorDesc) -> Self {
        Self::Color(c)
    }
}

impl<'a> ParamRef<'a> {
    /// The texture it reads, if it is not a plain value.
    #[must_use]
    pub const fn texture(self) -> Option<&'a TextureDesc> {
        match self {
            Self::Scalar(s) => s.texture(),
            Self::Color(c) => c.texture(),
        }
    }
}

/// A material's coefficient or colour, to edit ([`MaterialDesc::params_mut`]).
#[derive(Debug)]
pub enum ParamMut<'a> {
    /// A coefficient.
    Scalar(&'a mut ScalarDesc),
    /// A colour.
    Color(&'a mut ColorDesc),
}

impl<'a> ParamMut<'a> {
    /// The texture it reads, if it is not a plain value.
    #[must_use]
    pub fn into_texture(self) -> Option<&'a mut TextureDesc> {
        match self {
            Self::Scalar(s) => s.texture_mut(),
            Self::Color(c) => c.texture_mut(),
        }
    }
}

/// The kinds of [`MaterialDesc`], as the material menu names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[derive(strum::VariantArray, strum::IntoStaticStr, strum::Display)]
#[derive(strum::EnumString, strum::EnumMessage)]
pub enum MaterialKind {
    /// [`MaterialDesc::Matte`].
    #[strum(
        message = "The lecture's SV_Matte: ambient plus Lambertian diffuse with a textured colour."
    )]
    Matte,
    /// [`MaterialDesc::Phong`].
    #[strum(message = "Matte with a Phong highlight.")]
    Phong,
    /// [`MaterialDesc::Reflective`].
    #[strum(message = "Phong plus a perfect mirror kr cr: shows what the mirrored ray sees.")]
    Reflective,
    /// [`MaterialDesc::Emissive`].
    #[strum(message = "The lecture's SV_Emissive: glows with its texture and ignores the lights.")]
    Emissive,
}

impl crate::names::Named for MaterialKind {
    const WHAT: &'static str = "material";
}

impl MaterialDesc {
    /// Which kind of material this is.
    #[must_use]
    pub const fn kind(&self) -> MaterialKind {
        match self {
            Self::Matte { .. } => MaterialKind::Matte,
            Self::Phong { .. } => MaterialKind::Phong,
            Self::Reflective { .. } => MaterialKind::Reflective,
            Self::Emissive { .. } => MaterialKind::Emissive,
        }
    }

    /// A material of another kind with its defaults, keeping this one's texture and every
    /// coefficient and colour both kinds have (ambient and diffuse; Phong's highlight).
    #[must_use]
    pub fn converted(&self, kind: MaterialKind) -> Self {
        let mut m = kind.default_desc();
        *m.texture_mut() = self.texture().clone();
        // Parameters both kinds have keep their values.
        let from: Vec<(&str, ParamRef<'_>)> = self.params();
        for (name, to) in m.params_mut() {
            match (from.iter().find(|(n, _)| *n == name).map(|(_, p)| *p), to) {
                (Some(ParamRef::Scalar(f)), ParamMut::Scalar(t)) => *t = f.clone(),
                (Some(ParamRef::Color(f)), ParamMut::Color(t)) => *t = f.clone(),
                _ => {}
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use crate::mapping::{Mapping, UvTransform};
    use crate::math::Rgb;
    use crate::scene::*;
    use crate::texture::{Filter, Lookup, Wrap};

    #[test]
    fn switching_kinds_keeps_the_mapping_texture_and_coefficients() {
        let earth = TextureDesc::Image {
            path: "earth.jpg".into(),
            mapping: Mapping::Cylindrical.into(),
            filter: Filter::Ewa,
            lookup: Lookup::Lecture,
            wrap: Wrap::Clamp,
            scale: 2.0,
            srgb: true,
            max_anisotropy: 4.0,
            uv: UvTransform::IDENTITY,
        };
        assert_eq!(
            earth.converted(TextureKind::Checker).mapping(),
            Some(&Mapping::Cylindrical.into())
        );
        // A mesh's material is read through the mesh's (u, v) unless told otherwise.
        assert_eq!(
            earth.converted(TextureKind::MeshMaterial).mapping(),
            Some(&Mapping::Uv.into())
        );
        let phong = MaterialDesc::Phong {
            ka: 0.1.into(),
            kd: 0.9.into(),
            cd: earth.clone(),
            ks: 0.5.into(),
            cs: Rgb::WHITE.into(),
            exp: 50.0.into(),
            ce: Rgb::BLACK.into(),
        };
        assert_eq!(
            phong.converted(MaterialKind::Matte),
            MaterialDesc::Matte {
                ka: 0.1.into(),
                kd: 0.9.into(),
                cd: earth.clone()
            }
        );
        assert_eq!(
            phong.converted(MaterialKind::Emissive),
            MaterialDesc::Emissive {
                ls: 1.0.into(),
                ce: earth
            }
        );
    }
}
