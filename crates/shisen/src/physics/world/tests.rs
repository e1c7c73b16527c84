//! Tests of the physics world.
use super::*;

/// However abrupt the scripted path, a driven glove gains at most
/// `DRIVE_MAX_ACCEL dt` of speed in a step.
#[test]
fn a_driven_glove_is_capped() {
    let mut w = World::new(BodyPlan::default(), 0.001);
    let g = w.part(OpponentPart::LeftGlove);
    let p = w.rb(g).translation();
    w.drive(g, p + Vec3::X * 0.05, Vec3::X * 50.0, Vec3::X * 1e5);
    w.step();
    let v = w.rb(g).linvel().length();
    let cap = crate::physics::opponent::DRIVE_MAX_ACCEL * 0.001;
    assert!(v > 0.1 && v <= cap * 1.001, "{v}");
}

#[test]
fn joint_angles_round_trip() {
    let a = JointAngles {
        yaw: 0.4,
        pitch: -0.3,
        roll: 0.1,
    };
    let b = JointAngles::from_quat(a.to_quat());
    assert!((a.yaw - b.yaw).abs() < 1e-6);
    assert!((a.pitch - b.pitch).abs() < 1e-6);
    assert!((a.roll - b.roll).abs() < 1e-6);
    // positive pitch turns the forward axis up, positive yaw to the left (+X)
    let f = a.to_quat() * Vec3::Z;
    assert!(f.x > 0.0);
    let up = JointAngles {
        pitch: 0.3,
        ..Default::default()
    }
    .to_quat()
        * Vec3::Z;
    assert!(up.y > 0.0);
}

/// A welded glove is a collider on its forearm's body: it keeps its
/// place on the forearm however the arm swings, and its mass is the
/// forearm body's.
#[test]
fn a_welded_glove_rides_its_forearm() {
    let plan = BodyPlan::default();
    let (f, g) = (Seg::ForearmL, Seg::GloveL);
    let reach = (plan.segments[g.index()].centre - plan.segments[f.index()].pivot).length();
    let mass = plan.segments[f.index()].mass + plan.segments[g.index()].mass;
    let mut w = World::new(plan, 0.001);
    assert_eq!(w.info(g).handle, w.info(f).handle);
    assert!((w.rb(g).mass() - mass).abs() < 1e-4, "{}", w.rb(g).mass());
    let h = w.info(f).handle;
    w.phys.bodies[h].set_angvel(Vec3::new(3.0, 1.0, 0.0), true);
    for _ in 0..50 {
        w.step();
    }
    let elbow = w.pivot(f);
    let d = (w.position(g) - elbow).length();
    assert!((d - reach).abs() < 2e-3, "{d} vs {reach}");
    // The part's velocity is its point's, not the body centre's.
    let rb = w.rb(g);
    let lever = w.position(g) - rb.center_of_mass();
    let expect = rb.linvel() + rb.angvel().cross(lever);
    assert!((w.velocity(g) - expect).length() < 1e-4);
    assert!(w.joint_gap() < 2e-3, "{}", w.joint_gap());
}

#[test]
fn world_builds_at_rest() {
    let w = World::new(BodyPlan::default(), 0.001);
    assert_eq!(w.info(w.part(OpponentPart::LeftGlove)).name, "left_glove");
    let a = w.joint_angles(Seg::Head);
    assert!(a.yaw.abs() < 1e-9 && a.pitch.abs() < 1e-9);
    let i = w.subtree_inertia(Seg::EyeL, w.pivot(Seg::EyeL));
    let expect = shisen_gaze::anatomy::eye::INERTIA as f32;
    assert!(
        (i.x_axis.x - expect).abs() / expect < 1e-3,
        "{}",
        i.x_axis.x
    );
}
