//! The lower body and the waist: how the VH stands, steps and bends
//! (docs/model/body.md, W1-W3).
//!
//! **How the pelvis is carried: driven, not balanced.** The hips are
//! moved kinematically along the footwork's minimum-jerk paths (the
//! behaviour's range keeping, a punch's weight shift, a duck's knee bend);
//! the legs are placed under them by inverse kinematics with feet that stay
//! planted until they step (W2); from the hips up the body is physical: the
//! trunk turns and bends at the waist under a PD law acting on the upper
//! body's inertia with bounded torque (W1), and carries the physical head
//! and arms. A fully balanced biped would add ten contact-driven joints and
//! a balance controller to a model whose subject is gaze, for motion a
//! boxer's feet mostly keep out of sight; the driven pelvis keeps the
//! physics step near MuJoCo's cost and the 10-hour soak free of falls. What
//! it gives up: a blow cannot knock the VH off its feet, and the arms'
//! reaction torques do not turn the trunk.
//!
//! ```text
//! I q'' = clamp(I q''* + Kp (q* - q) + Kd (q'* - q'), +-tau_max)     (W1)
//!   Kp = I (2 pi f)^2,  Kd = 2 zeta I (2 pi f)   per axis (yaw, pitch, roll)
//! foot k steps when |place_k(pelvis) - foot_k| > trigger or its heel
//!   lifts > 8 cm, the other foot planted; it lands at place_k(pelvis at
//!   the step's end)                                                      (W2)
//! leg: two links hip-knee-ankle, knee in the foot's plane; an ankle out
//!   of reach lifts the heel about the toes (as a rear heel in a jab)    (W3)
//! ```

