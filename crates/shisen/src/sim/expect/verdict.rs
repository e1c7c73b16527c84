//! Judging: each expectation's accumulator turned into a verdict, in
//! words and a number.

use super::Expect;
use super::measure::Acc;
use shisen_gaze::behaviour::EYES_ON_TARGET;

/// The verdict on one expectation.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// What was expected, in words.
    pub what: String,
    /// What was measured, in words.
    pub measured: String,
    /// The measured number (share, degrees, seconds...).
    pub value: f64,
    /// Whether it holds.
    pub pass: bool,
}

fn share(a: &Acc) -> f64 {
    if a.n == 0 {
        0.0
    } else {
        a.hits as f64 / a.n as f64
    }
}

/// The verdict on `e` from what `a` measured over a run of `duration`
/// seconds.
pub(super) fn judge(e: &Expect, a: &Acc, duration: f64) -> Verdict {
    match e {
        Expect::GazeShare {
            target,
            from,
            to,
            at_least,
        } => {
            let v = share(a);
            Verdict {
                what: format!(
                    "gaze on `{target}` >= {:.0}% of [{from}, {to}] s",
                    at_least * 100.0
                ),
                measured: format!("{:.1}%", v * 100.0),
                value: v,
                pass: a.n > 0 && v >= *at_least,
            }
        }
        Expect::GazeShareAtMost {
            target,
            from,
            to,
            at_most,
        } => {
            let v = share(a);
            Verdict {
                what: format!(
                    "gaze on `{target}` <= {:.0}% of [{from}, {to}] s",
                    at_most * 100.0
                ),
                measured: format!("{:.1}%", v * 100.0),
                value: v,
                pass: a.n > 0 && v <= *at_most,
            }
        }
        Expect::GazeReaches { target, from, to } => Verdict {
            what: format!("gaze reaches `{target}` within [{from}, {to}] s"),
            measured: a.first.map_or("never".into(), |t| {
                format!("at {t:.3} s ({:.0} ms after {from})", (t - from) * 1e3)
            }),
            value: a.first.map_or(f64::INFINITY, |t| t - from),
            pass: a.first.is_some(),
        },
        Expect::AngleBelow {
            joint,
            max_deg,
            from,
            to,
        } => Verdict {
            what: format!(
                "|{joint:?}| < {max_deg} deg over [{}, {}] s",
                from.unwrap_or(0.0),
                to.unwrap_or(duration)
            ),
            measured: format!("max {:.2} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max < *max_deg,
        },
        Expect::AngleReaches {
            joint,
            min_deg,
            from,
            to,
        } => Verdict {
            what: format!("|{joint:?}| reaches {min_deg} deg within [{from}, {to}] s"),
            measured: format!("max {:.2} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max >= *min_deg,
        },
        Expect::Telegraph { min_lead } => Verdict {
            what: format!(
                "eyes on the attack target (< {} deg) >= {:.0} ms before every VH punch",
                EYES_ON_TARGET.to_degrees(),
                min_lead * 1e3
            ),
            measured: match a.min {
                Some(m) => format!("{} punches, shortest lead {:.0} ms", a.n, m * 1e3),
                None => "no punch thrown".into(),
            },
            value: a.min.unwrap_or(0.0),
            pass: a.min.is_some_and(|m| m >= *min_lead),
        },
        Expect::LineOfSight { max_deg, from, to } => Verdict {
            what: format!("line-of-sight error < {max_deg} deg over [{from}, {to}] s"),
            measured: format!("max {:.3} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max < *max_deg,
        },
        Expect::ActionShare {
            action,
            from,
            to,
            at_least,
        } => {
            let v = share(a);
            Verdict {
                what: format!(
                    "action {action:?} >= {:.0}% of [{from}, {to}] s",
                    at_least * 100.0
                ),
                measured: format!("{:.1}%", v * 100.0),
                value: v,
                pass: a.n > 0 && v >= *at_least,
            }
        }
        Expect::Blinks { from, to, at_least } => Verdict {
            what: format!("at least {at_least} blinks in [{from}, {to}] s"),
            measured: format!("{} blinks", a.hits),
            value: a.hits as f64,
            pass: a.hits >= u64::from(*at_least),
        },
        Expect::HeadHit { from, to, hit } => Verdict {
            what: format!(
                "the head is {}hit in [{from}, {to}] s",
                if *hit { "" } else { "not " }
            ),
            measured: a
                .first
                .map_or("no hit".into(), |t| format!("hit at {t:.3} s")),
            value: a.first.map_or(0.0, |_| 1.0),
            pass: a.first.is_some() == *hit,
        },
        Expect::Blows {
            kind,
            by,
            from,
            to,
            at_least,
            at_most,
        } => Verdict {
            what: format!(
                "{kind:?} by {by:?}: at least {at_least}{} in [{from}, {to}] s",
                at_most.map_or(String::new(), |m| format!(", at most {m}"))
            ),
            measured: format!("{}", a.hits),
            value: a.hits as f64,
            pass: a.hits >= u64::from(*at_least) && at_most.is_none_or(|m| a.hits <= u64::from(m)),
        },
        Expect::HeadRotation {
            at_least_deg,
            at_most_deg,
            from,
            to,
        } => Verdict {
            what: format!(
                "the head turns >= {at_least_deg}{} deg in [{from}, {to}] s",
                at_most_deg.map_or(String::new(), |m| format!(" and <= {m}"))
            ),
            measured: format!("peak {:.2} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max >= *at_least_deg && at_most_deg.is_none_or(|m| a.max <= m),
        },
        Expect::HeadSpeed {
            at_least,
            at_most,
            from,
            to,
        } => Verdict {
            what: format!(
                "the head's peak speed in [{at_least}, {at_most}] rad/s in [{from}, {to}] s"
            ),
            measured: format!("peak {:.2} rad/s", a.max),
            value: a.max,
            pass: a.n > 0 && a.max >= *at_least && a.max <= *at_most,
        },
        Expect::BlowMomentum {
            by,
            at_least,
            at_most,
            from,
            to,
        } => {
            let lo = a.min.unwrap_or(f64::NAN);
            Verdict {
                what: format!(
                    "hits by {by:?} in [{from}, {to}] s carry [{at_least}, {at_most}] N s"
                ),
                measured: if a.hits == 0 {
                    "no hit".into()
                } else {
                    format!("{} hits, {lo:.2}-{:.2} N s", a.hits, a.max)
                },
                value: a.max,
                pass: a.hits > 0 && lo >= *at_least && a.max <= *at_most,
            }
        }
        Expect::LineOfSightReaches { min_deg, from, to } => Verdict {
            what: format!("line-of-sight error reaches {min_deg} deg in [{from}, {to}] s"),
            measured: format!("max {:.3} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max >= *min_deg,
        },
        Expect::Evades {
            kind,
            from,
            to,
            at_least,
            at_most,
            offset,
        } => {
            // An evasion still under way at the end counts if it worked.
            let open = a
                .evasion
                .map_or(0, |(_, far, touched)| u64::from(far && !touched));
            let ok = a.hits + open;
            Verdict {
                what: format!(
                    "at least {at_least} {} in [{from}, {to}] s take the head {offset} m off its line untouched{}",
                    kind.map_or("evasions".to_string(), |k| format!("{k:?}")),
                    at_most.map_or(String::new(), |m| format!(", at most {m} started"))
                ),
                measured: format!("{ok} of {} evasions", a.n),
                value: ok as f64,
                pass: ok >= u64::from(*at_least) && at_most.is_none_or(|m| a.n <= u64::from(m)),
            }
        }
        Expect::Range {
            at_least,
            at_most,
            from,
            to,
        }
        | Expect::Fatigue {
            at_least,
            at_most,
            from,
            to,
        } => {
            let (what, unit) = match e {
                Expect::Range { .. } => ("the range", " m"),
                _ => ("the VH's fatigue", ""),
            };
            let lo = a.min.unwrap_or(f64::NAN);
            Verdict {
                what: format!("{what} stays in [{at_least}, {at_most}]{unit} in [{from}, {to}] s"),
                measured: format!("{lo:.3}-{:.3}{unit}", a.max),
                value: a.max,
                pass: a.n > 0 && lo >= *at_least && a.max <= *at_most,
            }
        }
        Expect::Knockdowns {
            from,
            to,
            at_least,
            at_most,
            get_ups,
        } => Verdict {
            what: format!(
                "knocked down {at_least}{} times in [{from}, {to}] s, up at least {get_ups} times",
                at_most.map_or("+".to_string(), |m| format!("-{m}"))
            ),
            measured: format!("{} knockdowns, {} get-ups", a.hits, a.n),
            value: a.hits as f64,
            pass: a.hits >= u64::from(*at_least)
                && at_most.is_none_or(|m| a.hits <= u64::from(m))
                && a.n >= u64::from(*get_ups),
        },
        Expect::Finite => Verdict {
            what: "state finite throughout (no NaN)".into(),
            measured: if a.bad {
                "non-finite state".into()
            } else {
                format!("{} ticks finite", a.n)
            },
            value: if a.bad { 1.0 } else { 0.0 },
            pass: !a.bad && a.n > 0,
        },
    }
}
