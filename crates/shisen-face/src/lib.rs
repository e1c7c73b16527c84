//! # shisen-face: the muscle-driven face, alone
//!
//! The face of shisen's virtual human (face.md): emotion -> region expressions -> Action
//! Units -> muscles -> skin, with onset/offset timing and spontaneous blinks.
//!
//! Static description (mesh, muscle placement, precomputed fields,
//! parameters) lives in [`Face`]; everything that evolves (current
//! contractions, transition timing, blink process, eye pitch) lives in
//! [`FaceState`], as MuJoCo separates model and data.

pub mod appearance;
pub mod blink;
pub mod calibrate;
pub mod emotion;
#[cfg(feature = "mesh-io")]
pub mod exchange;
#[cfg(feature = "mesh-io")]
pub mod import;
pub mod lip_seal;
pub mod mesh;
pub mod model;
pub mod muscle;
pub mod params;
pub mod reflex;
pub mod rig;
pub mod script;
pub mod spread;
pub mod tables;
pub mod timing;
pub mod wrinkle;

pub use model::{Face, FaceState, deform};
pub use params::FaceError;
