//! Behaviour of vision and attention in whole scenes, beyond what the
//! scenes' own expectations say: comparisons and latencies.

use std::path::Path;

use glam::Vec3;
use shisen::gaze::vision::{VisionParams, see};
use shisen::physics::body::{BodyPlan, Shape};
use shisen::physics::world::{PropSpec, World};
use shisen::scene::LoadedScene;
use shisen::sim::{DT, Sample, Sim};

fn scene(name: &str) -> LoadedScene {
    LoadedScene::load(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenes")
            .join(name),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

fn face_share(loaded: &LoadedScene, from: f64) -> f64 {
    let mut sim = loaded.sim();
    let (mut n, mut on) = (0, 0);
    while sim.time() < loaded.scene.duration - 1e-9 {
        let s: &Sample = sim.step();
        if s.t > from {
            n += 1;
            on += (s.gaze_target == "head") as u32;
        }
    }
    on as f64 / n as f64
}

/// The seed's "strong boxer" (A_face 4.0) watches the face through the same
/// punches for a measurably larger share of the time than a "weak boxer"
/// (A_face 0.5).
#[test]
fn strong_boxer_watches_the_face_more_than_a_weak_one() {
    let strong = face_share(&scene("strong_boxer.ron"), 0.8);
    let weak = face_share(&scene("weak_boxer.ron"), 0.8);
    println!(
        "gaze on the face over the punch sequence: strong {:.1} %, weak {:.1} %",
        strong * 100.0,
        weak * 100.0
    );
    assert!(strong - weak > 0.3, "strong {strong}, weak {weak}");
}

/// A hand entering the field of view is looked at within 150 ms of the
/// tick it first appears in the visible-body list, and never before.
#[test]
fn a_hand_entering_the_field_is_noticed_quickly() {
    let loaded = scene("fov_entry.ron");
    let hand = |sim: &Sim| sim.world.body_named("hand").unwrap();
    let mut sim = loaded.sim();
    let mut entered = None;
    let mut looked = None;
    while sim.time() < loaded.scene.duration - 1e-9 {
        let s = sim.step().clone();
        let visible = sim.seen().iter().any(|x| x.body == hand(&sim));
        if visible && entered.is_none() {
            entered = Some(s.t);
        }
        if s.gaze_target == "hand" {
            assert!(
                entered.is_some(),
                "looked at before it was visible, t = {}",
                s.t
            );
            looked.get_or_insert(s.t);
        }
    }
    let (e, l) = (entered.expect("enters"), looked.expect("looked at"));
    println!(
        "hand enters the field at {e:.3} s, gaze on it at {l:.3} s ({:.0} ms)",
        (l - e) * 1e3
    );
    assert!(l - e < 0.150);
}

/// Vision drops a body hidden behind another (ray test), keeps it when
/// occlusion is off, and sees it again when it moves out.
#[test]
fn occluded_bodies_are_not_seen() {
    let mut world = World::new(BodyPlan::default(), DT);
    let board = world.add_prop(&PropSpec {
        name: "board".into(),
        shape: Shape::Cuboid {
            half: Vec3::new(0.12, 0.12, 0.01),
        },
        position: Vec3::new(0.0, 1.67, 0.45),
        velocity: Vec3::ZERO,
        angvel: Vec3::ZERO,
        mass: 1.0,
        kinematic: true,
        gravity: false,
    });
    let ball = world.add_prop(&PropSpec {
        name: "ball".into(),
        shape: Shape::Ball { radius: 0.04 },
        position: Vec3::new(0.0, 1.67, 1.6),
        velocity: Vec3::ZERO,
        angvel: Vec3::ZERO,
        mass: 0.1,
        kinematic: true,
        gravity: false,
    });
    // Move the opponent's head out of the way of nothing; step once so the
    // query structures are built.
    world.step();
    let mut seen = Vec::new();
    let p = VisionParams::default();
    see(&world, &p, [true, true], &mut seen);
    assert!(seen.iter().any(|s| s.body == board), "the board is seen");
    assert!(
        !seen.iter().any(|s| s.body == ball),
        "the ball behind it is not"
    );
    let no_occlusion = VisionParams {
        occlusion: false,
        ..p.clone()
    };
    see(&world, &no_occlusion, [true, true], &mut seen);
    assert!(
        seen.iter().any(|s| s.body == ball),
        "without the ray test it would be"
    );
    world.drive(ball, Vec3::new(1.0, 1.67, 1.6), Vec3::ZERO, Vec3::ZERO);
    world.step();
    see(&world, &p, [true, true], &mut seen);
    assert!(
        seen.iter().any(|s| s.body == ball),
        "out from behind the board it is seen"
    );
    // With both eyes shut nothing is seen.
    see(&world, &p, [false, false], &mut seen);
    assert!(seen.is_empty());
}
