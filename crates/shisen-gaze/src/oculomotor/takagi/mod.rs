//! Takagi & Takeda's sigmoid head and gaze trajectories (gaze.md section 10,
//! equation T1): a parametric, expressive alternative to the reflexive laws.
//!
//! Per axis (yaw, pitch; roll = 0) a trajectory waits `T1`, moves along a
//! shifted logistic curve for `T2` reaching exactly `a`, and holds for `T3`.
//! The gaze (line of sight) uses the same form with its own parameters and
//! the eye-in-head angle is gaze minus head. Yaw depends only on the
//! horizontal target angle and pitch only on the vertical one (their table 2).
//! The "linear model" (constant angular velocity over the same interval) is
//! the baseline they compared against.
//!
//! In code the angles are radians and times seconds; the fitted tables are
//! kept as printed (degrees) and converted when used.

mod law;
mod presets;
mod tables;

pub use law::{AxisTrack, GazeShift, GazeShiftSample, Linear, Segment, Sigmoid};
pub use presets::Preset;
pub use tables::{Axis, HeadFitRow, TABLE_TEST2, TABLE1_HEAD_FITS, TEST2_B, TEST2_C, Test2Row};

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    fn every_row_sigmoid() -> Vec<Sigmoid> {
        let mut v: Vec<Sigmoid> = TABLE1_HEAD_FITS.iter().map(HeadFitRow::sigmoid).collect();
        for r in TABLE_TEST2 {
            v.extend(r.sigmoids());
        }
        v
    }

    /// (T1) middle piece written out from gaze.md as the oracle.
    fn spec_t1(a: f64, b: f64, c: f64, t1: f64, t2: f64, t: f64) -> f64 {
        let (ep, em) = ((c * t2 / 2.0).exp(), (-c * t2 / 2.0).exp());
        let amp = (a / b) * (1.0 + b * ep) * (1.0 + b * em) / (ep - em);
        let d = (a / b) * (1.0 + b * em) / (ep - em);
        amp / (1.0 + b * (-c * (t - t1 - t2 / 2.0)).exp()) - d
    }

    #[test]
    fn ends_exact_for_every_table_row() {
        let rows = every_row_sigmoid();
        assert_eq!(rows.len(), 8 + 16);
        for s in rows {
            // the middle piece itself evaluated at its ends
            let mid = |t: f64| {
                let tau = t - s.wait - 0.5 * s.moving;
                s.amp() / (1.0 + s.b * (-s.c * tau).exp()) - s.d()
            };
            assert!(mid(s.t1()).abs() < 1e-9, "{s:?}: f(t1) = {}", mid(s.t1()));
            assert!((mid(s.t2()) - s.a).abs() < 1e-9, "{s:?}: f(t2)");
            assert!(s.position(s.t1()).abs() < 1e-9 && (s.position(s.t2()) - s.a).abs() < 1e-9);
            assert!(s.position(s.t1() + 1e-9).abs() < 1e-6);
            assert!((s.position(s.t2() - 1e-9) - s.a).abs() < 1e-6);
            assert_eq!(s.position(s.t3()), s.a);
            // and the implementation equals the printed formula inside
            for i in 1..100 {
                let t = s.t1() + s.moving * i as f64 / 100.0;
                let want = spec_t1(s.a, s.b, s.c, s.wait, s.moving, t);
                assert!((s.position(t) - want).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn symmetric_when_b_is_one() {
        for s in every_row_sigmoid().into_iter().filter(|s| s.b == 1.0) {
            let mid = s.wait + 0.5 * s.moving;
            for i in 0..=50 {
                let u = 0.5 * s.moving * i as f64 / 50.0;
                let sum = s.position(mid + u) + s.position(mid - u);
                assert!((sum - s.a).abs() < 1e-9, "{s:?} u={u}");
            }
        }
    }

    #[test]
    fn monotone_and_velocity_is_derivative() {
        for s in every_row_sigmoid() {
            let sign = s.a.signum();
            let mut last = f64::NEG_INFINITY;
            for i in 0..=1000 {
                let t = s.t3() * i as f64 / 1000.0;
                let p = sign * s.position(t);
                assert!(p >= last - 1e-15, "{s:?} not monotone at {t}");
                last = p;
                assert!(sign * s.velocity(t) >= 0.0);
            }
            let h = 1e-6;
            for i in 1..100 {
                let t = s.t1() + s.moving * i as f64 / 100.0;
                let fd = (s.position(t + h) - s.position(t - h)) / (2.0 * h);
                assert!((fd - s.velocity(t)).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn eye_is_gaze_minus_head() {
        for r in TABLE_TEST2 {
            let g = r.gaze_shift();
            for i in 0..=200 {
                let t = g.end() * i as f64 / 200.0;
                let s = g.sample(t);
                assert_eq!(s.eye, s.gaze - s.head);
                assert_eq!(s.eye_rate, s.gaze_rate - s.head_rate);
            }
            let end = g.sample(g.end());
            let want = DVec2::new(r.target_deg.0, r.target_deg.1);
            assert!((end.gaze - want * std::f64::consts::PI / 180.0).length() < 1e-12);
        }
    }

    #[test]
    fn linear_baseline_endpoints_and_constant_speed() {
        for s in every_row_sigmoid() {
            let l = s.linear();
            assert_eq!(l.position(s.t1()), 0.0);
            assert!((l.position(s.t2()) - s.a).abs() < 1e-15);
            assert_eq!(l.position(s.t3()), s.a);
            let mid = s.t1() + 0.3 * s.moving;
            assert!((l.velocity(mid) - s.a / s.moving).abs() < 1e-15);
            assert!((l.position(mid) - 0.3 * s.a).abs() < 1e-12);
        }
        let g = TABLE_TEST2[1].gaze_shift();
        let lin = g.linear_baseline();
        let (a, b) = (g.sample(g.end()), lin.sample(lin.end()));
        assert!((a.head - b.head).length() < 1e-12 && (a.gaze - b.gaze).length() < 1e-12);
        assert_eq!(lin.sample(0.0).head, DVec2::ZERO);
    }

    #[test]
    fn offset_is_added() {
        let r = TABLE1_HEAD_FITS[0];
        let tr = r.track();
        assert!((tr.position(0.0) - 2.6f64.to_radians()).abs() < 1e-15);
        assert!((tr.position(tr.end()) - (2.6f64 - 17.3).to_radians()).abs() < 1e-12);
    }

    #[test]
    fn presets_reach_their_targets() {
        let target = DVec2::new(30.0, 20.0);
        let rad = target * std::f64::consts::PI / 180.0;
        for p in [
            Preset::Dialogue,
            Preset::UpwardGlance,
            Preset::Surprised,
            Preset::Eerie,
            Preset::WindUp,
            Preset::LookUpFromDesk,
        ] {
            let g = p.build(target);
            let end = g.sample(g.end());
            assert!(
                (end.gaze - rad).length() < 1e-9,
                "{p:?} gaze ends on target"
            );
            assert!(
                end.head.x.abs() <= rad.x.abs() + 1e-12,
                "{p:?} head does not overshoot"
            );
            assert!((end.eye - (end.gaze - end.head)).length() < 1e-15);
        }
        // wind-up turns away first
        let w = Preset::WindUp.build(target);
        assert!(w.sample(0.3).head.x < 0.0 && w.sample(0.3).gaze.x < 0.0);
        // upward glance: the eyes carry most of the elevation
        let u = Preset::UpwardGlance.build(target).sample(2.0);
        assert!(u.eye.y > u.head.y);
        // look up from desk: the eyes first counter-rotate, then lead
        let d = Preset::LookUpFromDesk.build(target);
        assert!(d.sample(0.35).eye.y < 0.0 && d.sample(0.9).eye.y > 0.0);
    }

    #[test]
    fn sigmoid_deserialises() {
        let s: Sigmoid =
            crate::util::ron::parse_ron("(a: 0.5, c: 4.0)", std::path::Path::new("t.ron")).unwrap();
        assert_eq!((s.a, s.b, s.c), (0.5, 1.0, 4.0));
        assert!(
            crate::util::ron::parse_ron::<Sigmoid>("(b: 0.0)", std::path::Path::new("t.ron"))
                .is_err()
        );
        let g: GazeShift = crate::util::ron::parse_ron(
            "(head_yaw: (segments: [Sigmoid((a: 0.3))]))",
            std::path::Path::new("t.ron"),
        )
        .unwrap();
        assert_eq!(g.head_yaw.segments.len(), 1);
    }
}
