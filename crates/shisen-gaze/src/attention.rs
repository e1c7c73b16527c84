//! Attention: bottom-up saliency against the action's top-down request,
//! arbitrated by the larger amount (gaze.md 5-6), plus what the seed lacks
//! so that the gaze neither sticks nor flickers:
//!
//! - **smoothing**: each body's score is low-pass filtered (time constant
//!   `smoothing_tau`), so a single fast tick does not steal the gaze;
//! - **habituation / inhibition of return**: while a body holds the gaze
//!   bottom-up, its weight decays toward `habituation_floor` with time
//!   constant `habituation_tau`, and recovers with `recovery_tau` once the
//!   gaze leaves, so a static-but-salient body cannot hold the gaze forever;
//! - **minimum fixation**: once the gaze target changes it stays at least
//!   `min_fixation` seconds, unless the target vanishes from view or a
//!   challenger's amount exceeds the holder's by `override_ratio`;
//! - **onset capture** (H5): a body that comes into view (enters the field
//!   or comes out from behind another) after being out of it for at least
//!   `onset_absence` gets a transient score `onset_gain exp(-(t - t_on) /
//!   onset_tau)` on top of its motion saliency, so it is noticed however
//!   slowly it moves. Abrupt onsets capture attention and the eyes
//!   (Yantis & Jonides 1984, J. Exp. Psychol. HPP 10:601; Theeuwes et al.
//!   1998, Psychol. Sci. 9:379, "our eyes do not always go where we want
//!   them to go"); the capture is transient, a few hundred ms.

use glam::DVec3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::behaviour::TopDown;
use crate::vision::Seen;

pub use crate::target::{BodyId, Source, Spot, TargetId};

/// Attention parameters (scene `vh.attention`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct AttentionParams {
    /// Whether bottom-up saliency competes at all.
    pub bottom_up: bool,
    /// Time constant of the saliency low-pass filter, s, 0-5. Default
    /// 0.03 (a few ticks); 0 is no filter. Beyond seconds the VH would
    /// not notice a punch before it lands.
    #[schemars(range(min = 0.0, max = 5.0))]
    pub smoothing_tau: f64,
    /// Minimum time on a new gaze target, s, 0-10. Default 0.15 (human
    /// fixations last 0.2-0.6 s); 10 s holds a target through any
    /// exchange.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub min_fixation: f64,
    /// A challenger this many times stronger interrupts a fixation early;
    /// a ratio, > 0 and at most 100. Default 2. Below 1 any challenger
    /// interrupts; at 100 practically nothing does (amounts are at most
    /// 100, and a target worth holding has one near 1 or more).
    #[schemars(range(max = 100.0), extend("exclusiveMinimum" = 0.0))]
    pub override_ratio: f64,
    /// Habituation time constant while a body holds the gaze bottom-up, s,
    /// 0.01-600. Default 2.5. The floor keeps the per-tick update stable
    /// (10 ticks of 1 ms); 600 s, longer than a bout's round, is
    /// habituation switched off.
    #[schemars(range(min = 0.01, max = 600.0))]
    pub habituation_tau: f64,
    /// Recovery time constant once the gaze has left, s, 0.01-600.
    /// Default 2. Bounds as `habituation_tau`'s.
    #[schemars(range(min = 0.01, max = 600.0))]
    pub recovery_tau: f64,
    /// Lowest weight habituation reaches, a fraction, 0-1. Default 0.2;
    /// 1 is no habituation.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub habituation_floor: f64,
    /// Peak transient score of a body that comes into view (H5), as an
    /// attention amount; 0 turns onset capture off (the seed). Default 3.5:
    /// above every top-down amount of the default personality, so an
    /// onset wins the gaze and turns the head fully (M8), but below a
    /// strong boxer's A_face (4), who keeps watching the face. 0-100, the
    /// bound of every attention amount (see `vh.personality`).
    #[schemars(range(min = 0.0, max = 100.0))]
    pub onset_gain: f64,
    /// Decay time constant of the onset transient, s, > 0 and at most 10.
    /// Default 0.3: onset capture is transient, a few hundred ms
    /// (Theeuwes et al. 1998); 10 s is far beyond any capture.
    #[schemars(range(max = 10.0), extend("exclusiveMinimum" = 0.0))]
    pub onset_tau: f64,
    /// A body must have been out of view this long for its return to count
    /// as an onset, s, 0-10. Default 0.15; 10 s counts only bodies long
    /// gone.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub onset_absence: f64,
}