use crate::physics::balance::params::BalanceParams;
use glam::{DQuat, DVec3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use shisen_gaze::util::math::{JointAngles, min_jerk};

/// Lower-body anthropometry: Winter (2009, "Biomechanics and Motor
/// Control of Human Movement", 4th ed., fig. 4.1) segment lengths as
/// fractions of stature, for a 1.85 m man (the VH's head top is at 1.80 m
/// in a boxer's slight crouch), and de Leva (1996, J. Biomech.
/// 29:1223) male segment masses as fractions of a 75 kg body.
pub mod anthro {
    /// Stature, m.
    pub const STATURE: f64 = 1.85;
    /// Hip joint centre to knee, m (0.245 H).
    pub const THIGH: f64 = 0.245 * STATURE;
    /// Knee to ankle, m (0.246 H).
    pub const SHANK: f64 = 0.246 * STATURE;
    /// Ankle above the sole, m (0.039 H).
    pub const ANKLE_HEIGHT: f64 = 0.039 * STATURE;
    /// Foot length, m (0.152 H).
    pub const FOOT_LENGTH: f64 = 0.152 * STATURE;
    /// Ankle ahead of the heel, as a share of the foot's length.
    pub const ANKLE_FROM_HEEL: f64 = 0.25;
    /// Half the distance between the hip joint centres, m (0.191 H hip
    /// width, joint centres about half of it apart).
    pub const HIP_HALF: f64 = 0.0875;
    /// Hip joint centres below the waist joint (the trunk's pivot), m.
    pub const HIP_BELOW_WAIST: f64 = 0.09;
    /// Body mass, kg.
    pub const MASS: f64 = 75.0;
    /// Mass above the waist (head 6.94 %, trunk less pelvis 32.29 %, arms
    /// 2 x 4.94 %; de Leva 1996), kg.
    pub const UPPER_MASS: f64 = (0.0694 + 0.3229 + 2.0 * 0.0494) * MASS;
    /// Its centre of mass above the waist joint, m (de Leva's trunk
    /// centres, with the head and arms).
    pub const UPPER_COM: f64 = 0.30;
    /// Moments of inertia of the upper body about the waist joint, kg m^2:
    /// yaw (the trunk's axial radius of gyration, 0.16 m, and the arms at
    /// the shoulders), pitch and roll (parallel axes to the centre of mass
    /// plus the segments' own, radius of gyration about 0.13 m).
    pub const WAIST_INERTIA: [f64; 3] = [
        UPPER_MASS * 0.16 * 0.16,
        UPPER_MASS * (UPPER_COM * UPPER_COM + 0.13 * 0.13),
        UPPER_MASS * (UPPER_COM * UPPER_COM + 0.12 * 0.12),
    ];
}

/// The lower body's parameters (scene `vh.body`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct BodyParams {
    /// Whether the VH stands and steps (legs, footwork, the waist): the
    /// default. `false` is the seed's VH, a trunk on a stand that neither
    /// bends nor steps (`profile: Seed`).
    pub human: bool,
    /// Natural frequency of the waist's PD law (W1), Hz. Default 2.5: a
    /// boxer's slip or duck takes the head 10-20 cm in about 0.2 s.
    /// 0.2-20 Hz (a trunk that barely follows to one eight times as
    /// quick as the default).
    #[schemars(range(min = 0.2, max = 20.0))]
    pub waist_frequency: f64,
    /// Damping ratio of the waist's law, dimensionless. Default 1 (no
    /// overshoot). 0.1-5 (a trunk that rings to one that creeps).
    #[schemars(range(min = 0.1, max = 5.0))]
    pub waist_damping: f64,
    /// Strongest torque the trunk's muscles give about yaw, pitch and
    /// roll, N m. Default 90, 220, 150: maximal isometric trunk moments of
    /// healthy men (axial rotation about 60-110 N m, extension 200-300,
    /// lateral bend 120-180; e.g. Kumar, Dufresne & Garand 1991,
    /// Ergonomics 34:1063; McGill 1992, J. Biomech. 25:395). Each 1-2000
    /// N m (several times the strongest man's, for a trunk that must not
    /// be limited).
    #[schemars(inner(range(min = 1.0, max = 2000.0)))]
    pub waist_max_torque: [f64; 3],
    /// The hips' turn in the stance, deg (negative: the left hip, the lead
    /// side of an orthodox boxer, forward). The waist turns the trunk back
    /// square to the opponent. Default -15. -60 to 60 deg (a square stance
    /// to one side-on past any boxer's).
    #[schemars(range(min = -60.0, max = 60.0))]
    pub hip_turn_deg: f64,
    /// Lead (left) foot's place relative to the pelvis at rest, `[x, z]`,
    /// m; the rear foot's mirrors it. Default `[0.13, 0.22]`: feet about
    /// shoulder width apart and a foot's length and a half between heels
    /// front to back, a boxer's stance. `x` 0.05-0.4 m (feet together
    /// to a wide straddle), `z` 0-0.5 m (side by side to a long stance).
    #[schemars(schema_with = "lead_foot_schema")]
    pub lead_foot: [f64; 2],
    /// A planted foot steps when it is this far from its place under the
    /// moving pelvis (W2), m. Default 0.08. 0.01-0.5 m (a foot that
    /// shuffles at every sway to one that lets the legs straddle).
    #[schemars(range(min = 0.01, max = 0.5))]
    pub step_trigger: f64,
    /// One foot's swing, s. Default 0.25 (see `docs/model/body.md`).
    /// 0.05-2 s (a flick to a slow, deliberate step).
    #[schemars(range(min = 0.05, max = 2.0))]
    pub step_time: f64,
    /// The swinging foot's highest lift, m. Default 0.04: boxers glide,
    /// their feet barely leave the canvas. 0-0.3 m (a slide to a high
    /// march step).
    #[schemars(range(min = 0.0, max = 0.3))]
    pub step_lift: f64,
    /// How the pelvis is carried: `Driven` (moved along the planned
    /// paths, the legs placed under it; the default) or `Balanced`
    /// (experimental: pelvis and legs physical, the root free, kept up by
    /// the balance controller; docs/model/balance.md).
    pub pelvis: Pelvis,
    /// The balance controller's parameters (used when `pelvis` is
    /// `Balanced`).
    pub balance: BalanceParams,
}

/// How the VH's pelvis is carried.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum Pelvis {
    /// Moved kinematically along the footwork's planned paths; blows move
    /// the trunk's joints but not the body (W1-W3).
    #[default]
    Driven,
    /// A free, physical root: pelvis, thighs, shanks and feet are rigid
    /// bodies on the canvas, kept up by their own control (B1-B5); blows
    /// push the body. Experimental: the balance does not yet keep it up
    /// (docs/model/balance.md).
    Balanced,
}

