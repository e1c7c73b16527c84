//! The face subsystem (face.md): emotion -> region expressions -> Action
//! Units -> muscles -> skin, with onset/offset timing and spontaneous blinks.
//!
//! Static description (mesh, muscle placement, precomputed fields,
//! parameters) lives in [`Face`]; everything that evolves (current
//! contractions, transition timing, blink process, eye pitch) lives in
//! [`FaceState`], as MuJoCo separates model and data.

pub mod blink;
pub mod calibrate;
pub mod emotion;
#[cfg(feature = "mesh-io")]
pub mod exchange;
#[cfg(feature = "mesh-io")]
pub mod import;
pub mod mesh;
pub mod model;
pub mod muscle;
pub mod params;
pub mod rig;
pub mod script;
pub mod tables;
pub mod timing;

pub use model::{Face, FaceState, deform};

/// Errors of the face subsystem.
#[derive(Debug, thiserror::Error)]
pub enum FaceError {
    /// The RON parameter file did not parse (file, line, field included).
    #[error("{0}")]
    Parse(#[from] crate::util::ron::LoadError),
    /// A parameter value is out of range or inconsistent.
    #[error("invalid parameters: {0}")]
    Invalid(String),
    /// A head mesh or landmark file could not be imported (file named).
    #[error("import: {0}")]
    Import(String),
}
