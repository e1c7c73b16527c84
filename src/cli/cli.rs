//! The command line: every command and option.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Parser, Subcommand};

use shisen::physics::body::Group;
use shisen::scene::LoadedScene;
use shisen::tools::table::Shard;
use shisen_app::render::View;

/// shisen (視線): a virtual human that boxes with you and looks where a person would.
#[derive(Parser)]
#[command(version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Window: scene file to spar in (default: the embedded scene).
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Window: bindings file (default: ~/.config/shisen/bindings.ron, else built in).
    #[arg(long)]
    pub bindings: Option<PathBuf>,
    /// Window: close after this many seconds (CI), 0-86400.
    #[arg(long, value_parser = number_in(0.0, 86400.0, " s"))]
    pub exit_after: Option<f64>,
    /// Window: save a screenshot here before closing (with --exit-after).
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Window: open the tuning panel at start.
    #[arg(long)]
    pub panels: bool,
    /// Window: open these panel sections at start (scene, attention,
    /// personality, gains, face; repeatable).
    #[arg(long, value_parser = ["scene", "attention", "personality", "gains", "face"])]
    pub open: Vec<String>,
    /// Window: start in the orbit view.
    #[arg(long)]
    pub orbit: bool,
    /// Window: gaze rays and saliency labels on at start.
    #[arg(long)]
    pub overlays: bool,
    /// Window: the VH as this opponent, `level` or `level-style` (novice,
    /// amateur, pro; boxer, out-fighter, brawler, counter-puncher), e.g.
    /// `pro-brawler`; skips the start menu.
    #[arg(long, value_parser = parse_opponent)]
    pub opponent: Option<shisen::scene::opponent::Opponent>,
    /// Window: rounds of the bout (1-15; default the scene's, 3).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=15))]
    pub rounds: Option<u32>,
    /// Window: length of a round, seconds (5-600).
    #[arg(long, value_parser = number_in(5.0, 600.0, " s"))]
    pub round_length: Option<f64>,
    /// Window: rest between rounds, seconds (0-300).
    #[arg(long, value_parser = number_in(0.0, 300.0, " s"))]
    pub rest: Option<f64>,
    /// Window: write the bout's punch statistics (JSON) here on closing.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Window: start with the round report open (for screenshots).
    #[arg(long)]
    pub report: bool,
    /// Window: start with the menu open even with --opponent or --exit-after.
    #[arg(long)]
    pub menu: bool,
    /// Window: render the 3D view at this fraction of the window's
    /// resolution, 0.5-1 (default: chosen to hold 60 fps).
    #[arg(long, value_parser = number_in(0.5, 1.0, ""))]
    pub render_scale: Option<f64>,
    /// Window: sound volume, 0-1 (0: muted; F4 mutes and unmutes).
    #[arg(long, value_parser = number_in(0.0, 1.0, ""))]
    pub volume: Option<f64>,
    /// Print the default bindings (RON) and exit.
    #[arg(long)]
    pub print_bindings: bool,
}

