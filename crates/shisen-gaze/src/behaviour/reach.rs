//! A minimum-jerk reach: how the gloves, the lunge and the body plan's
//! joints move from one point to another (and back).

use glam::DVec3;

use crate::util::math::min_jerk;

/// A glove reach in progress, in world coordinates.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Reach {
    pub(super) from: DVec3,
    pub(super) to: DVec3,
    pub(super) t0: f64,
    pub(super) dur: f64,
    pub(super) back: bool,
}

impl Reach {
    pub(super) fn at(&self, t: f64) -> DVec3 {
        let s = (t - self.t0) / self.dur;
        // Out and back uses one min-jerk profile per half.
        if self.back {
            let half = self.dur / 2.0;
            if t - self.t0 < half {
                self.from + (self.to - self.from) * min_jerk((t - self.t0) / half)
            } else {
                self.to + (self.from - self.to) * min_jerk((t - self.t0 - half) / half)
            }
        } else {
            self.from + (self.to - self.from) * min_jerk(s)
        }
    }

    pub(super) fn done(&self, t: f64) -> bool {
        t >= self.t0 + self.dur
    }
}
