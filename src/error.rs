//! The library's error type: every error names the file it is about and, where a parser stopped,
//! the position.

use crate::field::{FieldPath, Refusal, field_name};
use std::path::{Path, PathBuf};

/// Why a preset, image or mesh could not be used.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The file could not be read or written.
    #[error("{}: {io}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the OS said (kept out of the error chain: the message already includes it).
        io: std::io::Error,
    },
    /// An output could not be written, or was refused before writing (see [`crate::output`]).
    #[error("cannot write {}: {reason}", path.display())]
    Write {
        /// The output as the user named it.
        path: PathBuf,
        /// Why: "it is a FIFO, not a regular file", "permission denied", ...
        reason: String,
    },
    /// An image could not be decoded or was refused by the decode limits.
    #[error("{}: cannot load image: {message}", path.display())]
    Image {
        /// The image file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// A preset did not parse: line and column (1-based) where parsing stopped.
    #[error("{}:{line}:{column}: {message}", path.display())]
    Preset {
        /// The preset file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What was expected.
        message: String,
    },
    /// A mesh file could not be read: `at` says where (line or byte, and which element).
    #[error("{}: {at}: {message}", path.display())]
    Mesh {
        /// The mesh file.
        path: PathBuf,
        /// Where parsing stopped: `line 14 (face 1)`, `byte 812 (vertex 3)`, `header line 4`.
        at: String,
        /// What was wrong or expected.
        message: String,
    },
    /// A file a preset's field names could not be used: the preset, the field, and the file's
    /// own error (`p.ron: objects[0].material.kd (object "Earth"): earth.jpg: No such file or
    /// directory`).
    #[error("{}: {}: {cause}", path.display(), field_name(field, object.as_deref()))]
    InField {
        /// The preset.
        path: PathBuf,
        /// The field, as a lesson's path spells it (`objects[0].material.kd`).
        field: FieldPath,
        /// The name of the object the field is in, if it has one (said after the path).
        object: Option<String>,
        /// The asset's error (kept out of the error chain: the message already includes it).
        cause: Box<Error>,
    },
    /// A preset's field holds a value out of range or inconsistent: the preset, the field and
    /// why (`p.ron: objects[0].material.kd (object "Ball"): -1 must be finite and not negative`).
    #[error("{}: {}: {message}", path.display(), field_name(field, object.as_deref()))]
    InvalidField {
        /// The preset.
        path: PathBuf,
        /// The field, as a lesson's path spells it.
        field: FieldPath,
        /// The name of the object the field is in, if it has one (said after the path).
        object: Option<String>,
        /// Why.
        message: String,
    },
    /// A value is out of range or inconsistent (a zero scale, spp = 0, an absurd resolution).
    #[error("{}: {message}", path.display())]
    Invalid {
        /// The file the value came from.
        path: PathBuf,
        /// Which value, and why.
        message: String,
    },
}

impl Error {
    /// An [`Error::Io`] for `path`.
    #[must_use]
    pub fn io(path: &Path, io: std::io::Error) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            io,
        }
    }

    /// An [`Error::Invalid`] for `path`.
    #[must_use]
    pub fn invalid(path: &Path, message: impl Into<String>) -> Self {
        Self::Invalid {
            path: path.to_path_buf(),
            message: message.into(),
        }
    }
}

impl Error {
    /// An [`Error::InvalidField`]: `refusal`'s field of the preset at `path`.
    #[must_use]
    pub fn refused(path: &Path, refusal: Refusal) -> Self {
        Self::InvalidField {
            path: path.to_path_buf(),
            field: refusal.field,
            object: None,
            message: refusal.message,
        }
    }

    /// This error, met below field `prefix` of the preset at `path`: a field's error has
    /// `prefix` put in front of its field; an asset's error (a file that cannot be read, or
    /// whose content is refused) becomes the error of `prefix`; a preset's parse error is
    /// returned as it is.
    #[must_use]
    pub fn under(self, path: &Path, prefix: &FieldPath) -> Self {
        let path = path.to_path_buf();
        match self {
            Self::InField {
                field,
                object,
                cause,
                ..
            } => Self::InField {
                path,
                field: prefix.clone().join(&field),
                object,
                cause,
            },
            Self::InvalidField {
                field,
                object,
                message,
                ..
            } => Self::InvalidField {
                path,
                field: prefix.clone().join(&field),
                object,
                message,
            },
            e @ Self::Preset { .. } => e,
            cause => Self::InField {
                path,
                field: prefix.clone(),
                object: None,
                cause: Box::new(cause),
            },
        }
    }

    /// This error, its field (if it names one) said to be in the object named `name` (none
    /// for an unnamed object).
    #[must_use]
    pub fn in_object(mut self, name: &str) -> Self {
        if let Self::InField { object, .. } | Self::InvalidField { object, .. } = &mut self {
            *object = (!name.is_empty()).then(|| name.to_owned());
        }
        self
    }

    /// The field the error names, if any.
    #[must_use]
    pub const fn field(&self) -> Option<&FieldPath> {
        match self {
            Self::InField { field, .. } | Self::InvalidField { field, .. } => Some(field),
            _ => None,
        }
    }
}

/// The library's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
