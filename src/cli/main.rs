//! The `shisen` command line.

use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;

mod batch;
mod cli;
mod face;
mod run;
mod sound;
mod tune;

use batch::{jobs, merge_cmd, study_cmd, test_cmd};
use cli::*;
use face::face_cmd;
use run::{Animation, INTERRUPTED, Interrupted, RunArgs, install_interrupt, render, run, soak_cmd};
use tune::{sweep_cmd, tune_cmd};

fn report(r: Result<()>) -> ExitCode {
    exit(r.map(|()| ExitCode::SUCCESS))
}

/// A command's exit: its code, 130 if Ctrl-C stopped it ([`Interrupted`]),
/// 2 for any other error (bad input, an output that cannot be written).
fn exit(r: Result<ExitCode>) -> ExitCode {
    match r {
        // Stopped by Ctrl-C, even if the work ended before it noticed.
        Ok(_) if shisen::tools::stop_requested() => {
            eprintln!("interrupted");
            ExitCode::from(INTERRUPTED)
        }
        Ok(code) => code,
        Err(e) if e.downcast_ref::<Interrupted>().is_some() => {
            eprintln!("{e:#}");
            ExitCode::from(INTERRUPTED)
        }
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

/// A command that passes (0) or fails (1) what it checks.
fn verdict(r: Result<bool>) -> ExitCode {
    exit(r.map(|ok| {
        if ok {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(1)
        }
    }))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if matches!(
        cli.command,
        Some(
            Command::Render { .. }
                | Command::Face {
                    command: FaceCommand::Sheet { .. }
                }
        )
    ) && std::env::var_os("XDG_RUNTIME_DIR").is_none()
        && std::env::var_os("NODEVICE_SELECT").is_none()
    {
        // Offscreen rendering needs no display; without one, Mesa's implicit
        // device-select Vulkan layer still probes Wayland and prints an
        // "XDG_RUNTIME_DIR is invalid" error on success. Turn it off.
        // SAFETY: first thing in main, before any other thread exists.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "warn".into()),
        )
        .with_writer(std::io::stderr)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .init();
    if cli.command.is_some()
        && let Some(flag) = cli.window_flag()
    {
        eprintln!("error: {flag} is an option of the window; it does nothing before a subcommand");
        return ExitCode::from(2);
    }
    if cli.command.is_some() {
        install_interrupt();
        // Output piped into a reader that stops early (`| head`) ends the
        // command quietly, as it does any Unix tool, instead of a panic in
        // `println!` or an error. Rust ignores SIGPIPE by default.
        // SAFETY: resetting a signal's disposition to its default, before
        // any output and before any other thread exists.
        unsafe {
            libc::signal(libc::SIGPIPE, libc::SIG_DFL);
        }
    }
    match cli.command {
        None if cli.print_bindings => {
            print!("{}", shisen_app::input::DEFAULT_BINDINGS_RON);
            ExitCode::SUCCESS
        }
        None => {
            if let Some(s) = cli.exit_after
                && !(s.is_finite() && s >= 0.0)
            {
                eprintln!("error: --exit-after: must be a non-negative number of seconds");
                return ExitCode::from(2);
            }
            let opts = shisen_app::app::AppOptions {
                scene: cli.scene,
                bindings: cli.bindings,
                exit_after: cli.exit_after,
                screenshot: cli.screenshot,
                panels: cli.panels,
                open: cli.open,
                orbit: cli.orbit,
                overlays: cli.overlays,
                opponent: cli.opponent,
                rounds: cli.rounds,
                round_length: cli.round_length,
                rest: cli.rest,
                stats: cli.stats,
                report: cli.report,
                menu: cli.menu,
                render_scale: cli.render_scale.map(|s| s as f32),
                volume: cli.volume.map(|v| v as f32),
            };
            // Bad input files and outputs are usage errors (2), as for
            // every command, and are found before a window opens.
            let mut plan = shisen::tools::output::Outputs::new();
            for p in [&opts.scene, &opts.bindings].into_iter().flatten() {
                plan = plan.input(p);
            }
            if let Some(p) = &opts.stats {
                plan = plan.file_as("--stats", p, "JSON", &["json"]);
            }
            if let Some(p) = &opts.screenshot {
                plan = plan.file_as("--screenshot", p, "a PNG picture", &["png"]);
            }
            if let Err(e) = plan.check() {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
            if let Some(p) = &opts.scene
                && let Err(e) = shisen::scene::LoadedScene::load(p)
            {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
            if let Some(p) = &opts.bindings
                && let Err(e) = shisen_app::input::Bindings::load(p)
            {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
            match shisen_app::app::run(opts) {
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
            sound,
            force,
        }) => exit(run(RunArgs {
            scene,
            trace,
            every: trace_every,
            seed,
            duration,
            plot,
            sound,
            force,
        })),
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
            shard,
        }) => report(sweep_cmd(group.into(), runs, grid, seed, &out, shard)),
        Some(Command::Test {
            paths,
            jobs: j,
            junit,
            out,
            shard,
        }) => exit(test_cmd(
            &paths,
            jobs(j),
            shard,
            junit.as_deref(),
            out.as_deref(),
        )),
        Some(Command::Study {
            study,
            out,
            jobs: j,
            shard,
        }) => report(study_cmd(&study, &out, jobs(j), shard)),
        Some(Command::Merge { out, inputs }) => report(merge_cmd(&inputs, &out)),
        Some(Command::Face { command }) => report(face_cmd(command)),
        Some(Command::ExportMjcf { out, balanced }) => report(export_mjcf(&out, balanced)),
        Some(Command::Fidelity {
            scene,
            profile,
            out,
        }) => verdict(fidelity_cmd(scene, profile, out)),
        Some(Command::Pushes { scene }) => report(pushes_cmd(scene)),
        Some(Command::Soak {
            minutes,
            seed,
            balanced,
            opponent,
            rounds,
            partner_defence,
            partner_punches,
            force,
        }) => verdict(soak_cmd(
            minutes,
            seed,
            shisen::tools::soak::SoakSetup {
                balanced,
                opponent,
                rounds,
                partner: shisen::tools::soak::BotRates {
                    defend: partner_defence,
                    punch: partner_punches / 60.0,
                    ..Default::default()
                },
            },
            force,
        )),
        Some(Command::Plot { trace, out, size }) => report(
            shisen::tools::output::Outputs::new()
                .input(&trace)
                .file_as("--out", &out, "a PNG picture", &["png"])
                .check()
                .map_err(anyhow::Error::from)
                .and_then(|()| shisen::tools::plot::plot_trace(&trace, &out, size)),
        ),
        Some(Command::Render {
            scene,
            at,
            out,
            size,
            view,
            overlay,
            until,
            fps,
            slow,
            sound,
        }) => report(render(
            &scene,
            at,
            &out,
            size,
            view,
            &overlay,
            until.map(|until| Animation {
                until,
                fps,
                slow,
                sound,
            }),
        )),
        Some(Command::Schema { file, markdown }) => report(schema_cmd(file, markdown)),
    }
}

/// `shisen export-mjcf`.
fn export_mjcf(out: &std::path::Path, balanced: bool) -> Result<()> {
    shisen::tools::output::Outputs::new()
        .file_as("--out", out, "an MJCF model (XML)", &["xml"])
        .check()?;
    let body = shisen::physics::lower::BodyParams {
        pelvis: shisen::physics::lower::Pelvis::Balanced,
        ..Default::default()
    };
    let xml = shisen::tools::mjcf::mjcf(
        &shisen::physics::body::BodyPlan::default(),
        shisen::sim::DT,
        balanced.then_some(&body),
    );
    shisen::tools::output::write_whole(out, xml.as_bytes())
        .with_context(|| format!("cannot write {}", out.display()))
}

/// `shisen schema`: an input file kind's JSON Schema, or the reference.
fn schema_cmd(file: Option<shisen_app::schema::FileKind>, markdown: bool) -> Result<()> {
    use shisen_app::schema::{FileKind, reference, schema_json};
    if markdown {
        print!("{}", reference());
        return Ok(());
    }
    let kind = file.unwrap_or(FileKind::Scene);
    println!("{}", schema_json(kind));
    Ok(())
}

/// `shisen fidelity`: the battery, its table, and its files if asked.
fn pushes_cmd(scene: Option<std::path::PathBuf>) -> Result<()> {
    let loaded = match &scene {
        Some(p) => load(&p.display().to_string())?,
        None => shisen::scene::LoadedScene::default_scene(),
    };
    let model = shisen::tools::fidelity::model_of(&loaded, None);
    let table = shisen::tools::fidelity::push_table(&model);
    if shisen::tools::stop_requested() {
        return Err(Interrupted("before every shove ran; nothing printed".into()).into());
    }
    print!("{table}");
    Ok(())
}

fn fidelity_cmd(
    scene: Option<std::path::PathBuf>,
    profile: Option<ProfileArg>,
    out: Option<std::path::PathBuf>,
) -> Result<bool> {
    use shisen::tools::fidelity;
    let mut plan = shisen::tools::output::Outputs::new();
    if let Some(dir) = &out {
        plan = plan.folder("--out", dir);
    }
    plan.check()?;
    let loaded = match &scene {
        Some(p) => load(&p.display().to_string())?,
        None => shisen::scene::LoadedScene::default_scene(),
    };
    let profile = profile.map(|p| match p {
        ProfileArg::Human => shisen::sim::Profile::Human,
        ProfileArg::Seed => shisen::sim::Profile::Seed,
    });
    let model = fidelity::model_of(&loaded, profile);
    let (rows, curves) = fidelity::battery(&model);
    print!("{}", fidelity::table(&rows));
    let failed = rows.iter().filter(|r| !r.pass()).count();
    println!(
        "{} rows: {} pass, {failed} fail",
        rows.len(),
        rows.len() - failed
    );
    if let Some(dir) = out {
        fidelity::write(&dir, &rows, &curves)?;
        println!("wrote {}", dir.display());
    }
    Ok(failed == 0)
}
