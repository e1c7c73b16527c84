//! Static description of the sparring bodies: the virtual human's segments
//! and joints, and the opponent avatar. No simulation state lives here
//! (MuJoCo's "model" side); [`crate::physics::world`] builds the physics from it and
//! other exporters (e.g. an MJCF writer) can read the same description.
//!
//! World frame: +Y up, the VH stands at the origin facing +Z, so world +X is
//! the VH's left (the same convention as the head frame, see
//! [`shisen_gaze::util::math::dir_from_yaw_pitch`]). The opponent faces the VH from +Z.

use glam::{DVec3, Quat, Vec3};
use shisen_gaze::vision::BodyId;

/// Collision shape of a segment, in the segment's own frame (centred on its
/// reference point, capsules along local +Y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// Sphere of the given radius.
    Ball { radius: f32 },
    /// Capsule: segment of half-length `half_height` along Y, swept by `radius`.
    Capsule { half_height: f32, radius: f32 },
    /// Box with the given half extents.
    Cuboid { half: Vec3 },
}

/// How a segment hangs from its parent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointKind {
    /// The root: fixed to the ground (the VH stands on a rigid stand).
    Root,
    /// Three rotational degrees of freedom (neck, shoulder). Eyes are ball
    /// joints too, with their torsion held at zero by the controller.
    Ball,
    /// One rotational degree of freedom about `axis` (parent frame at rest).
    Hinge { axis: Vec3 },
    /// Rigidly welded (the glove on the forearm).
    Weld,
}

/// Joint ranges in degrees, in the yaw / pitch / roll parametrisation of
/// [`shisen_gaze::util::math::JointAngles`]. Targets are clamped to them; rapier's own
/// limits sit `HARD_STOP_MARGIN_DEG` beyond as a safety stop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Yaw range (about the parent's up axis), degrees.
    pub yaw: [f32; 2],
    /// Pitch range (positive up), degrees.
    pub pitch: [f32; 2],
    /// Roll range (about the forward axis), degrees.
    pub roll: [f32; 2],
}

/// Margin between the controller's clamping range and the physical stop.
pub const HARD_STOP_MARGIN_DEG: f32 = 5.0;

/// Joint groups share one set of PD gains (see [`crate::physics::control::Gains`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Group {
    /// The two eyeballs.
    Eye,
    /// The neck (head on torso).
    Neck,
    /// Both shoulders.
    Shoulder,
    /// Both elbows.
    Elbow,
}

impl Group {
    /// Every group, in file order.
    pub const ALL: [Group; 4] = [Group::Eye, Group::Neck, Group::Shoulder, Group::Elbow];

    /// Its place in per-group tables (its place in [`Group::ALL`]).
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The segment whose joint stands for the group (the left one of a pair).
    pub fn joint(self) -> Seg {
        match self {
            Group::Eye => Seg::EyeL,
            Group::Neck => Seg::Head,
            Group::Shoulder => Seg::UpperArmL,
            Group::Elbow => Seg::ForearmL,
        }
    }

    /// The group's main axis, 0 yaw or 1 pitch: yaw for the eyes; pitch
    /// for the neck (its larger, gravity-loaded inertia: yaw, 8x lighter,
    /// is then simply better damped) and flexion for shoulder and elbow.
    pub fn main_axis(self) -> usize {
        match self {
            Group::Eye => 0,
            Group::Neck | Group::Shoulder | Group::Elbow => 1,
        }
    }
}

/// One rigid segment of the virtual human.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// Unique name, used in traces, scenes and vision ("vh_head", ...).
    pub name: &'static str,
    /// The parent segment, `None` for the root.
    pub parent: Option<Seg>,
    /// Joint to the parent.
    pub joint: JointKind,
    /// Joint pivot in world coordinates at rest.
    pub pivot: Vec3,
    /// Centre of the segment (and of its collider) in world coordinates at rest.
    pub centre: Vec3,
    /// Collision shape; its axis is rotated by `axis_to` at rest.
    pub shape: Shape,
    /// Direction of the capsule's long axis at rest (world); ignored for balls and boxes.
    pub axis_to: Vec3,
    /// Mass in kg (ignored for the root).
    pub mass: f32,
    /// Gain group, for controlled joints.
    pub group: Option<Group>,
    /// Joint ranges (controlled joints).
    pub limits: Option<Limits>,
}