/// The schema of [`BodyParams::lead_foot`]: `[x, z]`, each with its own
/// range.
fn lead_foot_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    schemars::json_schema!({
        "type": "array",
        "prefixItems": [
            {"type": "number", "minimum": 0.05, "maximum": 0.4},
            {"type": "number", "minimum": 0.0, "maximum": 0.5},
        ],
        "minItems": 2,
        "maxItems": 2,
    })
}

impl Default for BodyParams {
    fn default() -> Self {
        BodyParams {
            human: true,
            waist_frequency: 2.5,
            waist_damping: 1.0,
            waist_max_torque: [90.0, 220.0, 150.0],
            hip_turn_deg: -15.0,
            lead_foot: [0.13, 0.22],
            step_trigger: 0.08,
            step_time: 0.25,
            step_lift: 0.04,
            pelvis: Pelvis::Driven,
            balance: BalanceParams::default(),
        }
    }
}

impl BodyParams {
    /// The same body standing and stepping (your avatar's, whatever the
    /// VH's profile: the seed's VH sits on a stand, you do not).
    pub fn standing(&self) -> Self {
        BodyParams {
            human: true,
            ..self.clone()
        }
    }

    /// The seed's VH: a trunk on a stand.
    pub fn seed() -> Self {
        BodyParams {
            human: false,
            ..BodyParams::default()
        }
    }
}

/// What the behaviour asks of the lower body this tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BodyCommand {
    /// Where the pelvis goes (ground point under the waist joint, world).
    pub pelvis: DVec3,
    /// Its velocity along the planned path, m/s (for the feet's landing).
    pub pelvis_velocity: DVec3,
    /// The waist's commanded turn and bend from neutral (yaw, pitch,
    /// roll), rad, and their rates and accelerations.
    pub waist: [DVec3; 3],
    /// How far the knees lower the hips, m.
    pub crouch: f64,
    /// The body's heading: its turn about +Y from facing +Z, rad (the
    /// pelvis, the stance and the trunk turn with it; the feet step round).
    pub facing: f64,
    /// Where the feet step to stay under, if not the pelvis: a physical
    /// body's capture point (B4), so its feet go where its weight is
    /// going, not where the plan wished it were.
    pub support: Option<DVec3>,
}

/// One foot: planted where it is, or swinging.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Foot {
    /// Heel-to-toe midpoint on the ground, world.
    at: DVec3,
    swing: Option<Swing>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Swing {
    from: DVec3,
    to: DVec3,
    t0: f64,
}

/// A leg's joint centres, world, for drawing and traces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Leg {
    /// Hip joint centre.
    pub hip: DVec3,
    /// Knee.
    pub knee: DVec3,
    /// Ankle.
    pub ankle: DVec3,
    /// Ball of the foot (the toes' base).
    pub toe: DVec3,
    /// Heel, on the sole.
    pub heel: DVec3,
}

/// The lower body's evolving state.
#[derive(Clone, Debug, PartialEq)]
pub struct LowerBody {
    /// Ground point under the waist joint, world.
    pelvis: DVec3,
    crouch: f64,
    facing: f64,
    feet: [Foot; 2],
    /// Waist angles from neutral (yaw, pitch, roll), rad, and rates.
    q: DVec3,
    qd: DVec3,
    /// Feet that started a step, counted.
    pub steps: u32,
}

/// A planted foot whose heel the leg lifts higher than this steps, m
/// (about 25 deg of lift: a rear heel in a cross).
const HEEL_STEP: f64 = 0.08;

/// A swinging foot this near its target that meets the canvas has landed,
/// m (our choice: a sole's half width; farther off it is scuffing the
/// canvas on its way).
const LANDED: f64 = 0.05;

/// The waist joint at rest, world (the trunk's pivot).
pub const WAIST_REST: DVec3 = DVec3::new(0.0, 1.0, 0.0);

