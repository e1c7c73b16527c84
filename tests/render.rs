//! Offscreen rendering on whatever adapter wgpu finds (lavapipe on a
//! machine without a GPU): the face is in frame, both eyes show a pupil,
//! and the pupils move in the picture when the VH's gaze moves.
//!
//! They need a graphics adapter, so a plain `cargo test` ignores them;
//! `.ci/run` installs Mesa's lavapipe and runs them with
//! `cargo test --test render -- --ignored`, where a missing adapter fails.

use std::path::Path;

use glam::Vec2;
use shisen::physics::body::Seg;
use shisen::scene::LoadedScene;
use shisen::sim::{DT, Sim};
use shisen_app::render::{Camera, Frame, Headless, Overlays, View};

const SIZE: (u32, u32) = (800, 800);

/// Why these tests are ignored by a plain `cargo test`.
const NEEDS_GPU: &str = "needs a graphics adapter (Mesa's lavapipe will do)";

fn gpu() -> Headless {
    Headless::new().unwrap_or_else(|e| panic!("{NEEDS_GPU}: {e}"))
}

fn run_to(sim: &mut Sim, t: f64) {
    while sim.time() + DT / 2.0 < t {
        sim.step();
    }
}

/// Near-black pixels of the pupil's blue-black (not the lashes' brown-black)
/// within `radius` px of `centre`: their centroid.
fn pupil(img: &image::RgbaImage, centre: Vec2, radius: f32) -> Option<Vec2> {
    let (mut sum, mut n) = (Vec2::ZERO, 0.0);
    for (x, y, p) in img.enumerate_pixels() {
        let at = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        let [r, _, b, _] = p.0;
        if at.distance(centre) <= radius && p.0[..3].iter().all(|&c| c < 40) && b >= r {
            sum += at;
            n += 1.0;
        }
    }
    (n >= 3.0).then(|| sum / n)
}

struct Look {
    /// Pupil centroid minus the projected eyeball centre, per eye, pixels.
    offset: [Vec2; 2],
}

fn look(gpu: &mut Headless, sim: &Sim) -> Look {
    let img = gpu
        .snapshot(sim, View::FACE, Overlays::default(), SIZE)
        .expect("render");
    let size = Vec2::new(SIZE.0 as f32, SIZE.1 as f32);
    let cam = Camera::of(View::FACE, sim, 1.0);
    let eyes = [Seg::EyeL, Seg::EyeR].map(|e| {
        cam.project(sim.world.pose(e).0, size)
            .expect("eye in front of the camera")
    });
    // Face in frame: lit skin around and between the eyes.
    let skin = img
        .pixels()
        .filter(|p| {
            let [r, g, b, _] = p.0;
            r > 110 && r as i32 > g as i32 + 20 && g > b
        })
        .count();
    let share = skin as f64 / (SIZE.0 * SIZE.1) as f64;
    assert!(
        share > 0.03,
        "face covers only {:.1} % of the picture",
        share * 100.0
    );
    for e in eyes {
        assert!(
            e.x > 0.0 && e.y > 0.0 && e.x < size.x && e.y < size.y,
            "eye outside the picture at {e}"
        );
    }
    let offset = eyes.map(|e| {
        pupil(&img, e, 14.0).unwrap_or_else(|| {
            let dump = std::env::temp_dir().join("shisen-render-failure.png");
            let _ = img.save(&dump);
            panic!(
                "no pupil near {e} at t = {} (picture: {})",
                sim.time(),
                dump.display()
            )
        }) - e
    });
    Look { offset }
}

#[test]
#[ignore = "needs a graphics adapter: cargo test --test render -- --ignored"]
fn pupils_follow_the_gaze() {
    let mut gpu = gpu();
    let scene = LoadedScene::load(Path::new("scenes/look_sequence.ron")).expect("scene");
    let mut sim = scene.sim();
    // 1.2 s: fixating 10 deg to the VH's left; 2.2 s: 20 deg right, 10 up.
    run_to(&mut sim, 1.2);
    let a = look(&mut gpu, &sim);
    run_to(&mut sim, 2.2);
    let b = look(&mut gpu, &sim);
    for k in 0..2 {
        let d = a.offset[k] - b.offset[k];
        eprintln!(
            "eye {k}: pupil offset {} px at 1.2 s, {} px at 2.2 s",
            a.offset[k], b.offset[k]
        );
        // The VH's left is the picture's right (you face it).
        assert!(
            d.x > 4.0,
            "eye {k}: pupil moved {d} px; expected rightward-to-leftward shift"
        );
        assert!(
            d.y > 2.0,
            "eye {k}: pupil should rise in the picture, moved {d} px"
        );
    }
}

