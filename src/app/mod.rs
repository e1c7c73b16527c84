//! The sparring window (eframe with its wgpu renderer): first-person view
//! of the VH, your gloves on the mouse, keyboard and gamepads, the HUD and
//! the tuning panels. The simulation runs at its fixed 1 kHz step in
//! simulation time, stepped each frame by the wall time elapsed (capped,
//! scaled by pause and slow motion).
//!
//! For CI, `--exit-after SECONDS` closes the window after that much wall
//! time and `--screenshot FILE.png` saves egui's screenshot of the window
//! first (failing if the picture is blank).

pub mod bout;
mod hud;
mod panels;
pub mod record;
pub mod session;
mod speaker;
pub mod tuning;
mod view3d;

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use anyhow::{Context as _, anyhow};
use eframe::egui;

use crate::input::pad::Pads;
use crate::input::{Bindings, Collector, Command};
use crate::render::View;
use shisen::scene::LoadedScene;

use hud::{BoutUi, MenuAction};
use panels::PanelState;
use session::{SceneSource, Session};
use view3d::Viewport;

/// How the window starts.
#[derive(Clone, Debug, Default)]
pub struct AppOptions {
    /// Scene file (the embedded default if `None`).
    pub scene: Option<PathBuf>,
    /// Bindings file (else the user's, else the defaults).
    pub bindings: Option<PathBuf>,
    /// Close after this many seconds of wall time.
    pub exit_after: Option<f64>,
    /// Save a screenshot of the window here before closing.
    pub screenshot: Option<PathBuf>,
    /// Start with the tuning panel open.
    pub panels: bool,
    /// Panel sections to open at start (implies `panels`); empty: the defaults.
    pub open: Vec<String>,
    /// Start in the orbit view.
    pub orbit: bool,
    /// Overlays on at start (gaze rays, saliency labels).
    pub overlays: bool,
    /// The VH as this opponent (skips the start menu).
    pub opponent: Option<shisen::scene::opponent::Opponent>,
    /// Rounds of the bout (else the scene's).
    pub rounds: Option<u32>,
    /// Length of a round, s (else the scene's).
    pub round_length: Option<f64>,
    /// Rest between rounds, s (else the scene's).
    pub rest: Option<f64>,
    /// Write the bout's statistics (JSON) here on closing.
    pub stats: Option<PathBuf>,
    /// Start with the round report open.
    pub report: bool,
    /// Start with the menu open whatever else is asked.
    pub menu: bool,
    /// Render the 3D view at this fraction of the window's resolution
    /// (fixed; else chosen to hold 60 fps).
    pub render_scale: Option<f32>,
    /// Sound volume, 0-1 (else full).
    pub volume: Option<f32>,
}

/// What the screenshot came to (shared with egui's callback).
type Shot = Arc<Mutex<Option<Arc<egui::ColorImage>>>>;

/// Where a frame's time goes, smoothed over about a second, and logged
/// every few seconds: the whole frame (wall time between frames), and the
/// CPU parts the app controls (stepping the simulation, describing the
/// scene, recording the render). The rest is egui and the driver
/// (rasterising, on a software Vulkan; presenting).
#[derive(Clone, Debug, Default)]
pub struct FrameClock {
    /// Frame interval, ms (exponential average).
    pub frame_ms: f32,
    /// Simulation, scene build and render recording, ms (averages).
    pub parts_ms: [f32; 3],
    frames: u32,
    since_log_ms: f32,
}

impl FrameClock {
    const SMOOTHING: f32 = 0.05;
    const LOG_EVERY_MS: f32 = 5000.0;

    fn add(&mut self, frame_ms: f32, parts_ms: [f32; 3]) {
        let a = if self.frames == 0 {
            1.0
        } else {
            Self::SMOOTHING
        };
        self.frame_ms += a * (frame_ms - self.frame_ms);
        for (avg, p) in self.parts_ms.iter_mut().zip(parts_ms) {
            *avg += a * (p - *avg);
        }
        self.frames += 1;
        self.since_log_ms += frame_ms;
        if self.since_log_ms >= Self::LOG_EVERY_MS {
            self.since_log_ms = 0.0;
            tracing::info!("{}", self.summary());
        }
    }

