//! The 3D viewport: renders the session with the shared wgpu device into
//! the renderer's texture, shows it as an egui image, turns the pointer
//! into a glove position (first person) or an orbit (orbit view), and
//! paints the saliency labels.

use eframe::egui;
use eframe::egui_wgpu;
use glam::{Vec2, Vec3};

use crate::input::Pointer;
use crate::render::{Frame, Overlays, Renderer, View};

use super::session::Session;

/// The viewport's GPU side.
pub struct Viewport {
    renderer: Renderer,
    texture: Option<(egui::TextureId, (u32, u32))>,
    /// Camera.
    pub view: View,
    /// Overlay toggles.
    pub overlays: Overlays,
    /// Wall time of the last render, ms.
    pub render_ms: f32,
}

impl Viewport {
    /// A viewport on eframe's device.
    pub fn new(rs: &egui_wgpu::RenderState, view: View) -> Self {
        Viewport {
            renderer: Renderer::new(&rs.adapter, &rs.device, &rs.queue),
            texture: None,
            view,
            overlays: Overlays::default(),
            render_ms: 0.0,
        }
    }

    /// Switch between first person and orbit.
    pub fn toggle_view(&mut self) {
        self.view = match self.view {
            View::First => View::ORBIT,
            View::Orbit { .. } => View::First,
        };
    }

    /// Draw the session into `ui`'s remaining space; returns the pointer
    /// (glove offset under it, buttons pressed over the view) and the wheel.
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        rs: &egui_wgpu::RenderState,
        session: &Session,
        active_glove: usize,
    ) -> (Pointer, f32) {
        let rect = ui.available_rect_before_wrap();
        let ppp = ui.ctx().pixels_per_point();
        let px = (
            ((rect.width() * ppp).round() as u32).max(16),
            ((rect.height() * ppp).round() as u32).max(16),
        );
        let aspect = px.0 as f32 / px.1 as f32;
        let frame = Frame::build(&session.sim, self.view, self.overlays, aspect);
        let started = std::time::Instant::now();
        self.renderer
            .render(&frame, &session.sim.face.mesh.triangles, px);
        self.render_ms = started.elapsed().as_secs_f32() * 1e3;
        let view = self.renderer.color_view_unorm().expect("rendered");
        let id = {
            let mut egui_r = rs.renderer.write();
            match self.texture {
                Some((id, size)) if size == px => id,
                Some((id, _)) => {
                    egui_r.update_egui_texture_from_wgpu_texture(
                        &rs.device,
                        &view,
                        wgpu::FilterMode::Linear,
                        id,
                    );
                    id
                }
                None => egui_r.register_native_texture(&rs.device, &view, wgpu::FilterMode::Linear),
            }
        };
        self.texture = Some((id, px));
        let response = ui.put(
            rect,
            egui::Image::new(egui::load::SizedTexture::new(id, rect.size()))
                .sense(egui::Sense::click_and_drag()),
        );

        let size = Vec2::new(rect.width(), rect.height());
        let mut pointer = Pointer::default();
        let mut wheel = 0.0;
        if let Some(pos) = response.hover_pos() {
            let local = Vec2::new(pos.x - rect.min.x, pos.y - rect.min.y);
            wheel = ui.input(|i| i.smooth_scroll_delta.y);
            match &mut self.view {
                View::First => {
                    let (o, d) = frame.camera.ray(local, size);
                    let rest = session.control.glove_rest(active_glove).as_vec3();
                    // Follow the pointer's motion (a pointer resting over the
                    // view at start does not grab the glove).
                    let moving = ui.input(|i| i.pointer.is_moving());
                    if moving && d.z.abs() > 1e-4 {
                        let hit = o + d * ((rest.z - o.z) / d.z);
                        pointer.glove_offset = Some(Vec3::new(hit.x - rest.x, hit.y - rest.y, 0.0));
                    }
                    ui.input(|i| {
                        pointer.pressed = [
                            egui::PointerButton::Primary,
                            egui::PointerButton::Secondary,
                            egui::PointerButton::Middle,
                        ]
                        .map(|b| i.pointer.button_pressed(b));
                    });
                }
                View::Orbit {
                    yaw,
                    pitch,
                    distance,
                } => {
                    let drag = response.drag_delta();
                    *yaw -= drag.x * 0.01;
                    *pitch = (*pitch + drag.y * 0.01).clamp(-1.2, 1.4);
                    *distance = (*distance * (1.0 - wheel * 0.002)).clamp(0.3, 6.0);
                    wheel = 0.0;
                }
            }
        }
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
        (pointer, wheel)
    }
}
