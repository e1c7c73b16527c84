//! # shisen (視線, "line of sight")
//!
//! A physically simulated virtual human (VH) that boxes with you and whose
//! eyes, head and face react the way a person's do.
//!
//! This crate is the simulation layer of a workspace whose crates are the
//! layers, bottom-up; each imports only those below it:
//!
//! | crate | modules | what lives there |
//! |---|---|---|
//! | `shisen-gaze` | `util`, `anatomy`, `vision`, `behaviour`, `attention`, `oculomotor` | the VH's brain: vision (M1), behaviour, attention, oculomotor (M2-M9); no physics, no graphics |
//! | `shisen-face` | the face | the muscle-driven face (F1-F8) |
//! | **`shisen`** | [`physics`], [`sim`], [`sound`], [`scene`], [`tools`] | body plan, rapier world, PD joints; [`Model`] (static) and [`Sim`] (state), the tick as named stages; the soundtrack heard from your head; RON scene files; headless runs, traces, tuning, soak |
//! | `shisen-app` | `render`, `input`, `app`, the `shisen` binary | wgpu renderer, your controls, the sparring window |
//!
//! The layers below are re-exported as [`gaze`] and [`face`] (with
//! [`util`] and [`anatomy`] at the root), so one dependency reaches all of
//! the simulation. Equations are cited by number (M1.., F1..);
//! `docs/model/` explains each.
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
//! Features (all off by default): `tools` (plots, parallel sweeps and
//! studies, fidelity), `mesh-io` (OBJ/glTF face meshes).

pub mod physics;
pub mod scene;
pub mod sim;
pub mod sound;
pub mod tools;

pub use shisen_face as face;
pub use shisen_gaze as gaze;
pub use shisen_gaze::{anatomy, util};

pub use face::{Face, FaceState};
pub use gaze::attention::{Attention, AttentionParams, GazeChoice};
pub use gaze::oculomotor::{GazeInput, GazeOutput, Oculomotor, OculomotorParams};
pub use gaze::personality::Personality;
pub use gaze::vision::{Scenery, Seen, VisionParams};
pub use physics::control::Gains;
pub use physics::world::World;
pub use scene::{LoadedScene, Scene};
pub use sim::{DT, Model, Params, Sample, Sim};
pub use util::ron::LoadError;