impl Default for AttentionParams {
    fn default() -> Self {
        AttentionParams {
            bottom_up: true,
            smoothing_tau: 0.03,
            min_fixation: 0.15,
            override_ratio: 2.0,
            habituation_tau: 2.5,
            recovery_tau: 2.0,
            habituation_floor: 0.2,
            onset_gain: 3.5,
            onset_tau: 0.3,
            onset_absence: 0.15,
        }
    }
}

/// The winning gaze target this tick.
#[derive(Clone, Debug, PartialEq)]
pub struct GazeChoice {
    /// Target name ("head", "left_glove", "point", ...).
    pub name: String,
    /// Body it rides on, if any.
    pub body: Option<BodyId>,
    /// Where on that body.
    pub spot: Spot,
    /// Gaze point, world.
    pub point: DVec3,
    /// Its attention amount A (used by the head law, M8).
    pub amount: f64,
    /// Who won.
    pub source: Source,
}

impl GazeChoice {
    /// The target's identity from tick to tick.
    pub fn id(&self) -> TargetId {
        TargetId {
            source: self.source,
            body: self.body,
            spot: self.spot,
        }
    }
}

/// Attention's evolving state.
#[derive(Clone, Debug, Default)]
pub struct Attention {
    names: Vec<String>,
    smoothed: Vec<f64>,
    weight: Vec<f64>,
    current: Option<GazeChoice>,
    since: f64,
    /// When each body was last in view (`None`: never).
    last_seen: Vec<Option<f64>>,
    /// When each body last came into view (H5).
    onset: Vec<f64>,
    /// When attention first ran.
    start: Option<f64>,
    /// Each body's effective bottom-up score this tick (smoothed x weight),
    /// indexed by body; 0 for bodies not in view.
    pub scores: Vec<f64>,
}

impl Attention {
    /// Attention over the bodies of a world, named by index.
    pub fn new(names: Vec<String>) -> Self {
        Attention {
            names,
            ..Default::default()
        }
    }

    /// The current choice, if any.
    pub fn current(&self) -> Option<&GazeChoice> {
        self.current.as_ref()
    }

