//! Closed sets of options named on the command line and in menus.
//!
//! Each such enum derives strum's `VariantArray` (every variant, in menu order),
//! `IntoStaticStr` (its name), `EnumString` (parsing; [`Named::from_name`] turns its error into
//! [`unknown`], which lists the valid names), `EnumMessage` (one sentence on the variant, for
//! tooltips and `--help`) and `Display`, and implements [`Named`]. Menus and the command line
//! read the variants from `VARIANTS`, so a variant can be missing from neither; the names are
//! the derive's, so they cannot drift from the parser's.

use std::str::FromStr;
use strum::{EnumMessage, VariantArray};

/// An enum whose variants have stable names and one-sentence descriptions.
pub trait Named:
    Copy + PartialEq + Send + Sync + 'static + VariantArray + EnumMessage + Into<&'static str> + FromStr
{
    /// What one option is called in messages ("filter", "wrap mode").
    const WHAT: &'static str;

    /// The variant's name on the command line and in menus.
    fn name(self) -> &'static str {
        self.into()
    }

    /// One sentence on the variant, for tooltips and `--help`.
    fn description(self) -> &'static str {
        self.get_message().unwrap_or_default()
    }

    /// The variant called `s`, or an error that lists the valid names ([`unknown`]).
    ///
    /// # Errors
    /// `s` names no variant.
    fn from_name(s: &str) -> Result<Self, String> {
        s.parse().map_err(|_| unknown::<Self>(s))
    }
}

/// Every variant's name, in menu order.
#[must_use]
pub fn names<T: Named>() -> Vec<&'static str> {
    T::VARIANTS.iter().map(|v| v.name()).collect()
}

/// The error for a name that is none of `T`'s: it lists the valid names.
#[must_use]
pub fn unknown<T: Named>(s: &str) -> String {
    format!(
        "unknown {} '{s}', expected one of: {}",
        T::WHAT,
        names::<T>().join(", ")
    )
}

/// A clap value parser for `T`: `--help` lists every name with its description, and an unknown
/// name is an error that lists the valid ones.
#[must_use]
pub fn value_parser<T: Named>() -> impl clap::builder::TypedValueParser<Value = T> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser as _};
    PossibleValuesParser::new(
        T::VARIANTS
            .iter()
            .map(|v| PossibleValue::new(v.name()).help(v.description())),
    )
    .try_map(|s| T::from_name(&s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Shading;
    use crate::mapping::Mapping;
    use crate::meshio::PlyFormat;
    use crate::sampler::{PixelFilter, PixelSampler};
    use crate::scene::{LightKind, MaterialKind, ProjectionKind, ShapeKind, TextureKind};
    use crate::texture::{Filter, Lookup, View, Wrap};

    /// Every variant parses back from its name and prints as it, and has a description.
    fn round_trips<T: Named + std::fmt::Debug + std::fmt::Display>() -> Vec<&'static str> {
        for &v in T::VARIANTS {
            assert_eq!(T::from_name(v.name()), Ok(v), "{} {v:?}", T::WHAT);
            assert_eq!(v.to_string(), v.name());
            assert!(
                !v.description().is_empty(),
                "{} {v:?} has no description",
                T::WHAT
            );
        }
        let err = T::from_name("no-such-name").unwrap_err();
        assert_eq!(
            err,
            format!(
                "unknown {} 'no-such-name', expected one of: {}",
                T::WHAT,
                names::<T>().join(", ")
            )
        );
        names::<T>()
    }

    /// The names users type and see: the same as before the sets were derived.
    #[test]
    fn every_variant_round_trips_through_its_name() {
        assert_eq!(
            round_trips::<Mapping>(),
            [
                "rectangular",
                "cylindrical",
                "spherical",
                "light-probe",
                "panoramic",
                "mirror-ball",
                "uv"
            ]
        );
        assert_eq!(
            round_trips::<Filter>(),
            [
                "nearest",
                "bilinear",
                "bicubic",
                "trilinear",
                "ewa",
                "footprint"
            ]
        );
        assert_eq!(round_trips::<Lookup>(), ["lecture", "centred"]);
        assert_eq!(
            round_trips::<crate::texture::Channel>(),
            ["Luminance", "Red", "Green", "Blue", "Alpha"]
        );
        assert_eq!(
            round_trips::<Wrap>(),
            ["repeat", "clamp", "mirror", "black"]
        );
        assert_eq!(
            round_trips::<View>(),
            [
                "shaded",
                "uv",
                "mip-level",
                "texel-grid",
                "seams",
                "difference"
            ]
        );
        assert_eq!(
            round_trips::<PixelSampler>(),
            [
                "regular",
                "random",
                "jittered",
                "n-rooks",
                "multi-jittered",
                "hammersley"
            ]
        );
        assert_eq!(round_trips::<PixelFilter>(), ["box", "tent", "gaussian"]);
        assert_eq!(round_trips::<Shading>(), ["flat", "smooth"]);
        assert_eq!(
            round_trips::<PlyFormat>(),
            ["ascii", "binary_little_endian", "binary_big_endian"]
        );
        assert_eq!(
            round_trips::<ShapeKind>(),
            ["Sphere", "Cylinder", "Plane", "Rectangle", "Disk", "Mesh"]
        );
        assert_eq!(
            round_trips::<TextureKind>(),
            [
                "Constant",
                "Image",
                "Checker",
                "UV grid",
                "Mesh material",
                "Formula"
            ]
        );
        assert_eq!(
            round_trips::<MaterialKind>(),
            ["Matte", "Phong", "Reflective", "Emissive"]
        );
        assert_eq!(round_trips::<LightKind>(), ["directional", "point"]);
        assert_eq!(
            round_trips::<ProjectionKind>(),
            ["Pinhole", "Fisheye", "Spherical", "Orthographic"]
        );
    }

    #[derive(Debug, clap::Parser)]
    struct Cli {
        #[arg(long, value_parser = value_parser::<Filter>())]
        filter: Filter,
    }

    #[test]
    fn the_command_line_takes_every_name_and_lists_them_for_an_unknown_one() {
        use clap::Parser as _;
        for &f in Filter::VARIANTS {
            let cli = Cli::try_parse_from(["t", "--filter", f.name()]).expect("a valid name");
            assert_eq!(cli.filter, f);
        }
        let err = Cli::try_parse_from(["t", "--filter", "linear"])
            .unwrap_err()
            .to_string();
        assert!(err.contains("'linear'"), "{err}");
        assert!(
            err.contains(
                "[possible values: nearest, bilinear, bicubic, trilinear, ewa, footprint]"
            ),
            "{err}"
        );
    }
}
