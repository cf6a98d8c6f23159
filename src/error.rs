//! The library's error type: every error names the file it is about and, where a parser stopped,
//! the position.

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
    /// own error (`p.ron: objects[0] (Earth).material: earth.jpg: No such file or directory`).
    #[error("{}: {field}: {cause}", path.display())]
    InField {
        /// The preset.
        path: PathBuf,
        /// The field, as a lesson's path spells it (`objects[0].material`).
        field: String,
        /// The asset's error (kept out of the error chain: the message already includes it).
        cause: Box<Error>,
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
    /// `cause` (an asset's error) as the error of `field` of the preset at `path`; an error
    /// that already names the preset and a field is returned as it is.
    #[must_use]
    pub fn in_field(path: &Path, field: impl Into<String>, cause: Self) -> Self {
        match cause {
            e @ (Self::InField { .. } | Self::Invalid { .. } | Self::Preset { .. }) => e,
            cause => Self::InField {
                path: path.to_path_buf(),
                field: field.into(),
                cause: Box::new(cause),
            },
        }
    }
}

/// The library's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
