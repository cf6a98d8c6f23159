//! Generic edits of a preset: a path into the [`SceneDesc`] (`objects[0].material.cd.mapping`)
//! and a value in the preset's own RON syntax (`Cylindrical`, `(0, 1, 4)`).
//!
//! The description is serialised to a `serde_json` tree only to find where the path goes;
//! the new description is then deserialised from that tree through `Splice`, a deserializer
//! that hands the one value at the path to RON's deserializer. `SceneDesc`'s own `Deserialize`
//! drives both, so the value is parsed as exactly the type the field has (an enum variant, a
//! point, a number), every field of every preset works, including fields added later, and a
//! value that does not fit gets the preset parser's own message.

use crate::scene::{FieldPath, SceneDesc, check_numbers};
use serde::de::{self, DeserializeSeed, Deserializer, IntoDeserializer, Visitor};
use serde_json::Value;
use std::fmt;

pub use crate::scene::Step;

/// Splits `objects[0].material.cd.mapping` into steps ([`FieldPath::parse`], the one path
/// syntax of errors, lessons and the window).
///
/// # Errors
/// An empty path, an empty name (`a..b`), or a bad index (`objects[x]`), with the reason.
pub fn parse_path(path: &str) -> Result<Vec<Step>, String> {
    FieldPath::parse(path).map(|p| p.steps().to_vec())
}

/// Writes steps back as a path (`objects[0].material`).
#[must_use]
pub fn path_text(steps: &[Step]) -> String {
    FieldPath::from(steps.to_vec()).to_string()
}

/// The single-key object `{"Variant": ...}` serde writes for an enum's data variant.
fn variant_of(map: &serde_json::Map<String, Value>) -> Option<&str> {
    let mut keys = map.keys();
    match (keys.next(), keys.next()) {
        (Some(k), None) if k.starts_with(|c: char| c.is_ascii_uppercase()) => Some(k.as_str()),
        _ => None,
    }
}

/// Follows `steps` through the serialised description, stepping into enum variants the path
/// does not name (`material.cd` means `material.Matte.cd` on a matte material). Returns the
/// explicit steps. A field may be absent from the tree (a field left at its default is not
/// written, `render.compare`); whether it exists is then up to the type's deserializer.
fn resolve(tree: &Value, steps: &[Step]) -> Result<Vec<Step>, String> {
    let empty = Value::Object(serde_json::Map::new());
    let mut out: Vec<Step> = Vec::new();
    let mut node = tree;
    for (i, step) in steps.iter().enumerate() {
        let last = i + 1 == steps.len();
        loop {
            let here = || {
                if out.is_empty() {
                    "the scene".to_owned()
                } else {
                    format!("`{}`", path_text(&out))
                }
            };
            match (step, node) {
                (Step::Field(name), Value::Object(map)) => {
                    if let Some(next) = map.get(name) {
                        out.push(step.clone());
                        node = next;
                        break;
                    }
                    if let Some(variant) = variant_of(map) {
                        out.push(Step::Field(variant.to_owned()));
                        node = &map[variant];
                        continue;
                    }
                    // Absent: a field left at its default is not written (`render.compare`),
                    // so the path goes on into its default, which the type's deserializer
                    // fills in; a name the type does not have is refused there.
                    out.push(step.clone());
                    if last {
                        return Ok(out);
                    }
                    node = &empty;
                    break;
                }
                (Step::Index(n), Value::Array(items)) => {
                    let Some(next) = items.get(*n) else {
                        return Err(format!(
                            "{} has {} item(s), so [{n}] is not one of them",
                            here(),
                            items.len()
                        ));
                    };
                    out.push(step.clone());
                    node = next;
                    break;
                }
                (Step::Index(_), Value::Object(map)) if variant_of(map).is_some() => {
                    let variant = variant_of(map).unwrap_or_default().to_owned();
                    node = &map[&variant];
                    out.push(Step::Field(variant));
                }
                (_, Value::Null) => {
                    return Err(format!(
                        "{} is None: set it whole, e.g. `Some(...)`",
                        here()
                    ));
                }
                (Step::Field(name), Value::String(s)) => {
                    return Err(format!("{} is `{s}`, which has no field `{name}`", here()));
                }
                (Step::Field(name), _) => {
                    return Err(format!(
                        "{} is a value, not something with a field `{name}`",
                        here()
                    ));
                }
                (Step::Index(n), _) => {
                    return Err(format!("{} is not a list, so it has no item [{n}]", here()));
                }
            }
        }
    }
    Ok(out)
}