#[test]
#[ignore = "needs a graphics adapter: cargo test --test render -- --ignored"]
fn rendering_is_deterministic_and_orbit_view_works() {
    let mut gpu = gpu();
    let mut sim = LoadedScene::default_scene().sim();
    run_to(&mut sim, 0.3);
    let all = Overlays {
        gaze_rays: true,
        fov_cones: true,
        saliency_labels: true,
        joint_frames: true,
    };
    let a = gpu.snapshot(&sim, View::ORBIT, all, (160, 120)).unwrap();
    let b = gpu.snapshot(&sim, View::ORBIT, all, (160, 120)).unwrap();
    assert_eq!(a.as_raw(), b.as_raw(), "same state, same pixels");
    let distinct: std::collections::HashSet<_> = a.pixels().map(|p| p.0).collect();
    assert!(distinct.len() > 50, "picture is nearly blank");
}

/// The window's view on a software rasteriser is drawn on a device of its
/// own and handed to the window's device a frame later: the picture that
/// arrives is the previous frame's, whole (rows of a width whose bytes are
/// not a multiple of the copy alignment), and none before the second.
#[test]
#[ignore = "needs a graphics adapter: cargo test --test render -- --ignored"]
fn the_relay_hands_over_the_previous_frame_whole() {
    let gpu = gpu();
    let (mut own, mut relay) = gpu.relay().expect("a second device");
    let mut sim = LoadedScene::default_scene().sim();
    run_to(&mut sim, 0.3);
    let face = &sim.model().face.mesh;
    let size = (150, 100);
    let aspect = size.0 as f32 / size.1 as f32;
    let first = Frame::build(&sim, View::FACE, Overlays::default(), aspect);
    let second = Frame::build(&sim, View::ORBIT, Overlays::default(), aspect);
    relay.render(&mut own, &first, face, size);
    relay.receive(&own).unwrap();
    assert!(relay.shown().is_none(), "nothing yet");
    relay.render(&mut own, &second, face, size);
    let second_drawn = own.read_rgba().unwrap();
    relay.receive(&own).unwrap();
    let shown = relay.shown().expect("the first picture");
    let got = gpu.renderer.read_texture(shown).unwrap();
    // The first frame drawn by a fresh renderer of the same kind (a
    // window's renderer redraws its shadow map every other frame).
    let (mut fresh, _) = gpu.relay().expect("a third device");
    fresh.render(&first, face, size);
    let first_drawn = fresh.read_rgba().unwrap();
    assert_ne!(first_drawn.as_raw(), second_drawn.as_raw(), "two views");
    assert_eq!(got.dimensions(), first_drawn.dimensions());
    assert!(
        got.as_raw() == first_drawn.as_raw(),
        "the relayed picture is not the first frame's"
    );
}

#[test]
#[ignore = "needs a graphics adapter: cargo test --test render -- --ignored"]
fn render_command_writes_a_png() {
    drop(gpu());
    let out = std::env::temp_dir().join(format!("shisen-render-{}.png", std::process::id()));
    let st = std::process::Command::new(env!("CARGO_BIN_EXE_shisen"))
        .args([
            "render", "default", "--at", "0.2", "--size", "96x64", "--view", "orbit",
        ])
        .arg("--out")
        .arg(&out)
        .status()
        .expect("run shisen");
    assert!(st.success());
    let img = image::open(&out).expect("png").to_rgba8();
    assert_eq!(img.dimensions(), (96, 64));
    let _ = std::fs::remove_file(out);
}

#[test]
#[ignore = "needs a graphics adapter: cargo test --test render -- --ignored"]
fn an_exported_head_imported_again_renders() {
    drop(gpu());
    let dir = std::env::temp_dir().join(format!("shisen-import-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shisen = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_shisen"))
            .args(args)
            .current_dir(&dir)
            .output()
            .expect("run shisen");
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "shisen {args:?}: {err}");
    };
    shisen(&["face", "export", "--out", "head.glb", "--rows", "32"]);
    assert!(dir.join("head.landmarks.ron").is_file());
    std::fs::write(
        dir.join("imported.ron"),
        "Scene(duration: 1.0, vh: (face: (mesh: \"head.glb\", landmarks: \"head.landmarks.ron\")),\n  timeline: [(at: 0.0, do: Emotion(emotion: Happiness, speed: Fast))])",
    )
    .unwrap();
    shisen(&[
        "render",
        "imported.ron",
        "--at",
        "0.8",
        "--view",
        "face",
        "--size",
        "200x200",
        "--out",
        "face.png",
    ]);
    let img = image::open(dir.join("face.png")).expect("png").to_rgba8();
    let distinct: std::collections::HashSet<_> = img.pixels().map(|p| p.0).collect();
    assert!(
        distinct.len() > 50,
        "the imported head's picture is nearly blank"
    );
    let _ = std::fs::remove_dir_all(dir);
}