impl LowerBody {
    /// Standing at rest in the stance, the pelvis under the waist's rest
    /// position.
    pub fn new(p: &BodyParams) -> Self {
        let pelvis = DVec3::new(WAIST_REST.x, 0.0, WAIST_REST.z);
        LowerBody {
            pelvis,
            crouch: 0.0,
            facing: 0.0,
            feet: [0, 1].map(|k| Foot {
                at: pelvis + place(p, k, 0.0),
                swing: None,
            }),
            q: DVec3::ZERO,
            qd: DVec3::ZERO,
            steps: 0,
        }
    }

    /// Standing at rest in the stance again (a physics reset), the count of
    /// steps running on.
    pub fn restarted(&self, p: &BodyParams) -> Self {
        LowerBody {
            steps: self.steps,
            ..LowerBody::new(p)
        }
    }

    /// Advance one tick toward `cmd`: the pelvis goes where it is sent,
    /// the waist follows its law (W1), the feet step to stay under the
    /// pelvis (W2).
    pub fn step(&mut self, p: &BodyParams, cmd: &BodyCommand, t: f64, dt: f64) {
        if !p.human {
            return;
        }
        self.pelvis = DVec3::new(cmd.pelvis.x, 0.0, cmd.pelvis.z);
        self.crouch = cmd.crouch;
        self.facing = cmd.facing;
        let w = std::f64::consts::TAU * p.waist_frequency;
        for i in 0..3 {
            let inertia = anthro::WAIST_INERTIA[i];
            let (kp, kd) = (inertia * w * w, 2.0 * p.waist_damping * inertia * w);
            let [q, qd, qdd] = cmd.waist.map(|v| v[i]);
            let tau = inertia * qdd + kp * (q - self.q[i]) + kd * (qd - self.qd[i]);
            let tau = tau.clamp(-p.waist_max_torque[i], p.waist_max_torque[i]);
            self.qd[i] += tau / inertia * dt;
            self.q[i] += self.qd[i] * dt;
        }
        // W2: a swing ends; a planted foot far from its place steps, one
        // foot at a time, landing where its place will be.
        for f in &mut self.feet {
            if f.swing.is_some_and(|s| t - s.t0 >= p.step_time) {
                f.at = f.swing.take().map_or(f.at, |s| s.to);
            }
        }
        let base = cmd.support.map_or(self.pelvis, |s| s.with_y(0.0));
        if self.feet.iter().all(|f| f.swing.is_none()) {
            let ahead = match cmd.support {
                Some(_) => base,
                None => self.pelvis + cmd.pelvis_velocity * p.step_time,
            };
            // A leg stretched so far that its heel lifts more than a rear
            // heel does in a punch steps too.
            let legs = self.legs(p);
            let far = [0, 1]
                .map(|k| {
                    let at = base + place(p, k, self.facing);
                    let off = (at - self.feet[k].at).length();
                    let stretched = legs[k].heel.y > HEEL_STEP;
                    // Of two feet as far off, the one on the side the body
                    // travels to steps first (the lead foot going in, the
                    // rear foot going back), as boxers are taught.
                    let lead = 0.01 * place(p, k, self.facing).dot(at - self.feet[k].at);
                    (k, if stretched { f64::MAX } else { off + lead })
                })
                .into_iter()
                .filter(|&(_, d)| d > p.step_trigger)
                .max_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((k, _)) = far {
                let to = ahead + place(p, k, self.facing);
                self.feet[k].swing = Some(Swing {
                    from: self.feet[k].at,
                    to,
                    t0: t,
                });
                self.steps += 1;
            }
        }
        for f in &mut self.feet {
            if let Some(s) = f.swing {
                let u = ((t - s.t0) / p.step_time).clamp(0.0, 1.0);
                f.at = s.from + (s.to - s.from) * min_jerk(u);
                f.at.y = p.step_lift * (std::f64::consts::PI * u).sin();
            }
        }
    }

    /// The waist's angles relative to the pelvis (yaw, pitch, roll), rad:
    /// the trace's `waist_*` columns.
    pub fn waist(&self, p: &BodyParams) -> JointAngles {
        if !p.human {
            return JointAngles::default();
        }
        JointAngles {
            yaw: self.q.x - p.hip_turn_deg.to_radians(),
            pitch: self.q.y,
            roll: self.q.z,
        }
    }

