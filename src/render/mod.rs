//! Rendering: the VH (body segments, the deforming face, eyes with sclera,
//! iris and pupil), your gloves and head, props and the floor, lit by a key
//! and a fill light, with optional overlays (gaze rays, fields of view,
//! saliency labels, joint frames).
//!
//! [`Frame::build`] turns a [`Sim`] into a CPU-side description; the wgpu
//! [`Renderer`] draws it into its own texture. [`Headless`] owns a device
//! without a window (on a machine with no GPU, Mesa's lavapipe) for
//! `shisen render`, the tests and the bench; the window shares its eframe
//! device with the same renderer.

mod blit;
pub mod body;
mod camera;
mod draw;
mod face_parts;
mod frame;
pub mod geometry;
mod gpu;
mod hall;
mod lod;
mod relay;
mod ring;

pub use blit::{Blit, BlitBind, MAX_PANELS, Panel};
pub use camera::{Camera, View};
pub use draw::{Draw, Label, LineVertex, Material, MeshKey};
pub use frame::{Frame, Overlays, face_offset};
pub use gpu::{COLOR_FORMAT, COLOR_FORMAT_UNORM, RenderError, Renderer};
pub use relay::Relay;

use std::path::Path;

use shisen::sim::Sim;

/// A device with no window, and a renderer on it.
pub struct Headless {
    /// The adapter's description (name, backend, device type).
    pub info: wgpu::AdapterInfo,
    /// The renderer.
    pub renderer: Renderer,
    adapter: wgpu::Adapter,
}

impl Headless {
    /// Open the first adapter wgpu finds with no surface: Vulkan (Metal,
    /// DX12) first, then GL, or what `WGPU_BACKEND` names. Trying Vulkan
    /// alone first keeps GL's EGL probing (and its noise) out of the usual case.
    pub fn new() -> Result<Headless, RenderError> {
        let from_env = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        let tries = if std::env::var_os("WGPU_BACKEND").is_some() {
            vec![from_env.backends]
        } else {
            vec![wgpu::Backends::PRIMARY, wgpu::Backends::all()]
        };
        let mut last_error = String::from("no backend tried");
        let mut found = None;
        for backends in tries {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
            desc.backends = backends;
            let instance = wgpu::Instance::new(desc);
            match pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                ..Default::default()
            })) {
                Ok(a) => {
                    found = Some(a);
                    break;
                }
                Err(e) => last_error = e.to_string(),
            }
        }
        let adapter = found.ok_or(RenderError::NoAdapter(last_error))?;
        let (device, queue) =
            pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
                label: Some("shisen headless"),
                required_limits:
                    wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
                ..Default::default()
            }))?;
        let info = adapter.get_info();
        tracing::info!(adapter = %info.name, backend = ?info.backend, "headless renderer");
        Ok(Headless {
            renderer: Renderer::new(&adapter, &device, &queue),
            info,
            adapter,
        })
    }

    /// A window's renderer on a device of its own, whose pictures reach
    /// this renderer's device through a [`Relay`], as the window's view
    /// does on a software rasteriser.
    pub fn relay(&self) -> Result<(Renderer, Relay), RenderError> {
        Relay::open(&self.adapter, self.renderer.device(), self.renderer.queue())
    }

    /// Render the current state of `sim` from `view` at `size` pixels and
    /// read the picture back.
    pub fn snapshot(
        &mut self,
        sim: &Sim,
        view: View,
        overlays: Overlays,
        size: (u32, u32),
    ) -> Result<image::RgbaImage, RenderError> {
        let mut frame = Frame::build(sim, view, overlays, size.0 as f32 / size.1 as f32);
        if view == View::First {
            // What the user sees: the view knocked by a blow taken.
            frame.camera.knock(sim, 1.0);
        }
        self.renderer.render(&frame, &sim.model().face.mesh, size);
        self.renderer.read_rgba()
    }
}

/// Write an image as PNG, whole or not at all
/// ([`shisen::tools::output::write_whole`]).
pub fn write_png(image: &image::RgbaImage, path: &Path) -> Result<(), RenderError> {
    let fail = |error| RenderError::Write {
        path: path.display().to_string(),
        error,
    };
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .map_err(fail)?;
    shisen::tools::output::write_whole(path, bytes.get_ref())
        .map_err(|e| fail(image::ImageError::IoError(e)))
}