    /// Choose the gaze target. `body_pos` gives any body's current centre
    /// (for top-down targets the VH remembers even when out of view).
    pub fn step(
        &mut self,
        p: &AttentionParams,
        seen: &[Seen],
        top_down: &TopDown,
        body_pos: impl Fn(BodyId) -> DVec3,
        t: f64,
        dt: f64,
    ) -> GazeChoice {
        let n = self.names.len();
        self.smoothed.resize(n, 0.0);
        self.weight.resize(n, 1.0);
        self.last_seen.resize(n, None);
        self.onset.resize(n, f64::NEG_INFINITY);
        self.scores.clear();
        self.scores.resize(n, 0.0);
        let alpha = if p.smoothing_tau > 0.0 {
            (dt / p.smoothing_tau).min(1.0)
        } else {
            1.0
        };
        let mut in_view = vec![false; n];
        for s in seen {
            let i = s.body.index();
            in_view[i] = true;
            self.smoothed[i] += alpha * (s.saliency - self.smoothed[i]);
            // (H5): an onset is a return after `onset_absence` out of view;
            // what is there when the VH starts looking is no onset.
            let start = *self.start.get_or_insert(t);
            let away = t - self.last_seen[i].unwrap_or(start);
            if away > p.onset_absence + dt / 2.0 {
                self.onset[i] = t;
            }
            self.last_seen[i] = Some(t);
        }
        self.start.get_or_insert(t);
        for (b, &visible) in in_view.iter().enumerate() {
            let id = BodyId::new(b);
            if !visible {
                self.smoothed[b] *= 1.0 - alpha;
            }
            let held = self
                .current
                .as_ref()
                .is_some_and(|c| c.source == Source::BottomUp && c.body == Some(id));
            let w = &mut self.weight[b];
            if held {
                *w += (p.habituation_floor - *w) * (dt / p.habituation_tau);
            } else {
                *w += (1.0 - *w) * (dt / p.recovery_tau);
            }
            if visible {
                self.scores[b] = self.smoothed[b] * *w + onset_score(p, t - self.onset[b]);
            }
        }
        let td_point = top_down
            .body
            .map_or(top_down.offset, |b| body_pos(b) + top_down.offset);
        let top = GazeChoice {
            name: top_down.name.clone(),
            body: top_down.body,
            spot: top_down.spot,
            point: td_point,
            amount: top_down.amount,
            source: Source::TopDown,
        };
        // Bottom-up candidate: the visible body with the largest score (M1).
        let bottom = if p.bottom_up {
            seen.iter()
                .map(|s| (s.body, self.scores[s.body.index()]))
                .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))
                .map(|(b, score)| GazeChoice {
                    name: self.names[b.index()].clone(),
                    body: Some(b),
                    spot: Spot::Centre,
                    point: body_pos(b),
                    amount: score,
                    source: Source::BottomUp,
                })
        } else {
            None
        };
        // Arbitration (gaze.md 6): the larger amount wins.
        let winner = match bottom {
            Some(b) if b.amount > top.amount => b,
            _ => top,
        };
        let choice = match &self.current {
            Some(cur) if !same_target(cur, &winner) => {
                let cur_valid = match cur.source {
                    Source::BottomUp => cur.body.is_some_and(|b| in_view[b.index()]),
                    Source::TopDown => top_down.aims_at(cur.body, cur.spot),
                    Source::Override => false,
                };
                let cur_amount = match cur.source {
                    Source::BottomUp => cur.body.map_or(0.0, |b| self.scores[b.index()]),
                    _ => cur.amount,
                };
                let young = t - self.since < p.min_fixation;
                if cur_valid && young && winner.amount < p.override_ratio * cur_amount {
                    // Keep the current target, at its current position.
                    let mut keep = cur.clone();
                    keep.amount = cur_amount;
                    if let Some(b) = keep.body {
                        keep.point = if keep.source == Source::TopDown {
                            td_point
                        } else {
                            body_pos(b)
                        };
                    }
                    keep
                } else {
                    self.since = t;
                    winner
                }
            }
            Some(_) => winner,
            None => {
                self.since = t;
                winner
            }
        };
        self.current = Some(choice.clone());
        choice
    }

    /// Force a choice (gaze override); attention's timers follow it.
    pub fn force(&mut self, choice: GazeChoice, t: f64) {
        if self
            .current
            .as_ref()
            .is_none_or(|c| !same_target(c, &choice))
        {
            self.since = t;
        }
        self.current = Some(choice);
    }
}

/// The transient score of a body `age` seconds after it came into view (H5).
pub fn onset_score(p: &AttentionParams, age: f64) -> f64 {
    if p.onset_gain > 0.0 && age >= 0.0 {
        p.onset_gain * (-age / p.onset_tau).exp() // (H5)
    } else {
        0.0
    }
}

