//! The body stage: the lower body steps and the waist turns toward the
//! planned posture, with the pelvis driven along the plan or balanced on
//! physical legs; your avatar's body carried under its head.

use std::f64::consts::{PI, TAU};

use glam::{DQuat, DVec3};

use super::Sim;
use crate::physics::balance::{Balance, Stance, share_between, shares};
use crate::physics::body::OpponentPart;
use crate::physics::body::Seg;
use crate::physics::legs::{Joint, Part};
use crate::physics::lower::{BodyCommand, LowerBody, Pelvis, WAIST_REST};
use shisen_gaze::behaviour::{Ranges, Zone};

/// A planted foot twisted this far from its heading is re-placed, deg
/// (our choice: a boxer's rear foot pivots some 20 deg in a cross).
const FOOT_TWIST: f64 = 25.0;

/// A swinging foot that meets the canvas past this share of its swing has
/// landed (our choice: the first half of a 4 cm glide scuffs the canvas).
const TOUCH_DOWN: f64 = 0.5;

/// The largest share of the weight a foot may carry when a footwork step
/// lifts it (our choice: people shift their weight onto the stance foot
/// before a step; the anticipatory postural adjustment, Jian et al. 1993,
/// Gait Posture 1:9).
const LIFT_LOAD: f64 = 0.3;

/// Where a weight shift before a step puts the body, as the share of the
/// way from the lifting foot to the stance foot.
const SHIFT_TO: f64 = 0.85;

/// A swinging foot still on the canvas this long after its swing began,
/// carrying more than `STUCK_LOAD` of the weight, has not stepped, s (our
/// choice: a foot unloads within about 0.1 s of a weight shift).
const LIFT_WAIT: f64 = 0.08;
const STUCK_LOAD: f64 = 0.5;

/// The referee's count after a knockdown that a boxer must wait out, even
/// on its feet before it, s: the mandatory eight-count (AIBA Technical &
/// Competition Rules 2019; the count is one a second).
pub const EIGHT_COUNT: f64 = 8.0;

impl Sim {
    /// Body: the lower body steps and the waist turns toward the planned
    /// posture (the lunge of a punch shifts the hips, so the feet step in
    /// and out with it); the trunk is put where they carry it.
    pub(super) fn plan_body(&mut self, t: f64) -> (DVec3, glam::DQuat) {
        let dt = self.model.dt;
        let carried = self
            .timeline
            .carry
            .map_or(DVec3::ZERO, |c| c.offset(t + dt));
        let lunge = self.behaviour.torso_offset(t + dt);
        let p = &self.model.params.body;
        if p.human && p.pelvis == Pelvis::Balanced && self.world.legs.is_some() {
            return self.balance_body(t, lunge);
        }
        if !p.human {
            self.world.set_root_offset((lunge + carried).as_vec3());
            return (lunge + carried, glam::DQuat::IDENTITY);
        }
        let at = |k: f64| self.behaviour.posture(t + dt + k * dt);
        let (before, now, after) = (at(-1.0), at(0.0), at(1.0));
        let lunge_v = (self.behaviour.torso_offset(t + 2.0 * dt) - lunge) / dt;
        let cmd = BodyCommand {
            pelvis: now.pelvis + DVec3::new(lunge.x, 0.0, lunge.z),
            pelvis_velocity: (after.pelvis - before.pelvis) / (2.0 * dt) + lunge_v,
            waist: [
                now.waist,
                (after.waist - before.waist) / (2.0 * dt),
                (after.waist - 2.0 * now.waist + before.waist) / (dt * dt),
            ],
            crouch: now.crouch,
            facing: now.facing,
            support: None,
        };
        self.lower.step(p, &cmd, t + dt, dt);
        let offset = self.lower.waist_offset() + DVec3::Y * lunge.y + carried;
        let rotation = self.lower.trunk_rotation();
        self.world
            .set_root_pose(offset.as_vec3(), rotation.as_quat());
        self.behaviour.set_trunk(offset, rotation);
        (offset, rotation)
    }

    /// Your avatar's body: its legs step and its waist bends under its
    /// head, wherever the input or the script puts the head.
    pub(super) fn carry_avatar(&mut self, t: f64) {
        let to_local = self.avatar_frame().inverse();
        let w = &self.world;
        let head = w.position(w.part(OpponentPart::Head)).as_dvec3();
        let vh = w.position(Seg::Head).as_dvec3();
        let (head, vh) = (
            to_local.transform_point3(head),
            to_local.transform_point3(vh),
        );
        let p = self.model.params.body.standing();
        self.avatar
            .step(&p, head, vh, t + self.model.dt, self.model.dt);
    }

