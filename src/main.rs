//! The `shisen` command line.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};

use shisen::headless;
use shisen::scene::LoadedScene;

/// shisen (視線): a virtual human that boxes with you and looks where a person would.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene (file path, or `default` for the embedded scene).
    Run {
        /// Scene file, or `default`.
        scene: String,
        /// Run without a window (the only mode until the sparring window lands).
        #[arg(long)]
        headless: bool,
        /// Write the trace (CSV) here.
        #[arg(long)]
        trace: Option<PathBuf>,
        /// Write every Nth tick to the trace.
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
        trace_every: u64,
        /// Override the scene's seed.
        #[arg(long)]
        seed: Option<u64>,
        /// Override the scene's duration, seconds.
        #[arg(long)]
        duration: Option<f64>,
    },
}

fn load(scene: &str) -> Result<LoadedScene> {
    if scene == "default" {
        return Ok(LoadedScene::default_scene());
    }
    Ok(LoadedScene::load(std::path::Path::new(scene))?)
}

fn run(
    scene: &str,
    trace: Option<PathBuf>,
    every: u64,
    seed: Option<u64>,
    duration: Option<f64>,
) -> Result<bool> {
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
    for v in &report.verdicts {
        println!(
            "{}  {}: measured {}",
            if v.pass { "PASS" } else { "FAIL" },
            v.what,
            v.measured
        );
    }
    let passed = report.verdicts.iter().filter(|v| v.pass).count();
    println!("{passed} passed, {} failed", report.verdicts.len() - passed);
    Ok(report.passed())
}

fn main() -> ExitCode {
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "warn".into()),
        )
        .with_writer(std::io::stderr)
        .init();
    let cli = Cli::parse();
    match cli.command {
        None => {
            println!(
                "The sparring window is not built yet. Run a scene headless:\n  \
                 shisen run default --headless\n  \
                 shisen run scenes/look_sequence.ron --headless --trace trace.csv"
            );
            ExitCode::SUCCESS
        }
        Some(Command::Run {
            scene,
            headless: _,
            trace,
            trace_every,
            seed,
            duration,
        }) => match run(&scene, trace, trace_every, seed, duration) {
            Ok(true) => ExitCode::SUCCESS,
            Ok(false) => ExitCode::from(1),
            Err(e) => {
                eprintln!("error: {e:#}");
                ExitCode::from(2)
            }
        },
    }
}
