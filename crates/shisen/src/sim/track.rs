//! Scripted motion of kinematic bodies (the opponent's head and gloves,
//! kinematic props): each is a [`Track`] of motion segments started by
//! timeline events or by live input, evaluated in simulation time.

use std::collections::VecDeque;

use glam::DVec3;

use shisen_gaze::util::math::{MIN_JERK_PEAK, min_jerk};

/// One piece of motion.
#[derive(Clone, Debug, PartialEq)]
enum Seg {
    /// Minimum-jerk move from `from` to `to` over [t0, t0 + dur].
    Reach {
        from: DVec3,
        to: DVec3,
        t0: f64,
        dur: f64,
    },
    /// Constant angular speed `rate` (rad/s) about +Y through `centre`,
    /// starting at `centre + arm`.
    Orbit {
        centre: DVec3,
        arm: DVec3,
        rate: f64,
        t0: f64,
        dur: f64,
    },
    /// Sinusoid about `centre`, starting and ending there.
    Wave {
        centre: DVec3,
        amplitude: DVec3,
        freq: f64,
        t0: f64,
        dur: f64,
    },
}

impl Seg {
    fn t0(&self) -> f64 {
        match self {
            Seg::Reach { t0, .. } | Seg::Wave { t0, .. } | Seg::Orbit { t0, .. } => *t0,
        }
    }

    fn end(&self) -> f64 {
        match self {
            Seg::Reach { t0, dur, .. } | Seg::Wave { t0, dur, .. } | Seg::Orbit { t0, dur, .. } => {
                t0 + dur
            }
        }
    }

    fn end_pos(&self) -> DVec3 {
        match self {
            Seg::Reach { to, .. } => *to,
            Seg::Wave { centre, .. } => *centre,
            Seg::Orbit { t0, dur, .. } => self.at(t0 + dur),
        }
    }

    fn at(&self, t: f64) -> DVec3 {
        match *self {
            // boxing.md: reaching uses minimum-jerk trajectories (M2 shape).
            Seg::Reach { from, to, t0, dur } => from + (to - from) * min_jerk((t - t0) / dur),
            Seg::Wave {
                centre,
                amplitude,
                freq,
                t0,
                ..
            } => centre + amplitude * (std::f64::consts::TAU * freq * (t - t0)).sin(),
            Seg::Orbit {
                centre,
                arm,
                rate,
                t0,
                ..
            } => centre + glam::DQuat::from_rotation_y(rate * (t - t0)) * arm,
        }
    }
}

/// The motion of one kinematic body.
#[derive(Clone, Debug, PartialEq)]
pub struct Track {
    rest: DVec3,
    queue: VecDeque<Seg>,
    /// While a punch is on its way out: where it started, the duration of
    /// its way back, and when the way out ends.
    punch: Option<(DVec3, f64, f64)>,
}

impl Track {
    /// A body holding still at `p`.
    pub fn new(p: DVec3) -> Self {
        Track {
            rest: p,
            queue: VecDeque::new(),
            punch: None,
        }
    }

    /// Position at time `t` (non-decreasing across calls).
    pub fn position(&mut self, t: f64) -> DVec3 {
        while let Some(s) = self.queue.front() {
            if t >= s.end() {
                self.rest = s.end_pos();
                self.queue.pop_front();
            } else {
                break;
            }
        }
        match self.queue.front() {
            Some(s) if t >= s.t0() => s.at(t),
            _ => self.rest,
        }
    }

    /// Where a move under way ends, if the body is moving.
    pub fn destination(&self) -> Option<DVec3> {
        self.queue.back().map(Seg::end_pos)
    }

    /// Interrupt whatever is going on at `t` and hold the current position.
    fn interrupt(&mut self, t: f64) -> DVec3 {
        let p = self.position(t);
        self.queue.clear();
        self.rest = p;
        self.punch = None;
        p
    }

    /// Start a minimum-jerk move to `to` lasting `dur`, from where the body is at `t`.
    pub fn reach(&mut self, t: f64, to: DVec3, dur: f64) {
        let from = self.interrupt(t);
        self.queue.push_back(Seg::Reach {
            from,
            to,
            t0: t,
            dur,
        });
    }

    /// A lunge: minimum-jerk out to `to` over `dur`, then back to the
    /// start over the same time (the body's step behind a punch).
    pub fn lunge(&mut self, t: f64, to: DVec3, dur: f64) {
        let from = self.interrupt(t);
        self.out_and_back(from, to, t, dur);
    }

    /// Minimum-jerk out from `from` to `to` over `dur` from `t0`, and back
    /// over the same time.
    fn out_and_back(&mut self, from: DVec3, to: DVec3, t0: f64, dur: f64) {
        self.queue.push_back(Seg::Reach { from, to, t0, dur });
        self.queue.push_back(Seg::Reach {
            from: to,
            to: from,
            t0: t0 + dur,
            dur,
        });
    }

    /// A punch: minimum-jerk out to `to` with peak speed `speed` (m/s), then
    /// back to the start over the same time. Returns the outbound duration.
    pub fn punch(&mut self, t: f64, to: DVec3, speed: f64) -> f64 {
        self.punch_after(t, 0.0, to, speed)
    }

