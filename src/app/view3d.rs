//! The 3D viewport: turns the pointer into a glove position (first person)
//! or an orbit (orbit view), renders the session with the shared wgpu
//! device into the renderer's texture, copies that into egui's pass (a
//! paint callback) and paints the saliency labels.

use eframe::egui;
use eframe::egui_wgpu;
use glam::{Vec2, Vec3};

use crate::input::Pointer;
use crate::render::{Blit, BlitBind, Camera, Frame, Overlays, Panel, Relay, Renderer, View};

use super::session::Session;
use shisen::sim::Sim;

/// The viewport's GPU side.
pub struct Viewport {
    renderer: Renderer,
    /// On a software rasteriser, the renderer draws on a device of its
    /// own and its pictures reach the window a frame later ([`Relay`]).
    relay: Option<Relay>,
    blit: Blit,
    /// Camera.
    pub view: View,
    /// Overlay toggles.
    pub overlays: Overlays,
    /// How much a blow you take knocks the first-person view, 0 (off) to
    /// 1 (as a head on a neck would turn; [`Camera::knock`]).
    pub knock: f32,
    /// CPU time of the last frame's scene description (pose, skin, face
    /// deformation), ms.
    pub build_ms: f32,
    /// CPU time of the last render call (recording and submitting; not
    /// the wait for the relayed picture), ms.
    pub render_ms: f32,
    /// Where the view was drawn last frame, and its camera.
    last: Option<(egui::Rect, Camera)>,
    /// The fraction of the window's pixels the view is rendered at.
    pub scale: RenderScale,
}

/// Dynamic resolution: the 3D view is rendered at a fraction of the
/// window's pixels (the blit scales it up, bilinear) chosen to hold the
/// frame rate. A software rasteriser shades every pixel on the CPU, so
/// the frame time follows the pixel count; the scale falls while frames
/// take longer than [`RenderScale::SLOW_MS`] and rises back while they
/// take less than [`RenderScale::FAST_MS`], between [`RenderScale::MIN`]
/// and 1. On a GPU it stays at 1.
#[derive(Clone, Copy, Debug)]
pub struct RenderScale {
    /// The fraction, per axis.
    pub value: f32,
    /// Adjusted to the frame time (else fixed).
    pub auto: bool,
    frames: u32,
    sum_ms: f32,
}

impl RenderScale {
    /// The lowest scale (a quarter of the pixels).
    pub const MIN: f32 = 0.5;
    /// Frames slower than this on average lower the scale, ms: 67 fps,
    /// so that the frame-to-frame spread of a software rasteriser on a
    /// shared machine (about 10 %) keeps the median at 60 fps or more.
    pub const SLOW_MS: f32 = 15.0;
    /// Frames faster than this raise it, ms.
    pub const FAST_MS: f32 = 11.5;
    /// Frames averaged per adjustment.
    const EVERY: u32 = 15;

    /// Start at `value`, adjusting.
    pub fn new(value: f32) -> Self {
        RenderScale {
            value: value.clamp(Self::MIN, 1.0),
            auto: true,
            frames: 0,
            sum_ms: 0.0,
        }
    }

    /// Note a frame of `ms` milliseconds.
    pub fn frame(&mut self, ms: f32) {
        if !self.auto || !ms.is_finite() {
            return;
        }
        self.frames += 1;
        self.sum_ms += ms.min(200.0);
        if self.frames < Self::EVERY {
            return;
        }
        let avg = self.sum_ms / self.frames as f32;
        self.frames = 0;
        self.sum_ms = 0.0;
        if avg > Self::SLOW_MS {
            self.value = (self.value * 0.92).max(Self::MIN);
        } else if avg < Self::FAST_MS {
            self.value = (self.value * 1.04).min(1.0);
        }
    }
}

impl Viewport {
    /// A viewport in eframe's window (on its device, or on a software
    /// rasteriser on a device of its own: [`Relay`]).
    pub fn new(rs: &egui_wgpu::RenderState, view: View) -> Self {
        let software = rs.adapter.get_info().device_type == wgpu::DeviceType::Cpu;
        // On a software rasteriser the view is drawn on a device of its
        // own, a frame ahead of the window ([`Relay`]).
        let (renderer, relay) = match software
            .then(|| Relay::open(&rs.adapter, &rs.device, &rs.queue))
            .transpose()
        {
            Ok(Some((renderer, relay))) => (renderer, Some(relay)),
            Ok(None) => (
                Renderer::for_window(&rs.adapter, &rs.device, &rs.queue),
                None,
            ),
            Err(e) => {
                tracing::warn!(error = %e, "the view is drawn on the window's device");
                (
                    Renderer::for_window(&rs.adapter, &rs.device, &rs.queue),
                    None,
                )
            }
        };
        // A software rasteriser starts below full resolution (about 60 fps
        // at 1280x720 on two cores) and finds its level from there. A GPU
        // renders at full resolution: the scale follows the interval
        // between frames, which a display's vsync holds at its refresh
        // period whatever the work, and would pull it down for nothing.
        let mut scale = RenderScale::new(if renderer.software() { 0.7 } else { 1.0 });
        scale.auto = renderer.software();
        Viewport {
            renderer,
            relay,
            blit: Blit::new(&rs.device, &rs.queue, rs.target_format),
            view,
            overlays: Overlays::default(),
            knock: 1.0,
            build_ms: 0.0,
            render_ms: 0.0,
            last: None,
            scale,
        }
    }

    /// Lay the HUD's `panels` (window pixels) over the view drawn in
    /// `rect` (points) at `pixels_per_point`, from this frame on.
    pub fn set_panels(&self, rect: egui::Rect, pixels_per_point: f32, panels: &[Panel]) {
        // Whole pixels, as egui rounds the paint callback's viewport.
        let px = |p: egui::Pos2| {
            [
                (p.x * pixels_per_point).round(),
                (p.y * pixels_per_point).round(),
            ]
        };
        self.blit.set_panels([px(rect.min), px(rect.max)], panels);
    }

