//! `shisen tune`, `shisen sweep`: PD gains.

use std::path::PathBuf;

use anyhow::{Context, Result};
use shisen::tools::output::{Outputs, write_whole};
use shisen::tools::table::{ResultsFile, Shard, settings_line};

use shisen::physics::body::Group;
use shisen::physics::control::Gains;

use crate::cli::*;

pub fn tune_cmd(
    groups: Vec<GroupArg>,
    gains: Option<PathBuf>,
    from_guess: bool,
    auto: bool,
    write_gains: Option<PathBuf>,
    out: &std::path::Path,
    dt: f64,
) -> Result<()> {
    if from_guess && !auto {
        anyhow::bail!("--from-guess starts the automatic tuning; give --auto with it");
    }
    if write_gains.is_some() && !auto {
        anyhow::bail!(
            "--write-gains writes the gains --auto tunes; without --auto it would write them unchanged (give --auto, or copy the gains file)"
        );
    }
    use shisen::tools::tune;
    let mut plan = Outputs::new().folder("--out", out);
    if let Some(p) = &gains {
        plan = plan.input(p);
    }
    if let Some(p) = &write_gains {
        plan = plan.file_as("--write-gains", p, "a gains file (RON)", &["ron"]);
    }
    plan.check()?;
    let mut g = match &gains {
        Some(p) => Gains::load(p)?,
        None => Gains::default(),
    };
    let groups: Vec<Group> = if groups.is_empty() {
        Group::ALL.to_vec()
    } else {
        groups.into_iter().map(Group::from).collect()
    };
    for group in groups {
        if auto {
            let start = if from_guess {
                tune::initial_guess(group)
            } else {
                *g.group(group)
            };
            let history = tune::auto_tune(group, &g, start, dt, 200);
            let (first, last) = (history[0], history[history.len() - 1]);
            println!(
                "{group:?}: auto-tuned in {} improvements: kp {:.4e} -> {:.4e}, kd {:.4e} -> {:.4e}, cost {:.3} -> {:.3}, objective {}",
                history.len() - 1,
                first.gains.kp,
                last.gains.kp,
                first.gains.kd,
                last.gains.kd,
                first.score.cost,
                last.score.cost,
                if last.score.meets { "met" } else { "NOT met" }
            );
            *g.group_mut(group) = last.gains;
        }
        let o = tune::Objective::for_group(group);
        let mut runs = Vec::new();
        println!(
            "{group:?} (kp {:.4e}, kd {:.4e}):",
            g.group(group).kp,
            g.group(group).kd
        );
        for e in [o.trajectory, o.step] {
            let r = tune::run(group, e, &g, dt);
            println!("  {}", tune::evaluate(e, &r).line());
            let name = format!(
                "{group:?}_{}",
                if matches!(e, tune::Experiment::Step { .. }) {
                    "step"
                } else {
                    "trajectory"
                }
            )
            .to_lowercase();
            tune::write_response_csv(&out.join(format!("{name}.csv")), &r)?;
            runs.push((e, r));
        }
        let png = out.join(format!("{group:?}.png").to_lowercase());
        tune::plot_responses(&png, group, &runs)?;
    }
    if let Some(p) = write_gains {
        // Six significant digits: the tuning is not finer than that, and
        // a file of 0.03266999982542984 reads as noise.
        let mut g = g.clone();
        for group in Group::ALL {
            let jg = g.group_mut(group);
            for x in [&mut jg.kp, &mut jg.kd, &mut jg.feedforward] {
                *x = format!("{:.5e}", *x)
                    .parse()
                    .expect("a formatted number parses");
            }
        }
        let text = ron::ser::to_string_pretty(&g, ron::ser::PrettyConfig::default())?;
        write_whole(
            &p,
            format!("// Written by `shisen tune`.\n{text}\n").as_bytes(),
        )
        .with_context(|| format!("cannot write {}", p.display()))?;
        println!("gains written to {}", p.display());
    }
    println!("CSV and plots in {}", out.display());
    Ok(())
}

pub fn sweep_cmd(
    group: Group,
    runs: usize,
    grid: bool,
    seed: u64,
    out: &std::path::Path,
    shard: Shard,
) -> Result<()> {
    use shisen::tools::tune;
    let all = tune::sweep_points(group, runs, grid, seed).map_err(anyhow::Error::msg)?;
    // A grid rounds the runs asked for to whole rows: the settings line
    // names the runs made, which `merge` checks a set of shards against.
    let total = all.len();
    let points: Vec<_> = all.into_iter().filter(|p| shard.contains(p.id)).collect();
    Outputs::new().folder("--out", out).check()?;
    let settings = settings_line(
        "sweep",
        &[
            ("group", format!("{group:?}")),
            ("runs", total.to_string()),
            ("grid", grid.to_string()),
            ("seed", seed.to_string()),
        ],
        shard,
    );
    let csv = out.join("sweep.csv");
    let results = ResultsFile::open(&csv, &settings, &tune::sweep_header())?;
    let rows = tune::sweep(group, &points, &Gains::default(), &results)?;
    results.finish()?;
    let best = rows
        .iter()
        .filter(|r| r.1.is_finite())
        .min_by(|a, b| a.1.total_cmp(&b.1));
    let meets = rows.iter().filter(|r| r.2).count();
    println!("{} runs, {meets} meet the objective", rows.len());
    if let Some((p, c, _)) = best {
        println!(
            "best: kp {:.4e}, kd {:.4e}, dt {} s, cost {c:.3}",
            p.kp, p.kd, p.dt
        );
    }
    tune::plot_sweep(&out.join("sweep.png"), group, &rows)?;
    println!("CSV and plot in {}", out.display());
    Ok(())
}
