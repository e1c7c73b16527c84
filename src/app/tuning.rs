//! The step-response button of the gains panel: the group's stated step
//! experiment ([`tune::Objective`]) run with the gains in force by
//! [`tune::run`] and judged by [`tune::evaluate`], the same code path as
//! `shisen tune` and the tuning tests.

use shisen::physics::body::Group;
use shisen::physics::control::Gains;
use shisen::sim::DT;
use shisen::tools::tune::{self, Objective, Report, Response};

/// A measured step response.
#[derive(Clone, Debug)]
pub struct StepResponse {
    /// Which group.
    pub group: Group,
    /// Time, reference and measured angle.
    pub response: Response,
    /// Rise, overshoot, settling, and whether it is stable.
    pub report: Report,
    /// The group's objective (its bounds are shown beside the result).
    pub objective: Objective,
}

/// Step one joint of `group` with `gains` and measure the response.
pub fn step_response(gains: &Gains, group: Group) -> StepResponse {
    let objective = Objective::for_group(group);
    let response = tune::run(group, objective.step, gains, DT);
    let report = tune::evaluate(objective.step, &response);
    StepResponse {
        group,
        response,
        report,
        objective,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_neck_gains_step_cleanly() {
        let r = step_response(&Gains::default(), Group::Neck);
        assert!(r.report.unstable.is_none());
        assert!(r.report.rise_time.is_finite(), "{:?}", r.report);
    }
}