    /// The waist joint's offset from its rest position, world, m.
    pub fn waist_offset(&self) -> DVec3 {
        DVec3::new(self.pelvis.x, -self.crouch, self.pelvis.z)
            - DVec3::new(WAIST_REST.x, 0.0, WAIST_REST.z)
    }

    /// The trunk's rotation in the world (the body's heading, and the
    /// waist's turn and bend; square to +Z at rest).
    pub fn trunk_rotation(&self) -> DQuat {
        let waist = JointAngles {
            yaw: self.q.x,
            pitch: self.q.y,
            roll: self.q.z,
        };
        DQuat::from_rotation_y(self.facing) * waist.to_quat().as_dquat()
    }

    /// The body's heading (turn about +Y from facing +Z), rad.
    pub fn facing(&self) -> f64 {
        self.facing
    }

    /// The ground point under the waist joint, world.
    pub fn pelvis(&self) -> DVec3 {
        self.pelvis
    }

    /// Put planted foot `k` where the body's foot is (`at`, on the
    /// canvas): the plan follows a foot that a push slid or a recovery
    /// step placed. A swinging foot is left to its swing.
    pub fn replant(&mut self, k: usize, at: DVec3) {
        if self.feet[k].swing.is_none() {
            self.feet[k].at = at.with_y(0.0);
        }
    }

    /// Foot `k` has met the canvas at `at`: a swing past `after` of its
    /// time ends there (touchdown ends a physical step, as the contact
    /// switch does in SIMBICON: Yin, Loken & van de Panne 2007, ACM TOG
    /// 26:105). Returns whether a swing ended.
    pub fn touch_down(&mut self, p: &BodyParams, k: usize, at: DVec3, after: f64, t: f64) -> bool {
        let f = &mut self.feet[k];
        match f.swing {
            Some(s)
                if (t - s.t0) / p.step_time >= after
                    && (s.to - at).with_y(0.0).length() < LANDED =>
            {
                f.swing = None;
                f.at = at.with_y(0.0);
                true
            }
            _ => false,
        }
    }

    /// Call off foot `k`'s swing if it began before `before`: a foot that
    /// the body's weight still holds on the canvas at `at` is planted there
    /// again.
    pub fn call_off(&mut self, k: usize, at: DVec3, before: f64) {
        let f = &mut self.feet[k];
        if f.swing.is_some_and(|s| s.t0 < before) {
            f.swing = None;
            f.at = at.with_y(0.0);
        }
    }

    /// Put the pelvis's ground point at `to` for this tick: a physical
    /// body shifting its weight onto one foot before it lifts the other.
    pub fn shift_weight(&mut self, to: DVec3) {
        self.pelvis = to.with_y(0.0);
    }

    /// Call off the footwork steps that began at `t`: the feet stay where
    /// they stand (a body settling after it got up, B5).
    pub fn hold_feet(&mut self, t: f64) {
        for f in &mut self.feet {
            if let Some(s) = f.swing.filter(|s| s.t0 >= t) {
                f.at = s.from;
                f.swing = None;
                self.steps -= 1;
            }
        }
    }

    /// Step planted foot `k` back to its place under the pelvis (a foot
    /// the body slid or twisted on the canvas, re-placed as a boxer
    /// resets the stance), if both feet are planted. Returns whether it
    /// steps.
    pub fn replace_foot(&mut self, p: &BodyParams, k: usize, t: f64) -> bool {
        if self.feet.iter().any(|f| f.swing.is_some()) {
            return false;
        }
        self.feet[k].swing = Some(Swing {
            from: self.feet[k].at,
            to: self.pelvis + place(p, k, self.facing),
            t0: t,
        });
        self.steps += 1;
        true
    }

    /// A recovery step (B4): foot `k` swings to `to` on the canvas,
    /// whatever its place, if no foot is swinging. Returns whether it
    /// steps.
    pub fn recovery_step(&mut self, k: usize, to: DVec3, t: f64) -> bool {
        if self.feet.iter().any(|f| f.swing.is_some()) {
            return false;
        }
        self.feet[k].swing = Some(Swing {
            from: self.feet[k].at,
            to: to.with_y(0.0),
            t0: t,
        });
        self.steps += 1;
        true
    }

