//! `shisen run`, `shisen render`, `shisen soak`: scenes headless.

use shisen::tools::output::{Outputs, write_whole};
use shisen::tools::stop_requested;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use shisen::scene::validate::check_duration;

use super::sound::SoundFile;
use shisen::sim::DT;
use shisen::tools::headless;
use shisen_app::render::{Headless, Overlays, View, write_png};

use crate::cli::*;

/// `render --until`: an animation instead of one picture.
pub struct Animation {
    /// Its end, s.
    pub until: f64,
    /// Frames a second of simulated time.
    pub fps: u32,
    /// Times slower than real time it plays.
    pub slow: u32,
    /// Its soundtrack's WAV file.
    pub sound: Option<PathBuf>,
}

pub fn render(
    scene: &str,
    at: f64,
    out: &std::path::Path,
    size: (u32, u32),
    view: View,
    overlay: &[OverlayArg],
    animation: Option<Animation>,
) -> Result<()> {
    if !(at.is_finite() && at >= 0.0) {
        anyhow::bail!("--at: must be a non-negative number of seconds, got {at}");
    }
    if let Some(&Animation {
        until, fps, slow, ..
    }) = animation.as_ref()
    {
        if !(until.is_finite() && until > at) {
            anyhow::bail!("--until {until}: must be after --at ({at} s)");
        }
        if !(1..=1000).contains(&fps) {
            anyhow::bail!("--fps {fps}: must be 1-1000");
        }
        if !(1..=100).contains(&slow) {
            anyhow::bail!("--slow {slow}: must be 1-100");
        }
        if fps > 60 * slow {
            anyhow::bail!(
                "--fps {fps} with --slow {slow} plays {} frames a second; at most 60 (lower --fps or raise --slow)",
                fps / slow
            );
        }
        if slow > 1 && animation.as_ref().is_some_and(|a| a.sound.is_some()) {
            anyhow::bail!(
                "--sound with --slow {slow}: the soundtrack runs at real speed; leave --slow at 1"
            );
        }
        if (until - at) * f64::from(fps) > 600.0 {
            anyhow::bail!(
                "--until: at most 600 frames ({:.0} asked)",
                (until - at) * f64::from(fps)
            );
        }
    }
    if at > LONG_RUN {
        anyhow::bail!("--at {at}: at most {LONG_RUN} s of simulated time");
    }
    if out
        .extension()
        .is_none_or(|e| !e.eq_ignore_ascii_case("png"))
    {
        anyhow::bail!("--out {}: must name a .png file", out.display());
    }
    let loaded = load(scene)?;
    let duration = loaded.scene.duration;
    let end = animation.as_ref().map_or(at, |a| a.until);
    if end > duration {
        let flag = if animation.is_some() {
            "--until"
        } else {
            "--at"
        };
        anyhow::bail!("{flag} {end}: after the scene's end ({duration} s)");
    }
    let mut plan = Outputs::new().file_as(
        "--out",
        out,
        "a PNG picture (an animated one with --until)",
        &["png", "apng"],
    );
    if scene != "default" {
        plan = plan.input(Path::new(scene));
    }
    for f in loaded.files() {
        plan = plan.input(&f);
    }
    let sound_path = animation.as_ref().and_then(|a| a.sound.as_deref());
    if let Some(p) = sound_path {
        plan = plan.file_as("--sound", p, "a WAV sound file", &["wav"]);
    }
    plan.check()?;
    let mut sim = loaded.sim();
    let mut sound = match sound_path {
        Some(p) => Some(SoundFile::create(p, loaded.scene.seed, end)?.starting_at(at)),
        None => None,
    };
    let bar = progress(at, "s simulated");
    let mut ticks = 0u64;
    while sim.time() + DT / 2.0 < at {
        sim.step();
        if let Some(s) = &mut sound {
            s.hear(&sim)?;
        }
        ticks += 1;
        if ticks.is_multiple_of(1000) {
            bar.set_position(sim.time() as u64);
            if stop_requested() {
                return Err(Interrupted(format!("at {:.1} s; nothing written", sim.time())).into());
            }
        }
    }
    bar.finish_and_clear();
    let overlays = Overlays {
        gaze_rays: overlay.contains(&OverlayArg::Gaze),
        fov_cones: overlay.contains(&OverlayArg::Fov),
        joint_frames: overlay.contains(&OverlayArg::Frames),
        saliency_labels: false,
    };
    let mut gpu = Headless::new()?;
    let image = gpu.snapshot(&sim, view, overlays, size)?;
    if let Some(Animation {
        until, fps, slow, ..
    }) = animation
    {
        let mut frames = vec![image];
        let n = ((until - at) * f64::from(fps)).round() as usize;
        for k in 1..=n {
            let t = at + k as f64 / f64::from(fps);
            while sim.time() + DT / 2.0 < t {
                sim.step();
                if let Some(s) = &mut sound {
                    s.hear(&sim)?;
                }
            }
            if stop_requested() {
                return Err(Interrupted(format!("at frame {k} of {n}; nothing written")).into());
            }
            frames.push(gpu.snapshot(&sim, view, overlays, size)?);
        }
        write_apng(&frames, fps, slow, out)?;
        if let Some(s) = sound {
            s.finish()?;
        }
        println!("{} frames at {fps} fps, {slow}x slow", frames.len());
    } else {
        write_png(&image, out)?;
    }
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

/// Write `frames` as an animated PNG (APNG), one frame every `slow / fps`
/// s, looping.
fn write_apng(
    frames: &[image::RgbaImage],
    fps: u32,
    slow: u32,
    out: &std::path::Path,
) -> Result<()> {
    let (w, h) = frames[0].dimensions();
    let mut bytes = Vec::new();
    let mut enc = png::Encoder::new(&mut bytes, w, h);
    enc.set_color(png::ColorType::Rgba);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_animated(frames.len() as u32, 0)?;
    enc.set_frame_delay(slow as u16, fps as u16)?;
    let mut writer = enc.write_header()?;
    for f in frames {
        writer.write_image_data(f.as_raw())?;
    }
    writer.finish()?;
    write_whole(out, &bytes).with_context(|| format!("cannot write {}", out.display()))
}

pub struct RunArgs {
    pub scene: String,
    pub trace: Option<PathBuf>,
    pub every: u64,
    pub seed: Option<u64>,
    pub duration: Option<f64>,
    pub plot: Option<PathBuf>,
    pub sound: Option<PathBuf>,
    pub force: bool,
}

/// Longest run (s of simulated time) made without `--force`: about two
/// minutes of wall time on one core.
pub const LONG_RUN: f64 = 3600.0;

/// Exit code of a command stopped by Ctrl-C (the shell's 128 + SIGINT).
pub const INTERRUPTED: u8 = 130;

/// A command stopped by Ctrl-C: what it kept (exit [`INTERRUPTED`]).
#[derive(Debug, thiserror::Error)]
#[error("interrupted {0}")]
pub struct Interrupted(pub String);

/// How long a command has to stop by itself after Ctrl-C before the
/// process ends anyway (exit 130): loops check the stop request between
/// runs and every simulated second, and this bounds the rest.
const STOP_GRACE: std::time::Duration = std::time::Duration::from_millis(800);

/// Make Ctrl-C ask every long job to stop ([`shisen::tools::request_stop`]),
/// exit 130 if the command has not ended within [`STOP_GRACE`], and at
/// once on a second Ctrl-C. Files are written whole (renamed into place),
/// so ending the process never leaves half a file.
pub fn install_interrupt() {
    // Without a handler (another one installed) Ctrl-C just ends the process.
    let _ = ctrlc::set_handler(|| {
        // Ending the process here must not wait on anything another thread
        // may hold (the standard streams' locks: `process::exit` flushes
        // standard output, a progress bar may be drawing on standard
        // error): a plain write and `_exit`.
        let end = || {
            const MSG: &[u8] = b"interrupted\n";
            // SAFETY: a write of a static buffer to fd 2, then the end of
            // the process; nothing runs after it.
            unsafe {
                libc::write(2, MSG.as_ptr().cast(), MSG.len());
                libc::_exit(i32::from(INTERRUPTED))
            }
        };
        if stop_requested() {
            end();
        }
        shisen::tools::request_stop();
        // The grace period on its own thread: the handler returns, so a
        // second Ctrl-C is heard at once.
        std::thread::spawn(move || {
            std::thread::sleep(STOP_GRACE);
            end();
        });
    });
}

/// `shisen run`: 0 if every expectation holds, 1 if one fails, 130 if
/// stopped by Ctrl-C; errors (exit 2) before anything is simulated.
pub fn run(a: RunArgs) -> Result<ExitCode> {
    // Every argument is checked before the simulation starts.
    if let Some(p) = &a.plot
        && p.extension().is_none_or(|e| !e.eq_ignore_ascii_case("png"))
    {
        bail!("--plot {}: must name a .png file", p.display());
    }
    let mut loaded = load(&a.scene)?;
    let mut plan = Outputs::new();
    if a.scene != "default" {
        plan = plan.input(Path::new(&a.scene));
    }
    for f in loaded.files() {
        plan = plan.input(&f);
    }
    if let Some(t) = &a.trace {
        plan = plan.file_as("--trace", t, "CSV", &["csv"]);
    }
    if let Some(p) = &a.plot {
        plan = plan.file_as("--plot", p, "a PNG picture", &["png"]);
    }
    if let Some(p) = &a.sound {
        plan = plan.file_as("--sound", p, "a WAV sound file", &["wav"]);
    }
    plan.check()?;
    if let Some(s) = a.seed {
        loaded.scene.seed = s;
    }
    let duration = a.duration.unwrap_or(loaded.scene.duration);
    if let Some(d) = a.duration
        && let Err(m) = check_duration(&loaded.scene, d, false)
    {
        bail!(
            "--duration {d}: {}: {}: {}",
            loaded.source,
            m.field,
            m.message
        );
    }
    if duration > LONG_RUN && !a.force {
        bail!(
            "a {duration} s run is longer than {LONG_RUN} s of simulated time; pass --force to run it"
        );
    }
    let stdout = a.trace.as_deref() == Some(Path::new("-"));
    // A plot needs a trace: without one asked for, a temporary file (no
    // file the user did not name is written or replaced).
    let temp = match (a.plot.is_some(), a.trace.is_none()) {
        (true, true) => Some(
            tempfile::Builder::new()
                .prefix("shisen-plot-")
                .suffix(".csv")
                .tempfile()
                .context("cannot make a temporary trace for --plot")?,
        ),
        _ => None,
    };
    let trace_path = a
        .trace
        .clone()
        .filter(|_| !stdout)
        .or(temp.as_ref().map(|t| t.path().to_path_buf()));
    let mut sink: Option<Box<dyn Write>> = if stdout {
        Some(Box::new(BufWriter::new(std::io::stdout().lock())))
    } else {
        match &trace_path {
            Some(p) => Some(Box::new(BufWriter::new(
                File::create(p).with_context(|| format!("cannot create trace {}", p.display()))?,
            ))),
            None => None,
        }
    };
    // With the trace on standard output, the report goes to standard error.
    let say = |line: String| {
        if stdout {
            eprintln!("{line}");
        } else {
            println!("{line}");
        }
    };
    let mut sound = match &a.sound {
        Some(p) => Some(SoundFile::create(p, loaded.scene.seed, duration)?),
        None => None,
    };
    let mut hear = sound.as_mut().map(|s| |sim: &shisen::Sim| s.hear(sim));
    let bar = progress(duration, "s simulated");
    let wall = std::time::Instant::now(); // reporting only; the model never reads it
    let report = headless::run_watched(
        &loaded,
        Some(duration),
        sink.as_mut().map(|f| f as &mut dyn Write),
        a.every,
        &mut |t| {
            bar.set_position(t as u64);
            true
        },
        hear.as_mut().map(|f| f as headless::EachTick),
    )?;
    bar.finish_and_clear();
    drop(sink);
    if let Some(s) = sound {
        s.finish()?;
    }
    let secs = wall.elapsed().as_secs_f64();
    say(format!(
        "scene {} ({}), seed {}: {:.3} s simulated in {} ticks, {:.3} s wall ({:.1}x real time)",
        loaded.scene.name,
        loaded.source,
        loaded.scene.seed,
        report.sim_time,
        report.ticks,
        secs,
        report.sim_time / secs.max(1e-9)
    ));
    if report.interrupted {
        say(format!(
            "interrupted at {:.3} s: the trace holds the run up to there; expectations not judged",
            report.sim_time
        ));
        return Ok(ExitCode::from(INTERRUPTED));
    }
    if report.resets > 0 {
        say(format!(
            "warning: the physics blew up {} times; the VH was reset each time (trace column `reset`)",
            report.resets
        ));
    }
    for v in &report.verdicts {
        say(format!(
            "{}  {}: measured {}",
            if v.pass { "PASS" } else { "FAIL" },
            v.what,
            v.measured
        ));
    }
    if let (Some(p), Some(t)) = (&a.plot, &trace_path) {
        shisen::tools::plot::plot_trace(t, p, (1400, 900))?;
        say(format!("plot written to {}", p.display()));
    }
    let passed = report.verdicts.iter().filter(|v| v.pass).count();
    say(format!(
        "{passed} passed, {} failed",
        report.verdicts.len() - passed
    ));
    Ok(if report.passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// A progress bar over `total` units, drawn (on standard error, only on
/// a terminal) for runs long enough to need one.
pub fn progress(total: f64, unit: &str) -> indicatif::ProgressBar {
    if total < 60.0 {
        return indicatif::ProgressBar::hidden();
    }
    shisen::tools::parallel::bar(total as u64, &format!("{unit} (Ctrl-C stops)"))
}

pub fn soak_cmd(
    minutes: f64,
    seed: u64,
    setup: shisen::tools::soak::SoakSetup,
    force: bool,
) -> Result<bool> {
    if !(minutes.is_finite() && minutes > 0.0) {
        anyhow::bail!("--minutes: must be a positive number, got {minutes}");
    }
    if minutes > LONG_RUN / 60.0 * 10.0 && !force {
        anyhow::bail!(
            "--minutes {minutes}: more than {} simulated minutes; pass --force to run it",
            LONG_RUN / 6.0
        );
    }
    let total = (minutes * 60.0) as u64;
    let bar = shisen::tools::parallel::bar(total, "s simulated (Ctrl-C stops)");
    let wall = std::time::Instant::now(); // reporting only
    let r = shisen::tools::soak::soak(minutes, seed, setup, |f| {
        bar.set_position((f * total as f64) as u64);
        !stop_requested()
    });
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
        "  the VH's body: {} evasions, {} footwork moves, {} foot steps; its pelvis at most {:.2} m from where it started",
        r.evasions, r.steps.0, r.steps.1, r.farthest
    );
    println!(
        "  effort: staggered {} times, fatigue {:.2} at the end; knocked down {} times ({} with no blow in the second before), up {} times",
        r.staggers.0, r.staggers.1, r.knockdowns.0, r.unprovoked, r.knockdowns.1
    );
    // Per minute of fighting (the rests between rounds not counted).
    let fought: u32 = r.card.at_range.iter().sum();
    let per_min = 60.0 / (f64::from(fought) * shisen::sim::DT).max(1e-9);
    let shares = r.card.range_shares();
    println!(
        "  ring craft{}, the partner throwing {:.0} a minute and defending {:.0} %: the VH threw {:.1} punches a minute, landed {:.1}, took {:.1}; time at clinch/mid/long/out {:.0}/{:.0}/{:.0}/{:.0} %",
        setup
            .opponent
            .map(|o| format!(" ({o})"))
            .unwrap_or_default(),
        60.0 * setup.partner.punch,
        100.0 * setup.partner.defend,
        f64::from(r.card.vh.total().thrown) * per_min,
        f64::from(r.card.vh.total().landed) * per_min,
        f64::from(r.card.you.total().landed) * per_min,
        100.0 * shares[0],
        100.0 * shares[1],
        100.0 * shares[2],
        100.0 * shares[3],
    );
    // CompuBox's categories: a punch lands when a blow of it strikes the
    // head or trunk (a glove's other contacts are in the blows line).
    for (who, f) in [("the VH", &r.card.vh), ("the opponent", &r.card.you)] {
        println!(
            "  punches, {who}: {} landed (jabs {}, power {}; head {}, body {}), {} blocked, {} missed",
            f.total().show(),
            f.jabs.show(),
            f.power.show(),
            f.head,
            f.body,
            f.blocked,
            f.missed,
        );
    }
    println!(
        "  feints, the VH: {} ({:.1} a minute)",
        r.card.vh.feints,
        f64::from(r.card.vh.feints) * per_min
    );
    let t = &r.tally;
    println!(
        "  blows: the opponent landed {} hits ({} blocked, {} punches stopped dead by the VH's guard), the VH {} ({} blocked)",
        t.opponent_hits, t.opponent_blocked, t.opponent_guarded, t.vh_hits, t.vh_blocked
    );
    println!(
        "  worst eye/neck excursion past its range {:.2} deg; widest joint gap {:.2} mm; resident memory {} -> {} KiB",
        r.worst_limit_excess_deg, r.worst_joint_gap_mm, r.rss_kib.0, r.rss_kib.1
    );
    for f in &r.failures {
        println!("  FAIL {f}");
    }
    println!(
        "  invariants {}",
        if r.passed() { "held" } else { "VIOLATED" }
    );
    if stop_requested() {
        return Err(Interrupted(format!(
            "after {:.1} simulated minutes: the figures cover those",
            r.sim_time / 60.0
        ))
        .into());
    }
    Ok(r.passed())
}
