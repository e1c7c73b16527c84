//! The sparring window (eframe with its wgpu renderer): first-person view
//! of the VH, your gloves on the mouse, keyboard and gamepads, the HUD and
//! the tuning panels. The simulation runs at its fixed 1 kHz step in
//! simulation time, stepped each frame by the wall time elapsed (capped,
//! scaled by pause and slow motion).
//!
//! For CI, `--exit-after SECONDS` closes the window after that much wall
//! time and `--screenshot FILE.png` saves egui's screenshot of the window
//! first (failing if the picture is blank).

mod panels;
pub mod record;
pub mod session;
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
    shot: Option<Shot>,
    /// Set when the run must end with an error (blank screenshot).
    failure: Arc<Mutex<Option<String>>>,
}

/// Open the window and run until it is closed.
pub fn run(opts: AppOptions) -> anyhow::Result<()> {
    let (source, loaded) = match &opts.scene {
        Some(p) => SceneSource::load(p).with_context(|| format!("scene {}", p.display()))?,
        None => (SceneSource::default_scene(), LoadedScene::default_scene()),
    };
    let bindings = Bindings::resolve(opts.bindings.as_deref())?;
    let failure = Arc::new(Mutex::new(None));
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("shisen 視線")
            .with_inner_size([1280.0, 800.0]),
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
            let session = Session::new(loaded, source);
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
                shot: None,
                failure: fail,
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
    fn command(&mut self, c: Command) {
        let s = &mut self.session;
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
            _ => {}
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

impl eframe::App for ShisenApp {
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
            v.overlays.gaze_rays = self.opts.overlays;
            v.overlays.saliency_labels = self.opts.overlays;
            v
        });

        // Input -> intent -> events, then the clock steps the simulation;
        // the frame drawn below shows the result.
        let typing = ctx.egui_wants_keyboard_input();
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
        let sim_ms = sim_started.elapsed().as_secs_f32() * 1e3;

        let Some(viewport) = self.viewport.as_mut() else {
            return;
        };
        self.frames.add(
            wall as f32 * 1e3,
            [sim_ms, viewport.build_ms, viewport.render_ms],
        );
        let frames = self.frames.clone();
        egui::Panel::top("hud").show(ui, |ui| {
            panels::hud(ui, &self.session, self.pads.names().len(), &frames);
        });
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
            .show(ui, |ui| viewport.draw(ui, &self.session));
        self.ci_exit(&ctx);
        ctx.request_repaint();
    }
}