    /// The body stage with a free pelvis (B1-B5): measure the balance,
    /// advance its states, re-plan the posture from where the body is (to
    /// the capture point when it must step), and actuate the legs and the
    /// waist toward it. Returns the trunk's offset and rotation, as the
    /// body carries them.
    fn balance_body(&mut self, t: f64, lunge: DVec3) -> (DVec3, DQuat) {
        let dt = self.model.dt;
        let p = self.model.params.body.clone();
        let legs = self.world.legs.clone().expect("a balanced body has legs");
        let state = Balance::measure(&self.world, &legs);
        let phys = &self.world.phys;
        let waist = legs.pivot(phys, Joint::Waist).as_dvec3();
        let pelvis_rot = *legs.rb(phys, Part::Pelvis).rotation();
        let ahead = pelvis_rot * glam::Vec3::Z;
        let facing = f64::from(ahead.x.atan2(ahead.z));
        let down_before = self.balance.knockdowns;
        if self
            .balance
            .update(&p.balance, &state, self.effort.damage, t)
        {
            // Up again: the stance is planned anew where the body stands.
            self.lower = LowerBody::standing_at(&p, waist, facing);
        }
        if self.balance.knockdowns > down_before {
            // Down: the referee counts, and the VH neither attacks nor
            // defends before the count of eight.
            let round = self.round(t);
            self.stats.knocked_down(round);
            self.crowd.knockdown();
            self.knocked_at = Some(t);
            let b = self
                .effort
                .behaviour(&self.model.params.effort, &self.model.params.behaviour);
            self.behaviour.stagger(&b, None, t, t + EIGHT_COUNT);
        }
        // The feet on the canvas (ground points), and each one's share of
        // the weight now, by where the centre of mass lies between them.
        let feet = [0, 1].map(|k| {
            legs.on_canvas(phys, Part::Foot(k))
                .then(|| legs.foot_ground(phys, k).0)
        });
        let load = shares(feet.map(|f| f.map(DVec3::as_vec3)), state.com.as_vec3());
        let mut twisted = [false; 2];
        for (k, twist) in twisted.iter_mut().enumerate() {
            if let Some(at) = feet[k] {
                let heading = legs.foot_ground(phys, k).1;
                self.lower.touch_down(&p, k, at, TOUCH_DOWN, t);
                // A swinging foot the weight still holds down after
                // `LIFT_WAIT` has not stepped: it stands where it is, and
                // the balance may step with the other (B4).
                if self.balance.stance == Stance::Standing && f64::from(load[k]) > STUCK_LOAD {
                    self.lower.call_off(k, at, t - LIFT_WAIT);
                }
                self.lower.replant(k, at);
                let off = (heading - self.lower.foot_heading(&p, k) + PI).rem_euclid(TAU) - PI;
                *twist = off.abs() > FOOT_TWIST.to_radians();
            }
        }
        let at = |k: f64| self.behaviour.posture(t + dt + k * dt);
        let (before, now, after) = (at(-1.0), at(0.0), at(1.0));
        // B4: a recovery step when the capture point has left the feet.
        let across = DVec3::new(ahead.z as f64, 0.0, -ahead.x as f64).normalize_or_zero();
        let side = [0, 1].map(|k| {
            let off = self.lower.foot(k) - self.lower.pelvis();
            across * (0.5 * off.dot(across))
        });
        let planted = (0..2).all(|k| self.lower.planted(k));
        if let Some((k, to)) = planted
            .then(|| {
                self.balance
                    .recovery(&p.balance, feet, side, p.step_time, t)
            })
            .flatten()
        {
            self.lower.recovery_step(k, to, t + dt);
        }
        // A foot twisted far from its heading is re-placed, unless a
        // recovery step is due or under way, or the body is settling (it
        // would stand in the way of both, B4, B5).
        if let Some(k) = (0..2).find(|&k| twisted[k])
            && self.balance.stance == Stance::Standing
            && !self.balance.settling(t)
            && !self.balance.recovering(t)
        {
            self.lower.replace_foot(&p, k, t + dt);
        }
        // The plan follows the body: re-planned from where it stands when
        // it is down, or when a blow or a step has taken it off the plan
        // by more than the leash.
        if !self.balance.stance.up() || (now.pelvis - waist).with_y(0.0).length() > p.balance.leash
        {
            self.behaviour.place(waist.with_y(0.0), t + dt);
        }
        let planned = now.pelvis + DVec3::new(lunge.x, 0.0, lunge.z);
        let pelvis = self.balance.steer(&p.balance, planned, waist, t);
        let mut cmd = BodyCommand {
            pelvis,
            pelvis_velocity: (after.pelvis - before.pelvis) / (2.0 * dt),
            waist: [
                now.waist,
                (after.waist - before.waist) / (2.0 * dt),
                (after.waist - 2.0 * now.waist + before.waist) / (dt * dt),
            ],
            crouch: (now.crouch - lunge.y).max(0.0),
            facing: now.facing,
            support: Some(state.capture),
        };
        let mid = match feet {
            [Some(a), Some(b)] => Some((0.5 * (a + b)).with_y(0.0)),
            _ => None,
        };
        let settling = self.balance.settling(t);
        match self.balance.stance {
            // Just up: the weight held over the feet where they are.
            Stance::Standing if settling => cmd.pelvis = mid.unwrap_or(cmd.pelvis),
            Stance::Standing => {}
            // Getting up: no footwork, no punches' bend; up to standing
            // height where the body's weight was when the rise began, the
            // feet gathered under it, facing as the body is.
            Stance::Rising => {
                cmd = BodyCommand {
                    pelvis: mid.unwrap_or(self.balance.rise_at()),
                    facing,
                    ..BodyCommand::default()
                };
            }
            // Down: a crouch under the hips where they are, facing as the
            // body lies.
            Stance::Falling | Stance::Down => {
                cmd = BodyCommand {
                    pelvis: waist.with_y(0.0),
                    crouch: 0.2,
                    facing,
                    ..BodyCommand::default()
                };
            }
        }
        if self.balance.stance.up() {
            let planted_before = [0, 1].map(|k| self.lower.planted(k));
            self.lower.step(&p, &cmd, t + dt, dt);
            if settling && !self.balance.recovering(t) {
                self.lower.hold_feet(t + dt);
            }
            // A footwork step lifts a foot only once the weight is off it
            // (B4): until then the step waits and the weight is shifted
            // over the other foot.
            if let (Some(k), [Some(a), Some(b)]) = (
                (0..2).find(|&k| planted_before[k] && !self.lower.planted(k)),
                feet,
            ) && !self.balance.recovering(t)
            {
                let load = share_between(a.as_vec3(), b.as_vec3(), state.capture.as_vec3())[k];
                if f64::from(load) > LIFT_LOAD {
                    self.lower.hold_feet(t + dt);
                    let (lift, stance) = if k == 0 { (a, b) } else { (b, a) };
                    self.lower.shift_weight(lift + (stance - lift) * SHIFT_TO);
                }
            }
        } else {
            // Down or rising: the legs posed over the feet where they are
            // (a stance planned around the hips would pull them, and the
            // body with them, toward feet it does not stand on).
            self.lower = LowerBody::standing_at(&p, cmd.pelvis, facing);
            for (k, f) in feet.iter().enumerate() {
                if let Some(f) = f {
                    self.lower.replant(k, *f);
                }
            }
            self.lower.step(&p, &cmd, t + dt, dt);
            self.lower.hold_feet(t + dt);
        }
        self.balance
            .actuate(&mut self.world, &self.lower, &p, t + dt, &mut self.rng.body);
        let trunk = self.world.rb(Seg::Torso);
        let rotation = trunk.rotation().as_dquat();
        let offset = waist - WAIST_REST;
        self.behaviour.set_trunk(offset, rotation);
        (offset, rotation)
    }

