//! A material's coefficients and colours: a plain value or a texture ([`ScalarDesc`],
//! [`ColorDesc`]), how RON's untagged values read back as textures, and their build into the
//! runtime [`Scalar`] and [`Colour`].

use super::super::assets::AssetCache;
use super::super::texture::{TextureDesc, alpha_texture, param_texture};
use super::super::values::finite_non_negative;
use crate::error::{Error, Result};
use crate::field::FieldPath;
use crate::material::{Colour, Scalar, ScalarTexture};
use crate::math::Rgb;
use crate::texture::{Channel, Texture};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A coefficient of a material: a plain number (`ks: 0.25`, a constant, costing nothing), or
/// a texture read as one number, by default its luminance (`ks: Image(path: "mask.png")`),
/// or one channel of it (`ks: (texture: Image(path: "mask.png"), channel: Red)`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "a number, a texture (Constant((r, g, b)), Image(path: \"...\"), Checker(), UvGrid()) or (texture: ..., channel: Red)"
)]
pub enum ScalarDesc {
    /// The same number everywhere.
    Value(f32),
    /// A texture's Rec. 709 luminance.
    Texture(#[serde(deserialize_with = "texture_in_param")] TextureDesc),
    /// One channel (or the luminance) of a texture.
    Channel(ChannelDesc),
}

/// A texture read as one number: [`ScalarDesc::Channel`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChannelDesc {
    /// The texture read.
    #[serde(deserialize_with = "texture_in_param")]
    pub texture: TextureDesc,
    /// Which channel of it; default `Luminance`.
    #[serde(default)]
    pub channel: Channel,
}

/// A colour of a material other than `cd` and `ce`: a plain linear colour (`cs: (1, 1, 1)`, a
/// constant costing nothing) or a texture (`cs: Image(path: "tint.png")`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "a colour (r, g, b) or a texture (Constant((r, g, b)), Image(path: \"...\"), Checker(), UvGrid())"
)]
pub enum ColorDesc {
    /// The same linear colour everywhere.
    Value(Rgb),
    /// A texture.
    Texture(#[serde(deserialize_with = "texture_in_param")] TextureDesc),
}

/// Reads a [`TextureDesc`] inside an untagged parameter. There serde buffers the value first
/// and RON hands it over as `{variant: body}` ("JSON enum semantics"); a texture written with
/// no fields (`UvGrid()`, `Checker`) then has a unit body, which a struct variant refuses. This
/// reads the variant's name and gives such a body the empty field list it stands for.
fn texture_in_param<'de, D: serde::Deserializer<'de>>(d: D) -> Result<TextureDesc, D::Error> {
    use serde::de::{self, IntoDeserializer, MapAccess, SeqAccess, Visitor};
    use std::fmt;

    /// `name()`: the texture with every field at its default.
    fn defaults<E: de::Error>(name: &str) -> Result<TextureDesc, E> {
        ron::from_str(&format!("{name}()")).map_err(|e| E::custom(format!("{name}: {}", e.code)))
    }

    /// The body of variant `name`.
    struct Body(String);

    impl<'de> de::DeserializeSeed<'de> for Body {
        type Value = TextureDesc;
        fn deserialize<D2: serde::Deserializer<'de>>(
            self,
            d: D2,
        ) -> Result<TextureDesc, D2::Error> {
            d.deserialize_any(self)
        }
    }

    /// Variant `name` with its body still to read, as serde's enum access.
    struct Variant<A>(String, A);

