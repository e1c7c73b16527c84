//! The `shisen` command line.

use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;

mod batch;
mod cli;
mod face;
mod run;
mod tune;

use batch::{jobs, merge_cmd, study_cmd, test_cmd};
use cli::*;
use face::face_cmd;
use run::{RunArgs, render, run, soak_cmd};
use tune::{sweep_cmd, tune_cmd};

fn report(r: Result<()>) -> ExitCode {
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
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
            };
            // Bad input files are usage errors (2), as for every command,
            // and are found before a window opens.
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
            force,
        }) => match run(RunArgs {
            scene,
            trace,
            every: trace_every,
            seed,
            duration,
            plot,
            force,
        }) {
            Ok(code) => code,
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
            shard,
        }) => report(sweep_cmd(group.into(), runs, grid, seed, &out, shard)),
        Some(Command::Test {
            paths,
            jobs: j,
            junit,
            out,
            shard,
        }) => match jobs(j)
            .and_then(|j| test_cmd(&paths, j, shard, junit.as_deref(), out.as_deref()))
        {
            Ok(code) => code,
            Err(e) => {
                eprintln!("error: {e:#}");
                ExitCode::from(2)
            }
        },
        Some(Command::Study {
            study,
            out,
            jobs: j,
            shard,
        }) => report(jobs(j).and_then(|j| study_cmd(&study, &out, j, shard))),
        Some(Command::Merge { out, inputs }) => report(merge_cmd(&inputs, &out)),
        Some(Command::Face { command }) => report(face_cmd(command)),
        Some(Command::ExportMjcf { out }) => report(
            std::fs::write(
                &out,
                shisen::tools::mjcf::mjcf(
                    &shisen::physics::body::BodyPlan::default(),
                    shisen::sim::DT,
                ),
            )
            .with_context(|| format!("cannot write {}", out.display())),
        ),
        Some(Command::Fidelity {
            scene,
            profile,
            out,
        }) => match fidelity_cmd(scene, profile, out) {
            Ok(true) => ExitCode::SUCCESS,
            Ok(false) => ExitCode::from(1),
            Err(e) => {
                eprintln!("error: {e:#}");
                ExitCode::from(2)
            }
        },
        Some(Command::Soak {
            minutes,
            seed,
            force,
        }) => match soak_cmd(minutes, seed, force) {
            Ok(true) => ExitCode::SUCCESS,
            Ok(false) => ExitCode::from(1),
            Err(e) => {
                eprintln!("error: {e:#}");
                ExitCode::from(2)
            }
        },
        Some(Command::Plot { trace, out, size }) => {
            match shisen::tools::plot::plot_trace(&trace, &out, size) {
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
            until,
            fps,
            slow,
        }) => match render(
            &scene,
            at,
            &out,
            size,
            view,
            &overlay,
            until.map(|u| (u, fps, slow)),
        ) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e:#}");
                ExitCode::from(2)
            }
        },
    }
}

/// `shisen fidelity`: the battery, its table, and its files if asked.
fn fidelity_cmd(
    scene: Option<std::path::PathBuf>,
    profile: Option<ProfileArg>,
    out: Option<std::path::PathBuf>,
) -> Result<bool> {
    use shisen::tools::fidelity;
    if let Some(dir) = &out
        && dir.exists()
        && !dir.is_dir()
    {
        anyhow::bail!("--out: {} exists and is not a folder", dir.display());
    }
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