/// Eye geometry in the physics' single precision (the facts live in
/// [`shisen_gaze::anatomy::eye`]).
pub mod eye {
    use shisen_gaze::anatomy::eye as a;
    /// Eyeball radius, metres.
    pub const RADIUS: f32 = a::RADIUS as f32;
    /// Interpupillary distance, metres.
    pub const IPD: f32 = a::IPD as f32;
    /// Eye centre below the top of the head, metres.
    pub const BELOW_TOP: f32 = a::BELOW_TOP as f32;
    /// Eyeball mass, kg.
    pub const MASS: f32 = a::MASS as f32;
    /// Horizontal range of motion, degrees.
    pub const YAW_RANGE: f32 = a::YAW_RANGE_DEG as f32;
    /// Vertical range of motion, degrees.
    pub const PITCH_RANGE: f32 = a::PITCH_RANGE_DEG as f32;
}

/// The complete static description of the sparring world.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyPlan {
    /// VH segments; index 0 is the root (torso).
    pub segments: Vec<Segment>,
    /// Opponent head centre at rest (world).
    pub opponent_head: Vec3,
    /// Opponent head radius.
    pub opponent_head_radius: f32,
    /// Opponent glove rest positions (opponent's left, right), world.
    pub opponent_gloves: [Vec3; 2],
    /// Glove radius (both boxers).
    pub glove_radius: f32,
}

/// A segment of the virtual human: a typed handle into
/// [`BodyPlan::segments`] (in this order). The VH's segments are also the
/// world's first bodies, so a segment converts into the [`BodyId`] vision
/// and the world know it by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Seg {
    /// The trunk (the root).
    Torso,
    /// The head, on the neck joint.
    Head,
    /// The left eyeball.
    EyeL,
    /// The right eyeball.
    EyeR,
    /// Left upper arm, on the shoulder.
    UpperArmL,
    /// Left forearm, on the elbow.
    ForearmL,
    /// Left glove, welded to the forearm.
    GloveL,
    /// Right upper arm.
    UpperArmR,
    /// Right forearm.
    ForearmR,
    /// Right glove.
    GloveR,
}

impl Seg {
    /// Every segment, in plan order.
    pub const ALL: [Seg; 10] = [
        Seg::Torso,
        Seg::Head,
        Seg::EyeL,
        Seg::EyeR,
        Seg::UpperArmL,
        Seg::ForearmL,
        Seg::GloveL,
        Seg::UpperArmR,
        Seg::ForearmR,
        Seg::GloveR,
    ];
    /// The eyes, left then right.
    pub const EYES: [Seg; 2] = [Seg::EyeL, Seg::EyeR];

    /// Its place in [`BodyPlan::segments`] (and in per-segment tables).
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The segment at plan index `i`, if there is one.
    pub fn from_index(i: usize) -> Option<Seg> {
        Seg::ALL.get(i).copied()
    }

    /// The world body it is.
    pub const fn body(self) -> BodyId {
        BodyId::new(self as usize)
    }
}

impl From<Seg> for BodyId {
    fn from(s: Seg) -> BodyId {
        s.body()
    }
}

/// A part of the opponent avatar (yours, in the window): a typed handle
/// into the world's opponent bodies ([`crate::physics::world::World::part`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum OpponentPart {
    /// The head.
    Head,
    /// The opponent's left glove.
    LeftGlove,
    /// The opponent's right glove.
    RightGlove,
    /// The opponent's trunk, carried under its head (not scripted on its
    /// own: it follows the head's path, [`trunk_under`]).
    Trunk,
}

/// The opponent's trunk: a capsule from the waist to the shoulders, its
/// centre this far below the head's (m): the torso of a 1.75 m man, chest
/// and abdomen about 0.5 m tall (suprasternale 1.44 m, waist 1.05 m;
/// Gordon et al. 1989, ANSUR, median men), the head's centre about 0.2 m
/// above the suprasternale.
pub const TRUNK_BELOW_HEAD: f32 = 0.45;
/// The trunk capsule's radius and half its straight length, m (chest
/// depth about 0.25 m and breadth 0.33 m, Gordon et al. 1989: a 0.15 m
/// radius; 0.5 m tall in all).
pub const TRUNK_RADIUS: f32 = 0.15;
pub const TRUNK_HALF_HEIGHT: f32 = 0.1;

