//! The balance controller's parameters (scene `vh.body.balance`), apart
//! from the controller so the body's parameters can embed them.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::physics::control::JointGains;

/// The balance controller's parameters (scene `vh.body.balance`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct BalanceParams {
    /// Ankles' PD gains. Default kp 900 N m/rad, kd 60: about 1.3 times
    /// the body's load stiffness m g h (75 kg, h 0.95 m: 700 N m/rad), as
    /// active ankle stiffness sits above it (Winter et al. 1998, J.
    /// Neurophysiol. 80:1211; the intrinsic stiffness alone is 91 % of it,
    /// Loram & Lakie 2002, J. Physiol. 545:1041).
    pub ankle: JointGains,
    /// Knees' gains. Default kp 1500, kd 60 (our calibration: a crouch
    /// held within 2 deg under the body's weight).
    pub knee: JointGains,
    /// Hips' gains. Default kp 1500, kd 80 (our calibration; no measured
    /// hip stiffness in standing was found).
    pub hip: JointGains,
    /// Waist's gains (trunk on pelvis). Default kp 1200, kd 80 (our
    /// calibration: the waist's planned turns and bends, W1, within a few
    /// degrees).
    pub waist: JointGains,
    /// Stiffness of the centre of mass's horizontal spring toward the
    /// planned pelvis, as a multiple of gravity's toppling stiffness
    /// `m g / h`. Default 1.5: above 1, as the body's active ankle
    /// stiffness is above its load stiffness (Winter et al. 1998, J.
    /// Neurophysiol. 80:1211). 0-10.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub com_stiffness: f64,
    /// Its damping ratio. Default 1. 0-5.
    #[schemars(range(min = 0.0, max = 5.0))]
    pub com_damping: f64,
    /// The capture point outside the feet's polygon by more than this
    /// makes a recovery step, m. Default 0.03 (young adults step well
    /// before the centre of mass reaches the polygon's edge: Maki &
    /// McIlroy 1997, Phys. Ther. 77:488). 0-0.3 m.
    #[schemars(range(min = 0.0, max = 0.3))]
    pub step_margin: f64,
    /// Longest recovery step, m: how far a foot may be sent from where it
    /// is (B4). Default 0.6 (our choice: young adults recover a
    /// forward lean of up to about 30 deg with one step, Thelen et al.
    /// 1997, J. Gerontol. A 52:M8, which takes steps of this order).
    /// 0.1-1.2 m.
    #[schemars(range(min = 0.1, max = 1.2))]
    pub max_step: f64,
    /// How far the planned pelvis may lead the body's, m (the posture is
    /// re-planned from where the body is). Default 0.1. 0.01-1 m.
    #[schemars(range(min = 0.01, max = 1.0))]
    pub leash: f64,
    /// Trunk tilt from upright past which the body falls, deg. Default
    /// 45: past the largest lean young men recover with one step (32.5
    /// deg, Thelen et al. 1997, J. Gerontol. A 52:M8) with the trunk's
    /// own bend on top. 10-80 deg.
    #[schemars(range(min = 10.0, max = 80.0))]
    pub fall_tilt_deg: f64,
    /// The hips lower than this fall, m. Default 0.5 (a boxer's deepest
    /// duck keeps them near 0.7). 0.2-0.9 m.
    #[schemars(range(min = 0.2, max = 0.9))]
    pub fall_height: f64,
    /// A blow that turns the head faster than this stuns: the legs go and
    /// the body falls, whatever its balance, rad/s. A knockdown in boxing
    /// is the brain's, not the balance's: the fastest head rotations are
    /// the ones that end in one (Walilko, Viano & Bir 2005, Br. J. Sports
    /// Med. 39:710: hooks turn the head fastest). Default 20: below the 50 %
    /// concussion risk of 28.3 rad/s in football impacts (Rowson et al.
    /// 2012, Ann. Biomed. Eng. 40:1), since a flash knockdown needs no
    /// concussion; our choice, over ten times the head's turn from a clean
    /// 5 m/s jab (about 4 rad/s here). 5-200 rad/s.
    #[schemars(range(min = 5.0, max = 200.0))]
    pub stun_head_speed: f64,
    /// Muscle tone while falling and down, a share of the gains. Default
    /// 0.12: a knocked-down boxer crumples but is not limp as a doll.
    /// 0-1.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub down_tone: f64,
    /// Least time on the canvas, s. Default 2. 0.2-9.
    #[schemars(range(min = 0.2, max = 9.0))]
    pub down_time: f64,
    /// More time on the canvas per unit of damage (0-1), s. Default 5: a
    /// fresh fighter is up at two, a battered one near the eight-count.
    /// 0-20 s.
    #[schemars(range(min = 0.0, max = 20.0))]
    pub down_per_damage: f64,
    /// Time to get up, s. Default 1.5. 0.3-5 s.
    #[schemars(range(min = 0.3, max = 5.0))]
    pub rise_time: f64,
    /// Strongest push of the arms and legs that lifts the hips while
    /// rising, as a share of body weight. Default 1.3. 0-3.
    #[schemars(range(min = 0.0, max = 3.0))]
    pub rise_push: f64,
    /// Motor noise in the stance legs' push, the RMS of a horizontal
    /// force on the body, N: what makes a person standing still sway
    /// (van der Kooij & Peterka 2011, J. Comput. Neurosci. 30:759, whose
    /// model needs motor noise besides sensory noise to sway as people
    /// do). Default 20 (our calibration: the centre of mass then sways
    /// within the human band of docs/model/balance.md, B2). 0-200 N.
    #[schemars(range(min = 0.0, max = 200.0))]
    pub sway_force: f64,
    /// The noise's correlation time, s. Default 0.5 (our calibration:
    /// quiet stance's sway has most of its power below 1 Hz). 0.01-10 s.
    #[schemars(range(min = 0.01, max = 10.0))]
    pub sway_time: f64,
}

impl Default for BalanceParams {
    fn default() -> Self {
        let g = |kp: f64, kd: f64| JointGains {
            kp,
            kd,
            feedforward: 0.0,
        };
        BalanceParams {
            ankle: g(900.0, 60.0),
            knee: g(1500.0, 60.0),
            hip: g(1500.0, 80.0),
            waist: g(1200.0, 80.0),
            com_stiffness: 1.5,
            com_damping: 1.0,
            step_margin: 0.03,
            max_step: 0.6,
            leash: 0.1,
            fall_tilt_deg: 45.0,
            fall_height: 0.5,
            stun_head_speed: 20.0,
            down_tone: 0.12,
            down_time: 2.0,
            down_per_damage: 5.0,
            rise_time: 1.5,
            rise_push: 1.3,
            sway_force: 20.0,
            sway_time: 0.5,
        }
    }
}
