//! Export the sparring bodies as an MJCF model (MuJoCo's XML), generated
//! from the same [`BodyPlan`] the rapier world is built from, so a peer
//! comparison steps the same bodies and joints (`benches/mujoco_compare.py`).
//!
//! Frames: MuJoCo is Z-up; our world is Y-up. A point (x, y, z) of ours
//! becomes (x, -z, y) there, a proper rotation (+90 deg about X).
//!
//! With a physical body ([`mjcf`]'s `legs`: `vh.body.pelvis: Balanced`)
//! the tree is rooted at the pelvis, a free body on a canvas plane, as the
//! rapier articulation is: hips, ankles and the waist ball joints, knees
//! hinges, the same masses (de Leva 1996) and the soles' friction.

use std::fmt::Write as _;

use glam::{Quat, Vec3};

use crate::physics::body::{
    BodyPlan, JointKind, Shape, TRUNK_HALF_HEIGHT, TRUNK_RADIUS, trunk_under,
};
use crate::physics::legs::{
    FOOT_HALF_HEIGHT, FOOT_HALF_WIDTH, PELVIS_HALF, SHANK_RADIUS, SOLE_FRICTION, THIGH_RADIUS,
    leg_frames, share,
};
use crate::physics::lower::{BodyParams, LowerBody, WAIST_REST, anthro};

fn zup(v: Vec3) -> String {
    format!("{:.5} {:.5} {:.5}", v.x, -v.z, v.y)
}

/// A rotation of ours as an MJCF `quat` (w x y z) in MuJoCo's frame.
fn zup_quat(q: Quat) -> String {
    let c = Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
    let r = c * q * c.inverse();
    format!("{:.6} {:.6} {:.6} {:.6}", r.w, r.x, r.y, r.z)
}

/// A capsule from `a` to `b` (body frame), radius `r`, mass `m`.
fn capsule(a: Vec3, b: Vec3, r: f32, m: f32) -> String {
    format!(
        "<geom type=\"capsule\" size=\"{r:.5}\" fromto=\"{} {}\" mass=\"{m:.5}\" contype=\"1\" conaffinity=\"2\"/>",
        zup(a),
        zup(b)
    )
}

/// The physical lower body under the waist (`waist`, the pelvis body's
/// origin), as MJCF bodies: pelvis box, and per leg thigh, shank, foot.
fn lower_body(p: &BodyParams, x: &mut String) {
    let m = anthro::MASS as f32;
    let waist = WAIST_REST.as_vec3();
    let rest = LowerBody::new(p).legs(p);
    let pelvis_centre = Vec3::new(0.0, -anthro::HIP_BELOW_WAIST as f32, 0.0);
    let turn = Quat::from_rotation_y(p.hip_turn_deg.to_radians() as f32);
    let _ = writeln!(
        x,
        "      <geom type=\"box\" size=\"{:.5} {:.5} {:.5}\" pos=\"{}\" quat=\"{}\" mass=\"{:.5}\" contype=\"1\" conaffinity=\"2\"/>",
        PELVIS_HALF.x,
        PELVIS_HALF.z,
        PELVIS_HALF.y,
        zup(pelvis_centre),
        zup_quat(turn),
        m * share::PELVIS
    );
    for (k, leg) in rest.iter().enumerate() {
        let [hip, knee, ankle] = [leg.hip, leg.knee, leg.ankle].map(|v| v.as_vec3());
        let (heel, toe) = (leg.heel.as_vec3(), leg.toe.as_vec3());
        let along = (toe - heel).normalize();
        let foot_centre =
            heel + along * anthro::FOOT_LENGTH as f32 / 2.0 + Vec3::Y * FOOT_HALF_HEIGHT;
        let [thigh_frame, _, _] = leg_frames(leg);
        let _ = writeln!(
            x,
            "      <body name=\"vh_thigh_{k}\" pos=\"{}\">",
            zup(hip - waist)
        );
        let _ = writeln!(x, "        <joint name=\"vh_hip_{k}\" type=\"ball\"/>");
        let _ = writeln!(
            x,
            "        {}",
            capsule(Vec3::ZERO, knee - hip, THIGH_RADIUS, m * share::THIGH)
        );
        let _ = writeln!(
            x,
            "        <body name=\"vh_shank_{k}\" pos=\"{}\">",
            zup(knee - hip)
        );
        let _ = writeln!(
            x,
            "          <joint name=\"vh_knee_{k}\" type=\"hinge\" axis=\"{}\"/>",
            zup(thigh_frame.x_axis)
        );
        let _ = writeln!(
            x,
            "          {}",
            capsule(Vec3::ZERO, ankle - knee, SHANK_RADIUS, m * share::SHANK)
        );
        let _ = writeln!(
            x,
            "          <body name=\"vh_foot_{k}\" pos=\"{}\">",
            zup(ankle - knee)
        );
        let _ = writeln!(
            x,
            "            <joint name=\"vh_ankle_{k}\" type=\"ball\"/>"
        );
        let _ = writeln!(
            x,
            "            <geom type=\"box\" size=\"{FOOT_HALF_WIDTH:.5} {:.5} {FOOT_HALF_HEIGHT:.5}\" pos=\"{}\" quat=\"{}\" mass=\"{:.5}\" friction=\"{SOLE_FRICTION} 0.005 0.0001\" contype=\"1\" conaffinity=\"2\"/>",
            anthro::FOOT_LENGTH as f32 / 2.0,
            zup(foot_centre - ankle),
            zup_quat(Quat::from_rotation_arc(Vec3::Z, along)),
            m * share::FOOT
        );
        let _ = writeln!(x, "          </body>");
        let _ = writeln!(x, "        </body>");
        let _ = writeln!(x, "      </body>");
    }
}

