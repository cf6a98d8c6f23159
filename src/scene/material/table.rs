//! What the material table ([`crate::material::material_table!`]) generates for descriptions:
//! the kinds' rows and defaults, the parameter accessors and the build of the runtime material.

use super::super::assets::AssetCache;
use super::super::texture::{TextureDesc, TextureKind, texture};
use super::param::{BuildParam, ColorDesc, ScalarDesc};
use super::{MaterialDesc, MaterialKind, ParamMut, ParamRef};
use crate::error::Result;
use crate::material::{Material, ParamDefault, ParamSpec, material_table};
use std::path::Path;

/// The description of a default: a plain number or colour.
macro_rules! plain {
    (Scalar, $v:expr) => {
        ScalarDesc::Value($v)
    };
    (Colour, $v:expr) => {
        ColorDesc::Value($v)
    };
}

/// Everything generated from the table for descriptions.
macro_rules! desc_params {
    ($($kind:ident ($colour:ident) {
        $($name:ident : $ty:ident = $default:expr, $label:literal, $max:expr, $speed:expr;)*
    })*) => {
        impl MaterialKind {
            /// The table's rows of this kind: name, label, range and default of each coefficient
            /// and colour besides the colour texture, in preset order.
            #[must_use]
            pub const fn params(self) -> &'static [ParamSpec] {
                match self {
                    $(Self::$kind => &[$(ParamSpec {
                        name: stringify!($name),
                        label: $label,
                        max: $max,
                        speed: $speed,
                        default: ParamDefault::$ty($default),
                    }),*],)*
                }
            }

            /// The name of this kind's colour texture: `cd`, or `ce` for an emissive material.
            #[must_use]
            pub const fn colour_name(self) -> &'static str {
                match self {
                    $(Self::$kind => stringify!($colour),)*
                }
            }

            /// The material with the table's defaults and a constant grey colour.
            #[must_use]
            pub fn default_desc(self) -> MaterialDesc {
                let colour = TextureKind::Constant.default_desc();
                match self {
                    $(Self::$kind => MaterialDesc::$kind {
                        $colour: colour,
                        $($name: plain!($ty, $default),)*
                    },)*
                }
            }
        }

        impl MaterialDesc {
            /// Every coefficient and colour besides the colour texture (`cd`, or an emissive
            /// material's `ce`; Phong's glow `ce` is listed), by its preset name, in preset
            /// order.
            #[must_use]
            pub fn params(&self) -> Vec<(&'static str, ParamRef<'_>)> {
                match self {
                    $(Self::$kind { $colour: _, $($name),* } => {
                        vec![$((stringify!($name), ParamRef::from($name))),*]
                    })*
                }
            }

            /// The same parameters as [`MaterialDesc::params`], mutably.
            pub fn params_mut(&mut self) -> Vec<(&'static str, ParamMut<'_>)> {
                self.texture_and_params_mut().1
            }

            /// The colour texture and the parameters, mutably (borrowed together).
            fn texture_and_params_mut(
                &mut self,
            ) -> (&mut TextureDesc, Vec<(&'static str, ParamMut<'_>)>) {
                match self {
                    $(Self::$kind { $colour, $($name),* } => {
                        ($colour, vec![$((stringify!($name), ParamMut::from($name))),*])
                    })*
                }
            }

            /// Every texture the material reads, mutably, in the order of
            /// [`MaterialDesc::textures`].
            pub fn textures_mut(&mut self) -> Vec<(&'static str, &mut TextureDesc)> {
                let colour = self.kind().colour_name();
                let (texture, params) = self.texture_and_params_mut();
                let mut v = vec![(colour, texture)];
                v.extend(
                    params
                        .into_iter()
                        .filter_map(|(name, p)| p.into_texture().map(|t| (name, t))),
                );
                v
            }
        }

        /// The runtime material: constants stay plain numbers and colours, textures are loaded
        /// through `cache` (paths relative to `base`); errors name fields below the material's
        /// (`kd.scale`).
        pub(in crate::scene) fn material(
            m: &MaterialDesc,
            base: &Path,
            cache: &mut AssetCache,
        ) -> Result<Material> {
            Ok(match m {
                $(MaterialDesc::$kind { $colour, $($name),* } => Material::$kind {
                    $colour: texture($colour, base, cache).map_err(|e| {
                        e.under(base, &stringify!($colour).into())
                    })?,
                    $($name: $name.build(stringify!($name), base, cache)?,)*
                },)*
            })
        }
    };
}

material_table!(desc_params);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;
    use std::collections::BTreeSet;
    use strum::VariantArray;

    /// The table's names are the fields a preset writes: every parameter set away from its
    /// default (so none is skipped), the description serialised, its keys compared.
    #[test]
    fn the_table_names_every_serialised_field() {
        for &kind in MaterialKind::VARIANTS {
            let mut m = kind.default_desc();
            for (_, p) in m.params_mut() {
                match p {
                    ParamMut::Scalar(s) => *s = ScalarDesc::Value(0.5),
                    ParamMut::Color(c) => *c = ColorDesc::Value(Rgb::grey(0.5)),
                }
            }
            let json = serde_json::to_value(&m).expect("serialise");
            let fields = json
                .as_object()
                .and_then(|o| o.get(<&str>::from(kind)))
                .and_then(serde_json::Value::as_object)
                .expect("a struct variant");
            let written: BTreeSet<&str> = fields.keys().map(String::as_str).collect();
            let mut table: BTreeSet<&str> = kind.params().iter().map(|p| p.name).collect();
            table.insert(kind.colour_name());
            assert_eq!(written, table, "{kind}");
            let listed: Vec<&str> = m.params().into_iter().map(|(n, _)| n).collect();
            let rows: Vec<&str> = kind.params().iter().map(|p| p.name).collect();
            assert_eq!(listed, rows, "{kind}");
        }
    }

    /// A preset that leaves every parameter out reads the table's defaults.
    #[test]
    fn serde_defaults_are_the_table_defaults() {
        for &kind in MaterialKind::VARIANTS {
            let text = format!(
                "{}({}: Constant((0.7, 0.7, 0.7)))",
                <&str>::from(kind),
                kind.colour_name()
            );
            let read: MaterialDesc = ron::from_str(&text).expect(&text);
            assert_eq!(read, kind.default_desc(), "{text}");
        }
    }

    /// The runtime material lists the same parameters, with the same rows.
    #[test]
    fn the_runtime_material_lists_the_table() {
        for &kind in MaterialKind::VARIANTS {
            let built = material(&kind.default_desc(), Path::new("."), &mut AssetCache::new())
                .expect("builds");
            let names: Vec<&str> = built.params().into_iter().map(|(n, _)| n).collect();
            let rows: Vec<&str> = kind.params().iter().map(|p| p.name).collect();
            assert_eq!(names, rows, "{kind}");
            assert_eq!(built.param_specs(), kind.params(), "{kind}");
        }
    }
}