/// The preset with the value at `path` replaced by `ron_value` (RON, as in a preset file).
///
/// # Errors
/// The path does not lead into the preset ("`objects` has 1 item(s), so `[3]` is not one of
/// them"), the value does not fit the field (RON's message: "Expected ..."), or it is not a
/// finite number where one is needed. The message names the path.
pub fn set_path(desc: &SceneDesc, path: &str, ron_value: &str) -> Result<SceneDesc, String> {
    let steps = parse_path(path)?;
    let tree = serde_json::to_value(desc).map_err(|e| e.to_string())?;
    let explicit = resolve(&tree, &steps)?;
    let new = SceneDesc::deserialize(Splice {
        value: tree,
        path: Some(&explicit),
        whole: &explicit,
        raw: ron_value,
    })
    .map_err(|e| format!("`{path}` = {ron_value}: {}", e.0))?;
    check_numbers(&new)
        .map_err(|r| format!("`{path}` = {ron_value}: {}", new.refusal_message(&r)))?;
    // What the preset reader refuses, an edit may not make: another format version.
    if new.version != crate::scene::PRESET_VERSION {
        return Err(format!(
            "`{path}` = {ron_value}: version {} is not supported (this texplore reads version {})",
            new.version,
            crate::scene::PRESET_VERSION
        ));
    }
    Ok(new)
}

use serde::Deserialize;

/// The serialised value at `path` (`None` if the path does not lead anywhere): what a test or
/// the window compares to see that an edit took effect.
#[must_use]
pub fn value_at(desc: &SceneDesc, path: &str) -> Option<Value> {
    let steps = parse_path(path).ok()?;
    let tree = serde_json::to_value(desc).ok()?;
    let explicit = resolve(&tree, &steps).ok()?;
    let mut node = &tree;
    for step in &explicit {
        node = match step {
            Step::Field(f) => node.get(f)?,
            Step::Index(i) => node.get(i)?,
        };
    }
    Some(node.clone())
}

/// A deserialisation error: the message only (the caller names the file and line).
#[derive(Debug)]
pub struct SpliceError(String);

impl fmt::Display for SpliceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SpliceError {}

impl de::Error for SpliceError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Self(msg.to_string())
    }
}

fn json_err(e: &serde_json::Error) -> SpliceError {
    SpliceError(e.to_string())
}

/// A serialised value to deserialise again, with the part of the path still to follow:
/// `None` off the path (the value as it was), `Some([])` at the target (parse `raw` as RON).
struct Splice<'a, 'de> {
    value: Value,
    path: Option<&'a [Step]>,
    /// The whole path (the steps already followed name a field in messages).
    whole: &'a [Step],
    raw: &'de str,
}