    impl<'de, A: MapAccess<'de>> de::EnumAccess<'de> for Variant<A> {
        type Error = A::Error;
        type Variant = Self;
        fn variant_seed<V: de::DeserializeSeed<'de>>(
            self,
            seed: V,
        ) -> Result<(V::Value, Self), A::Error> {
            let v = seed.deserialize(self.0.as_str().into_deserializer())?;
            Ok((v, self))
        }
    }

    impl<'de, A: MapAccess<'de>> de::VariantAccess<'de> for Variant<A> {
        type Error = A::Error;
        fn unit_variant(self) -> Result<(), A::Error> {
            Err(de::Error::custom(format!("{}: fields expected", self.0)))
        }
        fn newtype_variant_seed<T: de::DeserializeSeed<'de>>(
            self,
            seed: T,
        ) -> Result<T::Value, A::Error> {
            seed.deserialize(de::value::MapAccessDeserializer::new(self.1))
        }
        fn tuple_variant<V: Visitor<'de>>(self, _len: usize, v: V) -> Result<V::Value, A::Error> {
            v.visit_map(self.1)
        }
        fn struct_variant<V: Visitor<'de>>(
            self,
            _fields: &'static [&'static str],
            v: V,
        ) -> Result<V::Value, A::Error> {
            v.visit_map(self.1)
        }
    }

    /// Variant `name` whose body is a sequence (`Constant((r, g, b))`).
    struct SeqVariant<A>(String, A);

    impl<'de, A: SeqAccess<'de>> de::EnumAccess<'de> for SeqVariant<A> {
        type Error = A::Error;
        type Variant = Self;
        fn variant_seed<V: de::DeserializeSeed<'de>>(
            self,
            seed: V,
        ) -> Result<(V::Value, Self), A::Error> {
            let v = seed.deserialize(self.0.as_str().into_deserializer())?;
            Ok((v, self))
        }
    }

    impl<'de, A: SeqAccess<'de>> de::VariantAccess<'de> for SeqVariant<A> {
        type Error = A::Error;
        fn unit_variant(self) -> Result<(), A::Error> {
            Err(de::Error::custom(format!("{}: a value expected", self.0)))
        }
        fn newtype_variant_seed<T: de::DeserializeSeed<'de>>(
            self,
            seed: T,
        ) -> Result<T::Value, A::Error> {
            seed.deserialize(de::value::SeqAccessDeserializer::new(self.1))
        }
        fn tuple_variant<V: Visitor<'de>>(self, _len: usize, v: V) -> Result<V::Value, A::Error> {
            v.visit_seq(self.1)
        }
        fn struct_variant<V: Visitor<'de>>(
            self,
            _fields: &'static [&'static str],
            v: V,
        ) -> Result<V::Value, A::Error> {
            v.visit_seq(self.1)
        }
    }

    impl<'de> Visitor<'de> for Body {
        type Value = TextureDesc;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write!(f, "the fields of {}", self.0)
        }
        fn visit_unit<E: de::Error>(self) -> Result<TextureDesc, E> {
            defaults(&self.0)
        }
        fn visit_map<A: MapAccess<'de>>(self, m: A) -> Result<TextureDesc, A::Error> {
            TextureDesc::deserialize(de::value::EnumAccessDeserializer::new(Variant(self.0, m)))
        }
        fn visit_seq<A: SeqAccess<'de>>(self, s: A) -> Result<TextureDesc, A::Error> {
            TextureDesc::deserialize(de::value::EnumAccessDeserializer::new(SeqVariant(
                self.0, s,
            )))
        }
    }

    /// The outer `{variant: body}`, or a bare variant name.
    struct Outer;

    impl<'de> Visitor<'de> for Outer {
        type Value = TextureDesc;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("a texture")
        }
        fn visit_str<E: de::Error>(self, name: &str) -> Result<TextureDesc, E> {
            defaults(name)
        }
        fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<TextureDesc, A::Error> {
            let name: String = m
                .next_key()?
                .ok_or_else(|| de::Error::custom("a texture needs a kind"))?;
            let t = m.next_value_seed(Body(name))?;
            if m.next_key::<de::IgnoredAny>()?.is_some() {
                return Err(de::Error::custom("one texture expected"));
            }
            Ok(t)
        }
    }

    d.deserialize_any(Outer)
}

impl ScalarDesc {
    /// The texture this coefficient reads, if it is not a plain number.
    #[must_use]
    pub const fn texture(&self) -> Option<&TextureDesc> {
        match self {
            Self::Value(_) => None,
            Self::Texture(t) | Self::Channel(ChannelDesc { texture: t, .. }) => Some(t),
        }
    }

    /// The texture this coefficient reads, mutably.
    pub const fn texture_mut(&mut self) -> Option<&mut TextureDesc> {
        match self {
            Self::Value(_) => None,
            Self::Texture(t) | Self::Channel(ChannelDesc { texture: t, .. }) => Some(t),
        }
    }

    /// The channel read from the texture (luminance for a bare texture); `None` for a number.
    #[must_use]
    pub const fn channel(&self) -> Option<Channel> {
        match self {
            Self::Value(_) => None,
            Self::Texture(_) => Some(Channel::Luminance),
            Self::Channel(c) => Some(c.channel),
        }
    }
}

