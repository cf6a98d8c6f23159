//! The check that every number of a preset is finite, naming the field: one walk over the
//! description through its own `Serialize`, so a field added to the format is checked without
//! being listed anywhere.
//!
//! The walk is a serde [`Serializer`] that writes nothing: it keeps the path to the value it is
//! at (`objects[2].material.cd.scale`) and looks at every `f32` and `f64`. Written by hand
//! because it is the format's own rule (which steps a path names, which it leaves out), not a
//! data format a crate provides.

use super::SceneDesc;
use crate::field::{FieldPath, Refusal, Step};
use serde::Serialize;
use serde::ser::{self, Serializer};
use std::fmt;

/// Refuses a preset holding a NaN or an infinity anywhere (every `f32`, point and colour),
/// naming the field (`ambient.color`: `NaN is not a number`, `objects[2].material.cd.scale`:
/// `inf is not finite`; [`SceneDesc::refusal_message`] writes it as a message). A point or colour is named whole
/// (`camera.eye`), a list item by its index. Ranges are checked by
/// [`build_scene`](super::build_scene); this check needs no files, so it also guards every
/// preset written out (a saved preset or the one a PNG carries never holds a value that does
/// not read back).
///
/// # Errors
/// The first field that is not a finite number.
pub fn check_numbers(desc: &SceneDesc) -> std::result::Result<(), Refusal> {
    let mut walk = Walk::default();
    match desc.serialize(&mut walk) {
        Err(Stop::NotFinite(path, v)) => Err(Refusal::new(path, not_finite(v))),
        Err(Stop::Custom(m)) => Err(Refusal::new(FieldPath::root(), m)),
        Ok(()) => Ok(()),
    }
}

/// Why a non-finite number is refused.
fn not_finite(v: f64) -> String {
    if v.is_nan() {
        "NaN is not a number".into()
    } else {
        format!("{} is not finite", v as f32)
    }
}

/// Where the walk is: the steps to the value, each marked when it is a component of a tuple
/// (a point or colour, named whole in messages).
#[derive(Default)]
struct Walk {
    steps: Vec<(Step, bool)>,
}

impl Walk {
    /// The path a message names: components of a point or colour left out.
    fn named(&self) -> FieldPath {
        FieldPath::from(
            self.steps
                .iter()
                .filter(|(_, component)| !component)
                .map(|(s, _)| s.clone())
                .collect::<Vec<_>>(),
        )
    }

    fn number(&mut self, v: f64) -> Result<(), Stop> {
        if v.is_finite() {
            Ok(())
        } else {
            Err(Stop::NotFinite(self.named(), v))
        }
    }

    /// Serialises `value` one step further down.
    fn down<T: Serialize + ?Sized>(
        &mut self,
        step: Step,
        component: bool,
        value: &T,
    ) -> Result<(), Stop> {
        self.steps.push((step, component));
        let r = value.serialize(&mut *self);
        self.steps.pop();
        r
    }
}

/// What ends the walk early.
#[derive(Debug)]
enum Stop {
    /// The first number that is not finite, at the path a message names.
    NotFinite(FieldPath, f64),
    /// A value's own `Serialize` failed.
    Custom(String),
}

impl fmt::Display for Stop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite(path, v) => write!(f, "{path}: {}", not_finite(*v)),
            Self::Custom(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for Stop {}

impl ser::Error for Stop {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Self::Custom(msg.to_string())
    }
}

/// A list, tuple, struct or map being walked: its items become steps.
struct Compound<'a> {
    walk: &'a mut Walk,
    /// The next item's index (lists and tuples).
    next: usize,
    /// Whether items are components of one value (a tuple: a point or colour).
    components: bool,
}

impl Compound<'_> {
    fn item<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Stop> {
        let i = self.next;
        self.next += 1;
        self.walk.down(Step::Index(i), self.components, value)
    }
}

macro_rules! items {
    ($($trait:ident :: $method:ident),*) => {$(
        impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = Stop;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Stop> {
                self.item(value)
            }
            fn end(self) -> Result<(), Stop> {
                Ok(())
            }
        }
    )*};
}
items!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

macro_rules! fields {
    ($($trait:ident),*) => {$(
        impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = Stop;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), Stop> {
                self.walk.down(Step::Field(key.to_owned()), false, value)
            }
            fn end(self) -> Result<(), Stop> {
                Ok(())
            }
        }
    )*};
}
fields!(SerializeStruct, SerializeStructVariant);

impl ser::SerializeMap for Compound<'_> {
    type Ok = ();
    type Error = Stop;
    // A map's keys are not numbers of the scene; its values are walked as list items.
    fn serialize_key<T: Serialize + ?Sized>(&mut self, _key: &T) -> Result<(), Stop> {
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Stop> {
        self.item(value)
    }
    fn end(self) -> Result<(), Stop> {
        Ok(())
    }
}

macro_rules! leaves {
    ($($method:ident: $t:ty),*) => {$(
        fn $method(self, _: $t) -> Result<(), Stop> {
            Ok(())
        }
    )*};
}

impl<'a> Serializer for &'a mut Walk {
    type Ok = ();
    type Error = Stop;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = Compound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    leaves!(
        serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32,
        serialize_i64: i64, serialize_u8: u8, serialize_u16: u16, serialize_u32: u32,
        serialize_u64: u64, serialize_char: char, serialize_str: &str, serialize_bytes: &[u8],
        serialize_unit_struct: &'static str
    );

    fn serialize_f32(self, v: f32) -> Result<(), Stop> {
        self.number(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Result<(), Stop> {
        self.number(v)
    }
    fn serialize_none(self) -> Result<(), Stop> {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), Stop> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), Stop> {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Result<(), Stop> {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<(), Stop> {
        value.serialize(self)
    }
    // A variant's name is not a step: `material.ka`, not `material.Phong.ka`.
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        value: &T,
    ) -> Result<(), Stop> {
        value.serialize(self)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Compound<'a>, Stop> {
        Ok(self.compound(false))
    }
    fn serialize_tuple(self, _: usize) -> Result<Compound<'a>, Stop> {
        Ok(self.compound(true))
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, Stop> {
        Ok(self.compound(true))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, Stop> {
        Ok(self.compound(true))
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Compound<'a>, Stop> {
        Ok(self.compound(false))
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, Stop> {
        Ok(self.compound(false))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, Stop> {
        Ok(self.compound(false))
    }
}

impl Walk {
    const fn compound(&mut self, components: bool) -> Compound<'_> {
        Compound {
            walk: self,
            next: 0,
            components,
        }
    }
}