impl<'de> Splice<'_, 'de> {
    /// Parses the RON text with the visitor of the target's type, requiring all of it used.
    fn ron<V, F>(raw: &'de str, f: F) -> Result<V, SpliceError>
    where
        F: FnOnce(&mut ron::Deserializer<'de>) -> Result<V, ron::Error>,
    {
        let mut de = ron::Deserializer::from_str(raw).map_err(|e| SpliceError(e.to_string()))?;
        let position = |de: &ron::Deserializer<'de>, e: ron::Error| {
            let spanned = de.span_error(e);
            let col = spanned.span.start.col;
            SpliceError(format!(
                "{} (at character {col} of the value)",
                spanned.code
            ))
        };
        let v = f(&mut de).map_err(|e| position(&de, e))?;
        de.end().map_err(|e| position(&de, e))?;
        Ok(v)
    }

    /// On the path, not at its end: the next step's map, list or variant. A field absent from
    /// the tree (left at its default) is entered as an empty map, which the type fills with
    /// its defaults.
    fn descend<V: Visitor<'de>>(self, rest: &[Step], visitor: V) -> Result<V::Value, SpliceError> {
        let value = match (self.value, &rest[0]) {
            (Value::Null, Step::Field(_)) => Value::Object(serde_json::Map::new()),
            (v, _) => v,
        };
        match value {
            Value::Object(map) => {
                let mut entries: Vec<(String, Value)> = map.into_iter().collect();
                let absent =
                    matches!(&rest[0], Step::Field(f) if !entries.iter().any(|(k, _)| k == f));
                if let (true, Step::Field(f)) = (absent, &rest[0]) {
                    entries.push((f.clone(), Value::Null));
                }
                visitor.visit_map(SpliceMap {
                    entries: entries.into_iter(),
                    pending: None,
                    path: rest,
                    whole: self.whole,
                    raw: self.raw,
                })
            }
            Value::Array(items) => visitor.visit_seq(SpliceSeq {
                items: items.into_iter().enumerate(),
                path: rest,
                whole: self.whole,
                raw: self.raw,
            }),
            other => Err(SpliceError(format!("cannot go into {other}"))),
        }
    }

    /// The path followed so far, as a message names it (`render`), when `rest` is still to go.
    fn here(&self, rest: &[Step]) -> String {
        // The steps followed, without the enum variants `resolve` stepped into (the path a
        // lesson writes: `objects[0].material.cd`, not `...material.Matte.cd.Image`).
        let done: Vec<Step> = self.whole[..self.whole.len().saturating_sub(rest.len())]
            .iter()
            .filter(
                |s| !matches!(s, Step::Field(f) if f.starts_with(|c: char| c.is_ascii_uppercase())),
            )
            .cloned()
            .collect();
        if done.is_empty() {
            "the scene".to_owned()
        } else {
            format!("`{}`", path_text(&done))
        }
    }
}

macro_rules! forward {
    ($($method:ident $(($($arg:ident: $ty:ty),*))?;)*) => {
        $(
            fn $method<V: Visitor<'de>>(self, $($($arg: $ty,)*)? visitor: V) -> Result<V::Value, SpliceError> {
                match self.path {
                    None => self.value.$method($($($arg,)*)? visitor).map_err(|e| json_err(&e)),
                    Some([]) => Self::ron(self.raw, |de| de.$method($($($arg,)*)? visitor)),
                    Some(rest) => self.descend(rest, visitor),
                }
            }
        )*
    };
}

impl<'de> Deserializer<'de> for Splice<'_, 'de> {
    type Error = SpliceError;

