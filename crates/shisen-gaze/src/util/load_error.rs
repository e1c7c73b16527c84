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
    /// An unreadable file that another file names: reported at the naming
    /// file's `field` (its line and column), with the OS error once.
    pub fn named_by(self, file: &Path, text: &str, field: &str) -> LoadError {
        match self {
            LoadError::Io {
                file: missing,
                reason,
            } => {
                let (line, col) = super::locate::locate(text, field);
                LoadError::Invalid {
                    file: file.display().to_string(),
                    line,
                    col,
                    field: field.to_string(),
                    message: format!("cannot read {missing}: {reason}"),
                }
            }
            other => other,
        }
    }
}
