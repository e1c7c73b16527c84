//! Vision: the list of bodies the VH sees this tick (gaze.md 3), and their
//! bottom-up saliency (M1).
//!
//! A body is seen when its centre lies inside either eye's field of view
//! (a per-eye field around that eye's current line of sight) and the ray
//! from that eye to the centre, or to a point round it, hits the body
//! itself first (occlusion, a ray query the world answers: a body partly
//! behind another is seen). The VH's own segments are skipped unless
//! `see_self` is set.
//!
//! Vision reads the world through the small [`Scenery`] trait, so it runs
//! on any world: the physics world implements it, and so can a host
//! application's.

use glam::{DQuat, DVec3, Vec3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use crate::target::BodyId;

/// A body's orientation and motion, world frame (read only for bodies in
/// view).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    /// Orientation.
    pub orientation: DQuat,
    /// Linear velocity.
    pub velocity: DVec3,
    /// Angular velocity.
    pub angvel: DVec3,
}

/// What vision needs to know about the world it looks at.
pub trait Scenery {
    /// The VH's head orientation, world.
    fn head_rotation(&self) -> DQuat;
    /// Eye `k` (0 left, 1 right): its centre and its line of sight (unit), world.
    fn eye(&self, k: usize) -> (Vec3, DVec3);
    /// Number of bodies ([`BodyId`]s `0..n` name them).
    fn body_count(&self) -> usize;
    /// Whether body `b` is a part of the VH itself.
    fn is_own(&self, b: BodyId) -> bool;
    /// Centre of body `b`, world.
    fn position(&self, b: BodyId) -> DVec3;
    /// Orientation and motion of body `b`.
    fn motion(&self, b: BodyId) -> Motion;
    /// Whether the ray from `from` along `dir` (not normalised; its length
    /// reaches the target's centre) hits body `target` before anything else
    /// (VH parts never block: the eyes look out of the head).
    fn first_hit(&self, from: Vec3, dir: DVec3, target: BodyId) -> bool;
    /// How far body `b` reaches from its centre across a line of sight, m:
    /// about its half width (0, the default: vision tests its centre only).
    fn radius(&self, _b: BodyId) -> f64 {
        0.0
    }
}

/// Where vision looks for a body whose centre is hidden: four points
/// round the centre across the line of sight, at this fraction of the
/// body's [`Scenery::radius`] (inside its outline).
const RIM: f64 = 0.7;

/// Whether an eye at `eye` sees body `b` (centre `centre`): the ray to its
/// centre reaches it first or, if something stands in front of the centre,
/// a ray to one of four points round it does. A head behind two raised
/// gloves still shows between and above them, and is seen; only a body
/// hidden behind others is not (gaze.md 3).
fn sees(world: &impl Scenery, eye: Vec3, centre: DVec3, b: BodyId) -> bool {
    let from = eye.as_dvec3();
    let to = centre - from;
    if world.first_hit(eye, to, b) {
        return true;
    }
    let r = RIM * world.radius(b);
    if r <= 0.0 {
        return false;
    }
    let f = to.normalize_or(DVec3::Z);
    let across = f.cross(DVec3::Y).normalize_or(DVec3::X);
    let up = across.cross(f);
    [across, -across, up, -up]
        .into_iter()
        .any(|d| world.first_hit(eye, centre + d * r - from, b))
}

/// One eye's field of view around its line of sight, degrees (gaze.md 3:
/// human monocular field). Each side is 0-180 deg: a half turn is the
/// most a field can open to one side.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct FieldOfView {
    /// Toward the temple, deg, 0-180. Default 100 (human: about 100).
    #[schemars(range(min = 0.0, max = 180.0))]
    pub temporal_deg: f64,
    /// Toward the nose, deg, 0-180. Default 60 (human: about 60).
    #[schemars(range(min = 0.0, max = 180.0))]
    pub nasal_deg: f64,
    /// Up, deg, 0-180. Default 60 (human: about 60).
    #[schemars(range(min = 0.0, max = 180.0))]
    pub up_deg: f64,
    /// Down, deg, 0-180. Default 75 (human: about 75).
    #[schemars(range(min = 0.0, max = 180.0))]
    pub down_deg: f64,
}

