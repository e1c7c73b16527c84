//! # shisen (視線, "line of sight")
//!
//! A physically simulated virtual human (VH) that boxes with you and whose
//! eyes, head and face react the way a person's do.
//!
//! The modules follow the pipeline of one control tick (gaze.md 1):
//! [`world`] (rapier physics built from the static [`body`] plan) ->
//! [`vision`] (visible bodies, saliency M1) -> [`behaviour`] (guard /
//! attack / idle) -> [`attention`] (arbitration) -> [`oculomotor`]
//! (saccades M2-M6, pursuit/vergence/VOR M7, head M8-M9) -> [`control`]
//! (PD joints), with [`face`] beside them (muscle-driven face, F1-F8).
//! [`sim`] runs the tick; [`scene`] reads scene files;
//! [`trace`] and [`expect`] record and judge headless runs.
//! [`render`] draws it (offscreen or in the window); [`app`] is the
//! sparring window and [`input`] your side of the bout.

#[cfg(feature = "app")]
pub mod app;
pub mod attention;
pub mod behaviour;
pub mod body;
pub mod check;
pub mod control;
pub mod expect;
pub mod face;
pub mod headless;
#[cfg(feature = "app")]
pub mod input;
pub mod math;
pub mod metrics;
pub mod mjcf;
pub mod oculomotor;
pub mod plot;
#[cfg(feature = "app")]
pub mod render;
pub mod scene;
pub mod script;
pub mod sim;
pub mod soak;
pub mod trace;
pub mod tune;
pub mod vision;
pub mod world;
