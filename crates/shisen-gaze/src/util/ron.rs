//! Reading RON files: one error type that names `file:line:col: field.path`,
//! one parser that produces it, and one way to read a file's text.

use std::path::Path;

use serde::de::DeserializeOwned;
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

/// Parse RON text into `T`, reporting the file, line, column and field path.
pub fn parse_ron<T: DeserializeOwned>(text: &str, file: &Path) -> Result<T, LoadError> {
    let file_s = file.display().to_string();
    let invalid = |line, col, field: String, message: String| LoadError::Invalid {
        file: file_s.clone(),
        line,
        col,
        field,
        message,
    };
    // Optional fields are written plainly (`gains: Gains(...)`, not `Some(...)`).
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let mut de = ron::Deserializer::from_str_with_options(text, &options).map_err(|e| {
        invalid(
            e.span.start.line,
            e.span.start.col,
            "-".into(),
            e.code.to_string(),
        )
    })?;
    let value = match serde_path_to_error::deserialize::<_, T>(&mut de) {
        Ok(v) => v,
        Err(err) => {
            let path = err.path().to_string();
            let spanned = de.span_error(err.into_inner());
            let (line, col) = (spanned.span.start.line, spanned.span.start.col);
            // The path ends in `?` where the parser had not yet read a field
            // name (a syntax error): name the enclosing field instead.
            let field = path.trim_end_matches('?').trim_end_matches('.');
            let field = match (field.is_empty(), key_on_line(text, line)) {
                (true, Some(key)) => key,
                (true, None) => "-".to_string(),
                (false, _) => field.to_string(),
            };
            let message = explain(&spanned.code.to_string(), text, line, col);
            return Err(invalid(line, col, field, message));
        }
    };
    de.end().map_err(|e| {
        let s = de.span_error(e);
        invalid(
            s.span.start.line,
            s.span.start.col,
            "-".into(),
            s.code.to_string(),
        )
    })?;
    Ok(value)
}

/// The `key` of a line written `key: value`, if it is one.
fn key_on_line(text: &str, line: usize) -> Option<String> {
    let l = text.lines().nth(line.saturating_sub(1))?.trim_start();
    let (key, _) = l.split_once(':')?;
    (!key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
        .then(|| key.to_string())
}

/// A parser message with a hint where the usual cause is plain: a
/// fraction where a whole number belongs (`seed: 1.5` reads `1`, then
/// trips on `.5`), or a bracket left open on the line before.
fn explain(message: &str, text: &str, line: usize, col: usize) -> String {
    let rest = text
        .lines()
        .nth(line.saturating_sub(1))
        .and_then(|l| l.get(col.saturating_sub(1)..))
        .unwrap_or("");
    if message == "Expected comma" && rest.starts_with('.') {
        return format!("{message}: a whole number is expected here, not a fraction");
    }
    if message.starts_with("Expected identifier") || message.starts_with("Unexpected closing") {
        return format!("{message} (is a `)` or `]` missing before this?)");
    }
    message.to_string()
}

/// 1-based line of the first occurrence of `needle` in `text` (for errors
/// found after parsing, such as a reference to an undeclared body).
pub fn line_of(text: &str, needle: &str) -> (usize, usize) {
    match text.find(needle) {
        Some(pos) => {
            let before = &text[..pos];
            let line = before.matches('\n').count() + 1;
            let col = pos - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            (line, col)
        }
        None => (1, 1),
    }
}

/// Read a whole text file, mapping failure to [`LoadError::Io`] naming it.
/// (The OS error is the message, not a `source`, so a chain of errors
/// prints it once.)
pub fn read_text(path: &Path) -> Result<String, LoadError> {
    std::fs::read_to_string(path).map_err(|e| LoadError::Io {
        file: path.display().to_string(),
        reason: e,
    })
}

impl LoadError {
    /// An unreadable file that another file names: reported at the naming
    /// file's `line:col` and `field`, with the OS error once.
    pub fn named_by(self, file: &Path, text: &str, needle: &str, field: &str) -> LoadError {
        match self {
            LoadError::Io {
                file: missing,
                reason,
            } => {
                let (line, col) = line_of(text, needle);
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
