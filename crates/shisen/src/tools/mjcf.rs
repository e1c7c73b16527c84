//! Export the sparring bodies as an MJCF model (MuJoCo's XML), generated
//! from the same [`BodyPlan`] the rapier world is built from, so a peer
//! comparison steps the same bodies and joints (`benches/mujoco_compare.py`).
//!
//! Frames: MuJoCo is Z-up; our world is Y-up. A point (x, y, z) of ours
//! becomes (x, -z, y) there, a proper rotation (+90 deg about X).

use std::fmt::Write as _;

use glam::Vec3;

use crate::physics::body::{BodyPlan, JointKind, Shape};

fn zup(v: Vec3) -> String {
    format!("{:.5} {:.5} {:.5}", v.x, -v.z, v.y)
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
/// opponent's head and gloves as mocap bodies, VH parts not colliding with
/// each other (contype/conaffinity bits as in our collision groups).
pub fn mjcf(plan: &BodyPlan, dt: f64) -> String {
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
    emit(plan, &children, 0, Vec3::ZERO, 2, &mut x);
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
        let x = mjcf(&plan, 0.001);
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
        assert_eq!(x.matches("mocap=\"true\"").count(), 3);
        assert_eq!(x.matches("<body").count(), x.matches("</body>").count());
    }
}
