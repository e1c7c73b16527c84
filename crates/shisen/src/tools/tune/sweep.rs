//! Parallel gain sweeps (rayon, with a progress bar) and their plot.

use std::path::Path;

use rayon::prelude::*;

use super::auto::*;
use crate::physics::body::Group;
use crate::physics::control::{Gains, JointGains};
use crate::tools::plot::{Panel, Series, Stroke, chart};
use crate::tools::table::ResultsFile;

/// One run of a sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepPoint {
    /// Run number (stable across resumes).
    pub id: usize,
    /// Proportional gain.
    pub kp: f64,
    /// Derivative gain.
    pub kd: f64,
    /// Step size, s.
    pub dt: f64,
}

/// The points of a sweep around the physically based guess: a grid
/// (`grid = true`: kp x kd x dt, the largest square kp x kd grid with at
/// most `runs` points over the three steps, so at least 12) or `runs`
/// seeded random samples.
/// kp and kd range over a factor 5 either side of the guess (log scale);
/// dt over 0.5, 1 and 2 ms.
pub fn sweep_points(
    group: Group,
    runs: usize,
    grid: bool,
    seed: u64,
) -> Result<Vec<SweepPoint>, String> {
    use rand::{RngExt, SeedableRng};
    if runs == 0 {
        return Err("--runs: must be at least 1".into());
    }
    if grid && runs < 12 {
        return Err(format!(
            "--runs: a grid needs at least 12 runs (2 kp x 2 kd x 3 steps), got {runs}"
        ));
    }
    let g = initial_guess(group);
    let dts = [0.0005, 0.001, 0.002];
    let span = 5f64.ln();
    if grid {
        let per = ((runs as f64 / dts.len() as f64).sqrt().floor() as usize).max(2);
        let lin = |i: usize| -span + 2.0 * span * i as f64 / (per - 1) as f64;
        let mut v = Vec::new();
        for &dt in &dts {
            for i in 0..per {
                for j in 0..per {
                    v.push(SweepPoint {
                        id: v.len(),
                        kp: g.kp * lin(i).exp(),
                        kd: g.kd * lin(j).exp(),
                        dt,
                    });
                }
            }
        }
        Ok(v)
    } else {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        Ok((0..runs)
            .map(|id| SweepPoint {
                id,
                kp: g.kp * rng.random_range(-span..span).exp(),
                kd: g.kd * rng.random_range(-span..span).exp(),
                dt: dts[rng.random_range(0..dts.len())],
            })
            .collect())
    }
}

/// The columns of a sweep's results file ([`crate::tools::table`]), in
/// order: their one home. The header, each row ([`SweepRow::cells`]) and
/// reading a row back on resume ([`SweepRow::parse`]) all follow it.
pub const SWEEP_COLUMNS: [&str; 9] = [
    "id",
    "kp",
    "kd",
    "dt",
    "cost",
    "meets",
    "traj_rms_deg",
    "step_overshoot",
    "step_settling_s",
];

/// The header line of a sweep's results file.
pub fn sweep_header() -> String {
    SWEEP_COLUMNS.join(",")
}

/// One run of a sweep, as its results file holds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepRow {
    /// The run.
    pub point: SweepPoint,
    /// Its score's cost.
    pub cost: f64,
    /// Whether it meets the group's objective.
    pub meets: bool,
    /// Trajectory RMS error, deg.
    pub traj_rms_deg: f64,
    /// Step response overshoot (fraction).
    pub step_overshoot: f64,
    /// Step response settling time, s.
    pub step_settling_s: f64,
}

impl SweepRow {
    /// The row's cells after the id, in [`SWEEP_COLUMNS`] order.
    pub fn cells(&self) -> String {
        let p = &self.point;
        format!(
            "{:.6e},{:.6e},{},{:.5},{},{:.5},{:.5},{:.5}",
            p.kp,
            p.kd,
            p.dt,
            self.cost,
            u8::from(self.meets),
            self.traj_rms_deg,
            self.step_overshoot,
            self.step_settling_s
        )
    }

