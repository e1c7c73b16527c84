//! The error of a file that could not be loaded: `file: reason`, or
//! `file:line:col: field.path: message`. Its own module so that the RON
//! parser ([`super::ron`]) and the schema check ([`super::schema`]) both
//! produce it without importing each other.

use std::path::Path;

use thiserror::Error;

/// A scene or gains file that could not be loaded.
#[derive(Debug, Error)]
pub enum LoadError {
    /// The file could not be read.
    #[error("{file}: {reason}")]
    Io {
        /// The file.
        file: String,
        /// The OS error.
        reason: std::io::Error,
    },
    /// Syntax error, unknown field or invalid value.
    #[error("{file}:{line}:{col}: {field}: {message}")]
    Invalid {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        col: usize,
        /// Dotted path of the field (`timeline[2].do.Punch.speed`), or `-` for syntax errors.
        field: String,
        /// What is wrong.
        message: String,
    },
}

impl LoadError {
    /// What is wrong with `field` of `file`, at `line` and `col` (1-based):
    /// the one constructor of a located error.
    pub fn invalid(
        file: &Path,
        (line, col): (usize, usize),
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> LoadError {
        LoadError::Invalid {
            file: file.display().to_string(),
            line,
            col,
            field: field.into(),
            message: message.into(),
        }
    }

    /// What is wrong with `field` of `file`, placed where `field` is
    /// written in the file's `text` ([`super::locate::locate`]).
    pub fn at_field(
        file: &Path,
        text: &str,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> LoadError {
        let field = field.into();
        let at = super::locate::locate(text, &field);
        LoadError::invalid(file, at, field, message)
    }

    /// An unreadable file that another file names: reported at the naming
    /// file's `field` (its line and column), with the OS error once.
    pub fn named_by(self, file: &Path, text: &str, field: &str) -> LoadError {
        match self {
            LoadError::Io {
                file: missing,
                reason,
            } => LoadError::at_field(
                file,
                text,
                field,
                format!("cannot read {missing}: {reason}"),
            ),
            other => other,
        }
    }
}
