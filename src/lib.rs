//! # shisen-app: the sparring window and the command line
//!
//! The top layer of shisen: the wgpu [`render`]er (the VH's body and
//! deforming face, your gloves, props, overlays; offscreen PNGs and the
//! window share it), [`input`] (keyboard, mouse and gamepads turned into
//! timeline events, so a live session replays exactly) and the sparring
//! window ([`app`]). The `shisen` binary is built from this crate.
//!
//! Everything below (laws, face, physics, scenes, headless tools) is the
//! `shisen` crate, which this one imports and never the other way round.

pub mod app;
pub mod input;
pub mod render;
pub mod schema;
