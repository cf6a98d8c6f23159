//! Where a value sits in a scene description: one path type ([`FieldPath`],
//! `objects[0].material.cd.mapping`) names fields in errors, in lesson edits and in the window.

use std::fmt;

/// One step of a [`FieldPath`]: a field (or enum variant) name, or an index into a list.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Step {
    /// `.name`
    Field(String),
    /// `[n]`
    Index(usize),
}

impl fmt::Display for Step {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Field(name) => f.write_str(name),
            Self::Index(i) => write!(f, "[{i}]"),
        }
    }
}

/// A path into a scene description, written as a preset reads: fields joined by dots, list
/// items in brackets (`objects[0].material.ka`, `lights[1].color`). The empty path is the
/// description itself.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct FieldPath(Vec<Step>);

impl FieldPath {
    /// The description itself (no step).
    #[must_use]
    pub const fn root() -> Self {
        Self(Vec::new())
    }

    /// The path of one field (`FieldPath::field("camera")` is `camera`).
    #[must_use]
    pub fn field(name: &str) -> Self {
        Self::root().then(name)
    }

    /// This path followed by field `name`.
    #[must_use]
    pub fn then(mut self, name: &str) -> Self {
        self.0.push(Step::Field(name.to_owned()));
        self
    }

    /// This path followed by list item `i`.
    #[must_use]
    pub fn at(mut self, i: usize) -> Self {
        self.0.push(Step::Index(i));
        self
    }

    /// This path followed by every step of `rest`.
    #[must_use]
    pub fn join(mut self, rest: &Self) -> Self {
        self.0.extend(rest.0.iter().cloned());
        self
    }

    /// The steps, first to last.
    #[must_use]
    pub fn steps(&self) -> &[Step] {
        &self.0
    }

    /// The last field name on the path (`ka` of `objects[0].material.ka`), if any.
    #[must_use]
    pub fn last_field(&self) -> Option<&str> {
        self.0.iter().rev().find_map(|s| match s {
            Step::Field(name) => Some(name.as_str()),
            Step::Index(_) => None,
        })
    }

    /// The object the path is in (`2` for `objects[2].material.ka`), if it starts in one.
    #[must_use]
    pub fn object(&self) -> Option<usize> {
        match self.0.as_slice() {
            [Step::Field(list), Step::Index(i), ..] if list == "objects" => Some(*i),
            _ => None,
        }
    }

    /// Reads `objects[0].material.cd.mapping`.
    ///
    /// # Errors
    /// An empty path, an empty name (`a..b`), or a bad index (`objects[x]`), with the reason.
    pub fn parse(path: &str) -> Result<Self, String> {
        let mut steps = Vec::new();
        if path.trim().is_empty() {
            return Err("the path is empty".into());
        }
        for part in path.split('.') {
            let (name, mut rest) = part.find('[').map_or((part, ""), |i| part.split_at(i));
            let name = name.trim();
            if !name.is_empty() {
                if !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
                    return Err(format!("`{name}` in `{path}` is not a field name"));
                }
                steps.push(Step::Field(name.to_owned()));
            } else if rest.is_empty() || steps.is_empty() && !rest.is_empty() {
                return Err(format!("`{path}` has an empty name"));
            }
            while !rest.is_empty() {
                let Some(close) = rest.find(']').filter(|_| rest.starts_with('[')) else {
                    return Err(format!("`{path}`: expected `[number]` after `{name}`"));
                };
                let index = rest[1..close].trim();
                let i = index
                    .parse::<usize>()
                    .map_err(|_| format!("`{path}`: `[{index}]` is not an index (0, 1, 2, ...)"))?;
                steps.push(Step::Index(i));
                rest = &rest[close + 1..];
            }
        }
        Ok(Self(steps))
    }
}

/// A field as every message names it: its path, then the object it is in when that object has
/// a name, `objects[0].material.ka (object "Ball")`. The path comes first and alone, so it can be
/// copied into a lesson edit as it is; an empty or missing name adds nothing.
#[must_use]
pub fn field_name(path: &FieldPath, object: Option<&str>) -> String {
    match object.filter(|n| !n.is_empty()) {
        Some(name) => format!("{path} (object {name:?})"),
        None => path.to_string(),
    }
}

/// A value refused: the field (relative to what was checked; the caller puts its own path in
/// front with [`Refusal::under`]) and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal {
    /// The field.
    pub field: FieldPath,
    /// Why (`-1 must be finite and not negative`).
    pub message: String,
}

impl Refusal {
    /// Field `field` is refused for `message`.
    #[must_use]
    pub fn new(field: FieldPath, message: impl Into<String>) -> Self {
        Self {
            field,
            message: message.into(),
        }
    }

    /// The same refusal, its field below `prefix`.
    #[must_use]
    pub fn under(self, prefix: &FieldPath) -> Self {
        Self {
            field: prefix.clone().join(&self.field),
            message: self.message,
        }
    }
}

impl fmt::Display for Refusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.field.steps().is_empty() {
            f.write_str(&self.message)
        } else {
            write!(f, "{}: {}", self.field, self.message)
        }
    }
}

impl From<Refusal> for String {
    fn from(r: Refusal) -> Self {
        r.to_string()
    }
}

/// The path of one field (`"ka".into()` is `ka`).
impl From<&str> for FieldPath {
    fn from(name: &str) -> Self {
        Self::field(name)
    }
}

impl From<Vec<Step>> for FieldPath {
    fn from(steps: Vec<Step>) -> Self {
        Self(steps)
    }
}

impl fmt::Display for FieldPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, step) in self.0.iter().enumerate() {
            if matches!(step, Step::Field(_)) && i > 0 {
                f.write_str(".")?;
            }
            write!(f, "{step}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_read_and_write_back() {
        for text in [
            "objects[0].material.cd.mapping",
            "lights[1].color",
            "camera",
            "a[0][2].b",
        ] {
            assert_eq!(FieldPath::parse(text).expect(text).to_string(), text);
        }
        let built = FieldPath::field("objects")
            .at(2)
            .then("material")
            .then("ka");
        assert_eq!(built.to_string(), "objects[2].material.ka");
        assert_eq!(built.last_field(), Some("ka"));
        for bad in ["", "a..b", "objects[x]", "[0]", "a b"] {
            assert!(FieldPath::parse(bad).is_err(), "{bad}");
        }
    }
}