    /// "frame 33.0 ms (30.3 fps): sim 1.1, scene 2.0, render 0.4 ms".
    pub fn summary(&self) -> String {
        let [sim, build, render] = self.parts_ms;
        format!(
            "frame {:.1} ms ({:.1} fps): sim {sim:.1}, scene {build:.1}, render {render:.1} ms",
            self.frame_ms,
            1000.0 / self.frame_ms.max(1e-3)
        )
    }
}

struct ShisenApp {
    session: Session,
    collector: Collector,
    pads: Pads,
    viewport: Option<Viewport>,
    panels: PanelState,
    show_panels: bool,
    opts: AppOptions,
    started: Instant,
    last: Instant,
    frames: FrameClock,
    bout_ui: BoutUi,
    /// Bells already announced (logged, statistics written).
    bells: usize,
    /// The report's PNG being taken: the path and egui's screenshot.
    report_shot: Option<(PathBuf, Shot)>,
    shot: Option<Shot>,
    /// Set when the run must end with an error (blank screenshot).
    failure: Arc<Mutex<Option<String>>>,
    /// The sound output (`None`: no device, the bout runs silent).
    speaker: Option<speaker::Speaker>,
}

/// Open the window and run until it is closed.
pub fn run(opts: AppOptions) -> anyhow::Result<()> {
    keep_freed_memory();
    let (source, loaded) = match &opts.scene {
        Some(p) => SceneSource::load(p).with_context(|| format!("scene {}", p.display()))?,
        None => (SceneSource::default_scene(), LoadedScene::default_scene()),
    };
    let bindings = Bindings::resolve(opts.bindings.as_deref())?;
    let failure = Arc::new(Mutex::new(None));
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("shisen 視線")
            .with_inner_size([1280.0, 720.0]),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    let fail = failure.clone();
    eframe::run_native(
        "shisen",
        native,
        Box::new(move |_cc| {
            let mut panels = PanelState::default();
            if let Some(p) = &source.path {
                panels.scene_path = p.display().to_string();
            }
            let show_panels = opts.panels || !opts.open.is_empty();
            let mut session = Session::new(loaded, source);
            // The command line's opponent and bout over the scene's.
            let mut bout = session.loaded.scene.bout;
            if opts.rounds.is_some() || opts.round_length.is_some() || opts.rest.is_some() {
                let b = bout.get_or_insert_with(Default::default);
                b.rounds = opts.rounds.unwrap_or(b.rounds);
                b.round = opts.round_length.unwrap_or(b.round);
                b.rest = opts.rest.unwrap_or(b.rest);
            }
            let opponent = opts.opponent.or(session.loaded.scene.vh.opponent);
            if opponent != session.loaded.scene.vh.opponent || bout != session.loaded.scene.bout {
                session.restart_with(opponent, bout);
            }
            let mut bout_ui = BoutUi::new(opponent.unwrap_or_default(), bout);
            bout_ui.volume = opts.volume.unwrap_or(1.0);
            let speaker = match speaker::Speaker::open() {
                Ok(s) => Some(s),
                Err(why) => {
                    tracing::warn!("{why}: the bout runs silent");
                    None
                }
            };
            bout_ui.report = opts.report.then_some(0);
            if opts.menu || (opts.opponent.is_none() && opts.exit_after.is_none()) {
                bout_ui.toggle_menu(&mut session);
            }
            if !opts.open.is_empty() {
                panels.open_sections(&opts.open, &session.sim.params().gains);
            }
            Ok(Box::new(ShisenApp {
                session,
                collector: Collector::new(bindings),
                pads: Pads::new(),
                viewport: None,
                panels,
                show_panels,
                opts,
                started: Instant::now(),
                last: Instant::now(),
                frames: FrameClock::default(),
                bout_ui,
                bells: 0,
                report_shot: None,
                shot: None,
                failure: fail,
                speaker,
            }))
        }),
    )
    .map_err(|e| anyhow!("window: {e}"))?;
    match failure.lock().expect("not poisoned").take() {
        Some(msg) => Err(anyhow!(msg)),
        None => Ok(()),
    }
}

