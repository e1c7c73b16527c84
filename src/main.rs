//! The `shisen` command line.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};

use shisen::body::Group;
use shisen::control::Gains;
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
        /// Also plot the run (gaze, eye and head angles) to this PNG.
        #[arg(long)]
        plot: Option<PathBuf>,
    },
    /// Tune PD gains: step and trajectory experiments per joint group,
    /// metrics table, CSV and PNG plots; `--auto` improves the gains
    /// against the stated objective and can write a gains file.
    Tune {
        /// Groups to tune (default: all).
        #[arg(long, value_enum, value_delimiter = ',')]
        group: Vec<GroupArg>,
        /// Start from this gains file (default: the shipped gains).
        #[arg(long)]
        gains: Option<PathBuf>,
        /// Start the automatic tuning from the physically based guess
        /// instead of the current gains.
        #[arg(long)]
        from_guess: bool,
        /// Improve the gains automatically.
        #[arg(long)]
        auto: bool,
        /// Write the resulting gains file here.
        #[arg(long)]
        write_gains: Option<PathBuf>,
        /// Folder for CSV and PNG output.
        #[arg(long, default_value = "tune-out")]
        out: PathBuf,
        /// Step size, seconds.
        #[arg(long, default_value_t = 0.001)]
        dt: f64,
    },
    /// Sweep gains (and step size) for one group in parallel on all cores,
    /// resumable; writes CSV and a plot.
    Sweep {
        /// The group.
        #[arg(long, value_enum)]
        group: GroupArg,
        /// Number of runs.
        #[arg(long, default_value_t = 120)]
        runs: usize,
        /// A regular grid instead of seeded random samples.
        #[arg(long)]
        grid: bool,
        /// Seed of the random samples.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Folder for sweep.csv and sweep.png (re-running resumes).
        #[arg(long, default_value = "sweep-out")]
        out: PathBuf,
    },
    /// Spar against a seeded random opponent for N simulated minutes,
    /// checking invariants every tick, and print a summary.
    Soak {
        /// Simulated minutes.
        #[arg(long, default_value_t = 1.0)]
        minutes: f64,
        /// Seed of the opponent and the VH.
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
    /// Write the VH and opponent bodies as an MJCF model (for the MuJoCo
    /// comparison in benches/mujoco_compare.py).
    ExportMjcf {
        /// Output XML file.
        #[arg(long)]
        out: PathBuf,
    },
    /// Face tools: export the head with morph targets, calibrate the muscle
    /// database from subject data.
    Face {
        #[command(subcommand)]
        command: FaceCommand,
    },
    /// Plot a trace: gaze, eye and head angles against time, with the
    /// gaze-target switches marked.
    Plot {
        /// Trace CSV written by `run --trace`.
        trace: PathBuf,
        /// Output PNG.
        #[arg(long)]
        out: PathBuf,
        /// Image size, WxH.
        #[arg(long, default_value = "1400x900", value_parser = parse_size)]
        size: (u32, u32),
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
        /// Camera: `first` (from your head), `orbit` or `face` (close-up).
        #[arg(long, default_value = "first", value_parser = parse_view)]
        view: View,
        /// Overlays to draw (repeatable).
        #[arg(long, value_enum)]
        overlay: Vec<OverlayArg>,
    },
}

#[derive(Subcommand)]
enum FaceCommand {
    /// Export the neutral generated head to glTF (.glb) with one morph
    /// target per muscle and ARKit-named shapes.
    Export {
        /// Output .glb file.
        #[arg(long)]
        out: PathBuf,
        /// Mesh resolution (latitude bands).
        #[arg(long, default_value_t = 48)]
        rows: usize,
    },
    /// Turn per-subject settings (CSV: expression, subject, one column per
    /// muscle) into a muscle database with the thesis's rule (drop values
    /// outside mean +/- 1 SD, average the rest).
    Calibrate {
        /// Subject data, CSV.
        csv: PathBuf,
        /// Output muscle database (RON), usable as a scene's `vh.face.database`.
        #[arg(long)]
        out: PathBuf,
    },
}

/// Joint groups on the command line.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
enum GroupArg {
    Eye,
    Neck,
    Shoulder,
    Elbow,
}

impl From<GroupArg> for Group {
    fn from(g: GroupArg) -> Group {
        match g {
            GroupArg::Eye => Group::Eye,
            GroupArg::Neck => Group::Neck,
            GroupArg::Shoulder => Group::Shoulder,
            GroupArg::Elbow => Group::Elbow,
        }
    }
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
        .ok_or_else(|| format!("expected WxH, got `{s}`"))?;
    let n = |v: &str| {
        v.parse::<u32>()
            .ok()
            .filter(|v| (64..=8192).contains(v))
            .ok_or_else(|| format!("size must be 64-8192 pixels, got `{v}`"))
    };
    Ok((n(w)?, n(h)?))
}

