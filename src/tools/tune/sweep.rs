//! Parallel gain sweeps (rayon, with a progress bar) and their plot.

use std::path::Path;

use rayon::prelude::*;

use super::auto::*;
use crate::physics::body::Group;
use crate::physics::control::{Gains, JointGains};
use crate::tools::plot::{Panel, Series, Stroke, chart};

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
/// (`grid = true`: kp x kd x dt) or seeded random samples, `runs` of them.
/// kp and kd range over a factor 5 either side of the guess (log scale);
/// dt over 0.5, 1 and 2 ms.
pub fn sweep_points(group: Group, runs: usize, grid: bool, seed: u64) -> Vec<SweepPoint> {
    use rand::{RngExt, SeedableRng};
    let g = initial_guess(group);
    let dts = [0.0005, 0.001, 0.002];
    let span = 5f64.ln();
    if grid {
        let per = ((runs as f64 / dts.len() as f64).sqrt().ceil() as usize).max(2);
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
        v
    } else {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        (0..runs)
            .map(|id| SweepPoint {
                id,
                kp: g.kp * rng.random_range(-span..span).exp(),
                kd: g.kd * rng.random_range(-span..span).exp(),
                dt: dts[rng.random_range(0..dts.len())],
            })
            .collect()
    }
}

/// Run a sweep in parallel on all cores, appending one CSV row per run to
/// `csv` (resumable: runs already in the file are skipped), with a progress
/// bar. Returns every row (old and new) as (point, score cost, meets).
pub fn sweep(
    group: Group,
    points: &[SweepPoint],
    base: &Gains,
    csv: &Path,
) -> anyhow::Result<Vec<(SweepPoint, f64, bool)>> {
    use std::io::Write;
    let mut done = std::collections::BTreeMap::new();
    if let Ok(text) = std::fs::read_to_string(csv) {
        for line in text.lines().skip(1) {
            let f: Vec<&str> = line.split(',').collect();
            if let [id, kp, kd, dt, cost, meets, ..] = f[..]
                && let (Ok(id), Ok(kp), Ok(kd), Ok(dt), Ok(cost)) = (
                    id.parse(),
                    kp.parse(),
                    kd.parse(),
                    dt.parse(),
                    cost.parse::<f64>(),
                )
            {
                done.insert(id, (SweepPoint { id, kp, kd, dt }, cost, meets == "1"));
            }
        }
    }
    let fresh = !csv.exists();
    let file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(csv)?;
    let file = std::sync::Mutex::new(std::io::BufWriter::new(file));
    if fresh {
        writeln!(
            file.lock().expect("lock"),
            "id,kp,kd,dt,cost,meets,traj_rms_deg,step_overshoot,step_settling_s"
        )?;
    }
    let todo: Vec<SweepPoint> = points
        .iter()
        .copied()
        .filter(|p| !done.contains_key(&p.id))
        .collect();
    let bar = indicatif::ProgressBar::new(todo.len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} runs, {elapsed} elapsed, eta {eta}",
        )
        .expect("template"),
    );
    let rows: Vec<(SweepPoint, f64, bool)> = todo
        .par_iter()
        .map(|p| {
            let mut g = base.clone();
            *g.group_mut(group) = JointGains {
                kp: p.kp,
                kd: p.kd,
                feedforward: base.group(group).feedforward,
            };
            let s = score(group, &g, p.dt);
            let line = format!(
                "{},{:.6e},{:.6e},{},{:.5},{},{:.5},{:.5},{:.5}",
                p.id,
                p.kp,
                p.kd,
                p.dt,
                s.cost,
                u8::from(s.meets),
                s.trajectory.rms_deg,
                s.step.overshoot,
                s.step.settling_time
            );
            let _ = writeln!(file.lock().expect("lock"), "{line}");
            bar.inc(1);
            (*p, s.cost, s.meets)
        })
        .collect();
    bar.finish();
    file.into_inner().expect("lock").flush()?;
    let mut all: Vec<_> = done.into_values().chain(rows).collect();
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