#[derive(Subcommand)]
pub enum Command {
    /// Run a scene (file path, or `default` for the embedded scene).
    Run {
        /// Scene file, or `default`.
        scene: String,
        /// Run without a window (`run` never opens one; the flag is kept for scripts).
        #[arg(long)]
        headless: bool,
        /// Write the trace (CSV) here (`-`: standard output).
        #[arg(long)]
        trace: Option<PathBuf>,
        /// Write every Nth tick to the trace (with `--trace`).
        #[arg(long, default_value_t = 1, requires = "trace", value_parser = clap::value_parser!(u64).range(1..))]
        trace_every: u64,
        /// Override the scene's seed.
        #[arg(long)]
        seed: Option<u64>,
        /// Override the scene's duration, seconds (checked against the
        /// scene's timeline and expectation windows).
        #[arg(long)]
        duration: Option<f64>,
        /// Also plot the run (gaze, eye and head angles) to this PNG.
        #[arg(long)]
        plot: Option<PathBuf>,
        /// Write the run's soundtrack, heard from your avatar's head, here
        /// (WAV, stereo, 48 kHz, 16 bit).
        #[arg(long)]
        sound: Option<PathBuf>,
        /// Allow a run longer than an hour of simulated time.
        #[arg(long)]
        force: bool,
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
        /// Step size, seconds (0.0001-0.01).
        #[arg(long, default_value_t = 0.001, value_parser = number_in(0.0001, 0.01, " s"))]
        dt: f64,
    },
    /// Sweep gains (and step size) for one group in parallel on all cores,
    /// resumable; writes CSV and a plot.
    Sweep {
        /// The group.
        #[arg(long, value_enum)]
        group: GroupArg,
        /// Number of runs (1-100000).
        #[arg(long, default_value_t = 120, value_parser = count_in(1, 100_000))]
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
        /// Run only this share of the runs: I/N, 0 <= I < N.
        #[arg(long, default_value = "0/1")]
        shard: Shard,
    },
    /// Run every scene of some files and folders in parallel, judge their
    /// expectations, and report (exit 0 all hold, 1 one fails, 2 a scene
    /// cannot be loaded).
    Test {
        /// Scene files, or folders (their `.ron` files, not subfolders).
        #[arg(default_value = "scenes")]
        paths: Vec<PathBuf>,
        /// Scenes run at once, 1-256 (default: every core).
        #[arg(long, value_parser = count_in(1, 256))]
        jobs: Option<usize>,
        /// Write a JUnit XML report (Surefire/Jenkins junit-10.xsd) here.
        #[arg(long)]
        junit: Option<PathBuf>,
        /// Keep each scene's trace (NAME.csv) and plot (NAME.png) in this folder.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Run only this share of the scenes: I/N, 0 <= I < N (scene k is
        /// shard k mod N's).
        #[arg(long, default_value = "0/1")]
        shard: Shard,
    },
    /// Run a study (a base scene with fields varied over values and
    /// seeds) into a resumable CSV, one row per run.
    Study {
        /// The study file (RON).
        study: PathBuf,
        /// Results CSV (re-running resumes it; other settings are refused).
        #[arg(long)]
        out: PathBuf,
        /// Runs at once, 1-256 (default: every core).
        #[arg(long, value_parser = count_in(1, 256))]
        jobs: Option<usize>,
        /// Run only this share of the runs: I/N, 0 <= I < N.
        #[arg(long, default_value = "0/1")]
        shard: Shard,
    },
    /// Join the outputs of shards: results CSVs of `study` and `sweep`, or
    /// JUnit reports of `test` (when OUT ends in .xml).
    Merge {
        /// The merged file to write (must not exist).
        #[arg(long)]
        out: PathBuf,
        /// The shards' outputs.
        #[arg(required = true)]
        inputs: Vec<PathBuf>,
    },
    /// Measure the VH against human data: saccade main sequence, reaction
    /// time, head contribution, pursuit gain (speed and frequency), VOR gain
    /// and latency (head impulse), blink rate at rest and sparring,
    /// microsaccades and glance duration, each from the physics, with its
    /// human band and source, PASS or FAIL. Exit 1 if any row fails.
    Fidelity {
        /// Scene whose parameters the VH uses (default: the embedded one).
        #[arg(long)]
        scene: Option<PathBuf>,
        /// `seed` runs the papers' laws with no latencies (profile: Seed);
        /// default: the scene's profile.
        #[arg(long)]
        profile: Option<ProfileArg>,
        /// Write fidelity.csv and PNG plots into this folder.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Shove the physical VH (`pelvis: Balanced`) on the trunk from the
    /// front, behind and either side with rising impulses, and print what
    /// it does: holds with its feet in place, steps, or falls (a Markdown
    /// table, beside people's thresholds).
    Pushes {
        /// Scene whose parameters the VH uses (default: the embedded one).
        #[arg(long)]
        scene: Option<PathBuf>,
    },
    /// Spar against a seeded random opponent for N simulated minutes,
    /// checking invariants every tick, and print a summary.
    Soak {
        /// Simulated minutes (more than 600 needs --force).
        #[arg(long, default_value_t = 1.0, value_parser = number_in(0.001, 1e6, " min"))]
        minutes: f64,
        /// Seed of the opponent and the VH.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// The VH's whole body in the physics (`vh.body.pelvis: Balanced`):
        /// blows can stagger and knock it down.
        #[arg(long)]
        balanced: bool,
        /// The VH as this opponent, `level` or `level-style` (novice,
        /// amateur, pro; boxer, out-fighter, brawler, counter-puncher):
        /// its range, output and defence. Default: the default scene's VH.
        #[arg(long, value_parser = parse_opponent)]
        opponent: Option<shisen::scene::opponent::Opponent>,
        /// Fight in rounds, as a bout: three minutes with a minute's rest
        /// between them (AIBA's format), as many as `--minutes` holds,
        /// the partner resting too; rates are per minute of fighting.
        /// Without it the sparring goes on without a pause.
        #[arg(long)]
        rounds: bool,
        /// Share of the VH's punches the random partner defends against
        /// (covering up or slipping, after a human reaction time), 0-1;
        /// 0: it never defends. Half its idle glove moves go back to its
        /// guard whatever this is.
        #[arg(long, default_value_t = shisen::tools::soak::PARTNER_DEFENCE, value_parser = number_in(0.0, 1.0, ""))]
        partner_defence: f64,
        /// The random partner's punches a minute, 0-120 (by default an
        /// elite amateur's output; 48 is how hard it once pressed).
        #[arg(long, default_value_t = shisen::tools::soak::PARTNER_PUNCHES_PER_MIN, value_parser = number_in(0.0, 120.0, " a minute"))]
        partner_punches: f64,
        /// Allow more than 600 simulated minutes.
        #[arg(long)]
        force: bool,
    },
    /// Write the VH and opponent bodies as an MJCF model (for the MuJoCo
    /// comparison in benches/mujoco_compare.py).
    ExportMjcf {
        /// Output XML file.
        #[arg(long)]
        out: PathBuf,
        /// The whole physical body (`vh.body.pelvis: Balanced`): a free
        /// pelvis on the canvas, the waist, hips, knees and ankles.
        #[arg(long)]
        balanced: bool,
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
    /// Print the JSON Schema of an input file kind (for editors and
    /// validators), or with `--markdown` the whole file-format reference
    /// (docs/scene-format.md is this output).
    Schema {
        /// Which file kind.
        #[arg(value_enum)]
        file: Option<shisen_app::schema::FileKind>,
        /// The reference of every file kind as Markdown instead.
        #[arg(long, conflicts_with = "file")]
        markdown: bool,
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
        /// Camera: `first` (from your head), `orbit`, `face` (close-up),
        /// or `orbit:YAW,PITCH,DISTANCE` (radians, radians, metres about
        /// the VH's head).
        #[arg(long, default_value = "first", value_parser = parse_view)]
        view: View,
        /// Overlays to draw (repeatable).
        #[arg(long, value_enum)]
        overlay: Vec<OverlayArg>,
        /// Write an animation (APNG, `--out` still ends in .png) from
        /// `--at` to this time instead of one picture.
        #[arg(long)]
        until: Option<f64>,
        /// Frames per second of simulated time in the animation (with
        /// `--until`).
        #[arg(long, default_value_t = 25, requires = "until")]
        fps: u32,
        /// Slow motion: the animation plays this many times slower than
        /// real time (1-100; it plays at `fps / slow` frames a second, at
        /// most 60).
        #[arg(long, default_value_t = 1, requires = "until")]
        slow: u32,
        /// Also write the animation's soundtrack (WAV), heard from your
        /// avatar's head, from `--at` to `--until` (at real speed: not
        /// with `--slow`).
        #[arg(long, requires = "until")]
        sound: Option<PathBuf>,
    },
}

#[derive(Subcommand)]
pub enum FaceCommand {
    /// Export the neutral generated head to glTF (.glb) with one morph
    /// target per muscle and ARKit-named shapes, and its landmark file
    /// beside it (`NAME.landmarks.ron`), so it can be imported again.
    Export {
        /// Output .glb file.
        #[arg(long)]
        out: PathBuf,
        /// Mesh resolution (latitude bands, 24-400).
        #[arg(long, default_value_t = 48, value_parser = count_in(24, 400))]
        rows: usize,
    },
    /// Render every one of the 35 emotions at full intensity, face view,
    /// into one captioned contact sheet (PNG); with `--basic`, neutral and
    /// the six basic expressions at full and 60 % intensity, face view and
    /// three-quarter view.
    Sheet {
        /// Output PNG.
        #[arg(long)]
        out: PathBuf,
        /// Mesh resolution (latitude bands, 24-400).
        #[arg(long, default_value_t = 100, value_parser = count_in(24, 400))]
        rows: usize,
        /// Size of one face, WxH pixels (64-1024 each).
        #[arg(long, default_value = "220x250", value_parser = parse_cell)]
        cell: (u32, u32),
        /// The basic expressions' sheet instead of the 35 emotions'.
        #[arg(long)]
        basic: bool,
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
pub enum GroupArg {
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
pub enum OverlayArg {
    /// Lines of sight and the gaze point.
    Gaze,
    /// Fields of view.
    Fov,
    /// Joint frames.
    Frames,
}

pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    size_in(s, 64, 8192)
}

/// One face of a contact sheet (35 of them make the sheet).
fn parse_cell(s: &str) -> Result<(u32, u32), String> {
    size_in(s, 64, 1024)
}

fn size_in(s: &str, lo: u32, hi: u32) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once('x')
        .ok_or_else(|| format!("expected WxH, got `{s}`"))?;
    let n = |v: &str| {
        v.parse::<u32>()
            .ok()
            .filter(|v| (lo..=hi).contains(v))
            .ok_or_else(|| format!("size must be {lo}-{hi} pixels, got `{v}`"))
    };
    Ok((n(w)?, n(h)?))
}

/// A parser of a whole number within `[lo, hi]`.
fn count_in(lo: usize, hi: usize) -> impl Fn(&str) -> Result<usize, String> + Clone {
    move |s| match s.parse::<usize>() {
        Ok(v) if (lo..=hi).contains(&v) => Ok(v),
        _ => Err(format!("must be a whole number {lo}-{hi}, got {s}")),
    }
}

pub fn parse_view(s: &str) -> Result<View, String> {
    View::parse(s).ok_or_else(|| {
        format!(
            "expected first, orbit, face or orbit:YAW,PITCH,DISTANCE (distance 0.2-10 m), got {s}"
        )
    })
}

pub fn load(scene: &str) -> Result<LoadedScene> {
    if scene == "default" {
        return Ok(LoadedScene::default_scene());
    }
    Ok(LoadedScene::load(std::path::Path::new(scene))?)
}

fn parse_opponent(s: &str) -> Result<shisen::scene::opponent::Opponent, String> {
    s.parse()
}

/// A parser of a finite number within `[lo, hi]`, in `unit` ("s", "").
fn number_in(lo: f64, hi: f64, unit: &'static str) -> impl Fn(&str) -> Result<f64, String> + Clone {
    move |s| {
        let v: f64 = s
            .parse()
            .map_err(|_| format!("expected a number, got '{s}'"))?;
        if v.is_finite() && (lo..=hi).contains(&v) {
            Ok(v)
        } else {
            Err(format!("must be {lo}-{hi}{unit}, got {s}"))
        }
    }
}

impl Cli {
    /// The first window option given, if any (they mean nothing to a
    /// subcommand).
    pub fn window_flag(&self) -> Option<&'static str> {
        [
            (self.scene.is_some(), "--scene"),
            (self.bindings.is_some(), "--bindings"),
            (self.exit_after.is_some(), "--exit-after"),
            (self.screenshot.is_some(), "--screenshot"),
            (self.panels, "--panels"),
            (!self.open.is_empty(), "--open"),
            (self.orbit, "--orbit"),
            (self.overlays, "--overlays"),
            (self.print_bindings, "--print-bindings"),
            (self.opponent.is_some(), "--opponent"),
            (self.rounds.is_some(), "--rounds"),
            (self.round_length.is_some(), "--round-length"),
            (self.rest.is_some(), "--rest"),
            (self.stats.is_some(), "--stats"),
            (self.report, "--report"),
            (self.menu, "--menu"),
            (self.render_scale.is_some(), "--render-scale"),
            (self.volume.is_some(), "--volume"),
        ]
        .into_iter()
        .find_map(|(set, name)| set.then_some(name))
    }
}

/// `--profile` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ProfileArg {
    /// Human latencies and limits (the default profile).
    Human,
    /// The seed papers' laws, no latencies.
    Seed,
}