impl Default for FieldOfView {
    fn default() -> Self {
        FieldOfView {
            temporal_deg: 100.0,
            nasal_deg: 60.0,
            up_deg: 60.0,
            down_deg: 75.0,
        }
    }
}

/// Vision and saliency parameters (scene `vh.vision`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct VisionParams {
    /// Per-eye field (the same numbers mirrored for the two eyes).
    pub field: FieldOfView,
    /// Bodies farther than this are not seen, m, 0.01-1000. Default 20
    /// (the ring is a few metres across; 1 km is beyond any room or hall).
    #[schemars(range(min = 0.01, max = 1000.0))]
    pub max_distance: f64,
    /// Whether the VH sees its own body parts.
    pub see_self: bool,
    /// Whether hidden bodies are dropped (ray test).
    pub occlusion: bool,
    /// The original implementation's foveal weighting: multiply the score by
    /// exp(-2 theta^2), theta the angle (rad) from the line of sight
    /// (gaze.md 11). Off by default: the seed's (M1) has no such factor.
    pub foveal_weight: bool,
    /// The original's distance scaling: translation x3/r, expansion x2/r
    /// (gaze.md 11). Off by default.
    pub distance_scaling: bool,
    /// The axis `e` the motion of (M1) is split along.
    pub saliency_axis: SaliencyAxis,
    /// Visual latency, s: the stages after vision (behaviour, attention)
    /// act on what the eyes saw this long ago. Default 0.07: visual
    /// responses reach V1 and the motion area MT 66-72 ms after a stimulus
    /// (Schmolesky et al. 1998, J. Neurophysiol. 79:3272); the seed: 0.
    /// 0-1 s: a second covers slowed or fatigued subjects many times over.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub latency: f64,
}

/// The axis along which (M1) splits a body's motion into "across" and
/// "expansion".
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum SaliencyAxis {
    /// The gaze direction (the mean of the two lines of sight), as (M1) is
    /// printed: motion across the line of sight versus along it.
    #[default]
    Gaze,
    /// The direction from the eyes to each body: "expansion" then means
    /// looming toward the eyes wherever the body is in the field.
    ToBody,
}

impl Default for VisionParams {
    fn default() -> Self {
        VisionParams {
            field: FieldOfView::default(),
            max_distance: 20.0,
            see_self: false,
            occlusion: true,
            foveal_weight: false,
            distance_scaling: false,
            saliency_axis: SaliencyAxis::Gaze,
            latency: 0.07,
        }
    }
}

/// A body in view, in the terms vision and attention use.
#[derive(Clone, Debug, PartialEq)]
pub struct Seen {
    /// Which body (see [`Scenery`]).
    pub body: BodyId,
    /// Centre, world.
    pub position: DVec3,
    /// Orientation, world.
    pub orientation: DQuat,
    /// Linear velocity, world.
    pub velocity: DVec3,
    /// Angular velocity, world.
    pub angvel: DVec3,
    /// Unit direction from the cyclopean eye (midpoint of the eyes), head frame.
    pub dir_head: DVec3,
    /// Distance from the cyclopean eye, m.
    pub distance: f64,
    /// Seen by the left / right eye.
    pub by_eye: [bool; 2],
    /// Velocity in the head's axes (own head motion compensated).
    pub rel_velocity: DVec3,
    /// Angular velocity in the head's axes.
    pub rel_angvel: DVec3,
    /// The three terms of (M1): translation, expansion, rotation.
    pub terms: [f64; 3],
    /// Bottom-up saliency A_i (M1, with the optional weights).
    pub saliency: f64,
}

impl Seen {
    /// An all-zero record (tests build on it).
    pub fn test_default() -> Self {
        Seen {
            body: BodyId::new(0),
            position: DVec3::ZERO,
            orientation: DQuat::IDENTITY,
            velocity: DVec3::ZERO,
            angvel: DVec3::ZERO,
            dir_head: DVec3::Z,
            distance: 1.0,
            by_eye: [true, true],
            rel_velocity: DVec3::ZERO,
            rel_angvel: DVec3::ZERO,
            terms: [0.0; 3],
            saliency: 0.0,
        }
    }
}