/// Where the opponent's trunk sits under its head at `head`, world.
pub fn trunk_under(head: Vec3) -> Vec3 {
    head - Vec3::Y * TRUNK_BELOW_HEAD
}

impl OpponentPart {
    /// The parts a timeline moves (head and gloves), in world order; the
    /// trunk follows the head.
    pub const ALL: [OpponentPart; 3] = [
        OpponentPart::Head,
        OpponentPart::LeftGlove,
        OpponentPart::RightGlove,
    ];
    /// Every part, the trunk last.
    pub const EVERY: [OpponentPart; 4] = [
        OpponentPart::Head,
        OpponentPart::LeftGlove,
        OpponentPart::RightGlove,
        OpponentPart::Trunk,
    ];
    /// The gloves, left then right.
    pub const GLOVES: [OpponentPart; 2] = [OpponentPart::LeftGlove, OpponentPart::RightGlove];

    /// Its place in per-part tables.
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The name vision, traces and scenes know it by.
    pub const fn name(self) -> &'static str {
        match self {
            OpponentPart::Head => "head",
            OpponentPart::LeftGlove => "left_glove",
            OpponentPart::RightGlove => "right_glove",
            OpponentPart::Trunk => "torso",
        }
    }
}

/// Top of the VH's head (world y at rest).
pub const HEAD_TOP_Y: f32 = HEAD_TOP_Y_M as f32;
/// The same, in double precision (the gaze laws' frame), m.
pub const HEAD_TOP_Y_M: f64 = 1.80;
/// Neck pivot (base of the neck), world.
pub const NECK_PIVOT: Vec3 = Vec3::new(0.0, 1.52, 0.0);
/// Eye centres sit this far in front of the neck axis.
pub const EYE_FORWARD: f32 = EYE_FORWARD_M as f32;
/// The same, in double precision, m.
pub const EYE_FORWARD_M: f64 = 0.072;
/// Upper arm length (shoulder to elbow), metres.
pub const UPPER_ARM_LEN: f32 = shisen_gaze::anatomy::arm::UPPER as f32;
/// Forearm length (elbow to glove centre), metres.
pub const FOREARM_LEN: f32 = shisen_gaze::anatomy::arm::FOREARM as f32;

impl BodyPlan {
    /// Centre of the VH's left (`side = 0`) or right (`side = 1`) eye at rest.
    pub fn eye_centre(side: usize) -> Vec3 {
        let x = if side == 0 {
            eye::IPD / 2.0
        } else {
            -eye::IPD / 2.0
        };
        Vec3::new(x, HEAD_TOP_Y - eye::BELOW_TOP, EYE_FORWARD)
    }

    /// The midpoint of the VH's eyes at rest (the cyclopean eye), world:
    /// where gaze targets at eye height are measured from.
    pub fn eyes_midpoint() -> DVec3 {
        DVec3::new(
            0.0,
            HEAD_TOP_Y_M - shisen_gaze::anatomy::eye::BELOW_TOP,
            EYE_FORWARD_M,
        )
    }

    /// Shoulder pivot, left (`side = 0`, +X) or right.
    pub fn shoulder(side: usize) -> Vec3 {
        Vec3::from_array(shisen_gaze::anatomy::arm::shoulder(side).map(|v| v as f32))
    }
}

