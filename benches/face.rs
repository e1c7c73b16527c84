//! One skin deformation (`face::deform`) at about 2k, 20k and 100k
//! vertices: anger at full intensity (7 muscle kinds, 11 channels, jaw
//! 3.5 degrees) with both lids following a 10-degree downward gaze; and
//! the wrinkle measurement of that deformed skin (`face::wrinkle::measure`,
//! once per rendered frame).
use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use glam::Vec3;
use rand::SeedableRng;
use rand::rngs::StdRng;
use shisen::face::emotion::emotion_activation;
use shisen::face::mesh::MeshParams;
use shisen::face::params::FaceParams;
use shisen::face::tables::Emotion;
use shisen::face::timing::{Pattern, Speed};
use shisen::face::wrinkle::measure;
use shisen::face::{Face, FaceState, deform};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("deform");
    for rows in [32, 100, 224] {
        let face = Face::new(MeshParams { rows }, FaceParams::default_params());
        let mut state = FaceState::default();
        state.set_emotion(&face, Emotion::Anger, 1.0, Speed::Fast, Pattern::III);
        state.eye_pitch = [-0.17; 2];
        state.step(&face, 5.0, &mut StdRng::seed_from_u64(1));
        assert_eq!(
            state.activation.jaw_deg,
            emotion_activation(&face.params, Emotion::Anger, 1.0).jaw_deg
        );
        let n = face.mesh.positions.len();
        let mut out = vec![Vec3::ZERO; n];
        g.bench_function(format!("anger_rows{rows}_{n}v"), |b| {
            b.iter(|| deform(black_box(&face), black_box(&state), &mut out))
        });
        deform(&face, &state, &mut out);
        let mut wrinkles = Vec::new();
        g.bench_function(format!("wrinkles_rows{rows}_{n}v"), |b| {
            // W4 thickens the positions it measures: each run gets the
            // deformed skin afresh (the copy is not timed).
            b.iter_batched_ref(
                || out.clone(),
                |pos| {
                    measure(
                        black_box(&face.mesh),
                        &face.wrinkle_basis,
                        &face.params.skin,
                        black_box(pos),
                        &mut wrinkles,
                    )
                },
                BatchSize::SmallInput,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
