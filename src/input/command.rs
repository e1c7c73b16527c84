//! The vocabulary of your input: commands, and the gamepad's buttons,
//! sticks and triggers with their state.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// What a binding does.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
pub enum Command {
    /// Move your head to your left while held.
    DodgeLeft,
    /// Move your head to your right while held.
    DodgeRight,
    /// Duck while held.
    Duck,
    /// Lean back while held.
    LeanBack,
    /// Step in toward the VH (about 0.3 m).
    StepIn,
    /// Step back away from the VH.
    StepOut,
    /// Feint with your lead (left) hand: a half step in and a twitch of
    /// the glove, no punch.
    Feint,
    /// Throw your left glove forward.
    ThrowLeft,
    /// Throw your right glove forward.
    ThrowRight,
    /// Swap which glove the mouse pointer moves.
    SwapGlove,
    /// Show or hide the tuning panels.
    TogglePanel,
    /// First-person / orbit camera.
    ToggleView,
    /// Pause or resume the simulation.
    Pause,
    /// Advance one tick while paused.
    Step,
    /// Toggle slow motion.
    SlowMotion,
    /// Restart the scene.
    Restart,
    /// Start or stop recording the session.
    Record,
    /// Open or close the menu (opponent, rounds, restart, quit).
    Menu,
    /// Open or close the round report.
    Report,
    /// Watch the bout so far again (a time scrubber), or go back to it.
    Replay,
    /// Show or hide the developer's figures (frame time, sim time).
    DevFigures,
    /// Mute or unmute the sound.
    Mute,
}

impl Command {
    /// Commands that act while held (the others act when pressed).
    pub fn is_held(self) -> bool {
        matches!(
            self,
            Command::DodgeLeft | Command::DodgeRight | Command::Duck | Command::LeanBack
        )
    }
}

/// Gamepad buttons (the standard layout, named by position).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
pub enum PadButton {
    /// The bottom face button (A on Xbox, Cross on PlayStation).
    South,
    /// The right face button (B, Circle).
    East,
    /// The top face button (Y, Triangle).
    North,
    /// The left face button (X, Square).
    West,
    /// The left shoulder button (LB, L1).
    L1,
    /// The right shoulder button (RB, R1).
    R1,
    /// The left centre button (Back, View, Share).
    Select,
    /// The right centre button (Start, Menu, Options).
    Start,
    /// The logo button (Guide, Home, PS).
    Mode,
    /// Pressing the left stick ("L3" on a PlayStation pad).
    ThumbL,
    /// Pressing the right stick ("R3" on a PlayStation pad).
    ThumbR,
    /// D-pad up.
    DpadUp,
    /// D-pad down.
    DpadDown,
    /// D-pad left.
    DpadLeft,
    /// D-pad right.
    DpadRight,
}

/// A gamepad stick.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum Stick {
    /// Left stick.
    LeftStick,
    /// Right stick.
    RightStick,
}

/// A gamepad trigger.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum Trigger {
    /// Left trigger, L2.
    LeftTrigger,
    /// Right trigger, R2.
    RightTrigger,
}

/// The state of every pad merged: sticks in [-1, 1] (+x right, +y up),
/// triggers in [0, 1], buttons held.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PadState {
    /// Left and right stick.
    pub sticks: [glam::Vec2; 2],
    /// Left and right trigger.
    pub triggers: [f32; 2],
    /// Buttons held.
    pub held: std::collections::BTreeSet<PadButton>,
}

impl PadState {
    /// Deflection of a stick.
    pub fn stick(&self, s: Stick) -> glam::Vec2 {
        self.sticks[s as usize]
    }

    /// Pull of a trigger.
    pub fn trigger(&self, t: Trigger) -> f32 {
        self.triggers[t as usize]
    }

    /// Combine with another pad: the larger deflection wins, buttons add.
    pub fn merge(&mut self, other: &PadState) {
        for k in 0..2 {
            if other.sticks[k].length() > self.sticks[k].length() {
                self.sticks[k] = other.sticks[k];
            }
            self.triggers[k] = self.triggers[k].max(other.triggers[k]);
        }
        self.held.extend(other.held.iter().copied());
    }
}
