//! Gamepads without libudev: a small evdev backend.
//!
//! gilrs, the usual crate, links libudev through pkg-config on Linux, so
//! building it needs the libudev-dev system package; shisen must build with
//! no system development package. Instead this reads the kernel's evdev
//! nodes directly with the pure-Rust `evdev` crate: every
//! `/dev/input/event*` whose capabilities look like a gamepad (a south
//! button, or a joystick trigger, plus an X axis) is opened non-blocking and
//! drained each frame. Hot-plug: `/dev/input` is rescanned every
//! [`RESCAN`]; a device that errors (unplugged) is dropped. Without
//! `/dev/input`, or without permission to read it, there are simply no
//! pads. On other systems [`Pads`] is always empty.

use std::time::{Duration, Instant};

use super::command::{PadButton, PadState};

/// How often `/dev/input` is rescanned for new pads.
pub const RESCAN: Duration = Duration::from_secs(2);

/// Analog axes a pad reports, normalised into a [`PadState`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// Left stick X.
    LeftX,
    /// Left stick Y (down positive on the wire).
    LeftY,
    /// Right stick X.
    RightX,
    /// Right stick Y.
    RightY,
    /// Left trigger.
    LeftTrigger,
    /// Right trigger.
    RightTrigger,
    /// D-pad X as a hat (-1 left, +1 right).
    HatX,
    /// D-pad Y as a hat (-1 up, +1 down).
    HatY,
}

/// Apply one normalised axis value (sticks and hats in [-1, 1], triggers in
/// [0, 1]) to a pad's state.
pub fn apply_axis(state: &mut PadState, axis: Axis, v: f32) {
    let mut hat = |neg: PadButton, pos: PadButton| {
        state.held.remove(&neg);
        state.held.remove(&pos);
        if v < -0.5 {
            state.held.insert(neg);
        } else if v > 0.5 {
            state.held.insert(pos);
        }
    };
    match axis {
        Axis::HatX => hat(PadButton::DpadLeft, PadButton::DpadRight),
        Axis::HatY => hat(PadButton::DpadUp, PadButton::DpadDown),
        Axis::LeftX => state.sticks[0].x = v,
        Axis::LeftY => state.sticks[0].y = -v,
        Axis::RightX => state.sticks[1].x = v,
        Axis::RightY => state.sticks[1].y = -v,
        Axis::LeftTrigger => state.triggers[0] = v,
        Axis::RightTrigger => state.triggers[1] = v,
    }
}

/// Apply a button press (`down`) or release.
pub fn apply_button(state: &mut PadState, b: PadButton, down: bool) {
    if down {
        state.held.insert(b);
    } else {
        state.held.remove(&b);
    }
}

/// The connected pads.
pub struct Pads {
    #[cfg(target_os = "linux")]
    devices: Vec<linux::Pad>,
    last_scan: Option<Instant>,
}

impl Default for Pads {
    fn default() -> Self {
        Self::new()
    }
}

impl Pads {
    /// No pads yet; the first [`Pads::poll`] scans.
    pub fn new() -> Self {
        Pads {
            #[cfg(target_os = "linux")]
            devices: Vec::new(),
            last_scan: None,
        }
    }

    /// Names of the connected pads.
    pub fn names(&self) -> Vec<String> {
        #[cfg(target_os = "linux")]
        return self.devices.iter().map(|d| d.name.clone()).collect();
        #[cfg(not(target_os = "linux"))]
        Vec::new()
    }

    /// Read everything pending (never blocks), rescan when due, and return
    /// the merged state of all pads.
    pub fn poll(&mut self, now: Instant) -> PadState {
        if self
            .last_scan
            .is_none_or(|t| now.duration_since(t) >= RESCAN)
        {
            self.last_scan = Some(now);
            #[cfg(target_os = "linux")]
            linux::rescan(&mut self.devices);
        }
        let mut merged = PadState::default();
        #[cfg(target_os = "linux")]
        {
            self.devices.retain_mut(|d| d.drain());
            for d in &self.devices {
                merged.merge(&d.state);
            }
        }
        merged
    }
}

#[cfg(target_os = "linux")]
mod linux {
    use std::path::PathBuf;

    use evdev::{AbsoluteAxisCode as Abs, Device, EventSummary, KeyCode as Key};

    use super::{Axis, PadButton, PadState, apply_axis, apply_button};

    /// One open pad.
    pub struct Pad {
        pub name: String,
        path: PathBuf,
        device: Device,
        /// (min, max) of each absolute axis code, for normalising.
        ranges: Vec<(u16, i32, i32)>,
        pub state: PadState,
    }

    fn button(k: Key) -> Option<PadButton> {
        Some(match k {
            Key::BTN_SOUTH => PadButton::South,
            Key::BTN_EAST => PadButton::East,
            Key::BTN_NORTH => PadButton::North,
            Key::BTN_WEST => PadButton::West,
            Key::BTN_TL => PadButton::L1,
            Key::BTN_TR => PadButton::R1,
            Key::BTN_SELECT => PadButton::Select,
            Key::BTN_START => PadButton::Start,
            Key::BTN_MODE => PadButton::Mode,
            Key::BTN_THUMBL => PadButton::ThumbL,
            Key::BTN_THUMBR => PadButton::ThumbR,
            Key::BTN_DPAD_UP => PadButton::DpadUp,
            Key::BTN_DPAD_DOWN => PadButton::DpadDown,
            Key::BTN_DPAD_LEFT => PadButton::DpadLeft,
            Key::BTN_DPAD_RIGHT => PadButton::DpadRight,
            _ => return None,
        })
    }

