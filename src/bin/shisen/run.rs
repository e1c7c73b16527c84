//! `shisen run`, `shisen render`, `shisen soak`: scenes headless.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;

use anyhow::{Context, Result};

use shisen::render::{Headless, Overlays, View, write_png};
use shisen::sim::DT;
use shisen::tools::headless;

use crate::cli::*;

pub fn render(
    scene: &str,
    at: f64,
    out: &std::path::Path,
    size: (u32, u32),
    view: View,
    overlay: &[OverlayArg],
) -> Result<()> {
    if !(at.is_finite() && at >= 0.0) {
        anyhow::bail!("--at: must be a non-negative number of seconds, got {at}");
    }
    let loaded = load(scene)?;
    let mut sim = loaded.sim();
    while sim.time() + DT / 2.0 < at {
        sim.step();
    }
    let overlays = Overlays {
        gaze_rays: overlay.contains(&OverlayArg::Gaze),
        fov_cones: overlay.contains(&OverlayArg::Fov),
        joint_frames: overlay.contains(&OverlayArg::Frames),
        saliency_labels: false,
    };
    let mut gpu = Headless::new()?;
    let image = gpu.snapshot(&sim, view, overlays, size)?;
    write_png(&image, out)?;
    println!(
        "{} at {:.3} s -> {} ({}x{}, {})",
        loaded.scene.name,
        sim.time(),
        out.display(),
        size.0,
        size.1,
        gpu.info.name
    );
    Ok(())
}

pub struct RunArgs {
    pub scene: String,
    pub trace: Option<PathBuf>,
    pub every: u64,
    pub seed: Option<u64>,
    pub duration: Option<f64>,
    pub plot: Option<PathBuf>,
}

pub fn run(a: RunArgs) -> Result<bool> {
    let RunArgs {
        scene,
        trace,
        every,
        seed,
        duration,
        plot,
    } = a;
    let scene = scene.as_str();
    // A plot needs a trace; write one beside the plot if none was asked for.
    let trace = trace.or_else(|| plot.as_ref().map(|p| p.with_extension("csv")));
    let mut loaded = load(scene)?;
    if let Some(s) = seed {
        loaded.scene.seed = s;
    }
    if let Some(d) = duration
        && !(d.is_finite() && d > 0.0)
    {
        anyhow::bail!("--duration: must be a positive number of seconds, got {d}");
    }
    let mut file = match &trace {
        Some(p) => {
            Some(BufWriter::new(File::create(p).with_context(|| {
                format!("cannot create trace {}", p.display())
            })?))
        }
        None => None,
    };
    let wall = std::time::Instant::now(); // reporting only; the model never reads it
    let report = headless::run(
        &loaded,
        duration,
        file.as_mut().map(|f| f as &mut dyn Write),
        every,
    )?;
    let secs = wall.elapsed().as_secs_f64();
    println!(
        "scene {} ({}), seed {}: {:.3} s simulated in {} ticks, {:.2} s wall ({:.1}x real time)",
        loaded.scene.name,
        loaded.source,
        loaded.scene.seed,
        report.sim_time,
        report.ticks,
        secs,
        report.sim_time / secs.max(1e-9)
    );
    if report.resets > 0 {
        println!(
            "warning: the physics blew up {} times; the VH was reset each time (trace column `reset`)",
            report.resets
        );
    }
    for v in &report.verdicts {
        println!(
            "{}  {}: measured {}",
            if v.pass { "PASS" } else { "FAIL" },
            v.what,
            v.measured
        );
    }
    if let (Some(p), Some(t)) = (&plot, &trace) {
        drop(file);
        shisen::tools::plot::plot_trace(t, p, (1400, 900))?;
        println!("plot written to {}", p.display());
    }
    let passed = report.verdicts.iter().filter(|v| v.pass).count();
    println!("{passed} passed, {} failed", report.verdicts.len() - passed);
    Ok(report.passed())
}

pub fn soak_cmd(minutes: f64, seed: u64) -> Result<bool> {
    if !(minutes.is_finite() && minutes > 0.0) {
        anyhow::bail!("--minutes: must be a positive number, got {minutes}");
    }
    let bar = indicatif::ProgressBar::new(1000);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {percent}% simulated, {elapsed} elapsed, eta {eta}",
        )
        .expect("template"),
    );
    let wall = std::time::Instant::now(); // reporting only
    let r = shisen::tools::soak::soak(minutes, seed, |f| bar.set_position((f * 1000.0) as u64));
    bar.finish_and_clear();
    let secs = wall.elapsed().as_secs_f64();
    println!(
        "soak: {:.1} simulated minutes ({} ticks) in {:.1} s wall ({:.1}x real time), seed {seed}",
        r.sim_time / 60.0,
        r.ticks,
        secs,
        r.sim_time / secs.max(1e-9)
    );
    println!(
        "  {} opponent events, {} VH punches, {} head-contact ticks, {} physics resets",
        r.events, r.vh_punches, r.head_hit_ticks, r.resets
    );
    println!(
        "  worst eye/neck excursion past its range {:.2} deg; resident memory {} -> {} KiB",
        r.worst_limit_excess_deg, r.rss_kib.0, r.rss_kib.1
    );
    for f in &r.failures {
        println!("  FAIL {f}");
    }
    println!(
        "  invariants {}",
        if r.passed() { "held" } else { "VIOLATED" }
    );
    Ok(r.passed())
}
