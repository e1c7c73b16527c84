//! The trace: CSV, one row per control tick (or every Nth), angles in
//! degrees. Header and row come from one column table so they cannot drift
//! apart; docs/headless.md documents each column. Rows are written by the `csv`
//! crate, so a cell holding a comma or a quote (a body named `a,b`) is
//! quoted and the file stays readable; ordinary cells are written as they
//! are.

use std::fmt::Write as _;
use std::io::{self, Write};

use crate::sim::Sample;
use crate::sim::blows::BlowKind;
use crate::sim::bout::Phase;

/// How a column's cell is read from a sample.
#[derive(Clone, Copy)]
pub enum Cell {
    /// A number, written with this many decimals.
    Num(fn(&Sample) -> f64, usize),
    /// Text.
    Text(fn(&Sample, &mut String)),
}

impl Cell {
    /// Write the cell of sample `s`.
    pub fn write(&self, s: &Sample, out: &mut String) {
        match self {
            // Fixed precision keeps traces byte-comparable and diff-friendly.
            Cell::Num(get, decimals) => {
                let _ = write!(out, "{:.*}", decimals, get(s));
            }
            Cell::Text(put) => put(s, out),
        }
    }
}

fn deg(x: f64) -> f64 {
    x.to_degrees()
}

fn flag(b: bool) -> f64 {
    if b { 1.0 } else { 0.0 }
}

/// A number with the traces' usual precision.
const fn num(get: fn(&Sample) -> f64) -> Cell {
    Cell::Num(get, 4)
}

/// A 0/1 flag.
const fn yes(get: fn(&Sample) -> f64) -> Cell {
    Cell::Num(get, 0)
}

/// (name, cell) for every column, in order: the one home of the trace's
/// columns (the CSV and the Python bindings' arrays both read it).
pub const COLUMNS: &[(&str, Cell)] = &[
    ("t", Cell::Num(|s| s.t, 3)),
    (
        "action",
        Cell::Text(|s, o| o.push_str(&format!("{:?}", s.action).to_lowercase())),
    ),
    (
        "action_target",
        Cell::Text(|s, o| o.push_str(s.action_target.as_deref().unwrap_or(""))),
    ),
    ("gaze_target", Cell::Text(|s, o| o.push_str(&s.gaze_target))),
    ("gaze_x", num(|s| s.gaze_point.x)),
    ("gaze_y", num(|s| s.gaze_point.y)),
    ("gaze_z", num(|s| s.gaze_point.z)),
    ("source", Cell::Text(|s, o| o.push_str(s.source.as_str()))),
    ("amount", num(|s| s.amount)),
    ("eye_l_yaw_tgt", num(|s| deg(s.eye_target[0].x))),
    ("eye_l_pitch_tgt", num(|s| deg(s.eye_target[0].y))),
    ("eye_l_yaw", num(|s| deg(s.eye_actual[0].x))),
    ("eye_l_pitch", num(|s| deg(s.eye_actual[0].y))),
    ("eye_r_yaw_tgt", num(|s| deg(s.eye_target[1].x))),
    ("eye_r_pitch_tgt", num(|s| deg(s.eye_target[1].y))),
    ("eye_r_yaw", num(|s| deg(s.eye_actual[1].x))),
    ("eye_r_pitch", num(|s| deg(s.eye_actual[1].y))),
    ("los_err_l", num(|s| deg(s.los_error[0]))),
    ("los_err_r", num(|s| deg(s.los_error[1]))),
    ("torsion", num(|s| deg(s.torsion))),
    ("neck_yaw_tgt", num(|s| deg(s.neck_target.yaw))),
    ("neck_pitch_tgt", num(|s| deg(s.neck_target.pitch))),
    ("neck_roll_tgt", num(|s| deg(s.neck_target.roll))),
    ("neck_yaw", num(|s| deg(s.neck_actual.yaw))),
    ("neck_pitch", num(|s| deg(s.neck_actual.pitch))),
    ("neck_roll", num(|s| deg(s.neck_actual.roll))),
    ("head_yaw", num(|s| deg(s.head_world.x))),
    ("head_pitch", num(|s| deg(s.head_world.y))),
    ("head_speed", num(|s| deg(s.head_speed))),
    ("head_x", num(|s| s.head.x)),
    ("head_y", num(|s| s.head.y)),
    ("head_z", num(|s| s.head.z)),
    ("pelvis_x", num(|s| s.pelvis.x)),
    ("pelvis_z", num(|s| s.pelvis.z)),
    ("range", num(|s| s.range)),
    (
        "zone",
        Cell::Text(|s, o| o.push_str(shisen_gaze::behaviour::Ranges::HUMAN.zone(s.range).name())),
    ),
    ("heading", num(|s| deg(s.heading))),
    ("waist_yaw", num(|s| deg(s.waist.yaw))),
    ("waist_pitch", num(|s| deg(s.waist.pitch))),
    ("waist_roll", num(|s| deg(s.waist.roll))),
    ("punching", yes(|s| flag(s.punching))),
    ("head_hit", yes(|s| flag(s.head_hit))),
    (
        "blows",
        Cell::Text(|s, o| {
            for (i, b) in s.blows.iter().enumerate() {
                let kind = match b.kind {
                    BlowKind::Hit => "hit",
                    BlowKind::Block => "block",
                };
                let sep = if i > 0 { ";" } else { "" };
                let _ = write!(o, "{sep}{kind}:{}:{}:{:.2}", b.by.name(), b.part, b.impulse);
            }
        }),
    ),
    (
        "emotion",
        Cell::Text(|s, o| {
            let _ = write!(o, "{:?}", s.emotion);
        }),
    ),
    ("blink", num(|s| s.blink)),
    ("reset", yes(|s| flag(s.reset))),
    (
        "round",
        yes(|s| match s.phase {
            Some(Phase::Round(n) | Phase::Rest(n)) => f64::from(n),
            Some(Phase::Over) | None => 0.0,
        }),
    ),
    (
        "resting",
        yes(|s| flag(matches!(s.phase, Some(Phase::Rest(_))))),
    ),
    ("fatigue", Cell::Num(|s| s.fatigue, 3)),
    ("staggered", yes(|s| flag(s.staggered))),
    (
        "stance",
        Cell::Text(|s, o| {
            let _ = write!(o, "{}", s.stance.name());
        }),
    ),
    ("salient_1", Cell::Text(|s, o| top(o, s, 0))),
    ("salient_2", Cell::Text(|s, o| top(o, s, 1))),
    ("salient_3", Cell::Text(|s, o| top(o, s, 2))),
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
            cell.write(s, &mut out);
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
                cell.write(s, out);
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