impl ShisenApp {
    /// Play what the simulation made heard since the last frame (dropped
    /// where there is no device).
    fn play_sound(&mut self) {
        if let Some(sp) = &self.speaker {
            let ui = &self.bout_ui;
            sp.set_volume(if ui.muted { 0.0 } else { ui.volume });
            sp.play(&self.session.heard);
        }
        self.session.heard.clear();
    }

    fn command(&mut self, c: Command) {
        let s = &mut self.session;
        // While a replay is watched the bout waits: nothing may step,
        // restart or unpause it out of sight.
        if s.replay.is_some()
            && matches!(
                c,
                Command::Pause
                    | Command::Step
                    | Command::SlowMotion
                    | Command::Restart
                    | Command::Record
                    | Command::Menu
            )
        {
            return;
        }
        match c {
            Command::TogglePanel => self.show_panels = !self.show_panels,
            Command::ToggleView => {
                if let Some(v) = &mut self.viewport {
                    v.toggle_view();
                }
            }
            Command::Pause => s.clock.paused = !s.clock.paused,
            Command::Step if s.clock.paused => s.step(),
            Command::SlowMotion => s.clock.slow = !s.clock.slow,
            Command::Restart => s.restart(),
            Command::Record => {
                if s.recorder.is_some() {
                    panels::save_recording(s, &mut self.panels);
                } else {
                    s.start_recording();
                }
            }
            Command::Menu => self.bout_ui.toggle_menu(s),
            Command::Report => self.bout_ui.toggle_report(s),
            Command::Replay => s.toggle_replay(),
            Command::DevFigures => self.bout_ui.dev = !self.bout_ui.dev,
            Command::Mute => self.bout_ui.muted = !self.bout_ui.muted,
            _ => {}
        }
    }

