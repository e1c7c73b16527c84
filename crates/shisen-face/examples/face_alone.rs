//! The muscle-driven face on its own, with no physics, no renderer and no
//! gaze controller: build the generated head, ask for a smile, step the
//! face's state at 1 kHz and deform the mesh, as an animation system that
//! brings its own renderer would. Every 100 ms the example prints the
//! smile's two zygomatic major contractions, the upper lids' blink
//! closure and how far a mouth corner has moved.
//!
//! Run: `cargo run -p shisen-face --example face_alone`

use glam::Vec3;
use rand::SeedableRng;
use rand::rngs::StdRng;
use shisen_face::emotion::{MuscleId, Side};
use shisen_face::mesh::MeshParams;
use shisen_face::params::FaceParams;
use shisen_face::tables::{Emotion, MuscleKind};
use shisen_face::timing::{Pattern, Speed};
use shisen_face::{Face, FaceState, deform};

fn main() {
    // A light head (about 2k vertices); rows 48 is the window's default.
    let face = Face::new(MeshParams { rows: 32 }, FaceParams::default_params());
    let mut state = FaceState::default();
    let mut rng = StdRng::seed_from_u64(1);
    let rest = face.mesh.positions.clone();
    let mut skin = vec![Vec3::ZERO; rest.len()];
    // The last vertex of the upper lip's rim: a corner of the mouth.
    let corner = *face.mesh.rims.upper_lip.last().expect("the lip has a rim") as usize;
    let zygomatic = [Side::Left, Side::Right].map(|side| {
        MuscleId {
            kind: MuscleKind::ZygomaticMajor,
            side,
        }
        .index()
        .expect("zygomatic major drives a channel")
    });
    println!("{} vertices; smiling from t = 0.2 s", rest.len());
    let dt = 0.001;
    for tick in 0..=1500 {
        let t = tick as f64 * dt;
        if tick == 200 {
            state.set_emotion(&face, Emotion::Happiness, 1.0, Speed::Typical, Pattern::III);
        }
        state.step(&face, dt, &mut rng);
        if tick % 100 == 0 {
            deform(&face, &state, &mut skin);
            let moved = (skin[corner] - rest[corner]) * 1e3;
            println!(
                "t {t:.1} s  zygomatic major {:.2} / {:.2}  blink {:.2}  mouth corner moved ({:+.1}, {:+.1}, {:+.1}) mm",
                state.activation.k[zygomatic[0]],
                state.activation.k[zygomatic[1]],
                state.blink.closure(&face.params.blink),
                moved.x,
                moved.y,
                moved.z
            );
        }
    }
}