    /// A punch that leaves after `lead` s held where the glove is (the
    /// body's part of the punch goes first). Returns the outbound
    /// duration, lead excluded.
    pub fn punch_after(&mut self, t: f64, lead: f64, to: DVec3, speed: f64) -> f64 {
        let from = self.interrupt(t);
        if lead > 0.0 {
            self.queue.push_back(Seg::Reach {
                from,
                to: from,
                t0: t,
                dur: lead,
            });
        }
        let t = t + lead.max(0.0);
        // Peak speed of a minimum-jerk move is 1.875 d / T (see math::min_jerk_d).
        let dur = (MIN_JERK_PEAK * (to - from).length() / speed).max(1e-3);
        self.out_and_back(from, to, t, dur);
        self.punch = Some((from, dur, t + dur));
        dur
    }

    /// The glove struck something at `t`, where it really is `at`: if a
    /// punch is on its way out, it ends there and comes straight back (an
    /// arm recoils from the impact instead of pushing on along its path).
    /// Returns whether it did.
    pub fn recoil(&mut self, t: f64, at: DVec3) -> bool {
        match self.punch {
            Some((origin, back, out_end)) if t < out_end => {
                self.queue.clear();
                self.rest = at;
                self.punch = None;
                self.queue.push_back(Seg::Reach {
                    from: at,
                    to: origin,
                    t0: t,
                    dur: back,
                });
                true
            }
            _ => false,
        }
    }

    /// Wave about the current position.
    pub fn wave(&mut self, t: f64, amplitude: DVec3, freq: f64, dur: f64) {
        let centre = self.interrupt(t);
        self.queue.push_back(Seg::Wave {
            centre,
            amplitude,
            freq,
            t0: t,
            dur,
        });
    }

    /// Circle about `centre` (vertical axis) at `rate` rad/s from where the
    /// body is at `t`.
    pub fn orbit(&mut self, t: f64, centre: DVec3, rate: f64, dur: f64) {
        let from = self.interrupt(t);
        self.queue.push_back(Seg::Orbit {
            centre,
            arm: from - centre,
            rate,
            t0: t,
            dur,
        });
    }

    /// Put the body at `p` now (live input), cancelling scripted motion.
    pub fn set(&mut self, p: DVec3) {
        self.queue.clear();
        self.rest = p;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn punch_goes_out_and_back_at_the_requested_peak_speed() {
        let mut tr = Track::new(DVec3::ZERO);
        let to = DVec3::new(0.0, 0.0, -0.6);
        let dur = tr.punch(1.0, to, 6.0);
        assert!((dur - 1.875 * 0.6 / 6.0).abs() < 1e-12);
        assert_eq!(tr.position(0.5), DVec3::ZERO);
        let dt = 1e-4;
        let mid = 1.0 + dur / 2.0;
        let v = (tr.position(mid + dt) - tr.position(mid)).length() / dt;
        assert!((v - 6.0).abs() < 0.01, "peak speed {v}");
        assert!((tr.position(1.0 + dur) - to).length() < 1e-9);
        assert!(tr.position(1.0 + 2.0 * dur + 0.1).length() < 1e-9);
    }

    /// A punch stopped on its way out comes back from where the glove
    /// really is, over the back stroke's time; once the way out is over
    /// there is nothing to recoil from.
    #[test]
    fn a_stopped_punch_recoils_from_where_it_is() {
        let mut tr = Track::new(DVec3::ZERO);
        let dur = tr.punch(1.0, DVec3::new(0.0, 0.0, -0.6), 6.0);
        let hit = DVec3::new(0.01, 0.0, -0.3);
        assert!(tr.recoil(1.0 + dur / 2.0, hit));
        assert!((tr.position(1.0 + dur / 2.0) - hit).length() < 1e-12);
        assert!(tr.position(1.0 + 1.5 * dur + 1e-6).length() < 1e-9);
        assert!(!tr.recoil(1.0 + 2.0 * dur, hit), "no punch left");
        let mut late = Track::new(DVec3::ZERO);
        let d = late.punch(0.0, DVec3::X, 6.0);
        assert!(!late.recoil(d + 0.01, DVec3::X), "on its way back already");
    }

    #[test]
    fn a_new_move_starts_where_the_body_is() {
        let mut tr = Track::new(DVec3::ZERO);
        tr.reach(0.0, DVec3::X, 1.0);
        let p = tr.position(0.5);
        tr.reach(0.5, DVec3::Y, 1.0);
        assert!((tr.position(0.5) - p).length() < 1e-12, "continuous");
        assert!((tr.position(2.0) - DVec3::Y).length() < 1e-12);
    }

    #[test]
    fn orbit_keeps_radius_and_rate() {
        let mut tr = Track::new(DVec3::new(0.0, 1.0, 2.0));
        tr.orbit(0.0, DVec3::new(0.0, 1.0, 0.0), 0.5, 2.0);
        let p = tr.position(1.0);
        assert!(((p - DVec3::new(0.0, 1.0, 0.0)).length() - 2.0).abs() < 1e-12);
        assert!(
            (p.x.atan2(p.z) - 0.5).abs() < 1e-12,
            "positive rate turns toward +X (left)"
        );
        let end = tr.position(2.0);
        assert!(
            (tr.position(3.0) - end).length() < 1e-12,
            "holds where it ended"
        );
    }

    #[test]
    fn wave_returns_to_centre() {
        let mut tr = Track::new(DVec3::ONE);
        tr.wave(0.0, DVec3::new(0.2, 0.0, 0.0), 2.0, 1.0);
        assert!((tr.position(0.125).x - 1.2).abs() < 1e-9);
        assert!((tr.position(1.5) - DVec3::ONE).length() < 1e-12);
    }
}
