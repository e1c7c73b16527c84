//! One frame of raw input (keys, pointer, pads) through the bindings into
//! an [`Intent`] and the commands pressed this frame.

use std::collections::BTreeSet;

use eframe::egui::Key;
use glam::Vec3;

use super::bindings::Bindings;
use super::command::{Command, PadButton, PadState};
use super::opponent::{DODGE, Intent};

/// How far a full stick deflection moves a glove, m (sideways, up).
const STICK_RANGE: glam::Vec2 = glam::Vec2::new(0.25, 0.2);

/// The pointer this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pointer {
    /// Offset from the active glove's guard position to the point under
    /// the pointer in the glove plane, if the pointer is over the view.
    pub glove_offset: Option<Vec3>,
    /// Buttons pressed this frame: primary, secondary, middle.
    pub pressed: [bool; 3],
}

/// Remembers what persists between frames (active glove, last pointer
/// position, held buttons).
#[derive(Clone, Debug)]
pub struct Collector {
    /// The bindings in force.
    pub bindings: Bindings,
    /// Which glove the pointer moves (0 your left, 1 right).
    pub active_glove: usize,
    mouse_offset: Option<Vec3>,
    pad_held: BTreeSet<PadButton>,
}

impl Collector {
    /// A collector with `bindings`; the pointer moves your left glove.
    pub fn new(bindings: Bindings) -> Self {
        Collector {
            bindings,
            active_glove: 0,
            mouse_offset: None,
            pad_held: BTreeSet::new(),
        }
    }

    /// Combine this frame's input into an intent and the commands pressed
    /// (throws are in the intent; the rest are for the app).
    pub fn collect(
        &mut self,
        keys_held: &[Key],
        keys_pressed: &[Key],
        pointer: &Pointer,
        pad: &PadState,
        reach: f32,
    ) -> (Intent, Vec<Command>) {
        let b = &self.bindings;
        let mut held: BTreeSet<Command> =
            keys_held.iter().filter_map(|k| b.key_command(*k)).collect();
        held.extend(
            pad.held
                .iter()
                .filter_map(|p| b.pad_buttons.get(p).copied()),
        );
        let mut pressed: Vec<Command> = keys_pressed
            .iter()
            .filter_map(|k| b.key_command(*k))
            .collect();
        let mouse = [b.mouse.left, b.mouse.right, b.mouse.middle];
        for (down, c) in pointer.pressed.iter().zip(mouse) {
            if *down && let Some(c) = c {
                pressed.push(c);
            }
        }
        for p in pad.held.difference(&self.pad_held) {
            if let Some(c) = b.pad_buttons.get(p) {
                pressed.push(*c);
            }
        }
        self.pad_held = pad.held.clone();
        pressed.retain(|c| !c.is_held());

        if pressed.contains(&Command::SwapGlove) {
            self.active_glove = 1 - self.active_glove;
            self.mouse_offset = None;
        }
        if let Some(o) = pointer.glove_offset {
            self.mouse_offset = Some(o);
        }

        let mut intent = Intent::default();
        let dodge = [
            (Command::DodgeLeft, Vec3::new(-DODGE.x, 0.0, 0.0)),
            (Command::DodgeRight, Vec3::new(DODGE.x, 0.0, 0.0)),
            (Command::Duck, Vec3::new(0.0, -DODGE.y, 0.0)),
            (Command::LeanBack, Vec3::new(0.0, 0.0, DODGE.z)),
        ];
        for (c, v) in dodge {
            if held.contains(&c) {
                intent.head_offset += v;
            }
        }
        if let Some(o) = self.mouse_offset {
            intent.glove_offset[self.active_glove] = o;
        }
        let axes = &b.pad_axes;
        let sticks = [axes.left_glove, axes.right_glove];
        let triggers = [axes.left_throw, axes.right_throw];
        for k in 0..2 {
            let s = pad.stick(sticks[k]);
            if s.length() > axes.dead_zone {
                intent.glove_offset[k] += (s * STICK_RANGE).extend(0.0);
            }
            intent.glove_offset[k].z -= pad.trigger(triggers[k]) * reach;
        }
        intent.step = f32::from(u8::from(pressed.contains(&Command::StepIn)))
            - f32::from(u8::from(pressed.contains(&Command::StepOut)));
        intent.feint = pressed.contains(&Command::Feint);
        intent.throw = [
            pressed.contains(&Command::ThrowLeft),
            pressed.contains(&Command::ThrowRight),
        ];
        (intent, pressed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_dodge_buttons_throw_and_pads_push() {
        let mut c = Collector::new(Bindings::default());
        let pointer = Pointer {
            glove_offset: Some(Vec3::new(0.05, 0.02, 0.0)),
            pressed: [true, false, false],
        };
        let mut pad = PadState::default();
        pad.triggers[1] = 0.5;
        let (i, cmds) = c.collect(&[Key::A], &[Key::Space], &pointer, &pad, 0.4);
        assert_eq!(i.head_offset.x, -DODGE.x, "A dodges to your left (-X)");
        assert_eq!(i.throw, [true, false]);
        assert!(cmds.contains(&Command::Pause));
        assert_eq!(i.glove_offset[0], Vec3::new(0.05, 0.02, 0.0));
        assert!(
            (i.glove_offset[1].z + 0.2).abs() < 1e-6,
            "trigger pushes forward"
        );
        pad.held.insert(PadButton::South);
        let (_, cmds) = c.collect(&[], &[], &Pointer::default(), &pad, 0.4);
        assert_eq!(cmds, vec![Command::TogglePanel]);
        let (_, cmds) = c.collect(&[], &[], &Pointer::default(), &pad, 0.4);
        assert!(cmds.is_empty(), "held, not pressed again");
    }
}
