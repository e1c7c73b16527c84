//! PD gain tuning: step and trajectory experiments on one joint group in
//! the physics (no brain), their metrics (one code path: [`crate::tools::metrics`]),
//! a physically based starting guess, automatic improvement against a
//! stated objective, and parallel sweeps.

mod auto;
mod experiment;
mod sweep;

pub use auto::*;
pub use experiment::*;
pub use sweep::*;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::body::Group;
    use crate::physics::control::Gains;

    #[test]
    fn default_gains_meet_the_eye_objective() {
        let s = score(Group::Eye, &Gains::default(), 0.001);
        assert!(s.meets, "{}\n{}", s.trajectory.line(), s.step.line());
    }

    #[test]
    fn effective_inertia_of_the_eye_is_a_solid_sphere() {
        let i = crate::physics::plausible::group_inertia(Group::Eye);
        let expect = shisen_gaze::anatomy::eye::INERTIA;
        assert!((i - expect).abs() / expect < 1e-3, "{i}");
    }
}
