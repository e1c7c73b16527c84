//! Criterion benches: one full control step of the default scene (physics,
//! vision, attention, behaviour, oculomotor, PD), and vision + attention
//! against the number of bodies in view.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use shisen::gaze::attention::{Attention, AttentionParams, Spot};
use shisen::gaze::behaviour::TopDown;
use shisen::gaze::vision::{VisionParams, see};
use shisen::physics::body::{BodyPlan, OpponentPart, Shape};
use shisen::physics::world::{PropSpec, World};
use shisen::scene::LoadedScene;
use shisen::sim::DT;

fn full_step(c: &mut Criterion) {
    let loaded = LoadedScene::default_scene();
    let mut sim = loaded.sim();
    // Warm up into the sparring part of the scene.
    for _ in 0..1000 {
        sim.step();
    }
    c.bench_function("full control step (default scene)", |b| {
        b.iter(|| {
            if sim.time() > loaded.scene.duration {
                sim = loaded.sim();
            }
            black_box(sim.step().t)
        })
    });
}

fn vision_attention(c: &mut Criterion) {
    let mut group = c.benchmark_group("vision + attention");
    for n in [10usize, 100, 1000] {
        let mut world = World::new(BodyPlan::default(), DT);
        // A cloud of moving balls in front of the VH, 1-4 m away.
        for i in 0..n {
            let f = i as f32;
            world.add_prop(&PropSpec {
                name: format!("ball{i}"),
                shape: Shape::Ball { radius: 0.03 },
                position: glam::Vec3::new(
                    (f * 0.618).fract() * 3.0 - 1.5,
                    1.0 + (f * 0.377).fract() * 1.5,
                    1.0 + (f * 0.733).fract() * 3.0,
                ),
                velocity: glam::Vec3::new((f * 0.3).sin(), (f * 0.7).cos(), 0.2),
                angvel: glam::Vec3::ZERO,
                mass: 0.1,
                kinematic: false,
                gravity: false,
            });
        }
        world.step();
        let names: Vec<String> = world.bodies.iter().map(|b| b.name.clone()).collect();
        let params = VisionParams::default();
        let ap = AttentionParams::default();
        let top = TopDown {
            name: "head".into(),
            body: Some(world.part(OpponentPart::Head)),
            spot: Spot::Centre,
            offset: DVec3::ZERO,
            amount: 1.5,
        };
        let mut seen = Vec::new();
        let mut att = Attention::new(names.clone());
        let mut t = 0.0;
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| {
                see(&world, &params, [true, true], &mut seen);
                let c = att.step(
                    &ap,
                    &seen,
                    &top,
                    |i| world.rb(i).translation().as_dvec3(),
                    t,
                    DT,
                );
                t += DT;
                black_box(c.amount)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, full_step, vision_attention);
criterion_main!(benches);
