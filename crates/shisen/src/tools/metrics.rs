//! Response metrics, one code path for the CLI, the tests and the tuning
//! panel: step metrics (rise, overshoot, settling, steady-state error),
//! tracking error against a reference, and instability detection.

/// Metrics of a step response from `y0` toward `target`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepMetrics {
    /// 10 %-90 % rise time, s (NaN if never reached).
    pub rise_time: f64,
    /// Peak overshoot as a fraction of the step (0 if none).
    pub overshoot: f64,
    /// Time after which the response stays within 2 % of the step of the
    /// target, s (NaN if it never settles).
    pub settling_time: f64,
    /// |target - final value| at the end of the record.
    pub steady_state_error: f64,
}

/// Step metrics of samples `y` at times `t` (same length), for a step that
/// starts at `t[0]` from `y[0]` toward `target`.
pub fn step_metrics(t: &[f64], y: &[f64], target: f64) -> StepMetrics {
    assert_eq!(t.len(), y.len(), "one time per sample");
    let (t0, y0) = (t[0], y[0]);
    let step = target - y0;
    let frac = |v: f64| if step == 0.0 { 1.0 } else { (v - y0) / step };
    let cross = |level: f64| {
        t.iter()
            .zip(y)
            .find(|(_, v)| frac(**v) >= level)
            .map_or(f64::NAN, |(ti, _)| *ti)
    };
    let rise_time = cross(0.9) - cross(0.1);
    let peak = y.iter().map(|v| frac(*v)).fold(f64::NEG_INFINITY, f64::max);
    let overshoot = (peak - 1.0).max(0.0);
    let band = 0.02 * step.abs().max(1e-12);
    let last_out = y.iter().rposition(|v| (v - target).abs() > band);
    let settling_time = match last_out {
        None => 0.0,
        Some(i) if i + 1 < t.len() => t[i + 1] - t0,
        Some(_) => f64::NAN,
    };
    StepMetrics {
        rise_time,
        overshoot,
        settling_time,
        steady_state_error: (target - y[y.len() - 1]).abs(),
    }
}

/// RMS and peak absolute difference between two equally sampled signals.
pub fn tracking_error(reference: &[f64], actual: &[f64]) -> (f64, f64) {
    assert_eq!(reference.len(), actual.len(), "equal lengths");
    if reference.is_empty() {
        return (0.0, 0.0);
    }
    let mut sq = 0.0;
    let mut peak: f64 = 0.0;
    for (r, a) in reference.iter().zip(actual) {
        let e = (r - a).abs();
        sq += e * e;
        peak = peak.max(e);
    }
    ((sq / reference.len() as f64).sqrt(), peak)
}

/// Why a response is judged unstable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Instability {
    /// A sample was NaN or infinite.
    NonFinite,
    /// The error grew beyond `limit` times the step.
    Divergence,
    /// The error keeps oscillating in the last part of the record without
    /// decaying (limit cycle).
    LimitCycle,
}

/// Detect instability of a response toward `target` (step of size `step`).
pub fn instability(y: &[f64], target: f64, step: f64) -> Option<Instability> {
    if y.iter().any(|v| !v.is_finite()) {
        return Some(Instability::NonFinite);
    }
    let scale = step.abs().max(1e-9);
    if y.iter().any(|v| (v - target).abs() > 10.0 * scale) {
        return Some(Instability::Divergence);
    }
    // Limit cycle: in the last quarter, the error changes sign often and
    // its amplitude does not shrink between the two halves of that quarter.
    let tail = &y[y.len() * 3 / 4..];
    if tail.len() >= 8 {
        let e: Vec<f64> = tail.iter().map(|v| v - target).collect();
        let crossings = e.windows(2).filter(|w| w[0] * w[1] < 0.0).count();
        let half = e.len() / 2;
        let amp = |s: &[f64]| s.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let (a1, a2) = (amp(&e[..half]), amp(&e[half..]));
        if crossings >= 4 && a2 > 0.02 * scale && a2 >= 0.8 * a1 {
            return Some(Instability::LimitCycle);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn response(z: f64, w: f64) -> (Vec<f64>, Vec<f64>) {
        // Simple closed form: 1 - e^{-zwt} (cos wd t + z/sqrt(1-z^2) sin wd t)
        let wd = w * (1.0 - z * z).sqrt();
        let t: Vec<f64> = (0..20_000).map(|i| i as f64 * 1e-4).collect();
        let y = t
            .iter()
            .map(|&t| {
                1.0 - (-z * w * t).exp()
                    * ((wd * t).cos() + z / (1.0 - z * z).sqrt() * (wd * t).sin())
            })
            .collect();
        (t, y)
    }

    #[test]
    fn overshoot_matches_the_analytic_second_order_system() {
        for &z in &[0.2, 0.4, 0.6, 0.8] {
            let (t, y) = response(z, 20.0);
            let m = step_metrics(&t, &y, 1.0);
            let expect = (-z * std::f64::consts::PI / (1.0 - z * z).sqrt()).exp();
            assert!(
                (m.overshoot - expect).abs() < 1e-3,
                "zeta {z}: {} vs {expect}",
                m.overshoot
            );
        }
    }

    #[test]
    fn settling_and_rise_time_match_known_values() {
        // zeta = 0.5, w = 20: 10-90 % rise 0.08188 s and 2 % settling
        // 0.40381 s (the exact response solved at 1e-5 s resolution).
        let (t, y) = response(0.5, 20.0);
        let m = step_metrics(&t, &y, 1.0);
        assert!(
            (m.settling_time - 0.40381).abs() < 2e-4,
            "{}",
            m.settling_time
        );
        assert!((m.rise_time - 0.08188).abs() < 2e-4, "{}", m.rise_time);
        assert!(m.steady_state_error < 1e-3);
        // critically damped: no overshoot
        let t2: Vec<f64> = (0..20_000).map(|i| i as f64 * 1e-4).collect();
        let y2: Vec<f64> = t2
            .iter()
            .map(|&t| 1.0 - (1.0 + 20.0 * t) * (-20.0 * t).exp())
            .collect();
        let m2 = step_metrics(&t2, &y2, 1.0);
        assert_eq!(m2.overshoot, 0.0);
        // 2 % settling of the critically damped system: (1 + wt) e^{-wt} = 0.02 -> wt = 5.834
        assert!(
            (m2.settling_time - 5.834 / 20.0).abs() < 2e-3,
            "{}",
            m2.settling_time
        );
    }

    #[test]
    fn instability_is_detected_not_crashed_on() {
        assert_eq!(
            instability(&[0.0, f64::NAN], 1.0, 1.0),
            Some(Instability::NonFinite)
        );
        let growing: Vec<f64> = (0..100)
            .map(|i| (i as f64 * 0.5).sin() * 1.1f64.powi(i))
            .collect();
        assert_eq!(
            instability(&growing, 0.0, 1.0),
            Some(Instability::Divergence)
        );
        let cycling: Vec<f64> = (0..400)
            .map(|i| 1.0 + 0.3 * (i as f64 * 0.3).sin())
            .collect();
        assert_eq!(
            instability(&cycling, 1.0, 1.0),
            Some(Instability::LimitCycle)
        );
        let (_, y) = response(0.5, 20.0);
        assert_eq!(instability(&y, 1.0, 1.0), None);
    }
}
