//! The `shisen` command line.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};

use shisen::headless;
use shisen::render::{Headless, Overlays, View, write_png};
use shisen::scene::LoadedScene;
use shisen::sim::{DT, Sim};

/// shisen (視線): a virtual human that boxes with you and looks where a person would.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Window: scene file to spar in (default: the embedded scene).
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Window: bindings file (default: ~/.config/shisen/bindings.ron, else built in).
    #[arg(long)]
    bindings: Option<PathBuf>,
    /// Window: close after this many seconds (CI).
    #[arg(long)]
    exit_after: Option<f64>,
    /// Window: save a screenshot here before closing (with --exit-after).
    #[arg(long)]
    screenshot: Option<PathBuf>,
    /// Window: open the tuning panel at start.
    #[arg(long)]
    panels: bool,
    /// Window: open these panel sections at start (scene, attention,
    /// personality, gains, face; repeatable).
    #[arg(long, value_parser = ["scene", "attention", "personality", "gains", "face"])]
    open: Vec<String>,
    /// Window: start in the orbit view.
    #[arg(long)]
    orbit: bool,
    /// Window: gaze rays and saliency labels on at start.
    #[arg(long)]
    overlays: bool,
    /// Print the default bindings (RON) and exit.
    #[arg(long)]
    print_bindings: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene (file path, or `default` for the embedded scene).
    Run {
        /// Scene file, or `default`.
        scene: String,
        /// Run without a window (`run` never opens one; the flag is kept for scripts).
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
    /// Run a scene headless to a time and render a picture of it (PNG).
    Render {
        /// Scene file, or `default`.
        scene: String,
        /// Simulation time to render, seconds.
        #[arg(long, default_value_t = 1.0)]
        at: f64,
        /// Output PNG.
        #[arg(long)]
        out: PathBuf,
        /// Image size, WxH pixels.
        #[arg(long, default_value = "1280x720", value_parser = parse_size)]
        size: (u32, u32),
        /// Camera: `first` (from your head) or `orbit`.
        #[arg(long, default_value = "first", value_parser = parse_view)]
        view: View,
        /// Overlays to draw (repeatable).
        #[arg(long, value_enum)]
        overlay: Vec<OverlayArg>,
    },
}

/// Overlays selectable on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum OverlayArg {
    /// Lines of sight and the gaze point.
    Gaze,
    /// Fields of view.
    Fov,
    /// Joint frames.
    Frames,
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once('x')
        .ok_or_else(|| format!("expected WxH, got {s}"))?;
    let n = |v: &str| -> Result<u32, String> {
        match v.trim().parse::<u32>() {
            Ok(n) if (16..=8192).contains(&n) => Ok(n),
            _ => Err(format!("size must be 16-8192 pixels, got {v}")),
        }
    };
    Ok((n(w)?, n(h)?))
}

fn parse_view(s: &str) -> Result<View, String> {
    View::parse(s).ok_or_else(|| format!("expected first or orbit, got {s}"))
}

fn render(
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
    let mut sim = Sim::new(&loaded);
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
        None if cli.print_bindings => {
            print!("{}", shisen::input::DEFAULT_BINDINGS_RON);
            ExitCode::SUCCESS
        }
        None => {
            if let Some(s) = cli.exit_after
                && !(s.is_finite() && s >= 0.0)
            {
                eprintln!("error: --exit-after: must be a non-negative number of seconds");
                return ExitCode::from(2);
            }
            let opts = shisen::app::AppOptions {
                scene: cli.scene,
                bindings: cli.bindings,
                exit_after: cli.exit_after,
                screenshot: cli.screenshot,
                panels: cli.panels,
                open: cli.open,
                orbit: cli.orbit,
                overlays: cli.overlays,
            };
            match shisen::app::run(opts) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: {e:#}");
                    ExitCode::from(1)
                }
            }
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
        Some(Command::Render {
            scene,
            at,
            out,
            size,
            view,
            overlay,
        }) => match render(&scene, at, &out, size, view, &overlay) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e:#}");
                ExitCode::from(2)
            }
        },
    }
}
