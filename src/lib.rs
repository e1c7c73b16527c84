//! # shisen (視線, "line of sight")
//!
//! A physically simulated virtual human (VH) that boxes with you and whose
//! eyes, head and face react the way a person's do.
//!
//! The crate is layered bottom-up; each layer imports only those below it:
//!
//! | layer | modules | what lives there |
//! |---|---|---|
//! | helpers | [`util`], [`anatomy`] | math, value checks, RON loading; shared human measurements |
//! | the VH's brain | [`agent`], [`face`] | vision (M1), behaviour, attention, oculomotor (M2-M9); the muscle-driven face (F1-F8) |
//! | physics | [`physics`] | body plan, rapier world, PD joint control |
//! | simulation | [`sim`] | [`Model`] (static) and [`Sim`] (state), the tick as named stages, timeline, samples, expectations |
//! | scene format | [`scene`] | RON scene files: load, validate, save |
//! | tools | [`tools`] | headless runs, traces, tuning, soak, plots |
//! | app | `render`, `input`, `app` (feature `app`) | wgpu renderer, your controls, the sparring window |
//!
//! Equations are cited by number (M1.., F1..); `docs/model/` explains each.
//!
//! ```no_run
//! // Run a scene headless and read its samples.
//! let loaded = shisen::LoadedScene::load("scenes/wave.ron".as_ref()).unwrap();
//! let mut sim = loaded.sim();
//! while sim.time() < 1.0 {
//!     let s = sim.step();
//!     println!("{:.3} looking at {}", s.t, s.gaze_target);
//! }
//! ```
//!
//! Features: `tools` (plots, parallel sweeps), `mesh-io` (OBJ/glTF face
//! meshes) and `app` (window, renderer, gamepads; implies both) are on by
//! default; `default-features = false` builds the light library (laws,
//! face, physics, scenes, headless runs).

pub mod agent;
pub mod anatomy;
#[cfg(feature = "app")]
pub mod app;
pub mod face;
#[cfg(feature = "app")]
pub mod input;
pub mod physics;
#[cfg(feature = "app")]
pub mod render;
pub mod scene;
pub mod sim;
pub mod tools;
pub mod util;

pub use agent::attention::{Attention, AttentionParams, GazeChoice};
pub use agent::oculomotor::{GazeInput, GazeOutput, Oculomotor, OculomotorParams};
pub use agent::personality::Personality;
pub use agent::vision::{Scenery, Seen, VisionParams};
pub use face::{Face, FaceState};
pub use physics::control::Gains;
pub use physics::world::World;
pub use scene::{LoadedScene, Scene};
pub use sim::{DT, Model, Params, Sample, Sim};
pub use util::ron::LoadError;
