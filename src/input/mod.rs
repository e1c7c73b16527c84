//! Your side of the bout: keyboard, mouse and gamepads turned into an
//! [`Intent`] (where your gloves and head should be, which glove to
//! throw), and the intent into timeline events for the simulation
//! ([`OpponentControl`]), so a live session records and replays exactly.
//!
//! Bindings are remappable ([`Bindings`], RON). Gamepads are read with a
//! small evdev backend ([`pad::Pads`]): gilrs would need libudev-dev at build
//! time on Linux.

mod bindings;
mod collect;
mod command;
mod opponent;
pub mod pad;

pub use bindings::{Bindings, BindingsError, DEFAULT_BINDINGS_RON, MouseBindings, PadAxes};
pub use collect::{Collector, Pointer};
pub use command::{Command, PadButton, PadState, Stick, Trigger};
pub use opponent::{DODGE, Intent, OpponentControl, PUNCH_SPEED};
