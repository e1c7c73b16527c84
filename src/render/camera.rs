//! Cameras: first person from the opponent's head, and an orbit view.

use glam::{Mat4, Vec2, Vec3, Vec4Swizzles};

use shisen::physics::body::{EYE_FORWARD, OpponentPart, Seg};
use shisen::sim::Sim;

/// Which camera to render from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum View {
    /// From the opponent's (your) head toward the VH's face: the VH looks at you.
    First,
    /// Around the VH's head: `yaw` (about +Y, 0 = from the VH's front),
    /// `pitch` (up), `distance`, all about the VH's head centre.
    Orbit {
        /// Radians about +Y; 0 looks at the VH's face from its front.
        yaw: f32,
        /// Radians above the horizon.
        pitch: f32,
        /// Metres from the VH's head centre.
        distance: f32,
    },
}

impl View {
    /// The default orbit: three-quarter view from the VH's front left, a
    /// little above, far enough to see both boxers.
    /// A close-up of the face from the front (expression renders).
    pub const FACE: View = View::Orbit {
        yaw: 0.0,
        pitch: 0.05,
        distance: 0.42,
    };

    pub const ORBIT: View = View::Orbit {
        yaw: 0.9,
        pitch: 0.25,
        distance: 2.2,
    };

    /// Parse `first`, `orbit`, `face` or `orbit:YAW,PITCH,DISTANCE`
    /// (radians, radians, metres: yaw within +-2 pi, pitch within +-1.5
    /// (86 deg: the camera must not pass over the pole), distance
    /// 0.2-10 m).
    pub fn parse(s: &str) -> Option<View> {
        match s {
            "first" => Some(View::First),
            "orbit" => Some(View::ORBIT),
            "face" => Some(View::FACE),
            _ => {
                let v: Vec<f32> = s
                    .strip_prefix("orbit:")?
                    .split(',')
                    .map(|x| x.trim().parse().ok())
                    .collect::<Option<_>>()?;
                match v[..] {
                    [yaw, pitch, distance]
                        if yaw.abs() <= std::f32::consts::TAU
                            && pitch.abs() <= 1.5
                            && (0.2..=10.0).contains(&distance) =>
                    {
                        Some(View::Orbit {
                            yaw,
                            pitch,
                            distance,
                        })
                    }
                    _ => None,
                }
            }
        }
    }
}

/// A pinhole camera (right-handed, +Y up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position, world.
    pub eye: Vec3,
    /// Point looked at, world.
    pub target: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Width / height.
    pub aspect: f32,
}

/// Vertical field of view of the first-person camera (about 90 deg
/// across at 16:9, a desktop first-person view): the VH's head and arms,
/// and your own gloves in guard (some 27 deg below your line of sight)
/// whole in the lower corners, as you would see them.
const FIRST_FOV_DEG: f32 = 58.0;
/// How far behind your eyes the first-person camera sits, m.
const VIEW_BACK: f32 = 0.12;
/// How far above them, m.
const VIEW_UP: f32 = 0.04;
/// Height of a head's centre above its neck's pivot, m (the VH's plan:
/// `physics::body`), the lever through which a push on the head turns it.
const NECK_LEVER: f32 = 0.165;
/// The largest knock of the first-person view, deg.
pub const MAX_KNOCK_DEG: f32 = 12.0;
/// Orbit camera field of view.
const ORBIT_FOV_DEG: f32 = 45.0;

impl Camera {
    /// The camera of `view` for the current state of `sim`.
    pub fn of(view: View, sim: &Sim, aspect: f32) -> Camera {
        let w = &sim.world;
        let vh_head = w.pose(Seg::Head).0;
        match view {
            View::First => {
                let head = w.pose(w.part(OpponentPart::Head)).0;
                // Look at the VH's face (between its eyes), not the head centre.
                let face = (w.pose(Seg::EyeL).0 + w.pose(Seg::EyeR).0) / 2.0;
                // From just behind and above your eyes (your eyes are in
                // front of your head's centre as the VH's are of its own):
                // your gloves, 25 cm from your eyes, would fill the lower
                // third of the view from the eyes themselves; from here
                // they frame its bottom corners, a little smaller, under
                // the VH's face, and the view still moves with your head.
                let dir = (face - head).normalize_or_zero();
                let eye = head + dir * (EYE_FORWARD - VIEW_BACK) + Vec3::Y * VIEW_UP;
                Camera {
                    eye,
                    target: face + Vec3::Y * 0.02,
                    fov_y: FIRST_FOV_DEG.to_radians(),
                    aspect,
                }
            }
            View::Orbit {
                yaw,
                pitch,
                distance,
            } => {
                let dir = Vec3::new(
                    pitch.cos() * yaw.sin(),
                    pitch.sin(),
                    pitch.cos() * yaw.cos(),
                );
                Camera {
                    eye: vh_head + dir * distance,
                    target: vh_head,
                    fov_y: ORBIT_FOV_DEG.to_radians(),
                    aspect,
                }
            }
        }
    }