/// The three terms of the bottom-up saliency (M1) for velocity `v`, angular
/// velocity `l` and unit line of sight `e`:
/// `|v - (v.e) e|` (across), `|(v.e) e|` (expansion), `|(l.e) e|` (rotation).
///
/// `e` is the gaze direction as (M1) prints it, or, with
/// [`SaliencyAxis::ToBody`], the direction to the body itself (the two
/// agree for the fixated body).
pub fn saliency_terms(v: DVec3, l: DVec3, e: DVec3) -> [f64; 3] {
    let along = v.dot(e);
    [
        (v - along * e).length(), // (M1) translation across the line of sight
        along.abs(),              // (M1) expansion / contraction
        l.dot(e).abs(),           // (M1) rotation about the line of sight
    ]
}

/// Whether a head-frame direction, as seen from one eye whose line of sight
/// is `los` (unit, head frame), lies in that eye's field. `left` selects the
/// eye (its temporal side is +X, the VH's left).
pub fn in_field(f: &FieldOfView, los: DVec3, dir: DVec3, left: bool) -> bool {
    let (ly, lp) = crate::util::math::yaw_pitch_of(los);
    let (dy, dp) = crate::util::math::yaw_pitch_of(dir);
    let mut dyaw = dy - ly;
    if dyaw > std::f64::consts::PI {
        dyaw -= std::f64::consts::TAU;
    } else if dyaw < -std::f64::consts::PI {
        dyaw += std::f64::consts::TAU;
    }
    let dpitch = dp - lp;
    // Temporal is toward +yaw (left) for the left eye, -yaw for the right.
    let (temporal, nasal) = if left {
        (f.temporal_deg, f.nasal_deg)
    } else {
        (f.nasal_deg, f.temporal_deg)
    };
    let yaw_ok = dyaw <= temporal.to_radians() && -dyaw <= nasal.to_radians();
    let pitch_ok = dpitch <= f.up_deg.to_radians() && -dpitch <= f.down_deg.to_radians();
    yaw_ok && pitch_ok
}