    /// The referee's count after a knockdown (1, 2, ... one a second, at
    /// most 10), while the VH is down or the mandatory eight-count runs;
    /// `None` otherwise.
    pub fn count(&self) -> Option<u32> {
        let at = self.knocked_at?;
        let n = ((self.time() - at).max(0.0) as u32 + 1).min(10);
        (!self.balance.stance.up() || f64::from(n) <= EIGHT_COUNT).then_some(n)
    }

    /// Your avatar's frame: its own frame (facing +Z, as the VH's) turned
    /// to face the VH and put on the ground under its rest head.
    pub fn avatar_frame(&self) -> glam::DAffine3 {
        let h = self.world.plan.opponent_head.as_dvec3();
        glam::DAffine3::from_translation(DVec3::new(h.x, 0.0, h.z))
            * glam::DAffine3::from_rotation_y(std::f64::consts::PI)
    }

    /// The distance between the fighters: horizontally from the VH's
    /// pelvis to your head, m (trace column `range`).
    pub fn distance(&self) -> f64 {
        let w = &self.world;
        let d = w.position(w.part(OpponentPart::Head)).as_dvec3() - self.pelvis();
        d.x.hypot(d.z)
    }

    /// The range the fighters are at (behaviour/range.rs).
    pub fn zone(&self) -> Zone {
        Ranges::HUMAN.zone(self.distance())
    }