    /// The report's PNG: asked for by its button, taken from egui's
    /// screenshot of the window, cropped to the report.
    fn report_png(&mut self, ctx: &egui::Context) {
        if let Some(path) = self.bout_ui.report_png.take() {
            let s: Shot = Arc::new(Mutex::new(None));
            let sink = s.clone();
            ctx.request_screenshot(move |img| {
                *sink.lock().expect("not poisoned") = Some(img);
            });
            self.report_shot = Some((path, s));
        }
        let Some((path, shot)) = &self.report_shot else {
            return;
        };
        let Some(img) = shot.lock().expect("not poisoned").take() else {
            return;
        };
        let ppp = ctx.pixels_per_point();
        let whole = egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(img.width() as f32 / ppp, img.height() as f32 / ppp),
        );
        let img = match self.bout_ui.report_rect.map(|r| r.intersect(whole)) {
            Some(r) if r.width() >= 1.0 && r.height() >= 1.0 => img.region(&r, Some(ppp)),
            _ => (*img).clone(),
        };
        self.bout_ui.status = Some(match save_screenshot(&img, path) {
            Ok(()) => format!("saved {}", path.display()),
            Err(e) => format!("{e:#}"),
        });
        self.report_shot = None;
    }

    /// Each new bell: the statistics written (`--stats`), then the bell
    /// logged, so what a round came to is on disk when the log says it
    /// ended (a script that watches the log reads it whole).
    fn announce_bells(&mut self) {
        if self.session.log.bells.len() < self.bells {
            // A restart: a new bout.
            self.bells = 0;
        }
        if self.session.log.bells.len() == self.bells {
            return;
        }
        self.write_stats();
        let bells = &self.session.log.bells;
        for (t, b) in &bells[self.bells..] {
            tracing::info!(t, bell = ?b, "bell");
            // The round's report for the rest after it; the next round
            // starts without it.
            match b {
                // (Not when the next round starts at once: no rest.)
                shisen::sim::bout::Bell::End(n)
                    if !self
                        .session
                        .sim
                        .phase(*t)
                        .is_some_and(|(p, _)| p.fighting()) =>
                {
                    self.bout_ui.report = Some(*n)
                }
                shisen::sim::bout::Bell::End(_) => {}
                shisen::sim::bout::Bell::Start(n) if *n > 1 => self.bout_ui.report = None,
                shisen::sim::bout::Bell::Start(_) => {}
            }
        }
        self.bells = bells.len();
    }

    /// `--stats FILE`: the bout's statistics, per round and in total (JSON).
    fn write_stats(&self) {
        let Some(path) = &self.opts.stats else { return };
        let stats = &self.session.sim.stats;
        let bell = self.session.log.bells.last().map(|(t, b)| match b {
            shisen::sim::bout::Bell::Start(n) => serde_json::json!({"t": t, "start": n}),
            shisen::sim::bout::Bell::End(n) => serde_json::json!({"t": t, "end": n}),
        });
        let json = serde_json::json!({
            "opponent": self.session.opponent.map(|o| o.to_string()),
            "time": self.session.sim.time(),
            "bell": bell,
            "rounds": stats.rounds,
            "total": stats.total(),
        });
        let text = serde_json::to_string_pretty(&json).expect("plain data");
        if let Err(e) = shisen::tools::output::write_whole(path, (text + "\n").as_bytes()) {
            tracing::error!(path = %path.display(), error = %e, "cannot write the statistics");
        }
    }

    /// `--exit-after` / `--screenshot`: request the shot, wait for it, close.
    fn ci_exit(&mut self, ctx: &egui::Context) {
        let Some(after) = self.opts.exit_after else {
            return;
        };
        if self.started.elapsed().as_secs_f64() < after {
            ctx.request_repaint();
            return;
        }
        let Some(path) = self.opts.screenshot.clone() else {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        };
        let shot = match &self.shot {
            Some(s) => s.clone(),
            None => {
                let s: Shot = Arc::new(Mutex::new(None));
                let sink = s.clone();
                ctx.request_screenshot(move |img| {
                    *sink.lock().expect("not poisoned") = Some(img);
                });
                self.shot = Some(s);
                ctx.request_repaint();
                return;
            }
        };
        let Some(img) = shot.lock().expect("not poisoned").take() else {
            ctx.request_repaint();
            return;
        };
        if let Err(e) = save_screenshot(&img, &path) {
            *self.failure.lock().expect("not poisoned") = Some(format!("{e:#}"));
        } else {
            println!("screenshot saved to {}", path.display());
        }
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

/// Keep memory freed at the top of the allocator's heaps instead of
/// returning it to the kernel. A software Vulkan (lavapipe) frees and
/// allocates again buffers of 4 to 7 MB every frame (the window's picture
/// on its way to the X server, among others); with glibc's default trim
/// threshold their pages went back to the kernel (`madvise`) at each free
/// and were faulted in and zeroed again at the next frame: about 3 ms of a
/// 20 ms frame at 1280x720 on two cores, measured with the malloc
/// tunables. Each of the allocator's heaps may now keep up to 256 MB it
/// no longer uses (what the driver frees it soon allocates again).
fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt takes the allocator's lock and only sets two
    // thresholds.
    unsafe {
        libc::mallopt(libc::M_TRIM_THRESHOLD, 256 << 20);
        libc::mallopt(libc::M_MMAP_THRESHOLD, 32 << 20);
    }
}

/// Save egui's screenshot as PNG; an error if it is blank (one colour).
fn save_screenshot(img: &egui::ColorImage, path: &std::path::Path) -> anyhow::Result<()> {
    let [w, h] = img.size;
    let bytes: Vec<u8> = img.pixels.iter().flat_map(|c| c.to_array()).collect();
    let first = img.pixels.first().copied();
    let distinct = img.pixels.iter().filter(|p| Some(**p) != first).count();
    let rgba = image::RgbaImage::from_raw(w as u32, h as u32, bytes)
        .ok_or_else(|| anyhow!("screenshot has a bad size"))?;
    crate::render::write_png(&rgba, path)?;
    if distinct < w * h / 100 {
        anyhow::bail!("screenshot {} is blank", path.display());
    }
    Ok(())
}

/// At most this much wall time a frame moves a playing replay, s.
const MAX_REPLAY_STEP: f64 = 0.1;