fn geom(shape: Shape, axis: Vec3, mass: f32, contype: u32, conaff: u32) -> String {
    let common = format!("contype=\"{contype}\" conaffinity=\"{conaff}\"");
    let mass = if mass > 0.0 {
        format!(" mass=\"{mass:.5}\"")
    } else {
        String::new()
    };
    match shape {
        Shape::Ball { radius } => {
            format!("<geom type=\"sphere\" size=\"{radius:.5}\"{mass} {common}/>")
        }
        Shape::Capsule {
            half_height,
            radius,
        } => {
            let a = axis.normalize() * half_height;
            format!(
                "<geom type=\"capsule\" size=\"{radius:.5}\" fromto=\"{} {}\"{mass} {common}/>",
                zup(-a),
                zup(a)
            )
        }
        Shape::Cuboid { half } => format!(
            "<geom type=\"box\" size=\"{:.5} {:.5} {:.5}\"{mass} {common}/>",
            half.x, half.z, half.y
        ),
    }
}

/// The MJCF text for `plan` at step `dt`: the VH as a tree of bodies with
/// ball and hinge joints (the welded glove as a geom of its forearm), the
/// opponent's head, gloves and trunk as mocap bodies, VH parts not colliding with
/// each other (contype/conaffinity bits as in our collision groups). With
/// `legs` (a physical body), the pelvis is a free root on a canvas plane,
/// the trunk on it by a ball joint at the waist, the legs under it.
pub fn mjcf(plan: &BodyPlan, dt: f64, legs: Option<&BodyParams>) -> String {
    let mut plan = plan.clone();
    if legs.is_some() {
        // The trunk above the pelvis, as World::with_body makes it.
        plan.segments[0].mass = share::TRUNK * anthro::MASS as f32;
    }
    let plan = &plan;
    let mut x = String::new();
    let _ = writeln!(x, "<mujoco model=\"shisen\">");
    let _ = writeln!(
        x,
        "  <option timestep=\"{dt}\" gravity=\"0 0 -9.81\" integrator=\"implicitfast\"/>"
    );
    let _ = writeln!(x, "  <worldbody>");
    // Children of each segment (welds fold into their parent).
    let n = plan.segments.len();
    let mut children = vec![Vec::new(); n];
    for (i, s) in plan.segments.iter().enumerate() {
        if let Some(p) = s.parent {
            children[p.index()].push(i);
        }
    }
    fn emit(
        plan: &BodyPlan,
        children: &[Vec<usize>],
        i: usize,
        origin: Vec3,
        depth: usize,
        x: &mut String,
    ) {
        let s = &plan.segments[i];
        let pad = "  ".repeat(depth);
        let pos = s.pivot - origin;
        let _ = writeln!(x, "{pad}<body name=\"{}\" pos=\"{}\">", s.name, zup(pos));
        match s.joint {
            JointKind::Ball => {
                let _ = writeln!(
                    x,
                    "{pad}  <joint name=\"{}_j\" type=\"ball\" damping=\"0\"/>",
                    s.name
                );
            }
            JointKind::Hinge { axis } => {
                let _ = writeln!(
                    x,
                    "{pad}  <joint name=\"{}_j\" type=\"hinge\" axis=\"{}\"/>",
                    s.name,
                    zup(axis)
                );
            }
            JointKind::Root if depth > 2 => {
                // The trunk on a physical pelvis: the waist.
                let _ = writeln!(x, "{pad}  <joint name=\"vh_waist\" type=\"ball\"/>");
            }
            JointKind::Root | JointKind::Weld => {}
        }
        // The segment's geom, placed at its centre relative to the pivot.
        let g = geom(s.shape, s.axis_to, s.mass, 1, 2);
        let _ = writeln!(
            x,
            "{pad}  <frame pos=\"{}\">{g}</frame>",
            zup(s.centre - s.pivot)
        );
        for &c in &children[i] {
            if plan.segments[c].joint == JointKind::Weld {
                let w = &plan.segments[c];
                let g = geom(w.shape, w.axis_to, w.mass, 1, 2);
                let _ = writeln!(
                    x,
                    "{pad}  <frame pos=\"{}\">{g}</frame>",
                    zup(w.centre - s.pivot)
                );
            } else {
                emit(plan, children, c, s.pivot, depth + 1, x);
            }
        }
        let _ = writeln!(x, "{pad}</body>");
    }
    match legs {
        Some(p) => {
            let waist = WAIST_REST.as_vec3();
            let _ = writeln!(
                x,
                "    <geom name=\"canvas\" type=\"plane\" size=\"5 5 0.1\" friction=\"{SOLE_FRICTION} 0.005 0.0001\" contype=\"2\" conaffinity=\"1\"/>"
            );
            let _ = writeln!(x, "    <body name=\"vh_pelvis\" pos=\"{}\">", zup(waist));
            let _ = writeln!(x, "      <freejoint name=\"vh_root\"/>");
            lower_body(p, &mut x);
            emit(plan, &children, 0, waist, 3, &mut x);
            let _ = writeln!(x, "    </body>");
        }
        None => emit(plan, &children, 0, Vec3::ZERO, 2, &mut x),
    }
    let opp = [
        ("head", plan.opponent_head, plan.opponent_head_radius),
        ("left_glove", plan.opponent_gloves[0], plan.glove_radius),
        ("right_glove", plan.opponent_gloves[1], plan.glove_radius),
    ];
    for (name, p, r) in opp {
        let g = geom(Shape::Ball { radius: r }, Vec3::Y, 0.0, 2, 1);
        let _ = writeln!(
            x,
            "    <body name=\"{name}\" mocap=\"true\" pos=\"{}\">{g}</body>",
            zup(p)
        );
    }
    let trunk = Shape::Capsule {
        half_height: TRUNK_HALF_HEIGHT,
        radius: TRUNK_RADIUS,
    };
    let _ = writeln!(
        x,
        "    <body name=\"torso\" mocap=\"true\" pos=\"{}\">{}</body>",
        zup(trunk_under(plan.opponent_head)),
        geom(trunk, Vec3::Y, 0.0, 2, 1)
    );
    let _ = writeln!(x, "  </worldbody>");
    let _ = writeln!(x, "</mujoco>");
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mjcf_has_every_segment_and_joint() {
        let plan = BodyPlan::default();
        let x = mjcf(&plan, 0.001, None);
        for s in &plan.segments {
            if s.joint != JointKind::Weld {
                assert!(
                    x.contains(&format!("<body name=\"{}\"", s.name)),
                    "{}",
                    s.name
                );
            }
        }
        assert_eq!(
            x.matches("type=\"ball\"").count(),
            5,
            "neck, eyes, shoulders"
        );
        assert_eq!(x.matches("type=\"hinge\"").count(), 2, "elbows");
        assert_eq!(
            x.matches("mocap=\"true\"").count(),
            4,
            "head, gloves, trunk"
        );
        assert_eq!(x.matches("<body").count(), x.matches("</body>").count());
        assert!(!x.contains("freejoint"), "the driven body is rooted");
    }

    /// The physical body: a free pelvis, the waist, two legs of hip, knee
    /// and ankle, seven more bodies, the canvas, and the lower body's
    /// masses as rapier has them.
    #[test]
    fn the_physical_body_is_exported_whole() {
        let plan = BodyPlan::default();
        let p = BodyParams {
            pelvis: crate::physics::lower::Pelvis::Balanced,
            ..BodyParams::default()
        };
        let x = mjcf(&plan, 0.001, Some(&p));
        assert_eq!(x.matches("<freejoint").count(), 1);
        assert_eq!(
            x.matches("type=\"ball\"").count(),
            5 + 1 + 4,
            "+ waist, hips, ankles"
        );
        assert_eq!(x.matches("type=\"hinge\"").count(), 2 + 2, "+ knees");
        assert_eq!(x.matches("type=\"plane\"").count(), 1);
        assert_eq!(x.matches("<body").count(), x.matches("</body>").count());
        let masses: f32 = x
            .split("mass=\"")
            .skip(1)
            .map(|m| m.split('"').next().unwrap().parse::<f32>().unwrap())
            .sum();
        let world = crate::physics::world::World::with_body(plan.clone(), 0.001, Some(&p));
        let rapier: f32 = world
            .phys
            .bodies
            .iter()
            .filter(|(_, b)| b.is_dynamic())
            .map(|(_, b)| b.mass())
            .sum();
        // The opponent's mocap parts carry no mass in MJCF; rapier's are
        // dynamic bodies of their own.
        let opponent: f32 = crate::physics::body::OpponentPart::EVERY
            .iter()
            .map(|&p| world.rb(world.part(p)).mass())
            .sum();
        assert!(
            (masses - (rapier - opponent)).abs() < 0.05,
            "MJCF {masses} kg, rapier {} kg",
            rapier - opponent
        );
    }
}