fn parse_view(s: &str) -> Result<View, String> {
    View::parse(s).ok_or_else(|| format!("expected first, orbit or face, got {s}"))
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

struct RunArgs {
    scene: String,
    trace: Option<PathBuf>,
    every: u64,
    seed: Option<u64>,
    duration: Option<f64>,
    plot: Option<PathBuf>,
}

fn run(a: RunArgs) -> Result<bool> {
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
        shisen::plot::plot_trace(t, p, (1400, 900))?;
        println!("plot written to {}", p.display());
    }
    let passed = report.verdicts.iter().filter(|v| v.pass).count();
    println!("{passed} passed, {} failed", report.verdicts.len() - passed);
    Ok(report.passed())
}

fn report(r: Result<()>) -> ExitCode {
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn tune_cmd(
    groups: Vec<GroupArg>,
    gains: Option<PathBuf>,
    from_guess: bool,
    auto: bool,
    write_gains: Option<PathBuf>,
    out: &std::path::Path,
    dt: f64,
) -> Result<()> {
    use shisen::tune;
    if !(dt.is_finite() && dt > 0.0 && dt <= 0.01) {
        anyhow::bail!("--dt: must be in (0, 0.01] s, got {dt}");
    }
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
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
        let text = ron::ser::to_string_pretty(&g, ron::ser::PrettyConfig::default())?;
        std::fs::write(&p, format!("// Written by `shisen tune`.\n{text}\n"))
            .with_context(|| format!("cannot write {}", p.display()))?;
        println!("gains written to {}", p.display());
    }
    println!("CSV and plots in {}", out.display());
    Ok(())
}

fn sweep_cmd(
    group: Group,
    runs: usize,
    grid: bool,
    seed: u64,
    out: &std::path::Path,
) -> Result<()> {
    use shisen::tune;
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let points = tune::sweep_points(group, runs, grid, seed);
    let rows = tune::sweep(group, &points, &Gains::default(), &out.join("sweep.csv"))?;
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

fn soak_cmd(minutes: f64, seed: u64) -> Result<bool> {
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
    let r = shisen::soak::soak(minutes, seed, |f| bar.set_position((f * 1000.0) as u64));
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

fn face_cmd(c: FaceCommand) -> Result<()> {
    use shisen::face::{Face, calibrate, exchange, mesh::MeshParams, params::FaceParams};
    match c {
        FaceCommand::Export { out, rows } => {
            if !(24..=400).contains(&rows) {
                anyhow::bail!("--rows: must be 24-400, got {rows}");
            }
            let face = Face::new(MeshParams { rows }, FaceParams::default_params());
            std::fs::write(&out, exchange::export_glb(&face))
                .with_context(|| format!("cannot write {}", out.display()))?;
            println!(
                "{}: {} vertices, {} triangles, morph targets per muscle and ARKit shape",
                out.display(),
                face.mesh.positions.len(),
                face.mesh.triangles.len()
            );
        }
        FaceCommand::Calibrate { csv, out } => {
            let params = calibrate::calibrate_file(&FaceParams::default_params(), &csv)?;
            std::fs::write(&out, params.to_ron())
                .with_context(|| format!("cannot write {}", out.display()))?;
            println!("muscle database written to {}", out.display());
        }
    }
    Ok(())
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
            plot,
        }) => match run(RunArgs {
            scene,
            trace,
            every: trace_every,
            seed,
            duration,
            plot,
        }) {
            Ok(true) => ExitCode::SUCCESS,
            Ok(false) => ExitCode::from(1),
            Err(e) => {
                eprintln!("error: {e:#}");
                ExitCode::from(2)
            }
        },
        Some(Command::Tune {
            group,
            gains,
            from_guess,
            auto,
            write_gains,
            out,
            dt,
        }) => report(tune_cmd(
            group,
            gains,
            from_guess,
            auto,
            write_gains,
            &out,
            dt,
        )),
        Some(Command::Sweep {
            group,
            runs,
            grid,
            seed,
            out,
        }) => report(sweep_cmd(group.into(), runs, grid, seed, &out)),
        Some(Command::Face { command }) => report(face_cmd(command)),
        Some(Command::ExportMjcf { out }) => report(
            std::fs::write(
                &out,
                shisen::mjcf::mjcf(&shisen::body::BodyPlan::default(), shisen::sim::DT),
            )
            .with_context(|| format!("cannot write {}", out.display())),
        ),
        Some(Command::Soak { minutes, seed }) => match soak_cmd(minutes, seed) {
            Ok(true) => ExitCode::SUCCESS,
            Ok(false) => ExitCode::from(1),
            Err(e) => {
                eprintln!("error: {e:#}");
                ExitCode::from(2)
            }
        },
        Some(Command::Plot { trace, out, size }) => {
            match shisen::plot::plot_trace(&trace, &out, size) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: {e:#}");
                    ExitCode::from(2)
                }
            }
        }
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