impl Default for BodyPlan {
    /// A 1.8 m adult upper body (segment masses after Winter's anthropometric
    /// tables for a 75 kg adult: head 8.1 %, upper arm 2.8 %, forearm 1.6 %)
    /// facing an opponent at boxing distance (faces ~0.9 m apart).
    fn default() -> Self {
        use shisen_gaze::anatomy::neck;
        let neck_limits = Limits {
            yaw: [-neck::YAW_DEG as f32, neck::YAW_DEG as f32],
            pitch: [-neck::PITCH_DOWN_DEG as f32, neck::PITCH_UP_DEG as f32],
            roll: [-neck::ROLL_DEG as f32, neck::ROLL_DEG as f32],
        };
        let eye_limits = Limits {
            yaw: [-eye::YAW_RANGE, eye::YAW_RANGE],
            pitch: [-eye::PITCH_RANGE, eye::PITCH_RANGE],
            roll: [0.0, 0.0],
        };
        let shoulder_limits = Limits {
            yaw: [-100.0, 100.0],
            pitch: [-80.0, 170.0],
            roll: [-90.0, 90.0],
        };
        let elbow_limits = Limits {
            yaw: [0.0, 0.0],
            pitch: [0.0, 150.0],
            roll: [0.0, 0.0],
        };
        let head_centre = Vec3::new(0.0, HEAD_TOP_Y - 0.115, 0.0);
        let mut segments = vec![
            Segment {
                name: "vh_torso",
                parent: None,
                joint: JointKind::Root,
                pivot: Vec3::new(0.0, 1.0, 0.0),
                centre: Vec3::new(0.0, 1.25, 0.0),
                shape: Shape::Cuboid {
                    half: Vec3::new(0.16, 0.25, 0.10),
                },
                axis_to: Vec3::Y,
                mass: 0.0,
                group: None,
                limits: None,
            },
            Segment {
                name: "vh_head",
                parent: Some(Seg::Torso),
                joint: JointKind::Ball,
                pivot: NECK_PIVOT,
                centre: head_centre,
                shape: Shape::Ball { radius: 0.10 },
                axis_to: Vec3::Y,
                mass: 6.1,
                group: Some(Group::Neck),
                limits: Some(neck_limits),
            },
        ];
        for side in 0..2 {
            let c = Self::eye_centre(side);
            segments.push(Segment {
                name: ["vh_eye_l", "vh_eye_r"][side],
                parent: Some(Seg::Head),
                joint: JointKind::Ball,
                pivot: c,
                centre: c,
                shape: Shape::Ball {
                    radius: eye::RADIUS,
                },
                axis_to: Vec3::Y,
                mass: eye::MASS,
                group: Some(Group::Eye),
                limits: Some(eye_limits),
            });
        }
        for side in 0..2 {
            let sx = if side == 0 { 1.0 } else { -1.0 };
            let shoulder = Self::shoulder(side);
            // Arms hang forward-down in the rest pose; the guard stance is a target.
            let elbow = shoulder + Vec3::new(0.0, -UPPER_ARM_LEN, 0.0);
            let glove = elbow + Vec3::new(0.0, 0.0, FOREARM_LEN);
            let [upper, fore] = [
                [Seg::UpperArmL, Seg::ForearmL],
                [Seg::UpperArmR, Seg::ForearmR],
            ][side];
            debug_assert_eq!(segments.len(), upper.index());
            segments.push(Segment {
                name: ["vh_upper_arm_l", "vh_upper_arm_r"][side],
                parent: Some(Seg::Torso),
                joint: JointKind::Ball,
                pivot: shoulder,
                centre: (shoulder + elbow) / 2.0,
                shape: Shape::Capsule {
                    half_height: UPPER_ARM_LEN / 2.0 - 0.04,
                    radius: 0.045,
                },
                axis_to: Vec3::NEG_Y,
                mass: 2.1,
                group: Some(Group::Shoulder),
                limits: Some(shoulder_limits),
            });
            segments.push(Segment {
                name: ["vh_forearm_l", "vh_forearm_r"][side],
                parent: Some(upper),
                joint: JointKind::Hinge {
                    axis: Vec3::new(sx, 0.0, 0.0),
                },
                pivot: elbow,
                centre: elbow + Vec3::new(0.0, 0.0, FOREARM_LEN / 2.0 - 0.03),
                shape: Shape::Capsule {
                    half_height: FOREARM_LEN / 2.0 - 0.06,
                    radius: 0.04,
                },
                axis_to: Vec3::Z,
                mass: 1.2,
                group: Some(Group::Elbow),
                limits: Some(elbow_limits),
            });
            segments.push(Segment {
                name: ["vh_glove_l", "vh_glove_r"][side],
                parent: Some(fore),
                joint: JointKind::Weld,
                pivot: glove,
                centre: glove,
                shape: Shape::Ball { radius: 0.06 },
                axis_to: Vec3::Y,
                mass: 0.45,
                group: None,
                limits: None,
            });
        }
        debug_assert_eq!(segments.len(), Seg::ALL.len());
        BodyPlan {
            segments,
            opponent_head: Vec3::new(0.0, head_centre.y, 0.92),
            opponent_head_radius: 0.10,
            opponent_gloves: [Vec3::new(-0.13, 1.55, 0.66), Vec3::new(0.13, 1.55, 0.66)],
            glove_radius: 0.06,
        }
    }
}

