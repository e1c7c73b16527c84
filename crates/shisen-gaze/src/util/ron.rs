//! Reading RON files: one parser that produces the error naming
//! `file:line:col: field.path` ([`LoadError`], defined in
//! [`super::load_error`] and re-exported here), and one way to read a
//! file's text.

use std::path::Path;

use schemars::JsonSchema;
use serde::Serialize;
use serde::de::DeserializeOwned;

pub use super::load_error::LoadError;

/// Parse RON text into `T`, reporting the file, line, column and field path,
/// and check every value against the range its type documents
/// ([`super::schema::check`]).
pub fn parse_ron<T: DeserializeOwned + Serialize + JsonSchema>(
    text: &str,
    file: &Path,
) -> Result<T, LoadError> {
    let value = parse_unchecked(text, file)?;
    super::schema::check(&value, text, file)?;
    Ok(value)
}

/// Parse RON text into `T` with only the checks its `Deserialize` makes.
fn parse_unchecked<T: DeserializeOwned>(text: &str, file: &Path) -> Result<T, LoadError> {
    let invalid = |line, col, field: String, message: String| {
        LoadError::invalid(file, (line, col), field, message)
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
            let unread = path.ends_with('?');
            let field = path.trim_end_matches('?').trim_end_matches('.');
            let field = match (field.is_empty(), key_before(text, line, col)) {
                (true, Some(key)) => key,
                (true, None) => "-".to_string(),
                // The parser stopped inside a value whose key it had not
                // yet named: the nearest key written before the error.
                (false, Some(key))
                    if unread && !field.ends_with(&format!(".{key}")) && field != key =>
                {
                    format!("{field}.{key}")
                }
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

/// The last `key` written `key:` on line `line` before column `col`, if
/// any (the field a syntax error is in).
fn key_before(text: &str, line: usize, col: usize) -> Option<String> {
    let l = text.lines().nth(line.saturating_sub(1))?;
    let before: String = l.chars().take(col.saturating_sub(1)).collect();
    let colon = before.rfind(':')?;
    let head = before[..colon].trim_end();
    let start = head
        .char_indices()
        .rfind(|&(_, c)| !(c.is_ascii_alphanumeric() || c == '_'))
        .map_or(0, |(i, c)| i + c.len_utf8());
    let key = &head[start..];
    (!key.is_empty() && key.starts_with(|c: char| c.is_ascii_lowercase() || c == '_'))
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

/// Read a whole text file, mapping failure to [`LoadError::Io`] naming it.
/// (The OS error is the message, not a `source`, so a chain of errors
/// prints it once.)
pub fn read_text(path: &Path) -> Result<String, LoadError> {
    read_text_up_to(path, MAX_INPUT_BYTES)
}

/// [`read_text`] of a file that may be up to `max` bytes (traces and
/// results tables, which are data rather than settings).
pub fn read_text_up_to(path: &Path, max: u64) -> Result<String, LoadError> {
    use std::io::Read;
    let fail = |reason| LoadError::Io {
        file: path.display().to_string(),
        reason,
    };
    let bad = |m: String| fail(std::io::Error::new(std::io::ErrorKind::InvalidData, m));
    // A device or pipe (`/dev/zero`, a FIFO) would be read (or opened)
    // forever, and a file larger than any input is not one.
    if !std::fs::metadata(path).map_err(fail)?.is_file() {
        return Err(bad("not a regular file".into()));
    }
    let file = std::fs::File::open(path).map_err(fail)?;
    let mut text = String::new();
    file.take(max + 1).read_to_string(&mut text).map_err(fail)?;
    if text.len() as u64 > max {
        return Err(bad(format!("larger than {} MiB", max >> 20)));
    }
    Ok(text)
}

/// Largest input text file read (scenes, gains, studies, databases,
/// landmarks, bindings, scripts): 16 MiB, far beyond any real one.
pub const MAX_INPUT_BYTES: u64 = 16 << 20;