fn same_target(a: &GazeChoice, b: &GazeChoice) -> bool {
    a.id() == b.id()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> Vec<String> {
        ["head", "left_glove", "ball"].map(String::from).to_vec()
    }

    fn face(amount: f64) -> TopDown {
        TopDown {
            name: "head".into(),
            body: Some(BodyId::new(0)),
            spot: Spot::Centre,
            offset: DVec3::ZERO,
            amount,
        }
    }

    fn seen(body: usize, saliency: f64) -> Seen {
        Seen {
            body: BodyId::new(body),
            saliency,
            ..Seen::test_default()
        }
    }

    #[test]
    fn larger_amount_wins() {
        let p = AttentionParams {
            smoothing_tau: 0.0,
            min_fixation: 0.0,
            ..Default::default()
        };
        let mut a = Attention::new(names());
        let c = a.step(&p, &[seen(1, 1.0)], &face(1.5), |_| DVec3::ZERO, 0.0, 0.001);
        assert_eq!((c.name.as_str(), c.source), ("head", Source::TopDown));
        let c = a.step(
            &p,
            &[seen(1, 2.0)],
            &face(1.5),
            |_| DVec3::ZERO,
            0.001,
            0.001,
        );
        assert_eq!(
            (c.name.as_str(), c.source),
            ("left_glove", Source::BottomUp)
        );
        assert_eq!(c.amount, 2.0);
    }

    #[test]
    fn habituation_releases_a_constantly_salient_body() {
        let p = AttentionParams::default();
        let mut a = Attention::new(names());
        let dt = 0.001;
        let mut first_back = None;
        for i in 0..10_000 {
            let t = i as f64 * dt;
            let c = a.step(&p, &[seen(2, 3.0)], &face(1.5), |_| DVec3::ZERO, t, dt);
            if t > 0.5 && c.name == "head" && first_back.is_none() {
                first_back = Some(t);
            }
        }
        let back = first_back.expect("gaze returns to the face");
        // The ball takes the gaze once the face's minimum fixation (0.15 s)
        // is over; its weight then falls as w = 0.2 + 0.8 e^(-t/2.5) until
        // 3.0 w < 1.5, i.e. w = 0.5.
        let expect = p.min_fixation - 2.5 * ((0.5 - 0.2) / 0.8f64).ln();
        assert!(
            (back - expect).abs() < 0.01,
            "back at {back}, expected {expect}"
        );
    }

    #[test]
    fn minimum_fixation_prevents_flicker() {
        let p = AttentionParams {
            smoothing_tau: 0.0,
            ..Default::default()
        };
        let mut a = Attention::new(names());
        let dt = 0.001;
        let mut switches = 0;
        let mut last = String::new();
        for i in 0..1000 {
            let t = i as f64 * dt;
            // saliency alternating around the face's amount every tick
            let s = if i % 2 == 0 { 1.6 } else { 1.4 };
            let c = a.step(&p, &[seen(1, s)], &face(1.5), |_| DVec3::ZERO, t, dt);
            if c.name != last {
                switches += 1;
                last = c.name;
            }
        }
        assert!(
            switches <= 1 + (1.0 / p.min_fixation) as usize,
            "{switches} switches"
        );
    }

    /// (H5): a slow ball entering the view at 1 s takes the gaze from the
    /// face at once, for a while, then gives it back; the same ball in
    /// view from the start never does, nor does a blink-length absence.
    #[test]
    fn onset_captures_the_gaze_transiently() {
        let p = AttentionParams::default();
        let dt = 0.001;
        let run = |visible: &dyn Fn(f64) -> bool| {
            let mut a = Attention::new(names());
            let mut on_ball = Vec::new();
            for i in 0..3000 {
                let t = i as f64 * dt;
                let s = if visible(t) {
                    vec![seen(2, 0.3)]
                } else {
                    vec![]
                };
                let c = a.step(&p, &s, &face(1.5), |_| DVec3::ZERO, t, dt);
                if c.name == "ball" {
                    on_ball.push(t);
                }
            }
            on_ball
        };
        let entering = run(&|t| t >= 1.0);
        let (first, last) = (entering[0], *entering.last().unwrap());
        assert!((first - 1.0).abs() < 0.002, "captured at {first}");
        // Held while 0.3 + 3.5 e^(-age/0.3) > 1.5: about 0.32 s.
        let expect = 1.0 + 0.3 * (3.5f64 / 1.2).ln();
        assert!(
            (last - expect).abs() < 0.03,
            "released at {last}, expected {expect}"
        );
        assert!(run(&|_| true).is_empty(), "in view from the start");
        let flicker = run(&|t| !(0.1..0.2).contains(&t) || t < 0.0);
        assert!(flicker.is_empty(), "a 0.1 s absence is no onset");
        let back = run(&|t| !(0.1..0.4).contains(&t));
        assert!(back.first().is_some_and(|&b| (b - 0.4).abs() < 0.002));
    }
}