impl ColorDesc {
    /// Whether this is the plain colour black (a glow that is off).
    #[must_use]
    pub fn is_black(&self) -> bool {
        *self == Self::Value(Rgb::BLACK)
    }

    /// The texture this colour reads, if it is not a plain colour.
    #[must_use]
    pub const fn texture(&self) -> Option<&TextureDesc> {
        match self {
            Self::Value(_) => None,
            Self::Texture(t) => Some(t),
        }
    }

    /// The texture this colour reads, mutably.
    pub const fn texture_mut(&mut self) -> Option<&mut TextureDesc> {
        match self {
            Self::Value(_) => None,
            Self::Texture(t) => Some(t),
        }
    }
}

impl From<f32> for ScalarDesc {
    fn from(v: f32) -> Self {
        Self::Value(v)
    }
}

impl From<Rgb> for ColorDesc {
    fn from(c: Rgb) -> Self {
        Self::Value(c)
    }
}

/// A coefficient: a constant stays a plain number (a constant texture becomes one), so it
/// costs nothing when shading.
pub(in crate::scene) fn scalar(
    what: &str,
    s: &ScalarDesc,
    base: &Path,
    cache: &mut AssetCache,
) -> Result<Scalar> {
    let (t, channel) = match s {
        ScalarDesc::Value(v) => {
            finite_non_negative(what, &[*v]).map_err(|r| Error::refused(base, r))?;
            return Ok(Scalar::Const(*v));
        }
        ScalarDesc::Texture(t) => (t, Channel::Luminance),
        ScalarDesc::Channel(c) => (&c.texture, c.channel),
    };
    // One channel of a texture is one step deeper in the preset: `kd.texture`.
    let field = match s {
        ScalarDesc::Channel(_) => FieldPath::field(what).then("texture"),
        _ => FieldPath::field(what),
    };
    if channel == Channel::Alpha {
        let texture = alpha_texture(t, base, cache).map_err(|e| e.under(base, &field))?;
        return Ok(Scalar::Texture(Box::new(ScalarTexture {
            texture,
            channel,
        })));
    }
    let texture = param_texture(&field, t, base, cache)?;
    Ok(match texture {
        Texture::Constant(c) => Scalar::Const(channel.of(c)),
        texture => Scalar::Texture(Box::new(ScalarTexture { texture, channel })),
    })
}

/// A colour parameter: a constant stays a plain colour (a constant texture becomes one).
fn colour(what: &str, c: &ColorDesc, base: &Path, cache: &mut AssetCache) -> Result<Colour> {
    Ok(match c {
        ColorDesc::Value(c) => {
            finite_non_negative(what, &c.to_array()).map_err(|r| Error::refused(base, r))?;
            Colour::Const(*c)
        }
        ColorDesc::Texture(t) => match param_texture(&what.into(), t, base, cache)? {
            Texture::Constant(c) => Colour::Const(c),
            texture => Colour::Texture(Box::new(texture)),
        },
    })
}

/// A description of a coefficient or colour built into its runtime form (what the material
/// table's build calls for every row).
pub(super) trait BuildParam {
    /// The runtime parameter.
    type Runtime;

    /// Builds it; its errors name fields below `what` (the parameter's name).
    fn build(&self, what: &str, base: &Path, cache: &mut AssetCache) -> Result<Self::Runtime>;
}

impl BuildParam for ScalarDesc {
    type Runtime = Scalar;

    fn build(&self, what: &str, base: &Path, cache: &mut AssetCache) -> Result<Scalar> {
        scalar(what, self, base, cache)
    }
}

impl BuildParam for ColorDesc {
    type Runtime = Colour;

    fn build(&self, what: &str, base: &Path, cache: &mut AssetCache) -> Result<Colour> {
        colour(what, self, base, cache)
    }
}

#[cfg(test)]
mod tests {
    use crate::mapping::Mapping;
    use crate::math::Rgb;
    use crate::scene::*;
    use crate::texture::{Channel, Filter};

