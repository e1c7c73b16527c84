//! Criterion bench: one offscreen frame of the default scene at 1280x720
//! (frame description on the CPU, face deformation, draw, and read-back of
//! the pixels), on whatever adapter wgpu finds (lavapipe without a GPU).
//! Also the frame without read-back (what the window pays).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use shisen::scene::LoadedScene;
use shisen_app::render::{Frame, Headless, Overlays, View};

const SIZE: (u32, u32) = (1280, 720);

fn frame(c: &mut Criterion) {
    let mut gpu = match Headless::new() {
        Ok(g) => g,
        Err(e) => {
            eprintln!("render bench skipped: {e}");
            return;
        }
    };
    eprintln!("adapter: {} ({:?})", gpu.info.name, gpu.info.backend);
    let mut sim = LoadedScene::default_scene().sim();
    for _ in 0..1000 {
        sim.step();
    }
    let mut g = c.benchmark_group("render");
    g.sample_size(20);
    g.bench_function("offscreen frame 1280x720 with read-back", |b| {
        b.iter(|| {
            black_box(
                gpu.snapshot(&sim, View::First, Overlays::default(), SIZE)
                    .expect("render"),
            )
        })
    });
    g.bench_function(
        "frame description only (CPU: poses, face deformation, normals)",
        |b| {
            b.iter(|| {
                black_box(Frame::build(
                    &sim,
                    View::First,
                    Overlays::default(),
                    16.0 / 9.0,
                ))
            })
        },
    );
    g.bench_function("frame 1280x720, no read-back", |b| {
        b.iter(|| {
            let f = Frame::build(&sim, View::First, Overlays::default(), 16.0 / 9.0);
            gpu.renderer.render(&f, &sim.model().face.mesh, SIZE);
            gpu.renderer.wait();
        })
    });
    g.finish();
}

criterion_group!(benches, frame);
criterion_main!(benches);