    /// Switch between first person and orbit.
    pub fn toggle_view(&mut self) {
        self.view = match self.view {
            View::First => View::ORBIT,
            View::Orbit { .. } => View::First,
        };
    }

    /// The pointer over the view as drawn last frame: the glove offset
    /// under it (first person, while it moves), the buttons pressed over
    /// it, and the wheel; in the orbit view dragging turns the camera and
    /// the wheel zooms. Read before stepping, so the frame drawn after
    /// shows this frame's input.
    pub fn pointer(
        &mut self,
        ctx: &egui::Context,
        session: &Session,
        active_glove: usize,
    ) -> (Pointer, f32) {
        let mut pointer = Pointer::default();
        let Some((rect, camera)) = self.last else {
            return (pointer, 0.0);
        };
        let (pos, moving, pressed, down, delta, mut wheel) = ctx.input(|i| {
            (
                i.pointer.hover_pos(),
                i.pointer.is_moving() || i.pointer.delta() != egui::Vec2::ZERO,
                [
                    egui::PointerButton::Primary,
                    egui::PointerButton::Secondary,
                    egui::PointerButton::Middle,
                ]
                .map(|b| i.pointer.button_pressed(b)),
                i.pointer.primary_down(),
                i.pointer.delta(),
                i.smooth_scroll_delta.y,
            )
        });
        // Over the view and not under a popup or window on top of it.
        let over_view = |p: &egui::Pos2| {
            rect.contains(*p)
                && ctx
                    .layer_id_at(*p)
                    .is_none_or(|l| l.order == egui::Order::Background)
        };
        let Some(pos) = pos.filter(over_view) else {
            return (pointer, 0.0);
        };
        let size = Vec2::new(rect.width(), rect.height());
        match &mut self.view {
            View::First => {
                let local = Vec2::new(pos.x - rect.min.x, pos.y - rect.min.y);
                let (o, d) = camera.ray(local, size);
                let rest = session.control.glove_rest(active_glove).as_vec3();
                // Follow the pointer's motion (a pointer resting over the
                // view at start does not grab the glove).
                if moving && d.z.abs() > 1e-4 {
                    let hit = o + d * ((rest.z - o.z) / d.z);
                    pointer.glove_offset = Some(Vec3::new(hit.x - rest.x, hit.y - rest.y, 0.0));
                }
                pointer.pressed = pressed;
            }
            View::Orbit {
                yaw,
                pitch,
                distance,
            } => {
                if down {
                    *yaw -= delta.x * 0.01;
                    *pitch = (*pitch + delta.y * 0.01).clamp(-1.2, 1.4);
                }
                *distance = (*distance * (1.0 - wheel * 0.002)).clamp(0.3, 6.0);
                wheel = 0.0;
            }
        }
        (pointer, wheel)
    }

    /// Draw `sim` (the bout, or its replay) into `ui`'s remaining space;
    /// returns where.
    pub fn draw(&mut self, ui: &mut egui::Ui, sim: &Sim) -> egui::Rect {
        let rect = ui.available_rect_before_wrap();
        let ppp = ui.ctx().pixels_per_point() * self.scale.value;
        let px = (
            ((rect.width() * ppp).round() as u32).max(16),
            ((rect.height() * ppp).round() as u32).max(16),
        );
        let aspect = px.0 as f32 / px.1 as f32;
        let started = std::time::Instant::now();
        let mut frame = Frame::build(sim, self.view, self.overlays, aspect);
        if self.view == View::First {
            frame.camera.knock(sim, self.knock);
        }
        self.build_ms = started.elapsed().as_secs_f32() * 1e3;
        let started = std::time::Instant::now();
        let face = &sim.model().face.mesh;
        let picture = match &mut self.relay {
            Some(relay) => {
                relay.render(&mut self.renderer, &frame, face, px);
                self.render_ms = started.elapsed().as_secs_f32() * 1e3;
                if let Err(e) = relay.receive(&self.renderer) {
                    tracing::warn!(error = %e, "the view's picture did not arrive");
                }
                relay.shown()
            }
            None => {
                self.renderer.render(&frame, face, px);
                self.render_ms = started.elapsed().as_secs_f32() * 1e3;
                self.renderer.color_texture()
            }
        };
        if let Some(picture) = picture {
            ui.painter().add(egui_wgpu::Callback::new_paint_callback(
                rect,
                BlitPaint(self.blit.bind(picture)),
            ));
        }
        // Clicks and drags, but never keyboard focus: a focused view would
        // make egui take the dodge keys (the arrows move egui's focus).
        ui.allocate_rect(rect, egui::Sense::CLICK | egui::Sense::DRAG);
        self.last = Some((rect, frame.camera));
        let size = Vec2::new(rect.width(), rect.height());
        let painter = ui.painter_at(rect);
        for l in &frame.labels {
            if let Some(p) = frame.camera.project(l.at, size) {
                painter.text(
                    rect.min + egui::vec2(p.x, p.y),
                    egui::Align2::CENTER_BOTTOM,
                    &l.text,
                    egui::FontId::monospace(12.0),
                    egui::Color32::from_rgb(255, 230, 120),
                );
            }
        }
        rect
    }
}

/// egui's paint callback that copies the rendered picture into the
/// window's pass ([`Blit`]).
struct BlitPaint(BlitBind);

impl egui_wgpu::CallbackTrait for BlitPaint {
    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        _resources: &egui_wgpu::CallbackResources,
    ) {
        self.0.draw(pass);
    }
}