    /// The ground point under the waist joint, world: the physical
    /// pelvis's where it is physical, the plan's where it is driven.
    pub fn pelvis(&self) -> DVec3 {
        match &self.world.legs {
            Some(legs) => legs
                .pivot(&self.world.phys, Joint::Waist)
                .as_dvec3()
                .with_y(0.0),
            None => self.lower.pelvis(),
        }
    }

    /// The legs' joint centres, left then right: the physical legs' where
    /// they are physical, the plan's where the pelvis is driven.
    pub fn legs(&self) -> [crate::physics::lower::Leg; 2] {
        match &self.world.legs {
            Some(legs) => legs.posed(&self.world.phys),
            None => self.lower.legs(&self.model.params.body),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::DVec3;
    use shisen_face::Face;
    use shisen_face::mesh::MeshParams;
    use shisen_face::params::FaceParams;

    use crate::physics::balance::Stance;
    use crate::physics::lower::Pelvis;
    use crate::physics::world::PushPart;
    use crate::sim::timeline::{Action, Event};
    use crate::sim::{Model, Params, Sim};

    /// A VH that neither attacks nor evades, its pelvis as given, pushed
    /// on the trunk at 1 s with `impulse` (N s).
    fn pushed(pelvis: Pelvis, impulse: DVec3) -> Sim {
        let face = Arc::new(Face::new(
            MeshParams { rows: 16 },
            FaceParams::default_params(),
        ));
        let mut params = Params::default();
        params.body.pelvis = pelvis;
        params.behaviour.attacks = false;
        params.personality.evade = 0.0;
        let push = Event {
            at: 1.0,
            action: Action::Push {
                part: PushPart::Trunk,
                impulse,
            },
        };
        Sim::new(Model::new(face, params, 3), &[push])
    }

    fn run(sim: &mut Sim, secs: f64) {
        for _ in 0..(secs / sim.model().dt).round() as usize {
            sim.step();
        }
    }

    /// How far the physical legs' joints (hips, knees, ankles) are from
    /// their rest places, at most, m.
    fn legs_off_rest(sim: &Sim) -> f64 {
        let legs = sim.world.legs.as_ref().expect("a physical body");
        let posed = legs.posed(&sim.world.phys);
        (0..2)
            .flat_map(|k| {
                let (p, r) = (&posed[k], &legs.rest[k]);
                [p.hip - r.hip, p.knee - r.knee, p.ankle - r.ankle]
            })
            .map(|d| d.length())
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_reset_puts_the_physical_body_back_at_rest() {
        // Shoved hard at 1 s: by 2 s it has stepped or fallen off its place.
        let mut sim = pushed(Pelvis::Balanced, DVec3::X * 75.0);
        run(&mut sim, 2.0);
        assert!(legs_off_rest(&sim) > 0.1, "the shove did not move it");
        // A reset sets the articulation's joints, not only its bodies (set
        // alone, rapier posed them back where they were on the next step).
        sim.reset_vh("test");
        run(&mut sim, 0.01);
        let off = legs_off_rest(&sim);
        assert!(
            off < 0.03,
            "10 ms after a reset a leg joint is {off} m from rest"
        );
        run(&mut sim, 1.0);
        assert_eq!(sim.resets, 1, "the reset blew up again");
    }

    /// The physical body holds together: its pelvis is in the world, its
    /// feet start on the canvas, nothing blows up, and a push on the trunk
    /// moves the whole body (a driven pelvis does not move at all).
    #[test]
    fn a_push_moves_the_physical_body_and_not_the_driven_one() {
        let back = DVec3::new(0.0, 0.0, -30.0);
        let mut driven = pushed(Pelvis::Driven, back);
        let mut free = pushed(Pelvis::Balanced, back);
        assert!(driven.world.legs.is_none() && free.world.legs.is_some());
        run(&mut driven, 1.0);
        run(&mut free, 0.3);
        let legs = free.world.legs.clone().unwrap();
        for k in 0..2 {
            assert!(
                legs.on_canvas(&free.world.phys, crate::physics::legs::Part::Foot(k)),
                "foot {k} on the canvas"
            );
        }
        run(&mut free, 0.7);
        let (d0, f0) = (driven.pelvis(), free.pelvis());
        run(&mut driven, 0.3);
        run(&mut free, 0.3);
        let (d1, f1) = (driven.pelvis(), free.pelvis());
        assert!((d1 - d0).length() < 1e-9, "driven: {d0} -> {d1}");
        // 30 N s is 0.4 m/s on the whole body: held by the ankles and hips
        // within a few centimetres, as a person's (Pai & Patton 1997).
        let back = f0.z - f1.z;
        assert!(
            (0.01..0.15).contains(&back),
            "the push moved the body back: {f0} -> {f1}"
        );
        assert_eq!(free.resets, 0);
        assert!(free.world.is_finite());
    }

    /// Left alone, a physical VH stands: 30 s without a fall or a reset,
    /// its pelvis within a few centimetres of where it started.
    #[test]
    fn a_physical_vh_left_alone_stands() {
        let mut sim = pushed(Pelvis::Balanced, DVec3::ZERO);
        for _ in 0..30_000 {
            sim.step();
            assert_eq!(sim.balance.stance, Stance::Standing, "at {}", sim.time());
        }
        assert_eq!(sim.resets, 0);
        let at = sim.pelvis();
        assert!(at.length() < 0.1, "stood where it was: {at}");
    }

    /// Shoves on the trunk (B4): the boxer's long stance holds 45 N s
    /// from the front with its feet in place (the capture point stays
    /// over the rear foot); its narrow side holds 15 N s in place and
    /// steps to catch 30 N s. None puts it down (`shisen pushes` tables
    /// every side over three seeds).
    /// People step from about 0.4-0.5 m/s of the centre of mass (Pai &
    /// Patton 1997, J. Biomech. 30:347; 30 N s on 75 kg is 0.4 m/s), less
    /// across a narrow stance.
    #[test]
    fn a_harder_shove_is_caught_with_a_step() {
        let front = DVec3::NEG_Z;
        let side = DVec3::X;
        for (dir, impulse, stepped) in [
            (front, 45.0, false),
            (side, 15.0, false),
            (side, 30.0, true),
        ] {
            let mut sim = pushed(Pelvis::Balanced, dir * impulse);
            run(&mut sim, 5.0);
            let what = format!("{impulse} N s along {dir}");
            assert_eq!(sim.balance.knockdowns, 0, "{what} put it down");
            let steps = sim.balance.recovery_steps + sim.lower.steps;
            assert_eq!(steps > 0, stepped, "{what}: {steps} steps");
        }
    }

    /// A shove no one could stand against puts it down; it lies for a
    /// while, then gets up by itself.
    #[test]
    fn a_knockdown_and_a_get_up() {
        let mut sim = pushed(Pelvis::Balanced, DVec3::new(0.0, 0.0, -150.0));
        run(&mut sim, 3.0);
        assert_eq!(sim.balance.knockdowns, 1, "{:?}", sim.balance.stance);
        let mut up_at = None;
        for _ in 0..10_000 {
            sim.step();
            if sim.balance.get_ups > 0 {
                up_at = Some(sim.time());
                break;
            }
        }
        let up_at = up_at.expect("up within 10 s");
        assert!(up_at > 3.5, "it stayed down a while: up at {up_at}");
        assert!(sim.world.is_finite());
    }

    /// Issue 44's first must-show: left alone for ten minutes, the VH
    /// stands.
    #[test]
    fn a_physical_vh_left_alone_stands_for_ten_minutes() {
        let mut sim = pushed(Pelvis::Balanced, DVec3::ZERO);
        for _ in 0..600_000 {
            sim.step();
            assert_eq!(sim.balance.stance, Stance::Standing, "at {}", sim.time());
        }
    }
}