    fn axis(a: Abs) -> Option<Axis> {
        Some(match a {
            Abs::ABS_X => Axis::LeftX,
            Abs::ABS_Y => Axis::LeftY,
            Abs::ABS_RX => Axis::RightX,
            Abs::ABS_RY => Axis::RightY,
            Abs::ABS_Z | Abs::ABS_BRAKE => Axis::LeftTrigger,
            Abs::ABS_RZ | Abs::ABS_GAS => Axis::RightTrigger,
            Abs::ABS_HAT0X => Axis::HatX,
            Abs::ABS_HAT0Y => Axis::HatY,
            _ => return None,
        })
    }

    /// Whether a device's capabilities look like a gamepad.
    fn is_pad(d: &Device) -> bool {
        let keys = d.supported_keys();
        let has_button =
            keys.is_some_and(|k| k.contains(Key::BTN_SOUTH) || k.contains(Key::BTN_TRIGGER));
        let has_axis = d
            .supported_absolute_axes()
            .is_some_and(|a| a.contains(Abs::ABS_X));
        has_button && has_axis
    }

    impl Pad {
        fn open(path: PathBuf) -> Option<Pad> {
            let device = Device::open(&path).ok()?;
            if !is_pad(&device) {
                return None;
            }
            device.set_nonblocking(true).ok()?;
            let ranges = device
                .get_absinfo()
                .ok()?
                .map(|(code, info)| (code.0, info.minimum(), info.maximum()))
                .collect();
            let name = device.name().unwrap_or("gamepad").to_string();
            tracing::info!(%name, path = %path.display(), "gamepad connected");
            Some(Pad {
                name,
                path,
                device,
                ranges,
                state: PadState::default(),
            })
        }

        fn normalise(&self, code: u16, a: Axis, v: i32) -> f32 {
            let Some(&(_, lo, hi)) = self.ranges.iter().find(|r| r.0 == code) else {
                return 0.0;
            };
            let span = (hi - lo).max(1) as f32;
            let unit = (v - lo) as f32 / span; // 0..1
            match a {
                Axis::LeftTrigger | Axis::RightTrigger => unit.clamp(0.0, 1.0),
                _ => (unit * 2.0 - 1.0).clamp(-1.0, 1.0),
            }
        }

        /// Read pending events; false once the device is gone.
        pub fn drain(&mut self) -> bool {
            let events: Vec<EventSummary> = match self.device.fetch_events() {
                Ok(evs) => evs.map(|e| e.destructure()).collect(),
                Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => return true,
                Err(e) => {
                    tracing::info!(name = %self.name, error = %e, "gamepad disconnected");
                    return false;
                }
            };
            for ev in events {
                match ev {
                    EventSummary::Key(_, k, v) => {
                        if let Some(b) = button(k) {
                            apply_button(&mut self.state, b, v != 0);
                        } else if k == Key::BTN_TL2 || k == Key::BTN_TR2 {
                            // Digital triggers: fully pulled or released.
                            let a = if k == Key::BTN_TL2 {
                                Axis::LeftTrigger
                            } else {
                                Axis::RightTrigger
                            };
                            apply_axis(&mut self.state, a, if v != 0 { 1.0 } else { 0.0 });
                        }
                    }
                    EventSummary::AbsoluteAxis(_, code, v) => {
                        if let Some(a) = axis(code) {
                            let n = self.normalise(code.0, a, v);
                            apply_axis(&mut self.state, a, n);
                        }
                    }
                    _ => {}
                }
            }
            true
        }
    }

    /// Open pads that appeared in /dev/input; keep the open ones.
    pub fn rescan(devices: &mut Vec<Pad>) {
        let Ok(dir) = std::fs::read_dir("/dev/input") else {
            return;
        };
        let mut paths: Vec<PathBuf> = dir
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("event"))
            })
            .collect();
        paths.sort();
        for p in paths {
            if devices.iter().any(|d| d.path == p) {
                continue;
            }
            if let Some(pad) = Pad::open(p) {
                devices.push(pad);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hats_become_dpad_buttons_and_sticks_point_up() {
        let mut s = PadState::default();
        apply_axis(&mut s, Axis::HatX, -1.0);
        assert!(s.held.contains(&PadButton::DpadLeft));
        apply_axis(&mut s, Axis::HatX, 0.0);
        assert!(s.held.is_empty());
        apply_axis(&mut s, Axis::LeftY, -1.0); // pushed up on the wire
        assert_eq!(s.sticks[0].y, 1.0);
        apply_button(&mut s, PadButton::South, true);
        assert!(s.held.contains(&PadButton::South));
    }

    #[test]
    fn polling_without_pads_is_harmless() {
        let mut pads = Pads::new();
        let s = pads.poll(Instant::now());
        assert_eq!(s.triggers, [0.0, 0.0]);
    }
}