    /// Foot `k`'s planned heading (yaw about +Y, 0 along +Z).
    pub fn foot_heading(&self, p: &BodyParams, k: usize) -> f64 {
        foot_yaw(p, k) + self.facing
    }

    /// Standing at rest in the stance with the pelvis's ground point at
    /// `pelvis`, turned to `facing` (a body that got up where it fell).
    pub fn standing_at(p: &BodyParams, pelvis: DVec3, facing: f64) -> Self {
        let pelvis = pelvis.with_y(0.0);
        LowerBody {
            pelvis,
            facing,
            feet: [0, 1].map(|k| Foot {
                at: pelvis + place(p, k, facing),
                swing: None,
            }),
            ..LowerBody::new(p)
        }
    }

    /// Whether foot `k` (0 lead/left) is planted.
    pub fn planted(&self, k: usize) -> bool {
        self.feet[k].swing.is_none()
    }

    /// Foot `k`'s heel-to-toe midpoint, world.
    pub fn foot(&self, k: usize) -> DVec3 {
        self.feet[k].at
    }

    /// The legs' joint centres (W3), left then right.
    pub fn legs(&self, p: &BodyParams) -> [Leg; 2] {
        let turn = DQuat::from_rotation_y(p.hip_turn_deg.to_radians() + self.facing);
        let waist = WAIST_REST + self.waist_offset();
        [0, 1].map(|k| {
            let sx = if k == 0 { 1.0 } else { -1.0 };
            let hip =
                waist + turn * DVec3::new(sx * anthro::HIP_HALF, -anthro::HIP_BELOW_WAIST, 0.0);
            leg_ik(hip, self.feet[k].at, foot_yaw(p, k) + self.facing, sx)
        })
    }
}

/// A lower body carried under a head that is moved directly (your avatar,
/// whose head and gloves the input or the script drive): the pelvis
/// follows the head's ground point with a step's lag, the knees keep the
/// waist a trunk's length below the head, and the waist turns the trunk so
/// it meets the head; the feet step as the VH's do (W2). Works in the body's own
/// frame (facing +Z, the waist joint's rest at [`WAIST_REST`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Carried {
    /// The lower body.
    pub lower: LowerBody,
    pelvis: DVec3,
}

/// The head's centre above the waist joint at rest, m.
const HEAD_ABOVE_WAIST: f64 = 0.685;

impl Carried {
    /// Standing at rest.
    pub fn new(p: &BodyParams) -> Self {
        let lower = LowerBody::new(p);
        Carried {
            pelvis: lower.pelvis,
            lower,
        }
    }

    /// Advance one tick with the head's centre at `head`, the body turned
    /// to face `toward` (both in its own frame).
    pub fn step(&mut self, p: &BodyParams, head: DVec3, toward: DVec3, t: f64, dt: f64) {
        let ground = DVec3::new(head.x, 0.0, head.z);
        // The pelvis follows over about a step's time.
        let k = (dt / 0.3).min(1.0);
        let v = (ground - self.pelvis) / 0.3;
        self.pelvis += (ground - self.pelvis) * k;
        // The knees put the waist joint a trunk's length from the head.
        let lean = (head - self.pelvis).with_y(0.0).length().min(0.6);
        let waist_y = head.y - (HEAD_ABOVE_WAIST.powi(2) - lean * lean).sqrt();
        let cmd = BodyCommand {
            pelvis: self.pelvis,
            pelvis_velocity: v,
            waist: [DVec3::ZERO; 3],
            crouch: (WAIST_REST.y - waist_y).clamp(0.0, 0.3),
            facing: (toward.x - self.pelvis.x).atan2(toward.z - self.pelvis.z),
            support: None,
        };
        self.lower.step(p, &cmd, t, dt);
        // The trunk from the waist joint to the head, exactly.
        let waist = WAIST_REST + self.lower.waist_offset();
        let dir = (head - waist).normalize_or(DVec3::Y);
        let q =
            DQuat::from_rotation_arc(DVec3::Y, DQuat::from_rotation_y(-self.lower.facing) * dir);
        let a = JointAngles::from_quat(q.as_quat());
        self.lower.q = DVec3::new(a.yaw, a.pitch, a.roll);
        self.lower.qd = DVec3::ZERO;
    }
}