    /// Read a whole row (id first) back.
    pub fn parse(row: &str) -> anyhow::Result<SweepRow> {
        let f: Vec<&str> = row.split(',').collect();
        anyhow::ensure!(
            f.len() == SWEEP_COLUMNS.len(),
            "a sweep row has {} cells ({}): `{row}`",
            SWEEP_COLUMNS.len(),
            sweep_header()
        );
        let num = |i: usize| -> anyhow::Result<f64> {
            f[i].parse()
                .map_err(|e| anyhow::anyhow!("{}: `{}`: {e}", SWEEP_COLUMNS[i], f[i]))
        };
        Ok(SweepRow {
            point: SweepPoint {
                id: f[0].parse()?,
                kp: num(1)?,
                kd: num(2)?,
                dt: num(3)?,
            },
            cost: num(4)?,
            meets: f[5] == "1",
            traj_rms_deg: num(6)?,
            step_overshoot: num(7)?,
            step_settling_s: num(8)?,
        })
    }
}

/// Run the sweep points not yet in `results` in parallel on all cores,
/// appending one row per run as it finishes, with a progress bar. Returns
/// every row (resumed and new) as (point, score cost, meets), by id.
pub fn sweep(
    group: Group,
    points: &[SweepPoint],
    base: &Gains,
    results: &ResultsFile,
) -> anyhow::Result<Vec<(SweepPoint, f64, bool)>> {
    let mut done = Vec::new();
    for row in results.resumed().values() {
        let r = SweepRow::parse(row)?;
        done.push((r.point, r.cost, r.meets));
    }
    let todo: Vec<SweepPoint> = points
        .iter()
        .copied()
        .filter(|p| !results.has(p.id))
        .collect();
    let bar = crate::tools::parallel::bar(todo.len() as u64, "runs");
    let rows: Vec<anyhow::Result<(SweepPoint, f64, bool)>> = todo
        .par_iter()
        .map(|p| {
            let mut g = base.clone();
            *g.group_mut(group) = JointGains {
                kp: p.kp,
                kd: p.kd,
                feedforward: base.group(group).feedforward,
            };
            let s = score(group, &g, p.dt);
            let row = SweepRow {
                point: *p,
                cost: s.cost,
                meets: s.meets,
                traj_rms_deg: s.trajectory.rms_deg,
                step_overshoot: s.step.overshoot,
                step_settling_s: s.step.settling_time,
            };
            results.push(p.id, &row.cells())?;
            bar.inc(1);
            Ok((*p, s.cost, s.meets))
        })
        .collect();
    bar.finish();
    let mut all = done;
    for r in rows {
        all.push(r?);
    }
    all.sort_by_key(|r| r.0.id);
    Ok(all)
}

/// Plot a sweep: cost against kp (one dot series per dt), log-kp axis.
pub fn plot_sweep(
    path: &Path,
    group: Group,
    rows: &[(SweepPoint, f64, bool)],
) -> anyhow::Result<()> {
    let mut dts: Vec<f64> = rows.iter().map(|r| r.0.dt).collect();
    dts.sort_by(f64::total_cmp);
    dts.dedup();
    let series = dts
        .iter()
        .map(|&dt| Series {
            label: format!("dt {} ms", dt * 1e3),
            points: rows
                .iter()
                .filter(|r| r.0.dt == dt && r.1.is_finite())
                .map(|r| (r.0.kp.log10(), r.1.min(20.0)))
                .collect(),
            style: Stroke::Dots,
        })
        .collect();
    chart(
        path,
        (1200, 600),
        "log10 kp",
        &[Panel {
            title: format!("{group:?} gain sweep: cost (unstable runs omitted)"),
            y_label: "cost".into(),
            series,
        }],
        &[],
    )
}
