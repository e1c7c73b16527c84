//! Remappable bindings of keys, mouse buttons and gamepad controls to
//! [`Command`]s, stored as RON. The defaults are embedded
//! (`src/input/bindings.ron`); a user file replaces them.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use eframe::egui;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::command::{Command, PadButton, Stick, Trigger};
use shisen_gaze::util::ron::LoadError;

/// The embedded default bindings.
pub const DEFAULT_BINDINGS_RON: &str = include_str!("bindings.ron");

/// Mouse button bindings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MouseBindings {
    /// Primary button.
    pub left: Option<Command>,
    /// Secondary button.
    pub right: Option<Command>,
    /// Middle button.
    pub middle: Option<Command>,
}

/// Which analog control moves what.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PadAxes {
    /// Stick moving your left glove in the plane in front of you.
    pub left_glove: Stick,
    /// Stick moving your right glove.
    pub right_glove: Stick,
    /// Trigger pushing your left glove forward (analog depth).
    pub left_throw: Trigger,
    /// Trigger pushing your right glove forward.
    pub right_throw: Trigger,
    /// Stick deflection below this is ignored, as a share of full
    /// deflection (0-0.9: a larger dead zone leaves no travel).
    #[schemars(range(min = 0.0, max = 0.9))]
    pub dead_zone: f32,
}

/// All bindings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Bindings {
    /// Key name (egui's: `A`, `ArrowLeft`, `Space`, `F1`, ...) to command;
    /// each key once.
    #[serde(deserialize_with = "shisen_gaze::util::check::unique_keys")]
    pub keys: BTreeMap<String, Command>,
    /// Mouse buttons.
    pub mouse: MouseBindings,
    /// Gamepad buttons, each once.
    #[serde(deserialize_with = "shisen_gaze::util::check::unique_keys")]
    pub pad_buttons: BTreeMap<PadButton, Command>,
    /// Gamepad sticks and triggers.
    pub pad_axes: PadAxes,
}

/// Errors of reading bindings.
#[derive(Debug, thiserror::Error)]
pub enum BindingsError {
    /// The file did not parse.
    #[error(transparent)]
    Parse(#[from] LoadError),
    /// A key name egui does not know.
    #[error("{file}: unknown key name {name:?} (use egui's names: A, ArrowLeft, Space, F1, ...)")]
    UnknownKey {
        /// File.
        file: String,
        /// The name.
        name: String,
    },
}

impl Default for Bindings {
    fn default() -> Self {
        Bindings::parse(DEFAULT_BINDINGS_RON, Path::new("<embedded bindings.ron>"))
            .expect("embedded bindings are valid")
    }
}

impl Bindings {
    /// Parse and check bindings text.
    pub fn parse(text: &str, file: &Path) -> Result<Bindings, BindingsError> {
        let b: Bindings = shisen_gaze::util::ron::parse_ron(text, file)?;
        if let Some(name) = b.keys.keys().find(|k| egui::Key::from_name(k).is_none()) {
            return Err(BindingsError::UnknownKey {
                file: file.display().to_string(),
                name: name.clone(),
            });
        }
        Ok(b)
    }

    /// Read a bindings file.
    pub fn load(path: &Path) -> Result<Bindings, BindingsError> {
        let text = shisen_gaze::util::ron::read_text(path)?;
        Self::parse(&text, path)
    }

    /// The user's bindings file: `$XDG_CONFIG_HOME/shisen/bindings.ron`
    /// (or `~/.config/shisen/bindings.ron`).
    pub fn user_path() -> Option<PathBuf> {
        let base = std::env::var_os("XDG_CONFIG_HOME")
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
            .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")))?;
        Some(base.join("shisen").join("bindings.ron"))
    }

    /// `explicit` if given (errors if unreadable), else the user's file if
    /// it exists, else the defaults.
    pub fn resolve(explicit: Option<&Path>) -> Result<Bindings, BindingsError> {
        if let Some(p) = explicit {
            return Self::load(p);
        }
        match Self::user_path().filter(|p| p.exists()) {
            Some(p) => Self::load(&p),
            None => Ok(Bindings::default()),
        }
    }

    /// The commands bound to `key`.
    pub fn key_command(&self, key: egui::Key) -> Option<Command> {
        self.keys.get(key.name()).copied()
    }

    /// The RON text of these bindings (for writing a user file).
    pub fn to_ron(&self) -> String {
        let config = ron::ser::PrettyConfig::default()
            .struct_names(true)
            .extensions(ron::extensions::Extensions::IMPLICIT_SOME);
        ron::ser::to_string_pretty(self, config).expect("bindings serialise")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_parse_and_round_trip() {
        let b = Bindings::default();
        assert_eq!(b.key_command(egui::Key::A), Some(Command::DodgeLeft));
        assert_eq!(b.mouse.left, Some(Command::ThrowLeft));
        let again = Bindings::parse(&b.to_ron(), Path::new("x.ron")).unwrap();
        assert_eq!(again, b);
    }

    #[test]
    fn a_dead_zone_past_its_range_is_refused() {
        let text = DEFAULT_BINDINGS_RON.replacen("dead_zone: 0.12", "dead_zone: 0.95", 1);
        assert_ne!(text, DEFAULT_BINDINGS_RON);
        let e = Bindings::parse(&text, Path::new("b.ron"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("pad_axes.dead_zone"), "{e}");
    }

    #[test]
    fn unknown_keys_are_reported() {
        let text = DEFAULT_BINDINGS_RON.replacen("\"A\"", "\"NotAKey\"", 1);
        let e = Bindings::parse(&text, Path::new("b.ron")).unwrap_err();
        assert!(e.to_string().contains("NotAKey"), "{e}");
    }

    #[test]
    fn a_key_bound_twice_is_an_error() {
        let text = DEFAULT_BINDINGS_RON.replacen(
            "keys: {",
            "keys: {\n        \"Space\": Duck,\n        \"Space\": Duck,",
            1,
        );
        assert_ne!(text, DEFAULT_BINDINGS_RON);
        let e = Bindings::parse(&text, Path::new("b.ron"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("b.ron:") && e.contains("twice"), "{e}");
    }
}