/// Foot `k`'s place relative to the pelvis (the stance), the body facing
/// `facing`.
fn place(p: &BodyParams, k: usize, facing: f64) -> DVec3 {
    let [x, z] = p.lead_foot;
    let turn = DQuat::from_rotation_y(p.hip_turn_deg.to_radians() + facing);
    let v = if k == 0 {
        DVec3::new(x, 0.0, z)
    } else {
        DVec3::new(-x, 0.0, -z)
    };
    turn * v
}

/// Foot `k`'s heading (yaw about +Y, 0 along +Z): the lead foot points at
/// the opponent, the rear foot turned out 40 deg, as in a boxer's stance.
fn foot_yaw(p: &BodyParams, k: usize) -> f64 {
    let out = if k == 0 { 0.0 } else { -40f64.to_radians() };
    0.5 * p.hip_turn_deg.to_radians() + out
}

/// W3: the leg's joints for a hip and a foot (midpoint on the ground,
/// heading `yaw`); `sx` +1 for the left leg.
pub(crate) fn leg_ik(hip: DVec3, foot: DVec3, yaw: f64, sx: f64) -> Leg {
    use anthro::{ANKLE_FROM_HEEL, ANKLE_HEIGHT, FOOT_LENGTH, SHANK, THIGH};
    let fwd = DVec3::new(yaw.sin(), 0.0, yaw.cos());
    let heel0 = foot - fwd * FOOT_LENGTH / 2.0;
    let toe = heel0 + fwd * FOOT_LENGTH * 0.78;
    let reach = THIGH + SHANK - 1e-3;
    // The ankle, on the planted foot; out of reach, the heel lifts about
    // the toes until it is in reach (at most 40 deg; the foot steps first,
    // W2).
    let ankle_at = |lift: f64| {
        let r = DQuat::from_axis_angle(fwd.cross(DVec3::Y).normalize(), -lift);
        let heel = toe + r * (heel0 - toe);
        let ankle = heel + r * (fwd * FOOT_LENGTH * ANKLE_FROM_HEEL + DVec3::Y * ANKLE_HEIGHT);
        (heel, ankle)
    };
    let mut lift = 0.0;
    let (mut heel, mut ankle) = ankle_at(0.0);
    while (ankle - hip).length() > reach && lift < 40f64.to_radians() {
        lift += 1f64.to_radians();
        (heel, ankle) = ankle_at(lift);
    }
    let d = ankle - hip;
    let r = d.length().min(reach);
    let dir = d.normalize_or(DVec3::NEG_Y);
    // Knee forward (along the foot) and slightly out.
    let hint = (fwd + DVec3::X * sx * 0.15).normalize();
    let side = (hint - dir * hint.dot(dir)).normalize_or(DVec3::Z);
    let cos_a = ((THIGH * THIGH + r * r - SHANK * SHANK) / (2.0 * THIGH * r)).clamp(-1.0, 1.0);
    let a = cos_a.acos();
    let knee = hip + (dir * a.cos() + side * a.sin()) * THIGH;
    Leg {
        hip,
        knee,
        ankle,
        toe,
        heel,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(lb: &mut LowerBody, p: &BodyParams, cmd: impl Fn(f64) -> BodyCommand, secs: f64) {
        let dt = 1e-3;
        for i in 0..(secs / dt) as usize {
            let t = i as f64 * dt;
            lb.step(p, &cmd(t), t, dt);
        }
    }

    /// The stance's two numbers have their own ranges (the schema's
    /// `prefixItems`), and the file refuses what they exclude.
    #[test]
    fn the_stance_is_checked_per_component() {
        use shisen_gaze::util::ron::parse_ron;
        let file = std::path::Path::new("b.ron");
        let p: BodyParams = parse_ron("(lead_foot: (0.3, 0.45))", file).unwrap();
        assert_eq!(p.lead_foot, [0.3, 0.45]);
        for bad in ["(lead_foot: (0.45, 0.3))", "(lead_foot: (0.13, -0.1))"] {
            let e = parse_ron::<BodyParams>(bad, file).unwrap_err().to_string();
            assert!(e.contains("lead_foot"), "{bad}: {e}");
        }
        let e = parse_ron::<BodyParams>("(waist_max_torque: (90, 220, 1e9))", file)
            .unwrap_err()
            .to_string();
        assert!(e.contains("waist_max_torque"), "{e}");
    }

    #[test]
    fn legs_reach_the_ground_at_rest() {
        let p = BodyParams::default();
        let lb = LowerBody::new(&p);
        for leg in lb.legs(&p) {
            assert!((leg.knee - leg.hip).length() - anthro::THIGH < 1e-6);
            assert!(((leg.ankle - leg.knee).length() - anthro::SHANK).abs() < 1e-6);
            assert!(
                (leg.heel.y).abs() < 1e-9,
                "heel on the canvas: {}",
                leg.heel.y
            );
            assert!(leg.knee.y > leg.ankle.y && leg.knee.y < leg.hip.y);
        }
    }

    #[test]
    fn planted_feet_do_not_slide_and_the_body_steps_back() {
        let p = BodyParams::default();
        let mut lb = LowerBody::new(&p);
        let start = [lb.foot(0), lb.foot(1)];
        // The pelvis goes 0.4 m back over 1 s.
        let cmd = |t: f64| BodyCommand {
            pelvis: DVec3::new(0.0, 0.0, -0.4 * min_jerk(t)),
            ..Default::default()
        };
        let dt = 1e-3;
        let (mut last, mut was_planted) = (start, [true; 2]);
        for i in 0..2000 {
            let t = i as f64 * dt;
            lb.step(&p, &cmd(t), t, dt);
            for k in 0..2 {
                // Planted through the whole tick: it did not move.
                if lb.planted(k) && was_planted[k] {
                    assert!(
                        (lb.foot(k) - last[k]).length() < 1e-9,
                        "foot {k} slid at {t}"
                    );
                }
                assert!(lb.foot(k).y >= 0.0, "foot {k} below the canvas at {t}");
                last[k] = lb.foot(k);
                was_planted[k] = lb.planted(k);
            }
        }
        assert!(lb.steps >= 2, "it stepped: {}", lb.steps);
        for (k, s) in start.iter().enumerate() {
            let moved = lb.foot(k) - *s;
            assert!(
                (moved.z + 0.4).abs() < p.step_trigger,
                "foot {k} followed: {moved}"
            );
        }
    }

    #[test]
    fn the_foot_on_the_side_of_travel_steps_first() {
        let p = BodyParams::default();
        for (dz, first) in [(-0.3, 1), (0.3, 0)] {
            let mut lb = LowerBody::new(&p);
            let cmd = |t: f64| BodyCommand {
                pelvis: DVec3::new(0.0, 0.0, dz * min_jerk(t / 0.4)),
                ..Default::default()
            };
            let mut t = 0.0;
            while lb.planted(0) && lb.planted(1) && t < 1.0 {
                lb.step(&p, &cmd(t), t, 1e-3);
                t += 1e-3;
            }
            assert!(
                !lb.planted(first) && lb.planted(1 - first),
                "{dz}: foot {first} first"
            );
        }
    }

    #[test]
    fn the_waist_follows_its_command_within_its_strength() {
        let p = BodyParams::default();
        let mut lb = LowerBody::new(&p);
        let cmd = BodyCommand {
            waist: [DVec3::new(0.0, -0.4, 0.25), DVec3::ZERO, DVec3::ZERO],
            ..Default::default()
        };
        run(&mut lb, &p, |_| cmd, 0.1);
        let early = lb.q;
        run(&mut lb, &p, |_| cmd, 1.5);
        assert!(early.y > -0.3, "a step command takes time: {early}");
        assert!((lb.q - cmd.waist[0]).length() < 0.01, "settled: {}", lb.q);
        let w = lb.waist(&p);
        assert!(
            (w.yaw - 15f64.to_radians()).abs() < 0.01,
            "hips turned under the trunk"
        );
    }
}
