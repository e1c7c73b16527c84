//! Named expressive gaze shifts built on the sigmoid law (T1) and the
//! published tables.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use glam::DVec2;

use super::law::*;

/// Named expressive gaze shifts. Takagi & Takeda name these variants but
/// publish parameters only for the dialogue-like test 2; the values below are
/// our reading of their descriptions, documented per variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum Preset {
    /// Multi-party dialogue (their fig. 5a, test-2 timing): the eyes lead, the
    /// head follows 0.15 s later and turns about 60 % of the way (test-2 mean
    /// head/gaze ratio), so the face never quite faces the addressee.
    Dialogue,
    /// Upward glance ("uwame-zukai"): like dialogue, but the head pitch stops
    /// at 20 % of the target elevation; the eyes do the rest.
    UpwardGlance,
    /// Surprised: fast and front-loaded (b = 2: fast start, slow end); gaze in
    /// 0.5 s, head 90 % of the way in 0.6 s, almost together.
    Surprised,
    /// Eerie: the eyes snap to the target and stare while the head follows
    /// late (0.6 s), slowly (2.5 s) and almost mechanically (c = 1.5,
    /// nearly linear) until it faces the target.
    Eerie,
    /// Anticipatory wind-up (their "two sigmoids"): head and gaze first turn
    /// slightly away (15 % of the head's swing, 0.35 s), then swing to the
    /// target (gaze) and 80 % of it (head).
    WindUp,
    /// Looking up from a desk at a visitor (their fig. 5b): the head starts
    /// first while the gaze stays on the desk, then the gaze overtakes it and
    /// both end on the target (the eyes go back and forth).
    LookUpFromDesk,
}

impl Preset {
    /// Builds the preset for a target `(h, v)` in degrees (horizontal, vertical).
    pub fn build(self, target_deg: DVec2) -> GazeShift {
        let (h, v) = (target_deg.x, target_deg.y);
        let sig = |a: f64, b: f64, c: f64, t: [f64; 3]| {
            AxisTrack::sigmoid(Sigmoid::from_deg(a, b, c, t[0], t[1], t[2]))
        };
        match self {
            Preset::Dialogue | Preset::UpwardGlance => {
                let pitch_ratio = if self == Preset::Dialogue { 0.6 } else { 0.2 };
                GazeShift {
                    head_yaw: sig(0.6 * h, 1.0, 8.0, [0.15, 1.55, 0.1]),
                    head_pitch: sig(pitch_ratio * v, 1.0, 8.0, [0.15, 1.55, 0.1]),
                    gaze_yaw: sig(h, 1.0, 8.0, [0.0, 1.6, 0.2]),
                    gaze_pitch: sig(v, 1.0, 8.0, [0.0, 1.6, 0.2]),
                }
            }
            Preset::Surprised => GazeShift {
                head_yaw: sig(0.9 * h, 2.0, 14.0, [0.05, 0.6, 0.3]),
                head_pitch: sig(0.9 * v, 2.0, 14.0, [0.05, 0.6, 0.3]),
                gaze_yaw: sig(h, 2.0, 16.0, [0.0, 0.5, 0.45]),
                gaze_pitch: sig(v, 2.0, 16.0, [0.0, 0.5, 0.45]),
            },
            Preset::Eerie => GazeShift {
                head_yaw: sig(h, 1.0, 1.5, [0.6, 2.5, 0.2]),
                head_pitch: sig(v, 1.0, 1.5, [0.6, 2.5, 0.2]),
                gaze_yaw: sig(h, 1.0, 12.0, [0.0, 0.4, 2.9]),
                gaze_pitch: sig(v, 1.0, 12.0, [0.0, 0.4, 2.9]),
            },
            Preset::WindUp => {
                let wind = |a_head: f64, a_gaze: f64| {
                    let back = -0.15 * a_head;
                    let away = Sigmoid::from_deg(back, 1.0, 14.0, 0.0, 0.35, 0.0);
                    let head = AxisTrack {
                        offset: 0.0,
                        segments: vec![
                            Segment::Sigmoid(away),
                            Segment::Sigmoid(Sigmoid::from_deg(
                                a_head - back,
                                1.0,
                                10.0,
                                0.35,
                                0.9,
                                0.2,
                            )),
                        ],
                    };
                    let gaze = AxisTrack {
                        offset: 0.0,
                        segments: vec![
                            Segment::Sigmoid(away),
                            Segment::Sigmoid(Sigmoid::from_deg(
                                a_gaze - back,
                                1.0,
                                12.0,
                                0.35,
                                0.7,
                                0.4,
                            )),
                        ],
                    };
                    (head, gaze)
                };
                let (head_yaw, gaze_yaw) = wind(0.8 * h, h);
                let (head_pitch, gaze_pitch) = wind(0.8 * v, v);
                GazeShift {
                    head_yaw,
                    head_pitch,
                    gaze_yaw,
                    gaze_pitch,
                }
            }
            Preset::LookUpFromDesk => GazeShift {
                head_yaw: sig(h, 0.7, 6.0, [0.0, 1.2, 0.3]),
                head_pitch: sig(v, 0.7, 6.0, [0.0, 1.2, 0.3]),
                gaze_yaw: sig(h, 1.0, 14.0, [0.4, 0.5, 0.6]),
                gaze_pitch: sig(v, 1.0, 14.0, [0.4, 0.5, 0.6]),
            },
        }
    }
}
