//! Drive a character's eyes and neck from a moving target, with no physics
//! engine: the gaze controller (oculomotor laws M2-M9) alone, its commands
//! taken as the joints' new angles each tick, as an animation system would
//! (a perfect "plant").
//!
//! A ball swings slowly left and right in front of the character (smooth
//! pursuit), then jumps 40 degrees to the side (a saccade, with the head
//! following per M8-M9). Every 50 ms the example prints the target's
//! direction, both eyes' yaw and the neck's yaw.
//!
//! Run: `cargo run -p shisen-gaze --example gaze_without_physics`

use glam::{DQuat, DVec2, DVec3};
use rand::SeedableRng;
use rand::rngs::StdRng;
use shisen_gaze::anatomy::eye;
use shisen_gaze::oculomotor::head::Amount;
use shisen_gaze::oculomotor::{GazeInput, GazeShiftLaw, Oculomotor, OculomotorParams};
use shisen_gaze::target::{BodyId, TargetId};
use shisen_gaze::util::math::{JointAngles, yaw_pitch_of};

/// Head centre of our character, world metres (facing +Z, +X its left).
const HEAD: DVec3 = DVec3::new(0.0, 1.68, 0.0);
/// Step, s: the controller is written for a 1 kHz tick.
const DT: f64 = 0.001;

/// The target: a slow swing, then a jump to the side at t = 1.5 s.
fn target(t: f64) -> DVec3 {
    if t < 1.5 {
        DVec3::new(0.25 * (t * 2.0).sin(), 1.68, 1.0)
    } else {
        DVec3::new(0.84, 1.60, 1.0) // about 40 deg to the left
    }
}

fn main() {
    let params = OculomotorParams::default();
    let mut rng = StdRng::seed_from_u64(7);
    let mut gaze = Oculomotor::new(&params, &mut rng);
    // The joints' state: our plant follows each command exactly.
    let mut eyes = [DVec2::ZERO; 2];
    let mut neck = DVec2::ZERO;
    let mut neck_rate = DVec2::ZERO;
    println!("   t    target yaw   left eye   right eye    neck   (deg)");
    for tick in 0..3000u32 {
        let t = f64::from(tick) * DT;
        let neck_angles = JointAngles {
            yaw: neck.x,
            pitch: neck.y,
            roll: 0.0,
        };
        let head_rot = neck_angles.to_quat().as_dquat();
        // Eye centres: half the interpupillary distance either side, a
        // little in front of the head centre, carried by the head.
        let eye_pos =
            [1.0, -1.0].map(|s| HEAD + head_rot * DVec3::new(s * eye::IPD / 2.0, 0.05, 0.07));
        let point = target(t);
        let input = GazeInput {
            point,
            // One identity for the swinging ball, another for the thing
            // to the side: a new target is what triggers a saccade.
            target: TargetId::body(BodyId::new(if t < 1.5 { 1 } else { 2 })),
            amount: Amount {
                value: 3.0,
                least: 0.0,
                most: 3.0,
            },
            top_down: false,
            head_pos: HEAD,
            head_rot,
            head_angvel: DVec3::new(0.0, neck_rate.x, 0.0),
            torso_rot: DQuat::IDENTITY,
            eye_pos,
            eye_angles: eyes,
            neck_angles,
            visible: [true, true],
            style: GazeShiftLaw::Reflex,
            neck_override: None,
        };
        let out = gaze.step(&params, &input, t, DT, &mut rng);
        eyes = out.eyes.map(|e| e.angles);
        neck = out.neck.angles;
        neck_rate = out.neck.rates;
        if tick % 50 == 0 {
            let (ty, _) = yaw_pitch_of(point - HEAD);
            println!(
                "{t:5.2}  {:10.1}  {:9.1}  {:10.1}  {:7.1}",
                ty.to_degrees(),
                eyes[0].x.to_degrees(),
                eyes[1].x.to_degrees(),
                neck.x.to_degrees()
            );
        }
    }
    println!(
        "saccades: {}, head movements: {}",
        gaze.saccades, gaze.head_moves
    );
}