impl eframe::App for ShisenApp {
    fn on_exit(&mut self) {
        self.write_stats();
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        let Some(rs) = frame.wgpu_render_state() else {
            *self.failure.lock().expect("not poisoned") =
                Some("the window has no wgpu renderer".into());
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        };
        let viewport = self.viewport.get_or_insert_with(|| {
            let view = if self.opts.orbit {
                View::ORBIT
            } else {
                View::First
            };
            let mut v = Viewport::new(rs, view);
            if let Some(s) = self.opts.render_scale {
                v.scale.value = s;
                v.scale.auto = false;
            }
            v.overlays.gaze_rays = self.opts.overlays;
            v.overlays.saliency_labels = self.opts.overlays;
            v
        });

        // Input -> intent -> events, then the clock steps the simulation;
        // the frame drawn below shows the result.
        // Only a text field takes the keys from the bout: a focused slider
        // or button must not swallow the dodge and punch keys.
        let typing = ctx.text_edit_focused();
        let (pointer, wheel) = viewport.pointer(&ctx, &self.session, self.collector.active_glove);
        let now = Instant::now();
        let pad = self.pads.poll(now);
        let (held, pressed) = if typing {
            (Vec::new(), Vec::new())
        } else {
            ctx.input(|i| {
                let pressed = i
                    .events
                    .iter()
                    .filter_map(|e| match e {
                        egui::Event::Key {
                            key,
                            pressed: true,
                            repeat: false,
                            ..
                        } => Some(*key),
                        _ => None,
                    })
                    .collect();
                (i.keys_down.iter().copied().collect(), pressed)
            })
        };
        let c = &mut self.session.control;
        c.reach = (c.reach + wheel as f64 * 0.0005).clamp(0.2, 0.8);
        let (intent, commands) = self.collector.collect(
            &held,
            &pressed,
            &pointer,
            &pad,
            self.session.control.reach as f32,
        );
        for cmd in commands {
            self.command(cmd);
        }
        self.session.apply(&intent);
        let wall = now.duration_since(self.last).as_secs_f64();
        self.last = now;
        let sim_started = Instant::now();
        self.session.advance(wall);
        self.play_sound();
        if let Some(r) = &mut self.session.replay {
            r.advance(wall.min(MAX_REPLAY_STEP));
        }
        let sim_ms = sim_started.elapsed().as_secs_f32() * 1e3;
        self.announce_bells();

        let Some(viewport) = self.viewport.as_mut() else {
            return;
        };
        self.frames.add(
            wall as f32 * 1e3,
            [sim_ms, viewport.build_ms, viewport.render_ms],
        );
        viewport.scale.frame(wall as f32 * 1e3);
        let frames = self.frames.clone();
        if self.bout_ui.dev {
            egui::Panel::top("dev").show(ui, |ui| {
                hud::dev_line(ui, &self.session, self.pads.names().len(), &frames);
                ui.label(format!("view at {:.0} %", viewport.scale.value * 100.0));
            });
        }
        if self.session.replay.is_some() {
            egui::Panel::bottom("replay").show(ui, |ui| {
                hud::replay_bar(ui, &mut self.session);
            });
        }
        if self.show_panels {
            egui::Panel::right("tuning")
                .resizable(true)
                .default_size(420.0)
                .min_size(380.0)
                .show(ui, |ui| {
                    panels::tuning(ui, &mut self.session, &mut self.panels, viewport);
                });
        }
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| {
                let sim = self
                    .session
                    .replay
                    .as_ref()
                    .map_or(&self.session.sim, |r| &r.sim);
                let rect = viewport.draw(ui, sim);
                let panels = hud::scoreboard(ui, rect, &self.session, sim);
                viewport.set_panels(rect, ctx.pixels_per_point(), &panels);
            });
        if self.bout_ui.menu {
            match hud::menu(&ctx, &mut self.bout_ui, &mut self.session) {
                Some(MenuAction::Fight) => {
                    self.session
                        .restart_with(Some(self.bout_ui.opponent), self.bout_ui.bout);
                    self.bout_ui.toggle_menu(&mut self.session);
                    self.session.clock.paused = false;
                }
                Some(MenuAction::Quit) => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
                None => {}
            }
        }
        hud::report(&ctx, &mut self.bout_ui, &self.session);
        self.report_png(&ctx);
        self.ci_exit(&ctx);
        ctx.request_repaint();
    }
}
