//! # shisen-gaze: the virtual human's gaze, alone
//!
//! The bottom two layers of shisen, with no physics engine and no graphics:
//! helpers ([`util`]: math, value checks, RON loading; [`anatomy`]: the
//! human measurements the body, the laws and the face share) and the VH's
//! brain, one stage per module, in pipeline order:
//! [`vision`] (what is in view, bottom-up saliency M1) -> [`behaviour`]
//! (guard / attack / idle and its top-down request) -> [`attention`]
//! (which target wins) -> [`oculomotor`] (saccades M2-M6,
//! pursuit/vergence/VOR M7, head M8-M9). [`personality`] holds the amounts
//! the stages share.
//!
//! No stage knows the physics engine or the scene format: vision reads the
//! world through [`vision::Scenery`], and the oculomotor's outputs are
//! joint-space commands ([`oculomotor::AxisCommand`]). The gaze controller
//! (attention + oculomotor) runs on its own; see `examples/gaze_without_physics.rs`.

pub mod anatomy;
pub mod attention;
pub mod behaviour;
pub mod oculomotor;
pub mod personality;
pub mod target;
pub mod util;
pub mod vision;
