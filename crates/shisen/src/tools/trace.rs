//! The trace: CSV, one row per control tick (or every Nth), angles in
//! degrees. Header and row come from one column table so they cannot drift
//! apart; the README documents each column. Rows are written by the `csv`
//! crate, so a cell holding a comma or a quote (a body named `a,b`) is
//! quoted and the file stays readable; ordinary cells are written as they
//! are.

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

/// One sample's cells, in column order.
pub fn cells(s: &Sample) -> Vec<String> {
    COLUMNS
        .iter()
        .map(|(_, cell)| {
            let mut out = String::new();
            cell(s, &mut out);
            out
        })
        .collect()
}

/// Writes every `every`-th sample to a CSV sink.
pub struct TraceWriter<W: Write> {
    out: csv::Writer<W>,
    every: u64,
    n: u64,
    cells: Vec<String>,
}

fn csv_error(e: csv::Error) -> io::Error {
    match e.into_kind() {
        csv::ErrorKind::Io(e) => e,
        other => io::Error::other(format!("{other:?}")),
    }
}

impl<W: Write> TraceWriter<W> {
    /// Start a trace (writes the header).
    pub fn new(out: W, every: u64) -> io::Result<Self> {
        let mut out = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .from_writer(out);
        out.write_record(COLUMNS.iter().map(|c| c.0))
            .map_err(csv_error)?;
        Ok(TraceWriter {
            out,
            every: every.max(1),
            n: 0,
            cells: vec![String::new(); COLUMNS.len()],
        })
    }

    /// Offer one sample.
    pub fn push(&mut self, s: &Sample) -> io::Result<()> {
        if self.n.is_multiple_of(self.every) {
            for ((_, cell), out) in COLUMNS.iter().zip(&mut self.cells) {
                out.clear();
                cell(s, out);
            }
            self.out.write_record(&self.cells).map_err(csv_error)?;
        }
        self.n += 1;
        Ok(())
    }

    /// Flush and return the sink.
    pub fn finish(self) -> io::Result<W> {
        self.out.into_inner().map_err(|e| e.into_error())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A name with the separator in it is quoted, and reads back whole.
    #[test]
    fn a_cell_with_a_comma_is_quoted_and_reads_back() {
        let mut s = crate::scene::LoadedScene::default_scene()
            .sim()
            .step()
            .clone();
        s.gaze_target = "a,b \"c\"".into();
        let mut w = TraceWriter::new(Vec::new(), 1).unwrap();
        w.push(&s).unwrap();
        let text = String::from_utf8(w.finish().unwrap()).unwrap();
        assert!(text.contains("\"a,b \"\"c\"\"\""), "{text}");
        let mut r = csv::Reader::from_reader(text.as_bytes());
        let row = r.records().next().unwrap().unwrap();
        let i = column_names()
            .iter()
            .position(|c| *c == "gaze_target")
            .unwrap();
        assert_eq!(&row[i], "a,b \"c\"");
        assert_eq!(row.len(), COLUMNS.len());
    }
}