    /// Plain numbers and colours keep their meaning; textures, a channel of one, NaN and
    /// integers read as the format says, and each writes back as it was read.
    #[test]
    fn coefficients_read_as_numbers_or_textures() {
        let m: MaterialDesc = ron::from_str(
            r#"Phong(cd: Constant((0.5, 0.5, 0.5)), ka: 1, kd: 0.5,
                ks: Image(path: "mask.png", mapping: Spherical, filter: Ewa),
                cs: Checker(squares: (2, 2)),
                exp: (texture: UvGrid(wrap: Clamp), channel: Green))"#,
        )
        .expect("phong");
        let MaterialDesc::Phong {
            ka,
            kd,
            ks,
            cs,
            exp,
            ..
        } = &m
        else {
            panic!("not Phong: {m:?}")
        };
        assert_eq!(*ka, ScalarDesc::Value(1.0));
        assert_eq!(*kd, ScalarDesc::Value(0.5));
        let Some(TextureDesc::Image {
            path,
            mapping,
            filter,
            ..
        }) = ks.texture()
        else {
            panic!("ks: {ks:?}")
        };
        assert_eq!(
            (path.as_str(), mapping.builtin(), *filter),
            ("mask.png", Some(Mapping::Spherical), Filter::Ewa)
        );
        assert_eq!(ks.channel(), Some(Channel::Luminance));
        assert!(matches!(
            cs,
            ColorDesc::Texture(TextureDesc::Checker {
                squares: (2.0, 2.0),
                ..
            })
        ));
        assert_eq!(exp.channel(), Some(Channel::Green));
        assert_eq!(
            exp.texture().map(TextureDesc::kind),
            Some(TextureKind::UvGrid)
        );
        let text = ron::to_string(&m).expect("write");
        assert_eq!(ron::from_str::<MaterialDesc>(&text).expect("read back"), m);
        let nan: MaterialDesc = ron::from_str("Matte(ka: NaN, cd: Constant((1, 1, 1)))").unwrap();
        assert!(matches!(nan, MaterialDesc::Matte { ka: ScalarDesc::Value(v), .. } if v.is_nan()));
        let plain: MaterialDesc =
            ron::from_str("Phong(cs: (1, 0.5, 0), cd: Constant((1, 1, 1)))").unwrap();
        assert!(matches!(
            plain,
            MaterialDesc::Phong {
                cs: ColorDesc::Value(Rgb(1.0, 0.5, 0.0)),
                ..
            }
        ));
    }

    /// A texture inside a coefficient reads exactly as the same text does as `cd`, also with
    /// every field left out (`UvGrid()`) and for a constant.
    #[test]
    fn a_texture_in_a_coefficient_reads_as_it_does_as_cd() {
        for t in [
            "UvGrid(wrap: Clamp)",
            "UvGrid()",
            "Checker()",
            "Checker(squares: (2, 4), colors: ((1, 0, 0), (0, 0, 1)))",
            "Constant((0.2, 0.4, 0.6))",
            r#"Image(path: "x.png", mapping: Cylindrical, filter: Trilinear, scale: 2)"#,
        ] {
            let as_cd: TextureDesc = ron::from_str(t).expect(t);
            let s: ScalarDesc = ron::from_str(t).expect(t);
            assert_eq!(s, ScalarDesc::Texture(as_cd.clone()), "{t}");
            let c: ColorDesc = ron::from_str(t).expect(t);
            assert_eq!(c, ColorDesc::Texture(as_cd.clone()), "{t}");
            let ch: ScalarDesc = ron::from_str(&format!("(texture: {t}, channel: Blue)")).expect(t);
            assert_eq!(
                ch,
                ScalarDesc::Channel(ChannelDesc {
                    texture: as_cd,
                    channel: Channel::Blue
                }),
                "{t}"
            );
        }
    }

    /// A value that is neither a number nor a texture says what it may be.
    #[test]
    fn a_bad_coefficient_says_what_is_expected() {
        let e = ron::from_str::<MaterialDesc>(r#"Phong(ks: "shiny", cd: Constant((1, 1, 1)))"#)
            .expect_err("a string is no coefficient");
        let msg = e.to_string();
        assert!(msg.contains("a number, a texture"), "{msg}");
        let e = ron::from_str::<MaterialDesc>(
            r#"Phong(cs: Imag(path: "x.png"), cd: Constant((1, 1, 1)))"#,
        )
        .expect_err("no such texture");
        assert!(
            e.to_string().contains("a colour (r, g, b) or a texture"),
            "{e}"
        );
    }
}
