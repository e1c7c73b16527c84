//! What the planner sees coming: a punch starting at the head (to evade),
//! a glove aimed at the VH (to guard) and, before either, the body's cue
//! (the opponent's head stepping in behind a punch, or a feint).

use glam::DVec3;

use super::{BehaviourParams, OpponentView};
use crate::target::BodyId;
use crate::vision::Seen;

/// A punch at the head seen starting: the opponent glove closing fastest
/// on the VH's head, faster than `evade_speed`, on a path that passes
/// within 15 cm of it.
pub fn glove_onset<'a>(p: &BehaviourParams, view: &OpponentView<'a>) -> Option<&'a Seen> {
    let head = view.vh_points[0];
    view.seen
        .iter()
        .filter(|s| s.body == view.parts[1] || s.body == view.parts[2])
        .filter_map(|s| {
            let to = head - s.position;
            let dir = to.normalize_or_zero();
            let closing = s.velocity.dot(dir);
            let heading = s.velocity.normalize_or_zero();
            let miss = (to - to.dot(heading) * heading).length();
            (closing > p.evade_speed && miss < 0.15).then_some((s, closing))
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(s, _)| s)
}

/// The aimed-glove test (boxing.md, Guard): the fastest opponent glove that
/// is seen, faster than `guard_speed`, heading within `guard_angle_deg` of
/// the VH's head, torso or centre of mass, with time to contact under
/// `guard_ttc`. Returns (body, interception point at 0.4 ttc, ttc).
pub fn aimed_glove(p: &BehaviourParams, view: &OpponentView) -> Option<(BodyId, DVec3, f64)> {
    let cos_max = p.guard_angle_deg.to_radians().cos();
    let mut best: Option<(BodyId, DVec3, f64)> = None;
    for s in view.seen {
        if s.body != view.parts[1] && s.body != view.parts[2] {
            continue;
        }
        let speed = s.velocity.length();
        if speed <= p.guard_speed {
            continue;
        }
        let heading = s.velocity / speed;
        for aim in view.vh_points {
            let to = aim - s.position;
            let dist = to.length();
            if dist < 1e-9 || heading.dot(to / dist) < cos_max {
                continue;
            }
            let ttc = dist / speed;
            if ttc < p.guard_ttc && best.as_ref().is_none_or(|b| ttc < b.2) {
                best = Some((s.body, s.position + s.velocity * (0.4 * ttc), ttc));
            }
        }
    }
    best
}

/// The body's cue (docs/model/boxing.md "Cues"): the opponent's head, as
/// vision sees it, closing on the VH's head faster than `cue_speed`: the
/// step of a punch thrown from long range (the body leads the glove) or a
/// feint. Returns the head as seen and whether the cue predicts the rear
/// hand: a head that also moves to the opponent's lead side by more than
/// a third of its approach (the rear shoulder turning in carries it
/// there); otherwise the lead hand's jab.
pub fn body_cue<'a>(p: &BehaviourParams, view: &OpponentView<'a>) -> Option<(&'a Seen, bool)> {
    let s = view.seen.iter().find(|s| s.body == view.parts[0])?;
    let to = view.vh_points[0] - s.position;
    let to = DVec3::new(to.x, 0.0, to.z).normalize_or_zero();
    let closing = s.velocity.dot(to);
    if closing <= p.cue_speed {
        return None;
    }
    // The opponent faces the VH: its lead (left) side is up x forward.
    let lead = DVec3::Y.cross(to);
    Some((s, s.velocity.dot(lead) > closing / 3.0))
}