/// Everything the VH sees now, with saliency. `open` says which eyes are
/// open (a shut or covered eye sees nothing). `out` is reused between ticks.
pub fn see(world: &impl Scenery, p: &VisionParams, open: [bool; 2], out: &mut Vec<Seen>) {
    out.clear();
    let head_rot = world.head_rotation();
    let head_inv = head_rot.inverse();
    let eyes = [0, 1].map(|k| {
        let (pos, los_world) = world.eye(k);
        (pos, head_inv * los_world)
    });
    let cyclops = ((eyes[0].0 + eyes[1].0) / 2.0).as_dvec3();
    let gaze = (eyes[0].1 + eyes[1].1).normalize_or(DVec3::Z);
    for i in BodyId::all(world.body_count()) {
        if world.is_own(i) && !p.see_self {
            continue;
        }
        let pos = world.position(i);
        let to = pos - cyclops;
        let distance = to.length();
        if distance < 1e-6 || distance > p.max_distance {
            continue;
        }
        let mut by_eye = [false; 2];
        for (k, (eye_pos, los)) in eyes.iter().enumerate() {
            if !open[k] {
                continue;
            }
            let ray_dir = pos - eye_pos.as_dvec3();
            if !in_field(&p.field, *los, head_inv * ray_dir.normalize(), k == 0) {
                continue;
            }
            by_eye[k] = !p.occlusion || sees(world, *eye_pos, pos, i);
        }
        if !by_eye[0] && !by_eye[1] {
            continue;
        }
        let body = world.motion(i);
        let (velocity, angvel) = (body.velocity, body.angvel);
        // Head-relative motion (gaze.md 4): the body's own motion, in the
        // head's axes. The agent's own head motion is compensated (as the
        // vestibular signal and efference copy do for a person), so turning
        // or rocking the head makes nothing salient; only bodies that move
        // in the world do.
        let rel_v = head_inv * velocity;
        let rel_w = head_inv * angvel;
        let dir_head = head_inv * (to / distance);
        let axis = match p.saliency_axis {
            SaliencyAxis::Gaze => gaze,
            SaliencyAxis::ToBody => dir_head,
        };
        let mut terms = saliency_terms(rel_v, rel_w, axis); // (M1)
        if p.distance_scaling {
            terms[0] *= 3.0 / distance;
            terms[1] *= 2.0 / distance;
        }
        let mut saliency = terms.iter().sum::<f64>();
        if p.foveal_weight {
            let theta = crate::util::math::angle_between(gaze, dir_head);
            saliency *= (-2.0 * theta * theta).exp();
        }
        out.push(Seen {
            body: i,
            position: pos,
            orientation: body.orientation,
            velocity,
            angvel,
            dir_head,
            distance,
            by_eye,
            rel_velocity: rel_v,
            rel_angvel: rel_w,
            terms,
            saliency,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn m1_terms_separate_the_three_motions() {
        let e = DVec3::Z;
        assert_eq!(
            saliency_terms(DVec3::new(2.0, 0.0, 0.0), DVec3::ZERO, e),
            [2.0, 0.0, 0.0]
        );
        assert_eq!(
            saliency_terms(DVec3::new(0.0, 0.0, -3.0), DVec3::ZERO, e),
            [0.0, 3.0, 0.0]
        );
        assert_eq!(
            saliency_terms(DVec3::ZERO, DVec3::new(0.0, 0.0, 5.0), e),
            [0.0, 0.0, 5.0]
        );
        // spin about an axis across the line of sight is not "rotation about" it
        assert_eq!(
            saliency_terms(DVec3::ZERO, DVec3::new(5.0, 0.0, 0.0), e),
            [0.0, 0.0, 0.0]
        );
    }

    /// (M1) splits motion along the gaze direction: a body 45 deg off the
    /// line of sight looming straight at the eyes moves half across, half
    /// along the gaze; measured against its own direction it only expands.
    #[test]
    fn m1_axis_is_the_gaze_direction_unless_asked_otherwise() {
        let gaze = DVec3::Z;
        let to_body = DVec3::new(1.0, 0.0, 1.0).normalize();
        let v = -to_body * 2.0;
        let [across, along, _] = saliency_terms(v, DVec3::ZERO, gaze);
        assert!((across - 2f64.sqrt()).abs() < 1e-12 && (along - 2f64.sqrt()).abs() < 1e-12);
        let [across, along, _] = saliency_terms(v, DVec3::ZERO, to_body);
        assert!(across < 1e-12 && (along - 2.0).abs() < 1e-12);
    }

    /// One body looming at eyes that look straight ahead.
    struct Looming;

    impl Scenery for Looming {
        fn head_rotation(&self) -> DQuat {
            DQuat::IDENTITY
        }
        fn eye(&self, k: usize) -> (Vec3, DVec3) {
            (
                Vec3::new(if k == 0 { 0.03 } else { -0.03 }, 0.0, 0.0),
                DVec3::Z,
            )
        }
        fn body_count(&self) -> usize {
            1
        }
        fn is_own(&self, _: BodyId) -> bool {
            false
        }
        fn position(&self, _: BodyId) -> DVec3 {
            DVec3::new(1.0, 0.0, 1.0)
        }
        fn motion(&self, _: BodyId) -> Motion {
            Motion {
                orientation: DQuat::IDENTITY,
                velocity: -DVec3::new(1.0, 0.0, 1.0).normalize() * 2.0,
                angvel: DVec3::ZERO,
            }
        }
        fn first_hit(&self, _: Vec3, _: DVec3, _: BodyId) -> bool {
            true
        }
    }

    #[test]
    fn see_splits_motion_along_the_chosen_axis() {
        let terms = |axis| {
            let p = VisionParams {
                saliency_axis: axis,
                ..VisionParams::default()
            };
            let mut out = Vec::new();
            see(&Looming, &p, [true, true], &mut out);
            out[0].terms
        };
        let g = terms(SaliencyAxis::Gaze);
        assert!((g[0] - 2f64.sqrt()).abs() < 1e-9 && (g[1] - 2f64.sqrt()).abs() < 1e-9);
        let b = terms(SaliencyAxis::ToBody);
        assert!(b[0] < 1e-9 && (b[1] - 2.0).abs() < 1e-9, "{b:?}");
    }

    #[test]
    fn field_edges_are_per_eye() {
        let f = FieldOfView::default();
        let los = DVec3::Z;
        let at = |yaw: f64, pitch: f64| {
            crate::util::math::dir_from_yaw_pitch(yaw.to_radians(), pitch.to_radians())
        };
        // left eye: temporal (+yaw) to 100 deg, nasal (-yaw) to 60 deg
        assert!(in_field(&f, los, at(99.0, 0.0), true));
        assert!(!in_field(&f, los, at(101.0, 0.0), true));
        assert!(in_field(&f, los, at(-59.0, 0.0), true));
        assert!(!in_field(&f, los, at(-61.0, 0.0), true));
        // right eye mirrored
        assert!(in_field(&f, los, at(-99.0, 0.0), false));
        assert!(!in_field(&f, los, at(61.0, 0.0), false));
        // vertical: up 60, down 75
        assert!(in_field(&f, los, at(0.0, 59.0), true) && !in_field(&f, los, at(0.0, 61.0), true));
        assert!(
            in_field(&f, los, at(0.0, -74.0), true) && !in_field(&f, los, at(0.0, -76.0), true)
        );
        // the field moves with the line of sight
        let turned = at(40.0, 0.0);
        assert!(in_field(&f, turned, at(139.0, 0.0), true));
    }

    /// A head 1 m ahead behind a glove that hides its centre (a disc of
    /// radius `cover` round the line of sight, 0.2 m before it), seen
    /// round the glove when the glove is smaller than the head.
    struct Covered {
        head: f64,
        cover: f64,
    }

    impl Scenery for Covered {
        fn head_rotation(&self) -> DQuat {
            DQuat::IDENTITY
        }
        fn eye(&self, _: usize) -> (Vec3, DVec3) {
            (Vec3::ZERO, DVec3::Z)
        }
        fn body_count(&self) -> usize {
            1
        }
        fn is_own(&self, _: BodyId) -> bool {
            false
        }
        fn position(&self, _: BodyId) -> DVec3 {
            DVec3::Z
        }
        fn motion(&self, _: BodyId) -> Motion {
            Motion {
                orientation: DQuat::IDENTITY,
                velocity: DVec3::ZERO,
                angvel: DVec3::ZERO,
            }
        }
        fn first_hit(&self, from: Vec3, dir: DVec3, _: BodyId) -> bool {
            // Where the ray crosses the glove's plane (z = 0.8), and
            // whether it then reaches the head.
            let at = from.as_dvec3() + dir * (0.8 - f64::from(from.z)) / dir.z;
            let off = DVec3::new(at.x, at.y, 0.0).length();
            off >= self.cover && (dir.normalize() - DVec3::Z).length() <= self.head + 1e-9
        }
        fn radius(&self, _: BodyId) -> f64 {
            self.head
        }
    }

    #[test]
    fn a_body_partly_behind_another_is_seen() {
        let seen = |head, cover| {
            let mut out = Vec::new();
            see(
                &Covered { head, cover },
                &VisionParams::default(),
                [true, true],
                &mut out,
            );
            !out.is_empty()
        };
        assert!(seen(0.1, 0.0), "in the open");
        // A glove of 5 cm radius hides the centre, not the head's edges.
        assert!(seen(0.1, 0.05), "round a small glove");
        // One as wide as the head's rim points hides it all.
        assert!(!seen(0.1, 0.1), "behind a wide one");
        // A body of no size is tested at its centre only.
        assert!(seen(0.0, 0.0) && !seen(0.0, 0.05), "no size");
    }
}