    /// Knock a first-person camera by the blow its head took: the
    /// avatar's head pushed `d` off its driven path turns the view as a
    /// head on a neck would, by `d / NECK_LEVER` (pushed back: the view
    /// tips up; pushed aside: it turns), scaled by `scale` (0 off, 1 full;
    /// a setting, for comfort) and never more than [`MAX_KNOCK_DEG`]. The
    /// drive that pulls the head back is critically damped, so the view
    /// snaps and returns without shaking.
    pub fn knock(&mut self, sim: &Sim, scale: f32) {
        let w = &sim.world;
        let head = w.part(OpponentPart::Head);
        let Some(path) = w.drive_target(head) else {
            return;
        };
        let d = w.position(head) - path;
        let to = self.target - self.eye;
        let dist = to.length();
        let f = to / dist.max(1e-6);
        let right = f.cross(Vec3::Y).normalize_or_zero();
        let up = right.cross(f);
        let turn = Vec2::new(d.dot(right), -d.dot(f)) / NECK_LEVER * scale.clamp(0.0, 1.0);
        let turn = turn.clamp_length_max(MAX_KNOCK_DEG.to_radians());
        self.target += (right * turn.x + up * turn.y) * dist;
    }

    /// World to view matrix.
    pub fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye, self.target, Vec3::Y)
    }

    /// World to clip matrix (wgpu clip space: z in [0, 1]).
    pub fn view_proj(&self) -> Mat4 {
        let proj =
            glam::camera::rh::proj::directx::perspective(self.fov_y, self.aspect, 0.02, 30.0);
        proj * self.view()
    }

    /// Pixel position (origin top left) of a world point in an image of
    /// `size` pixels, or `None` behind the camera.
    pub fn project(&self, p: Vec3, size: Vec2) -> Option<Vec2> {
        let c = self.view_proj() * p.extend(1.0);
        if c.w <= 1e-6 {
            return None;
        }
        let ndc = c.xy() / c.w;
        Some(Vec2::new(
            (ndc.x + 1.0) * 0.5 * size.x,
            (1.0 - ndc.y) * 0.5 * size.y,
        ))
    }

    /// Ray (origin, unit direction) through a pixel of an image of `size`.
    pub fn ray(&self, pixel: Vec2, size: Vec2) -> (Vec3, Vec3) {
        let ndc = Vec2::new(pixel.x / size.x * 2.0 - 1.0, 1.0 - pixel.y / size.y * 2.0);
        let inv = self.view_proj().inverse();
        let far = inv.project_point3(ndc.extend(1.0));
        (self.eye, (far - self.eye).normalize_or(Vec3::NEG_Z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A blow pushing your head back tips the first-person view up, in
    /// proportion to the setting and never past the cap; at rest on its
    /// path the head does not move the view.
    #[test]
    fn a_blow_knocks_the_first_person_view() {
        let mut sim = shisen::scene::LoadedScene::default_scene().sim();
        for _ in 0..20 {
            sim.step();
        }
        let still = Camera::of(View::First, &sim, 1.5);
        let mut knocked = still;
        knocked.knock(&sim, 1.0);
        assert!(knocked.target.distance(still.target) < 1e-3, "at rest");
        // A blow: the avatar's head thrown back (+Z, away from the VH) at 2 m/s.
        let head = sim.world.part(OpponentPart::Head);
        let h = sim.world.info(head).handle;
        sim.world.phys.bodies[h].set_linvel(Vec3::Z * 2.0, true);
        for _ in 0..15 {
            sim.step();
        }
        let cam = Camera::of(View::First, &sim, 1.5);
        let turn = |scale: f32| {
            let mut c = cam;
            c.knock(&sim, scale);
            let (a, b) = (
                (cam.target - cam.eye).normalize(),
                (c.target - c.eye).normalize(),
            );
            (b.y - a.y, a.angle_between(b).to_degrees())
        };
        let (up, full) = turn(1.0);
        assert!(up > 0.0 && full > 2.0, "tips up: {up} {full} deg");
        let (_, half) = turn(0.5);
        assert!((half - full / 2.0).abs() < 0.2 * full, "{half} vs {full}");
        assert_eq!(turn(0.0).1, 0.0);
        assert!(full <= MAX_KNOCK_DEG + 0.01);
    }

    #[test]
    fn project_and_ray_are_inverse() {
        let cam = Camera {
            eye: Vec3::new(0.0, 1.7, 0.9),
            target: Vec3::new(0.0, 1.68, 0.0),
            fov_y: 0.7,
            aspect: 1.5,
        };
        let size = Vec2::new(300.0, 200.0);
        let p = Vec3::new(0.1, 1.6, 0.2);
        let px = cam.project(p, size).expect("in front");
        let (o, d) = cam.ray(px, size);
        let closest = o + d * (p - o).dot(d);
        assert!(closest.distance(p) < 1e-4, "{closest} vs {p}");
        let centre = cam.project(cam.target, size).unwrap();
        assert!(centre.distance(size / 2.0) < 1e-3);
    }

    #[test]
    fn orbit_views_parse_and_bad_ones_are_refused() {
        assert_eq!(
            View::parse("orbit:0.5, 0.1,0.8"),
            Some(View::Orbit {
                yaw: 0.5,
                pitch: 0.1,
                distance: 0.8
            })
        );
        for bad in [
            "orbit:0.5,0.1",
            "orbit:0.5,0.1,0.8,1",
            "orbit:NaN,0.1,0.8",
            "orbit:0.5,0.1,0.1",
            "orbit:0.5,0.1,11",
            "orbit:a,b,c",
            "orbit:1e30,0,1",
            "orbit:0,2,1",
            "sideways",
        ] {
            assert_eq!(View::parse(bad), None, "{bad}");
        }
    }
}