/// Analytic two-link inverse kinematics of one arm: joint rotations
/// (shoulder relative to torso, elbow relative to upper arm) that put the
/// glove centre at `glove` (world). `side` 0 = left. The elbow swivel is
/// chosen to keep the elbow down and out, as a boxer's guard does.
pub fn arm_ik(side: usize, glove: DVec3) -> (Quat, Quat) {
    let shoulder = BodyPlan::shoulder(side).as_dvec3();
    let (l1, l2) = (UPPER_ARM_LEN as f64, FOREARM_LEN as f64);
    let mut d = glove - shoulder;
    let r = d.length().clamp((l1 - l2).abs() + 1e-3, l1 + l2 - 1e-3);
    d = d.normalize_or(DVec3::Z) * r;
    // Interior elbow angle from the law of cosines; elbow "pitch" phi is
    // measured from the rest pose (forearm forward): sin(phi) = cos(interior).
    let cos_int = ((l1 * l1 + l2 * l2 - r * r) / (2.0 * l1 * l2)).clamp(-1.0, 1.0);
    let phi = cos_int.asin();
    let elbow = Quat::from_rotation_x(-phi as f32);
    // Glove position in the shoulder frame for that elbow angle.
    let g0 = DVec3::new(0.0, -l1, 0.0) + DVec3::new(0.0, phi.sin(), phi.cos()) * l2;
    let aim = glam::DQuat::from_rotation_arc(g0.normalize(), d.normalize());
    // Swivel about the shoulder-glove axis: bring the elbow toward down-and-out.
    let axis = d.normalize();
    let elbow_dir = aim * DVec3::NEG_Y;
    let sx = if side == 0 { 1.0 } else { -1.0 };
    let want = DVec3::new(0.6 * sx, -1.0, 0.0).normalize();
    let proj = |v: DVec3| (v - axis * v.dot(axis)).normalize_or_zero();
    let (a, b) = (proj(elbow_dir), proj(want));
    let swivel = if a == DVec3::ZERO || b == DVec3::ZERO {
        0.0
    } else {
        a.cross(b).dot(axis).atan2(a.dot(b))
    };
    let shoulder_q = glam::DQuat::from_axis_angle(axis, swivel) * aim;
    (shoulder_q.as_quat(), elbow)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ik_reaches_the_target() {
        for side in 0..2 {
            let sx: f32 = if side == 0 { 1.0 } else { -1.0 };
            for target in [
                DVec3::new(0.11 * sx as f64, 1.56, 0.27),
                DVec3::new(0.0, 1.55, 0.45),
                DVec3::new(0.3 * sx as f64, 1.3, 0.3),
            ] {
                let (qs, qe) = arm_ik(side, target);
                let shoulder = BodyPlan::shoulder(side);
                let elbow = shoulder + qs * Vec3::new(0.0, -UPPER_ARM_LEN, 0.0);
                let glove = elbow + qs * qe * Vec3::new(0.0, 0.0, FOREARM_LEN);
                assert!(
                    (glove.as_dvec3() - target).length() < 1e-4,
                    "side {side} target {target} got {glove}"
                );
                assert!(
                    (elbow.x - shoulder.x) * sx > -0.05,
                    "elbow stays out: {elbow} vs {shoulder}"
                );
            }
        }
    }

    #[test]
    fn plan_matches_seed_eye_geometry() {
        let plan = BodyPlan::default();
        let l = plan.segments[Seg::EyeL.index()].centre;
        let r = plan.segments[Seg::EyeR.index()].centre;
        assert!(((l - r).length() - 0.0619).abs() < 1e-6);
        assert!((HEAD_TOP_Y - l.y - 0.1255).abs() < 1e-6);
        assert!(l.x > 0.0, "left eye on the VH's left (+X)");
        assert_eq!(plan.segments[Seg::GloveR.index()].name, "vh_glove_r");
        for (i, s) in plan.segments.iter().enumerate() {
            if let Some(p) = s.parent {
                assert!(p.index() < i, "parents precede children");
            }
        }
    }
}
