//! A texture's mapping as a preset writes it: a built-in mapping's name (`Spherical`) or a
//! student's formulas (`Formula(u: "fract(atan2(x, z) / tau)", v: "1 - acos(y) / pi")`), and
//! its build into the runtime [`AnyMapping`] (the formulas compiled once, here).

use crate::field::{FieldPath, Refusal};
use crate::mapping::formula::FormulaError;
use crate::mapping::{AnyMapping, FormulaMapping, Mapping};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// How a texture's hit points become (u, v), in a preset.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(from = "Repr", into = "Repr")]
pub enum MappingDesc {
    /// One of the lecture's mappings, written by its name: `Spherical`.
    Builtin(Mapping),
    /// Two formulas over x, y, z, mesh_u, mesh_v (see `mapping::formula`):
    /// `Formula(u: "...", v: "...")`.
    Formula {
        /// The u formula.
        u: String,
        /// The v formula.
        v: String,
    },
}

impl Default for MappingDesc {
    fn default() -> Self {
        Self::Builtin(Mapping::default())
    }
}

impl From<Mapping> for MappingDesc {
    fn from(m: Mapping) -> Self {
        Self::Builtin(m)
    }
}

impl MappingDesc {
    /// The built-in mapping, `None` for formulas.
    #[must_use]
    pub const fn builtin(&self) -> Option<Mapping> {
        match self {
            Self::Builtin(m) => Some(*m),
            Self::Formula { .. } => None,
        }
    }

    /// What reads the shape's own (u, v) in this mapping, in words, if anything: the `Uv`
    /// mapping, or formulas reading mesh_u or mesh_v. A mesh without texture coordinates
    /// refuses it.
    #[must_use]
    pub fn reads_shape_uv(&self) -> Option<&'static str> {
        match self {
            Self::Builtin(Mapping::Uv) => Some("the Uv mapping"),
            Self::Builtin(_) => None,
            Self::Formula { u, v } => FormulaMapping::checked(u, v)
                .is_ok_and(|f| f.reads_mesh())
                .then_some("its formula's mesh_u and mesh_v"),
        }
    }

    /// The runtime mapping: formulas compiled.
    ///
    /// # Errors
    /// A formula's mistake, naming its field relative to the mapping's (`u`) and its column:
    /// `column 7: unknown name `w` ...`.
    pub fn build(&self) -> Result<AnyMapping, Refusal> {
        match self {
            Self::Builtin(m) => Ok(AnyMapping::Builtin(*m)),
            Self::Formula { u, v } => FormulaMapping::new(u, v)
                .map(|f| AnyMapping::Formula(Arc::new(f)))
                .map_err(|e| formula_refusal(&e)),
        }
    }
}

/// A formula's mistake as the refusal of its field (`u`, `grey`): its column, then why.
pub(super) fn formula_refusal(e: &FormulaError) -> Refusal {
    let message = match e.column {
        Some(c) => format!("column {c}: {}", e.message),
        None => e.message.clone(),
    };
    Refusal::new(FieldPath::field(&e.field), message)
}

/// The preset's spelling: the built-in names as unit variants beside `Formula`, so `Spherical`
/// reads as before. Converted by exhaustive matches: a new built-in mapping must be added here.
#[derive(Clone, Serialize, Deserialize)]
#[serde(rename = "Mapping", deny_unknown_fields)]
enum Repr {
    Rectangular,
    Cylindrical,
    Spherical,
    LightProbe,
    Panoramic,
    MirrorBall,
    Uv,
    Formula { u: String, v: String },
}

impl From<Repr> for MappingDesc {
    fn from(r: Repr) -> Self {
        let m = match r {
            Repr::Rectangular => Mapping::Rectangular,
            Repr::Cylindrical => Mapping::Cylindrical,
            Repr::Spherical => Mapping::Spherical,
            Repr::LightProbe => Mapping::LightProbe,
            Repr::Panoramic => Mapping::Panoramic,
            Repr::MirrorBall => Mapping::MirrorBall,
            Repr::Uv => Mapping::Uv,
            Repr::Formula { u, v } => return Self::Formula { u, v },
        };
        Self::Builtin(m)
    }
}

impl From<MappingDesc> for Repr {
    fn from(d: MappingDesc) -> Self {
        match d {
            MappingDesc::Builtin(m) => match m {
                Mapping::Rectangular => Self::Rectangular,
                Mapping::Cylindrical => Self::Cylindrical,
                Mapping::Spherical => Self::Spherical,
                Mapping::LightProbe => Self::LightProbe,
                Mapping::Panoramic => Self::Panoramic,
                Mapping::MirrorBall => Self::MirrorBall,
                Mapping::Uv => Self::Uv,
            },
            MappingDesc::Formula { u, v } => Self::Formula { u, v },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use strum::VariantArray;

    /// Every built-in name reads as before and writes back the same; formulas round-trip.
    #[test]
    fn builtin_names_and_formulas_round_trip_through_ron() {
        for &m in Mapping::VARIANTS {
            let d = MappingDesc::Builtin(m);
            let text = ron::to_string(&d).expect("write");
            assert_eq!(text, format!("{m:?}"));
            assert_eq!(ron::from_str::<MappingDesc>(&text).expect("read"), d);
        }
        let f = MappingDesc::Formula {
            u: "fract(atan2(x, z) / tau)".into(),
            v: "1 - acos(y) / pi".into(),
        };
        let text = ron::to_string(&f).expect("write");
        assert_eq!(
            text,
            r#"Formula(u:"fract(atan2(x, z) / tau)",v:"1 - acos(y) / pi")"#
        );
        assert_eq!(ron::from_str::<MappingDesc>(&text).expect("read"), f);
        let e = ron::from_str::<MappingDesc>(r#"Formula(u: "x", v: "y", w: "z")"#)
            .expect_err("unknown field");
        assert!(e.to_string().contains('w'), "{e}");
    }

    #[test]
    fn a_formula_error_names_the_field_and_column() {
        let d = MappingDesc::Formula {
            u: "x + w".into(),
            v: "y".into(),
        };
        let e = d.build().expect_err("unknown name");
        assert_eq!(e.field.to_string(), "u");
        assert!(
            e.to_string().starts_with("u: column 5: unknown name `w`"),
            "{e}"
        );
    }
}