    forward! {
        deserialize_any; deserialize_bool; deserialize_i8; deserialize_i16; deserialize_i32;
        deserialize_i64; deserialize_u8; deserialize_u16; deserialize_u32; deserialize_u64;
        deserialize_f32; deserialize_f64; deserialize_char; deserialize_str; deserialize_string;
        deserialize_bytes; deserialize_byte_buf; deserialize_unit; deserialize_seq;
        deserialize_map; deserialize_identifier; deserialize_ignored_any;
        deserialize_unit_struct(name: &'static str);
        deserialize_tuple(len: usize);
        deserialize_tuple_struct(name: &'static str, len: usize);
    }

    /// On the path, the next step must be one of the struct's fields: a field left at its
    /// default is absent from the tree, so the tree cannot say which names exist.
    fn deserialize_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, SpliceError> {
        match self.path {
            None => self
                .value
                .deserialize_struct(name, fields, visitor)
                .map_err(|e| json_err(&e)),
            Some([]) => Self::ron(self.raw, |de| de.deserialize_struct(name, fields, visitor)),
            Some(rest) => {
                if let Step::Field(f) = &rest[0]
                    && !fields.contains(&f.as_str())
                {
                    return Err(SpliceError(format!(
                        "{} has no field `{f}` (it has {})",
                        self.here(rest),
                        fields.join(", ")
                    )));
                }
                self.descend(rest, visitor)
            }
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SpliceError> {
        match self.path {
            None => self
                .value
                .deserialize_option(visitor)
                .map_err(|e| json_err(&e)),
            Some([]) => Self::ron(self.raw, |de| de.deserialize_option(visitor)),
            Some(_) => visitor.visit_some(self),
        }
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        visitor: V,
    ) -> Result<V::Value, SpliceError> {
        match self.path {
            None => self
                .value
                .deserialize_newtype_struct(name, visitor)
                .map_err(|e| json_err(&e)),
            Some([]) => Self::ron(self.raw, |de| de.deserialize_newtype_struct(name, visitor)),
            Some(_) => visitor.visit_newtype_struct(self),
        }
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, SpliceError> {
        match self.path {
            None => self
                .value
                .deserialize_enum(name, variants, visitor)
                .map_err(|e| json_err(&e)),
            Some([]) => Self::ron(self.raw, |de| de.deserialize_enum(name, variants, visitor)),
            Some([Step::Field(variant), rest @ ..]) => {
                let Value::Object(mut map) = self.value else {
                    return Err(SpliceError(format!("`{variant}` has no fields")));
                };
                let inner = map.remove(variant).unwrap_or(Value::Null);
                visitor.visit_enum(SpliceEnum {
                    variant: variant.clone(),
                    inner: Splice {
                        value: inner,
                        path: Some(rest),
                        whole: self.whole,
                        raw: self.raw,
                    },
                })
            }
            Some([Step::Index(i), ..]) => Err(SpliceError(format!("an enum has no item [{i}]"))),
        }
    }
}

struct SpliceMap<'a, 'de> {
    entries: std::vec::IntoIter<(String, Value)>,
    pending: Option<(bool, Value)>,
    path: &'a [Step],
    whole: &'a [Step],
    raw: &'de str,
}

impl<'de> de::MapAccess<'de> for SpliceMap<'_, 'de> {
    type Error = SpliceError;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, SpliceError> {
        let Some((key, value)) = self.entries.next() else {
            return Ok(None);
        };
        let on_path = matches!(&self.path[0], Step::Field(f) if *f == key);
        self.pending = Some((on_path, value));
        seed.deserialize(key.into_deserializer()).map(Some)
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(
        &mut self,
        seed: V,
    ) -> Result<V::Value, SpliceError> {
        let (on_path, value) = self
            .pending
            .take()
            .ok_or_else(|| SpliceError("a value without a key".into()))?;
        seed.deserialize(Splice {
            value,
            path: on_path.then(|| &self.path[1..]),
            whole: self.whole,
            raw: self.raw,
        })
    }
}

struct SpliceSeq<'a, 'de> {
    items: std::iter::Enumerate<std::vec::IntoIter<Value>>,
    path: &'a [Step],
    whole: &'a [Step],
    raw: &'de str,
}

impl<'de> de::SeqAccess<'de> for SpliceSeq<'_, 'de> {
    type Error = SpliceError;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, SpliceError> {
        let Some((i, value)) = self.items.next() else {
            return Ok(None);
        };
        let on_path = self.path[0] == Step::Index(i);
        seed.deserialize(Splice {
            value,
            path: on_path.then(|| &self.path[1..]),
            whole: self.whole,
            raw: self.raw,
        })
        .map(Some)
    }
}

struct SpliceEnum<'a, 'de> {
    variant: String,
    inner: Splice<'a, 'de>,
}

impl<'a, 'de> de::EnumAccess<'de> for SpliceEnum<'a, 'de> {
    type Error = SpliceError;
    type Variant = Splice<'a, 'de>;

    fn variant_seed<V: DeserializeSeed<'de>>(
        self,
        seed: V,
    ) -> Result<(V::Value, Splice<'a, 'de>), SpliceError> {
        let v = seed.deserialize(self.variant.into_deserializer())?;
        Ok((v, self.inner))
    }
}

impl<'de> de::VariantAccess<'de> for Splice<'_, 'de> {
    type Error = SpliceError;

    fn unit_variant(self) -> Result<(), SpliceError> {
        Err(SpliceError("this variant has no fields".into()))
    }

    fn newtype_variant_seed<T: DeserializeSeed<'de>>(
        self,
        seed: T,
    ) -> Result<T::Value, SpliceError> {
        seed.deserialize(self)
    }

    fn tuple_variant<V: Visitor<'de>>(
        self,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, SpliceError> {
        self.deserialize_tuple(len, visitor)
    }

    fn struct_variant<V: Visitor<'de>>(
        self,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, SpliceError> {
        self.deserialize_struct("", fields, visitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn earth() -> SceneDesc {
        crate::scene::parse_preset(
            include_str!("../../presets/earth.ron"),
            std::path::Path::new("presets/earth.ron"),
        )
        .expect("earth")
    }

    #[test]
    fn paths_parse_and_print() {
        let steps = parse_path("objects[0].material.cd.mapping").unwrap();
        assert_eq!(steps.len(), 5);
        assert_eq!(path_text(&steps), "objects[0].material.cd.mapping");
        assert!(parse_path("").unwrap_err().contains("empty"));
        assert!(
            parse_path("objects[x]")
                .unwrap_err()
                .contains("`[x]` is not an index")
        );
        assert!(parse_path("a..b").unwrap_err().contains("empty name"));
        assert!(
            parse_path("camera.ey e")
                .unwrap_err()
                .contains("not a field name")
        );
    }

    #[test]
    fn an_edit_to_another_format_version_is_refused_as_the_preset_reader_refuses_it() {
        let e = set_path(&earth(), "version", "7").unwrap_err();
        assert!(
            e.contains("`version` = 7: version 7 is not supported (this texplore reads version 1)"),
            "{e}"
        );
        assert!(set_path(&earth(), "version", "1").is_ok());
    }

    #[test]
    fn a_unit_variant_deep_in_an_enum_is_set() {
        let d = set_path(&earth(), "objects[0].material.cd.mapping", "Cylindrical").unwrap();
        assert_eq!(
            d.objects[0].material.texture().mapping(),
            Some(&crate::mapping::Mapping::Cylindrical.into())
        );
        // Nothing else changed.
        let mut back = d.clone();
        back.objects[0]
            .material
            .texture_mut()
            .set_mapping(crate::mapping::Mapping::Spherical.into());
        assert_eq!(back, earth());
    }

    #[test]
    fn points_numbers_whole_variants_and_defaulted_fields_are_set() {
        let d = set_path(&earth(), "camera.eye", "(0, 0, 1.5)").unwrap();
        assert_eq!(d.camera.eye, crate::math::Vec3::new(0.0, 0.0, 1.5));
        let d = set_path(&earth(), "camera.eye[2]", "2.5").unwrap();
        assert_eq!(d.camera.eye.z, 2.5);
        let d = set_path(
            &earth(),
            "objects[0].material.cd",
            "Constant((0.2, 0.4, 0.8))",
        )
        .unwrap();
        assert_eq!(
            value_at(&d, "objects[0].material.cd"),
            Some(serde_json::json!({"Constant": [0.2f32, 0.4f32, 0.8f32]}))
        );
        // `lookup` is not written in the preset (it is at its default) but is a field.
        let d = set_path(&earth(), "objects[0].material.cd.lookup", "Lecture").unwrap();
        assert_eq!(
            value_at(&d, "objects[0].material.cd.lookup"),
            Some(serde_json::json!("Lecture"))
        );
        let d = set_path(&earth(), "render.adaptive", "Some((max_spp: 64))").unwrap();
        assert_eq!(d.render.adaptive.map(|a| a.max_spp), Some(64));
        let d = set_path(&earth(), "objects[0].casts_shadows", "Some(false)").unwrap();
        assert_eq!(d.objects[0].casts_shadows, Some(false));
    }

    #[test]
    fn hostile_paths_and_values_are_errors_not_panics() {
        let deep = format!("{}1{}", "(".repeat(10_000), ")".repeat(10_000));
        for (path, value) in [
            ("[0]", "1"),
            ("objects[0", "1"),
            ("objects]0[", "1"),
            ("objects[0]]", "1"),
            (".", "1"),
            ("objects[18446744073709551616]", "1"),
            ("camera..eye", "1"),
            ("camera.eye", ""),
            ("camera.eye", "\"unterminated"),
            ("camera.eye", deep.as_str()),
            ("objects[0].material.cd.path", "\"\u{0}\""),
            ("render.spp", "0"),
            ("render.spp", "-1"),
            ("objects", "[]"),
        ] {
            // Either a clear error or a description that still checks out; never a panic.
            if let Ok(d) = set_path(&earth(), path, value) {
                assert!(check_numbers(&d).is_ok(), "{path} = {value}");
            }
        }
        assert!(set_path(&earth(), "camera.eye", &deep).is_err());
    }

    #[test]
    fn paths_and_values_that_do_not_fit_say_why() {
        let e = set_path(&earth(), "objects[3].material", "Constant((1, 1, 1))").unwrap_err();
        assert!(
            e.contains("`objects` has 1 item(s), so [3] is not one of them"),
            "{e}"
        );
        let e = set_path(&earth(), "objects[0].material.cd.maping", "Cylindrical").unwrap_err();
        assert!(
            e.contains("`objects[0].material.cd` has no field `maping` (it has path, mapping,"),
            "{e}"
        );
        // A field left at its default is reached all the same, and a name a type does not
        // have is refused by that type, even below a default.
        let d = set_path(&earth(), "render.compare.tolerance", "1000000").expect("a default");
        assert_eq!(d.render.compare.tolerance, 1e6);
        let e = set_path(&earth(), "render.compare.tolerence", "2").unwrap_err();
        assert!(
            e.contains("`render.compare` has no field `tolerence`"),
            "{e}"
        );
        let e = set_path(&earth(), "render.compar.tolerance", "2").unwrap_err();
        assert!(e.contains("`render` has no field `compar`"), "{e}");
        let e = set_path(&earth(), "camera.eyes.x", "1").unwrap_err();
        assert!(
            e.contains("the scene") || e.contains("`camera` has no field `eyes`"),
            "{e}"
        );
        let e = set_path(&earth(), "objects[0].material.cd.mapping", "Cylindric").unwrap_err();
        assert!(e.contains("Cylindric"), "{e}");
        let e = set_path(&earth(), "camera.eye", "(0, 1)").unwrap_err();
        assert!(e.starts_with("`camera.eye` = (0, 1): "), "{e}");
        let e = set_path(&earth(), "objects[0].shape.radius", "2").unwrap_err();
        assert!(
            e.contains("`objects[0].shape` is `Sphere`, which has no field `radius`"),
            "{e}"
        );
        let e = set_path(&earth(), "render.spp", "8 9").unwrap_err();
        assert!(e.contains("render.spp"), "{e}");
        let e = set_path(&earth(), "ambient.ls", "inf").unwrap_err();
        assert!(e.contains("not finite"), "{e}");
    }
}
