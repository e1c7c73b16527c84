//! The trace: CSV, one row per control tick (or every Nth), angles in
//! degrees. Header and row come from one column table so they cannot drift
//! apart; the README documents each column.

use std::fmt::Write as _;
use std::io::{self, Write};

use crate::sim::Sample;
use crate::sim::blows::BlowKind;

type Cell = fn(&Sample, &mut String);

fn deg(x: f64) -> f64 {
    x.to_degrees()
}

fn num(out: &mut String, x: f64) {
    // Fixed precision keeps traces byte-comparable and diff-friendly.
    let _ = write!(out, "{x:.4}");
}

/// (name, writer) for every column, in order.
const COLUMNS: &[(&str, Cell)] = &[
    ("t", |s, o| {
        let _ = write!(o, "{:.3}", s.t);
    }),
    ("action", |s, o| {
        o.push_str(&format!("{:?}", s.action).to_lowercase())
    }),
    ("action_target", |s, o| {
        o.push_str(s.action_target.as_deref().unwrap_or(""))
    }),
    ("gaze_target", |s, o| o.push_str(&s.gaze_target)),
    ("gaze_x", |s, o| num(o, s.gaze_point.x)),
    ("gaze_y", |s, o| num(o, s.gaze_point.y)),
    ("gaze_z", |s, o| num(o, s.gaze_point.z)),
    ("source", |s, o| o.push_str(s.source.as_str())),
    ("amount", |s, o| num(o, s.amount)),
    ("eye_l_yaw_tgt", |s, o| num(o, deg(s.eye_target[0].x))),
    ("eye_l_pitch_tgt", |s, o| num(o, deg(s.eye_target[0].y))),
    ("eye_l_yaw", |s, o| num(o, deg(s.eye_actual[0].x))),
    ("eye_l_pitch", |s, o| num(o, deg(s.eye_actual[0].y))),
    ("eye_r_yaw_tgt", |s, o| num(o, deg(s.eye_target[1].x))),
    ("eye_r_pitch_tgt", |s, o| num(o, deg(s.eye_target[1].y))),
    ("eye_r_yaw", |s, o| num(o, deg(s.eye_actual[1].x))),
    ("eye_r_pitch", |s, o| num(o, deg(s.eye_actual[1].y))),
    ("los_err_l", |s, o| num(o, deg(s.los_error[0]))),
    ("los_err_r", |s, o| num(o, deg(s.los_error[1]))),
    ("neck_yaw_tgt", |s, o| num(o, deg(s.neck_target.yaw))),
    ("neck_pitch_tgt", |s, o| num(o, deg(s.neck_target.pitch))),
    ("neck_roll_tgt", |s, o| num(o, deg(s.neck_target.roll))),
    ("neck_yaw", |s, o| num(o, deg(s.neck_actual.yaw))),
    ("neck_pitch", |s, o| num(o, deg(s.neck_actual.pitch))),
    ("neck_roll", |s, o| num(o, deg(s.neck_actual.roll))),
    ("head_yaw", |s, o| num(o, deg(s.head_world.x))),
    ("head_pitch", |s, o| num(o, deg(s.head_world.y))),
    ("punching", |s, o| {
        o.push_str(if s.punching { "1" } else { "0" })
    }),
    ("head_hit", |s, o| {
        o.push_str(if s.head_hit { "1" } else { "0" })
    }),
    ("blows", |s, o| {
        for (i, b) in s.blows.iter().enumerate() {
            let kind = match b.kind {
                BlowKind::Hit => "hit",
                BlowKind::Block => "block",
            };
            let sep = if i > 0 { ";" } else { "" };
            let _ = write!(o, "{sep}{kind}:{}:{}:{:.2}", b.by.name(), b.part, b.impulse);
        }
    }),
    ("emotion", |s, o| {
        let _ = write!(o, "{:?}", s.emotion);
    }),
    ("blink", |s, o| num(o, s.blink)),
    ("reset", |s, o| o.push_str(if s.reset { "1" } else { "0" })),
    ("salient_1", |s, o| top(o, s, 0)),
    ("salient_2", |s, o| top(o, s, 1)),
    ("salient_3", |s, o| top(o, s, 2)),
];

fn top(o: &mut String, s: &Sample, i: usize) {
    if let Some((name, score)) = s.top_saliency.get(i) {
        let _ = write!(o, "{name}:{score:.3}");
    }
}

/// The CSV header line (no newline).
pub fn header() -> String {
    COLUMNS.iter().map(|c| c.0).collect::<Vec<_>>().join(",")
}

/// Names of the columns, in order.
pub fn column_names() -> Vec<&'static str> {
    COLUMNS.iter().map(|c| c.0).collect()
}

/// One CSV row (no newline).
pub fn row(s: &Sample) -> String {
    let mut out = String::with_capacity(256);
    for (i, (_, cell)) in COLUMNS.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        cell(s, &mut out);
    }
    out
}

/// Writes every `every`-th sample to a CSV sink.
pub struct TraceWriter<W: Write> {
    out: W,
    every: u64,
    n: u64,
}

impl<W: Write> TraceWriter<W> {
    /// Start a trace (writes the header).
    pub fn new(mut out: W, every: u64) -> io::Result<Self> {
        writeln!(out, "{}", header())?;
        Ok(TraceWriter {
            out,
            every: every.max(1),
            n: 0,
        })
    }

    /// Offer one sample.
    pub fn push(&mut self, s: &Sample) -> io::Result<()> {
        if self.n.is_multiple_of(self.every) {
            writeln!(self.out, "{}", row(s))?;
        }
        self.n += 1;
        Ok(())
    }

    /// Flush and return the sink.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}
